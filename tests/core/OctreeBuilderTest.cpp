// Tests of buildShellOctree against an independent, dense evaluation of the contract in
// OctreeBuilder.h: a finest-level cell is a boundary voxel iff the trilinear field at its 8
// corners has some corner >= iso and some < iso, and no corner lies outside the grid or uses
// (with a non-zero weight) a masked sample. The test enumerates every cell; the builder may not.
#include "../TestScale.h"
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/util/Error.h"
#include "octrace/util/Timer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <thread>

using namespace octrace;

namespace {

// ---------------------------------------------------------------------------------------------
// Fields

using WorldFunction = std::function<double(const dvec3&)>;

/// Samples f at every grid point of a grid with the given geometry (uniform axes where
/// `coords[a]` is empty). Values are computed in double and stored as float, as a reader would.
ScalarField makeField(ivec3 dims, dvec3 origin, dvec3 spacing, dmat3 direction,
                      std::array<std::vector<double>, 3> coords, const WorldFunction& f) {
    ScalarField s;
    s.name = "test";
    s.source = "test-field";
    s.dims = dims;
    s.origin = origin;
    s.spacing = spacing;
    s.direction = direction;
    s.coords = std::move(coords);
    s.values.resize(s.sampleCount());
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) s.values[s.index(i, j, k)] = float(f(s.worldFromGrid(i, j, k)));
    s.validate();
    return s;
}

WorldFunction sphereAt(dvec3 centre, double radius) {
    return [centre, radius](const dvec3& p) { return radius - glm::length(p - centre); };
}

dmat3 rotationZ(double degrees) {
    const double a = glm::radians(degrees), c = std::cos(a), s = std::sin(a);
    dmat3 m(1.0);
    m[0] = dvec3(c, s, 0);   // columns: world directions of the grid axes
    m[1] = dvec3(-s, c, 0);
    m[2] = dvec3(0, 0, 1);
    return m;
}

/// Masks (valid = 0) a block of samples and a scattering of single samples.
void maskSomeSamples(ScalarField& f, ivec3 blockLo, ivec3 blockHi, int scattered, unsigned seed) {
    f.valid.assign(f.sampleCount(), 1);
    for (int k = blockLo.z; k <= blockHi.z; ++k)
        for (int j = blockLo.y; j <= blockHi.y; ++j)
            for (int i = blockLo.x; i <= blockHi.x; ++i) f.valid[f.index(i, j, k)] = 0;
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> pick(0, f.sampleCount() - 1);
    for (int n = 0; n < scattered; ++n) f.valid[pick(rng)] = 0;
}

// ---------------------------------------------------------------------------------------------
// Dense reference classification

/// Where a local coordinate falls along one grid axis.
struct AxisPos {
    bool outside = false;    ///< certainly outside [first, last] grid line
    bool borderline = false; ///< within rounding distance of the grid's end: either answer is right
    int i0 = 0;              ///< samples i0 (weight 1-t) and i0+1 (weight t)
    double t = 0.0;
};

AxisPos locateAxis(const ScalarField& f, int a, double u) {
    AxisPos p;
    const int n = f.dims[a];
    double idx;
    if (f.coords[a].empty()) {
        idx = u / f.spacing[a];
    } else {
        const auto& c = f.coords[a];
        if (u <= c.front()) {
            idx = (u - c[0]) / (c[1] - c[0]);
        } else if (u >= c.back()) {
            idx = (n - 1) + (u - c.back()) / (c.back() - c[std::size_t(n) - 2]);
        } else {
            std::size_t lo = 0, hi = std::size_t(n) - 1;  // c[lo] <= u < c[hi]
            while (hi - lo > 1) {
                std::size_t mid = (lo + hi) / 2;
                (c[mid] <= u ? lo : hi) = mid;
            }
            idx = double(lo) + (u - c[lo]) / (c[lo + 1] - c[lo]);
        }
    }
    const double eps = 1e-6;  // the builder accepts 1e-7 index units of rounding
    if (idx < -eps || idx > (n - 1) + eps) {
        p.outside = true;
        return p;
    }
    if (idx < 0.0 || idx > n - 1) p.borderline = true;
    idx = std::clamp(idx, 0.0, double(n - 1));
    p.i0 = std::min(int(std::floor(idx)), n - 2);
    p.t = idx - p.i0;
    return p;
}

enum class CellClass : std::uint8_t { Empty, Boundary, Ambiguous };

/// Classifies every cell of the tree's cube by the contract, independently of the builder.
struct DenseReference {
    int n = 0;                      // cells per axis
    std::vector<CellClass> cells;   // x fastest
    std::size_t boundary = 0, ambiguous = 0;

    CellClass at(const ivec3& c) const {
        return cells[std::size_t(c.x) + std::size_t(n) * (std::size_t(c.y) + std::size_t(n) * std::size_t(c.z))];
    }
};

DenseReference classifyDensely(const ScalarField& f, const dvec3& cubeOrigin, double cubeSide, int depth, double iso) {
    const int n = 1 << depth, m = n + 1;
    const double h = cubeSide / n;
    const dmat3 toLocal = glm::transpose(f.direction);  // orthonormal
    // Corner states: 0 = value, 1 = certainly masked/outside, 2 = masked or not depending on rounding.
    std::vector<std::uint8_t> state(std::size_t(m) * m * m);
    std::vector<double> value(state.size());
    std::vector<std::uint8_t> nearIso(state.size());
    const double tinyWeight = 1e-9;
    for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
                const std::size_t ci = std::size_t(i) + std::size_t(m) * (std::size_t(j) + std::size_t(m) * std::size_t(k));
                const dvec3 world = cubeOrigin + dvec3(i, j, k) * h;
                const dvec3 local = toLocal * (world - f.origin);
                AxisPos ax[3];
                bool outside = false, borderline = false;
                for (int a = 0; a < 3; ++a) {
                    ax[a] = locateAxis(f, a, local[a]);
                    outside |= ax[a].outside;
                    borderline |= ax[a].borderline;
                }
                if (outside) {
                    state[ci] = 1;
                    continue;
                }
                double v = 0.0;
                bool masked = false, maskedByTinyWeight = false;
                for (int q = 0; q < 8; ++q) {
                    const int dx = (q >> 2) & 1, dy = (q >> 1) & 1, dz = q & 1;
                    const double w = (dx ? ax[0].t : 1 - ax[0].t) * (dy ? ax[1].t : 1 - ax[1].t) * (dz ? ax[2].t : 1 - ax[2].t);
                    if (w == 0.0) continue;
                    const std::size_t si = f.index(ax[0].i0 + dx, ax[1].i0 + dy, ax[2].i0 + dz);
                    if (!f.isValid(si) || !std::isfinite(f.values[si])) {
                        (w < tinyWeight ? maskedByTinyWeight : masked) = true;
                        continue;
                    }
                    v += w * double(f.values[si]);
                }
                if (masked) state[ci] = 1;
                else if (maskedByTinyWeight || borderline) state[ci] = 2;
                value[ci] = v;
                // The builder interpolates in float: values this close to iso may go either way.
                nearIso[ci] = std::abs(v - iso) < 1e-5;
            }
    DenseReference r;
    r.n = n;
    r.cells.assign(std::size_t(n) * n * n, CellClass::Empty);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                bool certainlyMasked = false, uncertain = false, above = false, below = false;
                for (int q = 0; q < 8; ++q) {
                    const int x = i + ((q >> 2) & 1), y = j + ((q >> 1) & 1), z = k + (q & 1);
                    const std::size_t ci = std::size_t(x) + std::size_t(m) * (std::size_t(y) + std::size_t(m) * std::size_t(z));
                    if (state[ci] == 1) certainlyMasked = true;
                    if (state[ci] == 2 || (state[ci] == 0 && nearIso[ci])) uncertain = true;
                    if (state[ci] != 1) (value[ci] >= iso ? above : below) = true;
                }
                CellClass c = CellClass::Empty;
                if (certainlyMasked) c = CellClass::Empty;
                else if (uncertain) c = CellClass::Ambiguous;
                else if (above && below) c = CellClass::Boundary;
                r.cells[std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * std::size_t(k))] = c;
                if (c == CellClass::Boundary) ++r.boundary;
                if (c == CellClass::Ambiguous) ++r.ambiguous;
            }
    return r;
}

/// The cube the header promises: centred on the field's world box, side = its largest extent.
void expectCubeAroundField(const ScalarField& f, const Octree& t) {
    dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int c = 0; c < 8; ++c) {
        dvec3 p = f.worldFromGrid((c & 4) ? f.dims.x - 1 : 0, (c & 2) ? f.dims.y - 1 : 0, (c & 1) ? f.dims.z - 1 : 0);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const dvec3 ext = hi - lo;
    const double side = std::max(ext.x, std::max(ext.y, ext.z));
    EXPECT_NEAR(t.cubeSide, side, 1e-12 * side);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(t.cubeOrigin[a] + 0.5 * t.cubeSide, 0.5 * (lo[a] + hi[a]), 1e-12 * side);
}

/// Builds the field and checks that its boundary voxels are exactly the dense reference's.
void expectBoundaryMatchesDenseReference(const ScalarField& f, int depth, double iso, const std::string& what) {
    SCOPED_TRACE(what);
    BuildOptions o;
    o.depth = depth;
    o.iso = iso;
    o.threads = 0;
    BuildReport report;
    Octree t = buildShellOctree(f, o, &report);
    ASSERT_NO_THROW(t.validate());
    expectCubeAroundField(f, t);
    EXPECT_EQ(report.boundaryVoxels, t.voxels().size());
    EXPECT_EQ(report.nodes, t.nodes().size());

    DenseReference ref = classifyDensely(f, t.cubeOrigin, t.cubeSide, depth, iso);
    const int n = 1 << depth;
    std::vector<std::uint8_t> built(std::size_t(n) * n * n, 0);
    std::size_t extra = 0, duplicates = 0;
    std::string firstExtra;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t) {
        std::uint8_t& b = built[std::size_t(c.x) + std::size_t(n) * (std::size_t(c.y) + std::size_t(n) * std::size_t(c.z))];
        if (b++) ++duplicates;
        if (ref.at(c) == CellClass::Empty && extra++ == 0) {
            std::ostringstream s;
            s << "(" << c.x << "," << c.y << "," << c.z << ")";
            firstExtra = s.str();
        }
    });
    std::size_t missing = 0;
    std::string firstMissing;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const std::size_t ci = std::size_t(i) + std::size_t(n) * (std::size_t(j) + std::size_t(n) * std::size_t(k));
                if (ref.cells[ci] == CellClass::Boundary && !built[ci] && missing++ == 0) {
                    std::ostringstream s;
                    s << "(" << i << "," << j << "," << k << ")";
                    firstMissing = s.str();
                }
            }
    EXPECT_EQ(duplicates, 0u);
    EXPECT_EQ(extra, 0u) << "cells the builder marks boundary that are not; first " << firstExtra;
    EXPECT_EQ(missing, 0u) << "boundary cells the builder misses; first " << firstMissing;
    // The comparison must not be vacuous: many boundary cells, few left undecided by rounding.
    EXPECT_GT(ref.boundary, 500u);
    EXPECT_LE(double(ref.ambiguous), 0.01 * double(ref.boundary)) << ref.ambiguous << " ambiguous cells";
    std::cout << "[          ] " << what << ": " << ref.boundary << " boundary, " << ref.ambiguous
              << " undecidable by rounding, builder " << t.voxels().size() << "\n";
}

/// The cells of all boundary voxels, indexed by voxel.
std::vector<ivec3> voxelCells(const Octree& t) {
    std::vector<ivec3> cells(t.voxels().size());
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) { cells[i] = c; });
    return cells;
}

template <class T>
std::string shortestText(T v) {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

double angleDegrees(dvec3 a, dvec3 b) {
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

bool sameBytes(const Octree& a, const Octree& b) {
    return a.depth == b.depth && a.cubeOrigin == b.cubeOrigin && a.cubeSide == b.cubeSide &&
           a.nodes().size() == b.nodes().size() && a.voxels().size() == b.voxels().size() &&
           std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size() * sizeof(OctreeNode)) == 0 &&
           std::memcmp(a.voxels().data(), b.voxels().data(), a.voxels().size() * sizeof(Voxel)) == 0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Which cells are boundary voxels

TEST(OctreeBuilder, MarksExactlyTheSphereCellsWhoseCornersStraddleTheIsoValue) {
    // 33 samples over [-1,1]: at depth 5 the cell corners are the samples, at depth 6 they fall
    // half-way between samples.
    const ScalarField f = makeAnalyticField("sphere", 33);
    expectBoundaryMatchesDenseReference(f, 5, 0.0, "sphere 33^3 depth 5");
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "sphere 33^3 depth 6");
    // A non-zero iso value (a smaller sphere) and a grid that does not line up with the cells.
    const ScalarField g = makeAnalyticField("sphere", 27);
    expectBoundaryMatchesDenseReference(g, 6, 0.25, "sphere 27^3 depth 6 iso 0.25");
}

TEST(OctreeBuilder, CountsCornersEqualToTheIsoValueAsAbove) {
    // f = x on 17 samples over [0,4]: at depth 4 the cell corners are the samples, with exact
    // values 0, 0.25, ..., 4. With iso = 2 (the sample x = 2, i = 8) the cells [1.75, 2] have a
    // corner below and one equal (counted as above): boundary. The cells [2, 2.25] have corners
    // equal and above only: not boundary. So exactly the layer i = 7.
    ScalarField f = makeField(ivec3(17), dvec3(0.0), dvec3(0.25), dmat3(1.0), {}, [](const dvec3& p) { return p.x; });
    Octree t = buildShellOctree(f, {4, 2.0, 1});
    std::size_t inLayer = 0, outside = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t) { (c.x == 7 ? inLayer : outside)++; });
    EXPECT_EQ(inLayer, 16u * 16u);
    EXPECT_EQ(outside, 0u);
}

TEST(OctreeBuilder, MarksExactlyTheStraddlingCellsOfFieldsWithManySheets) {
    expectBoundaryMatchesDenseReference(makeAnalyticField("gyroid", 24), 5, 0.0, "gyroid 24^3 depth 5");
    expectBoundaryMatchesDenseReference(makeAnalyticField("noise", 21, 3), 6, 0.0, "noise 21^3 depth 6");
    expectBoundaryMatchesDenseReference(makeAnalyticField("torus", 40), 6, 0.05, "torus 40^3 depth 6 iso 0.05");
    expectBoundaryMatchesDenseReference(makeAnalyticField("spheres", 48), 6, 0.0, "spheres 48^3 depth 6");
}

TEST(OctreeBuilder, NeverMarksCellsThatTouchMaskedSamples) {
    ScalarField f = makeAnalyticField("sphere", 33);
    // A block through the sphere's shell and scattered single samples.
    maskSomeSamples(f, ivec3(20, 0, 10), ivec3(32, 12, 22), 400, 5);
    expectBoundaryMatchesDenseReference(f, 5, 0.0, "masked sphere depth 5");
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "masked sphere depth 6");

    // Directly: no boundary voxel has a corner in the masked block's (closed) world box.
    Octree t = buildShellOctree(f, {6, 0.0, 1});
    const dvec3 blockLo = f.worldFromGrid(20, 0, 10), blockHi = f.worldFromGrid(32, 12, 22);
    std::size_t touching = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t) {
        Box3 b = t.voxelBox(c);
        bool overlaps = true;
        for (int a = 0; a < 3; ++a) overlaps &= b.hi[a] >= blockLo[a] - 1e-12 && b.lo[a] <= blockHi[a] + 1e-12;
        if (overlaps) ++touching;
    });
    EXPECT_EQ(touching, 0u);
}

TEST(OctreeBuilder, MarksExactlyTheStraddlingCellsOnARectilinearAnisotropicGrid) {
    // Uneven z levels (like ocean depths) and different uniform spacings along x and y.
    std::array<std::vector<double>, 3> coords;
    for (int k = 0; k < 25; ++k) coords[2].push_back(0.03 * k + 0.002 * k * k);
    const dvec3 origin(-0.4, 0.3, -0.9);
    const dvec3 centre = origin + dvec3(0.5 * 39 * 0.05, 0.5 * 21 * 0.08, 0.5 * coords[2].back());
    ScalarField f = makeField(ivec3(40, 22, 25), origin, dvec3(0.05, 0.08, 1.0), dmat3(1.0), coords,
                              sphereAt(centre, 0.62));
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "rectilinear z, anisotropic");
    maskSomeSamples(f, ivec3(0, 0, 12), ivec3(15, 21, 16), 200, 9);
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "rectilinear z, anisotropic, masked");

    // Rectilinear x and z whose coordinates do not start at 0 (e.g. depth levels below a
    // surface layer, stored as negative heights), the sphere off-centre.
    std::array<std::vector<double>, 3> c2;
    for (int i = 0; i < 30; ++i) c2[0].push_back(0.37 + 0.05 * i + 0.0015 * i * i);
    for (int k = 0; k < 25; ++k) c2[2].push_back(-1.9 + 0.02 * k + 0.0025 * k * k);
    const dvec3 o2(2.0, -1.0, 0.5);
    ScalarField g = makeField(ivec3(30, 22, 25), o2, dvec3(1.0, 0.08, 1.0), dmat3(1.0), c2,
                              sphereAt(o2 + dvec3(1.4, 0.9, -1.1), 0.55));
    expectBoundaryMatchesDenseReference(g, 6, 0.0, "rectilinear x and z, offset coordinates");
}

TEST(OctreeBuilder, MarksExactlyTheStraddlingCellsOfARotatedGridWithAnOffsetOrigin) {
    const dmat3 rot = rotationZ(30.0);
    const dvec3 origin(0.3, -0.2, 0.5), spacing(0.07, 0.065, 0.06);
    const ivec3 dims(30, 26, 22);
    const dvec3 centre = origin + rot * (0.5 * dvec3(dims - 1) * spacing);
    ScalarField f = makeField(dims, origin, spacing, rot, {}, sphereAt(centre, 0.55));
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "rotated 30 degrees about z");
    maskSomeSamples(f, ivec3(0, 0, 0), ivec3(10, 25, 8), 150, 13);
    expectBoundaryMatchesDenseReference(f, 6, 0.0, "rotated, masked");

    // Rotated and rectilinear together.
    std::array<std::vector<double>, 3> coords;
    for (int k = 0; k < 22; ++k) coords[2].push_back(0.04 * k + 0.001 * k * k);
    const dvec3 c2 = origin + rot * dvec3(0.5 * 29 * 0.07, 0.5 * 25 * 0.065, 0.5 * coords[2].back());
    ScalarField g = makeField(dims, origin, spacing, rot, coords, sphereAt(c2, 0.5));
    expectBoundaryMatchesDenseReference(g, 6, 0.0, "rotated and rectilinear");
}

// ---------------------------------------------------------------------------------------------
// Determinism, structure, size

TEST(OctreeBuilder, GivesTheSameBytesForOneTwoAndSevenThreads) {
    struct Case {
        std::string name;
        ScalarField field;
        int depth;
    };
    std::vector<Case> cases;
    cases.push_back({"noise", makeAnalyticField("noise", 33, 7), 7});
    cases.push_back({"sphere", makeAnalyticField("sphere", 33), 7});
    {
        ScalarField f = makeField(ivec3(30, 26, 22), dvec3(0.3, -0.2, 0.5), dvec3(0.07, 0.065, 0.06), rotationZ(30.0), {},
                                  sphereAt(dvec3(0.6, 1.0, 1.1), 0.55));
        maskSomeSamples(f, ivec3(0, 0, 0), ivec3(10, 25, 8), 150, 13);
        cases.push_back({"rotated masked", std::move(f), 6});
    }
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Octree one = buildShellOctree(c.field, {c.depth, 0.0, 1});
        Octree two = buildShellOctree(c.field, {c.depth, 0.0, 2});
        Octree seven = buildShellOctree(c.field, {c.depth, 0.0, 7});
        EXPECT_TRUE(sameBytes(one, two));
        EXPECT_TRUE(sameBytes(one, seven));
        EXPECT_GT(one.voxels().size(), 0u);
    }
}

TEST(OctreeBuilder, BuildsValidOctreesOfEveryDepthFromOneToEight) {
    const ScalarField f = makeAnalyticField("sphere", 17);
    std::size_t previous = 0;
    for (int depth = 1; depth <= 8; ++depth) {
        SCOPED_TRACE(depth);
        Octree t = buildShellOctree(f, {depth, 0.0, 0});
        EXPECT_NO_THROW(t.validate());
        EXPECT_EQ(t.depth, depth);
        EXPECT_GE(t.voxels().size(), previous);
        previous = t.voxels().size();
    }
}

TEST(OctreeBuilder, StoresADepthEightSphereInAtMostSixteenBytesPerVoxel) {
    Octree t = buildShellOctree(makeAnalyticField("sphere", 65), {8, 0.0, 0});
    EXPECT_NO_THROW(t.validate());
    EXPECT_LE(t.bytesPerVoxel(), 16.0);
    EXPECT_EQ(t.bytes(), t.nodes().capacity() * sizeof(OctreeNode) + t.voxels().capacity() * sizeof(Voxel));
    std::cout << "[          ] depth-8 sphere: " << t.voxels().size() << " voxels, " << t.bytesPerVoxel()
              << " bytes per voxel\n";
}

TEST(OctreeBuilder, FindsAsManyBoundaryVoxelsAsASphericalShellHas) {
    // Expected count. Take a plane piece of area A, unit normal n, |nz| its largest component.
    // It lies over A|nz|/h^2 columns of cells along z; over one column's h x h square it spans
    // a z-range of h(|nx| + |ny|)/|nz|, so it crosses on average 1 + (|nx| + |ny|)/|nz| cells of
    // the column. Hence A(|nx| + |ny| + |nz|)/h^2 crossed cells, and a cell is crossed exactly
    // when its corners straddle the plane: the builder's criterion. On a sphere the mean of |nx|
    // is 1/2 (Archimedes: a coordinate of a uniform point on the sphere is uniform on [-1,1]),
    // so a shell of radius r gives 1.5 * 4 pi r^2 / h^2; curvature and the trilinear field change
    // this by O(h/r), about 1% at depth 7 (h = 2/128, r = 0.7).
    const ScalarField f = makeAnalyticField("sphere", 65);
    Octree t6 = buildShellOctree(f, {6, 0.0, 0});
    Octree t7 = buildShellOctree(f, {7, 0.0, 0});
    const double r = 0.7, h7 = 2.0 / 128;
    const double expected7 = 1.5 * 4.0 * M_PI * r * r / (h7 * h7);
    const double n6 = double(t6.voxels().size()), n7 = double(t7.voxels().size());
    std::cout << "[          ] sphere shell: depth 7 " << n7 << " voxels, expected " << expected7 << " (ratio "
              << n7 / expected7 << "); depth 6 " << n6 << ", ratio 7/6 = " << n7 / n6 << "\n";
    EXPECT_NEAR(n7 / expected7, 1.0, 0.03);
    EXPECT_NEAR(n7 / n6, 4.0, 0.15);
}

// ---------------------------------------------------------------------------------------------
// Normals

TEST(OctreeBuilder, StoresOutwardRadialNormalsOnTheSphere) {
    // The field 0.7 - |p| decreases outwards; the builder stores the normalised negative
    // gradient, so the normals point out of the sphere.
    Octree t = buildShellOctree(makeAnalyticField("sphere", 65), {7, 0.0, 0});
    const std::vector<ivec3> cells = voxelCells(t);
    double worst = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const dvec3 centre = t.voxelBox(cells[i]).centre();
        const double a = angleDegrees(dvec3(decodeNormal(t.voxels()[i].normal)), centre);
        worst = std::max(worst, a);
        sum += a;
    }
    std::cout << "[          ] sphere normals: mean " << sum / double(cells.size()) << " deg, max " << worst << " deg\n";
    EXPECT_LT(worst, 3.0);
    EXPECT_LT(sum / double(cells.size()), 1.0);
}

TEST(OctreeBuilder, StoresRadialWorldNormalsWhenTheSpacingIsAnisotropic) {
    // The same sphere sampled with spacing (0.02, 0.04, 0.08): a gradient taken in index space
    // would tilt the normals towards z by up to atan(4) - 45 degrees.
    const dvec3 spacing(0.02, 0.04, 0.08);
    const ivec3 dims(101, 51, 26);
    ScalarField f = makeField(dims, dvec3(-1.0), spacing, dmat3(1.0), {}, sphereAt(dvec3(0.0), 0.7));
    Octree t = buildShellOctree(f, {7, 0.0, 0});
    const std::vector<ivec3> cells = voxelCells(t);
    double worst = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const dvec3 centre = t.voxelBox(cells[i]).centre();
        const double a = angleDegrees(dvec3(decodeNormal(t.voxels()[i].normal)), centre);
        worst = std::max(worst, a);
        sum += a;
    }
    std::cout << "[          ] anisotropic sphere normals: mean " << sum / double(cells.size()) << " deg, max " << worst
              << " deg\n";
    EXPECT_LT(worst, 4.0);
    EXPECT_LT(sum / double(cells.size()), 1.0);

    // And on the rotated grid the normals are rotated with it (still radial in world space).
    ScalarField g = makeField(ivec3(30, 26, 22), dvec3(0.3, -0.2, 0.5), dvec3(0.07, 0.065, 0.06), rotationZ(30.0), {},
                              sphereAt(dvec3(0.3, -0.2, 0.5) + rotationZ(30.0) * dvec3(1.015, 0.8125, 0.63), 0.55));
    Octree r = buildShellOctree(g, {6, 0.0, 0});
    const dvec3 centreR = dvec3(0.3, -0.2, 0.5) + rotationZ(30.0) * dvec3(1.015, 0.8125, 0.63);
    const std::vector<ivec3> cellsR = voxelCells(r);
    double worstR = 0.0;
    for (std::size_t i = 0; i < cellsR.size(); ++i)
        worstR = std::max(worstR, angleDegrees(dvec3(decodeNormal(r.voxels()[i].normal)), r.voxelBox(cellsR[i]).centre() - centreR));
    EXPECT_LT(worstR, 4.0);

    // And on uneven (rectilinear) z levels.
    std::array<std::vector<double>, 3> coords;
    for (int k = 0; k < 30; ++k) coords[2].push_back(-1.0 + 0.03 * k + 0.00155 * k * k);
    ScalarField z = makeField(ivec3(41, 41, 30), dvec3(-1.0, -1.0, 0.0), dvec3(0.05), dmat3(1.0), coords,
                              sphereAt(dvec3(0.0), 0.7));
    Octree zt = buildShellOctree(z, {7, 0.0, 0});
    const std::vector<ivec3> cellsZ = voxelCells(zt);
    double worstZ = 0.0;
    for (std::size_t i = 0; i < cellsZ.size(); ++i)
        worstZ = std::max(worstZ, angleDegrees(dvec3(decodeNormal(zt.voxels()[i].normal)), zt.voxelBox(cellsZ[i]).centre()));
    std::cout << "[          ] rotated grid normals: max " << worstR << " deg; rectilinear z: max " << worstZ << " deg\n";
    EXPECT_LT(worstZ, 4.0);
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(OctreeBuilder, RejectsDepthsOutsideOneToFourteenAsUsageErrors) {
    const ScalarField f = makeAnalyticField("sphere", 9);
    EXPECT_THROW(buildShellOctree(f, {0, 0.0, 1}), UsageError);
    EXPECT_THROW(buildShellOctree(f, {-3, 0.0, 1}), UsageError);
    EXPECT_THROW(buildShellOctree(f, {Octree::kMaxDepth + 1, 0.0, 1}), UsageError);
    EXPECT_THROW(buildShellOctree(f, {15, 0.0, 1}), UsageError);
    EXPECT_THROW(buildShellOctree(f, {4, std::numeric_limits<double>::quiet_NaN(), 1}), UsageError);
    EXPECT_NO_THROW(buildShellOctree(f, {1, 0.0, 1}));
}

TEST(OctreeBuilder, NamesTheValueRangeWhenTheIsoValueIsOutsideIt) {
    const ScalarField f = makeAnalyticField("sphere", 17);
    const auto [lo, hi] = f.validRange();  // [-1.0320508, 0.7] as floats
    // The numbers are printed so that they read back as the same values: the range ends as
    // floats ("0.7" for 0.7f), the iso value with every digit it needs to differ from them.
    const std::string range = "[" + shortestText(lo) + ", " + shortestText(hi) + "]";
    for (double iso : {5.0, -3.0, 0.7001, -1.04}) {
        try {
            buildShellOctree(f, {5, iso, 1});
            ADD_FAILURE() << "no exception for iso " << iso;
        } catch (const EmptyResultError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(range), std::string::npos) << msg;
            EXPECT_NE(msg.find("iso value " + shortestText(iso) + " "), std::string::npos) << msg;
            EXPECT_NE(msg.find(f.source), std::string::npos) << msg;
            EXPECT_NE(msg.find("'sphere'"), std::string::npos) << msg;
        }
    }
    std::cout << "[          ] e.g. ";
    try {
        buildShellOctree(f, {5, 0.7001, 1});
    } catch (const Error& e) {
        std::cout << e.what() << "\n";
    }
}

TEST(OctreeBuilder, AcceptsAnIsoValueThatRoundsToTheLargestSample) {
    // The largest sample of the sphere field is 0.7f (= 0.699999988 < 0.7). Cells are classified
    // in float against float(iso), so --iso 0.7 is the largest value, not outside the range: the
    // 8 cells around the centre sample (corner equal to iso, counted as above) are boundary.
    const ScalarField f = makeAnalyticField("sphere", 33);
    ASSERT_EQ(f.validRange().second, 0.7f);
    Octree t;
    ASSERT_NO_THROW(t = buildShellOctree(f, {5, 0.7, 1}));
    std::vector<ivec3> cells = voxelCells(t);
    EXPECT_EQ(cells.size(), 8u);
    for (const ivec3& c : cells)
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(c[a] == 15 || c[a] == 16) << c.x << "," << c.y << "," << c.z;
    EXPECT_EQ(t.iso, 0.7);
    // Out of float range is outside the value range, not undefined behaviour.
    EXPECT_THROW(buildShellOctree(f, {5, 1e300, 1}), EmptyResultError);
    EXPECT_THROW(buildShellOctree(f, {5, -1e300, 1}), EmptyResultError);
}

TEST(OctreeBuilder, ReportsProgressInOrderOneCallAtATimeEndingAtOne) {
    // The callback runs on the builder's worker threads; it must not be entered twice at once
    // (a GUI progress bar or a plain counter must not need locks) and must not go backwards.
    const ScalarField f = makeAnalyticField("sphere", 33);
    for (int threads : {0, 2, 7}) {
        std::atomic<int> inside{0};
        int overlaps = 0, backwards = 0, calls = 0;
        double last = 0.0;
        BuildOptions o;
        o.depth = 6;
        o.threads = threads;
        o.progress = [&](double x) {
            if (inside.fetch_add(1) != 0) ++overlaps;
            // Widen the window in which a second worker could enter.
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            if (x < last) ++backwards;
            last = x;
            ++calls;
            inside.fetch_sub(1);
        };
        buildShellOctree(f, o);
        EXPECT_EQ(overlaps, 0) << threads << " threads";
        EXPECT_EQ(backwards, 0) << threads << " threads";
        EXPECT_GT(calls, 1);
        EXPECT_EQ(last, 1.0);
    }
}

TEST(OctreeBuilder, StopsWithCancelledErrorSoonAfterTheCallerAsksAndBuildsAsBeforeWhenNeverAsked) {
    // The studio's Cancel button: the hook is polled inside the subtrees, not only between them.
    const ScalarField f = makeAnalyticField("sphere", 65);
    for (int threads : {1, 0}) {
        std::atomic<int> polls{0};
        BuildOptions o;
        o.depth = 9;
        o.threads = threads;
        o.cancelled = [&] { return polls.fetch_add(1) >= 3; };
        int progressCalls = 0;
        o.progress = [&](double) { ++progressCalls; };
        EXPECT_THROW(buildShellOctree(f, o), CancelledError) << threads << " threads";
        // Asked after the third poll: at most one subtree of the 64 was finished (serially).
        EXPECT_LE(progressCalls, threads == 1 ? 1 : 8) << threads << " threads";
    }
    // Never asked to stop: the same tree as without the hook.
    BuildOptions plain;
    plain.depth = 7;
    BuildOptions hooked = plain;
    int polls = 0;
    hooked.threads = 1;
    hooked.cancelled = [&] { return ++polls < 0; };
    const Octree a = buildShellOctree(f, plain), b = buildShellOctree(f, hooked);
    EXPECT_GT(polls, 64);
    EXPECT_EQ(a.voxels().size(), b.voxels().size());
    EXPECT_EQ(a.nodes().size(), b.nodes().size());
}

TEST(OctreeBuilder, ReportsAnEmptyResultForAnAllMaskedFieldAndForAnIsoNoCellStraddles) {
    ScalarField f = makeAnalyticField("sphere", 9);
    f.valid.assign(f.sampleCount(), 0);
    EXPECT_THROW(buildShellOctree(f, {4, 0.0, 1}), EmptyResultError);
    // The minimum itself: every corner is >= iso, none below.
    ScalarField g = makeAnalyticField("sphere", 9);
    const float lo = g.validRange().first;
    EXPECT_THROW(buildShellOctree(g, {4, double(lo), 1}), EmptyResultError);
    // Only isolated valid samples: every cell has a masked corner.
    ScalarField s = makeAnalyticField("sphere", 9);
    s.valid.assign(s.sampleCount(), 0);
    for (int k = 0; k < 9; k += 2)
        for (int j = 0; j < 9; j += 2)
            for (int i = 0; i < 9; i += 2) s.valid[s.index(i, j, k)] = 1;
    EXPECT_THROW(buildShellOctree(s, {3, 0.0, 1}), EmptyResultError);
}

// ---------------------------------------------------------------------------------------------
// Memory

TEST(OctreeBuilder, UsesMemoryThatGrowsWithTheBoundaryNotWithTheCube) {
    // Depth 10 is a 1024^3 cube: a dense byte per cell would be 1 GiB, a float per cell 4 GiB.
    // Depth 9 (an eighth of that cube, a quarter of the voxels) in the scaled-down sanitizer run.
    const int depth = testutil::testScale() < 1.0 ? 9 : 10;
    const double side = double(1 << depth);
    const ScalarField f = makeAnalyticField("sphere", 33);
    const std::size_t rssBefore = peakRssBytes();
    Timer timer;
    BuildReport report;
    Octree t = buildShellOctree(f, {depth, 0.0, 0}, &report);
    const double ms = timer.ms();
    const std::size_t rssAfter = peakRssBytes();
    ASSERT_NO_THROW(t.validate());
    // 4 bytes per voxel plus one 8-byte node per <= 8 voxels at the level above and a
    // geometric tail of ancestors: well below 16 bytes per voxel.
    EXPECT_LT(t.bytes(), 16 * t.boundaryVoxels());
    // Roughly 1.5 * 4 pi 0.7^2 / (2/1024)^2 = 2.4 million voxels at depth 10.
    EXPECT_NEAR(double(t.boundaryVoxels()) / (1.5 * 4 * M_PI * 0.49 * side * side / 4), 1.0, 0.03);
    const std::size_t grown = rssAfter > rssBefore ? rssAfter - rssBefore : 0;
    std::cout << "[          ] depth-" << depth << " sphere: " << t.boundaryVoxels() << " voxels, " << t.bytes() / 1048576.0
              << " MiB, build " << ms << " ms, peak RSS " << rssBefore / 1048576.0 << " -> " << rssAfter / 1048576.0
              << " MiB\n";
    if (rssAfter > 0) {
        // The build keeps the subtrees and the joined copy: a few times the octree, never the cube.
        EXPECT_LT(grown, std::size_t(1) << 28) << "peak RSS grew by " << grown << " bytes";
        EXPECT_LT(grown, 8 * t.bytes() + (std::size_t(64) << 20));
    }
}
