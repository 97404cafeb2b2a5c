#include "netcdf/CurvilinearGrid.h"

#include "input/InputFile.h"
#include "octrace/build/PolarStereographic.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace octrace::io::detail {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kEarthRadiusKm = 6371.0;

AxisRole roleOf(const VariableInfo& v) {
    AxisInfo a;
    a.name = v.shortName;
    a.units = v.units;
    a.standardName = v.standardName;
    return classifyAxis(a).role;
}

// Great-circle angle between two points, degrees.
double arcDeg(double lon1, double lat1, double lon2, double lat2) {
    double s1 = std::sin((lat2 - lat1) * kDeg / 2), s2 = std::sin((lon2 - lon1) * kDeg / 2);
    double h = s1 * s1 + std::cos(lat1 * kDeg) * std::cos(lat2 * kDeg) * s2 * s2;
    return 2.0 * std::asin(std::min(1.0, std::sqrt(h))) / kDeg;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// Inverse bilinear mapping: (u, v) with P = (1-u)(1-v) p0 + u(1-v) p1 + uv p2 + (1-u)v p3, by
// Newton from the centre. False when it does not converge (a degenerate quad).
bool inverseBilinear(const double qx[4], const double qy[4], double px, double py, double& u, double& v) {
    const double e1x = qx[1] - qx[0], e1y = qy[1] - qy[0];
    const double e2x = qx[3] - qx[0], e2y = qy[3] - qy[0];
    const double e3x = qx[0] - qx[1] + qx[2] - qx[3], e3y = qy[0] - qy[1] + qy[2] - qy[3];
    u = 0.5, v = 0.5;
    for (int it = 0; it < 20; ++it) {
        double fx = qx[0] + u * e1x + v * e2x + u * v * e3x - px;
        double fy = qy[0] + u * e1y + v * e2y + u * v * e3y - py;
        double a = e1x + v * e3x, b = e2x + u * e3x, c = e1y + v * e3y, d = e2y + u * e3y;
        double det = a * d - b * c;
        if (det == 0.0 || !std::isfinite(det)) return false;
        double du = (d * fx - b * fy) / det, dv = (a * fy - c * fx) / det;
        u -= du, v -= dv;
        if (std::abs(du) < 1e-10 && std::abs(dv) < 1e-10) return std::isfinite(u) && std::isfinite(v);
    }
    return false;
}

}  // namespace

CurvilinearGrid CurvilinearGrid::read(const std::string& path, const CfSource& file, const VariableInfo& var,
                                      const std::vector<const VariableInfo*>& coords) {
    const std::string what = path + ": variable " + var.signature();
    const VariableInfo *lon = nullptr, *lat = nullptr;
    for (const auto* c : coords) {
        const VariableInfo*& slot = roleOf(*c) == AxisRole::Longitude ? lon : lat;
        if (slot)
            throw InputError(what + " has two 2-D " + (roleOf(*c) == AxisRole::Longitude ? "longitude" : "latitude") +
                             " coordinates, " + slot->signature() + " and " + c->signature() +
                             ": name the pair to use in its `coordinates` attribute");
        slot = c;
    }
    if (!lon || !lat)
        throw InputError(what + " has a 2-D " + (lon ? "longitude " + lon->signature() : "latitude " + lat->signature()) +
                         " but no 2-D " + (lon ? "latitude" : "longitude") + " beside it");
    CurvilinearGrid g;
    g.lonName = lon->signature();
    g.latName = lat->signature();
    // The two dimensions longer than 1 of each coordinate must be two of the variable's, the same
    // for both: a coordinate over other dimensions does not place this variable's samples.
    auto spread = [](const VariableInfo& c) {
        std::vector<std::size_t> d;
        for (std::size_t n = 0; n < c.dimSizes.size(); ++n)
            if (c.dimSizes[n] > 1) d.push_back(n);
        return d;
    };
    auto shape = [](const VariableInfo& v, const std::vector<std::size_t>& dims) {
        std::string s;
        for (std::size_t d : dims) s += (s.empty() ? "" : " x ") + std::to_string(v.dimSizes[d]);
        return s;
    };
    std::vector<std::size_t> varDims;
    std::vector<bool> transposedCoord;  // a coordinate over (x, y) where the variable has (y, x)
    for (const auto* c : {lon, lat}) {
        auto d = spread(*c);
        if (d.size() != 2)
            throw InputError(what + ": its coordinate " + c->signature() + " has " + std::to_string(d.size()) +
                             " dimensions longer than 1, a 2-D longitude/latitude coordinate needs 2");
        std::vector<std::size_t> at;
        for (std::size_t n : d) {
            auto it = std::find(var.dimNames.begin(), var.dimNames.end(), c->dimNames[n]);
            if (it == var.dimNames.end() || var.dimSizes[std::size_t(it - var.dimNames.begin())] != c->dimSizes[n]) break;
            at.push_back(std::size_t(it - var.dimNames.begin()));
        }
        bool transposed = at.size() == 2 && at[0] > at[1];
        if (transposed) std::swap(at[0], at[1]);
        transposedCoord.push_back(transposed);
        if (at.size() != 2 || (!varDims.empty() && at != varDims)) {
            std::string horizontal, names;
            for (std::size_t n = 0; n < var.dimNames.size(); ++n)
                if (var.dimSizes[n] > 1) {
                    horizontal += (horizontal.empty() ? "" : " x ") + std::to_string(var.dimSizes[n]);
                    names += (names.empty() ? "" : ", ") + var.dimNames[n];
                }
            throw FileError(what + ": its 2-D coordinate " + c->signature() + " is " + shape(*c, d) +
                             ", which is not the shape of two of the variable's dimensions (" + names + ": " +
                             horizontal + "): the coordinates must lie over the variable's horizontal dimensions");
        }
        varDims = at;
    }
    g.yDim = varDims[0];
    g.xDim = varDims[1];
    g.ny = var.dimSizes[g.yDim];
    g.nx = var.dimSizes[g.xDim];
    for (const auto* c : {lon, lat}) {
        std::vector<std::uint64_t> start(c->dimSizes.size(), 0);
        std::vector<double> v = file.read(*c, start, c->dimSizes);
        const SampleRules r = file.rules(*c);
        if (transposedCoord[c == lon ? 0 : 1]) {
            std::vector<double> t(v.size());
            for (std::size_t i = 0; i < g.nx; ++i)
                for (std::size_t j = 0; j < g.ny; ++j) t[j * g.nx + i] = v[i * g.ny + j];
            v.swap(t);
        }
        for (std::size_t n = 0; n < v.size(); ++n) {
            double x = v[n] * r.scale + r.offset;
            if (!r.isValid(v[n]) || !std::isfinite(x))
                throw FileError(what + ": its 2-D coordinate " + c->signature() + " is missing or not finite at (" +
                                 std::to_string(n / g.nx) + ", " + std::to_string(n % g.nx) +
                                 "): every grid point needs a longitude and a latitude (fill the land points' "
                                 "coordinates, as the model's mesh file has them)");
            v[n] = x;
        }
        (c == lon ? g.lon_ : g.lat_) = std::move(v);
    }
    g.check(what);
    return g;
}

CurvilinearGrid CurvilinearGrid::fromCoordinates(const std::string& what, std::size_t ny, std::size_t nx,
                                                 std::vector<double> lon, std::vector<double> lat) {
    CurvilinearGrid g;
    g.ny = ny, g.nx = nx;
    g.lonName = "longitude", g.latName = "latitude";
    if (ny < 2 || nx < 2 || lon.size() != ny * nx || lat.size() != ny * nx)
        throw FileError(what + ": 2-D coordinates of " + std::to_string(lon.size()) + " and " +
                         std::to_string(lat.size()) + " values for a " + std::to_string(nx) + " x " +
                         std::to_string(ny) + " grid (at least 2 x 2)");
    for (std::size_t n = 0; n < lon.size(); ++n)
        if (!std::isfinite(lon[n]) || !std::isfinite(lat[n]))
            throw FileError(what + ": 2-D coordinates not finite at (" + std::to_string(n / nx) + ", " +
                             std::to_string(n % nx) + ")");
    g.lon_ = std::move(lon);
    g.lat_ = std::move(lat);
    g.check(what);
    return g;
}

CurvilinearGrid CurvilinearGrid::fromAxes(const std::string& what, const std::vector<double>& lon,
                                          const std::vector<double>& lat, std::size_t lonDim, std::size_t latDim,
                                          const std::string& lonName, const std::string& latName) {
    const bool latRows = latDim < lonDim;  // rows along the slower dimension, as the variable stores them
    const std::size_t ny = latRows ? lat.size() : lon.size(), nx = latRows ? lon.size() : lat.size();
    std::vector<double> lon2(ny * nx), lat2(ny * nx);
    for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx; ++i) {
            lon2[j * nx + i] = latRows ? lon[i] : lon[j];
            lat2[j * nx + i] = latRows ? lat[j] : lat[i];
        }
    CurvilinearGrid g = fromCoordinates(what, ny, nx, std::move(lon2), std::move(lat2));
    g.yDim = std::min(lonDim, latDim);
    g.xDim = std::max(lonDim, latDim);
    g.lonName = lonName, g.latName = latName;
    g.northFold = false;  // a regular grid's top row is a parallel, never a fold
    return g;
}

void CurvilinearGrid::check(const std::string& what) {
    if (ny < 2 || nx < 2)
        throw FileError(what + ": its 2-D coordinates " + lonName + " and " + latName + " are " + std::to_string(nx) +
                         " x " + std::to_string(ny) + ", a curvilinear grid needs at least 2 x 2 points");
    for (std::size_t n = 0; n < lat_.size(); ++n) {
        const std::string at = " at (" + std::to_string(n / nx) + ", " + std::to_string(n % nx) + ")";
        if (lat_[n] < -90.0 || lat_[n] > 90.0)
            throw FileError(what + ": its latitude " + latName + " is " + num(lat_[n]) + at + ", outside -90 .. 90 degrees");
        if (std::abs(lon_[n]) > 1e4)
            throw FileError(what + ": its longitude " + lonName + " is " + num(lon_[n]) + at +
                             ", not a longitude in degrees");
    }
    periodicX = detectPeriodic();
    northFold = periodicX && detectFold();
}

double CurvilinearGrid::medianStepDeg() const {
    std::vector<double> steps;
    const std::size_t sy = std::max<std::size_t>(1, ny / 32), sx = std::max<std::size_t>(1, nx / 32);
    for (std::size_t j = 0; j + 1 < ny; j += sy)
        for (std::size_t i = 0; i + 1 < nx; i += sx) {
            std::size_t a = j * nx + i;
            steps.push_back(arcDeg(lon_[a], lat_[a], lon_[a + 1], lat_[a + 1]));
            steps.push_back(arcDeg(lon_[a], lat_[a], lon_[a + nx], lat_[a + nx]));
        }
    double m = median(steps);
    return m > 0.0 ? m : 1.0;
}

// The last column neighbours the first: in most rows they are no farther apart than 1.5 times
// the step before the last column.
bool CurvilinearGrid::detectPeriodic() const {
    if (nx < 3) return false;
    std::size_t near = 0;
    for (std::size_t j = 0; j < ny; ++j) {
        std::size_t a = j * nx;
        double seam = arcDeg(lon_[a + nx - 1], lat_[a + nx - 1], lon_[a], lat_[a]);
        double step = arcDeg(lon_[a + nx - 2], lat_[a + nx - 2], lon_[a + nx - 1], lat_[a + nx - 1]);
        if (seam <= 1.5 * step + 1e-9) ++near;
    }
    return near * 10 >= ny * 9;
}

// A tripolar fold: above the top row lies the top row itself mirrored (column i meets column
// nx-1-i), so each top point is about one row step from its mirror.
bool CurvilinearGrid::detectFold() const {
    if (ny < 2) return false;
    std::vector<double> ratio;
    const std::size_t top = (ny - 1) * nx, below = (ny - 2) * nx;
    for (std::size_t i = 0; i < nx; ++i) {
        std::size_t m = nx - 1 - i;
        double across = arcDeg(lon_[top + i], lat_[top + i], lon_[top + m], lat_[top + m]);
        double row = arcDeg(lon_[top + i], lat_[top + i], lon_[below + i], lat_[below + i]);
        if (row > 0.0) ratio.push_back(across / row);
    }
    double r = median(ratio);
    return r > 0.3 && r < 3.0;
}

namespace {
// The requested region as west, east (unwrapped past west), south, north, degrees.
void regionBox(const FieldRequest& req, double& w, double& e, double& s, double& n) {
    w = req.region[0];
    e = req.region[1] <= w ? req.region[1] + 360.0 : req.region[1];
    s = req.region[2];
    n = req.region[3];
}
}  // namespace

CurvilinearGrid::Lattice CurvilinearGrid::lattice(const std::string& path, const FieldRequest& req, int samples) const {
    double w, e, s, n;
    if (req.hasRegion) {
        regionBox(req, w, e, s, n);
    } else {
        // Unwrap around the centre point; a grid that goes round (or nearly) gets the whole circle.
        const double ref = lon_[(ny / 2) * nx + nx / 2];
        w = INFINITY, e = -INFINITY, s = INFINITY, n = -INFINITY;
        for (std::size_t k = 0; k < lon_.size(); ++k) {
            double u = ref + std::remainder(lon_[k] - ref, 360.0);
            w = std::min(w, u), e = std::max(e, u);
            s = std::min(s, lat_[k]), n = std::max(n, lat_[k]);
        }
        if (periodicX || e - w > 359.0) {  // the whole circle, from the dateline
            w = -180.0;
            e = 180.0;
        }
    }
    const double lat0 = 0.5 * (s + n), cosLat0 = std::max(0.05, std::cos(lat0 * kDeg));
    const double xKm = (e - w) * kDeg * kEarthRadiusKm * cosLat0, yKm = (n - s) * kDeg * kEarthRadiusKm;
    const double extentKm = std::max(xKm, yKm);
    double stepKm;
    const double sourceKm = medianStepDeg() * kDeg * kEarthRadiusKm;
    Lattice L;
    if (samples > 1) {
        stepKm = std::max(extentKm / double(samples - 1), sourceKm / 4.0);  // finer than 1/4 cell adds nothing
        L.how = std::to_string(samples) + " points along the larger extent (the octree's 2^depth + 1)";
        if (stepKm > extentKm / double(samples - 1)) L.how = "a quarter of the source's median cell (finer adds nothing)";
    } else {
        stepKm = sourceKm;
        L.how = "the source's median cell";
    }
    L.latStep = stepKm / (kDeg * kEarthRadiusKm);
    L.lonStep = L.latStep / cosLat0;
    const bool whole = e - w >= 360.0 - 1e-9;
    auto fill = [&](std::vector<double>& v, double a, double b, double step, bool open) {
        const double points = std::floor((b - a) / step + 1e-9) + 1.0;
        if (!(points <= double(kMaxAxisPoints)))
            throw InputError(path + ": resampling the curvilinear grid at a step of " + num(stepKm) + " km would take " +
                             num(points) + " lattice points along one axis, more than the " +
                             std::to_string(kMaxAxisPoints) + " octrace reads; choose a smaller region");
        if (!(points >= 1.0))  // an empty or reversed span, or a step of the wrong sign (broken coordinates)
            throw EmptyResultError(path + ": the curvilinear grid spans no lattice point from " + num(a) + " to " +
                                   num(b) + " degrees at a step of " + num(step) + " degrees");
        std::size_t count = std::size_t(points);
        if (open && a + double(count - 1) * step >= b - 1e-9) --count;  // the circle's end is its start
        for (std::size_t k = 0; k < count; ++k) v.push_back(a + double(k) * step);
    };
    if (whole) L.lonStep = 360.0 / std::ceil(360.0 / L.lonStep);  // the circle closes on a lattice point
    fill(L.lon, w, e, L.lonStep, whole);
    fill(L.lat, s, n, L.latStep, false);
    // The lookup (corners and weights per lattice point) counts against the memory budget.
    checkMemoryBudget(path + ": resampling the curvilinear grid onto " + std::to_string(L.lon.size()) + " x " +
                          std::to_string(L.lat.size()) + " lattice points",
                      saturatingMultiply(L.lon.size() * L.lat.size(), sizeof(Weights)), req.memoryBudget);
    if (L.lon.size() < 2 || L.lat.size() < 2)
        throw EmptyResultError(path + ": the region holds fewer than 2 lattice points along an axis at the resampling "
                                      "step of " + num(stepKm) + " km");
    return L;
}

CurvilinearGrid::PlaneLattice CurvilinearGrid::planeLattice(const std::string& path, const FieldRequest& req, int pole,
                                                            int samples) const {
    double w, e, s, n;
    if (req.hasRegion) {
        regionBox(req, w, e, s, n);
    } else {  // the source's latitudes on the pole's side, the whole circle
        const auto [lo, hi] = std::minmax_element(lat_.begin(), lat_.end());
        w = -180.0, e = 180.0;
        s = pole > 0 ? std::max(*lo, 0.0) : -90.0;
        n = pole > 0 ? 90.0 : std::min(*hi, 0.0);
        if (!(s < n))
            throw EmptyResultError(path + ": the curvilinear grid has no latitude on the " +
                                   std::string(pole > 0 ? "north" : "south") + "ern side for the polar mapping");
    }
    PlaneLattice L;
    L.pole = pole;
    const bool whole = e - w >= 360.0 - 1e-9;
    L.lon0 = whole ? 0.0 : 0.5 * (w + e);
    // The bounding box of the region's image: its boundary, sampled.
    double xLo = INFINITY, xHi = -INFINITY, yLo = INFINITY, yHi = -INFINITY;
    auto add = [&](double lon, double lat) {
        const dvec2 p = polar::planeFromLonLat(pole, L.lon0, lon, lat);
        xLo = std::min(xLo, p.x), xHi = std::max(xHi, p.x), yLo = std::min(yLo, p.y), yHi = std::max(yHi, p.y);
    };
    for (int t = 0; t <= 1440; ++t) add(w + (e - w) * t / 1440.0, s), add(w + (e - w) * t / 1440.0, n);
    for (int t = 0; t <= 360; ++t) add(w, s + (n - s) * t / 360.0), add(e, s + (n - s) * t / 360.0);
    const double extentKm = std::max(xHi - xLo, yHi - yLo);
    const double sourceKm = medianStepDeg() * kDeg * kEarthRadiusKm;
    if (samples > 1) {
        L.stepKm = std::max(extentKm / double(samples - 1), sourceKm / 4.0);
        L.how = L.stepKm > extentKm / double(samples - 1) ? "a quarter of the source's median cell (finer adds nothing)"
                                                          : std::to_string(samples) + " points along the larger extent (the octree's 2^depth + 1)";
    } else {
        L.stepKm = sourceKm;
        L.how = "the source's median cell";
    }
    L.x0 = 0.5 * (xLo + xHi), L.y0 = 0.5 * (yLo + yHi);
    auto fill = [&](std::vector<double>& v, double lo, double hi) {
        const double points = std::floor((hi - lo) / L.stepKm + 1e-9) + 1.0;
        if (!(points <= double(kMaxAxisPoints)))
            throw InputError(path + ": resampling onto the polar lattice at a step of " + num(L.stepKm) + " km would take " +
                             num(points) + " lattice points along one axis, more than the " +
                             std::to_string(kMaxAxisPoints) + " octrace reads; choose a smaller region");
        if (!(points >= 2.0))
            throw EmptyResultError(path + ": the region holds fewer than 2 polar lattice points along an axis at the "
                                          "resampling step of " + num(L.stepKm) + " km");
        const std::size_t count = std::size_t(points);
        for (std::size_t k = 0; k < count; ++k) v.push_back((double(k) - 0.5 * double(count - 1)) * L.stepKm);
    };
    fill(L.x, xLo, xHi);
    fill(L.y, yLo, yHi);
    checkMemoryBudget(path + ": resampling onto " + std::to_string(L.x.size()) + " x " + std::to_string(L.y.size()) +
                          " polar lattice points",
                      saturatingMultiply(L.x.size() * L.y.size(), sizeof(Weights) + 1), req.memoryBudget);
    L.inside.assign(L.x.size() * L.y.size(), 0);
    for (std::size_t j = 0; j < L.y.size(); ++j)
        for (std::size_t i = 0; i < L.x.size(); ++i) {
            const dvec2 ll = polar::lonLatFromPlane(pole, L.lon0, L.x[i] + L.x0, L.y[j] + L.y0);
            const double u = w + std::fmod(std::fmod(ll.x - w + 1e-7, 360.0) + 360.0, 360.0) - 1e-7;
            const bool lonIn = whole || std::abs(ll.y) >= 90.0 - 1e-9 || u <= e + 1e-7;
            L.inside[j * L.x.size() + i] = lonIn && ll.y >= s - 1e-7 && ll.y <= n + 1e-7;
        }
    return L;
}

void CurvilinearGrid::buildPlaneLookup(const PlaneLattice& L) {
    lookup_.assign(L.x.size() * L.y.size(), Weights{{kNone, kNone, kNone, kNone}, {0, 0, 0, 0}});
    skipped_ = 0;
    poleCap_ = false;
    std::vector<double> px(lon_.size()), py(lon_.size());
    std::vector<std::uint8_t> far(lon_.size());
    for (std::size_t k = 0; k < lon_.size(); ++k) {
        const dvec2 p = polar::planeFromLonLat(L.pole, L.lon0, lon_[k], lat_[k]);
        px[k] = p.x - L.x0, py[k] = p.y - L.y0;
        far[k] = double(L.pole) * lat_[k] < -60.0;  // 150 degrees or more from the pole: the plane runs off
    }
    static const std::vector<double> noShift{0.0};
    auto quad = [&](const std::uint32_t q[4]) {
        double qx[4], qy[4];
        double latLo = INFINITY, latHi = -INFINITY;
        for (int k = 0; k < 4; ++k) {
            if (far[q[k]]) return;
            qx[k] = px[q[k]], qy[k] = py[q[k]];
            latLo = std::min(latLo, lat_[q[k]]), latHi = std::max(latHi, lat_[q[k]]);
        }
        if (latHi - latLo > 45.0) {
            ++skipped_;
            return;
        }
        rasteriseQuad(q, qx, qy, 1.0, noShift, L.x, L.y);
    };
    auto at = [&](std::size_t j, std::size_t i) { return std::uint32_t(j * nx + i); };
    const std::size_t columns = periodicX ? nx : nx - 1;
    for (std::size_t j = 0; j + 1 < ny; ++j)
        for (std::size_t i = 0; i < columns; ++i) {
            std::size_t i1 = (i + 1) % nx;
            const std::uint32_t q[4] = {at(j, i), at(j, i1), at(j + 1, i1), at(j + 1, i)};
            quad(q);
        }
    if (northFold)
        for (std::size_t i = 0; i < nx; ++i) {
            std::size_t i1 = (i + 1) % nx;
            const std::uint32_t q[4] = {at(ny - 1, i), at(ny - 1, i1), at(ny - 1, nx - 1 - i1), at(ny - 1, nx - 1 - i)};
            quad(q);
        }
    // A first or last row that rings the pole (a regular grid's 89.5 N): the strips across it,
    // each the convex quad of ring points i, i+1, i+h, i+h+1 (h = nx / 2), cover the disc inside
    // the ring, and the pole gets the mean of opposite points.
    if (periodicX && nx >= 4)
        for (std::size_t r : {std::size_t(0), ny - 1}) {
            if (northFold && r == ny - 1) continue;
            bool ring = true;
            for (std::size_t i = 0; i < nx && ring; ++i) ring = double(L.pole) * lat_[r * nx + i] >= 80.0;
            if (!ring) continue;
            poleCap_ = true;
            const std::size_t h = nx / 2;
            for (std::size_t i = 0; i < nx; ++i) {
                const std::uint32_t q[4] = {at(r, i), at(r, (i + 1) % nx), at(r, (i + h) % nx), at(r, (i + h + 1) % nx)};
                quad(q);
            }
        }
    for (std::size_t p = 0; p < lookup_.size(); ++p)
        if (!L.inside[p]) lookup_[p].corner[0] = kNone;
}

std::string CurvilinearGrid::planeDescription(const PlaneLattice& L) const {
    const std::size_t inside = std::size_t(std::count(L.inside.begin(), L.inside.end(), std::uint8_t(1)));
    std::string s = "source " + std::to_string(nx) + " x " +
                    std::to_string(ny) + " points (" + lonName + ", " + latName + "), median cell " +
                    num(medianStepDeg()) + " deg" + (periodicX ? ", periodic in x" : "") +
                    (northFold ? ", tripolar north fold" : "");
    s += "; resampled onto a regular " + std::to_string(L.x.size()) + " x " + std::to_string(L.y.size()) +
         " lattice in the polar stereographic plane (step " + num(L.stepKm) + " km: " + L.how +
         ") by inverse bilinear mapping in each source cell projected, ocean corners only (land where less than half "
         "the weight is ocean)" + (poleCap_ ? ", the ring of points round the pole bridged across it" : "") + "; " +
         std::to_string(coveredPoints()) + " of the " + std::to_string(inside) + " lattice points inside the region lie in a cell";
    if (skipped_) s += ", " + std::to_string(skipped_) + " degenerate cell(s) skipped";
    return s;
}

void CurvilinearGrid::rasterise(const std::uint32_t corner[4], const std::vector<double>& lonOut,
                                const std::vector<double>& latOut) {
    double qx[4], qy[4];
    const double ref = lon_[corner[0]];
    for (int k = 0; k < 4; ++k) {
        qx[k] = ref + std::remainder(lon_[corner[k]] - ref, 360.0);  // unwrapped around the first corner
        qy[k] = lat_[corner[k]];
    }
    const double lonLo = *std::min_element(qx, qx + 4), lonHi = *std::max_element(qx, qx + 4);
    const double latLo = *std::min_element(qy, qy + 4), latHi = *std::max_element(qy, qy + 4);
    // A cell enclosing a pole (or spanning a quarter of the globe) is no quad in longitude/latitude.
    if (lonHi - lonLo > 90.0 || latHi - latLo > 45.0) {
        ++skipped_;
        return;
    }
    // cos(lat) keeps the shape near the poles in the convexity test.
    static const std::vector<double> shifts{-720.0, -360.0, 0.0, 360.0, 720.0};
    rasteriseQuad(corner, qx, qy, std::cos(0.25 * (qy[0] + qy[1] + qy[2] + qy[3]) * kDeg), shifts, lonOut, latOut);
}

void CurvilinearGrid::rasteriseQuad(const std::uint32_t corner[4], const double qx[4], const double qy[4], double c,
                                    const std::vector<double>& shifts, const std::vector<double>& lonOut,
                                    const std::vector<double>& latOut) {
    // Convex and not folded: the four turns agree in sign.
    int pos = 0, neg = 0;
    for (int k = 0; k < 4; ++k) {
        int a = (k + 1) % 4, b = (k + 2) % 4;
        double cross = (qx[a] - qx[k]) * c * (qy[b] - qy[a]) - (qy[a] - qy[k]) * (qx[b] - qx[a]) * c;
        pos += cross > 0.0, neg += cross < 0.0;
    }
    if ((pos && neg) || (pos + neg) < 3) {
        ++skipped_;
        return;
    }
    const double lonLo = *std::min_element(qx, qx + 4), lonHi = *std::max_element(qx, qx + 4);
    const double latLo = *std::min_element(qy, qy + 4), latHi = *std::max_element(qy, qy + 4);
    const double lon0 = lonOut.front(), lat0 = latOut.front();
    const double dLon = lonOut.size() > 1 ? lonOut[1] - lonOut[0] : 1.0, dLat = latOut.size() > 1 ? latOut[1] - latOut[0] : 1.0;
    const long nxo = long(lonOut.size()), nyo = long(latOut.size());
    // Lattice index ranges, clamped as doubles before any conversion.
    auto first = [](double x, long n) { return long(std::clamp(std::ceil(x - 1e-9), 0.0, double(n))); };
    auto last = [](double x, long n) { return long(std::clamp(std::floor(x + 1e-9), -1.0, double(n - 1))); };
    const long j0 = first((latLo - lat0) / dLat, nyo), j1 = last((latHi - lat0) / dLat, nyo);
    for (double shift : shifts) {
        const long i0 = first((lonLo + shift - lon0) / dLon, nxo), i1 = last((lonHi + shift - lon0) / dLon, nxo);
        for (long j = j0; j <= j1; ++j)
            for (long i = i0; i <= i1; ++i) {
                Weights& out = lookup_[std::size_t(j) * std::size_t(nxo) + std::size_t(i)];
                if (out.corner[0] != kNone) continue;  // on an edge two cells share: the first keeps it
                double u, v;
                if (!inverseBilinear(qx, qy, lonOut[std::size_t(i)] - shift, latOut[std::size_t(j)], u, v)) continue;
                constexpr double eps = 1e-7;
                if (u < -eps || u > 1 + eps || v < -eps || v > 1 + eps) continue;
                u = std::clamp(u, 0.0, 1.0), v = std::clamp(v, 0.0, 1.0);
                const double w[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
                for (int k = 0; k < 4; ++k) out.corner[k] = corner[k], out.w[k] = float(w[k]);
            }
    }
}

void CurvilinearGrid::buildLookup(const std::vector<double>& lonOut, const std::vector<double>& latOut) {
    lookup_.assign(lonOut.size() * latOut.size(), Weights{{kNone, kNone, kNone, kNone}, {0, 0, 0, 0}});
    skipped_ = 0;
    auto at = [&](std::size_t j, std::size_t i) { return std::uint32_t(j * nx + i); };
    const std::size_t columns = periodicX ? nx : nx - 1;
    for (std::size_t j = 0; j + 1 < ny; ++j)
        for (std::size_t i = 0; i < columns; ++i) {
            std::size_t i1 = (i + 1) % nx;
            const std::uint32_t q[4] = {at(j, i), at(j, i1), at(j + 1, i1), at(j + 1, i)};
            rasterise(q, lonOut, latOut);
        }
    if (northFold)  // the cells between the top row and its mirror image
        for (std::size_t i = 0; i < nx; ++i) {
            std::size_t i1 = (i + 1) % nx;
            const std::uint32_t q[4] = {at(ny - 1, i), at(ny - 1, i1), at(ny - 1, nx - 1 - i1), at(ny - 1, nx - 1 - i)};
            rasterise(q, lonOut, latOut);
        }
}

namespace {

// The weighted mean of the valid corners of each lattice point; `sample(c, x)` says whether
// source point c is valid and gives its value in x. Land where less than half the weight is
// valid (ocean): the coast stays between the source's ocean and land points, as on a regular
// grid, and only ocean values are averaged.
template <class Weights, class Sample, class Out>
void resampleLookup(const std::vector<Weights>& lookup, std::uint32_t none, Sample&& sample, Out&& put) {
    for (std::size_t p = 0; p < lookup.size(); ++p) {
        const Weights& w = lookup[p];
        double ws = 0.0, vs = 0.0;
        if (w.corner[0] != none)
            for (int k = 0; k < 4; ++k) {
                double x = 0.0;
                if (!sample(w.corner[k], x) || !std::isfinite(x)) continue;
                ws += w.w[k];
                vs += w.w[k] * x;
            }
        put(p, ws >= 0.5, ws >= 0.5 ? vs / ws : 0.0);
    }
}

}  // namespace

void CurvilinearGrid::resample(const std::vector<double>& raw, const SampleRules& rules, float* values,
                               std::uint8_t* valid) const {
    resampleLookup(
        lookup_, kNone,
        [&](std::uint32_t c, double& x) {
            if (!rules.isValid(raw[c])) return false;
            x = raw[c] * rules.scale + rules.offset;
            return true;
        },
        [&](std::size_t p, bool ok, double x) {
            values[p] = ok ? float(x) : 0.0f;
            valid[p] = ok && std::isfinite(values[p]) ? 1 : 0;
            if (!valid[p]) values[p] = 0.0f;
        });
}

void CurvilinearGrid::resample(const double* values, const std::uint8_t* valid, double* out,
                               std::uint8_t* outValid) const {
    resampleLookup(
        lookup_, kNone,
        [&](std::uint32_t c, double& x) {
            x = values[c];
            return valid[c] != 0;
        },
        [&](std::size_t p, bool ok, double x) {
            out[p] = ok ? x : std::numeric_limits<double>::quiet_NaN();
            outValid[p] = ok ? 1 : 0;
        });
}

std::pair<double, double> CurvilinearGrid::latitudeRange() const {
    const auto [lo, hi] = std::minmax_element(lat_.begin(), lat_.end());
    return {*lo, *hi};
}

std::size_t CurvilinearGrid::coveredPoints() const {
    return std::size_t(std::count_if(lookup_.begin(), lookup_.end(), [](const Weights& w) { return w.corner[0] != kNone; }));
}

std::string CurvilinearGrid::description(const Lattice& lattice, std::size_t nxOut, std::size_t nyOut) const {
    std::string s = "curvilinear grid: 2-D coordinates " + lonName + " and " + latName + ", source " +
                    std::to_string(nx) + " x " + std::to_string(ny) + " points, median cell " + num(medianStepDeg()) +
                    " deg" + (periodicX ? ", periodic in x" : "") + (northFold ? ", tripolar north fold" : "");
    s += "; resampled onto a regular " + std::to_string(nxOut) + " x " + std::to_string(nyOut) +
         " longitude/latitude lattice (step " + num(lattice.lonStep) + " x " +
         num(lattice.latStep) + " deg: " + lattice.how + ") by inverse bilinear mapping in each source cell, ocean corners only (land where "
         "less than half the weight is ocean); " +
         std::to_string(coveredPoints()) + " of " + std::to_string(lookup_.size()) + " lattice points inside a cell";
    if (skipped_) s += ", " + std::to_string(skipped_) + " degenerate or pole-enclosing cell(s) skipped";
    return s;
}

}  // namespace octrace::io::detail
