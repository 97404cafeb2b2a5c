// octrace build: read a field, build the octree of an isosurface (shell) or of the solid it
// bounds (volume), and write it to an octree file (.oct) that every command reads as INPUT.
#include "Commands.h"
#include "Input.h"
#include "Options.h"
#include "StatsJson.h"
#include "SurfaceOptions.h"

#include "octrace/build/Volume.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Timer.h"

#include <sstream>

namespace octrace::cli {
namespace {

struct BuildArgs : SurfaceArgs {
    std::string output, statsPath;
    int level = 19;
};

OptionParser makeParser(BuildArgs& a) {
    OptionParser p("build", "octrace build INPUT -o OUT.oct [options]");
    p.add({"o", "FILE", "output octree file (.oct; written atomically) (required)", [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    p.add({"compression", "LEVEL", "zstd compression level of the file's chunks, 1..22 (default 19)",
           [&](const std::string& v) { a.level = parseInt("compression", v, 1, 22); }});
    p.add({"stats", "FILE.json", "write timings and sizes as JSON (keys: docs/user/cli.md)",
           [&](const std::string& v) { a.statsPath = v; }});
    addThreadsOption(p, a, "the file");
    addGeographicOptions(p, a.request);
    addSeriesOption(p, a.request);
    addMessageOptions(p, a);
    return p;
}

}  // namespace

int runBuild(const std::vector<std::string>& args) {
    BuildArgs a;
    a.keepVolume = true;
    if (!parseCommandLine(makeParser(a), args, a, a.output, "an output file: -o OUT.oct")) return 0;
    Surface s = buildSurface(a);
    Timer t;
    const std::vector<std::uint8_t> bytes = io::encodeOctreeFile(s.tree, a.level);
    const double encodeMs = t.ms();
    io::writeFileAtomically(a.output, std::span<const std::uint8_t>(bytes));
    const double writeMs = t.ms();
    const Octree& tree = s.tree;
    std::ostringstream m;
    m.precision(4);
    m << a.output << ": " << (tree.form == OctreeForm::Volume ? "volume" : "shell") << " octree, depth " << tree.depth << ", "
      << tree.voxels.size() << " voxels, " << tree.nodes.size() << " nodes; " << formatBytes(tree.bytes()) << " in memory, "
      << formatBytes(bytes.size()) << " on disk (" << double(bytes.size()) / double(tree.voxels.size()) << " bytes per voxel)";
    log::info(m.str());
    if (!a.statsPath.empty()) {
        StatsJson js;
        js.set("input", a.input);
        js.set("output", a.output);
        js.set("form", std::string(tree.form == OctreeForm::Volume ? "volume" : "shell"));
        js.set("variable", tree.fieldName);
        js.set("iso", tree.iso);
        js.set("depth", tree.depth);
        js.set("load_ms", s.loadMs);
        js.set("build_ms", s.report.buildMs);
        js.set("encode_ms", encodeMs);
        js.set("write_ms", writeMs);
        js.set("voxels", std::uint64_t(tree.voxels.size()));
        js.set("boundary_voxels", std::uint64_t(countVoxels(tree).boundary));
        js.set("octree_nodes", std::uint64_t(tree.nodes.size()));
        js.set("octree_bytes", std::uint64_t(tree.bytes()));
        js.set("bytes_per_voxel", tree.bytesPerVoxel());
        js.set("file_bytes", std::uint64_t(bytes.size()));
        js.set("file_bytes_per_voxel", double(bytes.size()) / double(tree.voxels.size()));
        js.set("compression", a.level);
        io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    }
    return 0;
}

}  // namespace octrace::cli
