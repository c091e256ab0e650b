#include "terratin/gdal_error.hpp"

#include <cpl_error.h>
#include <gdal.h>

#include <cerrno>
#include <cstring>
#include <mutex>

namespace terratin {

namespace {
// GDAL prints warnings and errors to stderr by default. The CLI promises one clear error line,
// so GDAL's messages are kept (CPLGetLastErrorMsg still works) but not printed.
void CPL_STDCALL quietErrorHandler(CPLErr, CPLErrorNum, const char*) {}

/// errno values that name the cause of a failed write GDAL did not describe (GDAL's drivers
/// report few write failures themselves). Other values, ENOENT above all, are too often left
/// over from GDAL probing for sidecar files to be trusted.
bool isWriteErrno(int value) {
    return value == ENOSPC || value == EDQUOT || value == EFBIG || value == EIO || value == EROFS;
}
} // namespace

std::string lastGdalErrorMessage(std::string_view fallback) {
    const char* message = CPLGetLastErrorMsg();
    if (message != nullptr && *message != '\0')
        return oneLine(message);
    if (isWriteErrno(errno))
        return std::strerror(errno);
    return fallback.empty() ? std::string("GDAL gave no reason") : std::string(fallback);
}

void throwGdalError(std::string_view stage, std::string_view what, std::string_view path,
                    std::string_view fallback) {
    throw IoError(std::string(stage) + ": " + std::string(what) + " '" + std::string(path) +
                  "': " + lastGdalErrorMessage(fallback));
}

void initialiseGdal() {
    static std::once_flag once;
    std::call_once(once, [] {
        GDALAllRegister();
        CPLSetErrorHandler(quietErrorHandler);
    });
}

} // namespace terratin
