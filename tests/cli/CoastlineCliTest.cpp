// --coastline on figures: GSHHG's shorelines drawn where the Levitus atlas's land mask has its
// edge (a global depth slice at 1°), on 3-D figures behind the surface, from a vector file, and
// GSHHG not installed (the invalid coastline files: InvalidInputTest.cpp).
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include <cmath>
#include <cstdio>
#include <deque>

using namespace octrace::testcli;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

const char* kLevitus = "ocean/levitus_climatology.cdf";

/// The slice's rectangle in the figure, from --stats' figure_slice.
struct Rect {
    int x = 0, y = 0, w = 0, h = 0;
};
Rect figureSlice(const std::string& statsPath) {
    const std::string js = slurp(statsPath);
    Rect r;
    const std::size_t at = js.find("\"figure_slice\": \"");
    if (at != std::string::npos) std::sscanf(js.c_str() + at + 17, "%d,%d,%d,%d", &r.x, &r.y, &r.w, &r.h);
    return r;
}

/// The share of `coast` pixels (inside `r`) within `radius` pixels of an edge of `land` (a pixel
/// whose right or lower neighbour differs), each shifted `shift` pixels to the right first.
double shareNearEdges(const std::vector<bool>& coast, const std::vector<bool>& land, const Rect& r, int radius, int shift) {
    // Distance (chessboard) to the nearest edge by breadth-first search from the edges.
    std::vector<int> dist(std::size_t(r.w) * std::size_t(r.h), 1 << 30);
    std::deque<int> queue;
    for (int y = 0; y + 1 < r.h; ++y)
        for (int x = 0; x + 1 < r.w; ++x) {
            const int i = y * r.w + x;
            if (land[std::size_t(i)] != land[std::size_t(i + 1)] || land[std::size_t(i)] != land[std::size_t(i + r.w)])
                dist[std::size_t(i)] = 0, queue.push_back(i);
        }
    while (!queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        const int x = i % r.w, y = i / r.w;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= r.w || ny >= r.h) continue;
                const int j = ny * r.w + nx;
                if (dist[std::size_t(j)] > dist[std::size_t(i)] + 1) dist[std::size_t(j)] = dist[std::size_t(i)] + 1, queue.push_back(j);
            }
    }
    int total = 0, near = 0;
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            if (!coast[std::size_t(y * r.w + x)]) continue;
            const int sx = (x + shift) % r.w;
            ++total;
            near += dist[std::size_t(y * r.w + sx)] <= radius;
        }
    return total ? double(near) / total : 0.0;
}

}  // namespace

// A global map at the surface: the coastline's pixels (where the figure with coastlines differs
// from the one without) lie on the land mask's edge (masked samples in magenta), most within
// 2° (the atlas is 1°; GSHHG's islands and inlets finer than a cell have no masked cell). The
// same pixels moved 20° east far fewer: the check can fail.
TEST(CoastlineCli, GlobalSliceCoastlinesFollowTheLandMaskOfLevitus) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string lev = sharedData(kLevitus);
    const std::vector<std::string> base = {"slice", lev, "--var", "TEMP", "--plane", "z", "--at", "0", "--figure", "--masked-colour", "1,0,1"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    };
    Result r = run(with({"--coastline", "none", "--stats", s.path("none.json"), "-o", s.path("none.png")}));
    ASSERT_EQ(r.code, 0) << r.err;
    r = run(with({"--stats", s.path("auto.json"), "-o", s.path("auto.png")}));  // auto: GSHHG crude for the globe
    ASSERT_EQ(r.code, 0) << r.err;
    const Rect rect = figureSlice(s.path("none.json"));
    ASSERT_GT(rect.w, 300) << slurp(s.path("none.json"));
    const auto none = octrace::test::decodePng(octrace::test::readBytes(s.path("none.png")));
    const auto coast = octrace::test::decodePng(octrace::test::readBytes(s.path("auto.png")));
    std::vector<bool> land(std::size_t(rect.w) * std::size_t(rect.h)), line(land.size());
    int lines = 0, landPixels = 0;
    // The frame of the slice is drawn on its edge pixels: leave a margin of 3 pixels.
    for (int y = 3; y < rect.h - 3; ++y)
        for (int x = 3; x < rect.w - 3; ++x) {
            const int fx = rect.x + x, fy = rect.y + y;
            const std::size_t i = std::size_t(y) * std::size_t(rect.w) + std::size_t(x);
            land[i] = none.at(fx, fy, 0) == 255 && none.at(fx, fy, 1) == 0 && none.at(fx, fy, 2) == 255;
            line[i] = coast.at(fx, fy, 0) != none.at(fx, fy, 0) || coast.at(fx, fy, 1) != none.at(fx, fy, 1);
            lines += line[i];
            landPixels += land[i];
        }
    EXPECT_GT(landPixels, rect.w * rect.h / 10);
    EXPECT_GT(lines, 2000);
    const double pxPerDegree = rect.w / 360.0;
    const double share = shareNearEdges(line, land, rect, int(std::ceil(2.0 * pxPerDegree)), 0);
    const double shifted = shareNearEdges(line, land, rect, int(std::ceil(2.0 * pxPerDegree)), int(std::lround(20.0 * pxPerDegree)));
    const double near1 = shareNearEdges(line, land, rect, int(std::ceil(1.0 * pxPerDegree)), 0);
    std::printf("coastline pixels: %d, within 2 degrees of the mask's edge: %.3f (moved 20 degrees east: %.3f), within 1 degree: %.3f\n",
                lines, share, shifted, near1);
    EXPECT_GT(share, 0.85);
    EXPECT_GT(near1, 0.8);
    EXPECT_LT(shifted, 0.6);
}

// A 3-D figure of a geographic field has the coastline on the sea surface; --coastline none
// leaves it out, and a vector file's lines are drawn instead of GSHHG's.
TEST(CoastlineCli, RenderFiguresDrawCoastlinesFromGshhgOrAFile) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string lev = sharedData(kLevitus);
    auto render = [&](const std::string& coastline, const std::string& out) {
        return run({"render", lev, "--var", "TEMP", "--iso", "14", "--region", "0,30,30,50", "--depth", "7", "--size", "480x360",
                    "--figure", "--coastline", coastline, "-o", s.path(out)});
    };
    ASSERT_EQ(render("none", "none.png").code, 0);
    Result r = render("auto", "auto.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = render(std::string(OCTRACE_TEST_DATA) + "/coastline/island.geojson", "file.png");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto none = octrace::test::decodePng(octrace::test::readBytes(s.path("none.png")));
    auto differing = [&](const std::string& name) {
        const auto p = octrace::test::decodePng(octrace::test::readBytes(s.path(name)));
        int n = 0;
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x) n += p.at(x, y, 0) != none.at(x, y, 0) || p.at(x, y, 1) != none.at(x, y, 1);
        return n;
    };
    const int gshhg = differing("auto.png"), square = differing("file.png");
    EXPECT_GT(gshhg, 500) << "the Mediterranean's coasts";
    EXPECT_GT(square, 20) << "the square island at 10..12°E, 40..41°N";
    EXPECT_LT(square, gshhg / 4);
}

// The depth buffer hides the coastline behind the surface: seen from above, the TEMP = 10 °C
// surface lies below the sea surface and the coasts are drawn over it; seen from below, the
// surface is in front of the sea surface and hides them (no coastline pixel where a plain
// render shows the surface, but at its rim).
TEST(CoastlineCli, TheSurfaceHidesTheCoastlineBehindIt) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string lev = sharedData(kLevitus);
    auto render = [&](const std::string& coastline, const std::string& out, bool below) {
        std::vector<std::string> a = {"render", lev, "--var", "TEMP", "--iso", "10", "--region", "-100,20,0,70", "--depth", "7",
                                      "--size", "480x360", "--figure", "--coastline", coastline, "-o", s.path(out)};
        if (below) a.insert(a.end(), {"--camera-pos", "0,-14000,-6000", "--look-at", "0,0,-500", "--up", "0,0,1"});
        Result r = run(a);
        EXPECT_EQ(r.code, 0) << r.err;
        return octrace::test::decodePng(octrace::test::readBytes(s.path(out)));
    };
    int onSurface[2] = {0, 0}, drawn[2] = {0, 0};
    for (int below = 0; below < 2; ++below) {
        const auto none = render("none", "none.png", below), coast = render("low", "coast.png", below);
        for (int y = 1; y + 1 < none.height; ++y)
            for (int x = 1; x + 1 < none.width; ++x) {
                if (coast.at(x, y, 0) == none.at(x, y, 0) && coast.at(x, y, 1) == none.at(x, y, 1)) continue;
                ++drawn[below];
                // The surface (neither paper nor ink) here and all around, in the plain render.
                bool surface = true;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int r = none.at(x + dx, y + dy, 0), g = none.at(x + dx, y + dy, 1), b = none.at(x + dx, y + dy, 2);
                        surface = surface && !(r > 245 && g > 245 && b > 245) && (r + g + b > 60);
                    }
                onSurface[below] += surface;
            }
    }
    std::printf("coastline pixels drawn (on the surface): from above %d (%d), from below %d (%d)\n", drawn[0], onSurface[0],
                drawn[1], onSurface[1]);
    EXPECT_GT(drawn[1], 300) << "coasts where no surface is in front";
    EXPECT_GT(onSurface[0], 150);
    EXPECT_LT(onSurface[1], onSurface[0] / 20);
}

// GSHHG not installed: the default figure is drawn without coastlines and a warning names the
// package; asked for by resolution, it is an error naming the package.
TEST(CoastlineCli, MissingGshhgIsAWarningByDefaultAndAnErrorWhenAskedFor) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string lev = sharedData(kLevitus);
    setenv("OCTRACE_GSHHG_DIR", s.path("nowhere").c_str(), 1);
    Result r = run({"slice", lev, "--var", "TEMP", "--plane", "z", "--at", "0", "--figure", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "install the Debian package gmt-gshhg-low")) << r.err;
    EXPECT_TRUE(has(r.err, "the figure has no coastlines")) << r.err;
    r = run({"slice", lev, "--var", "TEMP", "--plane", "z", "--at", "0", "--figure", "--coastline", "high", "-o", s.path("b.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "install the Debian package gmt-gshhg-high")) << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("b.png")));
    unsetenv("OCTRACE_GSHHG_DIR");
}

// Coastlines asked for where there is no map: a warning says they are not drawn, and why.
TEST(CoastlineCli, AskedForWhereNoMapIsDrawnTheyAreNotDrawnWithAWarning) {
    Scratch s;
    Result r = run({"render", "analytic:sphere:6", "--size", "320x240", "--figure", "--coastline", "low", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "--coastline low is not drawn: the field is not on a longitude/latitude grid")) << r.err;
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent";
    r = run({"slice", sharedData(kLevitus), "--var", "TEMP", "--plane", "y", "--at", "30", "--figure", "--coastline", "low", "-o",
             s.path("b.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "--coastline low is not drawn: only a depth slice (plane z) is a map")) << r.err;
}
