#include "SphereRenderers.h"

#include "VoxelTracers.h"

#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace octrace {

RenderStats Renderer::renderSpheres(const ObjectOctree&, const Camera&, const RenderSettings&, Frame&) const {
    throw UsageError("renderer " + name() + " draws voxel octrees only; sphere scenes take reference, samet or beam");
}

namespace detail {
namespace {

constexpr int kTilePixels = 16;  // the initial beams: screen tiles of 16 x 16 pixels
constexpr double kInf = std::numeric_limits<double>::infinity();

int samplesPerSide(int samples) {
    const int s = int(std::lround(std::sqrt(double(samples))));
    if (samples < 1 || s * s != samples || s > 16)
        throw UsageError("--samples must be a square number of rays per pixel (1, 4, 9, 16, ... 256), got " + std::to_string(samples));
    return s;
}

/// Whitted shading shared by every sphere tracer. Secondary rays go by Samet's method.
class SphereShader {
public:
    SphereShader(const ObjectOctree& tree, const Camera& camera, const RenderSettings& s) : tree_(tree), s_(s) {
        dvec3 right, up, back;
        camera.basis(right, up, back);
        const dvec3 l = glm::normalize(s.lightCamera);
        light_ = glm::normalize(l.x * right + l.y * up + l.z * back);
        eps_ = tree.cubeSide * 1e-9;
    }
    /// Colour seen along a ray that found `hit` (or nothing).
    vec3 shade(const dvec3& o, const dvec3& d, const SphereHit& hit, int depth, ObjectTraceCounters& c, std::uint64_t& secondary) const {
        if (!hit.hit()) return miss(d);
        const Sphere& sp = tree_.scene.spheres[hit.sphere];
        const dvec3 p = o + d * hit.t;
        dvec3 n = glm::normalize(p - sp.centre);
        const bool inside = glm::dot(n, d) > 0.0;
        if (inside) n = -n;
        double lambert = std::max(0.0, glm::dot(n, light_));
        if (lambert > 0.0 && s_.shadows) {
            ++secondary;
            if (traceSamet(tree_, p, light_, eps_, c).hit()) lambert = 0.0;
        }
        const vec3 local = sp.colour * float(s_.ambient + s_.diffuse * lambert);
        const Material& m = tree_.scene.materials[sp.material];
        if (depth >= s_.bounces || (m.reflect <= 0.0f && m.transmit <= 0.0f)) return local;
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
    /// A ray that leaves the scene: the light's colour (white) within half a degree of the
    /// light's direction, else the background.
    vec3 miss(const dvec3& d) const { return glm::dot(d, light_) > kCosLight ? vec3(1.0f) : vec3(s_.background); }

private:
    vec3 follow(const dvec3& p, const dvec3& d, int depth, ObjectTraceCounters& c, std::uint64_t& secondary) const {
        ++secondary;
        return shade(p, d, traceSamet(tree_, p, d, eps_, c), depth + 1, c, secondary);
    }
    static constexpr double kCosLight = 0.99996192306;  // cos(0.5 degrees)
    const ObjectOctree& tree_;
    const RenderSettings& s_;
    dvec3 light_;
    double eps_;
};

/// Primary rays of one tile as beams (paper B): the beam is the eye and the screen rectangle
/// of its rays (a corner direction and two spanning vectors); it is cut by each node's
/// projected bounds on the way down, visited front to back; empty leaves only move it on;
/// in an occupied leaf its rays are selected from the tile's sorted ray matrix by binary
/// search, row by row within the leaf's projected outline, and intersected one by one; once
/// every ray of the tile is hit the tile ends.
class BeamTile {
public:
    /// `rays`: the tile's w x h rays, row by row, of the samples (x0 + i, y0 + j).
    BeamTile(const ObjectOctree& tree, const RayGenerator& gen, int x0, int y0, int w, int h, const std::vector<Ray>& rays,
             std::vector<SphereHit>& hits, ObjectTraceCounters& c, std::uint64_t& beams)
        : tree_(tree), gen_(gen), w_(w), h_(h), rays_(rays), hits_(hits), c_(c), beams_(beams) {
        // The sorted ray matrix: sample centres along x (columns) and y (rows), pixel units.
        xs_.resize(std::size_t(w));
        ys_.resize(std::size_t(h));
        for (int i = 0; i < w; ++i) xs_[std::size_t(i)] = x0 + i + 0.5;
        for (int j = 0; j < h; ++j) ys_[std::size_t(j)] = y0 + j + 0.5;
        remaining_ = std::size_t(w) * std::size_t(h);
        marked_.assign(remaining_, 0);
        right_ = gen.right();
        up_ = gen.up();
        back_ = gen.back();
    }
    void run() { visit(0, 0, w_, 0, h_); }

private:
    /// A node's box projected on the screen: its 8 corners in pixel units, unless a corner
    /// lies behind the eye (then no outline: every ray of the beam is tried).
    struct Outline {
        double x[8], y[8];
        bool valid = false;
    };

    void visit(std::uint32_t node, int i0, int i1, int j0, int j1) {
        const ObjectNode& nd = tree_.nodes[node];
        if (nd.leaf() && nd.objectCount == 0) return;  // empty: the beam only moves on
        ++beams_;
        ++c_.nodes;
        const Box3 box = tree_.nodeBox(node);
        Outline outline;
        if (!cut(box, outline, i0, i1, j0, j1)) return;
        if (nd.leaf()) {
            intersect(nd, box, outline, i0, i1, j0, j1);
            return;
        }
        // Front to back: children on the eye's side of each mid-plane first (for parallel
        // rays, the side the rays come from).
        unsigned mask = 0;
        const dvec3 mid = box.centre();
        for (int a = 0; a < 3; ++a) {
            const bool high = gen_.orthographic() ? (-back_[a] < 0.0) : (gen_.eye()[a] > mid[a]);
            if (high) mask |= 4u >> a;
        }
        for (unsigned k = 0; k < 8 && remaining_ > 0; ++k) visit(nd.firstChild + (k ^ mask), i0, i1, j0, j1);
    }

    // Narrows [i0,i1) x [j0,j1) to the rays inside the projected bounds of the box (binary
    // search in the sorted sample coordinates). False when none is left.
    bool cut(const Box3& b, Outline& o, int& i0, int& i1, int& j0, int& j1) const {
        double pxLo = kInf, pxHi = -kInf, pyLo = kInf, pyHi = -kInf;
        for (int k = 0; k < 8; ++k) {
            const dvec3 p((k & 4) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 1) ? b.hi.z : b.lo.z);
            const dvec3 rel = p - gen_.eye();
            const double cz = glm::dot(rel, back_);
            if (!gen_.orthographic() && !(cz < 0.0)) return true;  // reaches behind the eye: no cut
            gen_.toPixel(glm::dot(rel, right_), glm::dot(rel, up_), cz, o.x[k], o.y[k]);
            pxLo = std::min(pxLo, o.x[k]);
            pxHi = std::max(pxHi, o.x[k]);
            pyLo = std::min(pyLo, o.y[k]);
            pyHi = std::max(pyHi, o.y[k]);
        }
        o.valid = true;
        i0 = std::max(i0, int(std::lower_bound(xs_.begin(), xs_.end(), pxLo - kMargin) - xs_.begin()));
        i1 = std::min(i1, int(std::upper_bound(xs_.begin(), xs_.end(), pxHi + kMargin) - xs_.begin()));
        j0 = std::max(j0, int(std::lower_bound(ys_.begin(), ys_.end(), pyLo - kMargin) - ys_.begin()));
        j1 = std::min(j1, int(std::upper_bound(ys_.begin(), ys_.end(), pyHi + kMargin) - ys_.begin()));
        return i0 < i1 && j0 < j1;
    }

    /// The columns [i0, i1) of row j that lie within the outline (the convex hull of the 8
    /// projected corners: on a horizontal line, its extremes are where segments between two
    /// corners cross the line), widened by kMargin.
    void rowSpan(const Outline& o, int j, int& i0, int& i1) const {
        const double y = ys_[std::size_t(j)];
        double lo = kInf, hi = -kInf;
        for (int a = 0; a < 8; ++a)
            for (int b = a + 1; b < 8; ++b) {
                const double ya = o.y[a], yb = o.y[b];
                if ((ya < y - kMargin && yb < y - kMargin) || (ya > y + kMargin && yb > y + kMargin)) continue;
                double x0 = o.x[a], x1 = o.x[b];
                if (std::abs(yb - ya) > kMargin) {
                    const double f = std::clamp((y - ya) / (yb - ya), 0.0, 1.0);
                    x0 = x1 = o.x[a] + f * (o.x[b] - o.x[a]);
                }
                lo = std::min({lo, x0, x1});
                hi = std::max({hi, x0, x1});
            }
        if (!(lo <= hi)) {
            i1 = i0;
            return;
        }
        i0 = std::max(i0, int(std::lower_bound(xs_.begin(), xs_.end(), lo - kMargin) - xs_.begin()));
        i1 = std::min(i1, int(std::upper_bound(xs_.begin(), xs_.end(), hi + kMargin) - xs_.begin()));
    }

    // The leaf rule (nearestInLeaf) for the beam's rays not yet hit: the nearest sphere hit,
    // kept when the ray crosses the leaf and the hit is not beyond its exit. The beam first
    // culls the leaf's spheres: a ray is tested only against the spheres whose projected box
    // (widened by kMargin) holds its sample, since a ray that meets a sphere passes through its
    // box. The tests made are those of nearestInLeaf less ones that cannot hit, in the same
    // order, so the hit is the same. The exit comes from the slab test, made only for a ray
    // that hits a sphere; the outline only spares the rays that cannot cross the leaf.
    void intersect(const ObjectNode& leaf, const Box3& box, const Outline& o, int i0, int i1, int j0, int j1) {
        const std::uint32_t* list = tree_.objects.data() + leaf.firstObject;
        const std::uint32_t n = leaf.objectCount;
        rects_.resize(n);
        for (std::uint32_t q = 0; q < n; ++q) {
            const Sphere& sp = tree_.scene.spheres[list[q]];
            Outline so;
            int a0 = 0, a1 = w_, b0 = 0, b1 = h_;
            if (!cut(Box3{sp.centre - sp.radius, sp.centre + sp.radius}, so, a0, a1, b0, b1)) a0 = a1 = b0 = b1 = 0;
            rects_[q] = {a0, a1, b0, b1};
        }
        for (int j = j0; j < j1; ++j) {
            int r0 = i0, r1 = i1;
            if (o.valid) rowSpan(o, j, r0, r1);
            if (r0 >= r1) continue;
            rowSpheres_.clear();
            for (std::uint32_t q = 0; q < n; ++q)
                if (rects_[q][2] <= j && j < rects_[q][3] && rects_[q][0] < r1 && r0 < rects_[q][1]) rowSpheres_.push_back(q);
            if (rowSpheres_.empty()) continue;
            for (int i = r0; i < r1; ++i) {
                const std::size_t k = std::size_t(j) * std::size_t(w_) + std::size_t(i);
                if (marked_[k]) continue;
                const Ray& r = rays_[k];
                SphereHit h;
                for (std::uint32_t q : rowSpheres_) {
                    if (i < rects_[q][0] || i >= rects_[q][1]) continue;
                    ++c_.intersections;
                    const double t = intersectSphere(tree_.scene.spheres[list[q]], r.origin, r.direction, 0.0);
                    if (t < h.t) {
                        h.t = t;
                        h.sphere = list[q];
                    }
                }
                if (!h.hit()) continue;
                double t0, t1;
                slabInterval(box, r.origin, 1.0 / r.direction, r.direction, t0, t1);
                if (t0 > t1 || t1 < 0.0 || h.t > t1) continue;  // not this leaf's hit
                hits_[k] = h;
                marked_[k] = 1;
                --remaining_;
            }
        }
    }

    static constexpr double kMargin = 1e-6;  // pixels; the projection's rounding is far below
    const ObjectOctree& tree_;
    const RayGenerator& gen_;
    int w_, h_;
    const std::vector<Ray>& rays_;
    std::vector<SphereHit>& hits_;
    ObjectTraceCounters& c_;
    std::uint64_t& beams_;
    std::vector<double> xs_, ys_;
    std::vector<std::uint8_t> marked_;
    std::vector<std::array<int, 4>> rects_;      // per sphere of the leaf: columns [0,1), rows [2,3) its box covers
    std::vector<std::uint32_t> rowSpheres_;      // the leaf's spheres whose rows hold the current row
    std::size_t remaining_ = 0;
    dvec3 right_, up_, back_;
};

}  // namespace

RenderStats renderSphereScene(SphereTracer tracer, const std::string& name, const ObjectOctree& tree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame) {
    camera.validate();
    if (settings.bounces < 0) throw UsageError("--bounces must be >= 0");
    const int s = samplesPerSide(settings.samples);
    Timer timer;
    frame.resize(camera.width, camera.height);
    // The rays: the pixel grid of a camera s times finer (sample (x*s+a, y*s+b) of pixel (x, y)).
    Camera sampleCamera = camera;
    sampleCamera.width = camera.width * s;
    sampleCamera.height = camera.height * s;
    const RayGenerator gen(sampleCamera);
    const SphereShader shader(tree, camera, settings);
    const Box3 cube = tree.cube();
    const int tilesX = (camera.width + kTilePixels - 1) / kTilePixels, tilesY = (camera.height + kTilePixels - 1) / kTilePixels;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * std::size_t(tilesY));
    parallelFor(tileStats.size(), settings.threads, [&](std::size_t t) {
        RenderStats& st = tileStats[t];
        const int px0 = int(t % std::size_t(tilesX)) * kTilePixels, py0 = int(t / std::size_t(tilesX)) * kTilePixels;
        const int px1 = std::min(px0 + kTilePixels, camera.width), py1 = std::min(py0 + kTilePixels, camera.height);
        const int sx0 = px0 * s, sy0 = py0 * s, w = (px1 - px0) * s, h = (py1 - py0) * s;
        std::vector<SphereHit> hits(std::size_t(w) * std::size_t(h));
        std::vector<Ray> rays(hits.size());
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) rays[std::size_t(j) * std::size_t(w) + std::size_t(i)] = gen(sx0 + i, sy0 + j);
        ObjectTraceCounters primary, secondary;
        if (tracer == SphereTracer::Beam) {
            BeamTile(tree, gen, sx0, sy0, w, h, rays, hits, primary, st.beams).run();
        } else {
            for (std::size_t k = 0; k < rays.size(); ++k) {
                const Ray& r = rays[k];
                if (tracer == SphereTracer::Samet) hits[k] = traceSamet(tree, r.origin, r.direction, 0.0, primary);
                else if (tracer == SphereTracer::Reference) hits[k] = traceReference(tree, r.origin, r.direction, 0.0, primary);
                else hits[k] = traceBruteForce(tree.scene, r.origin, r.direction, 0.0);
            }
        }
        // Shade every sample, average per pixel.
        const float inv = 1.0f / float(s * s);
        for (int y = py0; y < py1; ++y)
            for (int x = px0; x < px1; ++x) {
                vec3 sum(0.0f);
                float alpha = 0.0f;
                for (int b = 0; b < s; ++b)
                    for (int a = 0; a < s; ++a) {
                        const int i = (x - px0) * s + a, j = (y - py0) * s + b;
                        const SphereHit& hit = hits[std::size_t(j) * std::size_t(w) + std::size_t(i)];
                        const Ray& r = rays[std::size_t(j) * std::size_t(w) + std::size_t(i)];
                        double t0, t1;
                        slabInterval(cube, r.origin, 1.0 / r.direction, r.direction, t0, t1);
                        st.rays += t0 <= t1 && t1 >= 0.0;
                        st.hits += hit.hit();
                        sum += shader.shade(r.origin, r.direction, hit, 0, secondary, st.secondaryRays);
                        alpha += hit.hit() ? 1.0f : settings.background.a;
                    }
                const std::size_t p = frame.pixel(x, y);
                const SphereHit& first = hits[std::size_t((y - py0) * s) * std::size_t(w) + std::size_t((x - px0) * s)];
                frame.rgba[p] = vec4(sum * inv, alpha * inv);
                frame.hitId[p] = first.sphere;
                frame.depth[p] = first.hit() ? float(first.t) : std::numeric_limits<float>::infinity();
                frame.flags[p] = Frame::kTraced;
                ++st.pixels;
            }
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
    bool multiResolution() const override { return false; }
    bool drawsSpheres() const override { return true; }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings, Frame& frame) const override {
        if (tracer_ == SphereTracer::BruteForce)
            throw UsageError("renderer " + name_ + " draws sphere scenes (object octree) only: give a .pdb, .cif, sphereflake:L or random:N input");
        return renderVoxelTracer(tracer_ == SphereTracer::Beam ? VoxelTracer::Beam : VoxelTracer::Samet, name_, tree, camera, settings, frame);
    }
    bool drawsVoxels() const override { return tracer_ != SphereTracer::BruteForce; }
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
