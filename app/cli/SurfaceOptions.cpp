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

/// Progress of a stage ("reading", "building octree") on stderr, only when stderr is a terminal.
std::function<void(double)> progressPrinter(bool quiet, const char* stage) {
    if (quiet || !isatty(2)) return {};
    // The line ends once the stage reports it is complete (the builder's and the readers' last
    // call is 1.0).
    return [stage](double f) {
        std::fprintf(stderr, "\roctrace: %s %3d%%", stage, int(f * 100.0 + 0.5));
        if (f >= 1.0) std::fputs("\n", stderr);
    };
}

}  // namespace

std::function<void(double)> readProgressPrinter(bool quiet) { return progressPrinter(quiet, "reading"); }

std::string joinNames(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

Surface buildSurface(const SurfaceArgs& a) {
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    model::BuildHooks terminal;
    terminal.readProgress = readProgressPrinter(a.quiet);
    terminal.progress = progressPrinter(a.quiet, "building octree");
    return model::buildSurface(a, terminal);
}

namespace {
model::SettingTargets into(SurfaceArgs& a) { return {.surface = &a}; }
model::SettingTargets into(io::FieldRequest& request) { return {.request = &request}; }
}  // namespace

void addVariableOption(OptionParser& p, io::FieldRequest& request) { p.add(settingOption(model::opt::variable, into(request))); }

void addSurfaceOptions(OptionParser& p, SurfaceArgs& a) {
    addVariableOption(p, a.request);
    std::string presets;
    for (const auto& pr : ctIsoPresets()) presets += std::string(presets.empty() ? "" : ", ") + pr.name + " " + huText(pr.hu);
    p.add(settingOption(model::opt::iso, into(a), "presets " + presets));
    p.add(settingOption(model::opt::depth, into(a)));
}

void addInsideOption(OptionParser& p, SurfaceArgs& a, const std::string& applies) {
    (void)applies;
    p.add(settingOption(model::opt::inside, into(a)));
}

void addExtendDownOption(OptionParser& p, SurfaceArgs& a) { p.add(settingOption(model::opt::extendDown, into(a))); }

void addFormOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(settingOption(model::opt::form, into(a)));
    p.add(settingOption(model::opt::surface, into(a)));
    addInsideOption(p, a, "volume form");
    p.add(settingOption(model::opt::cut, into(a)));
    p.add(settingOption(model::opt::clip, into(a)));
    addExtendDownOption(p, a);
}

void addBakeOptions(OptionParser& p, SurfaceArgs& a) {
    for (const model::Option* o : {&model::opt::bake, &model::opt::bakeLight, &model::opt::bakeAo, &model::opt::bakeAoDistance,
                                   &model::opt::bakeShadows})
        p.add(settingOption(*o, into(a)));
}

void addLightingOption(OptionParser& p, SurfaceArgs& a) {
    for (const model::Option* o : {&model::opt::lighting, &model::opt::ambient, &model::opt::shadows}) p.add(settingOption(*o, into(a)));
}

void addThreadsOption(OptionParser& p, SurfaceArgs& a, const std::string& result) { addThreadsOption(p, into(a), result); }

void addThreadsOption(OptionParser& p, const model::SettingTargets& targets, const std::string& result) {
    (void)result;
    p.add(settingOption(model::opt::threads, targets));
}

void addWindowOption(OptionParser& p, const model::SettingTargets& targets, const std::string& what, const std::string& byDefault) {
    std::string windows;
    for (const auto& w : ctWindowPresets())
        windows += std::string(windows.empty() ? "" : ", ") + w.name + " " + huText(w.window.centre) + "/" +
                   huText(w.window.width);
    p.add(settingOption(model::opt::window, targets,
                        what + "; the CT presets (centre/width in HU): " + windows + "; without it: " + byDefault));
}

void addColourMapOptions(OptionParser& p, const model::SettingTargets& targets, const std::string& colormapHelp,
                         const std::string& rangeHelp, const std::string& maskedWhat) {
    p.add(settingOption(model::opt::colormap, targets, joinNames(colormapNames()) + "; " + colormapHelp));
    p.add(settingOption(model::opt::colourRange, targets, rangeHelp));
    p.add(settingOption(model::opt::maskedColour, targets, "here " + maskedWhat));
}

void addColourOptions(OptionParser& p, SurfaceArgs& a) {
    a.colours = true;
    p.add(settingOption(model::opt::colour, into(a)));
    p.add({"color", "R,G,B", "same as --colour (default 0.85,0.62,0.35)",
           [&](const std::string& v) { model::applySetting(model::opt::colour, v, into(a)); }});
    addWindowOption(p, into(a), "here the surface, by the value just under it",
                    "the window stored in a DICOM file, unless --colour, --colormap or --colour-by is given");
    addColourMapOptions(p, into(a),
                        "here the surface's height, or --colour-by's values; with --colour-by, by default the variable's map "
                        "from its standard_name or name, thermal/haline/speed/viridis",
                        "here --colour-by's values, by default the surface voxels' range",
                        "surface voxels where --colour-by's variable is masked");
    p.add(settingOption(model::opt::floorColour, into(a)));
}

void addLayerOptions(OptionParser& p, SurfaceArgs& a) {
    p.add(settingOption(model::opt::colourBy, into(a)));
    p.add(settingOption(model::opt::floor, into(a)));
}

void addGeographicOptions(OptionParser& p, io::FieldRequest& request, bool timeStep) {
    for (const model::Option* o : {&model::opt::region, &model::opt::depthRange, &model::opt::mapProjection, &model::opt::time, &model::opt::verticalScale})
        if (timeStep || o != &model::opt::time) p.add(settingOption(*o, into(request)));
}

void addCityOptions(OptionParser& p, SurfaceArgs& a) {
    for (const model::Option* o : {&model::opt::lodSelect, &model::opt::terrainDepth, &model::opt::dem, &model::opt::texture,
                                   &model::opt::heightAttr, &model::opt::baseAttr, &model::opt::crs})
        p.add(settingOption(*o, into(a)));
}

void addSeriesOption(OptionParser& p, io::FieldRequest& request) {
    p.add(settingOption(model::opt::series, into(request)));
    p.add(settingOption(model::opt::volume, into(request)));
}

void addMessageOptions(OptionParser& p, SurfaceArgs& a) { addMessageOptions(p, a, into(a)); }

void addMessageOptions(OptionParser& p, MessageArgs& a, const model::SettingTargets& budget) {
    p.add(settingOption(model::opt::maxMemory, budget));
    p.add({"quiet", "", "print only errors", [&](const std::string&) { a.quiet = true; }});
    p.add({"verbose", "", "print debugging details", [&](const std::string&) { a.verbose = true; }});
    p.add({"help", "", "show this help and exit", [&](const std::string&) { a.help = true; }});
}

bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, SurfaceArgs& a,
                      const std::string& output, const std::string& missingOutput) {
    return parseCommandLine(p, args, a, a.input, output, missingOutput);
}

bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, MessageArgs& a, std::string& input,
                      const std::string& output, const std::string& missingOutput) {
    const std::vector<std::string> positional = p.parse(args);
    if (a.help) {
        std::fputs(p.help().c_str(), stdout);
        return false;
    }
    if (positional.size() != 1)
        throw UsageError(p.command() + " needs exactly one INPUT (got " + std::to_string(positional.size()) + ")");
    if (output.empty()) throw UsageError(p.command() + " needs " + missingOutput);
    input = positional[0];
    return true;
}

}  // namespace octrace::cli
