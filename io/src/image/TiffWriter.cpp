#include "octrace/io/TiffWriter.h"

#include "image/FrameCheck.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"

#include <tiffio.h>

#include <algorithm>
#include <cstring>

namespace octrace::io {
namespace {

constexpr std::uint32_t kRowsPerStrip = 64;

// libtiff writes through these callbacks into a growing buffer (it seeks back to patch the
// header and the directory).
struct MemoryFile {
    std::vector<std::uint8_t> bytes;
    std::size_t pos = 0;
};

tmsize_t readProc(thandle_t, void*, tmsize_t) { return 0; }

tmsize_t writeProc(thandle_t h, void* data, tmsize_t size) {
    auto* f = static_cast<MemoryFile*>(h);
    try {
        if (f->pos + std::size_t(size) > f->bytes.size()) f->bytes.resize(f->pos + std::size_t(size));
    } catch (...) {
        return 0;  // libtiff reports the short write
    }
    std::memcpy(f->bytes.data() + f->pos, data, std::size_t(size));
    f->pos += std::size_t(size);
    return size;
}

toff_t seekProc(thandle_t h, toff_t off, int whence) {
    auto* f = static_cast<MemoryFile*>(h);
    std::size_t base = whence == SEEK_CUR ? f->pos : whence == SEEK_END ? f->bytes.size() : 0;
    f->pos = base + std::size_t(off);
    return toff_t(f->pos);
}

int closeProc(thandle_t) { return 0; }
toff_t sizeProc(thandle_t h) { return toff_t(static_cast<MemoryFile*>(h)->bytes.size()); }
int mapProc(thandle_t, void**, toff_t*) { return 0; }
void unmapProc(thandle_t, void*, toff_t) {}

// libtiff's messages go nowhere; failures are reported by return values.
void quiet(const char*, const char*, va_list) {}

}  // namespace

std::vector<std::uint8_t> TiffWriter::encode(const Frame& frame, const ImageWriteOptions& options) {
    detail::checkFrameForWriting(frame, "TIFF", false);
    const int channels = needsAlphaChannel(frame, options.alpha) ? 4 : 3;
    const std::vector<std::uint8_t> pixels = quantizeSrgb8(frame, channels);
    const std::uint32_t w = std::uint32_t(frame.width), h = std::uint32_t(frame.height);

    TIFFSetErrorHandler(quiet);
    TIFFSetWarningHandler(quiet);
    MemoryFile file;
    TIFF* tif = TIFFClientOpen("memory", "w", &file, readProc, writeProc, seekProc, closeProc, sizeProc, mapProc, unmapProc);
    if (!tif) throw OutputError("TIFF encoding failed: libtiff could not be initialized");
    bool ok = TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w) && TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h) &&
              TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, channels) && TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 8) &&
              TIFFSetField(tif, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT) &&
              TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG) &&
              TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB) &&
              TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE) &&
              TIFFSetField(tif, TIFFTAG_PREDICTOR, PREDICTOR_HORIZONTAL) &&
              TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, std::min(kRowsPerStrip, h));
    if (ok && options.dpi > 0)
        ok = TIFFSetField(tif, TIFFTAG_XRESOLUTION, float(options.dpi)) &&
             TIFFSetField(tif, TIFFTAG_YRESOLUTION, float(options.dpi)) &&
             TIFFSetField(tif, TIFFTAG_RESOLUTIONUNIT, RESUNIT_INCH);
    if (ok && channels == 4) {
        const std::uint16_t extra[1] = {EXTRASAMPLE_UNASSALPHA};
        ok = TIFFSetField(tif, TIFFTAG_EXTRASAMPLES, 1, extra);
    }
    const std::size_t rowBytes = std::size_t(w) * std::size_t(channels);
    std::vector<std::uint8_t> row(rowBytes);  // TIFFWriteScanline may change the row (predictor)
    for (std::uint32_t y = 0; ok && y < h; ++y) {
        std::memcpy(row.data(), pixels.data() + std::size_t(y) * rowBytes, rowBytes);
        ok = TIFFWriteScanline(tif, row.data(), y, 0) == 1;
    }
    ok = ok && TIFFWriteDirectory(tif);
    TIFFClose(tif);
    if (!ok) throw OutputError("TIFF encoding failed (libtiff)");
    return std::move(file.bytes);
}

void TiffWriter::write(const Frame& frame, const std::string& path, const ImageWriteOptions& options) {
    detail::encodeAndWrite(path, [&] { return encode(frame, options); });
}

}  // namespace octrace::io
