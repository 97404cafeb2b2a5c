// Fuzz target: the curvilinear-grid resampling (io/src/netcdf/CurvilinearGrid) on coordinates of
// any value: the checks, the periodic-seam and north-fold detection, the lattice a region or the
// source extent gives, the rasterisation of every source cell (seams, degenerate and folded
// cells), and the resampling of one plane with land. Input: a header byte each for nx and ny
// (2..17), one for the lattice resolution and one for flags (1: a region; 2: the polar
// stereographic plane lattice instead, 4: its south pole), then the region (4 doubles),
// then doubles for the longitudes, latitudes and one plane of values (missing ones are 0).
#include "FuzzSupport.h"
#include "netcdf/CurvilinearGrid.h"
#include "octrace/util/Error.h"

#include <cstring>

namespace {

struct Reader {
    const std::uint8_t* data;
    std::size_t size, at = 0;
    double next() {
        double v = 0.0;
        if (at + sizeof v <= size) std::memcpy(&v, data + at, sizeof v);
        at += sizeof v;
        return v;
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace octrace::io;
    octrace::fuzz::quietLogs();
    if (size < 4) return 0;
    const std::size_t nx = 2 + data[0] % 16, ny = 2 + data[1] % 16;
    const int samples = data[2] % 2 ? 0 : 2 + data[2] % 130;
    FieldRequest req;
    req.hasRegion = data[3] % 2;
    req.memoryBudget = octrace::fuzz::kMemoryBudget;
    Reader r{data, size, 4};
    for (double& x : req.region) x = r.next();
    std::vector<double> lon(nx * ny), lat(nx * ny), plane(nx * ny);
    for (double& x : lon) x = r.next();
    for (double& x : lat) x = r.next();
    for (double& x : plane) x = r.next();
    try {
        if (req.hasRegion) checkRegion(req.region, "fuzz");
        auto g = detail::CurvilinearGrid::fromCoordinates("fuzz", ny, nx, lon, lat);
        if (data[3] & 2) {  // the polar stereographic plane lattice, north or south
            auto pl = g.planeLattice("fuzz", req, (data[3] & 4) ? -1 : 1, samples);
            if (pl.x.size() * pl.y.size() > (1u << 16)) return 0;
            g.buildPlaneLookup(pl);
            detail::SampleRules rules;
            rules.missing = {0.0};
            std::vector<float> values(pl.x.size() * pl.y.size());
            std::vector<std::uint8_t> valid(values.size());
            g.resample(plane, rules, values.data(), valid.data());
            (void)g.planeDescription(pl);
            return 0;
        }
        auto lattice = g.lattice("fuzz", req, samples);
        if (lattice.lon.size() * lattice.lat.size() > (1u << 16)) return 0;  // keeps one input well under a second
        g.buildLookup(lattice.lon, lattice.lat);
        detail::SampleRules rules;
        rules.missing = {0.0};  // zeros are land
        std::vector<float> values(lattice.lon.size() * lattice.lat.size());
        std::vector<std::uint8_t> valid(values.size());
        g.resample(plane, rules, values.data(), valid.data());
        // the decoded form (a parametric coordinate's column depths): validity from the first pass
        std::vector<std::uint8_t> ocean(plane.size());
        for (std::size_t p = 0; p < plane.size(); ++p) ocean[p] = rules.isValid(plane[p]) ? 1 : 0;
        std::vector<double> depths(values.size());
        std::vector<std::uint8_t> depthValid(values.size());
        g.resample(plane.data(), ocean.data(), depths.data(), depthValid.data());
        (void)g.description(lattice, lattice.lon.size(), lattice.lat.size());
    } catch (const octrace::Error&) {
    }
    return 0;
}
