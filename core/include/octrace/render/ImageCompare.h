#pragma once
/// @file ImageCompare.h
/// Quantization of linear colour to 8-bit sRGB, and the difference between two Frames as it
/// would show in the PNG files written from them. The PNG writer (io) uses the same
/// functions, so that `--verify` and the tests measure exactly what ends up on disk.
///
/// Every function here is stateless and thread-safe.
#include "octrace/render/Frame.h"

#include <cstdint>
#include <vector>

namespace octrace {

/// Linear [0,1] -> 8-bit sRGB code with the exact sRGB transfer function (linear segment below
/// 0.0031308, 1.055·c^(1/2.4) − 0.055 above), rounded to nearest (ties up). Values below 0
/// and NaN give 0, values above 1 give 255. Example: 0.5 -> 188.
std::uint8_t linearToSrgb8(float linear);

/// R, G, B through linearToSrgb8 and A through alphaTo8, packed R | G << 8 | B << 16 | A << 24
/// (one call for a pixel, for per-pixel use such as colour coherence).
std::uint32_t packSrgb8(const vec4& rgba);

/// 8-bit sRGB code -> linear value (the inverse transfer function, exact to float precision).
/// linearToSrgb8(srgb8ToLinear(k)) == k for every k.
float srgb8ToLinear(std::uint8_t code);

/// Straight alpha (or any other linear [0,1] quantity) -> 0..255, rounded to nearest, clamped;
/// NaN gives 0. Alpha is never sRGB-encoded.
std::uint8_t alphaTo8(float alpha);

/// Whether an 8-bit image of `frame` carries an alpha channel: when `forced`, or when some
/// pixel's alpha is below 1 (NaN counts as below), so that opaque renders stay RGB.
bool needsAlphaChannel(const Frame& frame, bool forced);

/// The frame's colour as 8-bit rows, top row first, `channels` (3 or 4) bytes a pixel:
/// R, G, B through linearToSrgb8 and, with 4, A through alphaTo8 — what the PNG and TIFF files
/// hold and what the studio shows. Throws UsageError for another channel count or an rgba
/// buffer that does not hold width·height pixels.
std::vector<std::uint8_t> quantizeSrgb8(const Frame& frame, int channels);

/// The same 8-bit values as quantizeSrgb8 with 4 channels, as 32-bit words A << 24 | R << 16 |
/// G << 8 | B (the layout of Qt's RGB32 and ARGB32 images), rows of `stride` bytes at `out`,
/// the rows split over `threads` threads (0: all cores). Returns whether every alpha is 255.
/// Throws UsageError as quantizeSrgb8 does, or for a stride shorter than a row.
bool packSrgb8Rows(const Frame& frame, std::uint8_t* out, std::size_t stride, int threads);

/// How far apart two images are once both are quantized as an 8-bit sRGB PNG would be
/// (RGB through linearToSrgb8, A through alphaTo8).
struct ImageDifference {
    std::uint64_t differingPixels = 0;  ///< pixels where any of R, G, B, A differs after quantization
    double psnrDb = 0.0;                ///< over R, G, B with peak 255; +infinity when identical
    double maxChannelError = 0.0;       ///< largest |difference| of any of R, G, B, A, in 0..255 units
};

/// Compares the colour of two frames (depth and hit ids are not looked at).
/// @throws UsageError if the frames differ in size or their rgba buffers do not hold
///         width·height pixels.
ImageDifference compareImages(const Frame& a, const Frame& b);

}  // namespace octrace
