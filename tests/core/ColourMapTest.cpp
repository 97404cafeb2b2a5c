// Tests of the colour maps (their ends against the published tables), the choice of a map from
// a variable's standard_name or name, and colouring a surface by per-voxel values in every
// renderer alike.
#include "RenderTestUtil.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;
using namespace octrace::test;

namespace {
float toLinear(double c) { return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4)); }
void expectColour(vec3 got, double r, double g, double b, const std::string& what) {
    EXPECT_NEAR(got.r, toLinear(r), 2e-6) << what;
    EXPECT_NEAR(got.g, toLinear(g), 2e-6) << what;
    EXPECT_NEAR(got.b, toLinear(b), 2e-6) << what;
}

/// The sphere's voxels with the value x + 2y at their centres, NaN on the top cap (z > 0.5).
Octree sphereWithValues() {
    Octree t = buildShellOctree(makeAnalyticField("sphere", 33), {7, 0.0, 0});
    std::vector<float> values(t.voxels().size());
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        const dvec3 p = t.cubeOrigin + (dvec3(c) + 0.5) * t.voxelSize();
        values[v] = p.z > 0.5 ? NAN : float(p.x + 2.0 * p.y);
    });
    t.setVoxelValues(std::move(values));
    return t;
}
}  // namespace

TEST(Colormap, EndsAreThePublishedFirstAndLastEntries) {
    // cmocean 4.0.3 cmocean/rgb/<name>-rgb.txt and matplotlib 3.8.4 _viridis_data, rounded to
    // the 6 decimals of scripts/colormaps.py.
    expectColour(colormap("thermal", 0.0f), 0.015556, 0.138244, 0.201811, "thermal 0");
    expectColour(colormap("thermal", 1.0f), 0.909042, 0.982157, 0.355508, "thermal 1");
    expectColour(colormap("haline", 0.0f), 0.162953, 0.095216, 0.422573, "haline 0");
    expectColour(colormap("haline", 1.0f), 0.994081, 0.936728, 0.602670, "haline 1");
    expectColour(colormap("speed", 0.0f), 0.999625, 0.991371, 0.804101, "speed 0");
    expectColour(colormap("speed", 1.0f), 0.090533, 0.137339, 0.073258, "speed 1");
    expectColour(colormap("viridis", 0.0f), 0.267004, 0.004874, 0.329415, "viridis 0");
    expectColour(colormap("viridis", 1.0f), 0.993248, 0.906157, 0.143936, "viridis 1");
    // Out of range and NaN clamp to the ends; "gray" is "grey".
    EXPECT_EQ(colormap("thermal", -3.0f), colormap("thermal", 0.0f));
    EXPECT_EQ(colormap("thermal", 7.0f), colormap("thermal", 1.0f));
    EXPECT_EQ(colormap("gray", 0.3f), colormap("grey", 0.3f));
    EXPECT_THROW(colormap("jet", 0.5f), UsageError);
}

TEST(Colormap, EveryMapRunsMonotonicallyInLightnessOrIsDiverging) {
    // thermal, haline, speed, viridis and grey are sequential: relative luminance changes one
    // way from end to end (the published maps are designed so).
    for (const char* name : {"thermal", "haline", "viridis", "grey", "speed"}) {
        auto lum = [&](float t) {
            vec3 c = colormap(name, t);
            return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
        };
        const float sign = lum(1.0f) > lum(0.0f) ? 1.0f : -1.0f;
        for (int i = 0; i < 64; ++i) EXPECT_GE(sign * (lum((i + 1) / 64.0f) - lum(i / 64.0f)), -1e-4f) << name << " " << i;
    }
}

TEST(Colormap, IsChosenByStandardNameThenByVariableName) {
    EXPECT_EQ(defaultColormap("sea_water_potential_temperature", "thetao"), "thermal");
    EXPECT_EQ(defaultColormap("sea_water_salinity", "x"), "haline");
    EXPECT_EQ(defaultColormap("speed_of_sound_in_sea_water", "c"), "speed");
    EXPECT_EQ(defaultColormap("", "TEMP"), "thermal");
    EXPECT_EQ(defaultColormap("", "SALT"), "haline");
    EXPECT_EQ(defaultColormap("", "sound_speed"), "speed");
    EXPECT_EQ(defaultColormap("", "density"), "viridis");
    EXPECT_EQ(defaultColormap("sea_water_density", "TEMP"), "thermal");  // an unknown standard name: the name decides
}

TEST(ColourByValue, GivesEachVoxelTheMapsColourForItsValueAndMaskedVoxelsTheMaskedColour) {
    const Octree t = sphereWithValues();
    RenderSettings s;
    s.ambient = 1.0f;  // unlit: the pixel is the albedo
    s.diffuse = 0.0f;
    s.colormap = "haline";
    const Albedo albedo(t, s);
    ASSERT_TRUE(albedo.byValue());
    // The surface's own range: x + 2y on the sphere of radius 0.7 below z = 0.5.
    EXPECT_NEAR(albedo.low(), -0.7 * std::sqrt(5.0), 0.05);
    EXPECT_NEAR(albedo.high(), 0.7 * std::sqrt(5.0), 0.05);
    std::size_t masked = 0, coloured = 0;
    for (const NamedCamera& nc : generalTestCameras(t)) {
        Frame f;
        render("full", t, nc.camera, f, s);
        for (std::size_t p = 0; p < f.hitId.size(); ++p) {
            if (f.hitId[p] == kNoHit) continue;
            const float v = t.voxelValues()[f.hitId[p]];
            const vec3 want = std::isnan(v) ? s.maskedColour : colormap("haline", (v - albedo.low()) / (albedo.high() - albedo.low()));
            ASSERT_EQ(vec3(f.rgba[p]), want) << nc.name << " pixel " << p;
            (std::isnan(v) ? masked : coloured) += 1;
        }
    }
    EXPECT_GT(masked, 50u);
    EXPECT_GT(coloured, 500u);
    // A given range: values beyond it take the ends.
    s.colourMin = 0.0f;
    s.colourMax = 0.1f;
    const Albedo narrow(t, s);
    std::size_t ends = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        const float value = t.voxelValues()[v];
        if (std::isnan(value) || (value > 0.0f && value < 0.1f)) return;
        EXPECT_EQ(narrow.at(v, float(c.z)), colormap("haline", value <= 0.0f ? 0.0f : 1.0f));
        ++ends;
    });
    EXPECT_GT(ends, 1000u);
}

TEST(ColourByValue, EveryExactRendererGivesTheReferencesFrameBitForBit) {
    const Octree t = sphereWithValues();
    RenderSettings s;
    s.colormap = "thermal";
    for (const NamedCamera& nc : allTestCameras(t)) {
        SCOPED_TRACE(nc.name);
        Frame ref;
        render("reference", t, nc.camera, ref, s);
        for (const char* name : {"full", "linear-exact", "area-exact"}) {
            Frame f;
            render(name, t, nc.camera, f, s);
            const FrameDiff d = diffFrames(f, ref);
            EXPECT_TRUE(d.identical()) << name << ": " << d.first;
        }
        // The direct renderers find the same voxel (DirectRendererTest) and then the same colour.
        for (const char* name : {"direct", "direct-f2b"}) {
            Frame f;
            render(name, t, nc.camera, f, s);
            for (std::size_t p = 0; p < f.hitId.size(); ++p) {
                if (f.hitId[p] != kNoHit && f.hitId[p] == ref.hitId[p]) {
                    ASSERT_EQ(f.rgba[p], ref.rgba[p]) << name;
                }
            }
        }
    }
}
