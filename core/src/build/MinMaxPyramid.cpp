#include "build/MinMaxPyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace::detail {

MinMaxPyramid::MinMaxPyramid(const float* samples, ivec3 dims) : samples_(samples), dims_(dims) {
    const float inf = std::numeric_limits<float>::infinity();
    ivec3 prevDims = dims;
    while (prevDims.x > 1 || prevDims.y > 1 || prevDims.z > 1) {
        Level L;
        L.dims = (prevDims + 1) / 2;
        std::size_t n = std::size_t(L.dims.x) * L.dims.y * L.dims.z;
        L.mn.assign(n, inf);
        L.mx.assign(n, -inf);
        L.masked.assign(n, 0);
        const bool first = levels_.empty();
        const Level* P = first ? nullptr : &levels_.back();
        for (int k = 0; k < prevDims.z; ++k)
            for (int j = 0; j < prevDims.y; ++j)
                for (int i = 0; i < prevDims.x; ++i) {
                    std::size_t src = std::size_t(i) + std::size_t(prevDims.x) * (std::size_t(j) + std::size_t(prevDims.y) * k);
                    std::size_t dst = std::size_t(i / 2) + std::size_t(L.dims.x) * (std::size_t(j / 2) + std::size_t(L.dims.y) * (k / 2));
                    float a, b;
                    if (first) {
                        a = b = samples[src];
                        if (std::isnan(a)) {
                            L.masked[dst] = 1;
                            continue;
                        }
                    } else {
                        a = P->mn[src];
                        b = P->mx[src];
                        L.masked[dst] |= P->masked[src];
                    }
                    L.mn[dst] = std::min(L.mn[dst], a);
                    L.mx[dst] = std::max(L.mx[dst], b);
                }
        prevDims = L.dims;
        levels_.push_back(std::move(L));
    }
}

std::uint64_t MinMaxPyramid::bytesFor(ivec3 dims) {
    std::uint64_t bytes = 0;
    while (dims.x > 1 || dims.y > 1 || dims.z > 1) {  // the levels of the constructor
        dims = (dims + 1) / 2;
        bytes += (2 * sizeof(float) + 1) * std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z);
    }
    return bytes;
}

void MinMaxPyramid::query(ivec3 lo, ivec3 hi, float& mn, float& mx, bool* masked) const {
    mn = std::numeric_limits<float>::infinity();
    mx = -mn;
    if (masked) *masked = false;
    lo = glm::max(lo, ivec3(0));
    hi = glm::min(hi, dims_ - 1);
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return;
    ivec3 ext = hi - lo + 1;
    int e = std::max(ext.x, std::max(ext.y, ext.z));
    int l = 0;
    while ((e >> l) > 2 && l < int(levels_.size())) ++l;
    if (l == 0) {
        for (int k = lo.z; k <= hi.z; ++k)
            for (int j = lo.y; j <= hi.y; ++j)
                for (int i = lo.x; i <= hi.x; ++i) {
                    float v = samples_[std::size_t(i) + std::size_t(dims_.x) * (std::size_t(j) + std::size_t(dims_.y) * k)];
                    if (std::isnan(v)) {
                        if (masked) *masked = true;
                        continue;
                    }
                    mn = std::min(mn, v);
                    mx = std::max(mx, v);
                }
        return;
    }
    const Level& L = levels_[std::size_t(l - 1)];
    ivec3 a = lo >> l, b = hi >> l;
    for (int k = a.z; k <= b.z; ++k)
        for (int j = a.y; j <= b.y; ++j)
            for (int i = a.x; i <= b.x; ++i) {
                std::size_t idx = std::size_t(i) + std::size_t(L.dims.x) * (std::size_t(j) + std::size_t(L.dims.y) * k);
                mn = std::min(mn, L.mn[idx]);
                mx = std::max(mx, L.mx[idx]);
                if (masked && L.masked[idx]) *masked = true;
            }
}

}  // namespace octrace::detail
