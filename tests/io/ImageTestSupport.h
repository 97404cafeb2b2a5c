#pragma once
// Shared by the image writer tests: a scratch folder, and independent decoders (libpng,
// OpenEXR) to read back what the writers produced.
#include "../FileBytes.h"
#include <gtest/gtest.h>
#include <png.h>
#include <tiffio.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

namespace octrace::test {

/// A fresh folder per test, removed afterwards.
class ScratchDir {
public:
    ScratchDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("octrace-img-") + std::to_string(::getpid()) + "-" +
                           (info ? std::string(info->test_suite_name()) + "." + info->name() : "x");
        path_ = std::filesystem::temp_directory_path() / name;
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
        std::filesystem::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }

    /// Names of everything in the folder, sorted.
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

private:
    std::filesystem::path path_;
};

inline std::vector<std::uint8_t> readBytes(const std::string& path) {
    return testutil::fileBytes<std::vector<std::uint8_t>>(path);
}

/// A PNG as stored: channels is 3 (RGB) or 4 (RGBA), 8 bits each, no conversion applied.
struct DecodedPng {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint8_t> pixels;
    std::uint8_t at(int x, int y, int c) const {
        return pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)];
    }
};

inline DecodedPng decodePng(const std::vector<std::uint8_t>& bytes) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    DecodedPng out;
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
        ADD_FAILURE() << "libpng cannot read it: " << image.message;
        return out;
    }
    // Keep the stored layout: 8-bit, no gamma or alpha conversion.
    const bool hasAlpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    EXPECT_TRUE(image.format & PNG_FORMAT_FLAG_COLOR) << "expected a colour PNG";
    EXPECT_FALSE(image.format & PNG_FORMAT_FLAG_LINEAR) << "expected 8-bit samples";
    image.format = hasAlpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    out.width = int(image.width);
    out.height = int(image.height);
    out.channels = hasAlpha ? 4 : 3;
    out.pixels.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) {
        ADD_FAILURE() << "libpng cannot decode it: " << image.message;
        png_image_free(&image);
    }
    return out;
}

/// Whether a PNG chunk of this type is present (walks the chunk list; signature is 8 bytes).
inline bool hasPngChunk(const std::vector<std::uint8_t>& bytes, const char type[5]) {
    std::size_t pos = 8;
    while (pos + 8 <= bytes.size()) {
        std::uint32_t len = (std::uint32_t(bytes[pos]) << 24) | (std::uint32_t(bytes[pos + 1]) << 16) |
                            (std::uint32_t(bytes[pos + 2]) << 8) | std::uint32_t(bytes[pos + 3]);
        if (std::equal(type, type + 4, bytes.begin() + std::ptrdiff_t(pos + 4))) return true;
        pos += 12 + len;
    }
    return false;
}

/// An EXR read back through OpenEXR, every channel as float.
struct DecodedExr {
    int width = 0;
    int height = 0;
    Imf::Compression compression = Imf::NO_COMPRESSION;
    std::map<std::string, Imf::PixelType> channelTypes;
    std::map<std::string, std::vector<float>> channels;
    float at(const std::string& channel, int x, int y) const {
        return channels.at(channel)[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

inline DecodedExr readExr(const std::string& path) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    DecodedExr out;
    out.width = dw.max.x - dw.min.x + 1;
    out.height = dw.max.y - dw.min.y + 1;
    EXPECT_EQ(dw.min.x, 0);
    EXPECT_EQ(dw.min.y, 0);
    EXPECT_EQ(file.header().displayWindow(), dw);
    out.compression = file.header().compression();
    Imf::FrameBuffer fb;
    const std::size_t n = std::size_t(out.width) * std::size_t(out.height);
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
        out.channelTypes[it.name()] = it.channel().type;
        out.channels[it.name()].assign(n, 0.0f);
    }
    for (auto& [name, data] : out.channels)
        fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float),
                                   sizeof(float) * std::size_t(out.width)));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return out;
}

/// A TIFF as libtiff reads it, scanline by scanline (no conversion).
struct DecodedTiff {
    std::uint32_t width = 0, height = 0;
    std::uint16_t samples = 0, bits = 0, photometric = 0, extra = 0;
    std::vector<std::uint8_t> pixels;  // as stored, samples per pixel
    float dpi = 0.0f;                  // XResolution when the unit is the inch, else 0
};

inline DecodedTiff decodeTiff(const std::string& path) {
    DecodedTiff d;
    TIFF* tif = TIFFOpen(path.c_str(), "r");
    if (!tif) {
        ADD_FAILURE() << "libtiff cannot open " << path;
        return d;
    }
    TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &d.width);
    TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &d.height);
    TIFFGetField(tif, TIFFTAG_SAMPLESPERPIXEL, &d.samples);
    TIFFGetField(tif, TIFFTAG_BITSPERSAMPLE, &d.bits);
    TIFFGetField(tif, TIFFTAG_PHOTOMETRIC, &d.photometric);
    std::uint16_t* types = nullptr;
    if (TIFFGetField(tif, TIFFTAG_EXTRASAMPLES, &d.extra, &types) && d.extra == 1) d.extra = types[0] == EXTRASAMPLE_UNASSALPHA ? 1 : 99;
    std::uint16_t unit = 0;
    float xres = 0.0f;
    if (TIFFGetField(tif, TIFFTAG_XRESOLUTION, &xres) && TIFFGetFieldDefaulted(tif, TIFFTAG_RESOLUTIONUNIT, &unit) &&
        unit == RESUNIT_INCH)
        d.dpi = xres;
    d.pixels.resize(std::size_t(d.width) * d.height * d.samples);
    for (std::uint32_t y = 0; y < d.height; ++y)
        if (TIFFReadScanline(tif, d.pixels.data() + std::size_t(y) * d.width * d.samples, y, 0) != 1)
            ADD_FAILURE() << "row " << y << " unreadable";
    TIFFClose(tif);
    return d;
}

}  // namespace octrace::test
