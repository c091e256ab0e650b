#include "terratin/io/gdal_error.hpp"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace terratin::io {

namespace {
// GDAL prints warnings and errors to stderr by default. The CLI promises one clear error line,
// so GDAL's messages are kept (CPLGetLastErrorMsg still works) but not printed.
void CPL_STDCALL quietErrorHandler(CPLErr, CPLErrorNum, const char*) {}
} // namespace

std::string lastGdalErrorMessage() {
    const char* message = CPLGetLastErrorMsg();
    if (message == nullptr || *message == '\0')
        return "unknown GDAL error";
    return message;
}

void throwGdalError(std::string_view stage, std::string_view what, std::string_view path) {
    throw IoError(std::string(stage) + ": " + std::string(what) + " '" + std::string(path) +
                  "': " + lastGdalErrorMessage());
}

void initialiseGdal() {
    static std::once_flag once;
    std::call_once(once, [] {
        GDALAllRegister();
        CPLSetErrorHandler(quietErrorHandler);
    });
}

} // namespace terratin::io
