#pragma once
/// @file Spheres.h
/// Sphere scenes (paper B's objects, paper A's molecule row): a set of spheres with a colour
/// and a material each, and the generators of the procedural ones. Readers of molecule files
/// live in io (SphereReader.h).
#include "octrace/build/ScalarField.h"
#include "octrace/octree/Octree.h"
#include "octrace/util/Math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

/// What a surface does with light beyond the local (Lambert) term: Whitted's reflected and
/// transmitted rays. reflect + transmit <= 1; the local term is weighted by what is left.
struct Material {
    float reflect = 0.0f;   ///< share of the colour taken from the mirror direction
    float transmit = 0.0f;  ///< share taken from the refracted direction
    float ior = 1.5f;       ///< index of refraction for transmit
};

struct Sphere {
    dvec3 centre{0.0};
    double radius = 1.0;
    vec3 colour{0.8f};          ///< linear RGB albedo
    std::uint16_t material = 0; ///< index into SphereSet::materials
};

/// Move-only owner of a scene's spheres (big for molecules).
class SphereSet {
public:
    SphereSet() { materials.emplace_back(); }
    SphereSet(SphereSet&&) noexcept = default;
    SphereSet& operator=(SphereSet&&) noexcept = default;
    SphereSet(const SphereSet&) = delete;
    SphereSet& operator=(const SphereSet&) = delete;

    std::string name;              ///< "4HHB", "sphereflake-4", ...
    std::string units;             ///< world units ("angstrom" for molecules, "" otherwise)
    std::string source;            ///< file or generator, for messages
    std::vector<Sphere> spheres;
    std::vector<Material> materials;  ///< [0] is the default matte material
    std::vector<std::string> notes;   ///< for info and logs

    /// Union of the spheres' boxes; lo > hi when empty.
    Box3 bounds() const;
    /// Finite centres, positive finite radii, material indices in range, at least one
    /// sphere, coordinates within ScalarField::kMaxWorldCoordinate. Throws FileError
    /// naming `source`.
    void validate() const;
};

/// Most spheres a scene may hold (readers and generators refuse more before allocating).
inline constexpr std::size_t kMaxSpheres = 50'000'000;

/// Haines' SphereFlake ("balls", Standard Procedural Databases, 1987): a sphere of radius 0.5
/// at the origin growing along +z; every sphere of the recursion carries 9 spheres of a third
/// of its radius, tangent to it, in its own frame (see Spheres.cpp for the directions).
/// `level` 0..6 (level 4: 7,381 spheres). Mirror-like material (reflect 0.5), as in the SPD.
SphereSet makeSphereFlake(int level);
/// `count` spheres with centres uniform in the unit cube [0,1]^3 and radii uniform in
/// [0.2, 1] * `radius`, from a 64-bit seed; the same set on every platform (own uniform
/// mapping of std::mt19937_64). Throws UsageError for count 0 or above kMaxSpheres.
SphereSet makeRandomSpheres(std::size_t count, std::uint64_t seed, double radius = 0.02);

/// The scene as a field for the voxel octree: the signed distance to the nearest sphere
/// surface (negative inside), clamped to +-2 samples, on a uniform grid of `samples` points
/// along the longest side of the spheres' box (padded by 2 samples), so that its isosurface
/// 0 is the union of the spheres and its gradient the nearest sphere's normal. The range is
/// [-c, c] whenever some sphere holds a grid point, so the middle of the range is 0.
/// Throws LimitError when the samples need more than `memoryBudget` bytes (0 = no limit).
ScalarField sphereDistanceField(const SphereSet& set, int samples, std::uint64_t memoryBudget = 0);

/// Per-voxel colours (Octree::colours(), packColour of the 8-bit sRGB value) for an octree of
/// the set's distance field: each boundary leaf takes the colour of the sphere whose surface
/// is nearest its centre (smallest |p - centre| - radius; the first such sphere on a tie),
/// found in a uniform grid of buckets. A molecule's voxels thus keep their atoms' CPK colours
/// as a city's keep their buildings'. The same result for any `threads`.
std::vector<std::uint32_t> sphereColoursAtVoxels(const Octree& tree, const SphereSet& set, int threads = 0);

}  // namespace octrace
