#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <mutex>
#include <sstream>
#include <utility>

namespace octrace {

namespace {
inline float signNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }
inline std::uint32_t quant16(float v) {  // [-1,1] -> [0,65535]
    float c = std::clamp(v, -1.0f, 1.0f);
    return std::uint32_t(std::lround((c * 0.5f + 0.5f) * 65535.0f));
}
inline float dequant16(std::uint32_t q) { return float(q) / 65535.0f * 2.0f - 1.0f; }
}  // namespace

std::uint32_t packColour(vec3 srgb) {
    auto byte = [](float c) { return std::uint32_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    return byte(srgb.r) | (byte(srgb.g) << 8) | (byte(srgb.b) << 16) | 0xFF000000u;
}

vec3 unpackColour(std::uint32_t packed) {
    return vec3(float(packed & 0xFFu), float((packed >> 8) & 0xFFu), float((packed >> 16) & 0xFFu)) / 255.0f;
}

std::uint32_t encodeNormal(vec3 n) {
    float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (!(l1 > 0.0f)) return (quant16(0.0f) << 16) | quant16(0.0f);  // decodes to +z
    float x = n.x / l1, y = n.y / l1;
    if (n.z < 0.0f) {
        float ox = (1.0f - std::abs(y)) * signNotZero(x);
        float oy = (1.0f - std::abs(x)) * signNotZero(y);
        x = ox;
        y = oy;
    }
    return (quant16(x) << 16) | quant16(y);
}

vec3 decodeNormal(std::uint32_t code) {
    float x = dequant16(code >> 16), y = dequant16(code & 0xFFFFu);
    float z = 1.0f - std::abs(x) - std::abs(y);
    if (z < 0.0f) {
        float ox = (1.0f - std::abs(y)) * signNotZero(x);
        float oy = (1.0f - std::abs(x)) * signNotZero(y);
        x = ox;
        y = oy;
    }
    return glm::normalize(vec3(x, y, z));
}

namespace {
/// Throws unless `attribute` is empty or one entry per voxel.
void checkLength(const char* what, std::size_t length, std::size_t voxels) {
    if (length != 0 && length != voxels)
        throw Error(std::string("octree attribute '") + what + "' has " + std::to_string(length) +
                    " entries; it must be empty or one per voxel (" + std::to_string(voxels) + ")");
}

void checkAttributes(const VoxelAttributes& a, std::size_t voxels) {
    checkLength("colours", a.colours.size(), voxels);
    checkLength("voxel values", a.voxelValues.size(), voxels);
    checkLength("baked light", a.baked.size(), voxels);
    checkLength("voxel materials", a.voxelMaterials.size(), voxels);
    checkLength("corner values", a.corners.size(), voxels);
}

template <class T>
void keepIfLength(std::vector<T>& v, std::size_t n) {
    if (v.size() != n) v = std::vector<T>{};  // release the buffer, not only clear it
}
}  // namespace

std::uint64_t encodeCorners(const float values[8], float iso) {
    double diff[8], m = 0.0;
    for (int q = 0; q < 8; ++q) {
        diff[q] = double(values[q]) - double(iso);
        m = std::max(m, std::abs(diff[q]));
    }
    if (!(m > 0.0) || !std::isfinite(m)) return 0;
    std::uint64_t code = 0;
    for (int q = 0; q < 8; ++q) {
        long v = std::lround(127.0 * diff[q] / m);
        if (diff[q] < 0.0 && v == 0) v = -1;  // the corner's side is kept exactly
        code |= std::uint64_t(std::uint8_t(std::int8_t(v))) << (8 * q);
    }
    return code;
}

void decodeCorners(std::uint64_t code, double d[8]) {
    for (int q = 0; q < 8; ++q) d[q] = double(std::int8_t(std::uint8_t(code >> (8 * q)))) * (1.0 / 127.0);
}

std::size_t Octree::bytes() const {
    const VoxelAttributes& a = attributes_;
    return nodes_.capacity() * sizeof(OctreeNode) + voxels_.capacity() * sizeof(Voxel) +
           summaries_.capacity() * sizeof(NodeSummary) + a.colours.capacity() * sizeof(std::uint32_t) +
           a.voxelValues.capacity() * sizeof(float) + a.baked.capacity() + a.voxelMaterials.capacity() +
           a.corners.capacity() * sizeof(std::uint64_t);
}

void Octree::setTopology(std::vector<OctreeNode> nodes, std::vector<Voxel> voxels) {
    nodes_ = std::move(nodes);
    voxels_ = std::move(voxels);
    // An attribute of the old length may still be meant for the new voxels (the caller knows);
    // one of another length cannot be.
    const std::size_t n = voxels_.size();
    keepIfLength(attributes_.colours, n);
    keepIfLength(attributes_.voxelValues, n);
    keepIfLength(attributes_.baked, n);
    keepIfLength(attributes_.voxelMaterials, n);
    keepIfLength(attributes_.corners, n);
    summaries_ = std::vector<NodeSummary>{};
    forgetOccupiedCells();
}

void Octree::setColours(std::vector<std::uint32_t> colours) {
    checkLength("colours", colours.size(), voxels_.size());
    attributes_.colours = std::move(colours);
}

void Octree::setVoxelValues(std::vector<float> values) {
    checkLength("voxel values", values.size(), voxels_.size());
    attributes_.voxelValues = std::move(values);
}

void Octree::setBaked(std::vector<std::uint8_t> baked) {
    checkLength("baked light", baked.size(), voxels_.size());
    attributes_.baked = std::move(baked);
}

void Octree::setVoxelMaterials(std::vector<std::uint8_t> materials) {
    checkLength("voxel materials", materials.size(), voxels_.size());
    attributes_.voxelMaterials = std::move(materials);
}

void Octree::setAttributes(VoxelAttributes attributes) {
    checkAttributes(attributes, voxels_.size());
    attributes_ = std::move(attributes);
}

void Octree::setCorners(std::vector<std::uint64_t> corners) {
    checkLength("corner values", corners.size(), voxels_.size());
    attributes_.corners = std::move(corners);
}

VoxelAttributes Octree::takeAttributes() { return std::exchange(attributes_, VoxelAttributes{}); }

const std::string& Octree::metadata(std::string_view key) const {
    static const std::string none;
    const auto it = metadata_.find(key);
    return it == metadata_.end() ? none : it->second;
}

void Octree::setMetadata(std::string_view key, std::string value) {
    if (value.empty()) {
        if (const auto it = metadata_.find(key); it != metadata_.end()) metadata_.erase(it);
        return;
    }
    const auto it = metadata_.find(key);
    if (it != metadata_.end()) it->second = std::move(value);
    else metadata_.emplace(std::string(key), std::move(value));
}

/// What occupiedCells found last, and for which nodes (their buffer and count), depth and form.
struct Octree::OccupiedCache {
    std::mutex mutex;
    bool valid = false;
    const OctreeNode* nodes = nullptr;
    std::size_t count = 0;
    int depth = 0;
    OctreeForm form = OctreeForm::Shell;
    ivec3 lo{0}, hi{0};
};

Octree::Octree() : occupied_(std::make_unique<OccupiedCache>()) {}
Octree::Octree(Octree&&) noexcept = default;
Octree& Octree::operator=(Octree&&) noexcept = default;
Octree::~Octree() = default;

void Octree::forgetOccupiedCells() {
    if (!occupied_) return;
    const std::lock_guard<std::mutex> lock(occupied_->mutex);
    occupied_->valid = false;
}

void Octree::occupiedCells(ivec3& lo, ivec3& hi) const {
    std::unique_lock<std::mutex> lock;
    if (occupied_) {
        lock = std::unique_lock<std::mutex>(occupied_->mutex);
        const OccupiedCache& c = *occupied_;
        if (c.valid && c.nodes == nodes_.data() && c.count == nodes_.size() && c.depth == depth && c.form == form) {
            lo = c.lo;
            hi = c.hi;
            return;
        }
    }
    findOccupiedCells(lo, hi);
    if (!occupied_) return;
    OccupiedCache& c = *occupied_;
    c.valid = true;
    c.nodes = nodes_.data();
    c.count = nodes_.size();
    c.depth = depth;
    c.form = form;
    c.lo = lo;
    c.hi = hi;
}

Octree Octree::emptyCopy() const {
    Octree o;
    o.depth = depth;
    o.cubeOrigin = cubeOrigin;
    o.cubeSide = cubeSide;
    o.form = form;
    o.iso = iso;
    o.insideBelow = insideBelow;
    o.metadata_ = metadata_;
    return o;
}

Octree Octree::copy() const {
    Octree o = emptyCopy();
    o.nodes_ = nodes_;
    o.voxels_ = voxels_;
    o.summaries_ = summaries_;
    o.attributes_ = attributes_;
    return o;
}

void Octree::computeSummaries() {
    summaries_.assign(nodes_.size(), NodeSummary{});
    if (nodes_.empty()) return;
    struct Sum {
        dvec3 normal{0.0};
        double z = 0.0;
        std::uint64_t count = 0;
        std::uint32_t first = 0;
    };
    // Post-order over the tree (depth <= kMaxDepth: plain recursion).
    auto visit = [&](auto&& self, std::uint32_t node, int level, const ivec3& cell) -> Sum {
        const OctreeNode& n = nodes_[node];
        Sum s;
        std::uint32_t slot = n.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(n.childMask & (1u << c))) continue;
            const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            Sum k;
            if (level == depth - 1) {
                k.normal = dvec3(decodeNormal(voxels_[slot].normal));
                k.z = double(cc.z) + 0.5;
                k.count = 1;
                k.first = slot;
            } else if (!(n.termMask & (1u << c))) {
                k = self(self, slot, level + 1, cc);
                k.z *= double(k.count);
            } else if (form == OctreeForm::Shell) {
                // A coarse leaf: one leaf, its own summary too (a cut may stop at it).
                const std::uint32_t v = nodes_[slot].firstChild;
                k.normal = dvec3(decodeNormal(voxels_[v].normal));
                k.z = (double(cc.z) + 0.5) * std::ldexp(1.0, depth - level - 1);
                k.count = 1;
                k.first = v;
                summaries_[slot] = NodeSummary{voxels_[v].normal, 1, v, float(k.z)};
            }
            if (k.count && !s.count) s.first = k.first;
            s.normal += k.normal;
            s.z += k.z;
            s.count += k.count;
            ++slot;
        }
        NodeSummary& out = summaries_[node];
        const double len = glm::length(s.normal);
        out.normal = encodeNormal(len > 1e-12 ? vec3(s.normal / len) : vec3(0, 0, 1));
        out.voxelCount = std::uint32_t(std::min<std::uint64_t>(s.count, 0xFFFFFFFFu));
        out.firstVoxel = s.first;
        s.z = s.count ? s.z / double(s.count) : 0.0;
        out.meanZ = float(s.z);
        return s;
    };
    visit(visit, 0u, 0, ivec3(0));
}

Box3 Octree::voxelBox(const ivec3& cell) const {
    double h = voxelSize();
    Box3 b;
    b.lo = cubeOrigin + dvec3(cell) * h;
    b.hi = b.lo + dvec3(h);
    return b;
}

bool Octree::hasCoarseLeaves() const {
    if (form != OctreeForm::Shell) return false;
    for (const OctreeNode& n : nodes_)
        if (n.termMask) return true;
    return false;
}

std::uint32_t Octree::findVoxel(const ivec3& cell) const {
    const int n = 1 << depth;
    if (nodes_.empty() || cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= n || cell.y >= n || cell.z >= n)
        return 0xFFFFFFFFu;
    std::uint32_t node = 0;
    for (int level = 0; level < depth; ++level) {
        int shift = depth - 1 - level;
        int c = (((cell.x >> shift) & 1) << 2) | (((cell.y >> shift) & 1) << 1) | ((cell.z >> shift) & 1);
        const OctreeNode& nd = nodes_[node];
        if (!(nd.childMask & (1u << c))) return 0xFFFFFFFFu;
        std::uint32_t slot = nd.firstChild + childRank(nd.childMask, unsigned(c));
        if (level == depth - 1) return slot;
        if (nd.termMask & (1u << c))  // interior term: not a boundary voxel; coarse leaf: its voxel
            return form == OctreeForm::Shell ? nodes_[slot].firstChild : 0xFFFFFFFFu;
        node = slot;
    }
    return 0xFFFFFFFFu;
}

void Octree::validate() const {
    auto fail = [](const std::string& w) { throw Error("invalid octree: " + w); };
    if (depth < 1 || depth > kMaxDepth) fail("depth out of range");
    if (nodes_.empty()) fail("no root node");
    if (!(cubeSide > 0.0)) fail("cube side not positive");
    // The setters keep these; checked here too, as validate() is the one place that vouches
    // for a whole octree.
    try {
        checkAttributes(attributes_, voxels_.size());
    } catch (const Error& e) {
        fail(e.what());
    }
    if (!summaries_.empty() && summaries_.size() != nodes_.size())
        fail("node summaries (" + std::to_string(summaries_.size()) + ") do not match the nodes (" +
             std::to_string(nodes_.size()) + ")");
    std::vector<std::uint8_t> seenNode(nodes_.size(), 0), seenVoxel(voxels_.size(), 0);
    struct Item { std::uint32_t node; int level; };
    std::vector<Item> stack{{0u, 0}};
    seenNode[0] = 1;
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const OctreeNode& n = nodes_[it.node];
        if (n.termMask & ~n.childMask) fail("term bit without child bit");
        const int count = detail::kPopcount8.v[n.childMask];
        if (it.level == depth - 1) {
            if (n.termMask && form != OctreeForm::Volume) fail("interior voxel in a shell octree");
            if (std::size_t(n.firstChild) + count > voxels_.size()) fail("voxel index out of range");
            for (int i = 0; i < count; ++i) {
                if (seenVoxel[n.firstChild + i]++) fail("voxel referenced twice");
            }
            continue;
        }
        if (std::size_t(n.firstChild) + count > nodes_.size()) fail("node index out of range");
        std::uint32_t slot = n.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(n.childMask & (1u << c))) continue;
            if (seenNode[slot]++) fail("node referenced twice");
            if (!(n.termMask & (1u << c))) {
                if (nodes_[slot].childMask == 0) fail("inner node without children");
                stack.push_back({slot, it.level + 1});
            } else if (nodes_[slot].childMask != 0 || nodes_[slot].termMask != 0) {
                fail(form == OctreeForm::Volume ? "interior term with children" : "coarse leaf with children");
            } else if (form == OctreeForm::Shell) {
                const std::uint32_t v = nodes_[slot].firstChild;
                if (v >= voxels_.size()) fail("coarse leaf's voxel index out of range");
                if (seenVoxel[v]++) fail("voxel referenced twice");
            }
            ++slot;
        }
    }
    for (std::size_t i = 0; i < seenNode.size(); ++i)
        if (!seenNode[i]) fail("unreachable node");
    for (std::size_t i = 0; i < seenVoxel.size(); ++i)
        if (!seenVoxel[i]) fail("unreachable voxel");
}

}  // namespace octrace
