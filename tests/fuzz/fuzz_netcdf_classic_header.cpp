// Fuzz target: the walker of NetCDF classic headers (CDF-1, CDF-2, CDF-5) that finds where a
// file's data end, so that NetcdfReader refuses truncated files before libnetcdf reads them
// as zeros. The input is the first bytes of a file, read from memory.
#include "FuzzSupport.h"
#include "netcdf/NetcdfClassicHeader.h"
#include "octrace/util/Error.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        (void)octrace::io::detail::classicDataEnd(in, size, "fuzz.nc");
    } catch (const octrace::Error&) {
    }
    return 0;
}
