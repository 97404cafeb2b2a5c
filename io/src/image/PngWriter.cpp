#include "octrace/io/PngWriter.h"

#include "image/FrameCheck.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace octrace::io {
namespace {

// Fixed so that the bytes never depend on libpng's defaults or heuristics changing. Each row
// filtered by `sub` (the difference with the pixel to the left) and deflated for runs (Z_RLE):
// renders are flat backgrounds and smooth shading, whose differences are runs of small values.
// libpng's adaptive choice among all five filters with zlib's default strategy at level 6 took
// 64-123 ms for a 1600x1200 render and this 15-25 ms, the files 9-28% larger (T, the molecule,
// CT skin and bone at their default views: 147-684 KB against 170-771 KB).
constexpr int kZlibLevel = 6;

// Everything libpng's callbacks touch. Plain data: libpng reports errors by longjmp, which
// must not cross C++ frames with destructors, so the setjmp frame below holds no such objects
// and the callbacks never let an exception escape into libpng.
struct PngSink {
    std::vector<std::uint8_t>* out = nullptr;
    bool outOfMemory = false;
    char error[256] = {};
};

void onPngError(png_structp png, png_const_charp message) {
    auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
    std::snprintf(sink->error, sizeof sink->error, "%s", message ? message : "unknown libpng error");
    std::longjmp(png_jmpbuf(png), 1);
}

void onPngWarning(png_structp, png_const_charp message) {
    log::debug(std::string("libpng: ") + (message ? message : ""));
}

void onPngWrite(png_structp png, png_bytep data, png_size_t length) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    try {
        sink->out->insert(sink->out->end(), data, data + length);
    } catch (...) {
        sink->outOfMemory = true;
    }
    if (sink->outOfMemory) png_error(png, "out of memory");  // outside the catch block
}

void onPngFlush(png_structp) {}

// Returns false with sink->error set on failure. `rows` point at height rows of
// width·channels bytes each.
bool encodeRows(png_bytep* rows, std::uint32_t width, std::uint32_t height, int channels, int dpi, PngSink* sink) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, onPngError, onPngWarning);
    if (!png) {
        std::snprintf(sink->error, sizeof sink->error, "libpng could not be initialized");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        std::snprintf(sink->error, sizeof sink->error, "libpng could not be initialized");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, sink, onPngWrite, onPngFlush);
    png_set_compression_level(png, kZlibLevel);
    png_set_compression_mem_level(png, 8);
    png_set_compression_strategy(png, Z_RLE);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(png, info, width, height, 8, channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    // sRGB chunk, plus gAMA and cHRM for readers that ignore sRGB.
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    if (dpi > 0) {
        const auto perMetre = png_uint_32(std::lround(dpi / 0.0254));
        png_set_pHYs(png, info, perMetre, perMetre, PNG_RESOLUTION_METER);
    }
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);  // no tIME, no text: nothing that changes between runs
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

std::vector<std::uint8_t> PngWriter::encode(const Frame& frame, const ImageWriteOptions& options) {
    detail::checkFrameForWriting(frame, "PNG", false);

    const int channels = needsAlphaChannel(frame, options.alpha) ? 4 : 3;
    const std::size_t w = std::size_t(frame.width);
    const std::size_t h = std::size_t(frame.height);
    std::vector<std::uint8_t> pixels = quantizeSrgb8(frame, channels);
    std::vector<png_bytep> rows(h);
    for (std::size_t y = 0; y < h; ++y) rows[y] = pixels.data() + y * w * std::size_t(channels);

    std::vector<std::uint8_t> out;
    out.reserve(pixels.size() / 2 + 1024);
    PngSink sink;
    sink.out = &out;
    if (!encodeRows(rows.data(), std::uint32_t(w), std::uint32_t(h), channels, options.dpi, &sink))
        throw OutputError(std::string("PNG encoding failed: ") + sink.error);
    return out;
}

void PngWriter::write(const Frame& frame, const std::string& path, const ImageWriteOptions& options) {
    detail::encodeAndWrite(path, [&] { return encode(frame, options); });
}

}  // namespace octrace::io
