#include "netcdf/GeoGrid.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace octrace::io::detail {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kEpsDeg = 1e-7;

double posMod(double a, double m) {
    double r = std::fmod(a, m);
    return r < 0.0 ? r + m : r;
}

void requireFinite(const std::string& path, const char* what, const std::vector<double>& v) {
    for (double x : v)
        if (!std::isfinite(x)) throw FileError(path + ": " + what + " axis holds a non-finite value");
}

// +1 increasing, -1 decreasing; throws otherwise.
int monotonicity(const std::string& path, const std::string& what, const std::vector<double>& v) {
    if (v.size() < 2) return 1;
    int sign = v[1] > v[0] ? 1 : -1;
    for (std::size_t n = 1; n < v.size(); ++n)
        if (!(sign > 0 ? v[n] > v[n - 1] : v[n] < v[n - 1]))
            throw FileError(path + ": " + what + " values are not strictly monotonic (" + num(v[n - 1]) + " then " +
                            num(v[n]) + " at index " + std::to_string(n) + ")");
    return sign;
}

std::string regionText(const FieldRequest& req) {
    return num(req.region[0]) + "," + num(req.region[1]) + "," + num(req.region[2]) + "," + num(req.region[3]);
}

void requireTwo(const std::string& path, const FieldRequest& req, std::size_t count, const char* what,
                const std::vector<double>& all) {
    if (count >= 2) return;
    auto [lo, hi] = std::minmax_element(all.begin(), all.end());
    std::string where = req.hasRegion ? "region " + regionText(req) : std::string("the grid");
    throw EmptyResultError(path + ": " + where + " holds " + std::to_string(count) + " " + what +
                           " grid point(s), need at least 2 (the file's " + what + "s run " + num(*lo) + " .. " +
                           num(*hi) + ")");
}

// (unwrapped longitude, stored index), increasing.
std::vector<std::pair<double, std::size_t>> selectLongitudes(const std::string& path, const std::vector<double>& lon,
                                                              const FieldRequest& req, double& lonCentre) {
    std::vector<std::pair<double, std::size_t>> sel;
    if (req.hasRegion) {
        double l0 = req.region[0], l1 = req.region[1] < l0 ? req.region[1] + 360.0 : req.region[1];
        for (std::size_t n = 0; n < lon.size(); ++n) {
            double u = l0 + posMod(lon[n] - l0 + kEpsDeg, 360.0) - kEpsDeg;
            if (u <= l1 + kEpsDeg) sel.emplace_back(u, n);
        }
        lonCentre = 0.5 * (l0 + l1);
    } else {
        // Whole grid: unwrap steps larger than half a turn (a grid stored across its seam).
        double u = lon.empty() ? 0.0 : lon[0];
        for (std::size_t n = 0; n < lon.size(); ++n) {
            if (n > 0) u += std::remainder(lon[n] - lon[n - 1], 360.0);
            sel.emplace_back(u, n);
        }
        std::vector<double> unwrapped;
        for (auto& s : sel) unwrapped.push_back(s.first);
        monotonicity(path, "longitude", unwrapped);
        if (!sel.empty()) lonCentre = 0.5 * (sel.front().first + sel.back().first);
    }
    std::sort(sel.begin(), sel.end());
    // A cyclic grid may store the same meridian twice (0 and 360): keep one.
    sel.erase(std::unique(sel.begin(), sel.end(),
                          [](const auto& a, const auto& b) { return std::abs(a.first - b.first) < kEpsDeg; }),
              sel.end());
    return sel;
}

// The levels of `depthKm` inside req's depth range, deepest first (z increases).
std::vector<std::size_t> selectLevels(const std::string& path, const std::vector<double>& depthKm, const FieldRequest& req,
                                      std::size_t minLevels, int depthOrder) {
    std::vector<std::size_t> zIdx;
    for (std::size_t n = 0; n < depthKm.size(); ++n) {
        double m = depthKm[n] * 1000.0;
        if (!req.hasDepthRange || (m >= req.depthRange[0] - 1e-6 && m <= req.depthRange[1] + 1e-6)) zIdx.push_back(n);
    }
    if (depthOrder > 0) std::reverse(zIdx.begin(), zIdx.end());  // deepest first: z increases
    if (zIdx.size() < minLevels) {
        if (!req.hasDepthRange) throw EmptyResultError(path + ": the vertical axis has fewer than 2 levels");
        auto [lo, hi] = std::minmax_element(depthKm.begin(), depthKm.end());
        throw EmptyResultError(path + ": depth range " + num(req.depthRange[0]) + "," + num(req.depthRange[1]) +
                               " m holds " + std::to_string(zIdx.size()) +
                               " level(s), need at least " + std::to_string(minLevels) + " (the file's levels run " + num(*lo * 1000.0) + " .. " +
                               num(*hi * 1000.0) + " m)");
    }
    return zIdx;
}

// The vertical scale (req's, else the default from the horizontal extent) and m.z; returns the
// depth extent (km) of the levels.
std::pair<double, double> scaleLevels(const std::vector<double>& depthKm, const std::vector<std::size_t>& zIdx,
                                      const FieldRequest& req, double horizontal, GeoMapping& m) {
    double dMin = depthKm[zIdx.front()], dMax = depthKm[zIdx.front()];
    for (std::size_t n : zIdx) {
        dMin = std::min(dMin, depthKm[n]);
        dMax = std::max(dMax, depthKm[n]);
    }
    bool byDefault = req.verticalScale == 0.0;
    m.verticalScale = !byDefault ? req.verticalScale : (dMax > dMin ? 0.25 * horizontal / (dMax - dMin) : 1.0);
    for (std::size_t n : zIdx) {
        m.z.stored.push_back(n);
        m.z.world.push_back(-depthKm[n] * m.verticalScale + 0.0);  // + 0.0: no -0 at the surface
    }
    return {dMin, dMax};
}

std::string verticalScaleNote(double scale, bool byDefault, bool extent) {
    return "vertical scale " + num(scale) +
           (!byDefault ? " (requested)"
            : extent   ? " (default: depth extent = 1/4 of the larger horizontal extent)"
                       : " (default: a single level)") +
           ", z = -depth_km * scale";
}

}  // namespace

bool isUniform(const std::vector<double>& v) {
    if (v.size() < 3) return true;
    double step = (v.back() - v.front()) / double(v.size() - 1);
    for (std::size_t n = 0; n < v.size(); ++n)
        if (std::abs(v[n] - (v.front() + double(n) * step)) > 1e-6 * std::abs(step)) return false;
    return true;
}


GeoMapping mapGeographic(const std::string& path, const std::vector<double>& lon, const std::vector<double>& lat,
                         const std::vector<double>& depthKm, const FieldRequest& req, std::size_t minLevels) {
    requireFinite(path, "longitude", lon);
    requireFinite(path, "latitude", lat);
    requireFinite(path, "vertical", depthKm);
    if (req.hasRegion) checkRegion(req.region, path);
    if (!(req.verticalScale >= 0.0) || !std::isfinite(req.verticalScale))
        throw UsageError(path + ": vertical scale must be positive (0 = default), got " + num(req.verticalScale));
    int latOrder = monotonicity(path, "latitude", lat);
    int depthOrder = monotonicity(path, "vertical", depthKm);

    GeoMapping m;
    auto lonSel = selectLongitudes(path, lon, req, m.lon0);
    requireTwo(path, req, lonSel.size(), "longitude", lon);

    std::vector<std::size_t> latIdx;
    for (std::size_t n = 0; n < lat.size(); ++n)
        if (!req.hasRegion || (lat[n] >= req.region[2] - kEpsDeg && lat[n] <= req.region[3] + kEpsDeg)) latIdx.push_back(n);
    if (latOrder < 0) std::reverse(latIdx.begin(), latIdx.end());
    requireTwo(path, req, latIdx.size(), "latitude", lat);
    m.lat0 = req.hasRegion ? 0.5 * (req.region[2] + req.region[3]) : 0.5 * (lat.front() + lat.back());

    const std::vector<std::size_t> zIdx = selectLevels(path, depthKm, req, minLevels, depthOrder);

    double cosLat0 = std::cos(m.lat0 * kDeg);
    for (auto& [u, n] : lonSel) {
        m.x.stored.push_back(n);
        m.x.world.push_back(kEarthRadiusKm * (u - m.lon0) * kDeg * cosLat0);
    }
    for (std::size_t n : latIdx) {
        m.y.stored.push_back(n);
        m.y.world.push_back(kEarthRadiusKm * (lat[n] - m.lat0) * kDeg);
    }
    double horizontal = std::max(m.x.world.back() - m.x.world.front(), m.y.world.back() - m.y.world.front());
    const auto [dMin, dMax] = scaleLevels(depthKm, zIdx, req, horizontal, m);
    const bool byDefault = req.verticalScale == 0.0;

    m.notes.push_back("geographic: lon0=" + num(m.lon0) + " lat0=" + num(m.lat0) +
                      " (world units km, x = R (lon - lon0) cos(lat0), y = R (lat - lat0), R = 6371)");
    m.notes.push_back((req.hasRegion ? "region " + regionText(req) : std::string("whole grid")) + ": " +
                      std::to_string(lonSel.size()) + " longitudes " + num(lonSel.front().first) + " .. " +
                      num(lonSel.back().first) + ", " + std::to_string(latIdx.size()) + " latitudes " +
                      num(lat[latIdx.front()]) + " .. " + num(lat[latIdx.back()]) + ", " + std::to_string(zIdx.size()) +
                      " levels " + num(dMin * 1000.0) + " .. " + num(dMax * 1000.0) + " m" +
                      (req.hasDepthRange ? " (depth range " + num(req.depthRange[0]) + "," + num(req.depthRange[1]) + " m)" : "") +
                      (isUniform(m.z.world) ? "" : " (uneven)"));
    m.notes.push_back(verticalScaleNote(m.verticalScale, byDefault, dMax > dMin));
    return m;
}

int polarPole(const FieldRequest& req, double latLo, double latHi) {
    if (req.hasRegion) latLo = req.region[2], latHi = req.region[3];
    using P = FieldRequest::Projection;
    if (req.projection == P::LonLat) return 0;
    if (req.projection == P::Polar) return latLo + latHi >= 0.0 ? 1 : -1;
    if (latHi >= kPolarAutoLatitude && latLo >= 0.0) return 1;
    if (latLo <= -kPolarAutoLatitude && latHi <= 0.0) return -1;
    return 0;
}

std::string polarReason(const FieldRequest& req, int pole) {
    const std::string side = pole > 0 ? "north" : "south";
    if (req.projection == FieldRequest::Projection::Polar) return "`map_projection` polar: the " + side + " pole, the side of the region's middle latitude";
    return "chosen automatically: the " + std::string(req.hasRegion ? "region" : "grid") + " lies in the " + side +
           "ern hemisphere and reaches " + num(kPolarAutoLatitude) + " degrees " + side + " or beyond";
}

GeoMapping mapPolar(const std::string& path, const std::vector<double>& xKm, const std::vector<double>& yKm,
                    const std::vector<double>& depthKm, const FieldRequest& req, std::size_t minLevels) {
    requireFinite(path, "vertical", depthKm);
    if (!(req.verticalScale >= 0.0) || !std::isfinite(req.verticalScale))
        throw UsageError(path + ": vertical scale must be positive (0 = default), got " + num(req.verticalScale));
    const int depthOrder = monotonicity(path, "vertical", depthKm);
    GeoMapping m;
    const std::vector<std::size_t> zIdx = selectLevels(path, depthKm, req, minLevels, depthOrder);
    for (std::size_t i = 0; i < xKm.size(); ++i) m.x.stored.push_back(i), m.x.world.push_back(xKm[i]);
    for (std::size_t j = 0; j < yKm.size(); ++j) m.y.stored.push_back(j), m.y.world.push_back(yKm[j]);
    const double horizontal = std::max(xKm.back() - xKm.front(), yKm.back() - yKm.front());
    const auto [dMin, dMax] = scaleLevels(depthKm, zIdx, req, horizontal, m);
    m.notes.push_back((req.hasRegion ? "region " + regionText(req) : std::string("whole grid")) + ": " +
                      std::to_string(xKm.size()) + " x " + std::to_string(yKm.size()) + " polar lattice points, " +
                      std::to_string(zIdx.size()) + " levels " + num(dMin * 1000.0) + " .. " + num(dMax * 1000.0) + " m" +
                      (req.hasDepthRange ? " (depth range " + num(req.depthRange[0]) + "," + num(req.depthRange[1]) + " m)" : "") +
                      (isUniform(m.z.world) ? "" : " (uneven)"));
    m.notes.push_back(verticalScaleNote(m.verticalScale, req.verticalScale == 0.0, dMax > dMin));
    return m;
}

AxisSelection increasingAxis(const std::string& path, const std::string& axisName, const std::vector<double>& values) {
    requireFinite(path, ("'" + axisName + "'").c_str(), values);
    int order = monotonicity(path, "axis '" + axisName + "'", values);
    AxisSelection s;
    for (std::size_t n = 0; n < values.size(); ++n) {
        std::size_t idx = order > 0 ? n : values.size() - 1 - n;
        s.stored.push_back(idx);
        s.world.push_back(values[idx]);
    }
    return s;
}

}  // namespace octrace::io::detail
