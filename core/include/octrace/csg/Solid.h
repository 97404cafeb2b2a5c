#pragma once
/// @file Solid.h
/// Solids for CSG and cut-aways (csg/Csg.h), in world units: the primitives box, sphere,
/// cylinder and half-space, and the ground under a relief surface (csg/Relief.h). The
/// primitives are convex, which classify() uses: an octant whose 8 corners are inside is
/// wholly inside. The relief is not: its octants are told by the surface's height range over
/// their footprint.
#include "octrace/util/Math.h"

#include <cstdint>
#include <memory>
#include <string>

namespace octrace {

class Relief;

/// How much of a box a solid holds.
enum class SolidCover : std::uint8_t { Outside, Inside, Mixed };

struct Solid {
    enum class Kind { Box, Sphere, Cylinder, HalfSpace, Relief };
    Kind kind = Kind::Box;
    dvec3 a{0.0};    ///< box: min corner; sphere: centre; cylinder: one end of the axis; half-space: a point on the plane
    dvec3 b{0.0};    ///< box: max corner; cylinder: the other end; half-space: the outward normal (unit)
    double r = 0.0;  ///< sphere, cylinder: radius
    /// relief: the surface; the solid is every point at or below it (z <= surfaceZ(x, y)),
    /// nothing where the relief has no height. Shared, immutable.
    std::shared_ptr<const Relief> relief;

    /// The solid under `r`'s surface.
    static Solid below(std::shared_ptr<const Relief> r);
    /// Every kind but the relief.
    bool convex() const { return kind != Kind::Relief; }

    /// Signed distance (negative inside), world units: the exact Euclidean distance for the
    /// primitives; for a relief the vertical distance to the surface (its sign is exact, its
    /// size at least the true distance), +infinity where the relief has no height.
    double distance(const dvec3& p) const;
    /// Outward unit normal of the surface nearest p (the gradient of distance()); for a relief
    /// the surface's upward normal above or below p.
    dvec3 normal(const dvec3& p) const;
    /// Whether the box [lo, hi] is wholly inside, wholly outside or in part inside. Inside and
    /// Outside are exact claims; Mixed may be said of a box that is not (primitives: one whose
    /// corners are not all inside but that is within its circumradius of the surface).
    SolidCover classify(const dvec3& lo, const dvec3& hi) const;
    /// "box:X0,Y0,Z0,X1,Y1,Z1" etc., as parseSolid reads it; "relief:SOURCE" for a relief.
    std::string describe() const;
};

/// Parses "box:X0,Y0,Z0,X1,Y1,Z1", "sphere:X,Y,Z,R", "cylinder:X0,Y0,Z0,X1,Y1,Z1,R" (the axis
/// from point 0 to point 1, flat ends) or "halfspace:X,Y,Z,NX,NY,NZ" (the solid is the side the
/// normal points away from: (p - X) . N <= 0). Throws UsageError naming what is wrong (unknown
/// kind, wrong count, not a number, an empty box, a radius not positive, a zero normal).
Solid parseSolid(const std::string& spec);
/// Whether `spec` names a primitive solid ("box:", "sphere:", "cylinder:", "halfspace:"), not a file.
bool isSolidSpec(const std::string& spec);
/// Whether `spec` names a relief solid, "relief:FILE" (read by the io library: io/ReliefReader.h).
bool isReliefSpec(const std::string& spec);
/// FILE of "relief:FILE"; UsageError when it is empty.
std::string reliefPath(const std::string& spec);

}  // namespace octrace
