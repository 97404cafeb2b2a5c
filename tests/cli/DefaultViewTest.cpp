// The first picture with no options (issue 27): `depth` auto from the data, a camera that
// frames the surface tightly (ocean north up, patient volumes from the front) and a default
// look (colour map or tissue colour, a background that contrasts with the surface).
#include "ChestCt.h"
#include "CliRunner.h"

#include "../io/ImageTestSupport.h"
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/model/Render.h"
#include "octrace/model/Surface.h"
#include "octrace/render/Shading.h"

#include <cmath>
#include <functional>
#include <regex>

using namespace octrace::testcli;
using octrace::dvec3;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

/// The number after "key": in the stats JSON.
double statNumber(const std::string& js, const std::string& key) {
    const std::size_t at = js.find("\"" + key + "\": ");
    if (at == std::string::npos) throw std::runtime_error("no " + key + " in " + js);
    return std::stod(js.substr(at + key.size() + 4));
}

/// The vector "x,y,z" of "key": in the stats JSON.
dvec3 statVector(const std::string& js, const std::string& key) {
    const std::size_t at = js.find("\"" + key + "\": \"");
    if (at == std::string::npos) throw std::runtime_error("no " + key + " in " + js);
    const std::string v = js.substr(at + key.size() + 5);
    dvec3 out;
    std::size_t pos = 0;
    for (int a = 0; a < 3; ++a) {
        std::size_t used = 0;
        out[a] = std::stod(v.substr(pos), &used);
        pos += used + 1;
    }
    return out;
}

/// The camera of a stats file, projecting world points to pixels as the renderers do (pinhole,
/// vertical field of view, row 0 at the top).
struct StatsCamera {
    dvec3 eye, right, up, forward;
    double tanV = 0.0, tanH = 0.0;
    int width = 0, height = 0;
    explicit StatsCamera(const std::string& js) {
        eye = statVector(js, "camera_pos");
        forward = glm::normalize(statVector(js, "look_at") - eye);
        right = glm::normalize(glm::cross(forward, statVector(js, "up")));
        up = glm::cross(right, forward);
        width = int(statNumber(js, "width"));
        height = int(statNumber(js, "height"));
        tanV = std::tan(glm::radians(statNumber(js, "fov")) * 0.5);
        tanH = tanV * width / height;
    }
    /// Pixel coordinates (x right, y down) of a world point in front of the camera.
    octrace::dvec2 pixel(const dvec3& p) const {
        const dvec3 o = p - eye;
        const double z = glm::dot(o, forward);
        return {(0.5 + 0.5 * glm::dot(o, right) / (z * tanH)) * width, (0.5 - 0.5 * glm::dot(o, up) / (z * tanV)) * height};
    }
};

/// The rectangle the 8 corners of the surface's box project to, as fractions of the frame:
/// {x0, y0, x1, y1}.
std::array<double, 4> projectedBox(const std::string& js) {
    const StatsCamera cam(js);
    const dvec3 lo = statVector(js, "surface_bounds_min"), hi = statVector(js, "surface_bounds_max");
    std::array<double, 4> r{1e300, 1e300, -1e300, -1e300};
    for (int k = 0; k < 8; ++k) {
        const dvec3 p((k & 4) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 1) ? hi.z : lo.z);
        const octrace::dvec2 px = cam.pixel(p);
        r[0] = std::min(r[0], px.x / cam.width);
        r[1] = std::min(r[1], px.y / cam.height);
        r[2] = std::max(r[2], px.x / cam.width);
        r[3] = std::max(r[3], px.y / cam.height);
    }
    return r;
}

/// The box fills most of the frame: inside it, touching one pair of sides at 92 %, centred.
void expectFillsTheFrame(const std::string& js, const std::string& what) {
    const auto r = projectedBox(js);
    EXPECT_GE(r[0], -1e-6) << what;
    EXPECT_GE(r[1], -1e-6) << what;
    EXPECT_LE(r[2], 1.0 + 1e-6) << what;
    EXPECT_LE(r[3], 1.0 + 1e-6) << what;
    EXPECT_GE(std::max(r[2] - r[0], r[3] - r[1]), 0.91) << what << ": the box fills " << r[2] - r[0] << " x " << r[3] - r[1];
    EXPECT_NEAR(0.5 * (r[0] + r[2]), 0.5, 0.005) << what << ": not centred across";
    EXPECT_NEAR(0.5 * (r[1] + r[3]), 0.5, 0.005) << what << ": not centred up and down";
}

/// Mean linear RGB of the pixels that hit something (finite Z) and of those that do not.
struct PixelMeans {
    dvec3 hit{0.0}, miss{0.0};
    std::size_t hits = 0, misses = 0;
    double hueSpread = 0.0;  ///< largest minus smallest R/(R+G+B) over the hit pixels
};

PixelMeans pixelMeans(const std::string& exr) {
    const auto img = octrace::test::readExr(exr);
    PixelMeans m;
    double lo = 1e300, hi = -1e300;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const dvec3 c(img.at("R", x, y), img.at("G", x, y), img.at("B", x, y));
            if (std::isfinite(img.at("Z", x, y))) {
                m.hit += c;
                ++m.hits;
                const double sum = c.r + c.g + c.b;
                if (sum > 0.02) {
                    lo = std::min(lo, c.r / sum);
                    hi = std::max(hi, c.r / sum);
                }
            } else {
                m.miss += c;
                ++m.misses;
            }
        }
    if (m.hits) m.hit /= double(m.hits);
    if (m.misses) m.miss /= double(m.misses);
    m.hueSpread = m.hits ? hi - lo : 0.0;
    return m;
}

}  // namespace

TEST(DefaultView, DepthAutoIsTheShallowestWhoseVoxelIsNoLargerThanTheSampleSpacingAndIsSaid) {
    Scratch s;
    // 65 samples over [-1, 1]: spacing 2/64, depth 6; 129 samples: depth 7.
    for (const auto& [input, depth] : {std::pair{"analytic:sphere", 6}, std::pair{"analytic:sphere:129", 7}}) {
        const Result r = run({"render", input, "--size", "64x48", "--stats", s.path("st.json"), "-o", s.path("a.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_TRUE(has(r.err, "--depth auto: " + std::to_string(depth) + ", voxel ")) << input << "\n" << r.err;
        EXPECT_TRUE(has(r.err, "median sample spacing")) << r.err;
        EXPECT_EQ(int(statNumber(slurp(s.path("st.json")), "depth")), depth) << input;
    }
    // A number still works, and is not said; `auto` can be given too.
    const Result given = run({"render", "analytic:sphere", "--depth", "5", "--size", "64x48", "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(given.code, 0) << given.err;
    EXPECT_FALSE(has(given.err, "auto")) << given.err;
    EXPECT_EQ(int(statNumber(slurp(s.path("st.json")), "depth")), 5);
    const Result word = run({"render", "analytic:sphere", "--depth", "auto", "--size", "64x48", "-o", s.path("a.png")});
    ASSERT_EQ(word.code, 0) << word.err;
    EXPECT_TRUE(has(word.err, "--depth auto: 6")) << word.err;
    EXPECT_EQ(run({"render", "analytic:sphere", "--depth", "automatic", "-o", s.path("a.png")}).code, 2);
}

TEST(DefaultView, DepthAutoIsCappedByTheMemoryBudget) {
    // analytic:sphere:129 asks for depth 7; a budget just below the build's estimate at depth 7
    // (and above depth 6's) gets depth 6, and says so.
    octrace::model::SurfaceSpec a;
    a.input = "analytic:sphere:129";
    octrace::model::Surface s;
    octrace::model::readSurfaceField(a, s);
    const auto [lo, hi] = s.field.validRange();
    const double iso = 0.5 * (double(lo) + double(hi));
    const auto est = octrace::estimateBuildMemory(s.field, iso, 7);
    ASSERT_LT(est[5].total(), est[6].total());
    EXPECT_EQ(octrace::model::chooseDepth(a, s.field, iso).depth, 7);
    a.maxMemory = est[6].total() - 1;
    const octrace::DepthChoice capped = octrace::model::chooseDepth(a, s.field, iso);
    EXPECT_EQ(capped.depth, 6);
    EXPECT_TRUE(has(capped.reason, "capped at 6 by `max_memory`")) << capped.reason;
    // Given, a depth is the user's: not capped here (the build refuses what does not fit).
    a.depth = 7;
    EXPECT_EQ(octrace::model::chooseDepth(a, s.field, iso).depth, 7);
}

TEST(DefaultView, InfoListsTheDepthAutoWouldPick) {
    const Result r = run({"info", "analytic:sphere"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "depth auto: 6 (voxel ")) << r.out;
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent";
    // Levitus: 1 degree = 111.2 km along x and y; the cube's side is 360 degrees at the equator.
    const Result ocean = run({"info", sharedData("ocean/levitus_climatology.cdf")});
    ASSERT_EQ(ocean.code, 0) << ocean.err;
    EXPECT_TRUE(has(ocean.out, "depth auto: 9 (voxel 77.97 km <= median sample spacing 111.2 km along x")) << ocean.out;
    const Result molecule = run({"info", sharedData("molecule/4HHB.pdb")});
    ASSERT_EQ(molecule.code, 0) << molecule.err;
    EXPECT_TRUE(std::regex_search(molecule.out, std::regex("depth auto: [0-9]+ \\(voxel .* one pixel of the view"))) << molecule.out;
}

TEST(DefaultView, TheSurfaceFillsTheFrameAndGivenCameraOptionsWin) {
    Scratch s;
    const Result r = run({"render", "analytic:torus", "--size", "160x90", "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    expectFillsTheFrame(slurp(s.path("st.json")), "torus, wide");
    const Result tall = run({"render", "analytic:torus", "--size", "60x120", "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(tall.code, 0) << tall.err;
    expectFillsTheFrame(slurp(s.path("st.json")), "torus, tall");
    const Result placed = run({"render", "analytic:torus", "--size", "64x48", "--camera-pos", "3,0.5,2", "--look-at", "0.1,0,0",
                               "--up", "0,1,0", "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(placed.code, 0) << placed.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_TRUE(has(js, "\"camera_pos\": \"3,0.5,2\"")) << js;
    EXPECT_TRUE(has(js, "\"look_at\": \"0.1,0,0\"")) << js;
    EXPECT_TRUE(has(js, "\"up\": \"0,1,0\"")) << js;
}

TEST(DefaultView, AnOceanIsSeenNorthUpFromTheSouthAndAbove) {
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const Result r = run({"render", sharedData("ocean/levitus_climatology.cdf"), "--var", "TEMP", "--iso", "10", "--depth", "6",
                          "--size", "160x120", "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    expectFillsTheFrame(js, "Levitus");
    const StatsCamera cam(js);
    // From the south and above: the camera is south of its look-at point and above it.
    const dvec3 towards = cam.eye - statVector(js, "look_at");
    EXPECT_NEAR(towards.x, 0.0, 1e-6 * glm::length(towards));
    EXPECT_LT(towards.y, 0.0);
    EXPECT_GT(towards.z, 0.0);
    // North up: a step north on the sea surface goes straight up the image.
    const dvec3 lo = statVector(js, "surface_bounds_min"), hi = statVector(js, "surface_bounds_max");
    const dvec3 centre((lo.x + hi.x) / 2, (lo.y + hi.y) / 2, hi.z);
    const octrace::dvec2 a = cam.pixel(centre), b = cam.pixel(centre + dvec3(0.0, 0.1 * (hi.y - lo.y), 0.0));
    EXPECT_LT(b.y, a.y - 1.0);
    EXPECT_NEAR(b.x, a.x, 1e-6 * cam.width);
}

TEST(DefaultView, APatientVolumeIsSeenFromTheFrontSuperiorUpAndACtPresetHasItsTissueColour) {
    if (!haveShared("medical/lidc2_chest_ct.nrrd")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    octrace::io::DicomSeriesWriteOptions o;
    o.window = {40.0, 400.0};  // soft tissue, as the issue's CT: it greyed a skin surface nearly black
    writeChestCtSeries(s.path("ct"), o);
    const Result skin = run({"render", s.path("ct"), "--iso", "skin", "--depth", "7", "--size", "160x120", "--stats",
                             s.path("st.json"), "-o", s.path("skin.exr")});
    ASSERT_EQ(skin.code, 0) << skin.err;
    const std::string js = slurp(s.path("st.json"));
    expectFillsTheFrame(js, "chest CT");
    // Anterior view (LPS: from -y), superior (+z) up.
    const dvec3 towards = glm::normalize(statVector(js, "camera_pos") - statVector(js, "look_at"));
    EXPECT_NEAR(towards.y, -1.0, 1e-9) << js;
    EXPECT_TRUE(has(js, "\"up\": \"0,0,1\"")) << js;
    const PixelMeans sk = pixelMeans(s.path("skin.exr"));
    ASSERT_GT(sk.hits, 1000u);
    // Skin-coloured (red over green over blue), not the window's near-black grey.
    EXPECT_GT(sk.hit.r, 0.12) << sk.hit.r << " " << sk.hit.g << " " << sk.hit.b;
    EXPECT_GT(sk.hit.r, 1.3 * sk.hit.g);
    EXPECT_GT(sk.hit.g, sk.hit.b);
    // A window asked for still greys it.
    const Result greyed = run({"render", s.path("ct"), "--iso", "skin", "--window", "soft-tissue", "--depth", "7", "--size",
                               "160x120", "-o", s.path("grey.exr")});
    ASSERT_EQ(greyed.code, 0) << greyed.err;
    const PixelMeans g = pixelMeans(s.path("grey.exr"));
    EXPECT_NEAR(g.hit.r, g.hit.g, 1e-3);
    // Bone: light ivory on a background that contrasts with it (not white on white).
    const Result bone = run({"render", s.path("ct"), "--iso", "bone", "--depth", "7", "--size", "160x120", "-o", s.path("bone.exr")});
    ASSERT_EQ(bone.code, 0) << bone.err;
    const PixelMeans b = pixelMeans(s.path("bone.exr"));
    ASSERT_GT(b.misses, 1000u);
    EXPECT_LT(b.miss.r + b.miss.g + b.miss.b, 1.0) << "background " << b.miss.r << "," << b.miss.g << "," << b.miss.b;
    EXPECT_GT(b.hit.r, b.hit.b);
    // A background given is kept.
    const Result white = run({"render", s.path("ct"), "--iso", "bone", "--background", "white", "--depth", "7", "--size", "160x120",
                              "-o", s.path("white.exr")});
    ASSERT_EQ(white.code, 0) << white.err;
    EXPECT_NEAR(pixelMeans(s.path("white.exr")).miss.r, 1.0, 1e-3);
}

TEST(DefaultView, AFewSagittalSlicesAreSeenFromThePatientsLeft) {
    if (!haveShared("medical/d2n_mr_sag_4slices_anatomical")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const Result r = run({"render", sharedData("medical/d2n_mr_sag_4slices_anatomical"), "--depth", "8", "--size", "96x72",
                          "--stats", s.path("st.json"), "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    const dvec3 towards = glm::normalize(statVector(js, "camera_pos") - statVector(js, "look_at"));
    EXPECT_NEAR(towards.x, 1.0, 1e-9) << js;
    EXPECT_TRUE(has(js, "\"up\": \"0,0,1\"")) << js;
}

TEST(DefaultView, AFieldWithoutColoursIsColouredByAColourMapNotOneColour) {
    Scratch s;
    const Result r = run({"render", "analytic:sphere", "--size", "96x72", "-o", s.path("a.exr")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GT(pixelMeans(s.path("a.exr")).hueSpread, 0.2);
    // One colour, given, has one hue whatever the light.
    const Result one = run({"render", "analytic:sphere", "--colour", "0.85,0.62,0.35", "--size", "96x72", "-o", s.path("b.exr")});
    ASSERT_EQ(one.code, 0) << one.err;
    EXPECT_LT(pixelMeans(s.path("b.exr")).hueSpread, 0.05);
}

// The default iso value (model::defaultIso): Otsu's threshold for an image volume, between the
// two classes of its samples even where a few outliers stretch the range; for a field on a
// longitude/latitude grid the middle of its range without those outliers; the middle of the
// range for an analytic one.
TEST(DefaultIso, OtsuSplitsAnImageVolumesTwoClassesAndOceanFieldsTakeTheMiddle) {
    octrace::ScalarField f;
    f.name = "MR";
    f.dims = {10, 10, 10};
    std::vector<float> v(1000);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = i % 5 == 0 ? 60.0f + float(i % 7) : 10.0f + float(i % 3);  // 80% near 10, 20% near 60
    v[1] = 0.0f;
    v[2] = 1000.0f;  // one bright outlier: the middle of the range would be 500
    f.values = octrace::SampleBuffer(std::move(v));
    const auto [iso, why] = octrace::model::defaultIso(f, "volume.nrrd");
    EXPECT_GT(iso, 12.0) << why;
    EXPECT_LT(iso, 60.0) << why;
    EXPECT_NE(why.find("Otsu"), std::string::npos) << why;
    EXPECT_DOUBLE_EQ(octrace::model::defaultIso(f, "analytic:sphere").first, 500.0);
    f.geographic.valid = true;
    // The two outliers (0.2% of the samples) left out: the middle of about [10, 66].
    const auto [middle, said] = octrace::model::defaultIso(f, "ocean.nc");
    EXPECT_NEAR(middle, 38.0, 0.5) << said;
    EXPECT_NE(said.find("between their 0.5th and 99.5th percentiles (all: [0, 1000])"), std::string::npos) << said;
    // Without outliers, the middle of the range (to within the 4096 bins that find the percentiles).
    std::vector<float> even(1000);
    for (std::size_t i = 0; i < even.size(); ++i) even[i] = float(i);
    f.values = octrace::SampleBuffer(std::move(even));
    EXPECT_NEAR(octrace::model::defaultIso(f, "ocean.nc").first, 499.5, 0.5);
}

// The Levitus salinity's range reaches from 4.6 (a few coastal samples) to 40.8: its default
// surface is the middle of the rest, which the atlas's cells cross (the middle of the whole
// range, 22.7, drew nothing: "no cell of 'SALT' straddles").
TEST(DefaultIso, AnOceanFieldsDefaultSurfaceIsDrawn) {
    const std::string levitus = std::string(OCTRACE_SHARED_DATA) + "/ocean/levitus_climatology.cdf";
    if (!std::filesystem::exists(levitus)) GTEST_SKIP() << "shared data absent: " << levitus;
    Scratch s;
    const Result r = run({"render", levitus, "--var", "SALT", "--depth", "6", "--size", "160x120", "-o", s.path("salt.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, std::regex("no --iso given: using ([0-9.]+), the middle of \\["))) << r.err;
    EXPECT_GT(std::stod(m[1].str()), 33.0) << r.err;
    EXPECT_LT(std::stod(m[1].str()), 35.0) << r.err;
}

// The studio remembers the contrasting background per surface while these settings stay the
// same (it is asked on every camera move): they must be every setting Albedo reads.
TEST(DefaultView, SameColouringComparesEverySettingTheSurfacesColourReads) {
    using namespace octrace;
    const RenderSettings base;
    EXPECT_TRUE(model::sameColouring(base, base));  // NaN colour range ends compare equal
    RenderSettings other = base;
    other.threads = 7;
    other.tileSize = 3;
    other.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    other.surface = SurfaceMode::Smooth;
    EXPECT_TRUE(model::sameColouring(base, other)) << "settings that do not colour the surface";
    const std::vector<std::pair<const char*, std::function<void(RenderSettings&)>>> changes = {
        {"colour", [](RenderSettings& s) { s.colour = vec3(0.1f); }},
        {"colormap", [](RenderSettings& s) { s.colormap = "viridis"; }},
        {"colourMin", [](RenderSettings& s) { s.colourMin = 1.0f; }},
        {"colourMax", [](RenderSettings& s) { s.colourMax = 2.0f; }},
        {"maskedColour", [](RenderSettings& s) { s.maskedColour = vec3(0.5f); }},
        {"floorColour", [](RenderSettings& s) { s.floorColour = vec3(0.5f); }},
        {"voxelColours", [](RenderSettings& s) { s.voxelColours = !s.voxelColours; }},
        {"window centre", [](RenderSettings& s) { s.window.centre = 40.0; }},
        {"window width", [](RenderSettings& s) { s.window.width = 400.0; }},
        {"invertedGrey", [](RenderSettings& s) { s.invertedGrey = !s.invertedGrey; }},
    };
    for (const auto& [name, change] : changes) {
        RenderSettings s = base;
        change(s);
        EXPECT_FALSE(model::sameColouring(base, s)) << name;
    }
}

// The contrasting background is chosen from the surface's mean luminance, which the function
// takes per cell layer when the colour depends on the height alone and per voxel otherwise: its
// choice equals the one made from every voxel's own colour, for colour ranges swept across the
// point where the choice flips, by height and by each voxel's value.
TEST(DefaultView, TheContrastingBackgroundIsTheOneEveryVoxelsColourChooses) {
    using namespace octrace;
    BuildOptions o;
    o.depth = 6;
    o.iso = 0.0;
    Octree tree = buildShellOctree(makeAnalyticField("torus", 33), o);
    const auto byVoxel = [&](const RenderSettings& rs) {
        const Albedo albedo(tree, rs);
        const auto luminance = [](vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
        double sum = 0.0;
        tree.forEachVoxel([&](const ivec3& cell, std::uint32_t v) { sum += luminance(albedo.at(v, float(cell.z) + 0.5f)); });
        const double y = sum / double(tree.voxels().size());
        const vec4 slate = model::displayToLinear(vec4(0.32f, 0.34f, 0.43f, 1.0f));
        const double ySlate = luminance(vec3(slate));
        const auto contrast = [](double a, double b) { return (std::max(a, b) + 0.05) / (std::min(a, b) + 0.05); };
        return contrast(y, 1.0) >= contrast(y, ySlate) ? vec4(1.0f) : slate;
    };
    const Box3 box = tree.occupiedBounds();
    const double h = box.hi.z - box.lo.z;
    int white = 0, slate = 0;
    for (int i = 0; i <= 40; ++i) {
        // Grey from black to white over a window sliding up through the surface's height.
        RenderSettings rs;
        rs.colormap = "grey";
        rs.colourMin = float(box.lo.z - h + h * 2.0 * i / 40.0);
        rs.colourMax = float(rs.colourMin + h);
        const vec4 want = byVoxel(rs), got = model::contrastingBackground(tree, rs);
        EXPECT_EQ(got, want) << "window from " << rs.colourMin;
        (want == vec4(1.0f) ? white : slate) += 1;
    }
    EXPECT_GT(white, 3);  // the sweep crosses the point where the choice flips
    EXPECT_GT(slate, 3);
    // By each voxel's value (its cell's x, 0 .. 2^depth - 1: the colour no longer follows the
    // height), a window of the values' width sliding across them.
    std::vector<float> values(tree.voxels().size());
    tree.forEachVoxel([&](const ivec3& cell, std::uint32_t v) { values[v] = float(cell.x); });
    tree.setVoxelValues(std::move(values));
    const float cells = float(1 << tree.depth);
    white = slate = 0;
    for (int i = 0; i <= 40; ++i) {
        RenderSettings rs;
        rs.colormap = "grey";
        rs.colourMin = -cells + 2.0f * cells * float(i) / 40.0f;
        rs.colourMax = rs.colourMin + cells;
        const vec4 want = byVoxel(rs);
        EXPECT_EQ(model::contrastingBackground(tree, rs), want) << "values from " << rs.colourMin;
        (want == vec4(1.0f) ? white : slate) += 1;
    }
    EXPECT_GT(white, 3);
    EXPECT_GT(slate, 3);
}
