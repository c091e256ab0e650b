#include "mpi_tiles.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/tile_handout.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <optional>
#include <thread>

namespace terratin::cli {

namespace {

enum Tag : int {
    kRequest = 1, // a rank asks for its first tile
    kResult = 2,  // a tile's number, then its packed TIN
    kFailure = 3, // a message
    kTile = 10,   // rank 0: refine this tile
    kStop = 11,   // rank 0: no more work
};

constexpr int kCoordinator = 0;

/// A message: its tag, sender and bytes.
struct Message {
    int tag = 0;
    int source = 0;
    std::vector<std::byte> bytes;
};

void send(const std::vector<std::byte>& bytes, int tag, int to) {
    if (bytes.size() > static_cast<std::size_t>(INT_MAX))
        throw Error("MPI: a message of " + std::to_string(bytes.size()) +
                    " bytes is too large; give a smaller --tile-size");
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

Message receive(const MPI_Status& probed) {
    int count = 0;
    MPI_Get_count(&probed, MPI_BYTE, &count);
    Message message{probed.MPI_TAG, probed.MPI_SOURCE,
                    std::vector<std::byte>(static_cast<std::size_t>(count))};
    MPI_Recv(message.bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG,
             MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return message;
}

/// The next message from ranks 1 .. ranks - 1 that `accept` takes (given its tag, sender and
/// size; one it leaves stays with its sender, unreceived, and is asked about again), probing
/// each rank in turn; keepGoing is asked every millisecond while none is there.
Message receiveAccepted(int ranks, const std::function<bool(int, int, std::uint64_t)>& accept,
                        const std::function<bool()>& keepGoing, bool& cancelled) {
    for (;;) {
        for (int rank = 1; rank < ranks; ++rank) {
            int arrived = 0;
            MPI_Status status;
            MPI_Iprobe(rank, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
            if (arrived == 0)
                continue;
            int count = 0;
            MPI_Get_count(&status, MPI_BYTE, &count);
            if (accept(status.MPI_TAG, rank, static_cast<std::uint64_t>(count)))
                return receive(status);
        }
        if (!cancelled && !keepGoing())
            cancelled = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

std::vector<std::byte> numberBytes(std::uint64_t number) {
    std::vector<std::byte> bytes(sizeof number);
    std::memcpy(bytes.data(), &number, sizeof number);
    return bytes;
}

std::uint64_t numberOf(const std::vector<std::byte>& bytes) {
    std::uint64_t number = 0;
    if (bytes.size() < sizeof number)
        throw Error("MPI: a message without its tile number");
    std::memcpy(&number, bytes.data(), sizeof number);
    return number;
}

std::vector<std::byte> textBytes(const std::string& text) {
    std::vector<std::byte> bytes(text.size());
    std::memcpy(bytes.data(), text.data(), text.size());
    return bytes;
}

std::string textOf(const std::vector<std::byte>& bytes) {
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

} // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
}

MpiSession::~MpiSession() {
    MPI_Finalize();
}

void MpiTiles::gather(std::size_t tileCount,
                      const std::function<void(std::size_t, std::vector<std::byte>)>& take,
                      const std::function<bool()>& keepGoing, std::uint64_t earlyBytes) {
    m_stopped.assign(static_cast<std::size_t>(m_size), false);
    m_stopped[kCoordinator] = true;
    TileHandout handout(tileCount, earlyBytes);
    std::deque<int> waiting; // ranks whose last message has no reply yet
    std::vector<std::size_t> tileOf(static_cast<std::size_t>(m_size), 0); // each rank's work
    std::optional<std::string> failure;
    bool cancelled = false;
    // A tile that came back before its turn and would pass the bound stays with its rank (its
    // send waits) until its turn comes or the early tiles make room; after a failure or a
    // cancellation every message is taken, so that each rank gets its Stop.
    const auto accept = [&](int tag, int rank, std::uint64_t bytes) {
        return tag != kResult || failure || cancelled ||
               handout.accepts(tileOf[static_cast<std::size_t>(rank)],
                               bytes - std::min<std::uint64_t>(bytes, sizeof(std::uint64_t)));
    };
    for (int working = m_size - 1; working > 0;) {
        Message message = receiveAccepted(m_size, accept, keepGoing, cancelled);
        if (message.tag == kResult && !failure && !cancelled) {
            const std::uint64_t tile = numberOf(message.bytes);
            message.bytes.erase(message.bytes.begin(), message.bytes.begin() + sizeof tile);
            try {
                handout.back(tile, message.bytes.size());
                take(tile, std::move(message.bytes));
            } catch (const Error& error) {
                failure = error.what();
            }
        } else if (message.tag == kFailure && !failure) {
            failure = "rank " + std::to_string(message.source) + ": " + textOf(message.bytes);
        }
        waiting.push_back(message.source);
        while (!waiting.empty()) {
            const bool stop = failure || cancelled || handout.allHandedOut();
            const std::optional<std::size_t> tile = stop ? std::nullopt : handout.next();
            if (!stop && !tile)
                break; // the early tiles hold too much: wait for the ones in turn
            const int rank = waiting.front();
            waiting.pop_front();
            if (tile) {
                tileOf[static_cast<std::size_t>(rank)] = *tile;
                send(numberBytes(*tile), kTile, rank);
            } else {
                send({}, kStop, rank);
                m_stopped[static_cast<std::size_t>(rank)] = true;
                --working;
            }
        }
    }
    if (failure)
        throw Error(*failure);
    if (cancelled)
        throw Cancelled("Tiles: cancelled");
    if (!handout.allHandedOut())
        throw Error("MPI: no rank to refine the tiles");
}

void MpiTiles::serve(const std::function<std::vector<std::byte>(std::size_t)>& refine) {
    m_served = true;
    send({}, kRequest, kCoordinator);
    for (;;) {
        MPI_Status status;
        MPI_Probe(kCoordinator, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
        const Message message = receive(status);
        if (message.tag == kStop)
            return;
        const std::uint64_t tile = numberOf(message.bytes);
        std::vector<std::byte> reply;
        int tag = kResult;
        try {
            reply = numberBytes(tile);
            const std::vector<std::byte> tin = refine(tile);
            reply.insert(reply.end(), tin.begin(), tin.end());
        } catch (const std::exception& error) {
            reply = textBytes(error.what());
            tag = kFailure;
        }
        send(reply, tag, kCoordinator);
    }
}

void MpiTiles::releaseAll() {
    if (m_rank != kCoordinator)
        return;
    m_stopped.resize(static_cast<std::size_t>(m_size), false);
    for (int rank = 1; rank < m_size; ++rank)
        if (!m_stopped[static_cast<std::size_t>(rank)]) {
            send({}, kStop, rank);
            m_stopped[static_cast<std::size_t>(rank)] = true;
        }
}

void MpiTiles::abandon(const std::string& message) {
    if (m_rank == kCoordinator || m_served)
        return;
    m_served = true;
    send(textBytes(message), kFailure, kCoordinator);
    MPI_Recv(nullptr, 0, MPI_BYTE, kCoordinator, kStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

} // namespace terratin::cli
