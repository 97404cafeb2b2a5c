// Paper A's coherent renderers: the exact variants give the full traversal's image bit for bit;
// the approximate ones differ only where the paper's shortcut skips something in front, which a
// scene built for it shows; colour coherence fills only between traced surface pixels.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"
#include "RenderTestUtil.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;
using namespace octrace::test;

namespace {

const Octree& tree(int which) {
    static const Octree sphere = buildShellOctree(makeAnalyticField("sphere", 33), {7, 0.0, 0});
    static const Octree torus = buildShellOctree(makeAnalyticField("torus", 33), {7, 0.0, 0});
    static const Octree noise = buildShellOctree(makeAnalyticField("noise", 65, 3), {8, 0.0, 0});
    return which == 0 ? sphere : which == 1 ? torus : noise;
}

std::vector<Camera> cameras(const Octree& t) {
    Box3 cube{t.cubeOrigin, t.cubeOrigin + dvec3(t.cubeSide)};
    std::vector<Camera> cams{Camera::framing(cube, 203, 149), Camera::framing(t.occupiedBounds(), 160, 120, 50.0)};
    Camera inside;
    inside.position = cube.centre() + dvec3(0.05, -0.02, 0.03) * t.cubeSide;
    inside.lookAt = inside.position + dvec3(1, 0.3, -0.2);
    inside.width = 120;
    inside.height = 90;
    inside.fovYDegrees = 70;
    cams.push_back(inside);
    return cams;
}

RenderStats draw(const std::string& name, const Octree& t, const Camera& c, Frame& f, int branchUp = 0,
                 bool missCoherence = true) {
    RenderSettings s;
    s.threads = 2;
    s.coherence.branchUp = branchUp;
    s.coherence.miss = missCoherence;
    return render(name, t, c, f, s);
}

/// A thin rod along y at z = 0.5 that, seen from the camera, covers about pixel column 102,
/// between the supporting columns 100 and 104; with `sheet`, a sheet at z = -0.6 behind it.
/// The rod at its distance spans the whole image height, the sheet not: rows above and below
/// the sheet see the rod in front of nothing. `full`: the full traversal's frame. The fixtures
/// RodAlone and RodBeforeSheet below give a test its members by name.
class RodScene : public ::testing::Test {
protected:
    static constexpr int W = 200, H = 150;
    Camera cam;
    Octree tree;
    Frame full;
    explicit RodScene(bool sheet) {
        cam.position = dvec3(0, 0, 3);
        cam.lookAt = dvec3(0, 0, 0);
        cam.up = dvec3(0, 1, 0);
        cam.width = W;
        cam.height = H;
        cam.fovYDegrees = 40;
        // World x where the centre of pixel column 102 meets the plane z = 0.5.
        const Ray r = cam.primaryRay(102, H / 2);
        const double t = (0.5 - r.origin.z) / r.direction.z;
        const double x0 = r.origin.x + t * r.direction.x;
        ScalarField f = sampleFunction("rod", ivec3(129), dvec3(-1.0), dvec3(2.0 / 128), [x0, sheet](const dvec3& p) {
            const double slab = sheet ? 0.05 - std::abs(p.z + 0.6) : -1.0;
            const double rod = 0.012 - std::hypot(p.x - x0, p.z - 0.5);
            return float(std::max(slab, rod));
        });
        tree = buildShellOctree(f, {8, 0.0, 0});
        draw("full", tree, cam, full);
    }
};

class RodAlone : public RodScene {
protected:
    RodAlone() : RodScene(false) {}
};

class RodBeforeSheet : public RodScene {
protected:
    RodBeforeSheet() : RodScene(true) {}
};

long differingHits(const Frame& a, const Frame& b) {
    long n = 0;
    for (std::size_t i = 0; i < a.hitId.size(); ++i) n += a.hitId[i] != b.hitId[i];
    return n;
}

}  // namespace

TEST(CoherentRenderers, SayWhichCoherenceSettingsTheyHonour) {
    // What the CLI's warnings and the studio's controls go by.
    for (const std::string& name : rendererNames()) {
        SCOPED_TRACE(name);
        const auto r = makeRenderer(name);
        const bool trajectory = name.rfind("linear", 0) == 0 || name.rfind("area", 0) == 0;
        EXPECT_EQ(r->trajectoryCoherence(), trajectory);
        EXPECT_EQ(r->missCoherence(), trajectory && name.find("-exact") == std::string::npos);
        EXPECT_EQ(r->colourCoherence(), trajectory || name == "full");
    }
}

TEST(CoherentRenderers, APlusColourNameIsTheRendererWithColourCoherenceOn) {
    // The +colour names are aliases: the setting selects the behaviour, the name only says it.
    const Octree& t = tree(0);
    const Camera cam = cameras(t)[1];
    for (const char* base : {"full", "linear", "area", "linear-exact", "area-exact"}) {
        SCOPED_TRACE(base);
        for (const char* suffix : {"+colour", "+color"}) {
            const RendererName n = resolveRendererName(std::string(base) + suffix);
            EXPECT_EQ(n.renderer, base);
            EXPECT_TRUE(n.colourCoherence);
        }
        EXPECT_FALSE(resolveRendererName(base).colourCoherence);
        RenderSettings on;
        on.coherence.colour = true;
        Frame a, b;
        const RenderStats sa = render(std::string(base) + "+colour", t, cam, a);
        const RenderStats sb = makeRenderer(base)->render(t, cam, on, b);
        EXPECT_TRUE(diffFrames(a, b).identical());
        EXPECT_EQ(sa.colourFilled, sb.colourFilled);
        EXPECT_EQ(sa.renderer, std::string(base) + "+colour");  // the stats name the settings
        EXPECT_EQ(sb.renderer, std::string(base) + "+colour");
        EXPECT_EQ(makeRenderer(base)->render(t, cam, RenderSettings{}, b).renderer, base);
    }
    // Not a renderer of the list, and not an alias that would drop its setting.
    const std::vector<std::string> names = rendererNames(), menu = rendererMenuNames();
    EXPECT_EQ(std::find(names.begin(), names.end(), "area+colour"), names.end());
    EXPECT_NE(std::find(menu.begin(), menu.end(), "area+colour"), menu.end());
    try {
        makeRenderer("area+colour");
        ADD_FAILURE() << "an alias made a renderer without its setting";
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("area with colour coherence"), std::string::npos) << e.what();
    }
    for (const char* bad : {"reference+colour", "direct+colour", "samet+colour", "area+colour+colour", "+colour", "nope"})
        EXPECT_THROW(resolveRendererName(bad), UsageError) << bad;
}

TEST(CoherentRenderers, ExactVariantsGiveTheFullTraversalsImageBitForBit) {
    long certified = 0, commonPath = 0;
    for (int ti = 0; ti < 3; ++ti)
        for (const Camera& cam : cameras(tree(ti))) {
            Frame full;
            draw("full", tree(ti), cam, full);
            for (const char* name : {"linear-exact", "area-exact"}) {
                SCOPED_TRACE(std::string(name) + " tree " + std::to_string(ti));
                Frame f;
                RenderStats st = draw(name, tree(ti), cam, f);
                EXPECT_EQ(differingHits(f, full), 0);
                EXPECT_TRUE(f.rgba == full.rgba);
                EXPECT_TRUE(f.depth == full.depth);
                EXPECT_LE(st.raysCertified + st.fallbacks, st.raysCommonPath);
                certified += long(st.raysCertified);
                commonPath += long(st.raysCommonPath);
            }
        }
    EXPECT_GT(commonPath, 0);
    EXPECT_GT(certified, 0);
}

TEST(CoherentRenderers, CountEveryPixelOnceAsFullCommonPathOrFilled) {
    for (const char* name : {"linear", "area", "area+colour", "linear-exact", "area-exact", "full+colour"}) {
        SCOPED_TRACE(name);
        Frame f;
        RenderStats st = draw(name, tree(1), cameras(tree(1))[0], f);
        EXPECT_EQ(st.raysFull + st.raysCommonPath + st.colourFilled + st.missFilled, st.pixels);
        EXPECT_LE(st.fallbacks, st.raysCommonPath);
        EXPECT_LE(st.raysCertified, st.raysCommonPath);
        long filled = 0, missFilled = 0;
        for (auto fl : f.flags) {
            filled += (fl & Frame::kColourFilled) != 0;
            missFilled += (fl & Frame::kMissFilled) != 0;
        }
        EXPECT_EQ(filled, long(st.colourFilled));
        EXPECT_EQ(missFilled, long(st.missFilled));
        // Miss coherence is part of the trajectory variants (the exact ones take a pixel as a
        // miss only where their frontier proves it); the torus's hole gives them pixels between
        // two misses.
        const std::string n = name;
        if (n.rfind("full", 0) != 0) EXPECT_GT(st.missFilled, 0u);
        else EXPECT_EQ(st.missFilled, 0u);
    }
}

TEST_F(RodAlone, MissCoherenceTakesThePixelsBetweenTwoMissesAsBackground) {
    // The rod alone: nothing behind it, so the supporting columns 100 and 104 miss and the rod
    // between them is seen only by full traversal, the exact variants, and the approximate
    // ones with miss coherence off.
    long rodPixels = 0;
    for (int y = 0; y < H; ++y) rodPixels += full.hitId[full.pixel(102, y)] != kNoHit;
    ASSERT_GT(rodPixels, H / 2);
    for (const char* name : {"linear", "area"}) {
        SCOPED_TRACE(name);
        Frame on, off;
        const RenderStats st = draw(name, tree, cam, on);
        const RenderStats stOff = draw(name, tree, cam, off, 0, false);
        EXPECT_GT(differingHits(on, full), H / 2) << "the rod should hide between its missing partners";
        EXPECT_EQ(differingHits(off, full), 0);
        EXPECT_TRUE(off.rgba == full.rgba);
        EXPECT_EQ(stOff.missFilled, 0u);
        EXPECT_GT(st.missFilled, 0u);
        EXPECT_EQ(st.rays, stOff.rays);  // a pixel taken as a miss still counts its ray
        for (std::size_t i = 0; i < on.flags.size(); ++i)
            if (on.flags[i] & Frame::kMissFilled) {
                ASSERT_EQ(on.hitId[i], kNoHit);
                ASSERT_EQ(on.rgba[i], RenderSettings{}.background);
                ASSERT_TRUE(std::isinf(on.depth[i]));
            }
        // Every pixel that differs from full traversal is one miss coherence took as background.
        for (std::size_t i = 0; i < on.flags.size(); ++i)
            if (on.hitId[i] != full.hitId[i]) {
                ASSERT_TRUE(on.flags[i] & Frame::kMissFilled) << i;
            }
    }
    for (const char* name : {"linear-exact", "area-exact"}) {
        Frame f;
        EXPECT_GT(draw(name, tree, cam, f).missFilled, 0u) << name;  // the background around the rod
        EXPECT_EQ(differingHits(f, full), 0) << name;
        for (int y = 0; y < H; ++y)  // the rod between missing partners is traced, not taken as a miss
            if (full.hitId[full.pixel(102, y)] != kNoHit) {
                ASSERT_FALSE(f.flags[f.pixel(102, y)] & Frame::kMissFilled) << y;
            }
    }
}

TEST(CoherentRenderers, ApproximateVariantsDifferRarelyOnSmoothSurfaces) {
    for (int ti = 0; ti < 2; ++ti)
        for (const char* name : {"linear", "area"}) {
            SCOPED_TRACE(std::string(name) + " tree " + std::to_string(ti));
            const Camera cam = cameras(tree(ti))[1];
            Frame full, f;
            draw("full", tree(ti), cam, full);
            RenderStats st = draw(name, tree(ti), cam, f);
            EXPECT_GT(st.raysCommonPath, st.hits / 2);
            EXPECT_LE(differingHits(f, full), long(st.pixels / 200));  // < 0.5 %
        }
}

TEST_F(RodBeforeSheet, ApproximateVariantsMissAThinRodInFrontThatTheExactOnesSee) {
    // A sheet at z = -0.6 and, in front of it, a thin rod along y that only the pixels between
    // the supporting columns see: the branch node of two supporting rays lies in the sheet, so
    // the paper's shortcut finds the sheet behind the rod.
    Frame lin, linExact, area, areaExact;
    draw("linear", tree, cam, lin);
    draw("linear-exact", tree, cam, linExact);
    draw("area", tree, cam, area);
    draw("area-exact", tree, cam, areaExact);
    EXPECT_GT(differingHits(lin, full), H / 2) << "the rod should hide from the linear shortcut";
    EXPECT_GT(differingHits(area, full), H / 4);
    EXPECT_EQ(differingHits(linExact, full), 0);
    EXPECT_EQ(differingHits(areaExact, full), 0);
    // Where `linear` starts column 102 at a branch node in the sheet (its partners are the
    // supporting columns 100 and 104, traced from the root by every variant) and misses the rod,
    // the frontier certificate finds the rod in front: those pixels are traced from the root,
    // never certified. In `area` that is the pattern of the base rows.
    for (const char* name : {"linear-exact", "area-exact"}) {
        Frame f;
        const RenderStats st = draw(name, tree, cam, f);
        EXPECT_GT(st.fallbacks, 0u) << name;
        long wrongStarts = 0, certified = 0;
        for (int y = 0; y < H; ++y) {
            if (std::string(name) == "area-exact" && y % 4 != 0) continue;
            const std::size_t p = full.pixel(102, y);
            if (lin.hitId[p] == full.hitId[p]) continue;
            ++wrongStarts;
            certified += (f.flags[p] & Frame::kCertified) != 0;
        }
        EXPECT_GT(wrongStarts, 0) << name;
        EXPECT_EQ(certified, 0) << name;
    }
}

TEST(CoherentRenderers, ExactVariantsEqualFullAndTheReferenceAtTheHardCamerasOnEveryScene) {
    // The tile renderer's test scenes (thin rods included) and cameras (grazing, inside,
    // orthographic, on the lattice): the frontier certificate never lets a wrong start through,
    // for any thread count, and it certifies most common-path rays.
    long certified = 0, commonPath = 0;
    for (const NamedTree& nt : hardTestTrees())
        for (const NamedCamera& nc : hardTestCameras(*nt.tree)) {
            Frame full, reference;
            const RenderStats fs = draw("full", *nt.tree, nc.camera, full);
            draw("reference", *nt.tree, nc.camera, reference);
            for (const char* name : {"linear-exact", "area-exact"})
                for (int threads : {1, 2, 7}) {
                    SCOPED_TRACE(std::string(name) + ", " + nt.name + ", " + nc.name + ", threads " + std::to_string(threads));
                    Frame f;
                    RenderSettings s;
                    s.threads = threads;
                    const RenderStats st = render(name, *nt.tree, nc.camera, f, s);
                    const FrameDiff d = diffFrames(f, full);
                    EXPECT_TRUE(d.identical()) << d.first;
                    EXPECT_EQ(differingHits(f, reference), 0);
                    EXPECT_EQ(st.rays, fs.rays);
                    EXPECT_EQ(st.hits, fs.hits);
                    EXPECT_EQ(st.raysFull + st.raysCommonPath + st.colourFilled + st.missFilled, st.pixels);
                    certified += long(st.raysCertified);
                    commonPath += long(st.raysCommonPath);
                }
        }
    EXPECT_GT(certified, commonPath / 2);
}

TEST_F(RodBeforeSheet, StartingAboveTheBranchNodeFindsTheRodAndFromTheRootEqualsFull) {
    // The rod scene above: a start high enough to hold the rod sees it. branchUp = depth starts
    // every common-path ray at the root, which is the full traversal (without miss coherence,
    // which would still take the rod between two missing rays above and below the sheet as
    // background); the exact variants stay exact at any start.
    for (const char* name : {"linear", "area"}) {
        SCOPED_TRACE(name);
        Frame atBranch, fromRoot, exact;
        draw(name, tree, cam, atBranch, 0);
        const RenderStats st = draw(name, tree, cam, fromRoot, tree.depth, false);
        EXPECT_GT(differingHits(atBranch, full), H / 4);
        EXPECT_EQ(differingHits(fromRoot, full), 0);
        EXPECT_GT(st.raysCommonPath, 0u);  // still the common-path code, started at the root
        draw(std::string(name) + "-exact", tree, cam, exact, 3);
        EXPECT_EQ(differingHits(exact, full), 0);
    }
}

TEST(CoherentRenderers, BranchNodeUpIsTheAncestorOnTheSamePath) {
    const Octree& t = tree(0);
    ivec3 a(-1), b(-1);
    t.forEachVoxel([&](const ivec3& cell, std::uint32_t) {
        if (a.x < 0) a = cell;
        else if (b.x < 0 && cell != a) b = cell;
    });
    const BranchNode bn = branchNode(t, a, b);
    ASSERT_TRUE(bn.valid());
    for (int up : {1, 2, 100}) {
        const BranchNode above = branchNode(t, a, b, up);
        ASSERT_TRUE(above.valid());
        EXPECT_EQ(above.level, std::max(bn.level - up, 0));
        EXPECT_EQ(above.cell, a >> (t.depth - above.level));
        for (int l = 0; l <= above.level; ++l) EXPECT_EQ(above.path[l], bn.path[l]) << l;
    }
}

TEST(CoherentRenderers, ColourCoherenceFillsOnlyBetweenTracedSurfacePixelsWithinTheTolerance) {
    const Octree& t = tree(0);
    const Camera cam = cameras(t)[1];
    Frame full, f;
    draw("full", t, cam, full);
    RenderSettings s;
    s.coherence.colourTolerance = 2.0f;
    RenderStats st = render("area+colour", t, cam, f, s);
    EXPECT_GT(st.colourFilled, 0u);
    for (std::size_t i = 0; i < f.flags.size(); ++i)
        if (f.flags[i] & Frame::kColourFilled) {
            EXPECT_NE(f.hitId[i], kNoHit);
        }
    // Approximate by design: judged by the image difference (the bar: PSNR >= 40 dB).
    const ImageDifference d = compareImages(f, full);
    EXPECT_GE(d.psnrDb, 40.0) << d.differingPixels << " pixels differ, max " << d.maxChannelError;
    // Tolerance 0 fills only identical neighbours; a full renderer with the option fills too.
    s.coherence.colourTolerance = 0.0f;
    RenderStats st0 = render("area+colour", t, cam, f, s);
    EXPECT_LE(st0.colourFilled, st.colourFilled);
    s.coherence.colour = true;
    s.coherence.colourTolerance = 3.0f;
    EXPECT_GT(makeRenderer("full")->render(t, cam, s, f).colourFilled, 0u);
}

TEST(CoherentRenderers, ColourCoherenceFillsABandPixelFromAFilledBaseRowPixelWithItsColour) {
    // Paper A compares the outer pixels' colours however they were made: in `area`, a pixel of
    // a band row next to a base row can be filled from that row's filled pixel (at most two
    // generations: filled pixels of the bands are no one's partners). Its average must use
    // the filled pixel's own colour.
    const Octree& t = tree(0);
    const Camera cam = cameras(t)[1];
    Frame full, f;
    draw("full", t, cam, full);
    RenderSettings s;
    s.coherence.colourTolerance = 255.0f;  // every pair of surface pixels fills
    render("area+colour", t, cam, f, s);
    std::size_t fromFilled = 0;
    for (int y = 1; y + 1 < f.height; y += 4)
        for (int x = 1; x + 1 < f.width; x += 2) {
            const std::size_t p = f.pixel(x, y), above = f.pixel(x, y - 1), below = f.pixel(x, y + 1);
            if (!(f.flags[above] & Frame::kColourFilled) || f.hitId[below] == kNoHit) continue;
            ASSERT_TRUE(f.flags[p] & Frame::kColourFilled) << x << "," << y;
            ++fromFilled;
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_FLOAT_EQ(f.rgba[p][ch], 0.5f * (f.rgba[above][ch] + f.rgba[below][ch])) << x << "," << y;
        }
    EXPECT_GT(fromFilled, 0u);
    const ImageDifference d = compareImages(f, full);
    EXPECT_GE(d.psnrDb, 30.0) << "even at the loosest tolerance the image stays close";
    // At the default tolerance the filled pixel's colour is compared (it must have one).
    render("area+colour", t, cam, f);
    std::size_t filledFromFilled = 0;
    for (int y = 1; y + 1 < f.height; y += 4)
        for (int x = 1; x + 1 < f.width; x += 2)
            filledFromFilled += (f.flags[f.pixel(x, y)] & Frame::kColourFilled) && (f.flags[f.pixel(x, y - 1)] & Frame::kColourFilled);
    EXPECT_GT(filledFromFilled, 0u);
}

TEST(CoherentRenderers, ColourCoherenceBetweenBackgroundPixelsFillsBackgroundAndStillCountsTheRays) {
    const Octree& t = tree(1);
    const Camera cam = cameras(t)[0];
    Frame full, surfaceOnly, withBackground;
    const RenderStats sf = draw("full", t, cam, full);
    RenderSettings s;
    const RenderStats a = render("area+colour", t, cam, surfaceOnly, s);
    s.coherence.colourFillsBackground = true;
    const RenderStats b = render("area+colour", t, cam, withBackground, s);
    EXPECT_GT(b.colourFilled, a.colourFilled);
    EXPECT_EQ(b.rays, sf.rays);  // filled background pixels still count when their ray meets the cube
    std::size_t filledBackground = 0;
    for (std::size_t i = 0; i < withBackground.flags.size(); ++i)
        if ((withBackground.flags[i] & Frame::kColourFilled) && withBackground.hitId[i] == kNoHit) {
            ++filledBackground;
            EXPECT_EQ(withBackground.rgba[i], s.background);
            EXPECT_TRUE(std::isinf(withBackground.depth[i]));
        }
    EXPECT_GT(filledBackground, 0u);
    const ImageDifference d = compareImages(withBackground, full);
    EXPECT_GE(d.psnrDb, 40.0) << d.differingPixels << " pixels differ";
}
