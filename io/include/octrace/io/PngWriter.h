#pragma once
/// @file PngWriter.h
/// 8-bit sRGB PNG output of a Frame's colour.
#include "octrace/io/ImageWriteOptions.h"
#include "octrace/render/Frame.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

/// Writes Frame::rgba (linear RGB, straight alpha) as an 8-bit PNG: RGB through the sRGB
/// transfer function (octrace::linearToSrgb8, the quantization ImageCompare measures), alpha
/// linear; an sRGB chunk (plus the gAMA/cHRM fallbacks) marks the colour space. RGBA when
/// options.alpha is set or any alpha < 1, else RGB.
///
/// The bytes depend only on the frame and the options (fixed zlib level and filters, no time
/// stamp), so equal frames give identical files. Thread-safe: no state.
class PngWriter {
public:
    /// The encoded file, in memory.
    /// @throws OutputError if the frame is empty or inconsistent (rgba size ≠ width·height),
    ///         or libpng fails.
    static std::vector<std::uint8_t> encode(const Frame& frame, const ImageWriteOptions& options = {});

    /// encode() then writeFileAtomically(): `path` is either left as it was or fully written.
    /// @throws OutputError naming `path` and the reason.
    static void write(const Frame& frame, const std::string& path, const ImageWriteOptions& options = {});
};

}  // namespace octrace::io
