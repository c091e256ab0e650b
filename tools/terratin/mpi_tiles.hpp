#pragma once
// terratin's tiles over MPI: rank 0 coordinates (hands tiles out as the others ask,
// joins their TINs, writes); every other rank refines the tiles it is handed. Each rank reads
// the DEM itself, from a filesystem they share.
//
// The protocol: a rank that refines sends Request, then after each tile Result (the tile's
// number and its packed TIN), Failure (a message) or Stopped (the signal that cancelled it);
// every message it sends gets exactly one reply, Tile (a number) or Stop; the reply to a Result
// waits while the tiles that came back before their turn hold more than rank 0's share of
// --memory-limit (TileHandout). Rank 0 sends each other rank exactly one Stop: when no tile is
// left, at the first failure (it then answers every message with Stop), or, when rank 0 fails
// before it gathers, from releaseAll(). So no rank waits for a message that never comes, with
// one exception: rank 0 stopped by a signal.
//
// A signal under mpirun: mpirun sends SIGTERM to every process when one of them dies or is
// killed, or when mpirun itself is interrupted, and SIGKILL a second later or as soon as one of
// them exits. Every wait polls (MPI_Iprobe, MPI_Test) so that rank 0 sees the signal even while
// the rank it waits for is gone; rank 0 then waits no longer and tells no rank to stop, removes
// its temporaries, prints why, and exits without MPI_Finalize; the other ranks keep waiting for
// rank 0, so that no exit of theirs brings mpirun's SIGKILL first, and are ended by mpirun.

#include "terratin/tile/tile_distribution.hpp"

#include <string>
#include <vector>

namespace terratin::cli {

/// MPI_Init_thread on construction, MPI_Finalize on destruction.
class MpiSession {
public:
    MpiSession(int& argc, char**& argv);
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    [[nodiscard]] int rank() const { return m_rank; }
    [[nodiscard]] int size() const { return m_size; }

private:
    int m_rank = 0;
    int m_size = 1;
};

class MpiTiles final : public TileDistribution {
public:
    explicit MpiTiles(const MpiSession& session) : m_rank(session.rank()), m_size(session.size()) {}

    [[nodiscard]] bool coordinates() const override { return m_rank == 0; }
    void gather(std::size_t tileCount,
                const std::function<void(std::size_t, std::vector<std::byte>)>& take,
                const std::function<bool()>& keepGoing, std::uint64_t earlyBytes) override;
    void serve(const std::function<std::vector<std::byte>(std::size_t)>& refine) override;

    /// Rank 0, failing before or outside gather: sends Stop to every rank not stopped yet;
    /// nothing once a signal has arrived (see above). Never throws.
    void releaseAll();
    /// Another rank, failing outside serve: tells rank 0 why and waits for its Stop.
    void abandon(const std::string& message);

private:
    int m_rank;
    int m_size;
    std::vector<bool> m_stopped; // rank 0: the ranks it has sent Stop
    bool m_served = false;       // another rank: whether serve ran (and got its Stop)
};

} // namespace terratin::cli
