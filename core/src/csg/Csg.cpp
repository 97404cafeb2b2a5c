#include "octrace/csg/Csg.h"

#include "build/TreeAssembly.h"
#include "octrace/build/Volume.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace octrace {
namespace {

using detail::Octant;

/// How much of an octant an operand holds.
enum class Cover : std::uint8_t { Empty, Full, Mixed };

constexpr float kNoValue = std::numeric_limits<float>::quiet_NaN();

/// A voxel of an operand or of the result: its state, (boundary) outward normal and the
/// attributes of its slot in a tree operand (Octree::voxelValues(), Octree::colours()).
struct VoxelState {
    CellState state = CellState::Empty;
    vec3 normal{0.0f};
    bool attributes = false;  ///< value and colour come from a voxel slot of a tree operand
    float value = kNoValue;
    std::uint32_t colour = 0;
};

/// The result's grid: cube and depth.
struct Grid {
    dvec3 origin{0.0};
    double side = 1.0;
    int depth = 1;
    double voxel() const { return side / double(1u << depth); }
    dvec3 corner(const ivec3& c) const { return origin + dvec3(c) * voxel(); }
};

constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;

/// Gives every voxel slot of `t` whose `known` flag is clear the value and colour of the
/// nearest known slot, by a breadth-first flood across face neighbours (voxels cut out of an
/// operand's interior term, which had no slot to inherit from).
void fillAttributes(Octree& t, std::vector<std::uint8_t>& known) {
    VoxelAttributes attributes = t.takeAttributes();  // edited in place, handed back below
    std::vector<ivec3> cells(t.voxels().size());
    t.forEachVoxel([&](const ivec3& c, std::uint32_t slot) { cells[slot] = c; });
    std::vector<std::uint32_t> queue;
    for (std::uint32_t i = 0; i < known.size(); ++i)
        if (known[i]) queue.push_back(i);
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t from = queue[q];
        for (int a = 0; a < 3; ++a)
            for (int d = -1; d <= 1; d += 2) {
                ivec3 nb = cells[from];
                nb[a] += d;
                std::uint32_t slot;
                if (cellSlot(t, nb, slot) == CellState::Empty || slot == kNoSlot || known[slot]) continue;
                known[slot] = 1;
                if (!attributes.voxelValues.empty()) attributes.voxelValues[slot] = attributes.voxelValues[from];
                if (!attributes.colours.empty()) attributes.colours[slot] = attributes.colours[from];
                queue.push_back(slot);
            }
    }
    t.setAttributes(std::move(attributes));
}

class Source {
public:
    virtual ~Source() = default;
    /// The octant at `level` with minimum cell c0 (result cells at the result's depth).
    virtual Cover cover(int level, const ivec3& c0) const = 0;
    /// Result voxel `cell`; `cell` may lie outside the cube (then: empty).
    virtual VoxelState voxel(const ivec3& cell) const = 0;
};

Cover coverOf(SolidCover c) { return c == SolidCover::Inside ? Cover::Full : c == SolidCover::Outside ? Cover::Empty : Cover::Mixed; }

class SolidSource final : public Source {
public:
    SolidSource(const Solid& s, const Grid& g) : s_(s), g_(g) {}
    Cover cover(int level, const ivec3& c0) const override {
        const int size = 1 << (g_.depth - level);
        return coverOf(s_.classify(g_.corner(c0), g_.corner(c0 + size)));
    }
    VoxelState voxel(const ivec3& cell) const override {
        VoxelState v;
        if (s_.convex()) {
            int inside = 0;
            for (int q = 0; q < 8; ++q) inside += s_.distance(g_.corner(cell + ivec3((q >> 2) & 1, (q >> 1) & 1, q & 1))) <= 0.0;
            v.state = inside == 8 ? CellState::Interior : inside > 0 ? CellState::Boundary : CellState::Empty;
        } else {
            // Not convex: the corners do not tell (the surface may dip into the voxel between them).
            const Cover c = coverOf(s_.classify(g_.corner(cell), g_.corner(cell + 1)));
            v.state = c == Cover::Full ? CellState::Interior : c == Cover::Mixed ? CellState::Boundary : CellState::Empty;
        }
        if (v.state == CellState::Boundary) v.normal = vec3(s_.normal(g_.corner(cell) + dvec3(0.5 * g_.voxel())));
        return v;
    }

private:
    Solid s_;
    Grid g_;
};

class TreeSource final : public Source {
public:
    TreeSource(const Octree& t, const Grid& g)
        : t_(t), g_(g), n_(1 << t.depth), values_(!t.voxelValues().empty()),
          colours_(t.hasColours()) {
        scale_ = double(n_) / t.cubeSide;
        same_ = t.depth == g.depth && t.cubeOrigin == g.origin && t.cubeSide == g.side;
    }
    Cover cover(int level, const ivec3& c0) const override {
        const int size = 1 << (g_.depth - level);
        if (same_) return range(c0, c0 + size - 1);
        // The operand's cells holding the centres of the octant's first and last voxels.
        return range(opCell(c0), opCell(c0 + size - 1));
    }
    VoxelState voxel(const ivec3& cell) const override {
        const int n = 1 << g_.depth;
        VoxelState v;
        if (cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= n || cell.y >= n || cell.z >= n) return v;
        std::uint32_t slot = 0;
        v.state = cellSlot(t_, same_ ? cell : opCell(cell), slot);
        if (v.state == CellState::Boundary) v.normal = decodeNormal(t_.voxels()[slot].normal);
        if (slot != kNoSlot && (values_ || colours_)) {
            v.attributes = true;
            if (values_) v.value = t_.voxelValues()[slot];
            if (colours_) v.colour = t_.colours()[slot];
        }
        return v;
    }

private:
    ivec3 opCell(const ivec3& cell) const {
        const dvec3 p = (g_.corner(cell) + dvec3(0.5 * g_.voxel()) - t_.cubeOrigin) * scale_;
        return ivec3(glm::floor(p));
    }
    /// Cover of the operand's inclusive cell box [lo, hi]; cells outside its cube are empty.
    Cover range(ivec3 lo, ivec3 hi) const {
        bool empty = false, full = false;
        for (int a = 0; a < 3; ++a) {
            if (lo[a] < 0 || hi[a] >= n_) empty = true;
            lo[a] = std::max(lo[a], 0);
            hi[a] = std::min(hi[a], n_ - 1);
            if (lo[a] > hi[a]) return Cover::Empty;
        }
        walk(0u, 0, ivec3(0), lo, hi, empty, full);
        if (empty && full) return Cover::Mixed;
        return full ? Cover::Full : Cover::Empty;
    }
    /// Notes what the octants of node (level, cell) overlapping [lo, hi] hold; stops once it
    /// has seen both empty and full (a boundary voxel counts as both).
    void walk(std::uint32_t node, int level, const ivec3& cell, const ivec3& lo, const ivec3& hi, bool& empty, bool& full) const {
        const OctreeNode& nd = t_.nodes()[node];
        const int shift = t_.depth - level - 1;
        std::uint32_t slot = nd.firstChild;
        for (int c = 0; c < 8 && !(empty && full); ++c) {
            const bool present = nd.childMask & (1u << c);
            const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            const ivec3 a = cc << shift, b = ((cc + 1) << shift) - 1;
            const bool overlaps = a.x <= hi.x && a.y <= hi.y && a.z <= hi.z && b.x >= lo.x && b.y >= lo.y && b.z >= lo.z;
            if (overlaps) {
                if (!present) empty = true;
                else if (nd.termMask & (1u << c)) full = true;
                else if (shift == 0) empty = full = true;  // a boundary voxel
                else walk(slot, level + 1, cc, lo, hi, empty, full);
            }
            if (present) ++slot;
        }
    }

    const Octree& t_;
    Grid g_;
    int n_;
    bool values_, colours_;
    double scale_ = 1.0;
    bool same_ = false;
};

Cover combine(Cover a, CsgOp op, Cover b) {
    switch (op) {
    case CsgOp::Union:
        if (a == Cover::Full || b == Cover::Full) return Cover::Full;
        return a == Cover::Empty && b == Cover::Empty ? Cover::Empty : Cover::Mixed;
    case CsgOp::Intersection:
        if (a == Cover::Empty || b == Cover::Empty) return Cover::Empty;
        return a == Cover::Full && b == Cover::Full ? Cover::Full : Cover::Mixed;
    case CsgOp::Difference:
        if (a == Cover::Empty || b == Cover::Full) return Cover::Empty;
        return a == Cover::Full && b == Cover::Empty ? Cover::Full : Cover::Mixed;
    }
    return Cover::Mixed;
}

vec3 sumNormal(vec3 a, vec3 b) {
    const vec3 s = a + b;
    const float l = glm::length(s);
    return l > 1e-6f ? s / l : a;
}

VoxelState intersect(const VoxelState& a, const VoxelState& b) {
    if (a.state == CellState::Empty || b.state == CellState::Empty) return {};
    if (a.state == CellState::Interior) return b;
    if (b.state == CellState::Interior) return a;
    return {CellState::Boundary, sumNormal(a.normal, b.normal)};
}

VoxelState combineStates(const VoxelState& a, CsgOp op, const VoxelState& b) {
    switch (op) {
    case CsgOp::Union:
        if (a.state == CellState::Interior || b.state == CellState::Interior) return {CellState::Interior, vec3(0.0f)};
        if (a.state == CellState::Empty) return b;
        if (b.state == CellState::Empty) return a;
        return {CellState::Boundary, sumNormal(a.normal, b.normal)};
    case CsgOp::Intersection: return intersect(a, b);
    case CsgOp::Difference: {
        VoxelState notB;
        notB.state = b.state == CellState::Empty ? CellState::Interior : b.state == CellState::Interior ? CellState::Empty : CellState::Boundary;
        notB.normal = -b.normal;
        return intersect(a, notB);
    }
    }
    return {};
}

/// The voxel of A OP B with the attributes of the first operand that holds it (never of a
/// subtracted B): a cut face keeps the value and colour of the solid it was cut from.
VoxelState combine(const VoxelState& a, CsgOp op, const VoxelState& b) {
    VoxelState r = combineStates(a, op, b);
    if (r.state == CellState::Empty) return r;
    const VoxelState* from = a.state != CellState::Empty && a.attributes                        ? &a
                             : op != CsgOp::Difference && b.state != CellState::Empty && b.attributes ? &b
                                                                                                      : nullptr;
    r.attributes = from != nullptr;
    if (from) r.value = from->value, r.colour = from->colour;
    return r;
}

class Combiner {
public:
    Combiner(const Source& a, CsgOp op, const Source& b, const Grid& g) : a_(a), b_(b), op_(op), g_(g) {}

    Octant build(int level, const ivec3& c0, OctreeNode& out) {
        const int size = 1 << (g_.depth - level);
        const Cover cover = combine(a_.cover(level, c0), op_, b_.cover(level, c0));
        if (cover == Cover::Empty) return Octant::Empty;
        const int n = 1 << g_.depth;
        const bool onFace = glm::any(glm::equal(c0, ivec3(0))) || glm::any(glm::equal(c0 + size, ivec3(n)));
        if (cover == Cover::Full && !onFace && level > 0) return Octant::Term;  // on a face: caps below
        if (level == g_.depth - 1) return leaf(c0, out);
        OctreeNode kids[8];
        Octant kinds[8];
        for (int c = 0; c < 8; ++c)
            kinds[c] = build(level + 1, c0 + (size / 2) * ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1), kids[c]);
        return pool_.node(kinds, kids, out);
    }

    detail::TreeAssembly pool_;

private:
    /// The 8 voxels at c0 from the result's states of the 4^3 cells around them.
    Octant leaf(const ivec3& c0, OctreeNode& out) {
        VoxelState s[4][4][4];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) {
                    const ivec3 cell = c0 + ivec3(i - 1, j - 1, k - 1);
                    s[i][j][k] = combine(a_.voxel(cell), op_, b_.voxel(cell));
                }
        const int n = 1 << g_.depth;
        unsigned mask = 0, interior = 0;
        Voxel vox[8];
        float vals[8];
        std::uint32_t cols[8];
        for (int c = 0; c < 8; ++c) {
            const ivec3 l(1 + ((c >> 2) & 1), 1 + ((c >> 1) & 1), 1 + (c & 1));
            const VoxelState& v = s[l.x][l.y][l.z];
            vals[c] = v.value;
            cols[c] = v.colour;
            if (v.state == CellState::Empty) continue;
            mask |= 1u << c;
            if (v.state == CellState::Boundary) {
                vox[c].normal = encodeNormal(v.normal);
                continue;
            }
            vec3 cap(0.0f);
            for (int a = 0; a < 3; ++a)
                for (int d = -1; d <= 1; d += 2) {
                    ivec3 nb = l;
                    nb[a] += d;
                    const int cell = c0[a] + nb[a] - 1;
                    if (cell < 0 || cell >= n || s[nb.x][nb.y][nb.z].state == CellState::Empty) cap[a] += float(d);
                }
            if (cap == vec3(0.0f)) interior |= 1u << c;
            else vox[c].normal = encodeNormal(glm::normalize(cap));
        }
        const Octant kind = pool_.leaf(mask, interior, vox, out, values_ ? vals : nullptr, colours_ ? cols : nullptr);
        if (kind == Octant::Node && (values_ || colours_))
            for (int c = 0; c < 8; ++c)
                if (mask & (1u << c)) {
                    const ivec3 l(1 + ((c >> 2) & 1), 1 + ((c >> 1) & 1), 1 + (c & 1));
                    known_.push_back(s[l.x][l.y][l.z].attributes);
                }
        return kind;
    }

public:
    bool values_ = false, colours_ = false;  ///< whether the result carries them (an operand does)
    std::vector<std::uint8_t> known_;        ///< per voxel slot of the result: its attributes come from an operand's slot

private:
    const Source& a_;
    const Source& b_;
    CsgOp op_;
    Grid g_;
};

Grid commonGrid(const Octree* a, const Octree* b) {
    if (!a && !b) throw UsageError("csg: at least one operand must be an octree or a field (a solid alone has no voxels)");
    for (const Octree* t : {a, b})
        if (t && t->form != OctreeForm::Volume)
            throw UsageError("csg: " + (t->source().empty() ? std::string("an operand") : t->source()) +
                             " is a shell octree; CSG needs the volume form (build it with `form` volume)");
    if (!a || !b) {
        const Octree* t = a ? a : b;
        return {t->cubeOrigin, t->cubeSide, t->depth};
    }
    if (a->cubeOrigin == b->cubeOrigin && a->cubeSide == b->cubeSide)
        return {a->cubeOrigin, a->cubeSide, std::max(a->depth, b->depth)};
    Grid g;
    const dvec3 lo = glm::min(a->cubeOrigin, b->cubeOrigin);
    const dvec3 hi = glm::max(a->cubeOrigin + dvec3(a->cubeSide), b->cubeOrigin + dvec3(b->cubeSide));
    const dvec3 ext = hi - lo;
    g.side = std::max(ext.x, std::max(ext.y, ext.z));
    g.origin = 0.5 * (lo + hi) - dvec3(0.5 * g.side);
    const double finest = std::min(a->voxelSize(), b->voxelSize());
    g.depth = std::clamp(int(std::ceil(std::log2(g.side / finest) - 1e-9)), 1, Octree::kMaxDepth);
    return g;
}

std::unique_ptr<Source> sourceOf(const CsgOperand& o, const Grid& g) {
    if (o.tree) return std::make_unique<TreeSource>(*o.tree, g);
    return std::make_unique<SolidSource>(o.solid, g);
}

std::string describe(const CsgOperand& o) { return o.tree ? o.tree->source() : o.solid.describe(); }

}  // namespace

CsgOp parseCsgOp(const std::string& name) {
    if (name == "union") return CsgOp::Union;
    if (name == "intersection" || name == "intersect") return CsgOp::Intersection;
    if (name == "difference" || name == "minus") return CsgOp::Difference;
    throw UsageError("unknown CSG operation '" + name + "' (union, intersection, difference)");
}

const char* csgOpName(CsgOp op) {
    return op == CsgOp::Union ? "union" : op == CsgOp::Intersection ? "intersection" : "difference";
}

Octree csg(const CsgOperand& a, CsgOp op, const CsgOperand& b) {
    const Grid g = commonGrid(a.tree, b.tree);
    const std::unique_ptr<Source> sa = sourceOf(a, g), sb = sourceOf(b, g);
    Octree out = (a.tree ? *a.tree : *b.tree).emptyCopy();
    out.cubeOrigin = g.origin;
    out.cubeSide = g.side;
    out.depth = g.depth;
    out.form = OctreeForm::Volume;
    std::string source(1, '(');  // (a plain "(" + string trips GCC 12's -Wrestrict)
    source += describe(a);
    source += ") ";
    source += csgOpName(op);
    source += " (";
    source += describe(b);
    source += ")";
    out.setMetadata(octree_key::kSource, std::move(source));
    Combiner c(*sa, op, *sb, g);
    for (const CsgOperand* o : {&a, &b})
        if (o->tree && !(op == CsgOp::Difference && o == &b)) {
            c.values_ |= !o->tree->voxelValues().empty();
            c.colours_ |= o->tree->hasColours();
        }
    OctreeNode root;
    const Octant kind = c.build(0, ivec3(0), root);
    if (!c.pool_.finish(kind, root, out)) throw EmptyResultError(out.source() + ": the result is empty");
    if (c.values_ || c.colours_) fillAttributes(out, c.known_);
    return out;
}

}  // namespace octrace
