// octrace render: read a field, build the shell octree of an isosurface, render, write the
// image (and optionally stats JSON), optionally verify against the reference traversal.
#include "Commands.h"
#include "Input.h"
#include "Options.h"
#include "StatsJson.h"
#include "SurfaceOptions.h"
#include "FigureOptions.h"

#include "octrace/io/AtomicFile.h"
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

std::string vecText(const dvec3& v) {
    std::ostringstream o;
    o.precision(10);
    o << v.x << "," << v.y << "," << v.z;
    return o.str();
}

struct RenderArgs : SurfaceArgs {
    FigureArgs figure;
    std::string output, statsPath, rendererName = "full";
    int width = 1600, height = 1200;
    std::optional<dvec3> cameraPos, lookAt, up;
    double fov = 30.0;
    bool ortho = false;
    double lod = 0.0;
    int level = -1;
    std::optional<double> orthoHeight;
    bool verify = false;
    vec4 background{1.0f, 1.0f, 1.0f, 1.0f};
    std::optional<dvec3> light;
    bool colourCoherence = false;
    float colourTolerance = 3.0f;
    bool colourToleranceGiven = false;
    bool colourFillsBackground = false;
    int branchUp = 0;
    bool branchUpGiven = false;
    bool missCoherence = true;
    bool missCoherenceGiven = false;
    int repeat = 1;
    std::string baseline;
    // Sphere scenes.
    std::string octreeKind;  // "object", "voxel" or empty: by the renderer
    int leafObjects = ObjectOctreeOptions{}.leafObjects;
    int samples = 1, bounces = RenderSettings{}.bounces;
    std::vector<std::string> sphereOptions;  // given, for the check that they apply
};

OptionParser makeParser(RenderArgs& a) {
    OptionParser p("render", "octrace render INPUT -o OUT.(png|exr|tif) [options]");
    p.add({"o", "FILE", "output image; format from the extension: " + joinNames(io::imageExtensions()) + " (required)",
           [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    addLightingOption(p, a);
    addBakeOptions(p, a);
    p.add({"renderer", "NAME", "renderer: " + joinNames(rendererNames()) + "; samet and beam (paper B) draw sphere scenes and voxel octrees alike (default full)",
           [&](const std::string& v) {
               makeRenderer(v);  // validates the name
               a.rendererName = v;
           }});
    p.add({"size", "WxH", "image size in pixels (default 1600x1200)",
           [&](const std::string& v) { parseSize("size", v, a.width, a.height); }});
    p.add({"camera-pos", "X,Y,Z", "camera position, world units (default: framing the surface from south-east, above)",
           [&](const std::string& v) { a.cameraPos = parseVec3("camera-pos", v); }});
    p.add({"look-at", "X,Y,Z", "point the camera looks at (default: centre of the surface's bounding box)",
           [&](const std::string& v) { a.lookAt = parseVec3("look-at", v); }});
    p.add({"up", "X,Y,Z", "camera up direction (default 0,0,1)", [&](const std::string& v) { a.up = parseVec3("up", v); }});
    p.add({"fov", "DEG", "vertical field of view in degrees, (0,180) (default 30)",
           [&](const std::string& v) {
               a.fov = parseNumber("fov", v);
               if (!(a.fov > 0.0 && a.fov < 180.0)) throw UsageError("--fov: must be in (0, 180) degrees, got " + v);
           }});
    p.add({"projection", "perspective|ortho", "camera projection; ortho draws every ray parallel to the view direction (default perspective)",
           [&](const std::string& v) {
               if (v == "perspective") a.ortho = false;
               else if (v == "ortho" || v == "orthographic") a.ortho = true;
               else throw UsageError("--projection: choose perspective or ortho, got '" + v + "'");
           }});
    p.add({"ortho-height", "H", "height of the orthographic view window in world units (default: framing the surface)",
           [&](const std::string& v) {
               a.orthoHeight = parseNumber("ortho-height", v);
               if (!(*a.orthoHeight > 0.0)) throw UsageError("--ortho-height: must be positive, got " + v);
           }});
    p.add({"lod", "PIXELS", "multi-resolution: stop at octree nodes whose projected size is below PIXELS and draw them whole; renderers " + voxelRenderersThat(&Renderer::multiResolution) + " (default 0 = exact)",
           [&](const std::string& v) {
               a.lod = parseNumber("lod", v);
               if (!(a.lod >= 0.0 && a.lod <= 1e6)) throw UsageError("--lod: must be a number of pixels >= 0, got " + v);
           }});
    p.add({"level", "L", "draw the octree at level L (1..depth) at the finest, for previews; renderers as --lod (default: the voxels)",
           [&](const std::string& v) { a.level = parseInt("level", v, 1, Octree::kMaxDepth); }});
    addThreadsOption(p, a, "the image");
    p.add({"stats", "FILE.json", "write timings and counters as JSON (keys: docs/user/cli.md)",
           [&](const std::string& v) { a.statsPath = v; }});
    p.add({"verify", "", "also trace every pixel with the reference traversal and report the differences",
           [&](const std::string&) { a.verify = true; }});
    p.add({"background", "R,G,B[,A]", "background colour, sRGB components in [0,1] (default 1,1,1,1)",
           [&](const std::string& v) { a.background = parseColour("background", v, true); }});
    p.add({"light", "X,Y,Z", "direction towards the light in camera space, x right, y up, z to the viewer (default 0.4,0.6,1)",
           [&](const std::string& v) {
               a.light = parseVec3("light", v);
               if (!(glm::length(*a.light) > 0.0)) throw UsageError("--light: direction must not be zero");
           }});
    addColourOptions(p, a);
    addLayerOptions(p, a);
    p.add({"colour-coherence", "", "colour coherence on the discrete ray casters: a pixel between two neighbours of nearly the same colour gets their average untraced (default off; on in area+colour)",
           [&](const std::string&) { a.colourCoherence = true; }});
    p.add({"colour-fill-background", "", "colour coherence also between two background pixels, as paper A does: the pixel between is taken as background untraced (default off: only between surface pixels)",
           [&](const std::string&) { a.colourFillsBackground = true; }});
    p.add({"colour-tolerance", "T", "largest difference per 8-bit sRGB channel for colour coherence, 0..255 (default 3)",
           [&](const std::string& v) {
               double t = parseNumber("colour-tolerance", v);
               if (t < 0.0 || t > 255.0) throw UsageError("--colour-tolerance: must be in [0, 255], got " + v);
               a.colourTolerance = float(t);
               a.colourToleranceGiven = true;
           }});
    p.add({"branch-up", "N", "trajectory coherence (linear, area, their exact and +colour variants): start a common-path ray N octree levels above its partners' branch node; fewer pixels differ from full traversal, at some speed (default 0: paper A, at the branch node)",
           [&](const std::string& v) {
               a.branchUp = parseInt("branch-up", v, 0, Octree::kMaxDepth);
               a.branchUpGiven = true;
           }});
    p.add({"miss-coherence", "on|off", "approximate linear and area (and +colour): a common-path pixel whose two partners both missed is taken as background untraced (default on; off: traced from the root)",
           [&](const std::string& v) {
               if (v != "on" && v != "off") throw UsageError("--miss-coherence: choose on or off, got '" + v + "'");
               a.missCoherence = v == "on";
               a.missCoherenceGiven = true;
           }});
    addGeographicOptions(p, a.request);
    addCityOptions(p, a);
    addSeriesOption(p, a.request);
    p.add({"repeat", "N", "render N times and report the fastest as render_ms (benchmarks on a noisy machine; default 1)",
           [&](const std::string& v) { a.repeat = parseInt("repeat", v, 1, 1000); }});
    p.add({"baseline", "NAME", "also render with renderer NAME, alternating with the main one --repeat times, and report baseline_render_ms, speedup_over_baseline and baseline_differing_pixels (pixels whose colour differs) (default: none)",
           [&](const std::string& v) {
               makeRenderer(v);
               a.baseline = v;
           }});
    p.add({"octree", "object|voxel", "sphere inputs: trace the spheres in paper B's object octree (renderers reference, samet, beam) or voxelize them into the voxel octree at --depth (every voxel renderer, samet and beam included) (default: object for reference, samet, beam; voxel for the others)",
           [&](const std::string& v) {
               if (v != "object" && v != "voxel") throw UsageError("--octree: choose object or voxel, got '" + v + "'");
               a.octreeKind = v;
           }});
    // An integer option of the object octree, noted as given (it applies to sphere scenes only).
    auto sphereInt = [&](const std::string& name, const std::string& help, int lo, int hi, int& target) {
        p.add({name, "N", help + ", " + std::to_string(lo) + ".." + std::to_string(hi) + " (default " + std::to_string(target) + ")",
               [&a, &target, name, lo, hi](const std::string& v) {
                   target = parseInt(name, v, lo, hi);
                   a.sphereOptions.push_back("--" + name);
               }});
    };
    sphereInt("leaf-objects", "object octree: split a node while it holds more than N spheres", 1, 100000, a.leafObjects);
    p.add({"samples", "N", "object octree: rays per pixel on a sqrt(N) x sqrt(N) grid, averaged; a square 1..256 (default 1)",
           [&](const std::string& v) {
               a.samples = parseInt("samples", v, 1, 256);
               const int side = int(std::lround(std::sqrt(double(a.samples))));
               if (side * side != a.samples) throw UsageError("--samples: must be a square number (1, 4, 9, 16, ...), got " + v);
               a.sphereOptions.push_back("--samples");
           }});
    sphereInt("bounces", "object octree: Whitted depth, reflected and transmitted rays at most N deep", 0, 16, a.bounces);
    addFigureOptions(p, a.figure);
    addMessageOptions(p, a);
    return p;
}

/// The frames (the image, the baseline's, with --verify the two references or oracles) and the
/// encoded file (at most 24 bytes a pixel): checked first alone, after the build with the rest.
std::uint64_t outputFrameBytes(const RenderArgs& a) {
    return Frame::bytesFor(a.width, a.height) * (1 + !a.baseline.empty() + 2 * a.verify) + std::uint64_t(a.width) * std::uint64_t(a.height) * 24;
}

/// The camera of the options, framing `bounds` unless told otherwise.
Camera makeCamera(const RenderArgs& a, const Box3& bounds) {
    Camera cam = Camera::framing(bounds, a.width, a.height, a.fov);
    if (a.lookAt) cam.lookAt = *a.lookAt;
    if (a.up) cam.up = *a.up;
    if (a.cameraPos) cam.position = *a.cameraPos;
    else if (a.lookAt) cam.position = cam.lookAt + (Camera::framing(bounds, a.width, a.height, a.fov).position - bounds.centre());
    if (a.ortho) {
        cam.validate();
        cam.frameOrthographic(bounds);
        if (a.cameraPos) cam.position = *a.cameraPos;  // the user's view plane, even if it cuts the surface
        if (a.orthoHeight) cam.orthoHeight = *a.orthoHeight;
    }
    cam.validate();
    return cam;
}

/// What the voxel and the sphere paths write alike: the view.
void setCameraStats(StatsJson& js, const Camera& cam, const Box3& bounds) {
    js.set("camera_pos", vecText(cam.position));
    js.set("look_at", vecText(cam.lookAt));
    js.set("up", vecText(cam.up));
    js.set("projection", std::string(cam.orthographic() ? "ortho" : "perspective"));
    if (cam.orthographic()) js.set("ortho_height", cam.orthoHeight);
    else js.set("fov", cam.fovYDegrees);
    js.set("surface_bounds_min", vecText(bounds.lo));
    js.set("surface_bounds_max", vecText(bounds.hi));
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

RepeatedRender renderRepeated(const RenderArgs& a, Frame& frame, const std::function<RenderStats(const Renderer&, Frame&)>& draw) {
    RepeatedRender r;
    r.renderer = makeRenderer(a.rendererName);
    const Renderer& renderer = *r.renderer;
    std::unique_ptr<Renderer> base = a.baseline.empty() ? nullptr : makeRenderer(a.baseline);
    const Renderer* baseline = base.get();
    Frame baseFrame;
    r.stats = draw(renderer, frame);
    r.times.push_back(r.stats.renderMs);
    if (baseline) r.baselineMs = draw(*baseline, baseFrame).renderMs;
    for (int i = 1; i < a.repeat; ++i) {
        r.times.push_back(draw(renderer, frame).renderMs);
        r.stats.renderMs = std::min(r.stats.renderMs, r.times.back());
        if (baseline) r.baselineMs = std::min(r.baselineMs, draw(*baseline, baseFrame).renderMs);
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
void setRepeatStats(StatsJson& js, const RenderArgs& a, const RepeatedRender& r) {
    if (a.repeat > 1) {
        js.set("repeat", a.repeat);
        js.set("render_ms_median", r.times[r.times.size() / 2]);
    }
    if (!a.baseline.empty()) {
        js.set("baseline", a.baseline);
        js.set("baseline_render_ms", r.baselineMs);
        js.set("speedup_over_baseline", r.stats.renderMs > 0 ? r.baselineMs / r.stats.renderMs : 0.0);
        js.set("baseline_differing_pixels", r.baselineDiffering);
    }
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
    if (a.lod > 0.0 || a.level >= 0) throw UsageError("--lod/--level: the object octree has no multi-resolution mode");
    if (a.figure.enabled) throw UsageError("--figure applies to voxel surfaces, not to the object octree of " + a.input);
    if (a.colourCoherence)
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
    const Camera cam = makeCamera(a, bounds);
    RenderSettings rs;
    rs.threads = a.threads;
    rs.background = displayToLinear(a.background);
    if (a.light) rs.lightCamera = *a.light;
    rs.samples = a.samples;
    rs.bounces = a.bounces;
    rs.shadows = a.shadows;  // unset: on (SphereRenderers.cpp)

    for (const std::string& name : {a.rendererName, a.baseline})
        if (!name.empty() && !makeRenderer(name)->drawsSpheres())
            throw UsageError("renderer " + name + " draws voxel octrees only; the object octree takes reference, samet or beam (or give --octree voxel)");
    Frame frame;
    const RepeatedRender rep = renderRepeated(a, frame, [&](const Renderer& r, Frame& f) {
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
    js.set("samples", a.samples);
    js.set("bounces", a.bounces);
    js.set("shadows", std::string(a.shadows.value_or(true) ? "on" : "off"));
    js.set("pixels", st.pixels);
    js.set("rays", st.rays);
    js.set("hits", st.hits);
    js.set("load_ms", loadMs);
    js.set("build_ms", buildMs);
    js.set("render_ms", st.renderMs);
    setRepeatStats(js, a, rep);
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
    setCameraStats(js, cam, bounds);
    js.set("cube_origin", vecText(tree.cubeOrigin));
    js.set("cube_side", tree.cubeSide);

    std::ostringstream summary;
    summary.precision(4);
    summary << a.output << ": " << cam.width << "x" << cam.height << ", " << st.renderer << ", " << st.renderMs << " ms ("
            << (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0) << " us/ray over " << st.rays << " rays, " << a.samples
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
    if (!parseCommandLine(makeParser(a), args, a, a.output, "an output image: -o OUT.png, -o OUT.exr or -o OUT.tif")) return 0;
    checkImageOutput(a.output);
    if (a.orthoHeight && !a.ortho) throw UsageError("--ortho-height needs --projection ortho");
    checkFigureOptions(a.figure, a.output);
    if (isSphereInput(a.input)) {
        const bool object = a.octreeKind.empty() ? makeRenderer(a.rendererName)->drawsSpheres() : a.octreeKind == "object";
        if (object) return renderObjectOctree(a);
    } else if (!a.octreeKind.empty()) {
        throw UsageError("--octree applies to sphere inputs (.pdb, .cif, sphereflake:L, random:N), not to " + a.input);
    }
    if (!a.sphereOptions.empty())
        throw UsageError(a.sphereOptions.front() + " applies to sphere scenes in the object octree (renderers reference, samet, beam)");
    if (a.level > a.depth) throw UsageError("--level " + std::to_string(a.level) + " is deeper than --depth " + std::to_string(a.depth));
    const bool multires = a.lod > 0.0 || (a.level >= 0 && a.level < a.depth);
    const std::unique_ptr<Renderer> chosen = makeRenderer(a.rendererName);
    if (a.colourCoherence && !chosen->colourCoherence())
        throw UsageError("--colour-coherence: renderer " + a.rendererName + " does not fill pixels by colour (use " +
                         voxelRenderersThat(&Renderer::colourCoherence) + ")");
    if (!a.colourCoherence && !chosen->fillsByColour()) {
        // Accepted (a script may set them always), but told: they change nothing here.
        for (const auto& [given, option] : {std::pair{a.colourToleranceGiven, "--colour-tolerance"},
                                            std::pair{a.colourFillsBackground, "--colour-fill-background"}})
            if (given)
                log::warning(std::string(option) + " has no effect without colour coherence (--colour-coherence or a +colour renderer)");
    }
    if (a.branchUpGiven && !chosen->trajectoryCoherence())
        log::warning("--branch-up has no effect on renderer " + a.rendererName + " (only on linear and area and their variants)");
    if (a.missCoherenceGiven && !chosen->missCoherence())
        log::warning("--miss-coherence has no effect on renderer " + a.rendererName + " (only on the approximate linear and area and their +colour variants)");
    if (multires) {
        for (const std::string& r : {a.rendererName, a.baseline})
            if (!r.empty() && !makeRenderer(r)->multiResolution())
                throw UsageError("--lod/--level: renderer " + r + " has no multi-resolution mode (use " + voxelRenderersThat(&Renderer::multiResolution) + ")");
    }
    const int threads = a.threads == 0 ? hardwareThreads() : a.threads;

    // A figure: the plot is the image area its layout leaves (--size or --print-size is the whole).
    std::optional<io::FigureLayout> figureLayoutUsed;
    if (a.figure.enabled) {
        figureLayoutUsed = figureLayout(a.figure, a.width, a.height, figureHasColourBar(a));
        a.width = figureLayoutUsed->plotW;
        a.height = figureLayoutUsed->plotH;
    }
    const std::uint64_t budget = memoryBudget(a);
    const std::uint64_t frameBytes = outputFrameBytes(a) + (figureLayoutUsed ? Frame::bytesFor(figureLayoutUsed->width, figureLayoutUsed->height) : 0);
    const std::string rendering = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    checkMemoryBudget(a.input + ": " + rendering, frameBytes, budget);

    // Load and build.
    Surface surface = buildSurface(a);
    const ScalarField& field = surface.field;
    const double iso = surface.iso, loadMs = surface.loadMs;
    const BuildReport& report = surface.report;
    Octree& tree = surface.tree;
    if (multires) tree.computeSummaries();
    const std::size_t rssAfterBuild = peakRssBytes();
    checkMemoryBudget(a.input + ": " + rendering + " beside the field and the octree",
                      frameBytes + tree.bytes() + field.values.capacity() * sizeof(float) + field.valid.capacity(), budget);

    // Camera: framing the surface (not the whole grid) unless told otherwise.
    const Box3 bounds = tree.occupiedBounds();
    const Camera cam = makeCamera(a, bounds);

    RenderSettings rs;
    rs.threads = a.threads;
    rs.background = displayToLinear(a.background);
    applyColour(a, surface, rs);
    if (a.light) rs.lightCamera = *a.light;
    applyLighting(a, rs);
    rs.colourCoherence = a.colourCoherence;
    rs.colourTolerance = a.colourTolerance;
    rs.colourFillsBackground = a.colourFillsBackground;
    rs.branchUp = a.branchUp;
    rs.missCoherence = a.missCoherence;
    rs.lodPixels = a.lod;
    rs.level = a.level;
    if (a.shadows.value_or(false) && !Shader(tree, cam, rs).shadows())
        log::warning("--shadows on: the octree is shaded by its baked light, which has its own shadows "
                     "(--bake-shadows); give --lighting dynamic for shadow rays towards --light");

    Frame frame;
    const RepeatedRender rep = renderRepeated(a, frame, [&](const Renderer& r, Frame& f) {
        return r.render(tree, cam, rs, f);
    });
    const RenderStats& st = rep.stats;
    const Renderer* renderer = rep.renderer.get();
    if (figureLayoutUsed) writeFigure(frame, a.figure, *figureLayoutUsed, figureSubject(surface, a.input), tree, cam, rs, a.output);

    StatsJson js;
    js.set("renderer", st.renderer);
    js.set("input", a.input);
    js.set("variable", field.name);
    js.set("units", field.units);
    js.set("iso", iso);
    if (surface.window.valid()) {
        js.set("window_centre", surface.window.centre);
        js.set("window_width", surface.window.width);
        js.set("window_source", surface.windowSource);
        js.set("window_inverted", surface.invertedGrey);
    }
    js.set("depth", tree.depth);
    js.set("width", cam.width);
    js.set("height", cam.height);
    if (figureLayoutUsed) {
        const io::FigureLayout& l = *figureLayoutUsed;
        js.set("figure_width", l.width);
        js.set("figure_height", l.height);
        js.set("figure_dpi", l.dpi);
        js.set("figure_plot", std::to_string(l.plotX) + "," + std::to_string(l.plotY) + "," + std::to_string(l.plotW) + "," + std::to_string(l.plotH));
        if (l.barW > 0)
            js.set("figure_colour_bar", std::to_string(l.barX) + "," + std::to_string(l.barY) + "," + std::to_string(l.barW) + "," + std::to_string(l.barH));
    }
    js.set("threads", threads);
    js.set("pixels", st.pixels);
    js.set("rays", st.rays);
    js.set("hits", st.hits);
    js.set("load_ms", loadMs);
    js.set("build_ms", report.buildMs);
    js.set("lighting", std::string(rs.baked && !tree.baked.empty() ? "baked" : "dynamic"));
    js.set("shadows", std::string(Shader(tree, cam, rs).shadows() ? "on" : "off"));
    js.set("shadow_rays", st.secondaryRays);
    js.set("bake_ms", surface.bake.bakeMs);
    js.set("render_ms", st.renderMs);
    setRepeatStats(js, a, rep);
    // A direct renderer traces no rays: no figure per ray (null), its footprints instead.
    js.set("us_per_ray", renderer->tracesRays() ? (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0)
                                                : std::numeric_limits<double>::quiet_NaN());
    js.set("voxels_splatted", st.voxelsSplatted);
    js.set("rays_full", st.raysFull);
    js.set("rays_common_path", st.raysCommonPath);
    js.set("fallbacks", st.fallbacks);
    js.set("rays_certified", st.raysCertified);
    js.set("states_deferred", st.statesDeferred);
    js.set("colour_filled", st.colourFilled);
    js.set("miss_filled", st.missFilled);
    if (rs.colourCoherence) js.set("colour_tolerance", double(rs.colourTolerance));
    js.set("branch_up", rs.branchUp);
    js.set("miss_coherence", std::string(rs.missCoherence ? "on" : "off"));
    js.set("nodes_visited", st.nodesVisited);
    js.set("nodes_per_ray", st.rays ? double(st.nodesVisited) / double(st.rays) : 0.0);
    js.set("beams", st.beams);
    js.set("intersections", st.intersections);
    js.set("boundary_voxels", std::uint64_t(tree.boundaryVoxels()));
    if (!tree.voxelMaterials.empty())
        js.set("floor_voxels", std::uint64_t(std::count(tree.voxelMaterials.begin(), tree.voxelMaterials.end(),
                                                        std::uint8_t(VoxelMaterial::Floor))));
    if (!rs.colormap.empty()) js.set("colormap", rs.colormap);
    if (!tree.voxelValues.empty()) {
        const Albedo albedo(tree, rs);
        js.set("colour_by", tree.valueName);
        js.set("colour_units", tree.valueUnits);
        js.set("colour_min", double(albedo.low()));
        js.set("colour_max", double(albedo.high()));
    }
    js.set("octree_nodes", std::uint64_t(tree.nodes.size()));
    js.set("octree_bytes", std::uint64_t(tree.bytes()));
    js.set("bytes_per_voxel", tree.bytesPerVoxel());
    js.set("peak_rss_bytes_after_build", std::uint64_t(rssAfterBuild));
    setCameraStats(js, cam, bounds);
    if (multires) {
        js.set("lod", a.lod);
        js.set("level", std::uint64_t(a.level < 0 ? tree.depth : a.level));
    }
    js.set("cube_origin", vecText(tree.cubeOrigin));
    js.set("cube_side", tree.cubeSide);
    for (const auto& n : field.notes) {
        if (n.rfind("vertical scale", 0) == 0 || n.find("vertical scale") != std::string::npos) js.set("geographic", n);
    }

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
        auto ref = makeRenderer("reference");
        Frame rf;
        RenderStats rst = ref->render(tree, cam, rs, rf);
        for (int i = 1; i < a.repeat; ++i) rst.renderMs = std::min(rst.renderMs, ref->render(tree, cam, rs, rf).renderMs);
        // Hit voxel or hit/miss differs, over the traced pixels (colour-filled pixels are not
        // traced: they are judged by the image difference).
        std::uint64_t mismatched = 0;
        for (std::size_t i = 0; i < frame.hitId.size(); ++i)
            mismatched += !(frame.flags[i] & Frame::kColourFilled) && frame.hitId[i] != rf.hitId[i];
        ImageDifference d = compareImages(frame, rf);
        js.set("mismatched_pixels", mismatched);
        js.set("psnr_db", d.psnrDb);
        js.set("max_channel_error", d.maxChannelError);
        js.set("reference_render_ms", rst.renderMs);
        js.set("reference_us_per_ray", rst.rays ? rst.renderMs * 1000.0 / double(rst.rays) : 0.0);
        js.set("speedup_over_reference", st.renderMs > 0 ? rst.renderMs / st.renderMs : 0.0);
        // What quantizing the ray changes: the reference on the exact (unquantized) rays.
        auto unq = makeRenderer("reference-unquantized");
        Frame uf;
        unq->render(tree, cam, rs, uf);
        std::uint64_t qdiff = 0;
        for (std::size_t i = 0; i < rf.hitId.size(); ++i) qdiff += rf.hitId[i] != uf.hitId[i];
        js.set("unquantized_mismatched_pixels", qdiff);
        // Hit agreement, for renderers that do not trace the reference's rays (direct): over the
        // pixels that either renderer hits, the share that both hit; and where both hit, how far
        // apart the depths are, in voxel diagonals.
        std::uint64_t either = 0, both = 0;
        double depthErr = 0.0;
        for (std::size_t i = 0; i < rf.hitId.size(); ++i) {
            const bool h = frame.hitId[i] != kNoHit, r = rf.hitId[i] != kNoHit;
            either += h || r;
            both += h && r;
            if (h && r) depthErr = std::max(depthErr, double(std::abs(frame.depth[i] - rf.depth[i])));
        }
        const double agreement = either ? double(both) / double(either) : 1.0;
        const double diagonals = depthErr / (tree.voxelSize() * std::sqrt(3.0));
        js.set("hit_agreement", agreement);
        if (multires) {
            // What the multi-resolution cut changes: the same renderer down to the voxels.
            RenderSettings exactSettings = rs;
            exactSettings.lodPixels = 0.0;
            exactSettings.level = -1;
            Frame exact;
            renderer->render(tree, cam, exactSettings, exact);
            const ImageDifference ld = compareImages(frame, exact);
            js.set("lod_psnr_db", ld.psnrDb);
            js.set("lod_differing_pixels", ld.differingPixels);
            summary << "; multi-resolution: PSNR " << ld.psnrDb << " dB against the exact image";
        }
        js.set("depth_max_error_voxel_diagonals", diagonals);
        summary << "; verify: " << mismatched << " pixels differ from the reference (" << qdiff
                << " from the unquantized rays), PSNR " << d.psnrDb << " dB (max channel error " << d.maxChannelError
                << "), hit agreement " << agreement * 100.0 << "%, depth within " << diagonals << " voxel diagonals";
        if (mismatched != 0) log::warning(std::to_string(mismatched) + " pixels differ from the reference traversal");
    }
    log::info(summary.str());
    if (!a.statsPath.empty()) io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    return 0;
}

}  // namespace octrace::cli
