// octrace render: read a field, build the shell octree of an isosurface, render, write the
// image (and optionally stats JSON), optionally verify against the reference traversal.
#include "Commands.h"
#include "Input.h"
#include "Options.h"
#include "StatsJson.h"

#include "octrace/build/OctreeBuilder.h"
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

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <optional>
#include <sstream>

namespace octrace::cli {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
vec4 displayToLinear(vec4 c) { return vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a); }

std::string joinNames(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

struct RenderArgs {
    std::string input, output, statsPath, rendererName = "full";
    io::FieldRequest request;
    std::optional<double> iso;
    int depth = 8, threads = 0, width = 1600, height = 1200;
    std::optional<dvec3> cameraPos, lookAt, up;
    double fov = 30.0;
    bool verify = false, help = false, quiet = false, verbose = false;
    vec4 background{1.0f, 1.0f, 1.0f, 1.0f};
    vec3 colour{0.85f, 0.62f, 0.35f};
    std::string colormap;
    std::optional<dvec3> light;
    bool colourCoherence = false;
    float colourTolerance = 3.0f;
    int repeat = 1;
    std::string baseline;
    std::uint64_t maxMemory = 0;  // 0: defaultMemoryBudget()
};

OptionParser makeParser(RenderArgs& a) {
    OptionParser p("render", "octrace render INPUT -o OUT.(png|exr) [options]");
    p.add({"o", "FILE", "output image; format from the extension: " + joinNames(io::imageExtensions()) + " (required)",
           [&](const std::string& v) { a.output = v; }});
    p.add({"var", "NAME", "variable to draw (default: the file's only 3-D variable)",
           [&](const std::string& v) { a.request.variable = v; }});
    p.add({"iso", "VALUE", "iso value of the surface (default: middle of the variable's valid range)",
           [&](const std::string& v) { a.iso = parseNumber("iso", v); }});
    p.add({"depth", "N", "octree depth, voxels = 2^N per cube edge (1.." + std::to_string(Octree::kMaxDepth) + ", default 8)",
           [&](const std::string& v) { a.depth = parseInt("depth", v, 1, Octree::kMaxDepth); }});
    p.add({"renderer", "NAME", "renderer: " + joinNames(rendererNames()) + " (default full)",
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
    p.add({"threads", "N", "worker threads, 0 = all cores (default 0); the image does not depend on it",
           [&](const std::string& v) { a.threads = parseInt("threads", v, 0, 1024); }});
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
    p.add({"colour", "R,G,B", "surface colour, sRGB components in [0,1] (default 0.85,0.62,0.35)",
           [&](const std::string& v) { a.colour = vec3(parseColour("colour", v, false)); }});
    p.add({"color", "R,G,B", "same as --colour (default 0.85,0.62,0.35)", [&](const std::string& v) { a.colour = vec3(parseColour("color", v, false)); }});
    p.add({"colormap", "NAME", "colour the surface by height with a map: " + joinNames(colormapNames()) + " (default: none, --colour)",
           [&](const std::string& v) {
               colormap(v, 0.0f);
               a.colormap = v;
           }});
    p.add({"colour-coherence", "", "colour coherence on any discrete renderer: a pixel between two traced neighbours of nearly the same colour gets their average untraced (default off; on in area+colour)",
           [&](const std::string&) { a.colourCoherence = true; }});
    p.add({"colour-tolerance", "T", "largest difference per 8-bit sRGB channel for colour coherence, 0..255 (default 3)",
           [&](const std::string& v) {
               double t = parseNumber("colour-tolerance", v);
               if (t < 0.0 || t > 255.0) throw UsageError("--colour-tolerance: must be in [0, 255], got " + v);
               a.colourTolerance = float(t);
           }});
    p.add({"region", "LON0,LON1,LAT0,LAT1", "geographic subregion in degrees, NetCDF only (default: the whole grid)",
           [&](const std::string& v) {
               auto r = io::parseRegion(v);
               a.request.hasRegion = true;
               for (int i = 0; i < 4; ++i) a.request.region[i] = r[std::size_t(i)];
           }});
    p.add({"vertical-scale", "S", "vertical exaggeration of depth, NetCDF only (default: depth extent = 1/4 of the larger horizontal extent)",
           [&](const std::string& v) {
               a.request.verticalScale = parseNumber("vertical-scale", v);
               if (!(a.request.verticalScale > 0.0)) throw UsageError("--vertical-scale: must be positive, got " + v);
           }});
    p.add({"repeat", "N", "render N times and report the fastest as render_ms (benchmarks on a noisy machine; default 1)",
           [&](const std::string& v) { a.repeat = parseInt("repeat", v, 1, 1000); }});
    p.add({"baseline", "NAME", "also render with renderer NAME, alternating with the main one --repeat times, and report baseline_render_ms and speedup_over_baseline (default: none)",
           [&](const std::string& v) {
               makeRenderer(v);
               a.baseline = v;
           }});
    p.add({"max-memory", "SIZE", "memory budget for reading the field, building the octree and rendering: bytes, K, M, G, T "
           "(powers of 1024) or N% of the physical memory; a larger job is refused up front (default " +
           std::to_string(kDefaultMemoryBudgetPercent) + "%)",
           [&](const std::string& v) { a.maxMemory = parseByteSize("max-memory", v); }});
    p.add({"quiet", "", "print only errors", [&](const std::string&) { a.quiet = true; }});
    p.add({"verbose", "", "print debugging details", [&](const std::string&) { a.verbose = true; }});
    p.add({"help", "", "show this help and exit", [&](const std::string&) { a.help = true; }});
    return p;
}

/// Progress on stderr while building, only when stderr is a terminal.
std::function<void(double)> progressPrinter(bool quiet) {
    if (quiet || !isatty(2)) return {};
    return [](double f) { std::fprintf(stderr, "\roctrace: building octree %3d%%", int(f * 100.0 + 0.5)); };
}

}  // namespace

int runRender(const std::vector<std::string>& args) {
    RenderArgs a;
    OptionParser parser = makeParser(a);
    auto positional = parser.parse(args);
    if (a.help) {
        std::fputs(parser.help().c_str(), stdout);
        return 0;
    }
    if (positional.size() != 1) throw UsageError("render needs exactly one INPUT (got " + std::to_string(positional.size()) + ")");
    if (a.output.empty()) throw UsageError("render needs an output image: -o OUT.png or -o OUT.exr");
    {
        // Check the output extension before the long work.
        std::string ext = a.output.substr(a.output.find_last_of('.') == std::string::npos ? a.output.size() : a.output.find_last_of('.'));
        for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        bool known = false;
        for (const auto& e : io::imageExtensions()) known = known || e == ext;
        if (!known)
            throw UsageError("-o " + a.output + ": unknown image format '" + ext + "' (use " + joinNames(io::imageExtensions()) + ")");
    }
    a.input = positional[0];
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    const int threads = a.threads == 0 ? hardwareThreads() : a.threads;

    const std::uint64_t budget = a.maxMemory ? a.maxMemory : defaultMemoryBudget();
    a.request.memoryBudget = budget;
    // The frames (the image, the baseline's, with --verify the two references) and the encoded
    // file (at most 24 bytes a pixel): checked first alone, after the build with the rest.
    const std::uint64_t frameBytes = Frame::bytesFor(a.width, a.height) * (1 + !a.baseline.empty() + 2 * a.verify) +
                                     std::uint64_t(a.width) * std::uint64_t(a.height) * 24;
    const std::string rendering = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    checkMemoryBudget(a.input + ": " + rendering, frameBytes, budget);

    // Load.
    Timer t;
    ScalarField field = loadField(a.input, a.request);
    const double loadMs = t.ms();
    auto [vmin, vmax] = field.validRange();
    double iso = a.iso ? *a.iso : 0.5 * (double(vmin) + double(vmax));
    if (!a.iso) {
        std::ostringstream s;
        s << "no --iso given: using " << iso << ", the middle of the range [" << vmin << ", " << vmax << "] of '" << field.name << "'";
        log::info(s.str());
    }
    for (const auto& n : field.notes) log::debug(n);

    // Build.
    BuildOptions bo;
    bo.depth = a.depth;
    bo.iso = iso;
    bo.threads = a.threads;
    bo.progress = progressPrinter(a.quiet);
    bo.memoryBudget = budget;
    BuildReport report;
    Octree tree = buildShellOctree(field, bo, &report);
    if (bo.progress) std::fputs("\n", stderr);
    const std::size_t rssAfterBuild = peakRssBytes();
    checkMemoryBudget(a.input + ": " + rendering + " beside the field and the octree",
                      frameBytes + tree.bytes() + field.values.capacity() * sizeof(float) + field.valid.capacity(), budget);

    // Camera.
    // Frame the surface (not the whole grid) unless told otherwise.
    Box3 bounds = tree.occupiedBounds();
    Camera cam = Camera::framing(bounds, a.width, a.height, a.fov);
    if (a.lookAt) cam.lookAt = *a.lookAt;
    if (a.up) cam.up = *a.up;
    if (a.cameraPos) cam.position = *a.cameraPos;
    else if (a.lookAt) cam.position = cam.lookAt + (Camera::framing(bounds, a.width, a.height, a.fov).position - bounds.centre());
    cam.validate();

    RenderSettings rs;
    rs.threads = a.threads;
    rs.background = displayToLinear(a.background);
    rs.colour = vec3(displayToLinear(vec4(a.colour, 1.0f)));
    rs.colormap = a.colormap;
    if (a.light) rs.lightCamera = *a.light;
    rs.colourCoherence = a.colourCoherence;
    rs.colourTolerance = a.colourTolerance;

    auto renderer = makeRenderer(a.rendererName);
    Frame frame;
    // With a baseline, the two renderers alternate so that a change in the machine's load hits
    // both alike; each reports its fastest render.
    std::unique_ptr<Renderer> baseline = a.baseline.empty() ? nullptr : makeRenderer(a.baseline);
    Frame baseFrame;
    double baseMs = std::numeric_limits<double>::infinity();
    RenderStats st = renderer->render(tree, cam, rs, frame);
    if (baseline) baseMs = baseline->render(tree, cam, rs, baseFrame).renderMs;
    std::vector<double> times{st.renderMs};
    for (int i = 1; i < a.repeat; ++i) {
        RenderStats again = renderer->render(tree, cam, rs, frame);
        times.push_back(again.renderMs);
        st.renderMs = std::min(st.renderMs, again.renderMs);
        if (baseline) baseMs = std::min(baseMs, baseline->render(tree, cam, rs, baseFrame).renderMs);
    }
    std::sort(times.begin(), times.end());
    if (st.hits == 0) log::warning("the surface is not in view: every pixel is background");
    io::writeImage(frame, a.output);

    StatsJson js;
    js.set("renderer", st.renderer);
    js.set("input", a.input);
    js.set("variable", field.name);
    js.set("units", field.units);
    js.set("iso", iso);
    js.set("depth", tree.depth);
    js.set("width", cam.width);
    js.set("height", cam.height);
    js.set("threads", threads);
    js.set("pixels", st.pixels);
    js.set("rays", st.rays);
    js.set("hits", st.hits);
    js.set("load_ms", loadMs);
    js.set("build_ms", report.buildMs);
    js.set("render_ms", st.renderMs);
    if (a.repeat > 1) {
        js.set("repeat", a.repeat);
        js.set("render_ms_median", times[times.size() / 2]);
    }
    if (baseline) {
        js.set("baseline", a.baseline);
        js.set("baseline_render_ms", baseMs);
        js.set("speedup_over_baseline", st.renderMs > 0 ? baseMs / st.renderMs : 0.0);
    }
    js.set("us_per_ray", st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0);
    js.set("rays_full", st.raysFull);
    js.set("rays_common_path", st.raysCommonPath);
    js.set("fallbacks", st.fallbacks);
    js.set("rays_certified", st.raysCertified);
    js.set("states_deferred", st.statesDeferred);
    js.set("colour_filled", st.colourFilled);
    if (rs.colourCoherence) js.set("colour_tolerance", double(rs.colourTolerance));
    js.set("nodes_visited", st.nodesVisited);
    js.set("nodes_per_ray", st.rays ? double(st.nodesVisited) / double(st.rays) : 0.0);
    js.set("boundary_voxels", std::uint64_t(tree.boundaryVoxels()));
    js.set("octree_nodes", std::uint64_t(tree.nodes.size()));
    js.set("octree_bytes", std::uint64_t(tree.bytes()));
    js.set("bytes_per_voxel", tree.bytesPerVoxel());
    js.set("peak_rss_bytes_after_build", std::uint64_t(rssAfterBuild));
    auto vec = [](const dvec3& v) {
        std::ostringstream o;
        o.precision(10);
        o << v.x << "," << v.y << "," << v.z;
        return o.str();
    };
    js.set("camera_pos", vec(cam.position));
    js.set("look_at", vec(cam.lookAt));
    js.set("up", vec(cam.up));
    js.set("fov", cam.fovYDegrees);
    js.set("cube_origin", vec(tree.cubeOrigin));
    js.set("cube_side", tree.cubeSide);
    js.set("surface_bounds_min", vec(bounds.lo));
    js.set("surface_bounds_max", vec(bounds.hi));
    for (const auto& n : field.notes) {
        if (n.rfind("vertical scale", 0) == 0 || n.find("vertical scale") != std::string::npos) js.set("geographic", n);
    }

    std::ostringstream summary;
    summary.precision(4);
    summary << a.output << ": " << cam.width << "x" << cam.height << ", " << st.renderer << ", " << st.renderMs << " ms ("
            << (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0) << " us/ray over " << st.rays << " rays), "
            << tree.boundaryVoxels() << " boundary voxels at depth " << tree.depth << " built in " << report.buildMs << " ms";

    if (a.verify) {
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
        summary << "; verify: " << mismatched << " pixels differ from the reference (" << qdiff
                << " from the unquantized rays)";
        if (mismatched != 0) log::warning(std::to_string(mismatched) + " pixels differ from the reference traversal");
    }
    log::info(summary.str());
    if (!a.statsPath.empty()) io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    return 0;
}

}  // namespace octrace::cli
