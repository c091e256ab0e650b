#include "mpi_tiles.hpp"

#include "cancel_signals.hpp"

#include "terratin/error.hpp"
#include "terratin/tile/tile_handout.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
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
    kStopped = 4, // the name of the signal that stopped this rank
    kTile = 10,   // rank 0: refine this tile
    kStop = 11,   // rank 0: no more work
};

constexpr int kCoordinator = 0;

/// How long a rank sleeps between two looks for a message: short next to a tile's refinement,
/// and a waiting rank takes no core from the ones refining (a blocking MPI_Probe spins one).
constexpr std::chrono::milliseconds kPollInterval{1};

/// Set when an MPI call failed (a process of the run is lost; errors return, see MpiSession):
/// MPI_Finalize would wait for that process forever.
std::atomic<bool> g_rankLost{false};
/// Set in rank 0 when it left ranks without their Stop (it was stopped by a signal): they never
/// reach MPI_Finalize, so neither may rank 0.
std::atomic<bool> g_ranksLeftWaiting{false};

/// Throws Error "MPI: <what>: <MPI's message>" when `code` is not MPI_SUCCESS.
void check(int code, const std::string& what) {
    if (code == MPI_SUCCESS)
        return;
    g_rankLost.store(true);
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw Error("MPI: " + what + ": " + std::string(text, static_cast<std::size_t>(length)) +
                "; a process of the run is lost");
}

/// Why a run stopped on a signal: "MPI: <who> was stopped by <signal> (...)". Under mpirun one
/// process's signal is usually every one's: mpirun sends SIGTERM to all when one of them dies or
/// is killed, or when it is interrupted.
std::string stoppedBy(const std::string& who, const std::string& signal) {
    return "MPI: " + who + " was stopped by " + signal +
           " (mpirun sends it to every process when one of them is lost or the run is "
           "interrupted); nothing was written";
}

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
    check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD),
          "cannot send to rank " + std::to_string(to));
}

/// The message `probed` announced; nullopt when `keepGoing` (asked every kPollInterval until
/// it is complete; none: never) said stop. Not a blocking MPI_Recv: a sender killed in the
/// middle of a large message never completes it (Open MPI's shared-memory transport then waits
/// for it forever).
std::optional<Message> receive(const MPI_Status& probed, const std::function<bool()>& keepGoing) {
    int count = 0;
    MPI_Get_count(&probed, MPI_BYTE, &count);
    Message message{probed.MPI_TAG, probed.MPI_SOURCE,
                    std::vector<std::byte>(static_cast<std::size_t>(count))};
    const std::string from = "cannot receive from rank " + std::to_string(probed.MPI_SOURCE);
    MPI_Request request = MPI_REQUEST_NULL;
    check(MPI_Irecv(message.bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG,
                    MPI_COMM_WORLD, &request),
          from);
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), from);
        if (done != 0)
            return message;
        if (keepGoing && !keepGoing()) {
            // The receive stays posted, so its buffer must outlive it: until the process ends,
            // which it does without another MPI call (gather leaves the ranks waiting, so
            // neither releaseAll nor ~MpiSession makes one).
            static std::vector<std::vector<std::byte>> unfinished;
            unfinished.push_back(std::move(message.bytes));
            return std::nullopt;
        }
        std::this_thread::sleep_for(kPollInterval);
    }
}

/// The next message from rank 0 with `tag` (MPI_ANY_TAG: any). A signal does not end the
/// wait: mpirun answers the first process that exits by killing the others at once (its
/// SIGTERM-to-SIGKILL pause ends early on SIGCHLD), and rank 0 needs that pause to remove its
/// temporaries and say why. This rank is ended by mpirun once rank 0 has exited, or gets its
/// Stop from a rank 0 that was not stopped.
Message receiveFromCoordinator(int tag) {
    for (;;) {
        int arrived = 0;
        MPI_Status status;
        check(MPI_Iprobe(kCoordinator, tag, MPI_COMM_WORLD, &arrived, &status),
              "cannot wait for rank 0");
        if (arrived != 0)
            return *receive(status, {});
        std::this_thread::sleep_for(kPollInterval);
    }
}

/// The next message from ranks 1 .. ranks - 1 that `accept` takes (given its tag, sender and
/// size; one it leaves stays with its sender, unreceived, and is asked about again), probing
/// each rank in turn; keepGoing is asked every kPollInterval while none is there, and nullopt
/// returned as soon as it says stop: the message awaited may never come (its rank was killed
/// or stopped, and mpirun's SIGTERM to the others is what ends the wait).
std::optional<Message> receiveAccepted(int ranks,
                                       const std::function<bool(int, int, std::uint64_t)>& accept,
                                       const std::function<bool()>& keepGoing) {
    for (;;) {
        for (int rank = 1; rank < ranks; ++rank) {
            int arrived = 0;
            MPI_Status status;
            check(MPI_Iprobe(rank, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status),
                  "cannot wait for rank " + std::to_string(rank));
            if (arrived == 0)
                continue;
            int count = 0;
            MPI_Get_count(&status, MPI_BYTE, &count);
            if (accept(status.MPI_TAG, rank, static_cast<std::uint64_t>(count)))
                return receive(status, keepGoing);
        }
        if (!keepGoing())
            return std::nullopt;
        std::this_thread::sleep_for(kPollInterval);
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

/// Rank 0's side of gather: the tiles handed out and back (TileHandout), the ranks awaiting a
/// reply, and the first failure, after which every rank is answered with Stop.
class Gathering {
public:
    Gathering(std::size_t tileCount, std::uint64_t earlyBytes, int ranks)
        : m_handout(tileCount, earlyBytes), m_tileOf(static_cast<std::size_t>(ranks), 0) {}

    /// Whether to receive now a message of `tag` and `bytes` from `rank`. A tile that came back
    /// before its turn and would pass the bound stays with its rank (its send waits) until its
    /// turn comes or the early tiles make room; after a failure every message is taken, so
    /// that each rank gets its Stop.
    [[nodiscard]] bool accepts(int tag, int rank, std::uint64_t bytes) const {
        return tag != kResult || m_failure ||
               m_handout.accepts(m_tileOf[static_cast<std::size_t>(rank)],
                                 bytes - std::min<std::uint64_t>(bytes, sizeof(std::uint64_t)));
    }

    /// Takes a tile's TIN to `take`, or notes the first failure (a failing `take` too); its
    /// sender now awaits a reply.
    void takeMessage(Message& message,
                     const std::function<void(std::size_t, std::vector<std::byte>)>& take) {
        if (message.tag == kResult && !m_failure) {
            const std::uint64_t tile = numberOf(message.bytes);
            message.bytes.erase(message.bytes.begin(), message.bytes.begin() + sizeof tile);
            try {
                m_handout.back(tile, message.bytes.size());
                take(tile, std::move(message.bytes));
            } catch (const Error& error) {
                m_failure = error.what();
            }
        } else if (message.tag == kFailure && !m_failure) {
            m_failure = "rank " + std::to_string(message.source) + ": " + textOf(message.bytes);
        } else if (message.tag == kStopped && !m_failure) {
            m_failure = stoppedBy("rank " + std::to_string(message.source), textOf(message.bytes));
            m_failureIsSignal = true;
        }
        m_waiting.push_back(message.source);
    }

    /// Replies to the waiting ranks in turn: a tile each while there is one to hand out, Stop
    /// (noted in `stopped`) once none is left or after a failure; returns how many were
    /// stopped. Leaves the rest waiting while the early tiles hold too much.
    int answerWaiting(std::vector<bool>& stopped) {
        int stops = 0;
        while (!m_waiting.empty()) {
            const bool stop = m_failure || m_handout.allHandedOut();
            const std::optional<std::size_t> tile = stop ? std::nullopt : m_handout.next();
            if (!stop && !tile)
                break; // the early tiles hold too much: wait for the ones in turn
            const int rank = m_waiting.front();
            m_waiting.pop_front();
            if (tile) {
                m_tileOf[static_cast<std::size_t>(rank)] = *tile;
                send(numberBytes(*tile), kTile, rank);
            } else {
                send({}, kStop, rank);
                stopped[static_cast<std::size_t>(rank)] = true;
                ++stops;
            }
        }
        return stops;
    }

    /// Rank 0 was stopped: throws the failure that came first, or Cancelled. A rank stopped by
    /// the signal that stopped this one too is one cause, said once.
    [[noreturn]] void throwStopped() const {
        const bool signalled = cancelledBySignal().load();
        if (m_failure && !(m_failureIsSignal && signalled))
            throw Error(*m_failure);
        throw Cancelled(signalled ? stoppedBy("the run", cancellingSignalName())
                                  : std::string("Tiles: cancelled"));
    }

    /// Every rank stopped: throws the failure, or Error when tiles are left that no rank took.
    void checkFinished() const {
        if (m_failure)
            throw Error(*m_failure);
        if (!m_handout.allHandedOut())
            throw Error("MPI: no rank to refine the tiles");
    }

private:
    TileHandout m_handout;
    std::deque<int> m_waiting;         // ranks whose last message has no reply yet
    std::vector<std::size_t> m_tileOf; // each rank's work
    std::optional<std::string> m_failure;
    bool m_failureIsSignal = false; // the failure is a rank stopped by a signal
};

} // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
    // A lost process makes the calls that reach it fail with an error this rank reports (one
    // `terratin:` line from rank 0), instead of aborting every process before rank 0 has
    // removed its temporaries.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession() {
    // MPI_Finalize waits for every process: for a lost one, or for ranks rank 0 left waiting,
    // until mpirun's SIGKILL. Leaving without it, this process's exit status (1) makes mpirun
    // end the rest of the run.
    if (g_rankLost.load() || g_ranksLeftWaiting.load())
        return;
    MPI_Finalize();
}

void MpiTiles::gather(std::size_t tileCount,
                      const std::function<void(std::size_t, std::vector<std::byte>)>& take,
                      const std::function<bool()>& keepGoing, std::uint64_t earlyBytes) {
    m_stopped.assign(static_cast<std::size_t>(m_size), false);
    m_stopped[kCoordinator] = true;
    Gathering gathering(tileCount, earlyBytes, m_size);
    const auto accept = [&](int tag, int rank, std::uint64_t bytes) {
        return gathering.accepts(tag, rank, bytes);
    };
    for (int working = m_size - 1; working > 0;) {
        std::optional<Message> received = receiveAccepted(m_size, accept, keepGoing);
        if (!received) {
            // Stopped (under mpirun, by a signal): the rank whose message is awaited may be gone,
            // so no more is awaited, and the others get no Stop (see releaseAll).
            g_ranksLeftWaiting.store(true);
            gathering.throwStopped();
        }
        gathering.takeMessage(*received, take);
        working -= gathering.answerWaiting(m_stopped);
    }
    gathering.checkFinished();
}

void MpiTiles::serve(const std::function<std::vector<std::byte>(std::size_t)>& refine) {
    m_served = true;
    send({}, kRequest, kCoordinator);
    for (;;) {
        const Message message = receiveFromCoordinator(MPI_ANY_TAG);
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
            // Cancelled by a signal: say so, not which stage happened to notice it.
            const bool signalled = cancelledBySignal().load();
            reply = textBytes(signalled ? cancellingSignalName() : std::string(error.what()));
            tag = signalled ? kStopped : kFailure;
        }
        send(reply, tag, kCoordinator);
    }
}

void MpiTiles::releaseAll() {
    if (m_rank != kCoordinator || g_ranksLeftWaiting.load())
        return;
    m_stopped.resize(static_cast<std::size_t>(m_size), false);
    // Stopped by a signal: mpirun is ending the run. A rank told to stop would exit, and mpirun
    // answers the first exit by killing the rest at once, perhaps before this process has
    // removed its temporaries and said why; mpirun ends them once this one has exited.
    if (cancelledBySignal().load()) {
        if (std::find(m_stopped.begin() + 1, m_stopped.end(), false) != m_stopped.end())
            g_ranksLeftWaiting.store(true);
        return;
    }
    for (int rank = 1; rank < m_size; ++rank)
        if (!m_stopped[static_cast<std::size_t>(rank)]) {
            m_stopped[static_cast<std::size_t>(rank)] = true;
            // On the way out of a failure: a rank that cannot be told is lost, and the error
            // that brought the run here is the one to report.
            try {
                send({}, kStop, rank);
            } catch (const Error&) {
            }
        }
}

void MpiTiles::abandon(const std::string& message) {
    if (m_rank == kCoordinator || m_served)
        return;
    m_served = true;
    if (g_rankLost.load())
        return; // rank 0 cannot be told
    try {
        const bool signalled = cancelledBySignal().load();
        send(textBytes(signalled ? cancellingSignalName() : message),
             signalled ? kStopped : kFailure, kCoordinator);
        receiveFromCoordinator(kStop);
    } catch (const Error&) {
        // Rank 0 is lost: this rank fails either way.
    }
}

} // namespace terratin::cli
