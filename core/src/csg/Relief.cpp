#include "octrace/csg/Relief.h"

#include "build/MinMaxPyramid.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace octrace {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = std::numbers::pi / 180.0;
/// Above this many raster cells along an axis, zRange asks the pyramid instead of evaluating
/// the bilinear surface at every grid line crossing the rectangle.
constexpr double kExactCells = 6.0;

}  // namespace

Relief::Relief(ReliefRaster raster, ReliefMapping mapping) : r_(std::move(raster)), m_(mapping) {
    const std::string what = r_.source.empty() ? std::string("relief") : r_.source;
    if (r_.nx < 2 || r_.ny < 2) throw UsageError(what + ": a relief needs at least 2 x 2 heights");
    if (r_.heights.size() != std::size_t(r_.nx) * std::size_t(r_.ny))
        throw UsageError(what + ": " + std::to_string(r_.heights.size()) + " heights for a " + std::to_string(r_.nx) + " x " +
                         std::to_string(r_.ny) + " raster");
    if (!(r_.du > 0.0) || !(r_.dv > 0.0) || !std::isfinite(r_.u0) || !std::isfinite(r_.v0))
        throw UsageError(what + ": the raster's steps must be positive");
    for (int a = 0; a < 3; ++a)
        if (!(m_.scale[a] > 0.0) || !std::isfinite(m_.scale[a])) throw UsageError(what + ": the world scale must be positive");
    if (std::none_of(r_.heights.begin(), r_.heights.end(), [](float h) { return std::isfinite(h); }))
        throw UsageError(what + ": no valid height");
    for (float& h : r_.heights)
        if (!std::isfinite(h)) h = std::numeric_limits<float>::quiet_NaN();
    pyramid_ = std::make_unique<detail::MinMaxPyramid>(r_.heights.data(), ivec3(r_.nx, r_.ny, 1));
}

Relief::~Relief() = default;

std::shared_ptr<const Relief> Relief::geographic(ReliefRaster r, const ScalarField::Geographic& g) {
    if (!g.valid) throw UsageError(r.source + ": a geographic relief needs a geographic field (longitude, latitude, depth)");
    if (g.polar())
        throw UsageError(r.source + ": a geographic relief is laid out on the longitude/latitude mapping only, and this "
                         "field is on the polar stereographic one: give `map_projection` lonlat");
    if (!(r.du > 0.0) || r.nx < 2) throw UsageError(r.source + ": a relief needs at least 2 x 2 heights");
    const double turns = 360.0 / r.du;
    const long period = std::lround(turns);
    const bool global = std::abs(turns - double(period)) < 1e-6 * turns && r.nx >= period;
    if (global) {
        // Columns over lon0 - 180 .. lon0 + 180 on the raster's own meridians.
        ReliefRaster w;
        w.nx = int(period) + 1;
        w.ny = r.ny;
        w.du = r.du;
        w.v0 = r.v0;
        w.dv = r.dv;
        w.source = r.source;
        const long first = long(std::ceil((g.lon0 - 180.0 - r.u0) / r.du - 1e-9));
        w.u0 = r.u0 + double(first) * r.du;
        w.heights.resize(std::size_t(w.nx) * std::size_t(w.ny));
        for (int i = 0; i < w.nx; ++i) {
            const long src = ((first + i) % period + period) % period;
            for (int j = 0; j < w.ny; ++j) w.heights[std::size_t(i) + std::size_t(w.nx) * std::size_t(j)] = r.at(int(src), j);
        }
        r = std::move(w);
    } else {
        const double centre = r.u0 + 0.5 * (r.nx - 1) * r.du;
        r.u0 += 360.0 * std::round((g.lon0 - centre) / 360.0);
    }
    ReliefMapping m;
    m.scale = dvec3(ScalarField::Geographic::kEarthRadiusKm * std::cos(g.lat0 * kDeg) * kDeg,
                    ScalarField::Geographic::kEarthRadiusKm * kDeg, g.verticalScale / 1000.0);
    m.centre = dvec2(g.lon0, g.lat0);
    return std::make_shared<const Relief>(std::move(r), m);
}

double Relief::heightAt(double s, double t) const {
    const double eps = 1e-9;
    if (!(s >= -eps && t >= -eps && s <= r_.nx - 1 + eps && t <= r_.ny - 1 + eps)) return kNaN;
    s = std::clamp(s, 0.0, double(r_.nx - 1));
    t = std::clamp(t, 0.0, double(r_.ny - 1));
    const int i = std::min(int(s), r_.nx - 2), j = std::min(int(t), r_.ny - 2);
    const double fs = s - i, ft = t - j;
    const double a = r_.at(i, j), b = r_.at(i + 1, j), c = r_.at(i, j + 1), d = r_.at(i + 1, j + 1);
    return (1 - ft) * ((1 - fs) * a + fs * b) + ft * ((1 - fs) * c + fs * d);  // NaN propagates
}

double Relief::surfaceZ(double x, double y) const { return m_.scale.z * heightAt(uOf(x), vOf(y)); }

dvec3 Relief::normal(double x, double y) const {
    const double s = uOf(x), t = vOf(y);
    if (!(s >= 0.0 && t >= 0.0 && s <= r_.nx - 1 && t <= r_.ny - 1)) return dvec3(0, 0, 1);
    const int i = std::min(int(s), r_.nx - 2), j = std::min(int(t), r_.ny - 2);
    const double fs = s - i, ft = t - j;
    const double a = r_.at(i, j), b = r_.at(i + 1, j), c = r_.at(i, j + 1), d = r_.at(i + 1, j + 1);
    const double dhds = (1 - ft) * (b - a) + ft * (d - c), dhdt = (1 - fs) * (c - a) + fs * (d - b);
    // s = (centre + x / scale.x - u0) / du: ds/dx = 1 / (scale.x du).
    const dvec3 n(-m_.scale.z * dhds / (m_.scale.x * r_.du), -m_.scale.z * dhdt / (m_.scale.y * r_.dv), 1.0);
    return std::isfinite(n.x) && std::isfinite(n.y) ? glm::normalize(n) : dvec3(0, 0, 1);
}

void Relief::zRange(double x0, double x1, double y0, double y1, double& zmin, double& zmax, bool& complete) const {
    zmin = std::numeric_limits<double>::infinity();
    zmax = -zmin;
    double s0 = uOf(x0), s1 = uOf(x1), t0 = vOf(y0), t1 = vOf(y1);
    const double sn = r_.nx - 1, tn = r_.ny - 1;
    complete = s0 >= 0.0 && t0 >= 0.0 && s1 <= sn && t1 <= tn;
    if (s1 < 0.0 || t1 < 0.0 || s0 > sn || t0 > tn) return;
    s0 = std::max(s0, 0.0), s1 = std::min(s1, sn), t0 = std::max(t0, 0.0), t1 = std::min(t1, tn);
    double hmin = std::numeric_limits<double>::infinity(), hmax = -hmin;
    if (s1 - s0 <= kExactCells && t1 - t0 <= kExactCells) {
        // A bilinear patch is linear along each axis, so over each raster cell's piece of the
        // rectangle its extremes lie at that piece's corners: the rectangle's corners, where
        // its edges cross grid lines, and the samples inside it.
        auto stops = [](double a, double b, double* out) {
            int n = 0;
            out[n++] = a;
            for (double k = std::floor(a) + 1.0; k < b; k += 1.0) out[n++] = k;
            out[n++] = b;
            return n;
        };
        double ss[int(kExactCells) + 3], ts[int(kExactCells) + 3];
        const int ns = stops(s0, s1, ss), nt = stops(t0, t1, ts);
        for (int a = 0; a < ns; ++a)
            for (int b = 0; b < nt; ++b) {
                const double h = heightAt(ss[a], ts[b]);
                if (std::isnan(h)) {
                    complete = false;
                    continue;
                }
                hmin = std::min(hmin, h);
                hmax = std::max(hmax, h);
            }
    } else {
        float mn, mx;
        bool masked = false;
        pyramid_->query(ivec3(int(std::floor(s0)), int(std::floor(t0)), 0), ivec3(int(std::ceil(s1)), int(std::ceil(t1)), 0),
                        mn, mx, &masked);
        if (masked) complete = false;
        if (mn <= mx) hmin = mn, hmax = mx;
    }
    if (hmin <= hmax) zmin = m_.scale.z * hmin, zmax = m_.scale.z * hmax;
}

}  // namespace octrace
