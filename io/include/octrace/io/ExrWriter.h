#pragma once
/// @file ExrWriter.h
/// OpenEXR output of a Frame: colour and depth.
#include "octrace/io/ImageWriteOptions.h"
#include "octrace/render/Frame.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

/// Writes a scanline OpenEXR file with ZIP compression and the channels
///  - R, G, B, A: HALF, linear, straight alpha (Frame::rgba, rounded to the nearest half;
///    values beyond ±65504 become ±infinity),
///  - Z: FLOAT = Frame::depth exactly (distance from the camera along the ray in world units,
///    +infinity where nothing was hit).
/// Data window = display window = [0, width−1] × [0, height−1], row 0 at the top.
///
/// The bytes depend only on the frame (fixed zlib level, no time stamp, independent of
/// OpenEXR's thread count). Thread-safe: no state.
class ExrWriter {
public:
    /// The encoded file, in memory.
    /// @throws OutputError if the frame is empty or inconsistent (rgba or depth size ≠
    ///         width·height), or OpenEXR fails.
    static std::vector<std::uint8_t> encode(const Frame& frame, const ImageWriteOptions& options = {});

    /// encode() then writeFileAtomically(): `path` is either left as it was or fully written.
    /// @throws OutputError naming `path` and the reason.
    static void write(const Frame& frame, const std::string& path, const ImageWriteOptions& options = {});
};

}  // namespace octrace::io
