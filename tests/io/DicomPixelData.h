#pragma once
// The stored 16-bit pixels of an uncompressed single-frame DICOM file, found by the bytes of
// its Pixel Data element alone, without GDCM or octrace's reader: an independent reference for
// what a reader decodes and a slice shows. Enough for the real single images of
// ../shared/data/medical (explicit VR, OW, little or big endian); anything else returns empty.
#include "../FileBytes.h"
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace octrace::test {

/// `count` samples of the file's (7FE0,0010) OW element, as signed or unsigned 16-bit values.
inline std::vector<double> storedPixels16(const std::string& path, std::size_t count, bool bigEndian, bool isSigned) {
    const auto b = testutil::fileBytes<std::vector<unsigned char>>(path);
    const unsigned char le[] = {0xE0, 0x7F, 0x10, 0x00, 'O', 'W', 0x00, 0x00};
    const unsigned char be[] = {0x7F, 0xE0, 0x00, 0x10, 'O', 'W', 0x00, 0x00};
    const unsigned char* tag = bigEndian ? be : le;
    for (std::size_t at = 0; at + 12 + 2 * count <= b.size(); ++at) {
        if (std::memcmp(b.data() + at, tag, 8) != 0) continue;
        const unsigned char* l = b.data() + at + 8;
        const std::uint32_t length = bigEndian ? std::uint32_t(l[0]) << 24 | std::uint32_t(l[1]) << 16 | std::uint32_t(l[2]) << 8 | l[3]
                                               : std::uint32_t(l[3]) << 24 | std::uint32_t(l[2]) << 16 | std::uint32_t(l[1]) << 8 | l[0];
        if (length != 2 * count) continue;
        std::vector<double> out(count);
        for (std::size_t i = 0; i < count; ++i) {
            const unsigned char* p = l + 4 + 2 * i;
            const std::uint16_t u = bigEndian ? std::uint16_t(p[0] << 8 | p[1]) : std::uint16_t(p[1] << 8 | p[0]);
            out[i] = isSigned ? double(std::int16_t(u)) : double(u);
        }
        return out;
    }
    return {};
}

}  // namespace octrace::test
