// Coastlines: GSHHG's binned shorelines decoded from the files Debian installs
// (/usr/share/gmt-gshhg, gmt-gshhg-low and -high), checked against places whose coast is
// known, and the OGR path on the small committed GeoJSON files of tests/data/coastline.
#include "octrace/io/Coastline.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

using namespace octrace;
using namespace octrace::io;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Great-circle-free distance in km between two nearby points (equirectangular at their mid latitude).
double km(dvec2 a, dvec2 b) {
    const double c = std::cos(0.5 * (a.y + b.y) * kPi / 180.0);
    return 6371.0 * kPi / 180.0 * std::hypot((a.x - b.x) * c, a.y - b.y);
}

/// The shortest distance in km from `p` to any segment of the lines (segments measured in the
/// equirectangular plane at p's latitude).
double distanceKm(const Coastlines& c, dvec2 p) {
    const double cosLat = std::cos(p.y * kPi / 180.0);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& line : c.lines)
        for (std::size_t i = 1; i < line.size(); ++i) {
            const dvec2 a((line[i - 1].x - p.x) * cosLat, line[i - 1].y - p.y), b((line[i].x - p.x) * cosLat, line[i].y - p.y);
            const dvec2 d = b - a;
            const double t = glm::dot(d, d) > 0.0 ? std::clamp(-glm::dot(a, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
            best = std::min(best, glm::length(a + t * d) * 6371.0 * kPi / 180.0);
        }
    return best;
}

bool haveGshhg(GshhgResolution r) { return std::filesystem::exists(gshhgPath(r)); }

#define REQUIRE_GSHHG(r) \
    if (!haveGshhg(r)) GTEST_SKIP() << gshhgPath(r) << " absent: install " << gshhgPackage(r)

const GshhgResolution kAll[] = {GshhgResolution::Crude, GshhgResolution::Low, GshhgResolution::Intermediate, GshhgResolution::High};

std::string data(const std::string& name) { return std::string(OCTRACE_TEST_DATA) + "/" + name; }

/// Sets an environment variable for the scope of a test.
struct ScopedEnv {
    ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
    ~ScopedEnv() { unsetenv(name_); }
    const char* name_;
};

}  // namespace

// Cape Town lies on Table Bay: some shoreline passes within a few km of the city centre at every
// resolution but crude (whose points lie ~25 km apart), and none within 300 km of Johannesburg.
TEST(Gshhg, ACoastPassesCapeTownAndNoneJohannesburg) {
    const LonLatBox southAfrica{10.0, 35.0, -40.0, -20.0};
    const double withinKm[] = {40.0, 10.0, 4.0, 4.0};
    for (int i = 0; i < 4; ++i) {
        REQUIRE_GSHHG(kAll[i]);
        const Coastlines c = readGshhg(kAll[i], southAfrica);
        EXPECT_GT(c.lines.size(), 0u);
        EXPECT_LT(distanceKm(c, {18.42, -33.92}), withinKm[i]) << gshhgResolutionName(kAll[i]);
        EXPECT_GT(distanceKm(c, {28.04, -26.20}), 300.0) << gshhgResolutionName(kAll[i]);
    }
}

// Tasmania is one polygon cut into pieces at the bins' edges: following piece to piece from the
// piece nearest Hobart comes back to where it started, and the ring spans Tasmania's extent.
TEST(Gshhg, TasmaniasPiecesCloseIntoOneRing) {
    for (GshhgResolution r : {GshhgResolution::Low, GshhgResolution::Intermediate, GshhgResolution::High}) {
        REQUIRE_GSHHG(r);
        const Coastlines c = readGshhg(r, {140.0, 152.0, -46.0, -38.0});
        // The piece nearest Hobart.
        std::size_t first = 0;
        double best = 1e30;
        for (std::size_t i = 0; i < c.lines.size(); ++i) {
            Coastlines one;
            one.lines = {c.lines[i]};
            const double d = distanceKm(one, {147.33, -42.88});
            if (d < best) best = d, first = i;
        }
        ASSERT_LT(best, 10.0) << gshhgResolutionName(r);
        const double tolerance = 1e-3;  // degrees: pieces meet at the same edge point
        std::vector<bool> used(c.lines.size(), false);
        used[first] = true;
        const dvec2 start = c.lines[first].front();
        dvec2 end = c.lines[first].back();
        dvec2 lo = start, hi = start;
        std::size_t pieces = 1;
        while (km(end, start) > tolerance * 111.0) {
            std::size_t next = c.lines.size();
            bool reversed = false;
            for (std::size_t i = 0; i < c.lines.size() && next == c.lines.size(); ++i) {
                if (used[i]) continue;
                if (glm::length(c.lines[i].front() - end) < tolerance) next = i;
                else if (glm::length(c.lines[i].back() - end) < tolerance) next = i, reversed = true;
            }
            ASSERT_LT(next, c.lines.size()) << gshhgResolutionName(r) << ": the ring stops at " << end.x << ", " << end.y
                                            << " after " << pieces << " pieces";
            used[next] = true;
            ++pieces;
            for (const dvec2& p : c.lines[next]) lo = glm::min(lo, p), hi = glm::max(hi, p);
            end = reversed ? c.lines[next].front() : c.lines[next].back();
        }
        for (const dvec2& p : c.lines[first]) lo = glm::min(lo, p), hi = glm::max(hi, p);
        // Low's bins are 10° (Tasmania lies in one); intermediate's and high's 5° cut it at 145°E.
        if (r != GshhgResolution::Low) {
            EXPECT_GT(pieces, 1u) << "Tasmania spans several bins";
        }
        // Tasmania: 144.6°E (west coast) to 148.4°E, 40.6°S to 43.65°S.
        EXPECT_NEAR(lo.x, 144.6, 0.3) << gshhgResolutionName(r);
        EXPECT_NEAR(hi.x, 148.35, 0.3) << gshhgResolutionName(r);
        EXPECT_NEAR(lo.y, -43.65, 0.2) << gshhgResolutionName(r);
        EXPECT_NEAR(hi.y, -40.65, 0.2) << gshhgResolutionName(r);
    }
}

// Over the globe (-180..180 or 0..360) no line jumps across it and every piece meets the box; over the Pacific across the dateline (160°E to
// 160°W as 160..200) Samoa comes at 187.6 (172.4°W unwrapped) and Fiji at 178°E.
TEST(Gshhg, LinesStayContiguousAcrossTheDateline) {
    for (GshhgResolution r : {GshhgResolution::Crude, GshhgResolution::Low}) {
        REQUIRE_GSHHG(r);
        for (const LonLatBox box : {LonLatBox{-180.0, 180.0, -90.0, 90.0}, LonLatBox{0.0, 360.0, -90.0, 90.0}}) {
            const Coastlines c = readGshhg(r, box);
            ASSERT_GT(c.lines.size(), 100u);
            double maxStep = 0.0;
            for (const auto& line : c.lines) {
                double lo = line[0].x, hi = lo;
                for (std::size_t i = 1; i < line.size(); ++i) {
                    maxStep = std::max(maxStep, std::abs(line[i].x - line[i - 1].x));
                    lo = std::min(lo, line[i].x), hi = std::max(hi, line[i].x);
                }
                // Each piece (whole, not clipped) meets the box.
                EXPECT_LE(lo, box.lonMax);
                EXPECT_GE(hi, box.lonMin);
            }
            EXPECT_LT(maxStep, 20.0) << gshhgResolutionName(r);  // within a bin (20° in crude); a wrap would be ~360°
        }
        const Coastlines pacific = readGshhg(r, {160.0, 200.0, -25.0, 0.0});
        EXPECT_LT(distanceKm(pacific, {187.6, -13.8}), 60.0) << "Samoa, " << gshhgResolutionName(r);
        EXPECT_LT(distanceKm(pacific, {178.0, -17.8}), 60.0) << "Fiji, " << gshhgResolutionName(r);
        for (const auto& line : pacific.lines)
            for (const dvec2& p : line) ASSERT_GE(p.x, 140.0) << "a piece west of the box by a turn of the globe";
    }
}

// Only level 1 (land against ocean) by default: the Caspian Sea's shore is a lake's (level 2).
TEST(Gshhg, LakeShoresOnlyWhenAsked) {
    REQUIRE_GSHHG(GshhgResolution::Low);
    const LonLatBox caspian{45.0, 56.0, 36.0, 48.0};
    const Coastlines land = readGshhg(GshhgResolution::Low, caspian);
    const Coastlines lakes = readGshhg(GshhgResolution::Low, caspian, true);
    EXPECT_GT(distanceKm(land, {51.0, 42.0}) , 150.0);  // mid-Caspian: no sea coast near
    EXPECT_LT(distanceKm(lakes, {49.6, 37.5}), 20.0);   // Bandar-e Anzali on the Caspian's shore
}

TEST(Gshhg, ResolutionFollowsTheRegionsSize) {
    EXPECT_EQ(gshhgResolutionFor({-180, 180, -90, 90}), GshhgResolution::Crude);
    EXPECT_EQ(gshhgResolutionFor({-80, 0, 0, 70}), GshhgResolution::Low);  // the North Atlantic
    EXPECT_EQ(gshhgResolutionFor({-12, 0, 35, 45}), GshhgResolution::Intermediate);
    EXPECT_EQ(gshhgResolutionFor({-10, -7, 37, 40}), GshhgResolution::High);  // a few degrees
    EXPECT_EQ(gshhgPackage(GshhgResolution::Crude), "gmt-gshhg-low");
    EXPECT_EQ(gshhgPackage(GshhgResolution::High), "gmt-gshhg-high");
}

TEST(Gshhg, AMissingFileNamesThePackageAndAForeignFileIsRefused) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("octrace-gshhg-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    ScopedEnv env("OCTRACE_GSHHG_DIR", dir.string());
    try {
        readGshhg(GshhgResolution::High, {});
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("binned_GSHHS_h.nc"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("install the Debian package gmt-gshhg-high"), std::string::npos) << e.what();
    }
    // A NetCDF file that is not GSHHG's, under GSHHG's name.
    std::filesystem::copy_file(data("netcdf/cartesian.nc"), dir / "binned_GSHHS_c.nc");
    try {
        readGshhg(GshhgResolution::Crude, {});
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("not a GSHHG binned shoreline file"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

// The OGR path: a polygon's ring and a line across the dateline, unwrapped and placed in the box.
TEST(VectorCoastlines, GeoJsonRingsAndLinesLandInTheBox) {
    const Coastlines c = readVectorCoastlines(data("coastline/island.geojson"), {-180.0, 180.0, -90.0, 90.0});
    ASSERT_EQ(c.lines.size(), 3u);  // the square, and the dateline line twice: at 179.5..180.5 and -180.5..-179.5
    EXPECT_EQ(c.lines[0].size(), 5u);
    EXPECT_EQ(c.lines[0][2], dvec2(12.0, 41.0));
    EXPECT_DOUBLE_EQ(c.lines[1][0].x, -180.5);
    EXPECT_DOUBLE_EQ(c.lines[1][1].x, -179.5);
    EXPECT_DOUBLE_EQ(c.lines[2][0].x, 179.5);
    EXPECT_DOUBLE_EQ(c.lines[2][1].x, 180.5);
    const Coastlines pacific = readVectorCoastlines(data("coastline/island.geojson"), {150.0, 210.0, -20.0, 20.0});
    ASSERT_EQ(pacific.lines.size(), 1u);  // only the line; the square lies outside
    EXPECT_DOUBLE_EQ(pacific.lines[0][1].x, 180.5);
}

TEST(VectorCoastlines, AnotherCrsIsReprojectedToLongitudeLatitude) {
    const Coastlines c = readVectorCoastlines(data("coastline/island_3857.geojson"), {-180.0, 180.0, -90.0, 90.0});
    ASSERT_EQ(c.lines.size(), 1u);
    ASSERT_EQ(c.lines[0].size(), 5u);
    EXPECT_NEAR(c.lines[0][2].x, 12.0, 1e-7);
    EXPECT_NEAR(c.lines[0][2].y, 41.0, 1e-7);
}

/// Reads `file` (under tests/data) as coastlines and expects an `E` whose message holds `expect`.
template <typename E>
void expectRefusal(const std::string& file, const std::string& expect) {
    try {
        readVectorCoastlines(data(file), LonLatBox{});
        ADD_FAILURE() << file << ": no error";
    } catch (const E& e) {
        EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(data(file)), std::string::npos) << e.what();
    }
}

TEST(VectorCoastlines, InvalidFilesAreRefusedWithTheirMessage) {
    expectRefusal<FormatNotSupported>("invalid/invalid_coastline_not_vector.geojson", "OGR cannot open it as vector data");
    expectRefusal<InputError>("invalid/invalid_coastline_points_only.geojson", "no line or polygon in any layer");
    expectRefusal<FileError>("coastline/no_such_file.geojson", "no such coastline file");
}
