#pragma once
/// @file PolarStereographic.h
/// The polar stereographic projection of ScalarField::Geographic's polar mapping, on the sphere
/// of radius ScalarField::Geographic::kEarthRadiusKm, true scale at
/// ScalarField::Geographic::kPolarStandardParallel (71 degrees, as EPSG:3995 and EPSG:3031).
/// Plane coordinates in km with the pole at the origin; world coordinates subtract (x0, y0).
/// Header-only, thread-safe, no state.
#include "octrace/build/ScalarField.h"
#include "octrace/util/Math.h"

#include <cmath>
#include <numbers>

namespace octrace::polar {

inline constexpr double kDeg = std::numbers::pi / 180.0;

/// rho at the pole's own side: R (1 + sin phi_c) tan(45 deg - |lat| / 2), |lat| seen from the pole.
inline double scaleKm() {
    return ScalarField::Geographic::kEarthRadiusKm * (1.0 + std::sin(ScalarField::Geographic::kPolarStandardParallel * kDeg));
}

/// Plane position (km, pole at the origin) of (lonDeg, latDeg) for `pole` (+1 north, -1 south)
/// and central meridian `lon0Deg`. Finite for every latitude but the opposite pole.
inline dvec2 planeFromLonLat(int pole, double lon0Deg, double lonDeg, double latDeg) {
    const double rho = scaleKm() * std::tan((45.0 - 0.5 * double(pole) * latDeg) * kDeg);
    const double a = (lonDeg - lon0Deg) * kDeg;
    return {rho * std::sin(a), -double(pole) * rho * std::cos(a)};
}

/// (longitude, latitude) in degrees of a plane position; the longitude within lon0 +- 180
/// (lon0 itself at the pole).
inline dvec2 lonLatFromPlane(int pole, double lon0Deg, double x, double y) {
    const double rho = std::hypot(x, y);
    const double lat = double(pole) * (90.0 - 2.0 * std::atan(rho / scaleKm()) / kDeg);
    const double lon = rho > 0.0 ? lon0Deg + std::atan2(x, -double(pole) * y) / kDeg : lon0Deg;
    return {lon, lat};
}

/// World (x, y) of a longitude/latitude on a polar Geographic mapping.
inline dvec2 worldFromLonLat(const ScalarField::Geographic& g, double lonDeg, double latDeg) {
    return planeFromLonLat(g.pole, g.lon0, lonDeg, latDeg) - dvec2(g.x0, g.y0);
}

/// Longitude/latitude of a world (x, y) on a polar Geographic mapping.
inline dvec2 lonLatFromWorld(const ScalarField::Geographic& g, double x, double y) {
    return lonLatFromPlane(g.pole, g.lon0, x + g.x0, y + g.y0);
}

}  // namespace octrace::polar
