#include "octrace/model/Render.h"

#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Parameter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace octrace::model {

CoherenceSettings tableCoherence() {
    CoherenceSettings c;
    c.colourTolerance = float(opt::colourTolerance.defaultValue);
    c.branchUp = int(opt::branchUp.defaultValue);
    c.miss = opt::missCoherence.defaultChoice() == "on";
    return c;
}

SphereShading tableSphereShading() {
    SphereShading s;
    s.samples = int(opt::samples.defaultValue);
    s.bounces = int(opt::bounces.defaultValue);
    return s;
}

bool checkRenderSpec(const SurfaceSpec& surface, const RenderSpec& spec, const std::string& baseline) {
    if (spec.orthoHeight && !spec.ortho) throw UsageError(param(opt::orthoHeight.key) + " needs " + param(opt::projection.key) + " ortho");
    if (surface.depth && spec.detail.level > *surface.depth)
        throw UsageError(param(opt::level.key) + " " + std::to_string(spec.detail.level) + " is deeper than " + param(opt::depth.key) +
                         " " + std::to_string(*surface.depth));
    // `depth` auto: a `level` is taken as a cut (the renderer draws a level at or below the
    // octree's depth as its voxels).
    const bool multires = spec.detail.lodPixels > 0.0 || (spec.detail.level >= 0 && spec.detail.level < surface.depth.value_or(Octree::kMaxDepth));
    const RendererName chosen = resolveRendererName(spec.renderer);
    if (spec.coherence.colour && !makeRenderer(chosen.renderer)->colourCoherence())
        throw UsageError(param(opt::colourCoherence.key) + ": renderer " + spec.renderer + " does not fill pixels by colour (use " +
                         voxelRenderersThat(&Renderer::colourCoherence) + ")");
    if (multires)
        for (const std::string& name : {spec.renderer, baseline})
            if (!name.empty() && !makeRenderer(resolveRendererName(name).renderer)->multiResolution())
                throw UsageError(param(opt::lod.key) + "/" + param(opt::level.key) + ": renderer " + name +
                                 " has no multi-resolution mode (use " + voxelRenderersThat(&Renderer::multiResolution) + ")");
    return multires;
}

SceneView sceneView(const ScalarField& field) {
    if (field.geographic.valid) return SceneView::NorthUp;
    if (!field.patientLps) return SceneView::Oblique;
    if (field.sampleCount() == 0) return SceneView::Anterior;
    const dvec3 e = field.worldBounds().size();
    return e.x < 0.25 * std::max({e.x, e.y, e.z}) ? SceneView::Lateral : SceneView::Anterior;
}

dvec3 viewDirection(SceneView view) {
    switch (view) {
    case SceneView::NorthUp: return {0.0, -std::cos(glm::radians(35.0)), std::sin(glm::radians(35.0))};
    case SceneView::Anterior: return {0.0, -1.0, 0.0};  // LPS: anterior is -y
    case SceneView::Lateral: return {1.0, 0.0, 0.0};    // the patient's left is +x
    case SceneView::Oblique: break;
    }
    return Camera::obliqueDirection();
}

Camera frameCamera(const RenderSpec& spec, const Box3& bounds, SceneView view) {
    const Camera framed = Camera::fit(bounds, spec.width, spec.height, spec.fov, viewDirection(view), dvec3(0.0, 0.0, 1.0));
    Camera cam = framed;
    if (spec.lookAt) cam.lookAt = *spec.lookAt;
    if (spec.up) cam.up = *spec.up;
    if (spec.cameraPos) cam.position = *spec.cameraPos;
    else if (spec.lookAt) cam.position = cam.lookAt + (framed.position - framed.lookAt);
    if (spec.ortho) {
        cam.validate();
        cam.frameOrthographic(bounds);
        if (spec.cameraPos) cam.position = *spec.cameraPos;  // the user's view plane, even if it cuts the surface
        if (spec.orthoHeight) cam.orthoHeight = *spec.orthoHeight;
    }
    cam.validate();
    return cam;
}

vec4 contrastingBackground(const Octree& tree, const RenderSettings& settings) {
    const vec4 white(1.0f), slate = displayToLinear(vec4(0.32f, 0.34f, 0.43f, 1.0f));
    if (tree.voxels().empty()) return white;
    const Albedo albedo(tree, settings);
    const auto luminance = [](vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    // The surface's mean luminance, over every entry of voxels().
    double sum = 0.0;
    const std::size_t n = tree.voxels().size();
    if (!albedo.byHeight()) {
        // The colour is the voxel's own (material, value, colour or one colour): no cells needed.
        for (std::size_t v = 0; v < n; ++v) sum += luminance(albedo.at(std::uint32_t(v), 0.0f));
    } else if (tree.voxelMaterials().empty()) {
        // By height alone: the voxels counted per cell layer, each layer's colour looked up once.
        std::vector<std::uint64_t> layer(std::size_t(1) << tree.depth, 0);
        tree.forEachVoxel([&](const ivec3& cell, std::uint32_t) { ++layer[std::size_t(cell.z)]; });
        for (std::size_t z = 0; z < layer.size(); ++z)
            if (layer[z]) sum += double(layer[z]) * luminance(albedo.at(0, float(z) + 0.5f));
    } else {
        tree.forEachVoxel([&](const ivec3& cell, std::uint32_t v) { sum += luminance(albedo.at(v, float(cell.z) + 0.5f)); });
    }
    const double y = n ? sum / double(n) : 1.0;
    const double yWhite = 1.0, ySlate = luminance(vec3(slate));
    const auto contrast = [](double a, double b) { return (std::max(a, b) + 0.05) / (std::min(a, b) + 0.05); };
    return contrast(y, yWhite) >= contrast(y, ySlate) ? white : slate;
}

bool sameColouring(const RenderSettings& a, const RenderSettings& b) {
    const auto same = [](float x, float y) { return x == y || (std::isnan(x) && std::isnan(y)); };
    return a.colour == b.colour && a.colormap == b.colormap && same(a.colourMin, b.colourMin) &&
           same(a.colourMax, b.colourMax) && a.maskedColour == b.maskedColour && a.floorColour == b.floorColour &&
           a.voxelColours == b.voxelColours && a.window.centre == b.window.centre && a.window.width == b.window.width &&
           a.invertedGrey == b.invertedGrey;
}

RenderSettings renderSettings(const SurfaceSpec& surfaceSpec, const Surface& surface, const RenderSpec& spec,
                              const BackgroundSource& background) {
    RenderSettings rs;
    rs.threads = surfaceSpec.threads;
    applyColour(surfaceSpec, surface, rs);
    rs.background = spec.background ? displayToLinear(*spec.background)
                                    : (background ? background(surface.tree, rs) : contrastingBackground(surface.tree, rs));
    if (spec.light) rs.lightCamera = *spec.light;
    applyLighting(surfaceSpec, rs);
    rs.coherence = spec.coherence;
    rs.detail = spec.detail;
    rs.tileSize = spec.tileSize;
    rs.spheres = spec.spheres;
    rs.surface = surfaceModeFor(surfaceSpec.surface, spec.renderer);
    return rs;
}

SurfaceMode surfaceModeFor(const std::optional<SurfaceMode>& given, const std::string& renderer) {
    if (given) return *given;
    return makeRenderer(resolveRendererName(renderer).renderer)->paperRenderer() ? SurfaceMode::Voxel : SurfaceMode::Smooth;
}

RenderStats renderFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                        const std::string& renderer, Frame& frame) {
    const RendererName name = resolveRendererName(renderer);
    const std::unique_ptr<Renderer> r = makeRenderer(name.renderer);
    if (!r->drawsVoxels()) throw UsageError("renderer " + renderer + " does not draw voxel octrees");
    RenderSettings s = settings;
    name.applyTo(s);
    return renderAntialiased(*r, tree, camera, s, frame);
}

std::string vectorText(const dvec3& v) {
    std::ostringstream o;
    o.precision(10);
    o << v.x << "," << v.y << "," << v.z;
    return o.str();
}

void addCameraStats(Stats& js, const Camera& cam, const Box3& bounds) {
    js.set("camera_pos", vectorText(cam.position));
    js.set("look_at", vectorText(cam.lookAt));
    js.set("up", vectorText(cam.up));
    js.set("projection", std::string(cam.orthographic() ? "ortho" : "perspective"));
    if (cam.orthographic()) js.set("ortho_height", cam.orthoHeight);
    else js.set("fov", cam.fovYDegrees);
    js.set("surface_bounds_min", vectorText(bounds.lo));
    js.set("surface_bounds_max", vectorText(bounds.hi));
}

void addRepeatStats(Stats& js, const FrameRecord& r) {
    if (r.repeat > 1) {
        js.set("repeat", r.repeat);
        js.set("render_ms_median", r.renderMsMedian);
    }
    if (!r.baseline.empty()) {
        js.set("baseline", r.baseline);
        js.set("baseline_render_ms", r.baselineMs);
        js.set("speedup_over_baseline", r.stats->renderMs > 0 ? r.baselineMs / r.stats->renderMs : 0.0);
        js.set("baseline_differing_pixels", r.baselineDifferingPixels);
    }
}

FrameRecord frameRecord(const std::string& input, const Surface& surface, const Camera& camera, const RenderSettings& settings,
                        const RenderStats& stats, const std::string& renderer, const Box3& bounds) {
    const RendererName resolved = resolveRendererName(renderer);
    FrameRecord r;
    r.input = input;
    r.surface = &surface;
    r.camera = &camera;
    r.settings = &settings;
    r.stats = &stats;
    r.tracesRays = makeRenderer(resolved.renderer)->tracesRays();
    r.colourCoherence = settings.coherence.colour || resolved.colourCoherence;
    r.threads = settings.threads == 0 ? hardwareThreads() : settings.threads;
    r.bounds = bounds;
    return r;
}

Stats frameStats(const FrameRecord& r) {
    const Surface& surface = *r.surface;
    const ScalarField& field = surface.field;
    const Octree& tree = surface.tree;
    const Camera& cam = *r.camera;
    const RenderSettings& rs = *r.settings;
    const RenderStats& st = *r.stats;
    Stats js;
    js.set("renderer", st.renderer);
    js.set("input", r.input);
    js.set("variable", field.name);
    js.set("units", field.units);
    js.set("iso", surface.iso);
    if (surface.window.valid()) {
        js.set("window_centre", surface.window.centre);
        js.set("window_width", surface.window.width);
        js.set("window_source", surface.windowSource);
        js.set("window_inverted", surface.invertedGrey);
    }
    js.set("depth", tree.depth);
    js.set("width", cam.width);
    js.set("height", cam.height);
    if (r.figure) {
        const io::FigureLayout& l = *r.figure;
        js.set("figure_width", l.width);
        js.set("figure_height", l.height);
        js.set("figure_dpi", l.dpi);
        js.set("figure_plot", std::to_string(l.plotX) + "," + std::to_string(l.plotY) + "," + std::to_string(l.plotW) + "," + std::to_string(l.plotH));
        if (l.barW > 0)
            js.set("figure_colour_bar", std::to_string(l.barX) + "," + std::to_string(l.barY) + "," + std::to_string(l.barW) + "," + std::to_string(l.barH));
    }
    js.set("threads", r.threads);
    js.set("pixels", st.pixels);
    js.set("rays", st.rays);
    js.set("hits", st.hits);
    js.set("load_ms", surface.loadMs);
    js.set("build_ms", surface.report.buildMs);
    js.set("lighting", std::string(rs.baked && !tree.baked().empty() ? "baked" : "dynamic"));
    js.set("shadows", std::string(Shader(tree, cam, rs).shadows() ? "on" : "off"));
    js.set("shadow_rays", st.secondaryRays);
    js.set("bake_ms", surface.bake.bakeMs);
    js.set("render_ms", st.renderMs);
    addRepeatStats(js, r);
    // A direct renderer traces no rays: no figure per ray (null), its footprints instead.
    js.set("us_per_ray", r.tracesRays ? (st.rays ? st.renderMs * 1000.0 / double(st.rays) : 0.0)
                                      : std::numeric_limits<double>::quiet_NaN());
    js.set("voxels_splatted", st.voxelsSplatted);
    js.set("rays_full", st.raysFull);
    js.set("rays_common_path", st.raysCommonPath);
    js.set("fallbacks", st.fallbacks);
    js.set("rays_certified", st.raysCertified);
    js.set("states_deferred", st.statesDeferred);
    js.set("colour_filled", st.colourFilled);
    js.set("miss_filled", st.missFilled);
    if (r.colourCoherence) js.set("colour_tolerance", double(rs.coherence.colourTolerance));
    js.set("branch_up", rs.coherence.branchUp);
    if (st.renderer == "tile") js.set("tile_size", rs.tileSize);
    js.set("miss_coherence", std::string(rs.coherence.miss ? "on" : "off"));
    js.set("nodes_visited", st.nodesVisited);
    js.set("nodes_per_ray", st.rays ? double(st.nodesVisited) / double(st.rays) : 0.0);
    js.set("beams", st.beams);
    js.set("intersections", st.intersections);
    js.set("boundary_voxels", std::uint64_t(tree.boundaryVoxels()));
    if (!tree.voxelMaterials().empty())
        js.set("floor_voxels", std::uint64_t(std::count(tree.voxelMaterials().begin(), tree.voxelMaterials().end(),
                                                        std::uint8_t(VoxelMaterial::Floor))));
    if (!rs.colormap.empty()) js.set("colormap", rs.colormap);
    if (!tree.voxelValues().empty()) {
        const Albedo albedo(tree, rs);
        js.set("colour_by", tree.valueName());
        js.set("colour_units", tree.valueUnits());
        js.set("colour_min", double(albedo.low()));
        js.set("colour_max", double(albedo.high()));
    }
    js.set("octree_nodes", std::uint64_t(tree.nodes().size()));
    js.set("octree_bytes", std::uint64_t(tree.bytes()));
    js.set("bytes_per_voxel", tree.bytesPerVoxel());
    // What was drawn (smooth only where the octree has corner values) and what it costs.
    js.set("surface", std::string(rs.surface == SurfaceMode::Smooth && !tree.corners().empty() ? "smooth" : "voxel"));
    js.set("corner_bytes_per_voxel", tree.corners().empty() ? 0.0 : double(sizeof(std::uint64_t)));
    js.set("peak_rss_bytes_after_build", r.peakRssAfterBuild);
    addCameraStats(js, cam, r.bounds);
    if (r.multiResolution) {
        js.set("lod", rs.detail.lodPixels);
        js.set("level", std::uint64_t(rs.detail.level < 0 ? tree.depth : rs.detail.level));
    }
    js.set("cube_origin", vectorText(tree.cubeOrigin));
    js.set("cube_side", tree.cubeSide);
    for (const auto& n : field.notes) {
        if (n.rfind("vertical scale", 0) == 0 || n.find("vertical scale") != std::string::npos) js.set("geographic", n);
    }
    return js;
}

}  // namespace octrace::model
