#pragma once
/// @file
/// The owner word of a triangle (DagNode::owner) in the circum-circle method: which worker,
/// in which of its attempts at a point, holds the triangle. The protocol around it is
/// described in docs/algorithms.md ("The circum-circle method").

#include <cstdint>
#include <optional>

namespace terratin::detail {

/// A circum-circle worker's index, from 0 to OwnerTag::kMaxWorkers - 1.
using WorkerIndex = unsigned;

/// The tag a worker writes into the owner word of each triangle it takes: the worker's index
/// + 1 in the low kWorkerBits bits, its attempt number above them. Each attempt to insert a
/// point takes triangles under a new tag, so an overriding worker, which may take its
/// victim's triangles, takes only those of the attempt it overrode: never one the victim
/// took again after giving up.
class OwnerTag {
public:
    static constexpr unsigned kWorkerBits = 12;
    /// The low bits hold the index + 1, and 0 there means free.
    static constexpr unsigned kMaxWorkers = (1U << kWorkerBits) - 2;
    /// The owner word of a free triangle.
    static constexpr std::uint32_t kFreeWord = 0;

    /// No worker's tag: the word of a free triangle.
    constexpr OwnerTag() = default;

    /// The tag of the worker's first attempt.
    [[nodiscard]] static constexpr OwnerTag firstOf(WorkerIndex worker) {
        return OwnerTag(worker + 1);
    }
    /// The tag of the same worker's next attempt. The attempt number wraps after 2^20
    /// attempts; harmless, since each attempt frees the triangles it took before the next
    /// begins.
    [[nodiscard]] constexpr OwnerTag nextAttempt() const {
        return OwnerTag(m_word + (1U << kWorkerBits));
    }

    /// The value stored in DagNode::owner.
    [[nodiscard]] constexpr std::uint32_t word() const { return m_word; }

    /// The worker holding a triangle whose owner word is `ownerWord`; nullopt when it is free.
    [[nodiscard]] static constexpr std::optional<WorkerIndex> holderOf(std::uint32_t ownerWord) {
        const std::uint32_t workerPlusOne = ownerWord & kWorkerMask;
        if (workerPlusOne == 0)
            return std::nullopt;
        return workerPlusOne - 1;
    }

private:
    static constexpr std::uint32_t kWorkerMask = (1U << kWorkerBits) - 1;

    explicit constexpr OwnerTag(std::uint32_t word) : m_word(word) {}

    std::uint32_t m_word = kFreeWord;
};

} // namespace terratin::detail
