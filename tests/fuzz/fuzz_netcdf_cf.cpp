// Fuzz target: the NetCDF / CF interpretation layer (NetcdfFile over GDAL's multidimensional
// API, axis roles, geographic mapping across the dateline, uneven depths, masking, packing,
// non-geographic grids, `octrace info`'s description). The input is the bytes of a NetCDF
// file (classic or NetCDF-4/HDF5), handed to GDAL as an in-memory file (/vsimem/) after the
// checks NetcdfReader::read makes on disk (signature; all of a classic file's data present).
// The file's arrays and attributes then go through the in-memory path (CfDataset.h) with the
// same requests.
#include "../io/CfDatasetFromGdal.h"
#include "FuzzSupport.h"
#include "netcdf/NetcdfClassicHeader.h"
#include "netcdf/NetcdfFile.h"
#include "netcdf/NetcdfInterpretation.h"
#include "octrace/io/CfDataset.h"
#include "octrace/util/Error.h"

#include <cpl_vsi.h>

#include <cstdlib>
#include <sstream>

namespace {

using octrace::io::FieldRequest;

FieldRequest region(double lon0, double lon1, double lat0, double lat1, double verticalScale) {
    FieldRequest r;
    r.hasRegion = true;
    r.region[0] = lon0;
    r.region[1] = lon1;
    r.region[2] = lat0;
    r.region[3] = lat1;
    r.verticalScale = verticalScale;
    return r;
}

// Sound speed from T and S, at the second time step (or a date), between 10 and 3000 m.
FieldRequest derived() {
    FieldRequest r;
    r.variable = "sound_speed";
    r.time = "1";
    r.hasDepthRange = true;
    r.depthRange[0] = 10.0;
    r.depthRange[1] = 3000.0;
    return r;
}

bool passesTheOnDiskChecks(const std::string& bytes) {
    static const std::string hdf5("\x89HDF\r\n\x1a\n", 8);
    if (bytes.size() >= 8 && bytes.compare(0, 8, hdf5) == 0) return true;
    if (bytes.size() < 4 || bytes.compare(0, 3, "CDF") != 0 || (bytes[3] != 1 && bytes[3] != 2 && bytes[3] != 5))
        return false;
    std::istringstream in(bytes);
    try {
        return octrace::io::detail::classicDataEnd(in, bytes.size(), "fuzz.nc") <= bytes.size();
    } catch (const octrace::Error&) {
        return false;
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    // HDF5 can loop forever on a corrupt NetCDF-4 file; NetcdfFile reads the metadata first in
    // a child process with this deadline (io/src/input/ChildProbe.h). An input is opened five times,
    // so one second each keeps such an input within libFuzzer's 10 s timeout.
    setenv("OCTRACE_HDF5_OPEN_SECONDS", "1", 0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    if (!passesTheOnDiskChecks(bytes)) return 0;
    const char* path = "/vsimem/octrace_fuzz.nc";
    VSIFCloseL(VSIFileFromMemBuffer(path, reinterpret_cast<GByte*>(const_cast<char*>(bytes.data())), bytes.size(),
                                    FALSE));
    const FieldRequest requests[] = {
        FieldRequest{},
        region(170.0, -170.0, -60.0, 60.0, 0.0),  // across the dateline
        region(0.0, 90.0, -45.0, 45.0, 3.0),
        derived(),
    };
    for (auto req : requests) {
        req.memoryBudget = octrace::fuzz::kMemoryBudget;
        try {
            (void)octrace::io::detail::interpretNetcdf(path, req);
        } catch (const octrace::Error&) {
        }
    }
    try {
        FieldRequest req;
        req.memoryBudget = octrace::fuzz::kMemoryBudget;
        (void)octrace::io::detail::describeNetcdf(path, "fuzz", req);
    } catch (const octrace::Error&) {
    }
    // The in-memory path, on the arrays GDAL reads (those within the memory budget as doubles),
    // once NetcdfFile has opened the file: its child-process guard has then seen HDF5 read the
    // metadata to the end, so the direct opening below cannot hang on them.
    std::unique_ptr<octrace::test::CfArrays> arrays;
    try {
        (void)octrace::io::detail::NetcdfFile(path);
        arrays = octrace::test::cfDatasetFromGdal(path, "fuzz arrays", octrace::fuzz::kMemoryBudget / sizeof(double));
    } catch (const std::exception&) {
    }
    if (arrays) {
        for (auto req : requests) {
            req.memoryBudget = octrace::fuzz::kMemoryBudget;
            try {
                (void)octrace::io::readCfDataset(arrays->data, req);
            } catch (const octrace::Error&) {
            }
        }
        try {
            FieldRequest req;
            req.memoryBudget = octrace::fuzz::kMemoryBudget;
            (void)octrace::io::describeCfDataset(arrays->data, req);
        } catch (const octrace::Error&) {
        }
    }
    VSIUnlink(path);
    return 0;
}
