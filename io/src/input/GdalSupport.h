#pragma once
// What the readers that go through GDAL share (internal to octrace_io).
#include "octrace/util/Log.h"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>
#include <string>

namespace octrace::io::detail {

/// GDAL's drivers, registered once.
inline void registerGdal() {
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAllRegister(); });
}

/// Sends GDAL's messages to octrace's log (debug level) instead of stderr, for the current
/// thread and scope.
class GdalMessages {
public:
    GdalMessages() {
        CPLPushErrorHandler(&handler);
        CPLErrorReset();
    }
    ~GdalMessages() { CPLPopErrorHandler(); }
    GdalMessages(const GdalMessages&) = delete;
    GdalMessages& operator=(const GdalMessages&) = delete;
    /// The last message GDAL gave on this thread.
    static std::string last() {
        const char* m = CPLGetLastErrorMsg();
        return m && *m ? std::string(m) : std::string("no detail from GDAL");
    }

private:
    static void CPL_STDCALL handler(CPLErr level, CPLErrorNum, const char* msg) {
        if (level >= CE_Warning) log::debug(std::string("GDAL: ") + (msg ? msg : ""));
    }
};

}  // namespace octrace::io::detail
