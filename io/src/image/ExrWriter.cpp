#include "octrace/io/ExrWriter.h"

#include "image/FrameCheck.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstring>
#include <exception>

namespace octrace::io {
namespace {

// Fixed so that the bytes never depend on OpenEXR's default level (which a program may change
// globally with Imf::setDefaultZipCompressionLevel).
constexpr int kZlibLevel = 6;

// OpenEXR writes the line-offset table last and seeks back to it, so the sink is seekable.
class MemoryOStream final : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("<memory>") {}
    void write(const char c[], int n) override {
        if (n <= 0) return;
        const std::size_t end = pos_ + std::size_t(n);
        if (end > bytes_.size()) bytes_.resize(end);
        std::memcpy(bytes_.data() + pos_, c, std::size_t(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = std::size_t(pos); }
    std::vector<std::uint8_t> take() { return std::move(bytes_); }

private:
    std::vector<std::uint8_t> bytes_;
    std::size_t pos_ = 0;
};

}  // namespace

std::vector<std::uint8_t> ExrWriter::encode(const Frame& frame, const ImageWriteOptions&) {
    detail::checkFrameForWriting(frame, "EXR", true);
    const int w = frame.width;
    const int h = frame.height;

    // Converted here rather than by OpenEXR so that the rounding is Imath::half's (nearest even)
    // whatever the library version does internally.
    std::vector<Imath::half> rgba(frame.rgba.size() * 4);
    for (std::size_t i = 0; i < frame.rgba.size(); ++i)
        for (int c = 0; c < 4; ++c) rgba[4 * i + std::size_t(c)] = Imath::half(frame.rgba[i][c]);

    try {
        Imf::Header header(w, h);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.zipCompressionLevel() = kZlibLevel;
        header.lineOrder() = Imf::INCREASING_Y;
        for (const char* name : {"R", "G", "B", "A"}) header.channels().insert(name, Imf::Channel(Imf::HALF));
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));

        Imf::FrameBuffer fb;
        const std::size_t halfPixel = 4 * sizeof(Imath::half);
        char* base = reinterpret_cast<char*>(rgba.data());
        const char* names[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::HALF, base + std::size_t(c) * sizeof(Imath::half), halfPixel,
                                           halfPixel * std::size_t(w)));
        // OpenEXR only reads from the slices when writing; the const_cast is for its API.
        char* depth = reinterpret_cast<char*>(const_cast<float*>(frame.depth.data()));
        fb.insert("Z", Imf::Slice(Imf::FLOAT, depth, sizeof(float), sizeof(float) * std::size_t(w)));

        MemoryOStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(fb);
            file.writePixels(h);
        }  // the destructor writes the line-offset table
        return stream.take();
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw OutputError(std::string("EXR encoding failed: ") + e.what());
    }
}

void ExrWriter::write(const Frame& frame, const std::string& path, const ImageWriteOptions& options) {
    detail::encodeAndWrite(path, [&] { return encode(frame, options); });
}

}  // namespace octrace::io
