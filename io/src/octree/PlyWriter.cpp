#include "octrace/io/PlyWriter.h"

#include "octrace/io/AtomicFile.h"

#include <bit>
#include <charconv>

namespace octrace::io {
namespace {

void append(std::vector<std::uint8_t>& out, std::string_view text) { out.insert(out.end(), text.begin(), text.end()); }

void appendLittleEndian(std::vector<std::uint8_t>& out, float v) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int shift = 0; shift < 32; shift += 8) out.push_back(std::uint8_t(bits >> shift));
}

void appendAscii(std::vector<std::uint8_t>& out, float v) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest exact, no locale
    out.insert(out.end(), buffer, r.ptr);
}

std::string header(std::size_t count, const PlyWriteOptions& options) {
    std::string h = "ply\nformat ";
    h += options.ascii ? "ascii" : "binary_little_endian";
    h += " 1.0\n";
    for (std::string c : options.comments) {
        for (char& ch : c)
            if (ch == '\n' || ch == '\r') ch = ' ';
        h += "comment " + c + "\n";
    }
    h += "element vertex " + std::to_string(count) + "\n";
    for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) h += std::string("property float ") + p + "\n";
    for (const char* p : {"red", "green", "blue", "alpha"}) h += std::string("property uchar ") + p + "\n";
    h += "property float radius\n";
    // No faces; the empty element is there for readers that insist on one (VTK before 8.2).
    h += "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
    return h;
}

}  // namespace

std::vector<std::uint8_t> PlyWriter::encode(std::span<const Surfel> surfels, const PlyWriteOptions& options) {
    std::vector<std::uint8_t> out;
    const std::string h = header(surfels.size(), options);
    out.reserve(h.size() + surfels.size() * (options.ascii ? 96 : 32));
    append(out, h);
    for (const Surfel& s : surfels) {
        const float floats[6] = {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z};
        if (options.ascii) {
            for (float f : floats) {
                appendAscii(out, f);
                out.push_back(' ');
            }
            for (std::uint8_t c : s.rgba) append(out, std::to_string(unsigned(c)) + " ");
            appendAscii(out, s.radius);
            out.push_back('\n');
        } else {
            for (float f : floats) appendLittleEndian(out, f);
            out.insert(out.end(), s.rgba.begin(), s.rgba.end());
            appendLittleEndian(out, s.radius);
        }
    }
    return out;
}

void PlyWriter::write(std::span<const Surfel> surfels, const std::string& path, const PlyWriteOptions& options) {
    writeFileAtomically(path, encode(surfels, options));
}

}  // namespace octrace::io
