// octrace export: read a field, build the shell octree of an isosurface and write it as surfels
// (position, normal, radius, colour) to a point-cloud file.
#include "Commands.h"
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/io/PlyWriter.h"
#include "octrace/render/Surfels.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <cctype>
#include <filesystem>
#include <sstream>

namespace octrace::cli {
namespace {

struct ExportArgs : SurfaceArgs {
    std::string output, format;
    int level = -1;
    bool ascii = false;
};

OptionParser makeParser(ExportArgs& a) {
    OptionParser p("export", "octrace export INPUT -o OUT.ply [options]");
    p.add({"o", "FILE", "output point cloud; format from --format or the extension: .ply (required)",
           [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    p.add(tableOption(model::opt::level, [&](const std::string& v) { a.level = tableInt(model::opt::level, v); },
                      "here one surfel per non-empty octree node at level L"));
    p.add(tableOption(model::opt::format, [&](const std::string& v) { a.format = model::parseChoice(model::opt::format, v); }));
    p.add(tableOption(model::opt::ascii, [&](const std::string&) { a.ascii = true; }));
    addThreadsOption(p, a, "the output");
    addColourOptions(p, a);
    addLayerOptions(p, a);
    addGeographicOptions(p, a.request);
    addCityOptions(p, a);
    addSeriesOption(p, a.request);
    addMessageOptions(p, a);
    return p;
}

std::string windowNumber(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

/// The header comments: where the surfels come from and what their attributes mean.
std::vector<std::string> provenance(const ExportArgs& a, const Surface& s, int level) {
    std::ostringstream iso;
    iso.precision(10);
    iso << s.iso;
    std::vector<std::string> c = {
        "octrace " OCTRACE_VERSION " surfels, one per " +
            (level == s.tree.depth ? std::string("boundary voxel") : "octree node at level " + std::to_string(level)),
        "input: " + a.input,
        "variable: " + s.field.name + (s.field.units.empty() ? "" : " (" + s.field.units + ")"),
        "iso: " + iso.str(),
        "depth: " + std::to_string(s.tree.depth) + ", level: " + std::to_string(level),
        "position: box centre in world units; radius: half the box diagonal",
        "colour: 8-bit sRGB albedo without lighting, " +
            (s.window.valid() ? "grey by the display window centre " + windowNumber(s.window.centre) + " width " +
                                    windowNumber(s.window.width) + " (" + model::sayForCli(s.windowSource) + ")" +
                                    (s.invertedGrey ? ", inverted (MONOCHROME1)" : "") + " of the value under the surface"
             : a.colormap.empty() ? "uniform"
                                  : "colour map " + a.colormap + " by height"),
    };
    for (const auto& n : s.field.notes) c.push_back("note: " + n);
    return c;
}

}  // namespace

int runExport(const std::vector<std::string>& args) {
    ExportArgs a;
    if (!parseCommandLine(makeParser(a), args, a, a.output, "an output file: -o OUT.ply")) return 0;
    if (a.format.empty()) {
        // Check the output format before the long work.
        std::string ext = std::filesystem::path(a.output).extension().string();
        for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".ply")
            throw UsageError("-o " + a.output + ": unknown point-cloud format '" + ext + "' (use .ply, or --format ply)");
        a.format = "ply";
    }
    if (a.depth && a.level > *a.depth) throw UsageError("--level " + std::to_string(a.level) + " is deeper than --depth " + std::to_string(*a.depth));

    if (!a.surface) a.surface = SurfaceMode::Voxel;  // surfels are the voxels: no corner values needed
    Surface surface = buildSurface(a);
    Octree& tree = surface.tree;
    const int level = a.level < 0 ? tree.depth : a.level;
    if (level < tree.depth) tree.computeSummaries();
    RenderSettings rs;
    rs.threads = a.threads;
    applyColour(a, surface, rs);
    const std::vector<Surfel> surfels = extractSurfels(tree, rs, level);

    io::PlyWriteOptions options;
    options.ascii = a.ascii;
    options.comments = provenance(a, surface, level);
    io::PlyWriter::write(surfels, a.output, options);

    std::ostringstream summary;
    summary.precision(4);
    summary << a.output << ": " << surfels.size() << " surfels ("
            << (level == tree.depth ? "one per boundary voxel" : "one per node at level " + std::to_string(level))
            << ", radius " << (surfels.empty() ? 0.0f : surfels[0].radius) << "), " << (a.ascii ? "ASCII" : "binary")
            << " PLY; " << tree.boundaryVoxels() << " boundary voxels at depth " << tree.depth << " built in "
            << surface.report.buildMs << " ms";
    log::info(summary.str());
    return 0;
}

}  // namespace octrace::cli
