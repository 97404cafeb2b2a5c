#include "SurfaceOptions.h"

#include "Input.h"
#include "SolidSpec.h"

#include "octrace/build/Layers.h"
#include "octrace/build/CityVoxelizer.h"
#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Timer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>

namespace octrace::cli {
namespace {

std::string huText(double hu) {
    std::ostringstream s;
    s << hu;
    return s.str();
}

/// --window's value: a preset (its window), "none" (invalid window) or "C,W".
ValueWindow parseWindow(const std::string& v) {
    if (v == "none") return {};
    if (auto w = ctWindowPreset(v)) return *w;
    const std::size_t comma = v.find(',');
    if (comma == std::string::npos || v.find(',', comma + 1) != std::string::npos) {
        std::string names;
        for (const auto& w : ctWindowPresets()) names += std::string(w.name) + ", ";
        throw UsageError("--window: give a preset (" + names + "none) or CENTRE,WIDTH, got '" + v + "'");
    }
    ValueWindow w{parseNumber("window", v.substr(0, comma)), parseNumber("window", v.substr(comma + 1))};
    if (!(w.width > 0.0)) throw UsageError("--window: the width must be positive, got '" + v + "'");
    return w;
}

}  // namespace

void requireHounsfield(const ScalarField& f, const std::string& input, const std::string& option) {
    if (f.units == "HU") return;
    throw InputError(input + ": " + option + " is a CT preset in Hounsfield units, but the values of '" + f.name + "' are " +
                     (f.units.empty() ? std::string("not in HU (no units: not a CT series)") : "in " + f.units) +
                     "; give a number instead");
}

namespace {

/// The surface's display window (see buildSurface).
void chooseWindow(const SurfaceArgs& a, Surface& s) {
    if (!a.colours) return;  // octrace build: no colours, no voxel values
    if (!a.windowName.empty()) {
        if (ctWindowPreset(a.windowName)) requireHounsfield(s.field, a.input, "--window " + a.windowName);
        s.window = a.window;
        s.windowSource = "--window " + a.windowName;
    } else if (!a.colourGiven && a.colormap.empty() && a.colourBy.empty() && s.field.window.valid()) {
        s.window = s.field.window;
        s.windowSource = "the file's display window";
        std::ostringstream m;
        m << "colouring by the file's display window, centre " << s.window.centre << " width " << s.window.width
          << " (--window none for a uniform colour)";
        log::info(m.str());
    }
    s.invertedGrey = s.window.valid() && s.field.invertedGrey;
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

/// Progress on stderr while building, only when stderr is a terminal.
std::function<void(double)> progressPrinter(bool quiet) {
    if (quiet || !isatty(2)) return {};
    return [](double f) { std::fprintf(stderr, "\roctrace: building octree %3d%%", int(f * 100.0 + 0.5)); };
}

/// buildSurface for an octree file: the octree as it is, the field empty but for its name.
void loadOctreeSurface(const SurfaceArgs& a, std::uint64_t budget, Surface& s) {
    const char* given = a.iso || !a.isoPreset.empty() ? "--iso"
                        : !a.windowName.empty()         ? "--window"
                        : a.depthGiven                  ? "--depth"
                        : a.formGiven                   ? "--form/--inside"
                        : !a.colourBy.empty()           ? "--colour-by"
                        : a.floor                       ? "--floor"
                        : a.extendDown                  ? "--extend-down"
                                                        : fieldOptionGiven(a.request);
    if (given)
        throw UsageError(std::string(given) + " does not apply to the octree file " + a.input +
                         " (its field, iso value and depth were fixed when it was built: see octrace info)");
    Timer t;
    s.tree = loadOctree(a.input, budget);
    s.loadMs = t.ms();
    if (!a.cuts.empty() && s.tree.form != OctreeForm::Volume)
        throw InputError(a.input + ": a shell octree cannot be cut (--cut needs the volume form: octrace build --form volume)");
    s.iso = s.tree.iso;
    s.field.name = s.tree.fieldName;
    s.field.units = s.tree.fieldUnits;
    s.field.source = a.input;
}

/// The cuts (--cut, --clip), then the shell unless the command keeps the volume.
void finishSurface(const SurfaceArgs& a, Surface& s) {
    if (!a.cuts.empty()) {
        Timer t;
        for (const SolidArgument& arg : a.cuts) {
            const Solid cut = resolveSolid(arg, s.field.geographic, a.input, memoryBudget(a));
            s.tree = csg(CsgOperand::of(s.tree), a.clip ? CsgOp::Intersection : CsgOp::Difference, CsgOperand::of(cut));
        }
        // The cut faces were inside: their values (a display window's grey) are the field's there.
        if (!s.tree.voxelValues.empty() && !s.field.values.empty()) fillVoxelValues(s.tree, s.field, a.threads);
        log::debug("cuts applied in " + std::to_string(t.ms()) + " ms");
        s.report.buildMs += t.ms();
    }
    if (!a.keepVolume) s.tree = extractShell(s.tree);
    // render --bake --lighting dynamic: the light would be baked into an octree that is
    // neither shaded by it nor saved.
    const bool bakeUnused = a.bake && a.lighting == SurfaceArgs::Lighting::Dynamic;
    if (bakeUnused)
        log::warning("--bake with --lighting dynamic: nothing baked (dynamic shading does not use baked light; "
                     "leave out --lighting dynamic to render with it)");
    if ((a.bake && !bakeUnused) || (a.lighting == SurfaceArgs::Lighting::Baked && s.tree.baked.empty())) {
        if (s.tree.form != OctreeForm::Shell) throw UsageError("--bake applies to the shell form (not with --form volume)");
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
    s.report.nodes = s.tree.nodes.size();
}

/// buildSurface for a city input: the model read and voxelized; the field empty but for its name.
void buildCitySurface(const SurfaceArgs& a, Surface& s) {
    const char* given = a.iso ? "--iso" : a.formGiven ? "--form/--inside" : !a.cuts.empty() ? "--cut" : a.extendDown ? "--extend-down" : !a.isoPreset.empty() ? "--iso"
                        : a.window.valid() ? "--window" : fieldOptionGiven(a.request);
    if (given)
        throw UsageError(std::string(given) + " does not apply to the city input " + a.input +
                         " (its buildings and terrain are voxelized as surfaces)");
    if (a.terrainDepth > a.depth)
        throw UsageError("--terrain-depth " + std::to_string(a.terrainDepth) + " is deeper than --depth " + std::to_string(a.depth) +
                         " (the terrain goes to the shallower depth, the buildings to --depth)");
    Timer t;
    io::CityRequest request = a.city;
    // The octree resolves the terrain no finer than its depth.
    request.maxSamples = (1 << std::min(a.terrainDepth > 0 ? a.terrainDepth : a.depth, 12)) + 1;
    const CityModel model = io::readCityModel(a.input, request);
    s.loadMs = t.ms();
    for (const auto& n : model.notes) log::warning(n);
    CityBuildOptions o;
    o.depth = a.depth;
    o.threads = a.threads;
    o.terrainDepth = a.terrainDepth;
    s.tree = voxelizeCity(model, o, &s.report);
    s.field.name = s.tree.fieldName;
    s.field.source = a.input;
    s.tree.source = a.input + " (" + std::to_string(model.objects.size()) + " objects, " + std::to_string(model.triangles.size()) +
                    " triangles, CRS " + (model.crs.empty() ? std::string("none") : model.crs) + ")";
}

/// What an octree was made from, for its file's header: input, variable, the reader's notes.
std::string sourceDescription(const std::string& input, const ScalarField& f) {
    std::string s = input + ", variable " + f.name;
    for (const auto& n : f.notes) s += "; " + n;
    return s;
}

/// --colour-by: the second variable, read with the same request (region, depth range, time)
/// and checked to lie on the field's grid.
ScalarField loadColourBy(const SurfaceArgs& a, const io::FieldRequest& request, const ScalarField& field) {
    io::FieldRequest second = request;
    second.variable = a.colourBy;
    ScalarField by = loadField(a.input, second, a.depth);
    if (by.dims != field.dims || by.origin != field.origin || by.spacing != field.spacing || by.coords != field.coords ||
        by.direction != field.direction)
        throw InputError(a.input + ": --colour-by " + a.colourBy + " is not on the grid of '" + field.name +
                         "' (both variables must share their coordinates)");
    return by;
}

}  // namespace

ValueWindow displayWindow(const std::string& text) { return parseWindow(text); }

std::string joinNames(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

vec4 displayToLinear(vec4 c) { return vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a); }

void addVariableOption(OptionParser& p, io::FieldRequest& request) {
    p.add(tableOption(model::opt::variable, [&](const std::string& v) {
        if (v.empty()) throw UsageError("--var: empty (give a variable name)");
        request.variable = v;
    }));
}

void addSurfaceOptions(OptionParser& p, SurfaceArgs& a) {
    addVariableOption(p, a.request);
    std::string presets;
    for (const auto& pr : ctIsoPresets()) presets += std::string(presets.empty() ? "" : ", ") + pr.name + " " + huText(pr.hu);
    p.add(tableOption(model::opt::iso, [&](const std::string& v) {
        a.isoPreset.clear();
        if (ctIsoPreset(v)) a.isoPreset = v;
        else a.iso = parseNumber("iso", v);
    }, "presets " + presets));
    p.add(tableOption(model::opt::depth, [&](const std::string& v) {
        a.depth = tableInt(model::opt::depth, v);
        a.depthGiven = true;
    }));
}

void addInsideOption(OptionParser& p, SurfaceArgs& a, const std::string& applies) {
    (void)applies;
    p.add(tableOption(model::opt::inside, [&](const std::string& v) {
        a.insideBelow = model::parseChoice(model::opt::inside, v) == "below";
        a.formGiven = true;
    }));
}

void addExtendDownOption(OptionParser& p, SurfaceArgs& a) {
    p.add({"extend-down", "", "geographic fields: extend each water column's deepest valid value down through the masked samples "
           "under it, so that a finer sea floor (--cut relief:FILE) bounds the water instead of the grid's own (default off)",
           [&](const std::string&) { a.extendDown = true; }});
}

void addFormOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::form, [&](const std::string& v) {
        a.form = model::parseChoice(model::opt::form, v) == "volume" ? OctreeForm::Volume : OctreeForm::Shell;
        a.formGiven = true;
    }));
    addInsideOption(p, a, "volume form");
    p.add({"cut", "SOLID", "cut a solid away: box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R, cylinder:X0,Y0,Z0,X1,Y1,Z1,R or "
           "halfspace:X,Y,Z,NX,NY,NZ in world units, or relief:FILE, the ground under a relief raster (e.g. ETOPO; geographic "
           "fields only, laid out in their world); repeatable; builds the volume form (default: none)",
           [&](const std::string& v) {
               checkSolidArgument(v);
               a.cuts.emplace_back(v);
           }});
    p.add({"clip", "", "keep only what lies inside the --cut solids instead of cutting them away (default off)",
           [&](const std::string&) { a.clip = true; }});
    addExtendDownOption(p, a);
}

void addBakeOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"bake", "", "bake diffuse lighting, shadows and ambient occlusion into the shell (default off)",
           [&](const std::string&) { a.bake = true; }});
    p.add({"bake-light", "dir:X,Y,Z[,I]|point:X,Y,Z[,I]", "a light to bake, world direction towards it or position, "
           "intensity I (default 1); repeatable (default one dir:0.3,-0.5,1)",
           [&](const std::string& v) {
               if (!a.bakeLightGiven) a.bakeOptions.lights.clear();
               a.bakeLightGiven = true;
               a.bakeOptions.lights.push_back(parseBakeLight(v));
           }});
    p.add(tableOption(model::opt::bakeAo, [&](const std::string& v) { a.bakeOptions.aoRays = tableInt(model::opt::bakeAo, v); }));
    p.add(tableOption(model::opt::bakeAoDistance, [&](const std::string& v) {
        a.bakeOptions.aoDistance = tableNumber(model::opt::bakeAoDistance, v);
    }));
    p.add(tableOption(model::opt::bakeShadows,
                      [&](const std::string& v) { a.bakeOptions.shadows = tableOnOff(model::opt::bakeShadows, v); }));
}

void addLightingOption(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::lighting, [&](const std::string& v) {
        a.lighting = model::parseChoice(model::opt::lighting, v) == "baked" ? SurfaceArgs::Lighting::Baked
                                                                            : SurfaceArgs::Lighting::Dynamic;
    }));
    p.add(tableOption(model::opt::ambient, [&](const std::string& v) { a.ambient = float(tableNumber(model::opt::ambient, v)); }));
    p.add(tableOption(model::opt::shadows, [&](const std::string& v) { a.shadows = tableOnOff(model::opt::shadows, v); }));
}

void addThreadsOption(OptionParser& p, SurfaceArgs& a, const std::string& result) {
    (void)result;
    p.add(tableOption(model::opt::threads, [&](const std::string& v) { a.threads = tableInt(model::opt::threads, v); }));
}

void addWindowOption(OptionParser& p, SurfaceArgs& a, const std::string& what, const std::string& byDefault) {
    std::string windows;
    for (const auto& w : ctWindowPresets())
        windows += std::string(windows.empty() ? "" : ", ") + w.name + " " + huText(w.window.centre) + "/" +
                   huText(w.window.width);
    p.add({"window", "NAME|C,W|none", "grey " + what + ": a CT preset (centre/width in HU: " + windows +
           "), a centre and width, or none (default: " + byDefault + ")",
           [&](const std::string& v) { a.windowName = v, a.window = parseWindow(v); }});
}

void addColourMapOptions(OptionParser& p, SurfaceArgs& a, const std::string& colormapHelp, const std::string& rangeHelp,
                         const std::string& maskedWhat) {
    p.add({"colormap", "NAME", "colour map: " + joinNames(colormapNames()) + "; " + colormapHelp,
           [&](const std::string& v) {
               colormap(v, 0.0f);
               a.colormap = v;
           }});
    p.add({"colour-range", "MIN,MAX", rangeHelp,
           [&](const std::string& v) {
               const std::size_t comma = v.find(',');
               if (comma == std::string::npos || v.find(',', comma + 1) != std::string::npos)
                   throw UsageError("--colour-range: expected MIN,MAX, got '" + v + "'");
               const double lo = parseNumber("colour-range", v.substr(0, comma)), hi = parseNumber("colour-range", v.substr(comma + 1));
               if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi) || std::abs(lo) > 3e38 || std::abs(hi) > 3e38)
                   throw UsageError("--colour-range: MIN must be below MAX, both finite, got '" + v + "'");
               a.colourMin = float(lo);
               a.colourMax = float(hi);
           }});
    p.add({"masked-colour", "R,G,B", "colour of " + maskedWhat + ", sRGB in [0,1] (default 0.6,0.6,0.6)",
           [&](const std::string& v) { a.maskedColour = vec3(parseColour("masked-colour", v, false)); }});
}

void addColourOptions(OptionParser& p, SurfaceArgs& a) {
    a.colours = true;
    p.add({"colour", "R,G,B", "surface colour, sRGB components in [0,1], also over a city's own colours (default 0.85,0.62,0.35; city inputs: per object and texture)",
           [&](const std::string& v) {
               a.colour = vec3(parseColour("colour", v, false));
               a.colourGiven = true;
           }});
    p.add({"color", "R,G,B", "same as --colour (default 0.85,0.62,0.35)", [&](const std::string& v) {
               a.colour = vec3(parseColour("color", v, false));
               a.colourGiven = true;
           }});
    addWindowOption(p, a, "the surface by a display window applied to the value just under it",
                    "the window stored in a DICOM file, unless --colour, --colormap or --colour-by is given");
    addColourMapOptions(p, a,
                        "colours by --colour-by's variable, else by height (default: with --colour-by the variable's map from its "
                        "standard_name or name, thermal/haline/speed/viridis; else none, --colour)",
                        "values of --colour-by mapped onto the colour map's ends (default: the surface voxels' range)",
                        "surface voxels where --colour-by's variable is masked");
    p.add({"floor-colour", "R,G,B", "colour of the sea floor and land (--floor), sRGB in [0,1] (default 0.55,0.5,0.45)",
           [&](const std::string& v) { a.floorColour = vec3(parseColour("floor-colour", v, false)); }});
}

void addLayerOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"colour-by", "VAR", "colour the isosurface by a second variable of the same file, sampled at each voxel (default: none)",
           [&](const std::string& v) {
               if (v.empty()) throw UsageError("--colour-by: empty variable name");
               a.colourBy = v;
           }});
    p.add({"floor", "", "also draw the sea floor and land where the variable is masked, under the isosurface (default off)",
           [&](const std::string&) { a.floor = true; }});
}

void addGeographicOptions(OptionParser& p, io::FieldRequest& request) {
    p.add({"region", "LON0,LON1,LAT0,LAT1", "geographic subregion in degrees, NetCDF only (default: the whole grid)",
           [&](const std::string& v) {
               auto r = io::parseRegion(v);
               request.hasRegion = true;
               for (int i = 0; i < 4; ++i) request.region[i] = r[std::size_t(i)];
           }});
    p.add({"depth-range", "Z0,Z1", "depth levels from Z0 to Z1 metres (positive down), NetCDF only (default: every level)",
           [&](const std::string& v) {
               auto r = io::parseDepthRange(v);
               request.hasDepthRange = true;
               request.depthRange[0] = r[0];
               request.depthRange[1] = r[1];
           }});
    p.add(tableOption(model::opt::time, [&](const std::string& v) {
        io::checkTimeText(v);
        request.time = v;
    }));
    p.add(tableOption(model::opt::verticalScale,
                      [&](const std::string& v) { request.verticalScale = tableNumber(model::opt::verticalScale, v); }));
}

void addCityOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"lod-select", "LOD", "city inputs: level of detail to voxelize, e.g. 1, 2 or 2.2 (a prefix takes its sublevels; default: each object's highest)",
           [&](const std::string& v) {
               if (v.empty() || v.find_first_not_of("0123456789.") != std::string::npos)
                   throw UsageError("--lod-select: expected a level of detail such as 1, 2 or 2.2, got '" + v + "'");
               a.city.lod = v;
               a.cityGiven = true;
           }});
    // A text option of CityRequest: not empty (`what` says what to give), marks a city option given.
    auto text = [&](const model::Option& o, std::string io::CityRequest::*field, const char* what) {
        const char* name = o.flag;
        p.add(tableOption(o, [&a, name, field, what](const std::string& v) {
                   if (v.empty()) throw UsageError(std::string("--") + name + ": empty (give " + what + ")");
                   a.city.*field = v;
                   a.cityGiven = true;
               }));
    };
    p.add(tableOption(model::opt::terrainDepth, [&](const std::string& v) {
        a.terrainDepth = tableInt(model::opt::terrainDepth, v);
        a.cityGiven = true;
    }));
    text(model::opt::dem, &io::CityRequest::dem, "a raster file");
    text(model::opt::texture, &io::CityRequest::texture, "a raster file");
    text(model::opt::heightAttr, &io::CityRequest::heightAttr, "an attribute name");
    text(model::opt::baseAttr, &io::CityRequest::baseAttr, "an attribute name");
    text(model::opt::crs, &io::CityRequest::crs, "e.g. EPSG:28992");
}

void addSeriesOption(OptionParser& p, io::FieldRequest& request) {
    p.add(tableOption(model::opt::series, [&](const std::string& v) {
        if (v.empty()) throw UsageError("--series: empty (give a UID, an index or a description)");
        request.series = v;
    }));
}

void addMessageOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::maxMemory, [&](const std::string& v) { a.maxMemory = parseByteSize("max-memory", v); }));
    p.add({"quiet", "", "print only errors", [&](const std::string&) { a.quiet = true; }});
    p.add({"verbose", "", "print debugging details", [&](const std::string&) { a.verbose = true; }});
    p.add({"help", "", "show this help and exit", [&](const std::string&) { a.help = true; }});
}

bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, SurfaceArgs& a,
                      const std::string& output, const std::string& missingOutput) {
    const std::vector<std::string> positional = p.parse(args);
    if (a.help) {
        std::fputs(p.help().c_str(), stdout);
        return false;
    }
    if (positional.size() != 1)
        throw UsageError(p.command() + " needs exactly one INPUT (got " + std::to_string(positional.size()) + ")");
    if (output.empty()) throw UsageError(p.command() + " needs " + missingOutput);
    a.input = positional[0];
    return true;
}

const char* fieldOptionGiven(const io::FieldRequest& request) {
    const io::FieldRequest none;
    return !request.variable.empty()                    ? "--var"
           : request.hasRegion                          ? "--region"
           : request.hasDepthRange                      ? "--depth-range"
           : !request.time.empty()                      ? "--time"
           : !request.series.empty()                    ? "--series"
           : request.verticalScale != none.verticalScale ? "--vertical-scale"
                                                         : nullptr;
}

std::uint64_t memoryBudget(const SurfaceArgs& a) { return a.maxMemory ? a.maxMemory : defaultMemoryBudget(); }

Surface buildSurface(const SurfaceArgs& a) {
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    if (a.insideBelow && a.form != OctreeForm::Volume && a.cuts.empty())
        throw UsageError("--inside applies to --form volume (or --cut)");
    if (a.clip && a.cuts.empty()) throw UsageError("--clip needs a --cut solid");
    const std::uint64_t budget = memoryBudget(a);
    if (a.window.valid() && (a.colourGiven || !a.colormap.empty()))
        throw UsageError("--window " + a.windowName + " and " + (a.colourGiven ? "--colour" : "--colormap") +
                         " both colour the surface: give one");
    Surface s;
    if (isOctreeInput(a.input)) {
        if (a.cityGiven) throw UsageError("--lod-select, --crs, --dem, --texture, --height-attr, --base-attr and --terrain-depth apply to city inputs, not to the octree file " + a.input);
        loadOctreeSurface(a, budget, s);
        finishSurface(a, s);
        return s;
    }
    if (io::isCityInput(a.input)) {
        buildCitySurface(a, s);
        return s;
    }
    if (a.cityGiven) throw UsageError("--lod-select, --crs, --dem, --texture, --height-attr, --base-attr and --terrain-depth apply to city inputs (CityJSON, CityGML, footprints, DEM rasters), not to " + a.input);
    readSurfaceField(a, s);
    BuildHooks terminal;
    terminal.progress = progressPrinter(a.quiet);
    terminal.endLine = true;
    buildFromField(a, s, terminal);
    return s;
}

void readSurfaceField(const SurfaceArgs& a, Surface& s) {
    io::FieldRequest request = a.request;
    request.memoryBudget = memoryBudget(a);
    Timer t;
    s.field = loadField(a.input, request, a.depth, &s.spheres);
    s.loadMs = t.ms();
}

void buildFromField(const SurfaceArgs& a, Surface& s, const BuildHooks& hooks) {
    io::FieldRequest request = a.request;
    request.memoryBudget = memoryBudget(a);
    if (a.extendDown) {
        if (!s.field.geographic.valid)
            throw InputError(a.input + ": --extend-down applies to geographic fields (longitude, latitude, depth)");
        log::info("--extend-down: " + std::to_string(extendColumnsDown(s.field)) + " masked samples under the water filled");
    }
    auto [vmin, vmax] = s.field.validRange();
    if (!a.isoPreset.empty()) requireHounsfield(s.field, a.input, "--iso " + a.isoPreset);
    // A sphere input's field is the signed distance to its spheres: their surface is at 0.
    const bool sphereDistance = isSphereInput(a.input);
    s.iso = !a.isoPreset.empty() ? *ctIsoPreset(a.isoPreset)
            : a.iso                ? *a.iso
            : sphereDistance       ? 0.0
                                   : 0.5 * (double(vmin) + double(vmax));
    if (!a.iso && a.isoPreset.empty() && !sphereDistance) {
        std::ostringstream m;
        m << "no --iso given: using " << s.iso << ", the middle of the range [" << vmin << ", " << vmax << "] of '"
          << s.field.name << "'";
        log::info(m.str());
    }
    for (const auto& n : s.field.notes) log::debug(n);
    if (!a.colourBy.empty() && !a.windowName.empty())
        throw UsageError("--window and --colour-by both colour the surface: give one of them");
    std::optional<ScalarField> colourBy;
    if (!a.colourBy.empty()) {
        colourBy = loadColourBy(a, request, s.field);
        if (a.extendDown) extendColumnsDown(*colourBy);
    }

    BuildOptions bo;
    bo.depth = a.depth;
    bo.iso = s.iso;
    bo.threads = a.threads;
    bo.progress = hooks.progress;
    bo.cancelled = hooks.cancelled;
    bo.memoryBudget = request.memoryBudget;
    bo.form = a.cuts.empty() ? a.form : OctreeForm::Volume;
    bo.insideBelow = a.insideBelow;
    chooseWindow(a, s);
    bo.voxelValues = s.window.valid();
    s.tree = buildOctree(s.field, bo, &s.report);
    s.tree.source = sourceDescription(a.input, s.field);
    if (hooks.progress && hooks.endLine) std::fputs("\n", stderr);
    finishSurface(a, s);
    // A molecule's voxels keep their atoms' colours, as a city's keep their buildings'.
    if (s.spheres) {
        Timer t;
        s.tree.colours = sphereColoursAtVoxels(s.tree, *s.spheres, a.threads);
        log::debug("voxels coloured by their nearest spheres in " + std::to_string(t.ms()) + " ms");
    }
    if (colourBy) {
        s.tree.voxelValues = sampleAtVoxels(s.tree, *colourBy, a.threads);
        s.tree.valueName = colourBy->name;
        s.tree.valueUnits = colourBy->units;
        s.tree.valueStandardName = colourBy->standardName;
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
        s.report.boundaryVoxels = s.tree.voxels.size();
        s.report.nodes = s.tree.nodes.size();
    }
}

void applyColour(const SurfaceArgs& a, const Surface& s, RenderSettings& settings) {
    settings.colour = vec3(displayToLinear(vec4(a.colour, 1.0f)));
    settings.colormap = a.colormap;
    settings.voxelColours = !a.colourGiven;
    settings.window = s.window;
    settings.invertedGrey = s.invertedGrey;
    if (settings.colormap.empty() && !s.tree.voxelValues.empty() && !s.window.valid())
        settings.colormap = defaultColormap(s.tree.valueStandardName, s.tree.valueName);
    settings.colourMin = a.colourMin;
    settings.colourMax = a.colourMax;
    settings.maskedColour = vec3(displayToLinear(vec4(a.maskedColour, 1.0f)));
    settings.floorColour = vec3(displayToLinear(vec4(a.floorColour, 1.0f)));
}

void applyLighting(const SurfaceArgs& a, RenderSettings& settings) {
    settings.baked = a.lighting != SurfaceArgs::Lighting::Dynamic;
    settings.shadows = a.shadows;
    if (a.ambient) {
        settings.ambient = *a.ambient;
        settings.diffuse = 1.0f - *a.ambient;
    }
}

}  // namespace octrace::cli
