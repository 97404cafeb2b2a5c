#pragma once
/// @file AnalyticField.h
/// Fields with known isosurfaces, for tests, benchmarks and the data_samples demo.
#include "octrace/build/ScalarField.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace octrace {

/// Samples f at every grid point of a uniform grid (origin, spacing, identity direction).
ScalarField sampleFunction(const std::string& name, ivec3 dims, dvec3 origin, dvec3 spacing,
                           const std::function<float(const dvec3&)>& f);

/// Names of the analytic samples: "sphere", "torus", "gyroid", "noise", "spheres".
std::vector<std::string> analyticFieldNames();

/// The names joined with ", " (for help and error texts).
std::string analyticFieldList();

/// A named analytic field on n^3 samples over [-1,1]^3:
///  - sphere: 0.7 - |p| (isosurface 0 is the sphere of radius 0.7)
///  - torus: 0.25 - distance to the circle of radius 0.6 in the xy plane (iso 0)
///  - gyroid: sin x cos y + sin y cos z + sin z cos x with p scaled by 2*pi (iso 0)
///  - noise: seeded value noise (thin, scattered features; iso 0), seed from `seed`
///  - spheres: 60 disjoint balls of radii 0.04 to 0.3 (log-uniform) at positions drawn from
///    `seed`; the field is the largest of radius - distance to the centre (iso 0: their union)
/// Throws UsageError for an unknown name or n < 2.
ScalarField makeAnalyticField(const std::string& name, int n, std::uint32_t seed = 1);

}  // namespace octrace
