#include "SurfaceOptions.h"

#include "octrace/model/Input.h"
#include "octrace/model/SolidSpec.h"

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

/// Progress on stderr while building, only when stderr is a terminal.
std::function<void(double)> progressPrinter(bool quiet) {
    if (quiet || !isatty(2)) return {};
    // The line ends once the build reports it is complete (the builder's last call is 1.0).
    return [](double f) {
        std::fprintf(stderr, "\roctrace: building octree %3d%%", int(f * 100.0 + 0.5));
        if (f >= 1.0) std::fputs("\n", stderr);
    };
}

}  // namespace

std::string joinNames(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

Surface buildSurface(const SurfaceArgs& a) {
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    model::BuildHooks terminal;
    terminal.progress = progressPrinter(a.quiet);
    return model::buildSurface(a, terminal);
}

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
           [&](const std::string& v) { a.windowName = v, a.window = displayWindow(v); }});
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

}  // namespace octrace::cli
