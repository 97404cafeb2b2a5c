#include "OctreeOutput.h"

#include "octrace/build/Volume.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Timer.h"

#include <sstream>
#include <vector>

namespace octrace::cli {

void addOctreeFileOptions(OptionParser& p, OctreeFileArgs& a) {
    p.add(tableOption(model::opt::compression, [&](const std::string& v) { a.level = tableInt(model::opt::compression, v); }));
    p.add({"stats", "FILE.json", "write timings and sizes as JSON (keys: docs/user/cli.md)",
           [&](const std::string& v) { a.statsPath = v; }});
    addThreadsOption(p, a, "the file");
    addGeographicOptions(p, a.request);
    addSeriesOption(p, a.request);
    addMessageOptions(p, a);
}

OctreeOutput writeOctreeOutput(const Octree& tree, const std::string& path, int level) {
    OctreeOutput out;
    Timer t;
    const std::vector<std::uint8_t> bytes = io::encodeOctreeFile(tree, level);
    out.encodeMs = t.ms();
    io::writeFileAtomically(path, std::span<const std::uint8_t>(bytes));
    out.writeMs = t.ms();
    out.fileBytes = bytes.size();
    std::ostringstream m;
    m.precision(4);
    m << path << ": " << (tree.form == OctreeForm::Volume ? "volume" : "shell") << " octree, depth " << tree.depth << ", "
      << tree.voxels().size() << " voxels, " << tree.nodes().size() << " nodes; " << formatBytes(tree.bytes()) << " in memory, "
      << formatBytes(bytes.size()) << " on disk (" << double(bytes.size()) / double(tree.voxels().size()) << " bytes per voxel)";
    log::info(m.str());
    return out;
}

void setOctreeStats(StatsJson& js, const Octree& tree, const OctreeOutput& out, int level) {
    js.set("form", std::string(tree.form == OctreeForm::Volume ? "volume" : "shell"));
    js.set("variable", tree.fieldName());
    js.set("iso", tree.iso);
    js.set("depth", tree.depth);
    js.set("encode_ms", out.encodeMs);
    js.set("write_ms", out.writeMs);
    js.set("voxels", std::uint64_t(tree.voxels().size()));
    js.set("boundary_voxels", std::uint64_t(countVoxels(tree).boundary));
    js.set("octree_nodes", std::uint64_t(tree.nodes().size()));
    js.set("octree_bytes", std::uint64_t(tree.bytes()));
    js.set("bytes_per_voxel", tree.bytesPerVoxel());
    js.set("file_bytes", out.fileBytes);
    js.set("file_bytes_per_voxel", double(out.fileBytes) / double(tree.voxels().size()));
    js.set("compression", level);
}

}  // namespace octrace::cli
