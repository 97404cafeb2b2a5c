#pragma once
// A minimal PLY reader for the tests, written from the format's definition (not from
// PlyWriter): the header's lines, the vertex element's properties (float, uchar) in any
// order, other elements only when empty, and an ascii or binary_little_endian body. Used to read back what octrace writes.
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace octrace::test {

struct PlyProperty {
    std::string type, name;
};

struct PlyCloud {
    std::string format;                         // "ascii" or "binary_little_endian"
    std::vector<std::string> comments;          // without "comment "
    std::vector<PlyProperty> properties;        // of the vertex element, in order
    std::vector<std::string> emptyElements;     // elements declared with 0 items (e.g. face)
    std::vector<std::map<std::string, double>> vertices;
    std::size_t trailingBytes = 0;              // after the last vertex (binary)

    double at(std::size_t vertex, const std::string& property) const { return vertices.at(vertex).at(property); }
};

/// Parses `bytes`; throws std::runtime_error on anything it does not understand.
inline PlyCloud parsePly(const std::string& bytes) {
    PlyCloud cloud;
    std::size_t pos = 0, count = 0;
    auto nextLine = [&] {
        const std::size_t end = bytes.find('\n', pos);
        if (end == std::string::npos) throw std::runtime_error("PLY header without end_header");
        std::string line = bytes.substr(pos, end - pos);
        pos = end + 1;
        return line;
    };
    if (nextLine() != "ply") throw std::runtime_error("no 'ply' magic line");
    bool inVertex = false;
    for (std::string line = nextLine(); line != "end_header"; line = nextLine()) {
        std::istringstream in(line);
        std::string keyword;
        in >> keyword;
        if (keyword == "format") {
            std::string version;
            in >> cloud.format >> version;
            if (version != "1.0") throw std::runtime_error("PLY version " + version);
        } else if (keyword == "comment") {
            cloud.comments.push_back(line.size() > 8 ? line.substr(8) : "");
        } else if (keyword == "element") {
            std::string name;
            std::size_t n = 0;
            in >> name >> n;
            inVertex = name == "vertex";
            if (inVertex) count = n;
            else if (n != 0) throw std::runtime_error("unexpected non-empty element " + name);
            else cloud.emptyElements.push_back(name);
        } else if (keyword == "property" && !inVertex) {
            // A property of an empty element (e.g. "property list uchar int vertex_indices"): no data.
        } else if (keyword == "property") {
            PlyProperty p;
            in >> p.type >> p.name;
            if (p.type != "float" && p.type != "uchar") throw std::runtime_error("unexpected type " + p.type);
            cloud.properties.push_back(p);
        } else {
            throw std::runtime_error("unexpected header line '" + line + "'");
        }
    }
    if (cloud.format == "ascii") {
        std::istringstream in(bytes.substr(pos));
        in.imbue(std::locale::classic());
        for (std::size_t v = 0; v < count; ++v) {
            std::map<std::string, double> vertex;
            for (const auto& p : cloud.properties) {
                double value;
                if (!(in >> value)) throw std::runtime_error("ASCII body ends early");
                vertex[p.name] = value;
            }
            cloud.vertices.push_back(vertex);
        }
    } else if (cloud.format == "binary_little_endian") {
        for (std::size_t v = 0; v < count; ++v) {
            std::map<std::string, double> vertex;
            for (const auto& p : cloud.properties) {
                const std::size_t size = p.type == "float" ? 4 : 1;
                if (pos + size > bytes.size()) throw std::runtime_error("binary body ends early");
                const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + pos);
                if (size == 1) {
                    vertex[p.name] = b[0];
                } else {
                    const std::uint32_t bits = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                                               std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
                    float f;
                    std::memcpy(&f, &bits, 4);
                    vertex[p.name] = f;
                }
                pos += size;
            }
            cloud.vertices.push_back(vertex);
        }
        cloud.trailingBytes = bytes.size() - pos;
    } else {
        throw std::runtime_error("unexpected format " + cloud.format);
    }
    return cloud;
}

}  // namespace octrace::test
