#pragma once
// Shared by the renderer tests: analytic scenes in [-1,1]^3 (a sphere of radius 0.7, a torus,
// value noise), test cameras, and bitwise frame comparison.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Renderer.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace octrace::test {

using namespace octrace;

/// An analytic field's shell octree with the field's corner values (drawn as smooth surfaces).
inline Octree smoothTree(const std::string& field, int n, int depth, std::uint32_t seed = 1) {
    BuildOptions o;
    o.depth = depth;
    o.iso = 0.0;
    o.corners = true;
    return buildShellOctree(makeAnalyticField(field, n, seed), o);
}
inline const Octree& sphereTree() {
    static const Octree t = buildShellOctree(makeAnalyticField("sphere", 33), {7, 0.0, 0});
    return t;
}
inline const Octree& torusTree() {
    static const Octree t = buildShellOctree(makeAnalyticField("torus", 33), {6, 0.0, 0});
    return t;
}
inline const Octree& noiseTree() {
    static const Octree t = buildShellOctree(makeAnalyticField("noise", 65, 7), {8, 0.0, 0});
    return t;
}

inline Box3 cubeOf(const Octree& t) { return Box3{t.cubeOrigin, t.cubeOrigin + dvec3(t.cubeSide)}; }

inline Camera makeCamera(dvec3 position, dvec3 lookAt, dvec3 up, double fov, int w, int h) {
    Camera c;
    c.position = position;
    c.lookAt = lookAt;
    c.up = up;
    c.fovYDegrees = fov;
    c.width = w;
    c.height = h;
    return c;
}

struct NamedCamera {
    std::string name;
    Camera camera;
};

/// Cameras in general position, for a scene in [-1,1]^3.
inline std::vector<NamedCamera> generalTestCameras(const Octree& t) {
    return {
        {"framing", Camera::framing(cubeOf(t), 120, 90)},
        {"inside", makeCamera({0.35, -0.2, 0.15}, {-0.5, 0.6, -0.1}, {0, 0, 1}, 70, 90, 70)},
        {"close, oblique", makeCamera({-1.3, 1.1, -0.9}, {0.1, -0.05, 0.2}, {0, 1, 0}, 50, 80, 64)},
    };
}

/// Cameras whose eye lies on the octree lattice (planes of every level), looking along an axis:
/// rays through voxel edges and corners, exactly axis-parallel rays.
inline std::vector<NamedCamera> latticeTestCameras(const Octree&) {
    return {
        // Odd sizes: the centre pixel's ray is exactly along the axis.
        {"along -z", makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 101, 75)},
        {"along +x", makeCamera({-4, 0, 0}, {0, 0, 0}, {0, 0, 1}, 35, 75, 61)},
        // The eye at the cube's centre: a lattice point of every level.
        {"at the centre", makeCamera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90, 65, 65)},
    };
}

inline std::vector<NamedCamera> allTestCameras(const Octree& t) {
    auto a = generalTestCameras(t), b = latticeTestCameras(t);
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// The scenes and cameras of the exact renderers' tests (tile, the exact trajectory variants):
// every scene of the renderer tests plus thin rods, at the hard cameras.
struct NamedTree {
    std::string name;
    const Octree* tree;
};

inline const Octree& volumeTree() {  // volume form: interior terms the shell renderers skip
    static const Octree t = buildOctree(makeAnalyticField("torus", 33), {6, 0.0, 0});
    return t;
}

/// Thin rods (radius 0.012, a voxel and a half at depth 8) in several directions, between
/// the pixel rays of any tile: what a bound that misses a sliver of a tile's rays gets wrong.
inline Octree buildRods(bool corners) {
    BuildOptions o;
    o.depth = 8;
    o.iso = 0.0;
    o.corners = corners;
    return buildShellOctree(
        sampleFunction("rods", ivec3(129), dvec3(-1.0), dvec3(2.0 / 128), [](const dvec3& p) {
            double v = -1.0;
            for (int i = 0; i < 7; ++i) {
                const double a = 0.31 * i - 0.9, b = 0.23 * i - 0.7;
                v = std::max(v, 0.012 - std::hypot(p.x - a, p.z - 0.4 * b));       // along y
                v = std::max(v, 0.012 - std::hypot(p.y - b, p.z + 0.5 * a));       // along x
                v = std::max(v, 0.012 - std::hypot(p.x - p.y - 0.2 * a, p.z - b)); // diagonal in x, y
            }
            return float(v);
        }),
        o);
}
inline const Octree& rodsTree() {
    static const Octree t = buildRods(false);
    return t;
}

inline std::vector<NamedTree> hardTestTrees() {
    return {{"sphere", &sphereTree()}, {"torus", &torusTree()}, {"noise", &noiseTree()},
            {"volume torus", &volumeTree()}, {"rods", &rodsTree()}};
}

/// The tile renderer's test cameras: the shared ones, plus a grazing view along a cube face, views from inside the cube and
/// orthographic views (one framed, one whose view plane cuts the cube).
inline std::vector<NamedCamera> hardTestCameras(const Octree& t) {
    std::vector<NamedCamera> c = allTestCameras(t);
    const Box3 cube = cubeOf(t);
    c.push_back({"grazing the top face", makeCamera({-3.0, -2.5, 1.0}, {1.0, 1.0, 0.999}, {0, 0, 1}, 40, 97, 61)});
    c.push_back({"inside, looking down", makeCamera({0.1, 0.05, 0.6}, {0.12, 0.1, -1.0}, {0, 1, 0}, 100, 80, 60)});
    Camera ortho = Camera::framing(cube, 90, 70);
    ortho.projection = Camera::Projection::Orthographic;
    ortho.frameOrthographic(cube);
    c.push_back({"orthographic", ortho});
    Camera cut = makeCamera({0.2, -0.1, 0.3}, {-0.4, 0.5, -0.2}, {0, 0, 1}, 30, 77, 59);
    cut.projection = Camera::Projection::Orthographic;
    cut.orthoHeight = 1.1;
    c.push_back({"orthographic, view plane inside", cut});
    return c;
}

/// Renders with a renderer's name or alias (area+colour: area with colour coherence), as the
/// front ends do.
inline RenderStats render(const std::string& renderer, const Octree& t, const Camera& c, Frame& f,
                   RenderSettings settings = RenderSettings{}) {
    const RendererName name = resolveRendererName(renderer);
    name.applyTo(settings);
    return makeRenderer(name.renderer)->render(t, c, settings, f);
}

inline bool tracesRays(const std::string& name) { return makeRenderer(name)->tracesRays(); }

inline bool sameFloatBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

/// Pixels where hit id, colour or depth differ in any bit.
struct FrameDiff {
    std::size_t hitId = 0, rgba = 0, depth = 0;
    std::string first;
    bool identical() const { return hitId == 0 && rgba == 0 && depth == 0; }
};

inline FrameDiff diffFrames(const Frame& a, const Frame& b) {
    FrameDiff d;
    if (a.width != b.width || a.height != b.height) {
        d.hitId = d.rgba = d.depth = std::size_t(-1);
        d.first = "sizes differ";
        return d;
    }
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t p = a.pixel(x, y);
            bool bad = false;
            if (a.hitId[p] != b.hitId[p]) ++d.hitId, bad = true;
            if (std::memcmp(&a.rgba[p], &b.rgba[p], sizeof(vec4)) != 0) ++d.rgba, bad = true;
            if (!sameFloatBits(a.depth[p], b.depth[p])) ++d.depth, bad = true;
            if (bad && d.first.empty()) {
                std::ostringstream s;
                s << "pixel (" << x << "," << y << "): hit " << a.hitId[p] << " vs " << b.hitId[p] << ", depth "
                  << a.depth[p] << " vs " << b.depth[p];
                d.first = s.str();
            }
        }
    return d;
}

inline std::size_t hitCount(const Frame& f) {
    std::size_t n = 0;
    for (auto id : f.hitId) n += id != kNoHit;
    return n;
}

}  // namespace octrace::test
