#include "octrace/render/SliceView.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace octrace {
namespace {

dvec3 axisVector(int a, double sign) {
    dvec3 v(0.0);
    v[a] = sign;
    return v;
}

/// The mean step of grid axis a (its spacing when uniform).
double gridStep(const ScalarField& f, int a) {
    const auto& c = f.coords[std::size_t(a)];
    if (c.size() < 2) return f.spacing[a];
    return (c.back() - c.front()) / double(c.size() - 1);
}

/// The grid axis whose direction is closest to world direction `d`, other than `skip`.
int closestGridAxis(const ScalarField& f, const dvec3& d, int skip = -1) {
    int best = -1;
    double bestDot = -1.0;
    for (int a = 0; a < 3; ++a) {
        if (a == skip) continue;
        const double dot = std::abs(glm::dot(f.direction[a], d));
        if (dot > bestDot) best = a, bestDot = dot;
    }
    return best;
}

/// Continuous sample index of local coordinate `x` along grid axis a (beyond the ends: by
/// the first or last step).
double continuousIndex(const ScalarField& f, int a, double x) {
    const auto& c = f.coords[std::size_t(a)];
    if (c.size() < 2) return x / f.spacing[a];
    if (x <= c.front()) return (x - c[0]) / (c[1] - c[0]);
    const std::size_t n = c.size();
    if (x >= c.back()) return double(n - 1) + (x - c[n - 1]) / (c[n - 1] - c[n - 2]);
    const std::size_t i = std::size_t(std::upper_bound(c.begin(), c.end(), x) - c.begin()) - 1;
    return double(i) + (x - c[i]) / (c[i + 1] - c[i]);
}

std::string num(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

}  // namespace

const char* slicePlaneName(SlicePlane p) {
    switch (p) {
        case SlicePlane::Axial: return "axial";
        case SlicePlane::Coronal: return "coronal";
        case SlicePlane::Sagittal: return "sagittal";
        case SlicePlane::X: return "x";
        case SlicePlane::Y: return "y";
        case SlicePlane::Z: return "z";
    }
    return "?";
}

int sliceNormalAxis(SlicePlane p) {
    switch (p) {
        case SlicePlane::Sagittal:
        case SlicePlane::X: return 0;
        case SlicePlane::Coronal:
        case SlicePlane::Y: return 1;
        default: return 2;
    }
}

dvec3 sliceScreenRight(SlicePlane p) { return sliceNormalAxis(p) == 0 ? axisVector(1, 1.0) : axisVector(0, 1.0); }

dvec3 sliceScreenUp(SlicePlane p) {
    if (p == SlicePlane::Axial) return axisVector(1, -1.0);  // anterior up
    return sliceNormalAxis(p) == 2 ? axisVector(1, 1.0) : axisVector(2, 1.0);
}

dvec3 SliceView::screenRight() const { return sliceScreenRight(plane); }
dvec3 SliceView::screenUp() const { return sliceScreenUp(plane); }

int sliceGridAxis(const ScalarField& f, SlicePlane plane) { return closestGridAxis(f, axisVector(sliceNormalAxis(plane), 1.0)); }

double slicePositionOfIndex(const ScalarField& f, SlicePlane plane, int index) {
    const int n = sliceNormalAxis(plane);
    const int a = sliceGridAxis(f, plane);
    const int count = f.dims[a];
    if (index < 0 || index >= count)
        throw UsageError("`index`: " + std::to_string(index) + " is outside the " + std::to_string(count) +
                         " samples (0.." + std::to_string(count - 1) + ") of grid axis " + std::to_string(a) +
                         ", the one across the " + slicePlaneName(plane) + " plane");
    ivec3 ijk(0);
    ijk[a] = index;
    return f.worldFromGrid(ijk.x, ijk.y, ijk.z)[n];
}

std::pair<double, double> slicePositionRange(const ScalarField& f, SlicePlane plane) {
    const int n = sliceNormalAxis(plane);
    const int g = sliceGridAxis(f, plane);
    const int count = f.dims[g];
    const Box3 b = f.worldBounds();
    const double first = count < 2 ? 0.0 : f.axisPosition(g, 1) - f.axisPosition(g, 0);
    const double last = count < 2 ? 0.0 : f.axisPosition(g, count - 1) - f.axisPosition(g, count - 2);
    const double dn = f.direction[g][n];
    const double halfLo = 0.5 * std::abs(dn) * (dn > 0.0 ? first : last), halfHi = 0.5 * std::abs(dn) * (dn > 0.0 ? last : first);
    return {b.lo[n] - halfLo, b.hi[n] + halfHi};
}

SliceView makeSliceView(const ScalarField& f, SlicePlane plane, double position, int width, int height) {
    SliceView v;
    v.plane = plane;
    v.position = position;
    const int n = sliceNormalAxis(plane);
    const dvec3 normal = axisVector(n, 1.0), R = sliceScreenRight(plane), U = sliceScreenUp(plane);
    double lo[3], hi[3];  // extents along R, U and the normal
    for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::infinity(), hi[k] = -lo[k];
    for (int c = 0; c < 8; ++c) {
        const dvec3 p = f.worldFromGrid((c & 4) ? f.dims.x - 1 : 0, (c & 2) ? f.dims.y - 1 : 0, (c & 1) ? f.dims.z - 1 : 0);
        const double d[3] = {glm::dot(p, R), glm::dot(p, U), p[n]};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], d[k]), hi[k] = std::max(hi[k], d[k]);
    }
    v.gridAxis = closestGridAxis(f, normal);
    const auto [onLo, onHi] = slicePositionRange(f, plane);
    if (!(position >= onLo - 1e-9 * (1.0 + std::abs(position)) && position <= onHi + 1e-9 * (1.0 + std::abs(position))))
        throw InputError(f.source + ": the " + std::string(slicePlaneName(plane)) + " plane at " + num(position) +
                         " lies outside the grid, which spans " + num(lo[2]) + " .. " + num(hi[2]) + " along world " +
                         std::string(1, char('x' + n)));
    // The plane's index along its grid axis, through the grid's origin line.
    const double along = (position - f.origin[n]) / f.direction[v.gridAxis][n];
    v.gridIndex = continuousIndex(f, v.gridAxis, along);

    const int aR = closestGridAxis(f, R, v.gridAxis);
    const int aU = 3 - v.gridAxis - aR;
    const double p0 = std::min(gridStep(f, aR), gridStep(f, aU));
    const double areaR = hi[0] - lo[0] + p0, areaU = hi[1] - lo[1] + p0;
    if (width > 0 && height > 0) {  // fitted
        v.width = width, v.height = height;
        v.pixelSize = std::max(areaR / width, areaU / height);
    } else {
        // Pixel centres every p0 from the first sample to within half a pixel past the last.
        v.width = int(std::floor((hi[0] - lo[0]) / p0 + 0.5 + 1e-9)) + 1;
        v.height = int(std::floor((hi[1] - lo[1]) / p0 + 0.5 + 1e-9)) + 1;
        v.pixelSize = p0;
    }
    // One pixel per sample: pixel centres on the samples from the grid's top-left corner (the
    // last may overhang by less than half a sample). Fitted: the slice centred.
    const double cR = 0.5 * (lo[0] + hi[0]), cU = 0.5 * (lo[1] + hi[1]);
    const bool fitted = width > 0 && height > 0;
    const double left = fitted ? cR - 0.5 * (v.width - 1) * v.pixelSize : lo[0];
    const double top = fitted ? cU + 0.5 * (v.height - 1) * v.pixelSize : hi[1];
    v.topLeft = R * left + U * top + normal * position;
    v.gridMin = dvec2((lo[0] - left) / v.pixelSize, (top - hi[1]) / v.pixelSize);
    v.gridMax = dvec2((hi[0] - left) / v.pixelSize, (top - lo[1]) / v.pixelSize);
    v.margin = 0.5 * p0 / v.pixelSize;
    v.right = R * v.pixelSize;
    v.down = -U * v.pixelSize;
    return v;
}

std::pair<float, float> SliceValues::range() const {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < values.size(); ++i)
        if (state[i] == SliceSample::Valid) lo = std::min(lo, values[i]), hi = std::max(hi, values[i]);
    if (lo > hi) return {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN()};
    return {lo, hi};
}

SliceValues sampleSlice(const ScalarField& f, const SliceView& v, int threads) {
    SliceValues s;
    s.width = v.width;
    s.height = v.height;
    const std::size_t count = std::size_t(v.width) * std::size_t(v.height);
    s.values.assign(count, std::numeric_limits<float>::quiet_NaN());
    s.state.assign(count, SliceSample::Outside);
    const dmat3 toLocal = glm::transpose(f.direction);  // orthonormal
    auto usable = [&](std::size_t idx) { return f.isValid(idx) && std::isfinite(f.values[idx]); };
    parallelFor(std::size_t(v.height), threads, [&](std::size_t row) {
        for (int px = 0; px < v.width; ++px) {
            const std::size_t out = row * std::size_t(v.width) + std::size_t(px);
            // The image's content ends half a pixel-sample past the grid's extent (gridMin,
            // gridMax), whatever the spacing across it.
            const double eps = 1e-6;
            if (px < v.gridMin.x - v.margin - eps || px > v.gridMax.x + v.margin + eps || double(row) < v.gridMin.y - v.margin - eps ||
                double(row) > v.gridMax.y + v.margin + eps)
                continue;
            const dvec3 local = toLocal * (v.world(px, double(row)) - f.origin);
            int i0[3];
            double t[3], w[3];
            bool inside = true;
            for (int a = 0; a < 3 && inside; ++a) {
                const int nA = f.dims[a];
                double x = continuousIndex(f, a, local[a]);
                inside = x >= -0.5 - 1e-9 && x <= nA - 0.5 + 1e-9;
                x = std::clamp(x, 0.0, double(nA - 1));
                const double r = std::round(x);
                if (std::abs(x - r) < 1e-6) x = r;  // on a sample: its value, exactly
                t[a] = x;
                i0[a] = nA < 2 ? 0 : std::min(int(std::floor(x)), nA - 2);
                w[a] = x - i0[a];
            }
            if (!inside) continue;
            double sum = 0.0;
            bool allValid = true;
            for (int c = 0; c < 8 && allValid; ++c) {
                double wc = 1.0;
                int ijk[3];
                for (int a = 0; a < 3; ++a) {
                    const int bit = (c >> a) & 1;
                    wc *= bit ? w[a] : 1.0 - w[a];
                    ijk[a] = std::min(i0[a] + bit, f.dims[a] - 1);
                }
                if (wc == 0.0) continue;
                const std::size_t idx = f.index(ijk[0], ijk[1], ijk[2]);
                allValid = usable(idx);
                sum += wc * double(f.values[idx]);
            }
            if (allValid) {
                s.values[out] = float(sum);
                s.state[out] = SliceSample::Valid;
                continue;
            }
            const std::size_t nearest = f.index(int(std::lround(t[0])), int(std::lround(t[1])), int(std::lround(t[2])));
            if (usable(nearest)) {
                s.values[out] = f.values[nearest];
                s.state[out] = SliceSample::Valid;
            } else {
                s.state[out] = SliceSample::Masked;
            }
        }
    });
    return s;
}

Frame colourSlice(const SliceValues& s, const SliceColouring& c) {
    colormap(c.colormap, 0.0f);  // validates the name
    Frame f(s.width, s.height);
    const double span = c.high - c.low;
    for (std::size_t i = 0; i < s.values.size(); ++i) {
        vec4 rgba = c.outside;
        if (s.state[i] == SliceSample::Masked) {
            rgba = c.masked;
        } else if (s.state[i] == SliceSample::Valid) {
            if (c.window.valid()) {
                const double g = c.window.greyValue(s.values[i], c.invertedGrey);
                const float l = srgb8ToLinear(std::uint8_t(std::lround(g * 255.0)));
                rgba = vec4(l, l, l, 1.0f);
            } else {
                const double t = span > 0.0 ? std::clamp((double(s.values[i]) - c.low) / span, 0.0, 1.0) : 0.5;
                rgba = vec4(colormap(c.colormap, float(t)), 1.0f);
            }
        }
        f.rgba[i] = rgba;
    }
    return f;
}

dvec3 sliceGridPosition(const ScalarField& f, const dvec3& p) {
    const dvec3 local = glm::transpose(f.direction) * (p - f.origin);
    return {continuousIndex(f, 0, local.x), continuousIndex(f, 1, local.y), continuousIndex(f, 2, local.z)};
}

}  // namespace octrace
