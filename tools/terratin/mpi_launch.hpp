#pragma once
// Whether this terratin was started by mpirun, read from the environment mpirun sets, before
// anything else runs (so that only rank 0 prints a usage error, and a build without MPI can
// refuse to run as several copies writing one output).

namespace terratin::cli {

struct MpiLaunch {
    int size = 1; ///< processes in the run; 1 when not started by mpirun
    int rank = 0;
};

/// From OMPI_COMM_WORLD_SIZE / OMPI_COMM_WORLD_RANK (Open MPI) or PMI_SIZE / PMI_RANK.
MpiLaunch mpiLaunch();

} // namespace terratin::cli
