// .oct octree files: layout in docs/dev/octree-files.md (keep the two in step).
#include "octrace/io/OctreeFile.h"

#include "octree/Crc32c.h"
#include "octree/VoxelNeighbours.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <system_error>
#include <filesystem>

namespace octrace::io {
namespace {

// The fuzz build checks everything but the checksums (tests/fuzz/fuzz_octree_file.cpp), so that
// mutated files reach the parser behind them. Never defined in a normal build.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kVerifyChecksums = false;
#else
constexpr bool kVerifyChecksums = true;
#endif

// "\x89OCT\r\n\x1a\n": a non-ASCII first byte (not text), CR LF and LF (line-ending
// conversions show), ^Z (stops a DOS `type`); the idea of PNG's signature.
constexpr std::uint8_t kMagic[8] = {0x89, 'O', 'C', 'T', '\r', '\n', 0x1A, '\n'};
constexpr std::size_t kPreambleBytes = 16;     // magic, version, header length
constexpr std::size_t kChunkHeadBytes = 24;    // tag, raw size, stored size, codec, reserved
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;
constexpr std::uint8_t kCodecZstd = 1;

// ---- little-endian writing -------------------------------------------------------------------
class Writer {
public:
    std::vector<std::uint8_t> bytes;
    void u8(std::uint8_t v) { bytes.push_back(v); }
    void u16(std::uint16_t v) { put(v, 2); }
    void u32(std::uint32_t v) { put(v, 4); }
    void u64(std::uint64_t v) { put(v, 8); }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void str(const std::string& s) {
        u32(std::uint32_t(s.size()));
        raw(s.data(), s.size());
    }
    void raw(const void* p, std::size_t n) {
        const auto* b = static_cast<const std::uint8_t*>(p);
        bytes.insert(bytes.end(), b, b + n);
    }
    void crcFrom(std::size_t start) { u32(detail::crc32c(bytes.data() + start, bytes.size() - start)); }

private:
    void put(std::uint64_t v, int n) {
        for (int i = 0; i < n; ++i) bytes.push_back(std::uint8_t(v >> (8 * i)));
    }
};

// ---- little-endian reading with bounds checks ------------------------------------------------
class Reader {
public:
    Reader(std::span<const std::uint8_t> b, const std::string& name, const char* what)
        : b_(b), name_(name), what_(what) {}
    std::size_t pos() const { return pos_; }
    std::size_t left() const { return b_.size() - pos_; }
    void need(std::size_t n) const {
        if (left() < n)
            throw FileError(name_ + ": truncated: " + what_ + " needs " + std::to_string(n) + " more bytes at byte " +
                            std::to_string(pos_) + ", the file has " + std::to_string(left()));
    }
    std::uint8_t u8() { return std::uint8_t(get(1)); }
    std::uint16_t u16() { return std::uint16_t(get(2)); }
    std::uint32_t u32() { return std::uint32_t(get(4)); }
    std::uint64_t u64() { return get(8); }
    double f64() { return std::bit_cast<double>(get(8)); }
    std::string str(const char* field) {
        const std::uint32_t n = u32();
        if (n > left()) throw FileError(name_ + ": header field '" + field + "' is longer than the header");
        std::string s(reinterpret_cast<const char*>(b_.data() + pos_), n);
        pos_ += n;
        return s;
    }
    std::span<const std::uint8_t> take(std::size_t n) {
        need(n);
        auto s = b_.subspan(pos_, n);
        pos_ += n;
        return s;
    }
    void setWhat(const char* w) { what_ = w; }

private:
    std::uint64_t get(int n) {
        need(std::size_t(n));
        std::uint64_t v = 0;
        for (int i = 0; i < n; ++i) v |= std::uint64_t(b_[pos_ + std::size_t(i)]) << (8 * i);
        pos_ += std::size_t(n);
        return v;
    }
    std::span<const std::uint8_t> b_;
    const std::string& name_;
    const char* what_;
    std::size_t pos_ = 0;
};

std::string hex32(std::uint32_t v) {
    std::ostringstream s;
    s << "0x" << std::hex << std::setw(8) << std::setfill('0') << v;
    return s.str();
}

/// Breadth-first: the child masks and term masks of every node, level by level (root first,
/// children in child-index order: each level in Morton order), and the voxels in that order.
struct Flattened {
    std::vector<std::uint8_t> masks, terms;
    std::vector<std::uint32_t> normals;
    std::vector<std::uint8_t> baked;  // Octree::baked() in the same order, when it has some
    std::vector<std::uint8_t> colours;  // per voxel, in the order of `normals`: 4 bytes (packColour, little endian)
    std::vector<std::uint64_t> corners;  // Octree::corners() in the same order, when it has some
    bool anyTerm = false;
};

Flattened flatten(const Octree& tree) {
    Flattened f;
    f.masks.reserve(tree.nodes().size());
    f.terms.reserve(tree.nodes().size());
    f.normals.reserve(tree.voxels().size());
    std::vector<std::uint32_t> level{0}, next;
    for (int l = 0; l < tree.depth; ++l) {
        next.clear();
        for (std::uint32_t n : level) {
            const OctreeNode& nd = tree.nodes()[n];
            f.masks.push_back(nd.childMask);
            f.terms.push_back(nd.termMask);
            f.anyTerm = f.anyTerm || nd.termMask;
            std::uint32_t slot = nd.firstChild;
            for (int c = 0; c < 8; ++c) {
                if (!(nd.childMask & (1u << c))) continue;
                if (l == tree.depth - 1) {
                    f.normals.push_back(tree.voxels()[slot].normal);
                    if (!tree.baked().empty()) f.baked.push_back(tree.baked()[slot]);
                    if (!tree.corners().empty()) f.corners.push_back(tree.corners()[slot]);
                    if (tree.hasColours())
                        for (int b = 0; b < 4; ++b) f.colours.push_back(std::uint8_t(tree.colours()[slot] >> (8 * b)));
                } else {
                    next.push_back(slot);
                }
                ++slot;
            }
        }
        level.swap(next);
    }
    return f;
}

/// The prediction of voxel i's normal from the normals before it (`normals`, in the file's order)
/// and its face neighbours (voxelNeighbours): per 16-bit octahedral component, the parallelogram
/// a + b - ab in each plane xy, xz, yz that holds the voxel's two face neighbours and their edge
/// neighbour, averaged; else the mean of its face neighbours; else the previous voxel's normal.
std::uint32_t predictNormal(std::size_t i, const std::vector<std::array<std::uint32_t, 3>>& neighbours,
                            const std::uint32_t* normals) {
    if (i == 0) return 0;
    // The neighbours at -1 along the axes of each non-empty subset s of {x, y, z} (bit a = axis
    // a): the face neighbours, then an edge neighbour where its two face neighbours are voxels
    // (the face neighbour at -a's own neighbour at -b), none at {x, y, z}.
    std::uint32_t at[8];
    for (int a = 0; a < 3; ++a) at[1 << a] = neighbours[i][std::size_t(a)];
    const auto edge = [&](int a, int b) {
        return at[1 << a] != detail::kNoNeighbour && at[1 << b] != detail::kNoNeighbour ? neighbours[at[1 << a]][std::size_t(b)]
                                                                                       : detail::kNoNeighbour;
    };
    at[3] = edge(0, 1);
    at[5] = edge(0, 2);
    at[6] = edge(1, 2);
    const auto has = [&](int s) { return at[s] != detail::kNoNeighbour; };
    const auto component = [&](int s, int h) { return std::int64_t(h ? normals[at[s]] & 0xFFFFu : normals[at[s]] >> 16); };
    std::int64_t sum[2] = {0, 0}, count = 0;
    for (int p : {3, 5, 6}) {
        const int a = p & -p, b = p - a;
        if (!(has(a) && has(b) && has(p))) continue;
        for (int h = 0; h < 2; ++h) sum[h] += std::clamp<std::int64_t>(component(a, h) + component(b, h) - component(p, h), 0, 0xFFFF);
        ++count;
    }
    if (!count)
        for (int a : {1, 2, 4})
            if (has(a)) {
                for (int h = 0; h < 2; ++h) sum[h] += component(a, h);
                ++count;
            }
    if (!count) return normals[i - 1];
    return std::uint32_t((sum[0] + count / 2) / count) << 16 | std::uint32_t((sum[1] + count / 2) / count);
}

/// Normals as 4 byte planes of zig-zagged differences to their prediction (per 16-bit
/// component): high bytes first, which are nearly all 0 on a smooth surface, so that zstd
/// packs them tightly.
std::vector<std::uint8_t> encodeNormals(const std::vector<std::uint32_t>& normals,
                                        const std::vector<std::array<std::uint32_t, 3>>& neighbours) {
    const std::size_t n = normals.size();
    std::vector<std::uint8_t> out(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t cur = normals[i], prev = predictNormal(i, neighbours, normals.data());
        for (int h = 0; h < 2; ++h) {
            const int shift = h ? 0 : 16;
            const auto d = std::int16_t(std::uint16_t(((cur >> shift) & 0xFFFFu) - ((prev >> shift) & 0xFFFFu)));
            const auto z = std::uint16_t((std::uint16_t(d) << 1) ^ std::uint16_t(d >> 15));
            out[std::size_t(2 * h) * n + i] = std::uint8_t(z >> 8);
            out[std::size_t(2 * h + 1) * n + i] = std::uint8_t(z & 0xFFu);
        }
    }
    return out;
}

std::vector<std::uint32_t> decodeNormals(const std::vector<std::uint8_t>& planes,
                                         const std::vector<std::array<std::uint32_t, 3>>& neighbours) {
    const std::size_t n = planes.size() / 4;
    std::vector<std::uint32_t> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t prev = predictNormal(i, neighbours, out.data());
        std::uint32_t cur = 0;
        for (int h = 0; h < 2; ++h) {
            const int shift = h ? 0 : 16;
            const auto z = std::uint16_t((planes[std::size_t(2 * h) * n + i] << 8) | planes[std::size_t(2 * h + 1) * n + i]);
            const auto d = std::uint16_t((z >> 1) ^ std::uint16_t(-(z & 1)));
            cur |= std::uint32_t(std::uint16_t(((prev >> shift) & 0xFFFFu) + d)) << shift;
        }
        out[i] = cur;
    }
    return out;
}

void putChunk(Writer& w, const char tag[4], const std::vector<std::uint8_t>& raw, int level) {
    std::vector<std::uint8_t> packed(ZSTD_compressBound(raw.size()));
    const std::size_t n = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), level);
    if (ZSTD_isError(n)) throw OutputError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
    const std::size_t start = w.bytes.size();
    w.raw(tag, 4);
    w.u64(raw.size());
    w.u64(n);
    w.u8(kCodecZstd);
    w.u8(0);
    w.u16(0);
    w.raw(packed.data(), n);
    w.crcFrom(start);
}

struct RawChunk {
    std::string tag;
    std::uint64_t rawBytes = 0;
    std::span<const std::uint8_t> stored;
};

/// Checks magic, version, header and every chunk's checksum; fills `info` and the chunks.
void parseFrame(std::span<const std::uint8_t> bytes, const std::string& name, OctreeFileInfo& info,
                std::vector<RawChunk>& chunks) {
    if (bytes.empty()) throw FileError(name + ": file is empty (0 bytes)");
    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
        const bool close = bytes.size() >= 4 && bytes[1] == 'O' && bytes[2] == 'C' && bytes[3] == 'T';
        if (close || bytes.size() < sizeof kMagic)
            throw FileError(name + ": not a valid octree file: its signature (first 8 bytes) is damaged or incomplete");
        throw FormatNotSupported(name + ": not an octree file (no .oct signature)");
    }
    Reader r(bytes, name, "the header");
    r.take(sizeof kMagic);
    info.version = r.u32();
    if (info.version > kOctreeFileVersion)
        throw FileError(name + ": written by a newer octrace (octree file format version " + std::to_string(info.version) +
                        "; this octrace reads versions 1 to " + std::to_string(kOctreeFileVersion) + ")");
    if (info.version == 0) throw FileError(name + ": octree file format version 0 does not exist (damaged header)");
    const std::uint32_t headerBytes = r.u32();
    if (headerBytes > kMaxHeaderBytes)
        throw FileError(name + ": header length " + std::to_string(headerBytes) + " is absurd (damaged header)");
    r.need(headerBytes + 4);
    const std::uint32_t expect = detail::crc32c(bytes.data(), kPreambleBytes + headerBytes);
    Reader h(bytes.subspan(kPreambleBytes, headerBytes), name, "the header");
    r.take(headerBytes);
    const std::uint32_t stored = r.u32();
    if (stored != expect && kVerifyChecksums)
        throw FileError(name + ": header checksum mismatch (stored " + hex32(stored) + ", computed " + hex32(expect) +
                        "): the file is damaged");
    const std::uint8_t form = h.u8();
    info.depth = h.u8();
    const std::uint16_t flags = h.u16();
    const std::uint32_t chunkCount = h.u32();
    info.nodes = h.u64();
    info.voxels = h.u64();
    for (int a = 0; a < 3; ++a) info.cubeOrigin[a] = h.f64();
    info.cubeSide = h.f64();
    info.iso = h.f64();
    info.insideBelow = (flags & 1u) != 0;
    info.fieldName = h.str("variable");
    info.fieldUnits = h.str("units");
    info.source = h.str("source");
    if (h.left() != 0) throw FileError(name + ": " + std::to_string(h.left()) + " unexpected bytes at the end of the header");
    if (form > 1) throw FileError(name + ": unknown octree form " + std::to_string(form));
    info.form = OctreeForm(form);
    if (flags & ~1u) throw FileError(name + ": unknown header flags " + std::to_string(flags));
    if (info.depth < 1 || info.depth > Octree::kMaxDepth)
        throw FileError(name + ": octree depth " + std::to_string(info.depth) + " is outside 1.." + std::to_string(Octree::kMaxDepth));
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(info.cubeOrigin[a])) throw FileError(name + ": cube origin is not finite");
    if (!(info.cubeSide > 0.0) || !std::isfinite(info.cubeSide)) throw FileError(name + ": cube side is not a positive number");
    if (!std::isfinite(info.iso)) throw FileError(name + ": iso value is not finite");
    if (info.nodes == 0 || info.nodes > 0xFFFFFFFFu || info.voxels == 0 || info.voxels > 0xFFFFFFFFu)
        throw FileError(name + ": node or voxel count out of range (" + std::to_string(info.nodes) + " nodes, " +
                        std::to_string(info.voxels) + " voxels)");
    if (chunkCount > 64) throw FileError(name + ": " + std::to_string(chunkCount) + " chunks is absurd (damaged header)");

    for (std::uint32_t i = 0; i < chunkCount; ++i) {
        r.setWhat("a chunk");
        const std::size_t start = r.pos();
        r.need(kChunkHeadBytes);
        RawChunk c;
        auto tag = r.take(4);
        c.tag.assign(reinterpret_cast<const char*>(tag.data()), 4);
        c.rawBytes = r.u64();
        const std::uint64_t storedBytes = r.u64();
        const std::uint8_t codec = r.u8();
        r.u8();
        r.u16();
        if (storedBytes > r.left() || r.left() - storedBytes < 4)
            throw FileError(name + ": truncated: chunk " + std::to_string(i + 1) + " of " + std::to_string(chunkCount) +
                            " needs " + std::to_string(storedBytes + 4) + " bytes at byte " + std::to_string(r.pos()) +
                            ", the file has " + std::to_string(r.left()));
        c.stored = r.take(std::size_t(storedBytes));
        const std::uint32_t expectChunk = detail::crc32c(bytes.data() + start, r.pos() - start);
        const std::uint32_t storedChunk = r.u32();
        if (storedChunk != expectChunk && kVerifyChecksums)
            throw FileError(name + ": checksum mismatch in chunk " + std::to_string(i + 1) + " at byte " + std::to_string(start) +
                            " (stored " + hex32(storedChunk) + ", computed " + hex32(expectChunk) + "): the file is damaged");
        if (codec != kCodecZstd) throw FileError(name + ": chunk '" + c.tag + "' has unknown compression " + std::to_string(codec));
        info.chunks.push_back({c.tag, c.rawBytes, storedBytes});
        chunks.push_back(c);
    }
    if (r.left() != 0)
        throw FileError(name + ": " + std::to_string(r.left()) + " unexpected bytes after the last chunk (at byte " +
                        std::to_string(r.pos()) + ")");
    info.fileBytes = bytes.size();
}

std::vector<std::uint8_t> inflate(const RawChunk& c, const std::string& name) {
    std::vector<std::uint8_t> out(std::size_t(c.rawBytes));
    const unsigned long long announced = ZSTD_getFrameContentSize(c.stored.data(), c.stored.size());
    if (announced != c.rawBytes)
        throw FileError(name + ": chunk '" + c.tag + "' does not decompress to its stated size");
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), c.stored.data(), c.stored.size());
    if (ZSTD_isError(n) || n != c.rawBytes)
        throw FileError(name + ": chunk '" + c.tag + "' does not decompress: " +
                        (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "wrong size"));
    return out;
}

std::vector<std::uint8_t> readAll(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not an octree file");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path + ": cannot open for reading");
    const std::streamoff size = in.tellg();
    if (size < 0) throw InputError(path + ": read error");
    std::vector<std::uint8_t> b(static_cast<std::size_t>(size));
    in.seekg(0);
    if (size > 0 && !in.read(reinterpret_cast<char*>(b.data()), size)) throw InputError(path + ": read error");
    return b;
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> detail::voxelNeighbours(const Octree& tree) {
    using Around = std::array<std::uint32_t, 3>;
    const std::vector<OctreeNode>& nodes = tree.nodes();
    if (nodes.empty()) return {};
    // Per breadth-first position p of the current level: its node, the position of its first
    // child on the next level, and its neighbours' positions at -x, -y, -z on its own level.
    std::vector<std::uint32_t> node{0}, nextNode, first;
    std::vector<Around> around{Around{kNoNeighbour, kNoNeighbour, kNoNeighbour}}, nextAround;
    for (int l = 0; l < tree.depth; ++l) {
        const bool voxelLevel = l == tree.depth - 1;
        first.resize(node.size());
        std::size_t children = 0;
        for (std::uint32_t n : node) children += octrace::detail::kPopcount8.v[nodes[n].childMask];
        nextNode.clear();
        nextAround.clear();
        if (!voxelLevel) nextNode.reserve(children);
        nextAround.reserve(children);  // exactly: a voxel's 12 bytes are most of the memory
        std::uint32_t q = 0;
        for (std::size_t p = 0; p < node.size(); ++p) {
            const OctreeNode& nd = nodes[node[p]];
            first[p] = q;
            std::uint32_t slot = nd.firstChild;
            for (unsigned c = 0; c < 8; ++c) {
                if (!(nd.childMask >> c & 1u)) continue;
                Around n;
                for (unsigned a = 0; a < 3; ++a) {
                    // Axis a is bit 2 - a of the child index (c = 4x + 2y + z). On the high side
                    // the neighbour is a sibling; on the low side, in the parent's neighbour
                    // (which precedes p, so its first child's position is known).
                    const unsigned bit = 4u >> a;
                    const std::uint32_t owner = c & bit ? std::uint32_t(p) : around[p][a];
                    const unsigned cc = c ^ bit;
                    const unsigned m = owner == kNoNeighbour ? 0u : nodes[node[owner]].childMask;
                    n[a] = m >> cc & 1u ? first[owner] + childRank(m, cc) : kNoNeighbour;
                }
                nextAround.push_back(n);
                if (!voxelLevel) nextNode.push_back(slot);
                ++slot;
                ++q;
            }
        }
        node.swap(nextNode);
        around.swap(nextAround);
    }
    return around;
}

std::vector<std::uint8_t> encodeOctreeFile(const Octree& tree, int zstdLevel) {
    if (tree.nodes().empty() || tree.voxels().empty()) throw Error("cannot write an empty octree");
    const Flattened f = flatten(tree);
    if (f.anyTerm && tree.form != OctreeForm::Volume) throw Error("a mixed-depth octree (coarse leaves, e.g. from `terrain_depth`) cannot be written to an octree file yet");
    if (!tree.baked().empty() && tree.form != OctreeForm::Shell) throw Error("baked light is kept in the shell form only");
    Writer w;
    w.raw(kMagic, sizeof kMagic);
    // Version 1 readers know no 'LITE' chunk, version 2 readers no 'CRNR'.
    w.u32(!f.corners.empty() ? 3 : f.baked.empty() ? 1 : 2);
    w.u32(0);  // header length, patched below
    const std::size_t headerStart = w.bytes.size();
    const bool withTerms = tree.form == OctreeForm::Volume;
    w.u8(std::uint8_t(tree.form));
    w.u8(std::uint8_t(tree.depth));
    w.u16(tree.insideBelow ? 1 : 0);
    w.u32(2 + (withTerms ? 1 : 0) + (f.colours.empty() ? 0 : 1) + (tree.crs().empty() ? 0 : 1) + (f.baked.empty() ? 0 : 1) +
          (f.corners.empty() ? 0 : 1));
    w.u64(tree.nodes().size());
    w.u64(tree.voxels().size());
    for (int a = 0; a < 3; ++a) w.f64(tree.cubeOrigin[a]);
    w.f64(tree.cubeSide);
    w.f64(tree.iso);
    w.str(tree.fieldName());
    w.str(tree.fieldUnits());
    w.str(tree.source());
    const auto headerBytes = std::uint32_t(w.bytes.size() - headerStart);
    for (int i = 0; i < 4; ++i) w.bytes[12 + std::size_t(i)] = std::uint8_t(headerBytes >> (8 * i));
    w.crcFrom(0);
    putChunk(w, "TREE", f.masks, zstdLevel);
    if (withTerms) putChunk(w, "TERM", f.terms, zstdLevel);
    putChunk(w, "NORM", encodeNormals(f.normals, detail::voxelNeighbours(tree)), zstdLevel);
    // Optional: per-voxel colours (city models) and the CRS of world space.
    if (!f.colours.empty()) putChunk(w, "COLR", f.colours, zstdLevel);
    if (!tree.crs().empty()) putChunk(w, "CRS ", std::vector<std::uint8_t>(tree.crs().begin(), tree.crs().end()), zstdLevel);
    if (!f.baked.empty()) putChunk(w, "LITE", f.baked, zstdLevel);
    if (!f.corners.empty()) {
        // Smooth surfaces: 8 byte planes, corner q's byte of every voxel in plane q.
        std::vector<std::uint8_t> planes(8 * f.corners.size());
        for (std::size_t i = 0; i < f.corners.size(); ++i)
            for (int q = 0; q < 8; ++q) planes[std::size_t(q) * f.corners.size() + i] = std::uint8_t(f.corners[i] >> (8 * q));
        putChunk(w, "CRNR", planes, zstdLevel);
    }
    return std::move(w.bytes);
}

Octree decodeOctreeFile(std::span<const std::uint8_t> bytes, const std::string& name, std::uint64_t memoryBudget,
                        OctreeFileInfo* infoOut) {
    OctreeFileInfo info;
    std::vector<RawChunk> chunks;
    parseFrame(bytes, name, info, chunks);
    // Which chunks: TREE and NORM once each, TERM once in the volume form only; COLR, CRS and
    // (version 2) LITE at most once.
    const RawChunk *treeChunk = nullptr, *termChunk = nullptr, *normChunk = nullptr, *colrChunk = nullptr, *crsChunk = nullptr,
                   *liteChunk = nullptr, *crnrChunk = nullptr;
    for (const RawChunk& c : chunks) {
        const RawChunk** slot = c.tag == "TREE"                          ? &treeChunk
                                : c.tag == "TERM"                        ? &termChunk
                                : c.tag == "NORM"                        ? &normChunk
                                : c.tag == "COLR"                        ? &colrChunk
                                : c.tag == "CRS "                        ? &crsChunk
                                : c.tag == "LITE" && info.version >= 2 ? &liteChunk
                                : c.tag == "CRNR" && info.version >= 3 ? &crnrChunk
                                                                         : nullptr;
        if (!slot) throw FileError(name + ": unknown chunk '" + c.tag + "'");
        if (*slot) throw FileError(name + ": chunk '" + c.tag + "' appears twice");
        *slot = &c;
    }
    if (!treeChunk || !normChunk) throw FileError(name + ": chunk '" + std::string(treeChunk ? "NORM" : "TREE") + "' is missing");
    if (termChunk && info.form != OctreeForm::Volume) throw FileError(name + ": a shell octree with a 'TERM' chunk");
    if (!termChunk && info.form == OctreeForm::Volume) throw FileError(name + ": chunk 'TERM' is missing");
    if (liteChunk && info.form != OctreeForm::Shell) throw FileError(name + ": a volume octree with a 'LITE' chunk");
    if (liteChunk && liteChunk->rawBytes != info.voxels)
        throw FileError(name + ": chunk 'LITE' does not match the header's " + std::to_string(info.voxels) + " voxels");
    if (treeChunk->rawBytes != info.nodes || (termChunk && termChunk->rawBytes != info.nodes) || normChunk->rawBytes != 4 * info.voxels)
        throw FileError(name + ": chunk sizes do not match the header's " + std::to_string(info.nodes) + " nodes and " +
                        std::to_string(info.voxels) + " voxels");
    if (crnrChunk && (info.form != OctreeForm::Shell || crnrChunk->rawBytes != 8 * info.voxels))
        throw FileError(name + ": chunk 'CRNR' holds " + std::to_string(crnrChunk->rawBytes) + " bytes, not 8 for each of the " +
                        std::to_string(info.voxels) + " voxels of a shell octree");
    if (colrChunk && colrChunk->rawBytes != 4 * info.voxels)
        throw FileError(name + ": chunk 'COLR' holds " + std::to_string(colrChunk->rawBytes) + " bytes, not 4 for each of the " +
                        std::to_string(info.voxels) + " voxels");
    if (crsChunk && crsChunk->rawBytes > 65536) throw FileError(name + ": chunk 'CRS ' is absurdly long");
    // Beside the tree: a level's positions while the normals' neighbours are found (20 bytes per
    // node) and each voxel's neighbours (12 bytes).
    const std::uint64_t need = info.nodes * (sizeof(OctreeNode) + 2 + 20) +
                               info.voxels * (sizeof(Voxel) + 12 + (colrChunk ? 4 : 0) + (crnrChunk ? 16 : 0));
    checkMemoryBudget(name + ": reading an octree of " + std::to_string(info.nodes) + " nodes and " +
                          std::to_string(info.voxels) + " voxels",
                      need, memoryBudget);

    const std::vector<std::uint8_t> masks = inflate(*treeChunk, name);
    const std::vector<std::uint8_t> terms = termChunk ? inflate(*termChunk, name) : std::vector<std::uint8_t>(masks.size(), 0);
    const std::vector<std::uint8_t> normalPlanes = inflate(*normChunk, name);
    std::vector<std::uint8_t> baked = liteChunk ? inflate(*liteChunk, name) : std::vector<std::uint8_t>{};

    Octree tree;
    tree.form = info.form;
    tree.depth = info.depth;
    tree.cubeOrigin = info.cubeOrigin;
    tree.cubeSide = info.cubeSide;
    tree.iso = info.iso;
    tree.insideBelow = info.insideBelow;
    tree.setMetadata(octree_key::kFieldName, info.fieldName);
    tree.setMetadata(octree_key::kFieldUnits, info.fieldUnits);
    tree.setMetadata(octree_key::kSource, info.source);
    std::vector<OctreeNode> nodes(std::size_t(info.nodes));
    // Breadth-first, as written: each node's children follow those of the nodes before it.
    std::uint64_t levelStart = 0, levelCount = 1, nextNode = 1, nextVoxel = 0;
    auto broken = [&](const std::string& why) { return FileError(name + ": damaged tree structure: " + why); };
    for (int level = 0; level < tree.depth; ++level) {
        if (levelStart + levelCount > info.nodes) throw broken("more nodes than the header's " + std::to_string(info.nodes));
        for (std::uint64_t k = 0; k < levelCount; ++k) {
            const std::size_t i = std::size_t(levelStart + k);
            OctreeNode& n = nodes[i];
            n.childMask = masks[i];
            n.termMask = terms[i];
            const unsigned count = octrace::detail::kPopcount8.v[n.childMask];
            std::uint64_t& next = level == tree.depth - 1 ? nextVoxel : nextNode;
            n.firstChild = std::uint32_t(next);
            next += count;
        }
        levelStart += levelCount;
        levelCount = nextNode - levelStart;
        if (nextVoxel > info.voxels) throw broken("more voxels than the header's " + std::to_string(info.voxels));
    }
    if (nextNode != info.nodes || nextVoxel != info.voxels)
        throw broken("the masks describe " + std::to_string(nextNode) + " nodes and " + std::to_string(nextVoxel) +
                     " voxels, the header " + std::to_string(info.nodes) + " and " + std::to_string(info.voxels));
    // The normals follow: their decoding needs the voxels' order, which the topology gives.
    tree.setTopology(std::move(nodes), std::vector<Voxel>(std::size_t(info.voxels)));
    try {
        tree.validate();
    } catch (const Error& e) {
        throw broken(e.what());
    }
    const std::vector<std::uint32_t> normals = decodeNormals(normalPlanes, detail::voxelNeighbours(tree));
    for (std::size_t i = 0; i < normals.size(); ++i) tree.setVoxelNormal(std::uint32_t(i), normals[i]);
    tree.setBaked(std::move(baked));  // its length was checked against the header's above
    if (crnrChunk) {
        const std::vector<std::uint8_t> planes = inflate(*crnrChunk, name);
        const std::size_t n = tree.voxels().size();
        std::vector<std::uint64_t> corners(n, 0);
        for (int q = 0; q < 8; ++q)
            for (std::size_t i = 0; i < n; ++i) corners[i] |= std::uint64_t(planes[std::size_t(q) * n + i]) << (8 * q);
        tree.setCorners(std::move(corners));
    }
    if (colrChunk) {
        // Written in breadth-first order, which is the order of the decoded voxels.
        const std::vector<std::uint8_t> c = inflate(*colrChunk, name);
        std::vector<std::uint32_t> colours(tree.voxels().size());
        for (std::size_t i = 0; i < colours.size(); ++i)
            colours[i] = std::uint32_t(c[4 * i]) | std::uint32_t(c[4 * i + 1]) << 8 | std::uint32_t(c[4 * i + 2]) << 16 |
                         std::uint32_t(c[4 * i + 3]) << 24;
        tree.setColours(std::move(colours));
    }
    if (crsChunk) {
        const std::vector<std::uint8_t> c = inflate(*crsChunk, name);
        tree.setMetadata(octree_key::kCrs, std::string(c.begin(), c.end()));
    }
    if (infoOut) *infoOut = std::move(info);
    return tree;
}

void writeOctreeFile(const std::string& path, const Octree& tree, int zstdLevel) {
    const std::vector<std::uint8_t> bytes = encodeOctreeFile(tree, zstdLevel);
    writeFileAtomically(path, std::span<const std::uint8_t>(bytes));
}

Octree readOctreeFile(const std::string& path, std::uint64_t memoryBudget, OctreeFileInfo* info) {
    const std::vector<std::uint8_t> bytes = readAll(path);
    return decodeOctreeFile(bytes, path, memoryBudget, info);
}

OctreeFileInfo readOctreeFileInfo(const std::string& path) {
    const std::vector<std::uint8_t> bytes = readAll(path);
    OctreeFileInfo info;
    std::vector<RawChunk> chunks;
    parseFrame(bytes, path, info, chunks);
    return info;
}

bool isOctreeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::uint8_t b[sizeof kMagic] = {};
    if (!in.read(reinterpret_cast<char*>(b), sizeof b)) return false;
    return std::memcmp(b, kMagic, sizeof kMagic) == 0;
}

std::string describeOctreeFile(const std::string& path, std::uint64_t memoryBudget) {
    OctreeFileInfo i;
    const Octree tree = readOctreeFile(path, memoryBudget, &i);  // every check, not only the header's
    std::ostringstream s;
    s.precision(10);
    s << path << "\n  format: octrace octree file, version " << i.version << "\n  form: "
      << (i.form == OctreeForm::Volume ? "volume (interior kept)" : "shell (boundary voxels only)") << "\n  depth: " << i.depth
      << " (" << (1u << i.depth) << " voxels per cube edge)\n  variable: " << i.fieldName << "  units: "
      << (i.fieldUnits.empty() ? "(none)" : i.fieldUnits) << "\n  iso: " << i.iso;
    if (i.form == OctreeForm::Volume) s << "  inside: value " << (i.insideBelow ? "< iso" : ">= iso");
    s << "\n  source: " << i.source << "\n  cube origin: " << i.cubeOrigin.x << ", " << i.cubeOrigin.y << ", "
      << i.cubeOrigin.z << "  side: " << i.cubeSide << "\n  nodes: " << i.nodes << "  voxels: " << i.voxels;
    s << "\n  in memory: " << formatBytes(tree.bytes()) << " (" << std::setprecision(3) << tree.bytesPerVoxel()
      << " bytes per voxel)\n  file: " << formatBytes(i.fileBytes) << " (" << double(i.fileBytes) / double(i.voxels)
      << " bytes per voxel)\n  chunks:";
    for (const auto& c : i.chunks)
        s << "\n    " << c.tag << ": " << c.rawBytes << " bytes, " << c.storedBytes << " compressed (zstd)";
    s << "\n";
    return s.str();
}

}  // namespace octrace::io
