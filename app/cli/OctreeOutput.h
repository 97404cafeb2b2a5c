#pragma once
// What the commands that write an octree file (build, csg) share: the write, its summary line
// and its keys in --stats.
#include "Options.h"
#include "StatsJson.h"
#include "SurfaceOptions.h"

#include "octrace/octree/Octree.h"

#include <cstdint>
#include <string>

namespace octrace::cli {

/// The arguments of a command that writes an octree file.
struct OctreeFileArgs : SurfaceArgs {
    std::string output, statsPath;
    int level = int(model::opt::compression.defaultValue);  // --compression
};

/// --compression, --stats, --threads, --region, --vertical-scale, --series, --max-memory,
/// --quiet, --verbose, --help.
void addOctreeFileOptions(OptionParser& p, OctreeFileArgs& a);

struct OctreeOutput {
    std::uint64_t fileBytes = 0;
    double encodeMs = 0.0, writeMs = 0.0;
};

/// Encodes `tree` at zstd `level`, writes it to `path` atomically and says so on stderr
/// (form, depth, voxels, nodes, sizes in memory and on disk).
OctreeOutput writeOctreeOutput(const Octree& tree, const std::string& path, int level);

/// The keys of an octree file written: form, variable, iso, depth, encode_ms, write_ms,
/// voxels, boundary_voxels, octree_nodes, octree_bytes, bytes_per_voxel, file_bytes,
/// file_bytes_per_voxel, compression.
void setOctreeStats(StatsJson& js, const Octree& tree, const OctreeOutput& out, int level);

}  // namespace octrace::cli
