#pragma once
/// @file TiffWriter.h
/// 8-bit sRGB TIFF output of a Frame's colour (libtiff), for figures in publishing tools that
/// prefer TIFF. The same pixels as the PNG writer's.
#include "octrace/io/ImageWriteOptions.h"
#include "octrace/render/Frame.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

/// Writes Frame::rgba as a baseline TIFF: one strip per 64 rows, Deflate compression with the
/// horizontal predictor, RGB (or RGBA with unassociated alpha when options.alpha is set or
/// any alpha < 1, as PngWriter), each channel quantized exactly as PngWriter does
/// (linearToSrgb8, alphaTo8). No date or software tag: equal frames give identical files.
/// Thread-safe: no state.
class TiffWriter {
public:
    /// The encoded file, in memory. @throws OutputError if the frame is empty or inconsistent,
    ///         or libtiff fails.
    static std::vector<std::uint8_t> encode(const Frame& frame, const ImageWriteOptions& options = {});
    /// encode() then writeFileAtomically(). @throws OutputError naming `path` and the reason.
    static void write(const Frame& frame, const std::string& path, const ImageWriteOptions& options = {});
};

}  // namespace octrace::io
