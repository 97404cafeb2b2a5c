// octrace render: read a field, build the shell octree of an isosurface, render, write the
// image (and optionally stats JSON), optionally verify against the reference traversal.
#include "Commands.h"
#include "octrace/model/Input.h"
#include "Options.h"
#include "StatsJson.h"
#include "SurfaceOptions.h"
#include "FigureOptions.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/model/Render.h"
#include "octrace/model/Verify.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace octrace::cli {
namespace {

/// The surface (SurfaceArgs), how it is drawn (model::RenderSpec), and what only the command
/// line has: files, --verify, --repeat, --baseline, the object octree of sphere scenes.
struct RenderArgs : SurfaceArgs, model::RenderSpec {
    FigureArgs figure;
    std::string output, statsPath;
    RendererName resolved;  // RenderSpec::renderer, split (after the parse)
    bool verify = false;
    int repeat = int(model::opt::repeat.defaultValue);
    std::string baseline;  // as given; empty: none
    RendererName baselineRenderer;  // `baseline`, split
    // Sphere scenes.
    std::string octreeKind;  // "object", "voxel" or empty: by the renderer
    int leafObjects = int(model::opt::leafObjects.defaultValue);
};

OptionParser makeParser(RenderArgs& a) {
    OptionParser p("render", "octrace render INPUT -o OUT.(png|exr|tif) [options]");
    p.add({"o", "FILE", "output image; format from the extension: " + joinNames(io::imageExtensions()) + " (required)",
           [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    addLightingOption(p, a);
    addBakeOptions(p, a);
    const model::SettingTargets into{.surface = &a, .render = &a, .figure = &a.figure};
    p.add(settingOption(model::opt::renderer, into,
                        "one of " + joinNames(rendererNames()) + "; " + voxelRenderersThat(&Renderer::colourCoherence) +
                            " take the suffix +colour, which turns --colour-coherence on (area+colour is paper A's)"));
    p.add({"size", "WxH", "image size in pixels, each side " + model::opt::width.rangeText() + " (default " +
           model::opt::width.defaultSaid() + "x" + model::opt::height.defaultSaid() + ")",
           [into](const std::string& v) { model::applySetting(model::opt::size, v, into); }});
    for (const model::Option* o : {&model::opt::cameraPos, &model::opt::lookAt, &model::opt::up, &model::opt::fov,
                                   &model::opt::projection, &model::opt::orthoHeight, &model::opt::lod, &model::opt::level})
        p.add(settingOption(*o, into));
    addThreadsOption(p, a, "the image");
    p.add({"stats", "FILE.json", "write timings and counters as JSON (keys: docs/user/cli.md)",
           [&](const std::string& v) { a.statsPath = v; }});
    p.add(tableOption(model::opt::verify, [&](const std::string&) { a.verify = true; }));
    p.add(settingOption(model::opt::background, into));
    p.add(settingOption(model::opt::light, into));
    addColourOptions(p, a);
    addLayerOptions(p, a);
    for (const model::Option* o : {&model::opt::colourCoherence, &model::opt::colourFillBackground, &model::opt::colourTolerance,
                                   &model::opt::branchUp, &model::opt::missCoherence, &model::opt::tileSize})
        p.add(settingOption(*o, into));
    addGeographicOptions(p, a.request);
    addCityOptions(p, a);
    addSeriesOption(p, a.request);
    p.add(tableOption(model::opt::repeat, [&](const std::string& v) { a.repeat = tableInt(model::opt::repeat, v); }));
    p.add(tableOption(model::opt::baseline, [&](const std::string& v) {
        (void)resolveRendererName(v);
        a.baseline = v;
    }));
    p.add(tableOption(model::opt::octree, [&](const std::string& v) { a.octreeKind = model::parseChoice(model::opt::octree, v); }));
    p.add(tableOption(model::opt::leafObjects, [&](const std::string& v) { a.leafObjects = tableInt(model::opt::leafObjects, v); }));
    p.add(settingOption(model::opt::samples, into));
    p.add(settingOption(model::opt::bounces, into));
    addFigureOptions(p, a.figure);
    addMessageOptions(p, a);
    return p;
}

/// The frames (the image, the baseline's, with --verify the two references or oracles) and the
/// encoded file (at most 24 bytes a pixel): checked first alone, after the build with the rest.
std::uint64_t outputFrameBytes(const RenderArgs& a) {
    return Frame::bytesFor(a.width, a.height) * (1 + !a.baseline.empty() + 2 * a.verify) + std::uint64_t(a.width) * std::uint64_t(a.height) * 24;
}


/// Pixels whose hit (the sphere of the first sample, or a miss) differs.
std::uint64_t mismatchedHits(const Frame& a, const Frame& b) {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < a.hitId.size(); ++i) n += a.hitId[i] != b.hitId[i];
    return n;
}

/// The main renderer's frame and its fastest of --repeat runs; with --baseline, the baseline
/// alternating with it (so that a change in the machine's load hits both alike), its fastest.
struct RepeatedRender {
    std::unique_ptr<Renderer> renderer;
    RenderStats stats;
    std::vector<double> times;  // sorted
    double baselineMs = std::numeric_limits<double>::infinity();
    std::uint64_t baselineDiffering = 0;  // pixels whose colour differs from the baseline's
};

RepeatedRender renderRepeated(const RenderArgs& a, Frame& frame,
                              const std::function<RenderStats(const Renderer&, const RendererName&, Frame&)>& draw) {
    RepeatedRender r;
    r.renderer = makeRenderer(a.resolved.renderer);
    const Renderer& renderer = *r.renderer;
    std::unique_ptr<Renderer> base = a.baseline.empty() ? nullptr : makeRenderer(a.baselineRenderer.renderer);
    const Renderer* baseline = base.get();
    Frame baseFrame;
    r.stats = draw(renderer, a.resolved, frame);
    r.times.push_back(r.stats.renderMs);
    if (baseline) r.baselineMs = draw(*baseline, a.baselineRenderer, baseFrame).renderMs;
    for (int i = 1; i < a.repeat; ++i) {
        r.times.push_back(draw(renderer, a.resolved, frame).renderMs);
        r.stats.renderMs = std::min(r.stats.renderMs, r.times.back());
        if (baseline) r.baselineMs = std::min(r.baselineMs, draw(*baseline, a.baselineRenderer, baseFrame).renderMs);
    }
    std::sort(r.times.begin(), r.times.end());
    if (baseline) r.baselineDiffering = compareImages(frame, baseFrame).differingPixels;
    if (r.stats.hits == 0) log::warning("the scene is not in view: every pixel is background");
    if (!a.figure.enabled) {  // a figure is written by the caller, around the frame
        io::ImageWriteOptions options;
        options.dpi = a.figure.dpi;
        io::writeImage(frame, a.output, options);
    }
    return r;
}

/// The stats keys of --repeat and --baseline.
void recordRepeats(model::FrameRecord& record, const RenderArgs& a, const RepeatedRender& r) {
    record.repeat = a.repeat;
    record.renderMsMedian = r.times[r.times.size() / 2];
    record.baseline = a.baseline;
    record.baselineMs = r.baselineMs;
    record.baselineDifferingPixels = r.baselineDiffering;
}

/// octrace render on a sphere scene traced in its object octree (paper B).
int renderObjectOctree(const RenderArgs& a) {
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    const char* voxelOption = a.iso || !a.isoPreset.empty() ? "--iso"
                              : a.depthGiven                 ? "--depth"
                              : !a.request.variable.empty()  ? "--var"
                              : a.formGiven                  ? "--form"
                              : !a.windowName.empty()        ? "--window"
                                                             : nullptr;
    if (voxelOption)
        throw UsageError(std::string(voxelOption) + " applies to voxel octrees; the object octree of " + a.input +
                         " traces the spheres themselves (--octree voxel voxelizes them)");
    if (a.detail.lodPixels > 0.0 || a.detail.level >= 0) throw UsageError("--lod/--level: the object octree has no multi-resolution mode");
    if (a.figure.enabled) throw UsageError("--figure applies to voxel surfaces, not to the object octree of " + a.input);
    if (a.coherence.colour)
        throw UsageError("--colour-coherence applies to the voxel ray casters " + voxelRenderersThat(&Renderer::colourCoherence));
    const int threads = a.threads == 0 ? hardwareThreads() : a.threads;
    const std::uint64_t budget = memoryBudget(a);
    const std::uint64_t frameBytes = outputFrameBytes(a);
    const std::string rendering = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    checkMemoryBudget(a.input + ": " + rendering, frameBytes, budget);

    Timer loadTimer;
    SphereSet set = loadSpheres(a.input, budget);
    const double loadMs = loadTimer.ms();
    for (const auto& n : set.notes) log::debug(n);
    const std::vector<std::string> notes = set.notes;
    const std::string units = set.units;
    Timer buildTimer;
    ObjectOctreeOptions oo;
    oo.leafObjects = a.leafObjects;
    oo.memoryBudget = budget;
    const ObjectOctree tree = ObjectOctree::build(std::move(set), oo);
    const double buildMs = buildTimer.ms();
    checkMemoryBudget(a.input + ": " + rendering + " beside the object octree", frameBytes + tree.bytes(), budget);

    const Box3 bounds = tree.scene.bounds();
    const Camera cam = model::frameCamera(a, bounds);
    RenderSettings rs;
    rs.threads = a.threads;
    rs.background = displayToLinear(a.background.value_or(vec4(1.0f)));
    if (a.light) rs.lightCamera = *a.light;
    rs.spheres.samples = a.spheres.samples;
    rs.spheres.bounces = a.spheres.bounces;
    rs.shadows = a.shadows;  // unset: on (SphereRenderers.cpp)

    for (const auto& [name, resolved] : {std::pair{a.renderer, a.resolved}, std::pair{a.baseline, a.baselineRenderer}})
        if (!name.empty() && !makeRenderer(resolved.renderer)->drawsSpheres())
            throw UsageError("renderer " + name + " draws voxel octrees only; the object octree takes reference, samet or beam (or give --octree voxel)");
    Frame frame;
    const RepeatedRender rep = renderRepeated(a, frame, [&](const Renderer& r, const RendererName&, Frame& f) {
        return r.renderSpheres(tree, cam, rs, f);
    });
    const RenderStats& st = rep.stats;

    StatsJson js;
    js.set("renderer", st.renderer);
    js.set("input", a.input);
    js.set("octree", std::string("object"));
    js.set("units", units);
    js.set("width", cam.width);
    js.set("height", cam.height);
    js.set("threads", threads);
    js.set("samples", a.spheres.samples);
    js.set("bounces", a.spheres.bounces);
    js.set("shadows", std::string(a.shadows.value_or(true) ? "on" : "off"));
    js.set("pixels", st.pixels);
    js.set("rays", st.rays);
    js.set("hits", st.hits);
    js.set("load_ms", loadMs);
    js.set("build_ms", buildMs);
    js.set("render_ms", st.renderMs);
    model::FrameRecord repeats;
    repeats.stats = &st;
    recordRepeats(repeats, a, rep);
    model::addRepeatStats(js, repeats);
    js.set("us_per_ray", st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0);
    js.set("nodes_visited", st.nodesVisited);
    js.set("nodes_per_ray", st.rays ? double(st.nodesVisited) / double(st.rays) : 0.0);
    js.set("intersections", st.intersections);
    js.set("secondary_rays", st.secondaryRays);
    js.set("beams", st.beams);
    js.set("spheres", std::uint64_t(tree.scene.spheres.size()));
    js.set("leaf_objects", a.leafObjects);
    js.set("octree_depth", tree.depth);
    js.set("octree_nodes", std::uint64_t(tree.nodes.size()));
    js.set("octree_leaves", std::uint64_t(tree.leaves()));
    js.set("occupied_leaves", std::uint64_t(tree.occupiedLeaves()));
    js.set("octree_bytes", std::uint64_t(tree.bytes()));
    model::addCameraStats(js, cam, bounds);
    js.set("cube_origin", model::vectorText(tree.cubeOrigin));
    js.set("cube_side", tree.cubeSide);

    std::ostringstream summary;
    summary.precision(4);
    summary << a.output << ": " << cam.width << "x" << cam.height << ", " << st.renderer << ", " << st.renderMs << " ms ("
            << (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0) << " us/ray over " << st.rays << " rays, " << a.spheres.samples
            << " per pixel), " << tree.scene.spheres.size() << " spheres in " << tree.nodes.size() << " nodes built in " << buildMs << " ms";
    if (a.verify) {
        // The reference (recursive parametric traversal of the same octree) and the brute force
        // (every sphere, no octree), so that no tracer is judged only against another octree tracer.
        Frame rf, bf;
        RenderStats rst = makeRenderer("reference")->renderSpheres(tree, cam, rs, rf);
        makeBruteForceSphereRenderer()->renderSpheres(tree, cam, rs, bf);
        const std::uint64_t mismatched = mismatchedHits(frame, rf), bruteMismatched = mismatchedHits(frame, bf);
        const ImageDifference d = compareImages(frame, rf);
        js.set("mismatched_pixels", mismatched);
        js.set("mismatched_pixels_brute_force", bruteMismatched);
        js.set("reference_mismatched_pixels_brute_force", mismatchedHits(rf, bf));
        js.set("psnr_db", d.psnrDb);
        js.set("max_channel_error", d.maxChannelError);
        js.set("reference_render_ms", rst.renderMs);
        js.set("speedup_over_reference", st.renderMs > 0 ? rst.renderMs / st.renderMs : 0.0);
        summary << "; verify: " << mismatched << " pixels differ from the reference, " << bruteMismatched << " from the brute force";
        if (mismatched != 0 || bruteMismatched != 0)
            log::warning(std::to_string(mismatched) + " pixels differ from the reference, " + std::to_string(bruteMismatched) + " from the brute force");
    }
    std::string noteText;
    for (const auto& n : notes) noteText += (noteText.empty() ? "" : "; ") + n;
    js.set("notes", noteText);
    log::info(summary.str());
    if (!a.statsPath.empty()) io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    return 0;
}

}  // namespace

int runRender(const std::vector<std::string>& args) {
    RenderArgs a;
    const OptionParser parser = makeParser(a);
    if (!parseCommandLine(parser, args, a, a.output, "an output image: -o OUT.png, -o OUT.exr or -o OUT.tif")) return 0;
    a.resolved = resolveRendererName(a.renderer);
    if (!a.baseline.empty()) a.baselineRenderer = resolveRendererName(a.baseline);
    checkImageOutput(a.output);
    if (a.orthoHeight && !a.ortho) throw UsageError("--ortho-height needs --projection ortho");
    checkFigureOptions(a.figure, a.output);
    if (isSphereInput(a.input)) {
        const bool object = a.octreeKind.empty() ? makeRenderer(a.resolved.renderer)->drawsSpheres() : a.octreeKind == "object";
        if (object) return renderObjectOctree(a);
    } else if (!a.octreeKind.empty()) {
        throw UsageError("--octree applies to sphere inputs (.pdb, .cif, sphereflake:L, random:N), not to " + a.input);
    }
    // The object octree's options, given for a voxel scene.
    for (const std::string& flag : parser.given())
        for (const model::Option* o : {&model::opt::leafObjects, &model::opt::bounces})
            if (flag == o->flag)
                throw UsageError("--" + flag + " applies to sphere scenes in the object octree (renderers reference, samet, beam)");
    const bool multires = model::checkRenderSpec(a, a, a.baseline);
    const std::unique_ptr<Renderer> chosen = makeRenderer(a.resolved.renderer);
    // Options the renderer does not read are accepted (a script may set them always), but told.
    // A +colour name turns colour coherence on as --colour-coherence does.
    warnUnused(parser, *chosen, a.renderer, [&](std::string_view key) {
        return key == model::opt::colourCoherence.key && (a.coherence.colour || a.resolved.colourCoherence);
    });

    // A figure: the plot is the image area its layout leaves (--size or --print-size is the whole).
    std::optional<io::FigureLayout> figureLayoutUsed;
    if (a.figure.enabled) {
        figureLayoutUsed = figureLayout(a.figure, a.width, a.height, figureHasColourBar(a));
        a.width = figureLayoutUsed->plotW;
        a.height = figureLayoutUsed->plotH;
    }
    // `depth` auto aims a geometry input's voxels at a pixel of this view.
    a.viewWidth = a.width;
    a.viewHeight = a.height;
    a.viewFov = a.fov;
    const std::uint64_t budget = memoryBudget(a);
    const std::uint64_t frameBytes = outputFrameBytes(a) + (figureLayoutUsed ? Frame::bytesFor(figureLayoutUsed->width, figureLayoutUsed->height) : 0);
    const std::string rendering = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    checkMemoryBudget(a.input + ": " + rendering, frameBytes, budget);

    // Load and build (with corner values when the frame is smooth: surfaceModeFor).
    const bool smoothAsked = a.surface == SurfaceMode::Smooth;
    if (!a.surface) a.surface = model::surfaceModeFor(std::nullopt, a.renderer);
    Surface surface = buildSurface(a);
    if (smoothAsked && surface.tree.corners().empty())
        log::warning(a.input + ": drawn as voxels: --surface smooth needs corner values, which cities, molecules, --cut and "
                     "octree files written without them (format version 1 or 2) do not have");
    const ScalarField& field = surface.field;
    const BuildReport& report = surface.report;
    Octree& tree = surface.tree;
    if (multires) tree.computeSummaries();
    const std::size_t rssAfterBuild = peakRssBytes();
    checkMemoryBudget(a.input + ": " + rendering + " beside the field and the octree",
                      frameBytes + tree.bytes() + field.values.capacity() * sizeof(float) + field.valid.capacity(), budget);

    // Camera: framing the surface (not the whole grid) unless told otherwise; a figure's plot
    // first takes the size its text leaves.
    const Box3 bounds = tree.occupiedBounds();
    const model::SceneView view = model::sceneView(field);
    const RenderSettings rs = model::renderSettings(a, surface, a);
    if (figureLayoutUsed) {
        figureLayoutUsed = model::fitFigureLayout(*figureLayoutUsed, a.figure, figureSubject(surface, a.input), tree, rs, a, bounds, view);
        a.width = figureLayoutUsed->plotW;
        a.height = figureLayoutUsed->plotH;
    }
    const Camera cam = model::frameCamera(a, bounds, view);
    if (a.shadows.value_or(false) && !Shader(tree, cam, rs).shadows())
        log::warning("--shadows on: the octree is shaded by its baked light, which has its own shadows "
                     "(--bake-shadows); give --lighting dynamic for shadow rays towards --light");

    Frame frame;
    const RepeatedRender rep = renderRepeated(a, frame, [&](const Renderer& r, const RendererName& name, Frame& f) {
        RenderSettings s = rs;
        name.applyTo(s);
        return renderAntialiased(r, tree, cam, s, f);
    });
    const RenderStats& st = rep.stats;
    const Renderer* renderer = rep.renderer.get();
    if (figureLayoutUsed) writeFigure(frame, a.figure, *figureLayoutUsed, figureSubject(surface, a.input), tree, cam, rs, a.output);

    model::FrameRecord record = model::frameRecord(a.input, surface, cam, rs, st, a.renderer, bounds);
    record.figure = figureLayoutUsed;
    recordRepeats(record, a, rep);
    record.peakRssAfterBuild = rssAfterBuild;
    record.multiResolution = multires;
    StatsJson js;
    static_cast<model::Stats&>(js) = model::frameStats(record);
    js.set("samples", a.spheres.samples);

    std::ostringstream summary;
    summary.precision(4);
    summary << a.output << ": " << cam.width << "x" << cam.height << ", " << st.renderer << ", " << st.renderMs << " ms (";
    if (renderer->tracesRays())
        summary << (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0) << " us/ray over " << st.rays << " rays), ";
    else
        summary << st.voxelsSplatted << " voxel footprints drawn), ";
    summary << tree.boundaryVoxels() << " boundary voxels at depth " << tree.depth << " built in " << report.buildMs << " ms";

    if (a.verify) {
        log::info("verifying: rendering the frame again with the reference traversal (slower than the renderers)");
        const model::Verification v = model::verifyFrame(tree, cam, rs, frame, *renderer, a.repeat);
        js.set("mismatched_pixels", v.mismatchedPixels);
        js.set("psnr_db", v.psnrDb);
        js.set("max_channel_error", v.maxChannelError);
        js.set("reference_render_ms", v.referenceMs);
        js.set("reference_us_per_ray", v.referenceUsPerRay);
        js.set("speedup_over_reference", st.renderMs > 0 ? v.referenceMs / st.renderMs : 0.0);
        js.set("unquantized_mismatched_pixels", v.unquantizedMismatchedPixels);
        js.set("hit_agreement", v.hitAgreement);
        if (v.levelOfDetail) {
            js.set("lod_psnr_db", v.levelOfDetail->psnrDb);
            js.set("lod_differing_pixels", v.levelOfDetail->differingPixels);
            summary << "; multi-resolution: PSNR " << v.levelOfDetail->psnrDb << " dB against the exact image";
        }
        js.set("depth_max_error_voxel_diagonals", v.depthMaxErrorDiagonals);
        summary << "; verify: " << v.mismatchedPixels << " pixels differ from the reference (" << v.unquantizedMismatchedPixels
                << " from the unquantized rays), PSNR " << v.psnrDb << " dB (max channel error " << v.maxChannelError
                << "), hit agreement " << v.hitAgreement * 100.0 << "%, depth within " << v.depthMaxErrorDiagonals
                << " voxel diagonals";
        if (v.mismatchedPixels != 0) log::warning(std::to_string(v.mismatchedPixels) + " pixels differ from the reference traversal");
    }
    log::info(summary.str());
    if (!a.statsPath.empty()) io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    return 0;
}

}  // namespace octrace::cli
