#include "SurfaceOptions.h"

#include "Input.h"

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
#include <sstream>

namespace octrace::cli {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

/// Progress on stderr while building, only when stderr is a terminal.
std::function<void(double)> progressPrinter(bool quiet) {
    if (quiet || !isatty(2)) return {};
    return [](double f) { std::fprintf(stderr, "\roctrace: building octree %3d%%", int(f * 100.0 + 0.5)); };
}

/// buildSurface for an octree file: the octree as it is, the field empty but for its name.
void loadOctreeSurface(const SurfaceArgs& a, std::uint64_t budget, Surface& s) {
    const io::FieldRequest none;
    const char* given = !a.request.variable.empty() ? "--var"
                        : a.iso                     ? "--iso"
                        : a.depthGiven              ? "--depth"
                        : a.formGiven               ? "--form/--inside"
                        : a.request.hasRegion       ? "--region"
                        : !a.request.series.empty() ? "--series"
                        : a.request.verticalScale != none.verticalScale ? "--vertical-scale"
                                                                         : nullptr;
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
        for (const Solid& cut : a.cuts)
            s.tree = csg(CsgOperand::of(s.tree), a.clip ? CsgOp::Intersection : CsgOp::Difference, CsgOperand::of(cut));
        log::debug("cuts applied in " + std::to_string(t.ms()) + " ms");
        s.report.buildMs += t.ms();
    }
    if (!a.keepVolume) s.tree = extractShell(s.tree);
    s.report.boundaryVoxels = countVoxels(s.tree).boundary;
    s.report.nodes = s.tree.nodes.size();
}

/// What an octree was made from, for its file's header: input, variable, the reader's notes.
std::string sourceDescription(const std::string& input, const ScalarField& f) {
    std::string s = input + ", variable " + f.name;
    for (const auto& n : f.notes) s += "; " + n;
    return s;
}

}  // namespace

std::string joinNames(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

vec4 displayToLinear(vec4 c) { return vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a); }

void addSurfaceOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"var", "NAME", "variable to draw (default: the file's only 3-D variable)",
           [&](const std::string& v) { a.request.variable = v; }});
    p.add({"iso", "VALUE", "iso value of the surface (default: middle of the variable's valid range)",
           [&](const std::string& v) { a.iso = parseNumber("iso", v); }});
    p.add({"depth", "N", "octree depth, voxels = 2^N per cube edge (1.." + std::to_string(Octree::kMaxDepth) + ", default 8)",
           [&](const std::string& v) {
               a.depth = parseInt("depth", v, 1, Octree::kMaxDepth);
               a.depthGiven = true;
           }});
}

void addInsideOption(OptionParser& p, SurfaceArgs& a, const std::string& applies) {
    p.add({"inside", "above|below", applies + ": the solid is where the value is >= iso (above) or < iso (below) (default above)",
           [&](const std::string& v) {
               if (v != "above" && v != "below") throw UsageError("--inside: expected above or below, got '" + v + "'");
               a.insideBelow = v == "below";
               a.formGiven = true;
           }});
}

void addFormOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"form", "shell|volume", "octree form: the isosurface's boundary voxels (shell), or the solid it bounds with its "
           "interior and caps where the grid ends (volume) (default shell)",
           [&](const std::string& v) {
               if (v != "shell" && v != "volume") throw UsageError("--form: expected shell or volume, got '" + v + "'");
               a.form = v == "volume" ? OctreeForm::Volume : OctreeForm::Shell;
               a.formGiven = true;
           }});
    addInsideOption(p, a, "volume form");
    p.add({"cut", "SOLID", "cut a solid away: box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R, cylinder:X0,Y0,Z0,X1,Y1,Z1,R or "
           "halfspace:X,Y,Z,NX,NY,NZ in world units; repeatable; builds the volume form (default: none)",
           [&](const std::string& v) { a.cuts.push_back(parseSolid(v)); }});
    p.add({"clip", "", "keep only what lies inside the --cut solids instead of cutting them away (default off)",
           [&](const std::string&) { a.clip = true; }});
}

void addThreadsOption(OptionParser& p, SurfaceArgs& a, const std::string& result) {
    p.add({"threads", "N", "worker threads, 0 = all cores (default 0); " + result + " does not depend on it",
           [&](const std::string& v) { a.threads = parseInt("threads", v, 0, 1024); }});
}

void addColourOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"colour", "R,G,B", "surface colour, sRGB components in [0,1] (default 0.85,0.62,0.35)",
           [&](const std::string& v) { a.colour = vec3(parseColour("colour", v, false)); }});
    p.add({"color", "R,G,B", "same as --colour (default 0.85,0.62,0.35)", [&](const std::string& v) { a.colour = vec3(parseColour("color", v, false)); }});
    p.add({"colormap", "NAME", "colour the surface by height with a map: " + joinNames(colormapNames()) + " (default: none, --colour)",
           [&](const std::string& v) {
               colormap(v, 0.0f);
               a.colormap = v;
           }});
}

void addGeographicOptions(OptionParser& p, SurfaceArgs& a) {
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
}

void addSeriesOption(OptionParser& p, io::FieldRequest& request) {
    p.add({"series", "UID|INDEX|DESCRIPTION", "DICOM series to read: its UID, its number in `octrace info`'s list or its description (default: the largest)",
           [&](const std::string& v) {
               if (v.empty()) throw UsageError("--series: empty (give a UID, an index or a description)");
               request.series = v;
           }});
}

void addMessageOptions(OptionParser& p, SurfaceArgs& a) {
    p.add({"max-memory", "SIZE", "memory budget for reading the field, building the octree and the output: bytes, K, M, G, T "
           "(powers of 1024) or N% of the physical memory; a larger job is refused up front (default " +
           std::to_string(kDefaultMemoryBudgetPercent) + "%)",
           [&](const std::string& v) { a.maxMemory = parseByteSize("max-memory", v); }});
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

std::uint64_t memoryBudget(const SurfaceArgs& a) { return a.maxMemory ? a.maxMemory : defaultMemoryBudget(); }

Surface buildSurface(const SurfaceArgs& a) {
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    if (a.insideBelow && a.form != OctreeForm::Volume && a.cuts.empty())
        throw UsageError("--inside applies to --form volume (or --cut)");
    if (a.clip && a.cuts.empty()) throw UsageError("--clip needs a --cut solid");
    const std::uint64_t budget = memoryBudget(a);
    io::FieldRequest request = a.request;
    request.memoryBudget = budget;
    Surface s;
    Timer t;
    if (isOctreeInput(a.input)) {
        loadOctreeSurface(a, budget, s);
        finishSurface(a, s);
        return s;
    }
    s.field = loadField(a.input, request);
    s.loadMs = t.ms();
    auto [vmin, vmax] = s.field.validRange();
    s.iso = a.iso ? *a.iso : 0.5 * (double(vmin) + double(vmax));
    if (!a.iso) {
        std::ostringstream m;
        m << "no --iso given: using " << s.iso << ", the middle of the range [" << vmin << ", " << vmax << "] of '"
          << s.field.name << "'";
        log::info(m.str());
    }
    for (const auto& n : s.field.notes) log::debug(n);

    BuildOptions bo;
    bo.depth = a.depth;
    bo.iso = s.iso;
    bo.threads = a.threads;
    bo.progress = progressPrinter(a.quiet);
    bo.memoryBudget = budget;
    bo.form = a.cuts.empty() ? a.form : OctreeForm::Volume;
    bo.insideBelow = a.insideBelow;
    s.tree = buildOctree(s.field, bo, &s.report);
    s.tree.source = sourceDescription(a.input, s.field);
    if (bo.progress) std::fputs("\n", stderr);
    finishSurface(a, s);
    return s;
}

void applyColour(const SurfaceArgs& a, RenderSettings& settings) {
    settings.colour = vec3(displayToLinear(vec4(a.colour, 1.0f)));
    settings.colormap = a.colormap;
}

}  // namespace octrace::cli
