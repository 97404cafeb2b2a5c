// Fuzz target: parametric vertical coordinates (io/src/netcdf/VerticalFormula.h): the
// `formula_terms` parser and the evaluation and column resampling of every formula, through
// the in-memory CF source (CfDataset.h) so that no file format stands in the way.
//
// Input: byte 0 picks the standard_name (the five formulas, an unknown one, none), byte 1 the
// number of levels (1..8), byte 2 the number of time steps (1..2) and whether the field also
// names a 4-D depth variable in `coordinates`; then the formula_terms text up to the first
// '\n'; then int16 little-endian numbers / 100 filling, in order, the level values and every
// term variable (s/sigma, C, h, zeta, the scalars hc, a, b, z1, z2, href, k_c, a depth
// variable, one on a foreign dimension) and the field (zeros when the input runs out).
// tests/fuzz/corpus/fuzz_formula_terms holds one seed per formula (corpus/make_seeds.py).
#include "FuzzSupport.h"
#include "netcdf/VerticalFormula.h"
#include "octrace/io/CfDataset.h"
#include "octrace/util/Error.h"

#include <cstring>
#include <string>
#include <vector>

namespace {

using octrace::io::CfDataset;
using octrace::io::CfVariable;

struct Numbers {
    const std::uint8_t* p;
    std::size_t n;
    double next() {
        if (n < 2) return 0.0;
        std::int16_t v = std::int16_t(p[0] | (p[1] << 8));
        p += 2;
        n -= 2;
        return double(v) / 100.0;
    }
    std::vector<double> take(std::size_t count) {
        std::vector<double> out(count);
        for (auto& v : out) v = next();
        return out;
    }
};

CfVariable var(const std::string& name, std::vector<std::string> dims, std::vector<std::size_t> shape, Numbers& in) {
    CfVariable v;
    v.name = name;
    std::size_t count = 1;
    for (auto s : shape) count *= s;
    v.dims = std::move(dims);
    v.shape = std::move(shape);
    v.values = in.take(count);
    return v;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return 0;
    static const char* const names[] = {"ocean_s_coordinate_g1", "ocean_s_coordinate_g2", "ocean_sigma_coordinate",
                                        "ocean_double_sigma_coordinate", "ocean_s_coordinate",
                                        "atmosphere_sigma_coordinate", ""};
    const std::string standardName = names[data[0] % 7];
    const std::size_t nk = 1 + data[1] % 8, nt = 1 + data[2] % 2;
    const bool givenDepth = (data[2] & 2) != 0;
    const std::uint8_t* rest = data + 3;
    std::size_t left = size - 3;
    const void* nl = std::memchr(rest, '\n', left);
    const std::size_t textLength = nl ? std::size_t(static_cast<const std::uint8_t*>(nl) - rest) : left;
    const std::string text(reinterpret_cast<const char*>(rest), textLength);
    Numbers in{rest + textLength + (nl ? 1 : 0), left - textLength - (nl ? 1 : 0)};

    try {
        (void)octrace::io::detail::parseFormulaTerms(text, "fuzz");
    } catch (const octrace::Error&) {
    }

    const std::size_t nx = 3, ny = 2;
    CfDataset d;
    d.description = "fuzz";
    CfVariable lon = var("lon", {"lon"}, {nx}, in);
    lon.values = std::vector<double>{0.0, 1.0, 2.0};
    lon.attributes["units"] = "degrees_east";
    CfVariable lat = var("lat", {"lat"}, {ny}, in);
    lat.values = std::vector<double>{10.0, 11.0};
    lat.attributes["units"] = "degrees_north";
    CfVariable time = var("time", {"time"}, {nt}, in);
    time.values = std::vector<double>(nt == 1 ? std::vector<double>{0.0} : std::vector<double>{0.0, 1.0});
    time.attributes["units"] = "days since 2000-01-01";
    CfVariable lev = var("lev", {"lev"}, {nk}, in);
    lev.attributes["positive"] = "up";
    if (!standardName.empty()) lev.attributes["standard_name"] = standardName;
    if (!text.empty()) lev.attributes["formula_terms"] = text;
    d.variables = {lon, lat, time, lev};
    d.variables.push_back(var("s", {"lev"}, {nk}, in));
    d.variables.push_back(var("C", {"lev"}, {nk}, in));
    d.variables.push_back(var("h", {"lat", "lon"}, {ny, nx}, in));
    d.variables.push_back(var("zeta", {"time", "lat", "lon"}, {nt, ny, nx}, in));
    for (const char* scalar : {"hc", "a", "b", "z1", "z2", "href", "k_c"}) d.variables.push_back(var(scalar, {}, {}, in));
    CfVariable depth = var("depth", {"time", "lev", "lat", "lon"}, {nt, nk, ny, nx}, in);
    depth.attributes["units"] = "m";
    depth.attributes["positive"] = "down";
    d.variables.push_back(depth);
    d.variables.push_back(var("foreign", {"other", "lon"}, {4, nx}, in));
    CfVariable temp = var("temp", {"time", "lev", "lat", "lon"}, {nt, nk, ny, nx}, in);
    if (givenDepth) temp.attributes["coordinates"] = "time depth lat lon";
    d.variables.push_back(temp);

    octrace::io::FieldRequest req;
    req.variable = "temp";
    req.memoryBudget = octrace::fuzz::kMemoryBudget;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {  // the last step, a depth range and a vertical scale
            req.time = std::to_string(nt - 1);
            req.hasDepthRange = true;
            req.depthRange[0] = 1.0;
            req.depthRange[1] = 50.0;
            req.verticalScale = 10.0;
        }
        try {
            (void)octrace::io::readCfDataset(d, req);
        } catch (const octrace::Error&) {
        }
    }
    try {
        (void)octrace::io::describeCfDataset(d, {});
    } catch (const octrace::Error&) {
    }
    return 0;
}
