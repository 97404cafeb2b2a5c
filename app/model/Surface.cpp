#include "octrace/model/Surface.h"

#include "octrace/model/Figure.h"
#include "octrace/model/Input.h"
#include "octrace/model/Render.h"
#include "octrace/model/SolidSpec.h"

#include "octrace/build/CityVoxelizer.h"
#include "octrace/build/Layers.h"
#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/io/CityReader.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parameter.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>
#include <tuple>

namespace octrace::model {
namespace {

/// The value of `window`: a preset (its window), "none" (invalid window) or "C,W".
ValueWindow parseWindow(const std::string& v) {
    if (v == "none") return {};
    if (auto w = ctWindowPreset(v)) return *w;
    const std::size_t comma = v.find(',');
    if (comma == std::string::npos || v.find(',', comma + 1) != std::string::npos) {
        std::string names;
        for (const auto& w : ctWindowPresets()) names += std::string(w.name) + ", ";
        throw UsageError("`window`: give a preset (" + names + "none) or CENTRE,WIDTH, got '" + v + "'");
    }
    ValueWindow w{parseNumber(opt::window, v.substr(0, comma)), parseNumber(opt::window, v.substr(comma + 1))};
    if (!(w.width > 0.0)) throw UsageError("`window`: the width must be positive, got '" + v + "'");
    return w;
}

}  // namespace

std::pair<double, std::string> defaultIso(const ScalarField& field, const std::string& input) {
    const auto [lo, hi] = field.validRange();
    std::ostringstream why;
    if (input.rfind("analytic:", 0) == 0 || !(hi > lo)) {
        why << "the middle of the range [" << lo << ", " << hi << "] of '" << field.name << "'";
        return {0.5 * (double(lo) + double(hi)), why.str()};
    }
    // The valid samples between their 0.5th and 99.5th percentiles (from a fine histogram of the
    // whole range): the few beyond would pull an image volume's split towards themselves (one
    // bright outlier splits off alone), and an ocean field's middle to where no cell crosses it.
    const auto histogram = [&](double from, double to, std::vector<double>& count) {
        const double width = (to - from) / double(count.size());
        const int last = int(count.size()) - 1;
        for (std::size_t i = 0; i < field.values.size(); ++i) {
            const float v = field.values[i];
            if (!field.isValid(i) || !std::isfinite(v)) continue;
            count[std::size_t(std::clamp(int(std::floor((double(v) - from) / width)), 0, last))] += 1.0;
        }
        return width;
    };
    std::vector<double> fine(4096, 0.0);
    const double fineWidth = histogram(double(lo), double(hi), fine);
    double total = 0.0;
    for (double c : fine) total += c;
    std::size_t a = 0, b = fine.size() - 1;
    for (double seen = 0.0; a < fine.size() && seen + fine[a] < 0.005 * total; ++a) seen += fine[a];
    for (double seen = 0.0; b > a && seen + fine[b] < 0.005 * total; --b) seen += fine[b];
    const double from = double(lo) + double(a) * fineWidth, to = double(lo) + double(b + 1) * fineWidth;
    if (field.geographic.valid) {
        // An ocean field has no two classes to split: the middle of its range without the few
        // extreme samples (Levitus salinity: 33.7 rather than 22.7, which the 4.6 of a few
        // coastal samples put where no cell of the atlas crosses).
        const double middle = 0.5 * (from + to);
        why << "the middle of [" << from << ", " << to << "], the range of the valid samples of '" << field.name
            << "' between their 0.5th and 99.5th percentiles (all: [" << lo << ", " << hi << "])";
        return {middle, why.str()};
    }
    // Otsu (1979) over the samples between those percentiles, clamped to those ends.
    constexpr int kBins = 256;
    std::vector<double> count(kBins, 0.0);
    const double width = histogram(from, to, count);
    double sum = 0.0;
    for (int k = 0; k < kBins; ++k) sum += count[std::size_t(k)] * (k + 0.5);
    double below = 0.0, sumBelow = 0.0, best = -1.0;
    int split = kBins / 2;  // the bins below it are one class
    for (int k = 1; k < kBins; ++k) {
        below += count[std::size_t(k - 1)];
        sumBelow += count[std::size_t(k - 1)] * (k - 0.5);
        const double above = total - below;
        if (below <= 0.0 || above <= 0.0) continue;
        const double d = sumBelow / below - (sum - sumBelow) / above;
        const double between = below * above * d * d;
        if (between > best) best = between, split = k;
    }
    const double iso = from + split * width;
    why << "Otsu's threshold of the valid samples of '" << field.name << "' (range [" << lo << ", " << hi
        << "]: the value that best splits them in two)";
    return {iso, why.str()};
}

void requireHounsfield(const ScalarField& f, const std::string& input, const std::string& option) {
    if (f.units == "HU") return;
    throw InputError(input + ": " + option + " is a CT preset in Hounsfield units, but the values of '" + f.name + "' are " +
                     (f.units.empty() ? std::string("not in HU (no units: not a CT series)") : "in " + f.units) +
                     "; give a number instead");
}

namespace {

/// The surface's display window (see buildSurface).
void chooseWindow(const SurfaceSpec& a, Surface& s) {
    if (!a.colours) return;  // octrace build: no colours, no voxel values
    if (!a.windowName.empty()) {
        if (ctWindowPreset(a.windowName)) requireHounsfield(s.field, a.input, "`window` " + a.windowName);
        s.window = a.window;
        s.windowSource = "`window` " + a.windowName;
    } else if (!a.colourGiven && a.colormap.empty() && a.colourBy.empty() && s.field.window.valid() && !a.isoPreset.empty()) {
        // A CT preset has its tissue's colour (defaultLook): a file's window (often 40/400,
        // soft tissue) would grey a skin surface at -500 HU nearly black.
        log::info("`iso` " + a.isoPreset + ": coloured as " + a.isoPreset + " (`window` with a preset or the file's " +
                  numberText(s.field.window.centre) + "," + numberText(s.field.window.width) + " greys it instead)");
    } else if (!a.colourGiven && a.colormap.empty() && a.colourBy.empty() && s.field.window.valid()) {
        s.window = s.field.window;
        s.windowSource = "the file's display window";
        std::ostringstream m;
        m << "colouring by the file's display window, centre " << s.window.centre << " width " << s.window.width
          << " (`window` none for a uniform colour)";
        log::info(m.str());
    }
    s.invertedGrey = s.window.valid() && s.field.invertedGrey;
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }


/// buildSurface for an octree file: the octree as it is, the field empty but for its name.
void loadOctreeSurface(const SurfaceSpec& a, std::uint64_t budget, Surface& s) {
    const char* given = a.iso || !a.isoPreset.empty() ? "`iso`"
                        : !a.windowName.empty()         ? "`window`"
                        : a.depthGiven                  ? "`depth`"
                        : a.formGiven                   ? "`form`/`inside`"
                        : !a.colourBy.empty()           ? "`colour_by`"
                        : a.floor                       ? "`floor`"
                        : a.extendDown                  ? "`extend_down`"
                                                        : fieldOptionGiven(a.request);
    if (given)
        throw UsageError(std::string(given) + " does not apply to the octree file " + a.input +
                         " (its field, iso value and depth were fixed when it was built: see octrace info)");
    Timer t;
    s.tree = loadOctree(a.input, budget);
    s.loadMs = t.ms();
    if (!a.cuts.empty() && s.tree.form != OctreeForm::Volume)
        throw InputError(a.input + ": a shell octree cannot be cut (`cut` needs the volume form: build it with `form` volume)");
    s.iso = s.tree.iso;
    s.field.name = s.tree.fieldName();
    s.field.units = s.tree.fieldUnits();
    s.field.source = a.input;
}

/// The cuts (--cut, --clip), then the shell unless the command keeps the volume.
void finishSurface(const SurfaceSpec& a, Surface& s) {
    if (!a.cuts.empty()) {
        Timer t;
        for (const SolidArgument& arg : a.cuts) {
            const Solid cut = resolveSolid(arg, s.field.geographic, a.input, memoryBudget(a));
            s.tree = csg(CsgOperand::of(s.tree), a.clip ? CsgOp::Intersection : CsgOp::Difference, CsgOperand::of(cut));
        }
        // The cut faces were inside: their values (a display window's grey) are the field's there.
        if (!s.tree.voxelValues().empty() && !s.field.values.empty()) fillVoxelValues(s.tree, s.field, a.threads);
        log::debug("cuts applied in " + std::to_string(t.ms()) + " ms");
        s.report.buildMs += t.ms();
    }
    if (!a.keepVolume) s.tree = extractShell(s.tree);
    // render --bake --lighting dynamic: the light would be baked into an octree that is
    // neither shaded by it nor saved.
    const bool bakeUnused = a.bake && a.lighting == SurfaceSpec::Lighting::Dynamic;
    if (bakeUnused)
        log::warning("`bake` with `lighting` dynamic: nothing baked (dynamic shading does not use baked light; "
                     "leave out `lighting` dynamic to render with it)");
    if ((a.bake && !bakeUnused) || (a.lighting == SurfaceSpec::Lighting::Baked && s.tree.baked().empty())) {
        if (s.tree.form != OctreeForm::Shell) throw UsageError("`bake` applies to the shell form (not with `form` volume)");
        BakeOptions o = a.bakeOptions;
        o.threads = a.threads;
        if (a.ambient) {
            o.ambient = *a.ambient;
            o.diffuse = 1.0f - *a.ambient;
        }
        bakeLighting(s.tree, o, &s.bake);
        log::debug("lighting baked in " + std::to_string(s.bake.bakeMs) + " ms (" + std::to_string(s.bake.rays) + " rays)");
    }
    s.report.boundaryVoxels = countVoxels(s.tree).boundary;
    s.report.nodes = s.tree.nodes().size();
}

/// buildSurface for a city input: the model read and voxelized; the field empty but for its name.
void buildCitySurface(const SurfaceSpec& a, Surface& s) {
    const char* given = a.iso ? "`iso`" : a.formGiven ? "`form`/`inside`" : !a.cuts.empty() ? "`cut`" : a.extendDown ? "`extend_down`" : !a.isoPreset.empty() ? "`iso`"
                        : a.window.valid() ? "`window`" : fieldOptionGiven(a.request);
    if (given)
        throw UsageError(std::string(given) + " does not apply to the city input " + a.input +
                         " (its buildings and terrain are voxelized as surfaces)");
    if (a.depth && a.terrainDepth > *a.depth)
        throw UsageError("`terrain_depth` " + std::to_string(a.terrainDepth) + " is deeper than `depth` " + std::to_string(*a.depth) +
                         " (the terrain goes to the shallower depth, the buildings to `depth`)");
    Timer t;
    io::CityRequest request = a.city;
    // The octree resolves the terrain no finer than its depth (auto: not known before the model's box).
    request.maxSamples = (1 << std::min(a.terrainDepth > 0 ? a.terrainDepth : a.depth.value_or(12), 12)) + 1;
    const CityModel model = io::readCityModel(a.input, request);
    s.loadMs = t.ms();
    for (const auto& n : model.notes) log::warning(n);
    // The voxelizer's peak is its octree: about 4^depth boundary voxels over a box's faces, a
    // generous 64 bytes each with the colours and the node pool.
    s.depth = chooseGeometryDepth(a, model.bounds(), "m", [](int d) { return 64.0 * std::pow(4.0, d); });
    if (a.terrainDepth > s.depth.depth)
        throw UsageError("`terrain_depth` " + std::to_string(a.terrainDepth) + " is deeper than `depth` auto " +
                         std::to_string(s.depth.depth) + " (give `depth` as a number)");
    CityBuildOptions o;
    o.depth = s.depth.depth;
    o.threads = a.threads;
    o.terrainDepth = a.terrainDepth;
    s.tree = voxelizeCity(model, o, &s.report);
    s.field.name = s.tree.fieldName();
    s.field.source = a.input;
    s.tree.setMetadata(octree_key::kSource, a.input + " (" + std::to_string(model.objects.size()) + " objects, " +
                                                std::to_string(model.triangles.size()) + " triangles, CRS " +
                                                (model.crs.empty() ? std::string("none") : model.crs) + ")");
}

/// What an octree was made from, for its file's header: input, variable, the reader's notes.
std::string sourceDescription(const std::string& input, const ScalarField& f) {
    std::string s = input + ", variable " + f.name;
    for (const auto& n : f.notes) s += "; " + n;
    return s;
}

/// --colour-by: the second variable, read with the same request (region, depth range, time)
/// and checked to lie on the field's grid.
ScalarField loadColourBy(const SurfaceSpec& a, const io::FieldRequest& request, const ScalarField& field) {
    io::FieldRequest second = request;
    second.variable = a.colourBy;
    ScalarField by = loadField(a.input, second, readDepth(a));
    if (by.dims != field.dims || by.origin != field.origin || by.spacing != field.spacing || by.coords != field.coords ||
        by.direction != field.direction)
        throw InputError(a.input + ": `colour_by` " + a.colourBy + " is not on the grid of '" + field.name +
                         "' (both variables must share their coordinates)");
    return by;
}

}  // namespace

ValueWindow displayWindow(const std::string& text) { return parseWindow(text); }


vec4 displayToLinear(vec4 c) { return vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a); }

const char* fieldOptionGiven(const io::FieldRequest& request) {
    const io::FieldRequest none;
    return !request.variable.empty()                    ? "`var`"
           : request.hasRegion                          ? "`region`"
           : request.hasDepthRange                      ? "`depth_range`"
           : !request.time.empty()                      ? "`time`"
           : !request.series.empty()                    ? "`series`"
           : request.verticalScale != none.verticalScale ? "`vertical_scale`"
                                                         : nullptr;
}

std::uint64_t memoryBudget(const SurfaceSpec& a) { return a.maxMemory ? a.maxMemory : defaultMemoryBudget(); }

Surface buildSurface(const SurfaceSpec& a, const BuildHooks& hooks) {
    if (a.insideBelow && a.form != OctreeForm::Volume && a.cuts.empty())
        throw UsageError("`inside` applies to `form` volume (or `cut`)");
    if (a.clip && a.cuts.empty()) throw UsageError("`clip` needs a `cut` solid");
    const std::uint64_t budget = memoryBudget(a);
    if (a.window.valid() && (a.colourGiven || !a.colormap.empty()))
        throw UsageError("`window` " + a.windowName + " and " + (a.colourGiven ? "`colour`" : "`colormap`") +
                         " both colour the surface: give one");
    Surface s;
    if (isOctreeInput(a.input)) {
        if (a.cityGiven) throw UsageError("`lod_select`, `crs`, `dem`, `texture`, `height_attr`, `base_attr` and `terrain_depth` apply to city inputs, not to the octree file " + a.input);
        loadOctreeSurface(a, budget, s);
        finishSurface(a, s);
        return s;
    }
    if (io::isCityInput(a.input)) {
        buildCitySurface(a, s);
        return s;
    }
    if (a.cityGiven) throw UsageError("`lod_select`, `crs`, `dem`, `texture`, `height_attr`, `base_attr` and `terrain_depth` apply to city inputs (CityJSON, CityGML, footprints, DEM rasters), not to " + a.input);
    readSurfaceField(a, s, hooks);
    buildFromField(a, s, hooks);
    return s;
}

void readSurfaceField(const SurfaceSpec& a, Surface& s, const BuildHooks& hooks) {
    io::FieldRequest request = a.request;
    request.memoryBudget = memoryBudget(a);
    request.hooks = hooks.forRead();
    Timer t;
    if (isSphereInput(a.input) && !a.depth) {
        // Auto: the spheres' box gives the depth, which gives the distance field's samples.
        auto set = std::make_shared<const SphereSet>(loadSpheres(a.input, request.memoryBudget));
        // The distance field (2^d + 5 samples a side) and the builder's copy and pyramid of it:
        // about 10 bytes a sample.
        s.depth = chooseGeometryDepth(a, set->bounds(), set->units,
                                      [](int d) { return 10.0 * std::pow(std::ldexp(1.0, d) + 5.0, 3.0); });
        s.field = sphereField(a.input, std::move(set), request, s.depth.depth, &s.spheres);
    } else {
        s.field = loadField(a.input, request, readDepth(a), &s.spheres);
    }
    s.loadMs = t.ms();
}

int readDepth(const SurfaceSpec& a) { return a.depth.value_or(int(opt::depth.defaultValue)); }

namespace {

void sayAutoDepth(const DepthChoice& c, const std::string& cap) {
    log::info("`depth` auto: " + std::to_string(c.depth) + ", " + c.reason + cap + " (give `depth` N for another)");
}

}  // namespace

DepthChoice chooseDepth(const SurfaceSpec& a, const ScalarField& field, double iso) {
    if (a.depth) return {*a.depth, "given"};
    DepthChoice c = depthForField(field);
    const std::uint64_t budget = memoryBudget(a);
    const std::vector<BuildMemoryEstimate> est = estimateBuildMemory(field, iso, c.depth, a.threads);
    std::string cap;
    int d = c.depth;
    while (d > 1 && est[std::size_t(d - 1)].total() > budget) --d;
    if (d < c.depth) {
        cap = "; capped at " + std::to_string(d) + " by `max_memory` " + formatBytes(budget) + " (depth " +
              std::to_string(c.depth) + " would need about " + formatBytes(est[std::size_t(c.depth - 1)].total()) + ")";
        c.reason += cap;
        c.depth = d;
    }
    sayAutoDepth(c, "");
    return c;
}

DepthChoice viewDepth(const Box3& bounds, int width, int height, double fov, const std::string& unit) {
    const dvec3 e = bounds.size();
    const double side = std::max({e.x, e.y, e.z});
    if (!(side > 0.0) || !std::isfinite(side)) return {int(opt::depth.defaultValue), "the box has no extent"};
    RenderSpec defaultView;
    defaultView.width = width;
    defaultView.height = height;
    defaultView.fov = fov;
    DepthChoice c = depthForPixel(side, frameCamera(defaultView, bounds).pixelFootprint(), unit);
    c.reason += " at " + std::to_string(width) + "x" + std::to_string(height);
    return c;
}

DepthChoice chooseGeometryDepth(const SurfaceSpec& a, const Box3& bounds, const std::string& unit,
                                const std::function<double(int)>& bytesAtDepth) {
    if (a.depth) return {*a.depth, "given"};
    DepthChoice c = viewDepth(bounds, a.viewWidth, a.viewHeight, a.viewFov, unit);
    const std::uint64_t budget = memoryBudget(a);
    int d = c.depth;
    while (d > 1 && bytesAtDepth(d) > double(budget)) --d;
    if (d < c.depth) {
        c.reason += "; capped at " + std::to_string(d) + " by `max_memory` " + formatBytes(budget) + " (depth " +
                    std::to_string(c.depth) + " would need about " + formatBytes(std::uint64_t(bytesAtDepth(c.depth))) + ")";
        c.depth = d;
    }
    sayAutoDepth(c, "");
    return c;
}

void buildFromField(const SurfaceSpec& a, Surface& s, const BuildHooks& hooks) {
    io::FieldRequest request = a.request;
    request.memoryBudget = memoryBudget(a);
    if (a.extendDown) {
        if (!s.field.geographic.valid)
            throw InputError(a.input + ": `extend_down` applies to geographic fields (longitude, latitude, depth)");
        log::info("`extend_down`: " + std::to_string(extendColumnsDown(s.field)) + " masked samples under the water filled");
    }
    (void)s.field.validRange();  // throws for a field with no valid sample
    if (!a.isoPreset.empty()) requireHounsfield(s.field, a.input, "`iso` " + a.isoPreset);
    // A sphere input's field is the signed distance to its spheres: their surface is at 0.
    const bool sphereDistance = isSphereInput(a.input);
    // Chosen once (a histogram of the whole field): its value here, its reason in the log below.
    const bool chosen = !a.iso && a.isoPreset.empty() && !sphereDistance;
    const std::pair<double, std::string> byDefault = chosen ? defaultIso(s.field, a.input) : std::pair<double, std::string>{};
    s.iso = !a.isoPreset.empty() ? *ctIsoPreset(a.isoPreset)
            : a.iso                ? quantityIn({*a.iso, a.isoUnit, numberText(*a.iso) + a.isoUnit}, s.field.units, "`iso`",
                                                a.input + ": variable '" + s.field.name + "'")
            : sphereDistance       ? 0.0
                                   : byDefault.first;
    if (a.iso && !a.isoUnit.empty()) {
        std::ostringstream m;
        m << "`iso` " << numberText(*a.iso) << a.isoUnit << " is " << numberText(s.iso, 9) << " " << s.field.units
          << ", the units of '" << s.field.name << "' (UDUNITS-2)";
        log::info(m.str());
    }
    if (chosen) {
        std::ostringstream m;
        m << "no `iso` given: using " << s.iso << ", " << byDefault.second;
        log::info(m.str());
    }
    for (const auto& n : s.field.notes) log::debug(n);
    if (!a.colourBy.empty() && !a.windowName.empty())
        throw UsageError("`window` and `colour_by` both colour the surface: give one of them");
    std::optional<ScalarField> colourBy;
    if (!a.colourBy.empty()) {
        colourBy = loadColourBy(a, request, s.field);
        if (a.extendDown) extendColumnsDown(*colourBy);
    }

    // A sphere input's depth was chosen with its distance field (readSurfaceField).
    if (!s.spheres || a.depth || s.depth.depth == 0) s.depth = chooseDepth(a, s.field, s.iso);
    BuildOptions bo;
    bo.depth = s.depth.depth;
    bo.iso = s.iso;
    bo.threads = a.threads;
    bo.progress = hooks.progress;
    bo.cancelled = hooks.cancelled;
    bo.memoryBudget = request.memoryBudget;
    bo.form = a.cuts.empty() ? a.form : OctreeForm::Volume;
    bo.insideBelow = a.insideBelow;
    chooseWindow(a, s);
    bo.voxelValues = s.window.valid();
    // Smooth surfaces need the corner values; a molecule's distance field keeps its voxels (its
    // spheres are the geometry, docs/dev/smooth-surfaces.md).
    bo.corners = a.surface.value_or(SurfaceMode::Smooth) == SurfaceMode::Smooth && !s.spheres;
    s.tree = buildOctree(s.field, bo, &s.report);
    s.tree.setMetadata(octree_key::kSource, sourceDescription(a.input, s.field));
    finishSurface(a, s);
    // A molecule's voxels keep their atoms' colours, as a city's keep their buildings'.
    if (s.spheres) {
        Timer t;
        s.tree.setColours(sphereColoursAtVoxels(s.tree, *s.spheres, a.threads));
        log::debug("voxels coloured by their nearest spheres in " + std::to_string(t.ms()) + " ms");
    }
    if (colourBy) {
        s.tree.setVoxelValues(sampleAtVoxels(s.tree, *colourBy, a.threads));
        s.tree.setMetadata(octree_key::kValueName, colourBy->name);
        s.tree.setMetadata(octree_key::kValueUnits, colourBy->units);
        s.tree.setMetadata(octree_key::kValueStandardName, colourBy->standardName);
    }
    if (a.floor) {
        BuildOptions fo = bo;
        fo.iso = 0.5;
        fo.progress = {};
        fo.form = OctreeForm::Shell;
        fo.voxelValues = false;
        Octree floor = buildShellOctree(solidFromMask(s.field), fo);
        setMaterial(floor, VoxelMaterial::Floor);
        s.tree = mergeShells(s.tree, floor);
        s.report.boundaryVoxels = s.tree.voxels().size();
        s.report.nodes = s.tree.nodes().size();
    }
}

namespace {

/// The look of a surface that no colour setting colours (`colour`, `colormap`, `colour_by`, a
/// display window, its own per-voxel colours): a CT preset's tissue colour, skin for another
/// patient volume, else the colour map by height.
void applyDefaultLook(const SurfaceSpec& a, const Surface& s, RenderSettings& settings) {
    if (a.colourGiven || !a.colormap.empty() || !a.colourBy.empty() || s.window.valid() || !s.tree.colours().empty() ||
        !s.tree.voxelValues().empty())
        return;
    if (const CtIsoPreset* p = findCtIsoPreset(a.isoPreset)) {
        settings.colour = vec3(displayToLinear(vec4(p->colour, 1.0f)));
    } else if (s.field.patientLps) {
        settings.colour = vec3(displayToLinear(vec4(findCtIsoPreset("skin")->colour, 1.0f)));
    } else {
        settings.colormap = kHeightColormap;
    }
}

}  // namespace

void applyColour(const SurfaceSpec& a, const Surface& s, RenderSettings& settings) {
    settings.colour = vec3(displayToLinear(vec4(a.colour, 1.0f)));
    settings.colormap = a.colormap;
    applyDefaultLook(a, s, settings);
    settings.voxelColours = !a.colourGiven;
    settings.window = s.window;
    settings.invertedGrey = s.invertedGrey;
    if (settings.colormap.empty() && !s.tree.voxelValues().empty() && !s.window.valid())
        settings.colormap = defaultColormap(s.tree.valueStandardName(), s.tree.valueName());
    settings.colourMin = a.colourMin;
    settings.colourMax = a.colourMax;
    const bool byHeight = !settings.colormap.empty() && s.tree.voxelValues().empty();
    const bool values = !s.tree.voxelValues().empty();
    if (!std::isnan(a.colourMin) && (values || byHeight) && (!a.colourMinGiven.unit.empty() || !a.colourMaxGiven.unit.empty())) {
        // The units of what is coloured: colour_by's variable (or the window's field), else heights
        // in metres on a geographic grid.
        const std::string units = values ? (s.tree.valueName().empty() ? s.field.units : s.tree.valueUnits())
                                  : byHeight && s.field.geographic.valid ? std::string("m") : std::string();
        const std::string subject = values ? a.input + ": variable '" + (s.tree.valueName().empty() ? s.field.name : s.tree.valueName()) + "'"
                                  : s.field.geographic.valid ? a.input + ": the surface's heights (coloured by height, in metres above the sea surface)"
                                                             : a.input + ": the surface's heights (coloured by height, in world z)";
        std::tie(settings.colourMin, settings.colourMax) =
            colourRangeIn(a.colourMinGiven, a.colourMaxGiven, units, subject);
    }
    if (byHeight && !std::isnan(a.colourMin)) {
        // Coloured by height: `colour_range` is in the figure's units (metres above the sea
        // surface on a geographic field, else world z); the renderers take world z.
        const auto worldZ = [&](float height) {
            return s.field.geographic.valid ? float(GeoAxes{s.field.geographic}.z(-double(height))) : height;
        };
        settings.colourMin = worldZ(settings.colourMin);
        settings.colourMax = worldZ(settings.colourMax);
    }
    settings.maskedColour = vec3(displayToLinear(vec4(a.maskedColour, 1.0f)));
    settings.floorColour = vec3(displayToLinear(vec4(a.floorColour, 1.0f)));
}

std::pair<float, float> colourRangeIn(const Quantity& min, const Quantity& max, const std::string& units,
                                      const std::string& subject) {
    const double lo = quantityIn(min, units, "`colour_range`", subject), hi = quantityIn(max, units, "`colour_range`", subject);
    const std::string given = "`colour_range` " + min.text + "," + max.text;
    std::ostringstream m;
    m << given << " is " << numberText(lo, 9) << "," << numberText(hi, 9) << " " << units;
    if (!(lo < hi) || std::abs(lo) > 3e38 || std::abs(hi) > 3e38)
        throw InputError(subject + ": " + m.str() + ", not an increasing range (give MIN below MAX)");
    if (!min.unit.empty() || !max.unit.empty()) log::debug(m.str() + " (UDUNITS-2)");
    return {float(lo), float(hi)};
}

void applyLighting(const SurfaceSpec& a, RenderSettings& settings) {
    settings.baked = a.lighting != SurfaceSpec::Lighting::Dynamic;
    settings.shadows = a.shadows;
    if (a.ambient) {
        settings.ambient = *a.ambient;
        settings.diffuse = 1.0f - *a.ambient;
    }
}

}  // namespace octrace::model
