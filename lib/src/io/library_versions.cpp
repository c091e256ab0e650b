#include "terratin/io/library_versions.hpp"

#include <GeographicLib/Config.h>
#include <gdal.h>
#include <proj.h>
#include <sqlite3.h>

namespace terratin::io {

std::string libraryVersions() {
    return std::string("GDAL ") + GDALVersionInfo("RELEASE_NAME") + ", PROJ " +
           proj_info().version + ", GeographicLib " + GEOGRAPHICLIB_VERSION_STRING + ", SQLite " +
           sqlite3_libversion();
}

} // namespace terratin::io
