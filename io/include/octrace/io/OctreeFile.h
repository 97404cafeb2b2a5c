#pragma once
/// @file OctreeFile.h
/// `.oct` octree files: the octree of `octrace build` (shell or volume form, with baked
/// lighting when it has some), compressed, checksummed, versioned. The byte layout is in
/// docs/dev/octree-files.md. A file round-trips exactly: the octree read back has the same
/// cells, normals, terms, per-voxel colours (optional chunk "COLR": 4 bytes a voxel, packColour
/// little endian, in the voxels' breadth-first order), CRS (optional chunk "CRS ": its text)
/// and provenance (its node pool is in breadth-first order, which may
/// differ from the order the builder left it in; indices of voxels follow the same order).
#include "octrace/octree/Octree.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace octrace::io {

/// The newest format version this build reads. It writes version 1, version 2 when the octree
/// has baked light (chunk 'LITE', which version 1 readers do not know), or version 3 when it has
/// corner values for smooth surfaces (chunk 'CRNR', which version 2 readers do not know).
inline constexpr std::uint32_t kOctreeFileVersion = 3;

/// What the header and the chunk table of a file say (octrace info).
struct OctreeFileInfo {
    std::uint32_t version = 0;
    OctreeForm form = OctreeForm::Shell;
    int depth = 0;
    dvec3 cubeOrigin{0.0};
    double cubeSide = 0.0;
    double iso = 0.0;
    bool insideBelow = false;
    std::string fieldName, fieldUnits, source;
    std::uint64_t nodes = 0, voxels = 0;
    struct Chunk {
        std::string tag;             ///< "TREE", "TERM", "NORM", "LITE", "COLR", "CRS "
        std::uint64_t rawBytes = 0;  ///< after decompression
        std::uint64_t storedBytes = 0;
    };
    std::vector<Chunk> chunks;
    std::uint64_t fileBytes = 0;
};

/// The file's bytes (what writeOctreeFile writes). `zstdLevel`: 1..22.
std::vector<std::uint8_t> encodeOctreeFile(const Octree& tree, int zstdLevel = 19);

/// Reads a file's bytes. `name` is the path for messages. Every check of the format is made
/// (magic, version, header and chunk checksums, sizes, structure, Octree::validate); what
/// fails throws FileError "NAME: <problem>" (a file of a newer format version: "written by a
/// newer octrace"), FormatNotSupported when the bytes are not an octree file at all, and
/// LimitError when the octree would need more than `memoryBudget` bytes (0 = no limit).
Octree decodeOctreeFile(std::span<const std::uint8_t> bytes, const std::string& name, std::uint64_t memoryBudget = 0,
                        OctreeFileInfo* info = nullptr);

/// Writes atomically (AtomicFile.h); OutputError on failure.
void writeOctreeFile(const std::string& path, const Octree& tree, int zstdLevel = 19);

/// Reads `path` (InputError "PATH: no such file", else as decodeOctreeFile).
Octree readOctreeFile(const std::string& path, std::uint64_t memoryBudget = 0, OctreeFileInfo* info = nullptr);

/// Header and chunk table only, all checksums verified, nothing decompressed.
OctreeFileInfo readOctreeFileInfo(const std::string& path);

/// True when the file starts with the .oct magic (a missing or short file: false).
bool isOctreeFile(const std::string& path);

/// The text `octrace info FILE.oct` prints (the whole file is read and checked, within
/// `memoryBudget` bytes, 0 = no limit).
std::string describeOctreeFile(const std::string& path, std::uint64_t memoryBudget = 0);

}  // namespace octrace::io
