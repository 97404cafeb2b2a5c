#pragma once
/// @file Solid.h
/// Primitive solids for CSG and cut-aways (csg/Csg.h), in world units: box, sphere, cylinder,
/// half-space. All are convex, which the voxelization uses: an octant whose 8 corners are
/// inside is wholly inside.
#include "octrace/util/Math.h"

#include <string>

namespace octrace {

struct Solid {
    enum class Kind { Box, Sphere, Cylinder, HalfSpace };
    Kind kind = Kind::Box;
    dvec3 a{0.0};    ///< box: min corner; sphere: centre; cylinder: one end of the axis; half-space: a point on the plane
    dvec3 b{0.0};    ///< box: max corner; cylinder: the other end; half-space: the outward normal (unit)
    double r = 0.0;  ///< sphere, cylinder: radius

    /// Signed distance (negative inside; exact Euclidean distance for every kind), world units.
    double distance(const dvec3& p) const;
    /// Outward unit normal of the surface nearest p (the gradient of distance()).
    dvec3 normal(const dvec3& p) const;
    /// "box:X0,Y0,Z0,X1,Y1,Z1" etc., as parseSolid reads it.
    std::string describe() const;
};

/// Parses "box:X0,Y0,Z0,X1,Y1,Z1", "sphere:X,Y,Z,R", "cylinder:X0,Y0,Z0,X1,Y1,Z1,R" (the axis
/// from point 0 to point 1, flat ends) or "halfspace:X,Y,Z,NX,NY,NZ" (the solid is the side the
/// normal points away from: (p - X) . N <= 0). Throws UsageError naming what is wrong (unknown
/// kind, wrong count, not a number, an empty box, a radius not positive, a zero normal).
Solid parseSolid(const std::string& spec);
/// Whether `spec` names a solid ("box:", "sphere:", "cylinder:", "halfspace:"), not a file.
bool isSolidSpec(const std::string& spec);

}  // namespace octrace
