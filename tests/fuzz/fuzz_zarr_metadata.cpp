// Fuzz target: Zarr stores. The input is a tiny store, its files separated by the byte 0x1E
// (record separator), in this order: `.zgroup`, `.zmetadata`, `zarr.json` (each left out when
// empty), then the array `v`'s `.zarray`, `.zattrs` and chunk `0.0.0`. The root metadata go
// through octrace's layout checks (io/src/zarr/ZarrStore.cpp, as the folder sniffing does);
// a store they accept is written as a GDAL in-memory folder (/vsimem/) and read through GDAL's
// Zarr driver and the CF interpretation (NetcdfFile, NetcdfReader), as `octrace render` and
// `octrace info` read a store. tests/data/zarr/make_zarr_stores.py writes the seeds.
#include "FuzzSupport.h"
#include "netcdf/NetcdfFile.h"
#include "netcdf/NetcdfInterpretation.h"
#include "octrace/util/Error.h"
#include "zarr/ZarrStore.h"

#include <cpl_vsi.h>

#include <optional>
#include <string>
#include <vector>

namespace {

using octrace::io::FieldRequest;

std::vector<std::string> parts(const std::string& bytes) {
    std::vector<std::string> out(1);
    for (char c : bytes) {
        if (c == '\x1e' && out.size() < 6) out.emplace_back();
        else out.back() += c;
    }
    out.resize(6);
    return out;
}

void writeFile(const std::string& path, const std::string& bytes) {
    VSILFILE* f = VSIFOpenL(path.c_str(), "wb");
    if (!f) return;
    VSIFWriteL(bytes.data(), 1, bytes.size(), f);
    VSIFCloseL(f);
}

std::optional<std::string> present(const std::string& s) { return s.empty() ? std::nullopt : std::optional(s); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto p = parts(std::string(reinterpret_cast<const char*>(data), size));
    octrace::io::detail::ZarrMetadata root;
    root.zgroup = present(p[0]);
    root.zmetadata = present(p[1]);
    root.zarrJson = present(p[2]);
    try {
        (void)octrace::io::detail::classifyZarrMetadata("fuzz.zarr", root);
    } catch (const octrace::Error&) {
        return 0;  // refused before GDAL sees it, as octrace refuses such a folder
    }
    const std::string store = "/vsimem/octrace_fuzz.zarr";
    VSIMkdir(store.c_str(), 0755);
    VSIMkdir((store + "/v").c_str(), 0755);
    const char* names[] = {"/.zgroup", "/.zmetadata", "/zarr.json", "/v/.zarray", "/v/.zattrs", "/v/0.0.0"};
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!p[i].empty()) writeFile(store + names[i], p[i]);
    FieldRequest req;
    req.memoryBudget = octrace::fuzz::kMemoryBudget;
    try {
        (void)octrace::io::detail::interpretNetcdf(store, req, octrace::io::detail::GdalDriver::Zarr);
    } catch (const octrace::Error&) {
    }
    try {
        (void)octrace::io::detail::describeNetcdf(store, "fuzz", req, octrace::io::detail::GdalDriver::Zarr);
    } catch (const octrace::Error&) {
    }
    VSIRmdirRecursive(store.c_str());
    return 0;
}
