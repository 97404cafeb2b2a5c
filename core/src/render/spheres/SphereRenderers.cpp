#include "render/spheres/SphereRenderers.h"

#include "render/spheres/VoxelTracers.h"

#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace octrace {

RenderStats Renderer::renderSpheres(const ObjectOctree&, const Camera&, const RenderSettings&, Frame&) const {
    throw UsageError("renderer " + name() + " draws voxel octrees only; sphere scenes take reference, samet or beam");
}

namespace detail {
namespace {

// The initial beams: screen tiles of whole pixels, kTileSamples x kTileSamples rays (fewer
// when a pixel holds more). A tile's beam starts at the root and meets each of its spheres'
// projections once, so the tile should be large; 64 to 128 rays a side measured fastest on the
// Figure 5 scenes at 1, 4 and 16 rays per pixel (16 pixels at 1 ray took 1.5 times as long).
constexpr int kTileSamples = 128;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Whitted shading shared by every sphere tracer. Secondary rays go by Samet's method.
class SphereShader {
public:
    SphereShader(const ObjectOctree& tree, const Camera& camera, const RenderSettings& s) : tree_(tree), s_(s) {
        dvec3 right, up, back;
        camera.basis(right, up, back);
        const dvec3 l = glm::normalize(s.lightCamera);
        light_ = glm::normalize(l.x * right + l.y * up + l.z * back);
        eps_ = tree.cubeSide * 1e-9;
        shadows_ = s.shadows.value_or(true);
    }
    /// Colour seen along a ray that found `hit` (or nothing). Reflected and transmitted rays
    /// are followed out of line, so the common case of a primary ray is inlined.
    vec3 shade(const dvec3& o, const dvec3& d, const SphereHit& hit, int depth, ObjectTraceCounters& c, std::uint64_t& secondary) const {
        if (!hit.hit()) return miss(d);
        const Sphere& sp = tree_.scene.spheres[hit.sphere];
        const dvec3 p = o + d * hit.t;
        // The hit point lies on the sphere: dividing by the radius normalises (to rounding),
        // without normalize's square root.
        dvec3 n = (p - sp.centre) * (1.0 / sp.radius);
        const bool inside = glm::dot(n, d) > 0.0;
        if (inside) n = -n;
        double lambert = std::max(0.0, glm::dot(n, light_));
        if (shadows_ && lambert > 0.0) {  // shadows_ first: the sign of lambert is not predictable
            ++secondary;
            if (traceSamet(tree_, p, light_, eps_, c).hit()) lambert = 0.0;
        }
        const vec3 local = sp.colour * float(s_.ambient + s_.diffuse * lambert);
        const Material& m = tree_.scene.materials[sp.material];
        if (depth >= s_.spheres.bounces || (m.reflect <= 0.0f && m.transmit <= 0.0f)) return local;
        return secondaries(p, d, n, inside, local, m, depth, c, secondary);
    }
    /// A ray that leaves the scene: the light's colour (white) within half a degree of the
    /// light's direction, else the background.
    vec3 miss(const dvec3& d) const { return glm::dot(d, light_) > kCosLight ? vec3(1.0f) : vec3(s_.background); }
    vec3 background() const { return vec3(s_.background); }
    /// False when no ray through the rectangle of samples x0..x1, y0..y1 can come within half
    /// a degree of the light (miss() is then the background for each): the rays lie in the
    /// circular cone around the normalised sum of the corner rays that holds the corner rays.
    bool lightMayShow(const RayGenerator& gen, int x0, int y0, int x1, int y1) const {
        const dvec3 c[4] = {gen(x0, y0).direction, gen(x1, y0).direction, gen(x0, y1).direction, gen(x1, y1).direction};
        const dvec3 axis = glm::normalize(c[0] + c[1] + c[2] + c[3]);
        double spread = 0.0;
        for (const dvec3& d : c) spread = std::max(spread, std::acos(std::clamp(glm::dot(axis, d), -1.0, 1.0)));
        const double toLight = std::acos(std::clamp(glm::dot(axis, light_), -1.0, 1.0));
        return spread > 1.4 || toLight <= spread + std::acos(kCosLight) + 1e-6;
    }

private:
    /// The share of a reflecting or transmitting material's colour that its secondary rays bring.
    [[gnu::noinline]] vec3 secondaries(const dvec3& p, const dvec3& d, const dvec3& n, bool inside, const vec3& local, const Material& m, int depth,
                                       ObjectTraceCounters& c, std::uint64_t& secondary) const {
        vec3 out = local * (1.0f - m.reflect - m.transmit);
        const dvec3 r = d - 2.0 * glm::dot(d, n) * n;
        if (m.reflect > 0.0f) out += m.reflect * follow(p, r, depth, c, secondary);
        if (m.transmit > 0.0f) {
            // Snell: eta = n1 / n2; total internal reflection sends the share along r.
            const double eta = inside ? double(m.ior) : 1.0 / double(m.ior);
            const double ci = -glm::dot(d, n), k = 1.0 - eta * eta * (1.0 - ci * ci);
            const dvec3 t = k < 0.0 ? r : glm::normalize(eta * d + (eta * ci - std::sqrt(k)) * n);
            out += m.transmit * follow(p, t, depth, c, secondary);
        }
        return out;
    }
    vec3 follow(const dvec3& p, const dvec3& d, int depth, ObjectTraceCounters& c, std::uint64_t& secondary) const {
        ++secondary;
        return shade(p, d, traceSamet(tree_, p, d, eps_, c), depth + 1, c, secondary);
    }
    static constexpr double kCosLight = 0.99996192306;  // cos(0.5 degrees)
    const ObjectOctree& tree_;
    const RenderSettings& s_;
    dvec3 light_;
    double eps_;
    bool shadows_;
};

/// Columns first .. last of a tile's row (none when first > last).
struct ColumnSpan {
    int first, last;
};

/// A box's projection on the screen, bounded by the projections of its 8 corners (pixel
/// units); not valid when the box reaches behind a perspective eye.
struct PixelBounds {
    double xLo = kInf, xHi = -kInf, yLo = kInf, yHi = -kInf;
    bool valid = false;
};
/// The pixel coordinates of a box's 8 corners; false when one is not in front of a
/// perspective eye.
bool projectCorners(const RayGenerator& gen, const Box3& b, dvec2 (&out)[8]) {
    // Camera coordinates of the low corner and of the three edges: the corners are sums.
    const dvec3 &right = gen.right(), &up = gen.up(), &back = gen.back();
    const dvec3 rel = b.lo - gen.eye(), size = b.hi - b.lo;
    const dvec3 c0(glm::dot(rel, right), glm::dot(rel, up), glm::dot(rel, back));
    const dvec3 e[3] = {size.x * dvec3(right.x, up.x, back.x), size.y * dvec3(right.y, up.y, back.y), size.z * dvec3(right.z, up.z, back.z)};
    for (int k = 0; k < 8; ++k) {
        const dvec3 p = c0 + ((k & 4) ? e[0] : dvec3(0.0)) + ((k & 2) ? e[1] : dvec3(0.0)) + ((k & 1) ? e[2] : dvec3(0.0));
        if (!gen.orthographic() && !(p.z < 0.0)) return false;
        gen.toPixel(p.x, p.y, p.z, out[k].x, out[k].y);
    }
    return true;
}
PixelBounds projectBox(const RayGenerator& gen, const Box3& b) {
    dvec2 c[8];
    if (!projectCorners(gen, b, c)) return {};
    PixelBounds o;
    for (const dvec2& p : c) {
        o.xLo = std::min(o.xLo, p.x);
        o.xHi = std::max(o.xHi, p.x);
        o.yLo = std::min(o.yLo, p.y);
        o.yHi = std::max(o.yHi, p.y);
    }
    o.valid = true;
    return o;
}

/// Counts the rays that meet the scene cube (the statistic `rays`), row by row. The rays whose
/// points on the screen meet the cube are those inside the convex hull of its 8 projected
/// corners when they all lie in front of the eye: a row's samples well inside the hull's span
/// on that row are counted, those well outside are not, and only the one or two near each end
/// get the slab test (as every sample does when the eye is inside the cube or beside it).
class CubeRayCounter {
public:
    CubeRayCounter(const RayGenerator& gen, const Box3& cube) : gen_(gen), cube_(cube) {
        dvec2 c[8];
        if (!projectCorners(gen, cube, c)) return;
        // Monotone chain over the 8 points.
        std::sort(std::begin(c), std::end(c), [](const dvec2& a, const dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
        const auto cross = [](const dvec2& o, const dvec2& a, const dvec2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
        for (int pass = 0; pass < 2; ++pass) {
            const std::size_t start = hull_.size();
            for (int n = 0; n < 8; ++n) {
                const dvec2& p = c[pass == 0 ? n : 7 - n];
                while (hull_.size() >= start + 2 && cross(hull_[hull_.size() - 2], hull_.back(), p) <= 0.0) hull_.pop_back();
                hull_.push_back(p);
            }
            hull_.pop_back();
        }
        valid_ = hull_.size() >= 3;
    }
    /// Of samples x0 .. x0 + w - 1 of sample row y: those whose rays may meet the cube,
    /// first .. last (none when first > last; every ray outside surely misses it), and the
    /// number that do.
    struct Span {
        int first, last;
        std::uint64_t meeting;
    };
    Span row(int x0, int w, int y) const {
        if (!valid_) return {x0, x0 + w - 1, countExactly(x0, x0 + w, y)};
        // The hull's span on the row's centre line.
        const double yc = y + 0.5;
        double xl = kInf, xh = -kInf;
        for (std::size_t e = 0; e < hull_.size(); ++e) {
            const dvec2 &p = hull_[e], &q = hull_[(e + 1) % hull_.size()];
            if ((p.y - yc) * (q.y - yc) > 0.0) continue;
            const double x = p.y == q.y ? p.x : p.x + (yc - p.y) * (q.x - p.x) / (q.y - p.y);
            const double x2 = p.y == q.y ? q.x : x;
            xl = std::min({xl, x, x2});
            xh = std::max({xh, x, x2});
        }
        if (!(xl <= xh)) xl = xh = -1e9;  // no span: only the band test below, on nothing
        // Sample x (centre x + 0.5) is surely in when xl + m < x + 0.5 < xh - m and surely
        // out when x + 0.5 < xl - m or > xh + m; m is far above the projection's rounding.
        constexpr double m = 1e-3;
        const auto clampX = [&](double v) { return int(std::clamp(v, double(x0) - 1.0, double(x0 + w) + 1.0)); };
        const int first = std::max(x0, clampX(std::ceil(xl - m - 0.5))), last = std::min(x0 + w - 1, clampX(std::floor(xh + m - 0.5)));
        if (first > last) return {x0, x0 - 1, 0};
        const int in0 = std::max(first, clampX(std::floor(xl + m - 0.5) + 1.0)), in1 = std::min(last, clampX(std::ceil(xh - m - 0.5) - 1.0));
        if (in0 > in1) return {first, last, countExactly(first, last + 1, y)};
        return {first, last, countExactly(first, in0, y) + std::uint64_t(in1 - in0 + 1) + countExactly(in1 + 1, last + 1, y)};
    }

private:
    std::uint64_t countExactly(int x0, int x1, int y) const {
        std::uint64_t n = 0;
        for (int x = x0; x < x1; ++x) {
            const Ray r = gen_(x, y);
            double t0, t1;
            slabInterval(cube_, r.origin, 1.0 / r.direction, r.direction, t0, t1);
            n += t0 <= t1 && t1 >= 0.0;
        }
        return n;
    }
    const RayGenerator& gen_;
    Box3 cube_;
    std::vector<dvec2> hull_;
    bool valid_ = false;
};

/// A sphere met by a tile: the rectangle of the tile's rays that may hit it, for a perspective
/// eye (every ray's origin) the terms of intersectSphereFrom, and the rays it is the nearest
/// sphere for so far.
struct SphereSlot {
    std::uint32_t sphere;
    int i0, i1, j0, j1;
    dvec3 oc;
    double c;
    std::int32_t owners;   // first entry of the list of rays whose nearest sphere so far this is (BeamScratch::owners), -1: none
    std::uint32_t ownerCount;  // entries in that list (some may be out of date)
};

/// An entry of a sphere's list of rays (row << 16 | column) and the next entry (-1: none).
struct OwnerEntry {
    std::uint32_t ray;
    std::int32_t next;
};

/// The buffers of the tile being traced on this thread, kept from tile to tile: a tile does
/// not allocate them again nor clear an array of every sphere (BeamTile puts back the slots it
/// used).
struct BeamScratch {
    std::vector<std::int32_t> slotOf;   // per sphere of the scene: its slot, -1 when none
    std::vector<SphereSlot> slots;
    std::vector<OwnerEntry> owners;     // the slots' lists of rays
    std::vector<std::uint32_t> leafMark; // per sphere of the scene: the number of the last leaf that listed it
    std::uint32_t leaf = 0;             // leaves visited on this thread
    std::vector<std::uint64_t> live;    // per row, words of bits: bit i set while ray i is not hit
    std::vector<double> nearT;          // per ray: nearest hit among the spheres tested so far
    std::vector<std::uint32_t> nearSphere;
};
BeamScratch& threadBeamScratch(std::size_t spheres) {
    thread_local BeamScratch scratch;
    if (scratch.slotOf.size() < spheres) scratch.slotOf.assign(spheres, -1);
    if (scratch.leafMark.size() < spheres) scratch.leafMark.assign(spheres, 0);
    return scratch;
}

/// Primary rays of one tile as beams (paper B): the beam is the eye and the screen rectangle
/// of its rays (a corner direction and two spanning vectors); it is cut by each node's
/// projected bounds on the way down, visited front to back, and ends where every ray of its
/// rectangle is already hit (the rays not yet hit are a bit mask per row); empty leaves only
/// move it on. A sphere is tested against the unhit rays of its projected rectangle when the
/// tile first meets it, each ray keeping its nearest hit; in an occupied leaf, a ray whose
/// nearest hit is one of the leaf's spheres and not beyond its exit from the leaf is hit
/// (intersect() says why that is the leaf rule).
class BeamTile {
public:
    /// `rays`: the tile's w x h rays, row by row, of the samples (x0 + i, y0 + j); only the
    /// columns spans[j].first .. spans[j].last of row j are traced (the others miss the scene).
    BeamTile(const ObjectOctree& tree, const RayGenerator& gen, int x0, int y0, int w, int h, const std::vector<Ray>& rays,
             const std::vector<ColumnSpan>& spans, std::vector<SphereHit>& hits, ObjectTraceCounters& c, std::uint64_t& beams)
        : tree_(tree), gen_(gen), w_(w), h_(h), rays_(rays), hits_(hits), c_(c), beams_(beams),
          x_(threadBeamScratch(tree.scene.spheres.size())) {
        // Sample (x0 + i, y0 + j) is centred on pixel coordinates (x0 + i + 0.5, y0 + j + 0.5).
        xOff_ = x0 + 0.5;
        yOff_ = y0 + 0.5;
        words_ = (w + 63) / 64;
        x_.live.resize(std::size_t(h) * std::size_t(words_));
        remaining_ = 0;
        for (int j = 0; j < h; ++j) {
            const ColumnSpan& sp = spans[std::size_t(j)];
            for (int wi = 0; wi < words_; ++wi) x_.live[std::size_t(j * words_ + wi)] = columnMask(wi, sp.first, sp.last + 1);
            remaining_ += std::size_t(std::max(0, sp.last - sp.first + 1));
        }
        x_.nearT.assign(std::size_t(w) * std::size_t(h), kInf);
        x_.nearSphere.resize(std::size_t(w) * std::size_t(h));
        x_.slots.clear();
        x_.owners.clear();
        right_ = gen.right();
        up_ = gen.up();
        back_ = gen.back();
        perspective_ = !gen.orthographic();
        eps_ = tree.cubeSide * 1e-9;
    }
    ~BeamTile() {
        for (const SphereSlot& e : x_.slots) x_.slotOf[e.sphere] = -1;
    }
    BeamTile(const BeamTile&) = delete;
    BeamTile& operator=(const BeamTile&) = delete;
    void run() {
        visit(0, 0, w_, 0, h_);
        forEachLive(0, w_, 0, h_, [&](int, int, std::size_t k) { hits_[k] = SphereHit{}; });  // the rays left miss
    }

private:
    void visit(std::uint32_t node, int i0, int i1, int j0, int j1) {
        const ObjectNode& nd = tree_.nodes[node];
        if (nd.leaf() && nd.objectCount == 0) return;  // empty: the beam only moves on
        const Box3 box = tree_.nodeBox(node);
        if (!cutToBox(box, i0, i1, j0, j1) || !anyLive(i0, i1, j0, j1)) return;
        ++beams_;
        ++c_.nodes;
        if (nd.leaf()) {
            intersect(nd, box, i0, i1, j0, j1);
            return;
        }
        // Front to back: children on the eye's side of each mid-plane first (for parallel
        // rays, the side the rays come from).
        unsigned mask = 0;
        const dvec3 mid = box.centre();
        for (int a = 0; a < 3; ++a) {
            const bool high = perspective_ ? (gen_.eye()[a] > mid[a]) : (-back_[a] < 0.0);
            if (high) mask |= 4u >> a;
        }
        for (unsigned k = 0; k < 8 && remaining_ > 0; ++k) visit(nd.firstChild + (k ^ mask), i0, i1, j0, j1);
    }

    /// Narrows [i0,i1) x [j0,j1) to the rays whose samples lie within [pxLo, pxHi] x [pyLo, pyHi]
    /// (pixel units) widened by kMargin. False when none is left.
    bool cutToPixels(double pxLo, double pxHi, double pyLo, double pyHi, int& i0, int& i1, int& j0, int& j1) const {
        // Sample i is inside when xOff_ + i >= pxLo - kMargin and <= pxHi + kMargin; the
        // clamps keep far-off bounds (a box grazing the eye plane) in int range.
        const auto first = [](double lo, int n) { return int(std::ceil(std::clamp(lo, -1.0, double(n) + 1.0))); };
        const auto last = [](double hi, int n) { return int(std::floor(std::clamp(hi, -2.0, double(n)))) + 1; };
        i0 = std::max(i0, first(pxLo - kMargin - xOff_, w_));
        i1 = std::min(i1, last(pxHi + kMargin - xOff_, w_));
        j0 = std::max(j0, first(pyLo - kMargin - yOff_, h_));
        j1 = std::min(j1, last(pyHi + kMargin - yOff_, h_));
        return i0 < i1 && j0 < j1;
    }

    /// Cuts the rectangle to the box's projected bounds; a box reaching behind a perspective
    /// eye does not cut. False when no ray is left.
    bool cutToBox(const Box3& b, int& i0, int& i1, int& j0, int& j1) const {
        const PixelBounds p = projectBox(gen_, b);
        return !p.valid || cutToPixels(p.xLo, p.xHi, p.yLo, p.yHi, i0, i1, j0, j1);
    }

    /// The tile's rays that may hit sphere s: within its projected bounds, taken from its box
    /// in camera coordinates (centre -+ radius on each camera axis), divided by the nearest
    /// and farthest depth as the sign requires. False when none.
    bool sphereRect(const Sphere& s, int& i0, int& i1, int& j0, int& j1) const {
        const dvec3 rel = s.centre - gen_.eye();
        const double r = s.radius * (1.0 + 1e-12);  // the camera axes are unit up to rounding
        const double cx = glm::dot(rel, right_), cy = glm::dot(rel, up_), cz = glm::dot(rel, back_);
        double x[2], y[2];
        if (perspective_) {
            const double nearW = -cz - r, farW = -cz + r;  // depth in front of the eye
            if (!(nearW > 0.0)) return true;               // reaches behind the eye: every ray
            const double xl = cx - r, xh = cx + r, yl = cy - r, yh = cy + r;
            gen_.toPixel(xl / (xl >= 0.0 ? farW : nearW), yl / (yl >= 0.0 ? farW : nearW), -1.0, x[0], y[0]);
            gen_.toPixel(xh / (xh >= 0.0 ? nearW : farW), yh / (yh >= 0.0 ? nearW : farW), -1.0, x[1], y[1]);
        } else {
            gen_.toPixel(cx - r, cy - r, cz, x[0], y[0]);
            gen_.toPixel(cx + r, cy + r, cz, x[1], y[1]);
        }
        return cutToPixels(std::min(x[0], x[1]), std::max(x[0], x[1]), std::min(y[0], y[1]), std::max(y[0], y[1]), i0, i1, j0, j1);
    }

    /// The tile's slot of a sphere, made the first time the tile meets it; nullptr when no ray
    /// of the tile can hit it.
    SphereSlot* slot(std::uint32_t sphere) {
        std::int32_t& k = x_.slotOf[sphere];
        if (k < 0) {
            const Sphere& s = tree_.scene.spheres[sphere];
            SphereSlot e{sphere, 0, w_, 0, h_, dvec3(0.0), 0.0, -1, 0};
            if (!sphereRect(s, e.i0, e.i1, e.j0, e.j1)) e.i0 = e.i1 = 0;
            e.oc = s.centre - gen_.eye();
            e.c = glm::dot(e.oc, e.oc) - s.radius * s.radius;
            k = std::int32_t(x_.slots.size());
            x_.slots.push_back(e);
            if (e.i0 < e.i1) testAll(x_.slots.back());
        }
        SphereSlot& e = x_.slots[std::size_t(k)];
        return e.i0 < e.i1 ? &e : nullptr;
    }

    /// Bits of the columns [i0, i1) in word wi of a row.
    static std::uint64_t columnMask(int wi, int i0, int i1) {
        const int lo = std::max(i0 - wi * 64, 0), hi = std::min(i1 - wi * 64, 64);
        if (lo >= hi) return 0;
        const std::uint64_t upto = hi == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << hi) - 1;
        return upto & ~((std::uint64_t(1) << lo) - 1);
    }
    bool anyLive(int i0, int i1, int j0, int j1) const {
        for (int j = j0; j < j1; ++j)
            for (int wi = i0 / 64; wi <= (i1 - 1) / 64; ++wi)
                if (x_.live[std::size_t(j * words_ + wi)] & columnMask(wi, i0, i1)) return true;
        return false;
    }

    /// Tests sphere e against every ray of its rectangle not yet hit, the first time the tile
    /// meets the sphere; each ray keeps its nearest hit (ties to the lower sphere number).
    void testAll(SphereSlot& e) {
        const Sphere& sp = tree_.scene.spheres[e.sphere];
        if (!perspective_) {
            forEachLive(e.i0, e.i1, e.j0, e.j1, [&](int i, int j, std::size_t k) {
                const Ray& r = rays_[k];
                keepNearer(e, i, j, k, intersectSphere(sp, r.origin, r.direction, 0.0));
            });
            return;
        }
        // Every ray starts at the eye, so a hit of the sphere lies at least |oc| - r along it.
        // intersectSphereFrom's t falls short of that by less than 1e-7 (|oc| + r): the square
        // root's argument carries a few roundings of |oc|^2 and the direction's length differs
        // from 1 by rounding, which move the root by at most about the square root of their size
        // (4e-8 and 3e-8 of |oc| + r), near a tangent too. So a ray whose nearest hit so far lies
        // nearer than `beyond` keeps it whatever the test would say (no tie either), and the
        // test is not made (docs/dev/spheres.md).
        const double distance = glm::length(e.oc);
        const double beyond = distance - sp.radius - 1e-6 * (distance + sp.radius);
        forEachLive(e.i0, e.i1, e.j0, e.j1, [&](int i, int j, std::size_t k) {
            if (x_.nearT[k] < beyond) return;
            keepNearer(e, i, j, k, intersectSphereFrom(e.oc, e.c, rays_[k].direction, 0.0));
        });
    }
    /// Ray (i, j) (index k) meets sphere e at t: kept when nearer than its nearest hit so far.
    void keepNearer(SphereSlot& e, int i, int j, std::size_t k, double t) {
        ++c_.intersections;
        std::vector<double>& nearT = x_.nearT;
        if (t < nearT[k] || (t == nearT[k] && t != kInf && e.sphere < x_.nearSphere[k])) {
            nearT[k] = t;
            x_.nearSphere[k] = e.sphere;
            x_.owners.push_back({std::uint32_t(j) << 16 | std::uint32_t(i), e.owners});
            e.owners = std::int32_t(x_.owners.size() - 1);
            ++e.ownerCount;
        }
    }

    /// Calls f(i, j, k) for each ray not yet hit in columns [i0, i1) of rows [j0, j1) (k: its
    /// index in the tile); f may mark the ray hit.
    template <class F>
    void forEachLive(int i0, int i1, int j0, int j1, F&& f) {
        for (int j = j0; j < j1; ++j)
            for (int wi = i0 / 64; wi <= (i1 - 1) / 64; ++wi)
                for (std::uint64_t m = x_.live[std::size_t(j * words_ + wi)] & columnMask(wi, i0, i1); m; m &= m - 1) {
                    const int i = wi * 64 + std::countr_zero(m);
                    f(i, j, std::size_t(j) * std::size_t(w_) + std::size_t(i));
                }
    }

    /// Ray (i, j) (index k) hits `sphere` at its nearest t.
    void markHit(int i, int j, std::size_t k, std::uint32_t sphere) {
        hits_[k] = SphereHit{x_.nearT[k], sphere};
        x_.live[std::size_t(j * words_ + i / 64)] &= ~(std::uint64_t(1) << (i % 64));
        --remaining_;
    }

    // The leaf rule (nearestInLeaf: per leaf, the nearest hit among its spheres, ties to the
    // earlier in its list, kept when not beyond the ray's exit from the leaf), for the beam's
    // rays not yet hit, found another way. Each sphere is tested once per ray, when the tile
    // first meets it (testAll), and each ray keeps its nearest hit over the spheres tested so
    // far. At a leaf the ray crosses, every sphere of the leaf has been tested (the leaf's new
    // ones are tested first), so when that nearest hit is not beyond the leaf's exit it is the
    // leaf rule's hit: a nearer hit of a sphere in the leaf would be the ray's nearest, and a hit
    // not beyond the exit lies in this leaf or one before it on the ray, whose spheres have been
    // tested as well. Ties go to the lower sphere number, the leaf lists' order (ascending, as
    // ObjectOctree::validate checks). So a leaf checks its rectangle's unhit rays whose nearest
    // sphere so far is one of its own. They are found either from each sphere's list of the
    // rays it is nearest for, or by scanning the leaf's rectangle for rays whose nearest sphere
    // is marked with the leaf's number, whichever has fewer rays to look at (a large sphere of
    // many leaves has a long list, most of it outside any one leaf).
    void intersect(const ObjectNode& leaf, const Box3& box, int i0, int i1, int j0, int j1) {
        const std::uint32_t* list = tree_.objects.data() + leaf.firstObject;
        if (++x_.leaf == 0) {  // the numbers wrapped around: forget the old marks
            std::fill(x_.leafMark.begin(), x_.leafMark.end(), 0u);
            x_.leaf = 1;
        }
        std::size_t listed = 0;
        for (std::uint32_t q = 0; q < leaf.objectCount; ++q) {
            const SphereSlot* e = slot(list[q]);  // tests the spheres met for the first time
            if (e) listed += e->ownerCount;
            x_.leafMark[list[q]] = x_.leaf;
        }
        if (listed <= std::size_t(i1 - i0) * std::size_t(j1 - j0)) {
            for (std::uint32_t q = 0; q < leaf.objectCount && remaining_ > 0; ++q)
                if (SphereSlot* e = slot(list[q])) checkOwners(*e, box, i0, i1, j0, j1);
            return;
        }
        forEachLive(i0, i1, j0, j1, [&](int i, int j, std::size_t k) {
            const double t = x_.nearT[k];
            if (t != kInf && x_.leafMark[x_.nearSphere[k]] == x_.leaf && inLeaf(box, rays_[k], t)) markHit(i, j, k, x_.nearSphere[k]);
        });
    }

    /// The rays sphere e is nearest for, inside the leaf's rectangle: hit where the leaf rule
    /// says so. Entries out of date (ray hit, or nearer to another sphere since) are dropped.
    void checkOwners(SphereSlot& e, const Box3& box, int i0, int i1, int j0, int j1) {
        std::int32_t* link = &e.owners;
        while (*link >= 0) {
            OwnerEntry& en = x_.owners[std::size_t(*link)];
            const int i = int(en.ray & 0xffff), j = int(en.ray >> 16);
            const std::size_t k = std::size_t(j) * std::size_t(w_) + std::size_t(i);
            const bool live = (x_.live[std::size_t(j * words_ + i / 64)] >> (i % 64)) & 1u;
            if (!live || x_.nearSphere[k] != e.sphere) {
                *link = en.next;
                --e.ownerCount;
                continue;
            }
            if (i >= i0 && i < i1 && j >= j0 && j < j1 && inLeaf(box, rays_[k], x_.nearT[k])) {
                markHit(i, j, k, e.sphere);
                *link = en.next;
                --e.ownerCount;
                continue;
            }
            link = &en.next;
        }
    }

    /// The leaf rule's last test: the ray crosses the leaf and its hit at t is not beyond the
    /// leaf's exit (slab test, as nearestInLeaf's callers). The divisions of the slab test are
    /// spared when the hit point lies inside the leaf, or beyond one of its exit faces, by far
    /// more than rounding (eps_): the slab test could not say otherwise.
    bool inLeaf(const Box3& box, const Ray& r, double t) const {
        const dvec3 p = r.origin + r.direction * t;
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
            if (r.direction[a] > 0.0 ? p[a] > box.hi[a] + eps_ : r.direction[a] < 0.0 && p[a] < box.lo[a] - eps_) return false;
            inside = inside && p[a] > box.lo[a] + eps_ && p[a] < box.hi[a] - eps_;
        }
        if (inside) return true;
        double t0, t1;
        slabInterval(box, r.origin, 1.0 / r.direction, r.direction, t0, t1);
        return !(t0 > t1 || t1 < 0.0 || t > t1);
    }

    static constexpr double kMargin = 1e-6;  // pixels; the projection's rounding is far below
    const ObjectOctree& tree_;
    const RayGenerator& gen_;
    int w_, h_;
    const std::vector<Ray>& rays_;
    std::vector<SphereHit>& hits_;
    ObjectTraceCounters& c_;
    std::uint64_t& beams_;
    BeamScratch& x_;
    double xOff_ = 0.0, yOff_ = 0.0;
    int words_ = 1;
    std::size_t remaining_ = 0;
    dvec3 right_, up_, back_;
    bool perspective_ = true;
    double eps_ = 0.0;  // scene units: far above the rounding of a point on a ray in the cube
};

}  // namespace

RenderStats renderSphereScene(SphereTracer tracer, const std::string& name, const ObjectOctree& tree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame) {
    camera.validate();
    if (settings.spheres.bounces < 0) throw UsageError("`bounces` must be >= 0");
    const int s = samplesPerSide(settings.spheres.samples);
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every field of every pixel is written below
    const bool streamColours = reinterpret_cast<std::uintptr_t>(frame.rgba.data()) % 16 == 0;
    // The rays: the pixel grid of a camera s times finer (sample (x*s+a, y*s+b) of pixel (x, y)).
    Camera sampleCamera = camera;
    sampleCamera.width = camera.width * s;
    sampleCamera.height = camera.height * s;
    const RayGenerator gen(sampleCamera);
    const SphereShader shader(tree, camera, settings);
    const Box3 cube = tree.cube();
    const CubeRayCounter cubeRays(gen, cube);
    const int tilePixels = std::max(1, kTileSamples / s);
    const int tilesX = (camera.width + tilePixels - 1) / tilePixels, tilesY = (camera.height + tilePixels - 1) / tilePixels;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * std::size_t(tilesY));
    parallelFor(tileStats.size(), settings.threads, [&](std::size_t t) {
        RenderStats& st = tileStats[t];
        const int px0 = int(t % std::size_t(tilesX)) * tilePixels, py0 = int(t / std::size_t(tilesX)) * tilePixels;
        const int px1 = std::min(px0 + tilePixels, camera.width), py1 = std::min(py0 + tilePixels, camera.height);
        const int sx0 = px0 * s, sy0 = py0 * s, w = (px1 - px0) * s, h = (py1 - py0) * s;
        // The tile's rays and hits, in buffers kept per thread (a tile holds up to 786 KB of
        // rays: allocated per tile, every tile would fault its pages in).
        // Only the rays that may meet the scene cube are made and traced (on the ray-traced
        // scenes of Figure 5, most of the screen is outside it): the others surely miss every
        // sphere, and are shaded as misses.
        thread_local std::vector<SphereHit> hits;
        thread_local std::vector<Ray> rays;
        thread_local std::vector<ColumnSpan> spans;
        // Each tracer writes the hit (or miss) of every ray it traces, and only those are read:
        // the buffer is not cleared.
        hits.resize(std::size_t(w) * std::size_t(h));
        rays.resize(hits.size());
        spans.resize(std::size_t(h));
        for (int j = 0; j < h; ++j) {
            const CubeRayCounter::Span r = cubeRays.row(sx0, w, sy0 + j);
            st.rays += r.meeting;
            spans[std::size_t(j)] = {r.first - sx0, r.last - sx0};
            if (r.first <= r.last) gen.row(r.first, sy0 + j, r.last - r.first + 1, rays.data() + std::size_t(j) * std::size_t(w) + std::size_t(r.first - sx0));
        }
        ObjectTraceCounters primary, secondary;
        if (tracer == SphereTracer::Beam) {
            BeamTile(tree, gen, sx0, sy0, w, h, rays, spans, hits, primary, st.beams).run();
        } else {
            for (int j = 0; j < h; ++j)
                for (int i = spans[std::size_t(j)].first; i <= spans[std::size_t(j)].last; ++i) {
                    const std::size_t k = std::size_t(j) * std::size_t(w) + std::size_t(i);
                    const Ray& r = rays[k];
                    if (tracer == SphereTracer::Samet) hits[k] = traceSamet(tree, r.origin, r.direction, 0.0, primary);
                    else if (tracer == SphereTracer::Reference) hits[k] = traceReference(tree, r.origin, r.direction, 0.0, primary);
                    else hits[k] = traceBruteForce(tree.scene, r.origin, r.direction, 0.0);
                }
        }
        const bool lightMayShow = shader.lightMayShow(gen, sx0, sy0, sx0 + w - 1, sy0 + h - 1);
        // Shade every sample, average per pixel. The samples are visited row by row (the
        // buffers' order), each added to its pixel's sum; a pixel still receives its samples in
        // the order b, then a, so its sum is the same float as summed pixel by pixel.
        const float inv = 1.0f / float(s * s);
        const int pw = px1 - px0;
        std::array<vec4, kTileSamples> sums;  // per pixel of the tile's row (a tile is at most kTileSamples pixels wide)
        const vec3 background = shader.background();
        const float backgroundAlpha = settings.background.a;
        std::uint64_t hitSamples = 0, secondaryRays = 0;  // kept in registers, added to st once
        for (int y = py0; y < py1; ++y) {
            std::fill_n(sums.begin(), pw, vec4(0.0f));
            for (int b = 0; b < s; ++b) {
                const int j = (y - py0) * s + b;
                const ColumnSpan span = spans[std::size_t(j)];
                const SphereHit* hitRow = hits.data() + std::size_t(j) * std::size_t(w);
                const Ray* rayRow = rays.data() + std::size_t(j) * std::size_t(w);
                for (int i = 0, x = 0; x < pw; ++x) {
                    vec4 sum = sums[std::size_t(x)];  // in a register across the pixel's samples of the row
                    for (int a = 0; a < s; ++a, ++i) {
                        if (i < span.first || i > span.last) {  // outside the cube: no ray made
                            sum += vec4(lightMayShow ? shader.miss(gen(sx0 + i, sy0 + j).direction) : background, backgroundAlpha);
                            continue;
                        }
                        const SphereHit& hit = hitRow[i];
                        hitSamples += hit.hit();
                        sum += vec4(shader.shade(rayRow[i].origin, rayRow[i].direction, hit, 0, secondary, secondaryRays),
                                    hit.hit() ? 1.0f : backgroundAlpha);
                    }
                    sums[std::size_t(x)] = sum;
                }
            }
            for (int x = px0; x < px1; ++x) {
                const std::size_t p = frame.pixel(x, y);
                const int i = (x - px0) * s;
                const ColumnSpan& span = spans[std::size_t((y - py0) * s)];
                const SphereHit first = i < span.first || i > span.last ? SphereHit{} : hits[std::size_t((y - py0) * s) * std::size_t(w) + std::size_t(i)];
#if defined(__SSE2__)
                // Streamed past the caches (the frame is not read again while rendering) when the
                // buffer has the 16-byte alignment the streaming store needs.
                if (streamColours) {
                    const vec4 c = sums[std::size_t(x - px0)] * inv;
                    _mm_stream_ps(&frame.rgba[p].x, _mm_setr_ps(c.x, c.y, c.z, c.w));
                } else {
                    frame.rgba[p] = sums[std::size_t(x - px0)] * inv;
                }
#else
                frame.rgba[p] = sums[std::size_t(x - px0)] * inv;
#endif
                frame.hitId[p] = first.sphere;
                frame.depth[p] = first.hit() ? float(first.t) : std::numeric_limits<float>::infinity();
                frame.flags[p] = Frame::kTraced;
            }
        }
#if defined(__SSE2__)
        _mm_sfence();  // the streamed colours are written before the tile counts as done
#endif
        st.pixels += std::uint64_t(pw) * std::uint64_t(py1 - py0);
        st.hits += hitSamples;
        st.secondaryRays += secondaryRays;
        st.raysFull = st.rays;
        st.nodesVisited = primary.nodes;
        st.intersections = primary.intersections;
    });
    return RenderStats::total(name, tileStats, timer.ms());
}

namespace {

class SphereRenderer final : public Renderer {
public:
    SphereRenderer(SphereTracer t, std::string name) : tracer_(t), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    RendererTraits traits() const override {
        RendererTraits t;
        t.levelOfDetail = false;
        t.drawsSpheres = true;
        t.drawsVoxels = tracer_ != SphereTracer::BruteForce;  // the brute-force oracle: spheres only
        t.paper = true;
        return t;
    }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings, Frame& frame) const override {
        if (tracer_ == SphereTracer::BruteForce)
            throw UsageError("renderer " + name_ + " draws sphere scenes (object octree) only: give a .pdb, .cif, sphereflake:L or random:N input");
        return renderVoxelTracer(tracer_ == SphereTracer::Beam ? VoxelTracer::Beam : VoxelTracer::Samet, name_, tree, camera, settings, frame);
    }
    RenderStats renderSpheres(const ObjectOctree& tree, const Camera& camera, const RenderSettings& settings,
                              Frame& frame) const override {
        return renderSphereScene(tracer_, name_, tree, camera, settings, frame);
    }

private:
    SphereTracer tracer_;
    std::string name_;
};

}  // namespace

std::unique_ptr<Renderer> makeSphereRenderer(const std::string& name) {
    if (name == "samet") return std::make_unique<SphereRenderer>(SphereTracer::Samet, name);
    if (name == "beam") return std::make_unique<SphereRenderer>(SphereTracer::Beam, name);
    return nullptr;
}

}  // namespace detail

std::unique_ptr<Renderer> makeBruteForceSphereRenderer() {
    return std::make_unique<detail::SphereRenderer>(detail::SphereTracer::BruteForce, "brute-force");
}

}  // namespace octrace
