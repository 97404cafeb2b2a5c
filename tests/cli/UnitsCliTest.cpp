// Values given with a unit (`--iso 10degC`, `--colour-range 278.15K,293.15K`), converted by
// UDUNITS-2 into the units of the field, and a depth axis in centimetres, on the Levitus atlas
// and on tests/data/netcdf/levitus_{cm,kelvin}.nc (made from it by make_units_fixtures.py).
#include "CliRunner.h"

#include "../io/ImageTestSupport.h"

using namespace octrace::testcli;

namespace {

const std::string kKelvin = std::string(OCTRACE_TEST_DATA) + "/netcdf/levitus_kelvin.nc";
const std::string kCentimetres = std::string(OCTRACE_TEST_DATA) + "/netcdf/levitus_cm.nc";
// The fixtures hold the atlas over this region, whole.
const std::vector<std::string> kRegion = {"--region", "300,340,20,60"};

std::vector<std::string> args(std::vector<std::string> a, const std::vector<std::string>& more) {
    a.insert(a.end(), more.begin(), more.end());
    return a;
}

/// The largest difference of two PNGs' 8-bit channels (256 when their sizes differ). The same
/// surface from a field in K and in degC is the same up to the rounding of the normals'
/// gradients (values 273.15 apart in float): at most 1 in a channel of a few pixels.
int maxChannelDifference(const std::string& a, const std::string& b) {
    const auto pa = octrace::test::decodePng(octrace::test::readBytes(a)), pb = octrace::test::decodePng(octrace::test::readBytes(b));
    if (pa.width != pb.width || pa.height != pb.height || pa.channels != pb.channels) return 256;
    int most = 0;
    for (std::size_t i = 0; i < pa.pixels.size(); ++i) most = std::max(most, std::abs(int(pa.pixels[i]) - int(pb.pixels[i])));
    return most;
}

}  // namespace

TEST(UnitsCli, IsoInDegreesCelsiusOnAFieldInKelvinRendersAsTheAtlasInDegreesCelsius) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const std::vector<std::string> view = {"--var", "TEMP", "--size", "320x240", "--depth", "8"};
    Result r = run(args({"render", lev, "--iso", "10", "-o", s.path("c.png")}, args(view, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    r = run(args({"render", kKelvin, "--iso", "10degC", "--verbose", "--stats", s.path("k.json"), "-o", s.path("k.png")}, view));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("--iso 10degC is 283.15 K, the units of 'TEMP'"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("k.json")).find("\"iso\": 283.15,"), std::string::npos) << slurp(s.path("k.json"));
    const std::string celsius = slurp(s.path("c.png"));
    ASSERT_GT(celsius.size(), 1000u);
    EXPECT_LE(maxChannelDifference(s.path("k.png"), s.path("c.png")), 1) << "--iso 10degC on kelvin differs from --iso 10 on the atlas";
    // And the other way: kelvin given on the atlas's "DEG C".
    r = run(args({"render", lev, "--iso", "283.15 K", "-o", s.path("ck.png")}, args(view, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_LE(maxChannelDifference(s.path("ck.png"), s.path("c.png")), 1) << "--iso '283.15 K' on degC differs from --iso 10";
    // A wrong iso in K on the kelvin field is not the same surface (the comparison can fail).
    r = run(args({"render", kKelvin, "--iso", "285.15", "-o", s.path("k12.png")}, view));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GT(maxChannelDifference(s.path("k12.png"), s.path("c.png")), 1);
}

TEST(UnitsCli, ADepthAxisInCentimetresRendersAsTheAtlasInMetres) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const std::vector<std::string> view = {"--var", "TEMP", "--iso", "10", "--size", "320x240", "--floor"};
    Result r = run(args({"render", lev, "-o", s.path("m.png")}, args(view, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    r = run(args({"render", kCentimetres, "-o", s.path("cm.png")}, view));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(s.path("cm.png")) == slurp(s.path("m.png"))) << "centimetres differ from metres";
    r = run({"info", kCentimetres});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("vertical axis 'ZAXLEVITR' in centimeters, converted to metres (0.01 m each"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("20 levels 0 .. 5000 m"), std::string::npos) << r.out;
}

TEST(UnitsCli, ColourRangeWithUnitsIsConvertedIntoTheColouredVariablesUnits) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const std::vector<std::string> view = {"--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP", "--size", "240x180"};
    Result r = run(args({"render", lev, "--colour-range", "5,20", "-o", s.path("plain.png")}, args(view, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    r = run(args({"render", lev, "--colour-range", "278.15K,293.15K", "--stats", s.path("k.json"), "-o", s.path("k.png")},
                 args(view, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("k.json"));
    EXPECT_NE(js.find("\"colour_min\": 5,"), std::string::npos) << js;
    EXPECT_NE(js.find("\"colour_max\": 20,"), std::string::npos) << js;
    EXPECT_TRUE(slurp(s.path("k.png")) == slurp(s.path("plain.png")));
    // Heights of a surface coloured by height are metres: -1km,0km is -1000,0.
    const std::vector<std::string> height = {"--var", "TEMP", "--iso", "10", "--colormap", "viridis", "--size", "160x120"};
    r = run(args({"render", lev, "--colour-range", "-1000,0", "-o", s.path("h0.png")}, args(height, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    r = run(args({"render", lev, "--colour-range", "-1km,0km", "-o", s.path("h1.png")}, args(height, kRegion)));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(s.path("h0.png")) == slurp(s.path("h1.png")));
    // A slice's colour range is in the sliced variable's units.
    r = run({"slice", kKelvin, "--var", "TEMP", "--plane", "z", "--at", "100", "--colour-range", "5degC,20degC", "-o", s.path("s.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("over 278.15 .. 293.15 (--colour-range)"), std::string::npos) << r.err;
}

TEST(UnitsCli, RefusesUnitsThatDoNotFitTheField) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const auto render = [&](std::vector<std::string> more) {
        return run(args(args({"render", lev, "--size", "32x24", "-o", s.path("x.png")}, kRegion), more));
    };
    // A unit of another quantity: exit 1, naming what was given, the field's units and what to do.
    Result r = render({"--var", "TEMP", "--iso", "10m"});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("variable 'TEMP' is in DEG C: --iso 10m does not convert to DEG C (give a value in a unit of the same "
                         "quantity as DEG C, or a plain number in DEG C)"),
              std::string::npos)
        << r.err;
    // A field whose units UDUNITS-2 does not know (PPT).
    r = render({"--var", "SALT", "--iso", "10degC"});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("variable 'SALT' is in 'PPT', which UDUNITS-2 does not know, so --iso 10degC cannot be converted"),
              std::string::npos)
        << r.err;
    // A field without units.
    r = run({"render", "analytic:sphere:9", "--iso", "1degC", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("variable 'sphere' has no units, so --iso 1degC cannot be converted"), std::string::npos) << r.err;
    // A colour range that converts to a decreasing one.
    r = run({"slice", lev, "--var", "TEMP", "--plane", "z", "--at", "100", "--colour-range", "300K,5degC", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("--colour-range 300K,5degC is 26.85,5 DEG C, not an increasing range"), std::string::npos) << r.err;
    // An unknown unit is a malformed value: exit 2 before anything is read.
    for (const char* iso : {"10degx", "10 parsecsx"}) {
        r = render({"--var", "TEMP", "--iso", iso});
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_NE(r.err.find("--iso: unknown unit"), std::string::npos) << r.err;
    }
    r = render({"--var", "TEMP", "--colour-range", "5degC,20bogus", "--colormap", "viridis"});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("--colour-range: unknown unit 'bogus' in '20bogus'"), std::string::npos) << r.err;
    // The CT presets are still names, not units.
    r = render({"--var", "TEMP", "--iso", "skin"});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("--iso skin is a CT preset in Hounsfield units"), std::string::npos) << r.err;
}

TEST(UnitsCli, AMissingUnitDatabaseIsSaidClearly) {
    // The child inherits the environment: UDUNITS-2 then looks for its database where there is none.
    Scratch s;
    ASSERT_EQ(setenv("UDUNITS2_XML_PATH", s.path("none.xml").c_str(), 1), 0);
    const Result r = run({"render", kCentimetres, "--var", "TEMP", "--iso", "10", "-o", s.path("x.png")});
    unsetenv("UDUNITS2_XML_PATH");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("the UDUNITS-2 unit database could not be read (UDUNITS2_XML_PATH="), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("install Debian's libudunits2-data"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("x.png")));
}
