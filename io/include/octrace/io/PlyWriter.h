#pragma once
/// @file PlyWriter.h
/// Surfels as a PLY point cloud (Stanford polygon format, vertices only) that ParaView,
/// CloudCompare, MeshLab and VTK's vtkPLYReader open.
#include "octrace/render/Surfels.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace octrace::io {

struct PlyWriteOptions {
    /// ASCII body ("format ascii 1.0", floats in the shortest form that reads back exactly)
    /// instead of binary little-endian.
    bool ascii = false;
    /// Header comment lines (e.g. provenance), written as "comment TEXT" in this order. Line
    /// breaks in a text become spaces: a comment cannot end the header early.
    std::vector<std::string> comments;
};

/// Writes one `vertex` element per surfel, with the properties
///   float x, y, z (position), float nx, ny, nz (unit normal),
///   uchar red, green, blue, alpha (8-bit sRGB colour), float radius (disc radius),
/// in this order and surfel order, and an empty `face` element (a point cloud). Binary little-endian by default (32 bytes per vertex,
/// independent of the host's byte order). Readers that know no `radius` show it as an extra
/// scalar (CloudCompare) or ignore it.
///
/// The bytes depend only on the surfels and the options. Thread-safe: no state.
class PlyWriter {
public:
    /// The encoded file, in memory. Never throws but for std::bad_alloc.
    static std::vector<std::uint8_t> encode(std::span<const Surfel> surfels, const PlyWriteOptions& options = {});

    /// encode() then writeFileAtomically(): `path` is either left as it was or fully written.
    /// @throws OutputError naming `path` and the reason.
    static void write(std::span<const Surfel> surfels, const std::string& path, const PlyWriteOptions& options = {});
};

}  // namespace octrace::io
