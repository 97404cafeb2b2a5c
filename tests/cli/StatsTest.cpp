// The pipeline's stats (model::Stats): typed values in insertion order, written as the flat JSON
// of --stats, with texts reworded by the front end, and a frame's keys from the real pipeline.
#include "octrace/model/OptionTable.h"
#include "octrace/model/Render.h"
#include "octrace/model/Stats.h"
#include "octrace/model/Surface.h"
#include "octrace/render/Renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace octrace;

TEST(Stats, KeepTypedValuesInOrderAndWriteTheFlatJson) {
    model::Stats s;
    s.set("renderer", "full");
    s.set("pixels", std::uint64_t(12));
    s.set("branch_up", -3);  // a count is never negative
    s.set("render_ms", 1.5);
    s.set("us_per_ray", std::numeric_limits<double>::quiet_NaN());
    s.set("window_inverted", false);
    s.set("note", std::string("try a smaller `depth`"));
    s.set("pixels", std::uint64_t(13));  // set again: keeps its place
    ASSERT_EQ(s.entries().size(), 7u);
    EXPECT_EQ(s.entries()[1].first, "pixels");
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("pixels")), 13u);
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("branch_up")), 0u);
    EXPECT_TRUE(std::holds_alternative<std::nullptr_t>(*s.find("us_per_ray")));
    EXPECT_EQ(s.find("absent"), nullptr);
    EXPECT_EQ(s.json(model::sayForCli),
              "{\n  \"renderer\": \"full\",\n  \"pixels\": 13,\n  \"branch_up\": 0,\n  \"render_ms\": 1.5,\n"
              "  \"us_per_ray\": null,\n  \"window_inverted\": false,\n  \"note\": \"try a smaller --depth\"\n}\n");
    EXPECT_NE(s.json().find("`depth`"), std::string::npos);  // no wording: the key as it is
}

TEST(Stats, AFrameOfThePipelineSaysWhatWasDrawn) {
    model::SurfaceSpec spec;
    spec.input = "analytic:sphere";
    spec.iso = 0.0;
    spec.depth = 5;
    spec.colours = true;
    model::Surface surface = model::buildSurface(spec);
    model::RenderSpec view;
    view.renderer = "area+colour";
    view.width = 64;
    view.height = 48;
    const Box3 bounds = surface.tree.occupiedBounds();
    const Camera cam = model::frameCamera(view, bounds);
    const RenderSettings rs = model::renderSettings(spec, surface, view);
    Frame frame;
    const RenderStats st = model::renderFrame(surface.tree, cam, rs, view.renderer, frame);
    model::FrameRecord r;
    r.input = spec.input;
    r.surface = &surface;
    r.camera = &cam;
    r.settings = &rs;
    r.stats = &st;
    r.colourCoherence = resolveRendererName(view.renderer).colourCoherence;
    r.bounds = bounds;
    const model::Stats s = model::frameStats(r);
    EXPECT_EQ(std::get<std::string>(*s.find("renderer")), "area+colour");
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("width")), 64u);
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("pixels")), 64u * 48u);
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("depth")), 5u);
    EXPECT_EQ(std::get<double>(*s.find("colour_tolerance")), model::opt::colourTolerance.defaultValue);
    EXPECT_EQ(std::get<std::uint64_t>(*s.find("boundary_voxels")), surface.tree.boundaryVoxels());
    EXPECT_EQ(std::get<std::string>(*s.find("projection")), "perspective");
    EXPECT_EQ(s.find("lod"), nullptr);  // no cut asked for
    EXPECT_GT(std::get<std::uint64_t>(*s.find("hits")), 0u);
}
