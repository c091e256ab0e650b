#pragma once
/// @file
/// Tiles refined by other processes (MPI ranks): what the tiled refiner asks of a
/// transport. terratin's command line implements it with MPI (tools/terratin/mpi_tiles.hpp);
/// the library only packs a tile's TIN into bytes and unpacks it, and joins the tiles in tile
/// order whatever order they come back in, so the TIN is the same as in one process.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace terratin {

class TileDistribution {
public:
    virtual ~TileDistribution() = default;

    /// True in the process that hands the tiles out, joins their TINs and writes the output;
    /// false in the processes that refine the tiles they are handed.
    [[nodiscard]] virtual bool coordinates() const = 0;

    /// The coordinator: hands out the tiles 0 .. tileCount - 1 as the others ask for work and
    /// calls take(tile, bytes) with each tile's packed TIN as it comes back, until all have;
    /// then releases every other process. Tiles that come back before their turn wait for it
    /// in the coordinator: while they hold more than `earlyBytes` bytes (0: no bound) it hands
    /// out no more (tile_handout.hpp keeps that count). Calls `keepGoing` while it waits and
    /// stops when it returns false. Throws terratin::Error naming the process and its message
    /// when one fails (take's exceptions too), and Cancelled when keepGoing stopped it. Every
    /// other process is released first, except where a signal stopped the run: then the
    /// implementation may leave them (an MPI launcher that lost a process ends them itself,
    /// and a process waiting to be told would never hear).
    virtual void
    gather(std::size_t tileCount,
           const std::function<void(std::size_t tile, std::vector<std::byte> tin)>& take,
           const std::function<bool()>& keepGoing, std::uint64_t earlyBytes) = 0;

    /// The others: calls refine(tile) for each tile handed out and sends back the bytes it
    /// returns, until released. An exception from refine goes to the coordinator as its
    /// message.
    virtual void serve(const std::function<std::vector<std::byte>(std::size_t tile)>& refine) = 0;
};

} // namespace terratin
