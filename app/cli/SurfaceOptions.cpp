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
    p.add(tableOption(model::opt::extendDown, [&](const std::string&) { a.extendDown = true; }));
}

void addFormOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::form, [&](const std::string& v) {
        a.form = model::parseChoice(model::opt::form, v) == "volume" ? OctreeForm::Volume : OctreeForm::Shell;
        a.formGiven = true;
    }));
    addInsideOption(p, a, "volume form");
    p.add(tableOption(model::opt::cut, [&](const std::string& v) {
        checkSolidArgument(v);
        a.cuts.emplace_back(v);
    }));
    p.add(tableOption(model::opt::clip, [&](const std::string&) { a.clip = true; }));
    addExtendDownOption(p, a);
}

void addBakeOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::bake, [&](const std::string&) { a.bake = true; }));
    p.add(tableOption(model::opt::bakeLight, [&](const std::string& v) {
        if (!a.bakeLightGiven) a.bakeOptions.lights.clear();
        a.bakeLightGiven = true;
        a.bakeOptions.lights.push_back(parseBakeLight(v));
    }));
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
    p.add(tableOption(model::opt::window, [&](const std::string& v) { a.windowName = v, a.window = displayWindow(v); },
                      what + "; the CT presets (centre/width in HU): " + windows + "; without it: " + byDefault));
}

void addColourMapOptions(OptionParser& p, SurfaceArgs& a, const std::string& colormapHelp, const std::string& rangeHelp,
                         const std::string& maskedWhat) {
    p.add(tableOption(model::opt::colormap, [&](const std::string& v) {
        colormap(v, 0.0f);
        a.colormap = v;
    }, joinNames(colormapNames()) + "; " + colormapHelp));
    p.add(tableOption(model::opt::colourRange, [&](const std::string& v) {
               const std::size_t comma = v.find(',');
               if (comma == std::string::npos || v.find(',', comma + 1) != std::string::npos)
                   throw UsageError("--colour-range: expected MIN,MAX, got '" + v + "'");
               const double lo = parseNumber("colour-range", v.substr(0, comma)), hi = parseNumber("colour-range", v.substr(comma + 1));
               if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi) || std::abs(lo) > 3e38 || std::abs(hi) > 3e38)
                   throw UsageError("--colour-range: MIN must be below MAX, both finite, got '" + v + "'");
               a.colourMin = float(lo);
               a.colourMax = float(hi);
           }, rangeHelp));
    p.add(tableOption(model::opt::maskedColour, [&](const std::string& v) { a.maskedColour = vec3(parseColour("masked-colour", v, false)); },
                      "here " + maskedWhat));
}

void addColourOptions(OptionParser& p, SurfaceArgs& a) {
    a.colours = true;
    p.add(tableOption(model::opt::colour, [&](const std::string& v) {
        a.colour = vec3(parseColour("colour", v, false));
        a.colourGiven = true;
    }));
    p.add({"color", "R,G,B", "same as --colour (default 0.85,0.62,0.35)", [&](const std::string& v) {
               a.colour = vec3(parseColour("color", v, false));
               a.colourGiven = true;
           }});
    addWindowOption(p, a, "here the surface, by the value just under it",
                    "the window stored in a DICOM file, unless --colour, --colormap or --colour-by is given");
    addColourMapOptions(p, a,
                        "here the surface's height, or --colour-by's values; with --colour-by, by default the variable's map "
                        "from its standard_name or name, thermal/haline/speed/viridis",
                        "here --colour-by's values, by default the surface voxels' range",
                        "surface voxels where --colour-by's variable is masked");
    p.add(tableOption(model::opt::floorColour, [&](const std::string& v) { a.floorColour = vec3(parseColour("floor-colour", v, false)); }));
}

void addLayerOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::colourBy, [&](const std::string& v) {
        if (v.empty()) throw UsageError("--colour-by: empty variable name");
        a.colourBy = v;
    }));
    p.add(tableOption(model::opt::floor, [&](const std::string&) { a.floor = true; }));
}

void addGeographicOptions(OptionParser& p, io::FieldRequest& request, bool timeStep) {
    p.add(tableOption(model::opt::region, [&](const std::string& v) {
        auto r = io::parseRegion(v);
        request.hasRegion = true;
        for (int i = 0; i < 4; ++i) request.region[i] = r[std::size_t(i)];
    }));
    p.add(tableOption(model::opt::depthRange, [&](const std::string& v) {
        auto r = io::parseDepthRange(v);
        request.hasDepthRange = true;
        request.depthRange[0] = r[0];
        request.depthRange[1] = r[1];
    }));
    if (timeStep)
        p.add(tableOption(model::opt::time, [&](const std::string& v) {
            io::checkTimeText(v);
            request.time = v;
        }));
    p.add(tableOption(model::opt::verticalScale,
                      [&](const std::string& v) { request.verticalScale = tableNumber(model::opt::verticalScale, v); }));
}

void addCityOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(tableOption(model::opt::lodSelect, [&](const std::string& v) {
        if (v.empty() || v.find_first_not_of("0123456789.") != std::string::npos)
            throw UsageError("--lod-select: expected a level of detail such as 1, 2 or 2.2, got '" + v + "'");
        a.city.lod = v;
        a.cityGiven = true;
    }));
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
