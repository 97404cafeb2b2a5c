#pragma once
// Private to core: the primary ray of each pixel, in world space (for depth) and quantized
// in octree space (for the traversals). Every renderer takes its rays from here, so that the
// exact renderers and the reference trace bitwise the same quantized rays.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/DiscreteTraversal.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace octrace::detail {

class PixelRays {
public:
    /// `surfaceLevel`: the surface's bounding box is rounded out to the node grid of that level
    /// (a multi-resolution cut draws nodes down from it whole: LodCut::coarsestLevel); < 0 or
    /// the tree's depth: the voxels' own box.
    PixelRays(const Octree& tree, const Camera& camera, int surfaceLevel = -1);
    /// Unnormalised world direction of pixel (x, y) (quantization only needs its ratios).
    dvec3 direction(int x, int y) const { return gen_.direction(x, y); }
    /// Ray origin of pixel (x, y) in octree space.
    dvec3 originOS(int x, int y) const { return tree_.toOctreeSpace(gen_.origin(x, y)); }
    QuantizedRay quantized(int x, int y, const dvec3& direction) const { return quantizeRay(originOS(x, y), direction); }
    /// quantized(x0 + i, y, directions[i]) into out[i] for i < n: a perspective eye's rays
    /// eight at a time where the processor can (quantizeRays), the same bits.
    void quantizedRow(int y, int x0, int n, const dvec3* directions, QuantizedRay* out) const {
        if (!gen_.orthographic()) {
            quantizeRays(originOS(x0, y), directions, n, out);
            return;
        }
        for (int i = 0; i < n; ++i) out[i] = quantized(x0 + i, y, directions[i]);
    }
    /// The world ray (unit direction), for the distance of a hit.
    Ray world(int x, int y, const dvec3& direction) const { return {gen_.origin(x, y), glm::normalize(direction)}; }
    /// False only when the pixel's ray cannot meet the scene cube: the pixel lies more than a
    /// pixel outside the cube's projected outline (the convex hull of its projected corners).
    /// Always true when the cube reaches behind a perspective eye. A renderer may then draw
    /// the background without quantizing the ray: the ray would not meet the cube.
    bool mayMeetCube(int x, int y) const {
        const auto& s = cubeSpans_[std::size_t(y)];
        return x >= s.first && x <= s.second;
    }
    /// True only when the pixel's quantized ray certainly meets the scene cube: the pixel's
    /// centre lies more than a pixel inside the cube's projected outline, so no rounding of the
    /// ray can take it out (a pixel at the screen is far wider than the fixed point's unit). A
    /// renderer that would quantize the ray only to count it in `rays` may count it unquantized.
    bool surelyMeetsCube(int x, int y) const {
        const auto& s = cubeInnerSpans_[std::size_t(y)];
        return x >= s.first && x <= s.second;
    }
    /// The pixels x of row y for which mayMeetCube holds, and those for which surelyMeetsCube
    /// holds (first > second: none), as surfaceSpan.
    std::pair<int, int> cubeSpan(int y) const { return cubeSpans_[std::size_t(y)]; }
    std::pair<int, int> cubeInnerSpan(int y) const { return cubeInnerSpans_[std::size_t(y)]; }
    /// Whether the pixel's quantized ray meets the cube, quantizing it only when that is not
    /// certain (for counting rays that are not traced).
    bool meetsCube(int x, int y) const { return surelyMeetsCube(x, y) || quantized(x, y, direction(x, y)).meetsCube; }
    /// How many pixels x0 .. x1-1 of row y meetsCube: those inside the inner span counted at
    /// once, those between it and the outline quantized, none outside the outline.
    std::uint64_t raysMeetingCube(int y, int x0, int x1) const {
        const auto [cubeLo, cubeHi] = cubeSpan(y);
        const auto [innerLo, innerHi] = cubeInnerSpan(y);
        const int lo = std::max(x0, cubeLo), hi = std::min(x1 - 1, cubeHi);
        const int inLo = std::max(lo, innerLo), inHi = std::min(hi, innerHi);
        std::uint64_t n = inLo <= inHi ? std::uint64_t(inHi - inLo + 1) : 0;
        for (int x = lo; x <= hi; ++x)
            if ((x < inLo || x > inHi) && meetsCube(x, y)) ++n;
        return n;
    }
    /// False only when the pixel's ray cannot hit a boundary voxel: outside the projected
    /// outline of the surface's bounding box (Octree::occupiedCells), in the same way.
    bool mayHitSurface(int x, int y) const {
        const auto& s = surfaceSpans_[std::size_t(y)];
        return x >= s.first && x <= s.second;
    }
    /// Whether mayHitSurface holds for some pixel of columns x0 .. x1-1 of rows y0 .. y1-1.
    bool mayHitSurfaceIn(int x0, int y0, int x1, int y1) const {
        for (int y = y0; y < y1; ++y) {
            const auto& s = surfaceSpans_[std::size_t(y)];
            if (s.first <= s.second && s.first < x1 && s.second >= x0) return true;
        }
        return false;
    }
    /// The pixels x of row y for which mayHitSurface holds: first <= x <= second (first >
    /// second: none; the ends may lie outside the image).
    std::pair<int, int> surfaceSpan(int y) const { return surfaceSpans_[std::size_t(y)]; }
    /// The columns of x0 .. x1-1 in row y for which mayHitSurface holds, as [lo, hi] (lo > hi:
    /// none): what forRunsOutsideSurface leaves of them.
    std::pair<int, int> surfaceSpanIn(int y, int x0, int x1) const {
        const auto [first, second] = surfaceSpan(y);
        return {std::max(first, x0), std::min(second, x1 - 1)};
    }
    /// The pixels of row y (of an image `width` wide) outside surfaceSpan, as at most two runs:
    /// calls run(x0, x1) for columns x0 .. x1-1 of each non-empty one. Returns the columns left,
    /// clipped to the image (lo > hi: none).
    template <class Run>
    std::pair<int, int> forRunsOutsideSurface(int y, int width, const Run& run) const {
        const auto [lo, hi] = surfaceSpanIn(y, 0, width);
        if (lo > hi) {
            run(0, width);
            return {1, 0};
        }
        if (lo > 0) run(0, lo);
        if (hi + 1 < width) run(hi + 1, width);
        return {lo, hi};
    }

private:
    const Octree& tree_;
    RayGenerator gen_;
    using Spans = std::vector<std::pair<int, int>>;  // per row: pixels that may see the box
    /// Per row, the pixels whose rays may meet the box's projected outline; with `inner`, those
    /// whose rays certainly do (empty spans when that cannot be told).
    Spans outline(const Box3& box, int width, int height, Spans* inner = nullptr) const;
    Spans cubeSpans_, cubeInnerSpans_, surfaceSpans_;
};

}  // namespace octrace::detail
