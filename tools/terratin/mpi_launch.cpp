#include "mpi_launch.hpp"

#include <cstdlib>
#include <string>

namespace terratin::cli {

namespace {

int environmentNumber(const char* name, int fallback) {
    const char* text = std::getenv(name);
    if (text == nullptr)
        return fallback;
    try {
        return std::stoi(text);
    } catch (const std::exception&) {
        return fallback;
    }
}

} // namespace

MpiLaunch mpiLaunch() {
    MpiLaunch launch;
    launch.size = environmentNumber("OMPI_COMM_WORLD_SIZE", environmentNumber("PMI_SIZE", 1));
    launch.rank = environmentNumber("OMPI_COMM_WORLD_RANK", environmentNumber("PMI_RANK", 0));
    return launch;
}

} // namespace terratin::cli
