// Parametric vertical coordinates (io/src/netcdf/VerticalFormula.h): formula_terms parsing,
// each CF Appendix D formula against an independent evaluation (a field whose value is its own
// depth must come back as the lattice depth), masking above the surface and below the floor,
// time steps of eta, the ROMS-like test file over ETOPO20 against Levitus, the in-memory twin,
// and the invalid corpus.
#include "CfDatasetFromGdal.h"
#include "IoTestSupport.h"

#include "netcdf/VerticalFormula.h"
#include "octrace/io/CfDataset.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

using namespace octrace;
using io::CfAttribute;
using io::CfDataset;
using io::CfVariable;

namespace {

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// Depth (m, positive down) of lattice level k.
double latticeDepth(const ScalarField& f, int k) {
    double z = f.origin.z + f.axisPosition(2, k);
    return -z / f.geographic.verticalScale * 1000.0;
}

CfVariable variable(const std::string& name, std::vector<std::string> dims, std::vector<std::size_t> shape,
                    std::vector<double> values, std::map<std::string, CfAttribute> attributes = {}) {
    CfVariable v;
    v.name = name;
    v.dims = std::move(dims);
    v.shape = std::move(shape);
    v.values = std::move(values);
    v.attributes = std::move(attributes);
    return v;
}

// A 3 x 3 column grid (lon 0..2, lat 0..2) with nk levels, one time step; depth D(i, j) =
// 100 + 200 i + 50 j, eta(i, j) = 0.5 (i - 1). `depthOf(k, D, eta)` is the test's own
// evaluation of the formula (m, positive down); the field `temp` holds it, so that a correct
// reading gives each sample its own lattice depth.
struct Columns {
    static constexpr std::size_t nk = 6, n = 3;
    static double D(std::size_t i, std::size_t j) { return 100.0 + 200.0 * double(i) + 50.0 * double(j); }
    static double eta(std::size_t i, std::size_t) { return 0.5 * (double(i) - 1.0); }

    CfDataset data;
    Columns(const std::string& standardName, const std::string& formulaTerms, const std::vector<double>& levels,
            const std::function<double(std::size_t k, double D, double eta)>& depthOf) {
        data.description = "test columns";
        data.variables.push_back(variable("lon", {"lon"}, {n}, {0.0, 1.0, 2.0}, {{"units", "degrees_east"}}));
        data.variables.push_back(variable("lat", {"lat"}, {n}, {0.0, 1.0, 2.0}, {{"units", "degrees_north"}}));
        data.variables.push_back(variable("time", {"time"}, {1}, {0.0}, {{"units", "days since 2000-01-01"}}));
        data.variables.push_back(variable("lev", {"lev"}, {nk}, levels,
                                          {{"standard_name", standardName}, {"formula_terms", formulaTerms},
                                           {"positive", "up"}}));
        std::vector<double> D2, eta3, temp;
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = 0; i < n; ++i) {
                D2.push_back(D(i, j));
                eta3.push_back(eta(i, j));
            }
        for (std::size_t k = 0; k < nk; ++k)
            for (std::size_t j = 0; j < n; ++j)
                for (std::size_t i = 0; i < n; ++i) temp.push_back(depthOf(k, D(i, j), eta(i, j)));
        data.variables.push_back(variable("depth", {"lat", "lon"}, {n, n}, D2, {{"units", "m"}}));
        data.variables.push_back(variable("eta", {"time", "lat", "lon"}, {1, n, n}, eta3, {{"units", "m"}}));
        data.variables.push_back(variable("temp", {"time", "lev", "lat", "lon"}, {1, nk, n, n}, temp, {{"units", "m"}}));
    }
    void scalar(const std::string& name, double value) { data.variables.push_back(variable(name, {}, {}, {value})); }
    void level(const std::string& name, std::vector<double> values) {
        data.variables.push_back(variable(name, {"lev"}, {nk}, std::move(values)));
    }
};

// Every valid sample of `f` (from Columns) equals its lattice depth where that depth lies
// between the column's shallowest and deepest native level; samples above the surface or
// below the floor are masked. Returns the number of samples checked exactly.
int expectValuesAreDepths(const ScalarField& f, const std::function<double(std::size_t k, double D, double eta)>& depthOf) {
    int exact = 0;
    EXPECT_EQ(f.dims.x, 3);
    EXPECT_EQ(f.dims.y, 3);
    for (int j = 0; j < f.dims.y; ++j)
        for (int i = 0; i < f.dims.x; ++i) {
            const double D = Columns::D(std::size_t(i), std::size_t(j)), eta = Columns::eta(std::size_t(i), std::size_t(j));
            double lo = INFINITY, hi = -INFINITY;
            for (std::size_t k = 0; k < Columns::nk; ++k) {
                lo = std::min(lo, depthOf(k, D, eta));
                hi = std::max(hi, depthOf(k, D, eta));
            }
            for (int k = 0; k < f.dims.z; ++k) {
                const double d = latticeDepth(f, k);
                const std::size_t idx = f.index(i, j, k);
                if (d < -eta - 1e-6 || d > D + 1e-6) {
                    EXPECT_FALSE(f.isValid(idx)) << "column " << i << "," << j << " depth " << d;
                    continue;
                }
                EXPECT_TRUE(f.isValid(idx)) << "column " << i << "," << j << " depth " << d;
                if (d < lo || d > hi) continue;  // the half layers take the nearest level's value
                EXPECT_NEAR(f.values[idx], d, 1e-4 * std::max(1.0, d)) << "column " << i << "," << j << " k " << k;
                ++exact;
            }
        }
    return exact;
}

io::FieldRequest temp() {
    io::FieldRequest r;
    r.variable = "temp";
    return r;
}

}  // namespace

TEST(VerticalFormulaParse, TermsAndVariablesInOrderWithLooseColons) {
    // "term:variable" pairs joined back into one text: the parse must give the same pairs
    auto pairs = [](const std::string& text) {
        std::string joined;
        for (const auto& t : io::detail::parseFormulaTerms(text, "x")) joined += t.term + "=" + t.variable + ";";
        return joined;
    };
    EXPECT_EQ(pairs("s: s_rho C: Cs_r eta: zeta depth: h depth_c: hc"), "s=s_rho;C=Cs_r;eta=zeta;depth=h;depth_c=hc;");
    EXPECT_EQ(pairs("  sigma : sig\teta:zeta  depth :h "), "sigma=sig;eta=zeta;depth=h;");
}

TEST(VerticalFormulaParse, MalformedTextsAreRefusedSayingWhy) {
    using io::detail::parseFormulaTerms;
    EXPECT_THROW_WITH(parseFormulaTerms("sigma: s eta eta depth: h", "f"), InputError, "'eta' is not of the form 'term:'");
    EXPECT_THROW_WITH(parseFormulaTerms("sigma: s eta:", "f"), InputError, "term 'eta' names no variable");
    EXPECT_THROW_WITH(parseFormulaTerms("sigma: eta: e", "f"), InputError, "term 'sigma' names no variable");
    EXPECT_THROW_WITH(parseFormulaTerms("s: a s: b", "f"), InputError, "term 's' comes twice");
    EXPECT_THROW_WITH(parseFormulaTerms(": a", "f"), InputError, "a ':' without a term");
    EXPECT_THROW_WITH(parseFormulaTerms("", "f"), InputError, "is empty");
}

TEST(VerticalFormulaColumns, OceanSigmaCoordinate) {
    const std::vector<double> sigma = {-0.95, -0.8, -0.6, -0.4, -0.2, -0.05};
    auto depthOf = [&](std::size_t k, double D, double eta) { return -(eta + sigma[k] * (D + eta)); };
    Columns c("ocean_sigma_coordinate", "sigma: lev eta: eta depth: depth", sigma, depthOf);
    ScalarField f = io::readCfDataset(c.data, temp());
    EXPECT_TRUE(hasNote(f, "parametric, ocean_sigma_coordinate (sigma: lev, eta: eta, depth: depth)"));
    EXPECT_GT(expectValuesAreDepths(f, depthOf), 30);
}

TEST(VerticalFormulaColumns, OceanSCoordinateG1AndG2) {
    const std::vector<double> s = {-11.0 / 12, -9.0 / 12, -7.0 / 12, -5.0 / 12, -3.0 / 12, -1.0 / 12};
    std::vector<double> C;
    for (double x : s) C.push_back(-x * x);  // any stretching; here C = -s^2
    const double hc = 40.0;
    auto g1 = [&](std::size_t k, double D, double eta) {
        double S = hc * s[k] + (D - hc) * C[k];
        return -(S + eta * (1.0 + S / D));
    };
    auto g2 = [&](std::size_t k, double D, double eta) {
        double S = (hc * s[k] + D * C[k]) / (hc + D);
        return -(eta + (eta + D) * S);
    };
    for (auto [name, depthOf] : {std::pair<std::string, std::function<double(std::size_t, double, double)>>{"ocean_s_coordinate_g1", g1},
                                 {"ocean_s_coordinate_g2", g2}}) {
        Columns c(name, "s: lev C: Cs eta: eta depth: depth depth_c: hc", s, depthOf);
        c.level("Cs", C);
        c.scalar("hc", hc);
        ScalarField f = io::readCfDataset(c.data, temp());
        EXPECT_TRUE(hasNote(f, "parametric, " + name)) << name;
        EXPECT_GT(expectValuesAreDepths(f, depthOf), 30) << name;
    }
}

TEST(VerticalFormulaColumns, OceanSCoordinateAndDoubleSigma) {
    const std::vector<double> s = {-11.0 / 12, -9.0 / 12, -7.0 / 12, -5.0 / 12, -3.0 / 12, -1.0 / 12};
    const double a = 3.0, b = 0.5, hc = 20.0;
    auto sc = [&](std::size_t k, double D, double eta) {
        double C = (1 - b) * std::sinh(a * s[k]) / std::sinh(a) +
                   b * (std::tanh(a * (s[k] + 0.5)) / (2 * std::tanh(0.5 * a)) - 0.5);
        return -(eta * (1 + s[k]) + hc * s[k] + (D - hc) * C);
    };
    Columns c("ocean_s_coordinate", "s: lev eta: eta depth: depth a: a b: b depth_c: hc", s, sc);
    c.scalar("a", a);
    c.scalar("b", b);
    c.scalar("hc", hc);
    EXPECT_GT(expectValuesAreDepths(io::readCfDataset(c.data, temp()), sc), 30);

    // Double sigma: sigma 0..1 above f, 1..2 below; this file's z is positive down.
    const std::vector<double> sigma = {0.1, 0.5, 0.9, 1.2, 1.6, 1.95};
    const double z1 = 40.0, z2 = 80.0, aa = 30.0, href = 250.0;
    auto ds = [&](std::size_t k, double D, double) {
        double f = 0.5 * (z1 + z2) + 0.5 * (z1 - z2) * std::tanh(2 * aa / (z1 - z2) * (D - href));
        return sigma[k] <= 1 ? sigma[k] * f : f + (sigma[k] - 1) * (D - f);
    };
    Columns d("ocean_double_sigma_coordinate", "sigma: lev depth: depth z1: z1 z2: z2 a: a href: href k_c: k_c", sigma, ds);
    for (auto [n, v] : {std::pair<const char*, double>{"z1", z1}, {"z2", z2}, {"a", aa}, {"href", href}, {"k_c", 3.0}})
        d.scalar(n, v);
    // No eta here: the surface is at 0, so the columns with eta != 0 in Columns do not matter.
    ScalarField f = io::readCfDataset(d.data, temp());
    int exact = 0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < f.dims.z; ++k) {
                const double dep = latticeDepth(f, k), D = Columns::D(std::size_t(i), std::size_t(j));
                if (dep > D + 1e-6) {
                    EXPECT_FALSE(f.isValid(f.index(i, j, k)));
                    continue;
                }
                if (dep < ds(0, D, 0) || dep > ds(5, D, 0)) continue;
                ASSERT_TRUE(f.isValid(f.index(i, j, k)));
                EXPECT_NEAR(f.values[f.index(i, j, k)], dep, 1e-4 * std::max(1.0, dep));
                ++exact;
            }
    EXPECT_GT(exact, 30);
}

TEST(VerticalFormulaColumns, DepthsGivenByAFourDimensionalVariable) {
    // z*: depth(time, lev, lat, lon) named in temp's coordinates; the nominal lev axis is 1-D.
    Columns c("", "", {5, 15, 30, 60, 120, 200}, [](std::size_t, double, double) { return 0.0; });
    c.data.variables[3].attributes = {{"units", "m"}, {"positive", "down"}};  // lev: a plain depth axis
    std::vector<double> depth, tempValues;
    for (std::size_t k = 0; k < Columns::nk; ++k)
        for (std::size_t j = 0; j < 3; ++j)
            for (std::size_t i = 0; i < 3; ++i) {
                double d = (double(k) + 0.5) / double(Columns::nk) * Columns::D(i, j);
                depth.push_back(d);
                tempValues.push_back(d);
            }
    c.data.variables.push_back(variable("zdepth", {"time", "lev", "lat", "lon"}, {1, Columns::nk, 3, 3}, depth,
                                        {{"units", "m"}, {"positive", "down"}, {"standard_name", "depth"}}));
    c.data.variables[6].values = tempValues;
    c.data.variables[6].attributes["coordinates"] = "time zdepth lat lon";
    ScalarField f = io::readCfDataset(c.data, temp());
    EXPECT_TRUE(hasNote(f, "depths given by zdepth(time, lev, lat, lon)"));
    int exact = 0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const double D = Columns::D(std::size_t(i), std::size_t(j));
            const double lo = 0.5 / 6 * D, hi = 5.5 / 6 * D;
            for (int k = 0; k < f.dims.z; ++k) {
                const double d = latticeDepth(f, k);
                const bool inside = d >= lo - 1e-6 && d <= hi + 1e-6;
                EXPECT_EQ(f.isValid(f.index(i, j, k)), inside) << i << "," << j << " depth " << d;
                if (!inside) continue;
                EXPECT_NEAR(f.values[f.index(i, j, k)], d, 1e-4 * std::max(1.0, d));
                ++exact;
            }
        }
    EXPECT_GT(exact, 30);
}

TEST(VerticalFormulaColumns, MaskedNativeLevelsAreNotInterpolatedAcross) {
    const std::vector<double> sigma = {-0.95, -0.8, -0.6, -0.4, -0.2, -0.05};
    auto depthOf = [&](std::size_t k, double D, double eta) { return -(eta + sigma[k] * (D + eta)); };
    Columns c("ocean_sigma_coordinate", "sigma: lev eta: eta depth: depth", sigma, depthOf);
    auto& t = std::get<std::vector<double>>(c.data.variables[6].values);
    t[2 * 9 + 4] = NAN;  // level 2 of the centre column (i = j = 1)
    ScalarField f = io::readCfDataset(c.data, temp());
    const double D = Columns::D(1, 1), eta = Columns::eta(1, 1);
    const double d1 = depthOf(1, D, eta), d2 = depthOf(2, D, eta), d3 = depthOf(3, D, eta);
    int masked = 0;
    for (int k = 0; k < f.dims.z; ++k) {
        const double d = latticeDepth(f, k);
        if (d > std::min(d1, d3) + 1e-6 && d < std::max(d1, d3) - 1e-6) {
            EXPECT_FALSE(f.isValid(f.index(1, 1, k))) << "depth " << d << " next to the masked level at " << d2;
            ++masked;
        }
    }
    EXPECT_GT(masked, 0);
}

TEST(VerticalFormulaFiles, SigmaSmallFollowsTheSurfaceOfEachTimeStep) {
    // make_sigma.py: temp = 20 - 0.01 * (depth below the surface), eta 0 then up to 1 m.
    const std::string path = test::testData("netcdf/sigma_small.nc");
    for (const char* time : {"0", "1"}) {
        io::FieldRequest r = temp();
        r.time = time;
        ScalarField f = io::NetcdfReader::read(path, r);
        EXPECT_TRUE(hasNote(f, "ocean_sigma_coordinate (sigma: sigma, eta: eta, depth: depth)"));
        const double R = 6371.0, deg = std::numbers::pi / 180.0;
        int checked = 0;
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) {
                const double lon = f.geographic.lon0 + (f.origin.x + f.axisPosition(0, i)) / (R * std::cos(f.geographic.lat0 * deg)) / deg;
                const double lat = f.geographic.lat0 + (f.origin.y + f.axisPosition(1, j)) / R / deg;
                const double D = 20.0 + 400.0 * (lon - 10.0) / 4.0 * (0.5 + 0.5 * (lat - 40.0) / 3.0);
                const double eta = std::string(time) == "0" ? 0.0 : (lat - 40.0) / 3.0;
                for (int k = 0; k < f.dims.z; ++k) {
                    const double d = latticeDepth(f, k);
                    const std::size_t idx = f.index(i, j, k);
                    if (d > D + 1e-3 || d < -eta - 1e-3) {
                        EXPECT_FALSE(f.isValid(idx)) << lon << "," << lat << " depth " << d;
                        continue;
                    }
                    // between the shallowest and the deepest level (sigma -1/16 and -15/16): the linear law
                    const double below = d + eta;
                    if (below < (D + eta) / 16.0 + 1e-3 || below > (D + eta) * 15.0 / 16.0 - 1e-3) continue;
                    ASSERT_TRUE(f.isValid(idx));
                    EXPECT_NEAR(f.values[idx], 20.0 - 0.01 * below, 2e-4);
                    ++checked;
                }
            }
        EXPECT_GT(checked, 200) << time;
    }
}

TEST(VerticalFormulaFiles, RomsLikeFileOverEtopo20AgreesWithLevitus) {
    // make_sigma.py interpolated Levitus's TEMP onto 20 s-levels over ETOPO20; read back on the
    // lattice, a deep column must give Levitus's profile again (within the interpolation error).
    const std::string levitusPath = test::sharedData("ocean/levitus_climatology.cdf");
    if (levitusPath.empty()) GTEST_SKIP() << "shared data absent";
    io::FieldRequest r = test::regionRequest("temp", -66.2, -63.8, 34.8, 35.2);  // Sargasso Sea, > 5000 m deep
    r.time = "0";
    r.hasDepthRange = true;
    r.depthRange[0] = 0.0;
    r.depthRange[1] = 2000.0;
    ScalarField roms = io::NetcdfReader::read(test::testData("netcdf/roms_g2_nwatlantic.nc"), r);
    EXPECT_TRUE(hasNote(roms, "ocean_s_coordinate_g2 (s: s_rho, C: Cs_r, eta: zeta, depth: h, depth_c: hc)"));
    EXPECT_GT(roms.dims.z, 5);
    // Levitus at 64.5W (and 63.5W) 34.5N/35.5N, levels 0..2000 m, averaged over the two latitudes
    io::FieldRequest lr = test::regionRequest("TEMP", -64.6, -63.4, 34.4, 35.6);
    ScalarField lev = io::NetcdfReader::read(levitusPath, lr);
    ASSERT_EQ(lev.dims.y, 2);
    auto levitusAt = [&](double depth) {
        for (int k = 0; k + 1 < lev.dims.z; ++k) {
            double d0 = latticeDepth(lev, k), d1 = latticeDepth(lev, k + 1);  // deepest first
            if (depth <= d0 && depth >= d1) {
                double w = (d0 - depth) / (d0 - d1);
                double a = 0.5 * (lev.values[lev.index(0, 0, k)] + lev.values[lev.index(0, 1, k)]);
                double b = 0.5 * (lev.values[lev.index(0, 0, k + 1)] + lev.values[lev.index(0, 1, k + 1)]);
                return a * (1 - w) + b * w;
            }
        }
        return double(NAN);
    };
    int i = 0;  // the column nearest 64.5W
    for (int n = 0; n < roms.dims.x; ++n)
        if (std::abs(roms.origin.x + roms.axisPosition(0, n) - (-0.5 * 111.19 * std::cos(35.0 * std::numbers::pi / 180))) <
            std::abs(roms.origin.x + roms.axisPosition(0, i) - (-0.5 * 111.19 * std::cos(35.0 * std::numbers::pi / 180))))
            i = n;
    int compared = 0;
    for (int k = 0; k < roms.dims.z; ++k) {
        const double d = latticeDepth(roms, k);
        const double want = levitusAt(d);
        if (std::isnan(want)) continue;
        ASSERT_TRUE(roms.isValid(roms.index(i, 0, k))) << d;
        // Above 700 m the s-levels are tens of metres apart; below, 20 levels over 5400 m are
        // ~300 m apart at 1000 m and their chord misses Levitus's thermocline curve by < 1 degC.
        EXPECT_NEAR(roms.values[roms.index(i, 0, k)], want, d < 700.0 ? 0.2 : 1.0) << "depth " << d;
        ++compared;
    }
    EXPECT_GE(compared, 5);
}

TEST(VerticalFormulaFiles, RomsLikeFileMasksBelowTheShelfFloorAndHonoursTime) {
    const std::string path = test::testData("netcdf/roms_g2_nwatlantic.nc");
    io::FieldRequest r = test::regionRequest("temp", -75.0, -70.0, 38.0, 41.0);  // shelf and slope south of New England
    r.time = "0";
    ScalarField t0 = io::NetcdfReader::read(path, r);
    // every valid sample lies above its column's floor: count columns whose deepest valid
    // lattice level is shallower than 200 m (the shelf) and deeper than 2000 m (the slope)
    int shelf = 0, deep = 0;
    for (int j = 0; j < t0.dims.y; ++j)
        for (int i = 0; i < t0.dims.x; ++i) {
            double deepest = -1.0;
            for (int k = 0; k < t0.dims.z; ++k)
                if (t0.isValid(t0.index(i, j, k))) deepest = std::max(deepest, latticeDepth(t0, k));
            if (deepest >= 0 && deepest < 200) ++shelf;
            if (deepest > 2000) ++deep;
        }
    EXPECT_GT(shelf, 10);
    EXPECT_GT(deep, 10);
    r.time = "2000-01-02";
    ScalarField t1 = io::NetcdfReader::read(path, r);
    EXPECT_TRUE(hasNote(t1, "nearest step 1"));
    ASSERT_EQ(t1.sampleCount(), t0.sampleCount());
    EXPECT_NE(std::memcmp(t0.values.data(), t1.values.data(), t0.values.size() * sizeof(float)), 0);
}

TEST(VerticalFormulaFiles, DepthRangeAndVerticalScaleWorkAsOnZLevels) {
    io::FieldRequest r = temp();
    r.time = "0";
    r.hasDepthRange = true;
    r.depthRange[0] = 100.0;
    r.depthRange[1] = 300.0;
    r.verticalScale = 50.0;
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/sigma_small.nc"), r);
    EXPECT_EQ(f.geographic.verticalScale, 50.0);
    ASSERT_GE(f.dims.z, 2);
    for (int k = 0; k < f.dims.z; ++k) {
        EXPECT_GE(latticeDepth(f, k), 100.0 - 1e-6);
        EXPECT_LE(latticeDepth(f, k), 300.0 + 1e-6);
    }
}

// Both ROMS-like files: on 1-D longitude/latitude and on the curvilinear grid (2-D lat_rho/lon_rho).
TEST(VerticalFormulaFiles, InMemoryTwinOfTheRomsFileGivesTheSameFieldBitForBit) {
    for (const char* name : {"netcdf/roms_g2_nwatlantic.nc", "netcdf/roms_curvilinear_nwatlantic.nc"}) {
        SCOPED_TRACE(name);
        const std::string path = test::testData(name);
        auto arrays = test::cfDatasetFromGdal(path, "ROMS twin");
        io::FieldRequest r = test::regionRequest("temp", -76.0, -60.0, 33.0, 44.0);
        r.time = "1";
        ScalarField file = io::NetcdfReader::read(path, r);
        ScalarField memory = io::readCfDataset(arrays->data, r);
        ASSERT_EQ(memory.dims, file.dims);
        EXPECT_EQ(memory.coords[2], file.coords[2]);
        EXPECT_EQ(std::memcmp(memory.values.data(), file.values.data(), file.values.size() * sizeof(float)), 0);
        EXPECT_EQ(memory.valid, file.valid);
        EXPECT_EQ(memory.notes, file.notes);
    }
}

TEST(VerticalFormulaInvalid, CorpusFilesAreRefusedNamingTheTermAndVariable) {
    io::FieldRequest r = temp();
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_formula_terms_missing_variable.nc"), r),
                      InputError, "name variable 'eta' for term 'eta', which the file does not have");
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_formula_terms_malformed.nc"), r), InputError,
                      "formula_terms 'sigma: sigma eta eta depth: depth' is malformed: 'eta' is not of the form 'term:'");
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_formula_terms_shape.nc"), r), InputError,
                      "depth(lat_v, lon): its dimension 'lat_v' is not one of variable temp(time, sigma, lat, lon)'s");
}

TEST(VerticalFormulaInvalid, KnownFormulaWithoutTermsOrWithAMissingTermIsRefused) {
    const std::vector<double> sigma = {-0.95, -0.8, -0.6, -0.4, -0.2, -0.05};
    auto depthOf = [&](std::size_t k, double D, double eta) { return -(eta + sigma[k] * (D + eta)); };
    Columns none("ocean_sigma_coordinate", "", sigma, depthOf);
    none.data.variables[3].attributes.erase("formula_terms");
    EXPECT_THROW_WITH(io::readCfDataset(none.data, temp()), InputError, "has no formula_terms attribute");
    Columns lacking("ocean_sigma_coordinate", "sigma: lev depth: depth", sigma, depthOf);
    EXPECT_THROW_WITH(io::readCfDataset(lacking.data, temp()), InputError, "lacks term 'eta'");
    Columns unknown("atmosphere_ln_pressure_coordinate", "p0: p lev: lev", sigma, depthOf);
    EXPECT_THROW_WITH(io::readCfDataset(unknown.data, temp()), InputError, "not a formula octrace evaluates");
}

TEST(VerticalFormulaFiles, InfoSaysTheFormulaItsTermsAndTheLattice) {
    io::FieldRequest r = temp();
    r.time = "0";
    const std::string text = io::NetcdfReader::describe(test::testData("netcdf/roms_g2_nwatlantic.nc"), r);
    for (const char* part : {"s_rho = 20: vertical (positive up), parametric: ocean_s_coordinate_g2, formula_terms 's: "
                             "s_rho C: Cs_r eta: zeta depth: h depth_c: hc'",
                             "note: vertical: parametric, ocean_s_coordinate_g2 (s: s_rho, C: Cs_r, eta: zeta, depth: h, "
                             "depth_c: hc), depths computed per column",
                             "note: vertical: 20 native levels per column resampled onto 24 levels 0 .. 5603.81 m",
                             "the median level spacing of the columns at each depth"})
        EXPECT_NE(text.find(part), std::string::npos) << "lacks '" << part << "' in\n" << text;
    // the terms are not offered as volumes: without `var`, temp is the one
    const std::string plain = io::NetcdfReader::describe(test::testData("netcdf/roms_g2_nwatlantic.nc"), io::FieldRequest{});
    EXPECT_NE(plain.find("grid of temp (whole grid)"), std::string::npos) << plain;
}

// The ROMS-like file on a curvilinear grid (make_sigma.py: 2-D lat_rho/lon_rho turned 30
// degrees, the same s-levels, h from ETOPO20 and temperatures from Levitus) against the same
// model set-up on ETOPO20's own regular grid: a Sargasso Sea column's profile agrees, both
// reach the surface, and both reach the deep floor there (over 5000 m).
TEST(VerticalFormulaFiles, RomsLikeFileOnACurvilinearGridHasTheRegularFilesColumns) {
    io::FieldRequest r = test::regionRequest("temp", -66.0, -63.0, 33.5, 36.5);
    r.time = "0";
    r.horizontalSamples = 10;
    ScalarField curvi = io::NetcdfReader::read(test::testData("netcdf/roms_curvilinear_nwatlantic.nc"), r);
    ScalarField regular = io::NetcdfReader::read(test::testData("netcdf/roms_g2_nwatlantic.nc"), r);
    EXPECT_TRUE(hasNote(curvi, "curvilinear grid: 2-D coordinates lon_rho(eta_rho, xi_rho) and lat_rho(eta_rho, xi_rho)"));
    EXPECT_TRUE(hasNote(curvi, "ocean_s_coordinate_g2 (s: s_rho, C: Cs_r, eta: zeta, depth: h, depth_c: hc)"));
    EXPECT_TRUE(hasNote(curvi, "each column's depths resampled onto the horizontal lattice with the field's weights"));
    // The profile of each at the centre of the region (64.5 W, 35 N), by depth.
    auto profile = [](const ScalarField& f) {
        const int i = f.dims.x / 2, j = f.dims.y / 2;
        std::vector<std::pair<double, double>> p;  // (depth, value), valid only, ascending depth
        for (int k = 0; k < f.dims.z; ++k)
            if (f.isValid(f.index(i, j, k))) p.emplace_back(latticeDepth(f, k), f.values[f.index(i, j, k)]);
        std::sort(p.begin(), p.end());
        return p;
    };
    const auto a = profile(curvi), b = profile(regular);
    ASSERT_GE(a.size(), 10u);
    ASSERT_GE(b.size(), 10u);
    EXPECT_LT(a.front().first, 10.0);  // from the surface
    EXPECT_GT(a.back().first, 4000.0);  // to the abyssal floor
    EXPECT_NEAR(a.back().first, b.back().first, 300.0);  // the same floor, within ETOPO20's relief between the grids
    int compared = 0;
    for (const auto& [d, v] : a) {
        if (d < b.front().first || d > b.back().first || d > 3000.0) continue;
        auto it = std::lower_bound(b.begin(), b.end(), std::make_pair(d, -1e30));
        if (it == b.begin()) continue;
        const auto& [d1, v1] = *it;
        const auto& [d0, v0] = *(it - 1);
        const double want = v0 + (v1 - v0) * (d - d0) / (d1 - d0);
        // above 700 m tens of metres between s-levels; deeper ~300 m, whose chords differ more
        EXPECT_NEAR(v, want, d < 700.0 ? 0.3 : 1.0) << "depth " << d;
        ++compared;
    }
    EXPECT_GE(compared, 8);
}

TEST(VerticalFormulaFiles, InfoOnACurvilinearRomsFileSaysTheGridTheFormulaAndTheResampling) {
    io::FieldRequest r = temp();
    r.time = "0";
    const std::string text = io::NetcdfReader::describe(test::testData("netcdf/roms_curvilinear_nwatlantic.nc"), r);
    for (const char* part : {"parametric: ocean_s_coordinate_g2, formula_terms 's: s_rho C: Cs_r eta: zeta depth: h depth_c: hc'",
                             "note: curvilinear grid: 2-D coordinates lon_rho(eta_rho, xi_rho) and lat_rho(eta_rho, xi_rho), source 100 x 96 points",
                             "resampled onto a regular",
                             "note: vertical: each column's depths resampled onto the horizontal lattice with the field's weights",
                             "note: vertical: 20 native levels per column resampled onto"})
        EXPECT_NE(text.find(part), std::string::npos) << "lacks '" << part << "' in\n" << text;
}
