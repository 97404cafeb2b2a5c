#include "octrace/scene/Spheres.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

namespace octrace {

Box3 SphereSet::bounds() const {
    Box3 b{dvec3(std::numeric_limits<double>::infinity()), dvec3(-std::numeric_limits<double>::infinity())};
    for (const Sphere& s : spheres) {
        b.lo = glm::min(b.lo, s.centre - s.radius);
        b.hi = glm::max(b.hi, s.centre + s.radius);
    }
    return b;
}

void SphereSet::validate() const {
    if (spheres.empty()) throw FileError(source + ": no spheres (no atoms)");
    if (spheres.size() > kMaxSpheres)
        throw FileError(source + ": " + std::to_string(spheres.size()) + " spheres, more than the " +
                        std::to_string(kMaxSpheres) + " octrace handles");
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        const Sphere& s = spheres[i];
        const double lim = ScalarField::kMaxWorldCoordinate;
        bool ok = std::isfinite(s.radius) && s.radius > 0.0 && s.radius < lim && s.material < materials.size();
        for (int a = 0; a < 3; ++a) ok = ok && std::isfinite(s.centre[a]) && std::abs(s.centre[a]) < lim;
        if (!ok) throw FileError(source + ": sphere " + std::to_string(i + 1) + " has a non-finite or out-of-range centre or radius");
    }
}

namespace {

// Rotation of v by `angle` radians about the unit `axis`, right-handed (Rodrigues).
dvec3 rotate(const dvec3& v, const dvec3& axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

// The 9 child directions of a SphereFlake sphere growing along +z, after Haines' SPD
// "balls" definition: three directions (1,1,0)/sqrt2, (1,0,-1)/sqrt2, (0,1,-1)/sqrt2 turned
// about (1,-1,0)/sqrt2 by asin(2/sqrt6), then that trio repeated at 0, 120 and 240 degrees
// about z. The result is 6 directions around the equator (z = 0) and 3 above it.
std::array<dvec3, 9> flakeDirections() {
    const double d = 1.0 / std::sqrt(2.0);
    std::array<dvec3, 3> trio{dvec3(d, d, 0.0), dvec3(d, 0.0, -d), dvec3(0.0, d, -d)};
    const dvec3 axis = glm::normalize(dvec3(1.0, -1.0, 0.0));
    for (auto& t : trio) t = rotate(t, axis, std::asin(2.0 / std::sqrt(6.0)));
    std::array<dvec3, 9> out;
    const double pi = 3.14159265358979323846;
    for (int set = 0; set < 3; ++set)
        for (int v = 0; v < 3; ++v) out[std::size_t(set * 3 + v)] = glm::normalize(rotate(trio[std::size_t(v)], dvec3(0, 0, 1), set * 2.0 * pi / 3.0));
    return out;
}

void addFlake(SphereSet& set, const std::array<dvec3, 9>& dirs, const dvec3& centre, double radius, const dvec3& growth, int level) {
    set.spheres.push_back({centre, radius, vec3(1.0f, 0.9f, 0.7f), 1});
    if (level == 0) return;
    // The frame that takes +z to the growth direction.
    dvec3 axis(0.0, 0.0, 1.0);
    double angle = 0.0;
    if (growth.z <= -1.0) { axis = dvec3(0.0, 1.0, 0.0); angle = 3.14159265358979323846; }
    else if (growth.z < 1.0) { axis = glm::normalize(glm::cross(dvec3(0, 0, 1), growth)); angle = std::acos(growth.z); }
    const double childRadius = radius / 3.0, dist = radius + childRadius;
    for (const dvec3& d : dirs) {
        const dvec3 dir = rotate(d, axis, angle);
        addFlake(set, dirs, centre + dir * dist, childRadius, dir, level - 1);
    }
}

}  // namespace

SphereSet makeSphereFlake(int level) {
    if (level < 0 || level > 6) throw UsageError("sphereflake level must be 0..6, got " + std::to_string(level));
    SphereSet set;
    set.name = "sphereflake-" + std::to_string(level);
    set.source = "sphereflake:" + std::to_string(level);
    // SPD balls: object colour (1, 0.9, 0.7), specular 0.5 (a mirror share of one half).
    set.materials.push_back({0.5f, 0.0f, 1.5f});
    std::size_t count = 0;
    for (int l = 0, p = 1; l <= level; ++l, p *= 9) count += std::size_t(p);
    set.spheres.reserve(count);
    addFlake(set, flakeDirections(), dvec3(0.0), 0.5, dvec3(0.0, 0.0, 1.0), level);
    set.notes.push_back("Haines' SphereFlake (SPD balls), level " + std::to_string(level) + ": " + std::to_string(count) + " spheres");
    return set;
}

SphereSet makeRandomSpheres(std::size_t count, std::uint64_t seed, double radius) {
    if (count == 0 || count > kMaxSpheres)
        throw UsageError("random spheres: count must be 1.." + std::to_string(kMaxSpheres) + ", got " + std::to_string(count));
    if (!(radius > 0.0 && radius < 1.0)) throw UsageError("random spheres: radius must be in (0, 1)");
    SphereSet set;
    set.name = "random-" + std::to_string(count);
    set.source = "random:" + std::to_string(count) + ":" + std::to_string(seed);
    set.materials.push_back({0.4f, 0.0f, 1.5f});   // mirror
    set.materials.push_back({0.1f, 0.8f, 1.5f});   // glass
    std::mt19937_64 rng(seed);
    auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53; };  // [0,1), the same everywhere
    set.spheres.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        Sphere s;
        s.centre = dvec3(uniform(), uniform(), uniform());
        s.radius = radius * (0.2 + 0.8 * uniform());
        s.colour = vec3(float(0.25 + 0.75 * uniform()), float(0.25 + 0.75 * uniform()), float(0.25 + 0.75 * uniform()));
        const double m = uniform();
        s.material = std::uint16_t(m < 0.8 ? 0 : (m < 0.9 ? 1 : 2));
        set.spheres.push_back(s);
    }
    set.notes.push_back("random spheres: " + std::to_string(count) + ", seed " + std::to_string(seed));
    return set;
}

ScalarField sphereDistanceField(const SphereSet& set, int samples, std::uint64_t memoryBudget) {
    set.validate();
    if (samples < 3) throw UsageError("sphere distance field: need at least 3 samples, got " + std::to_string(samples));
    Box3 b = set.bounds();
    const double extent = std::max({b.size().x, b.size().y, b.size().z});
    const double h = extent / double(samples - 5);  // 2 samples of padding each side, +1 for the far corner
    const double clampAt = 2.0 * h;
    ScalarField f;
    f.name = "distance";
    f.units = set.units;
    f.source = set.source;
    f.spacing = dvec3(h);
    f.origin = b.lo - 2.0 * h;
    for (int a = 0; a < 3; ++a) f.dims[a] = int(std::ceil(b.size()[a] / h)) + 5;
    f.validateGeometry();
    const std::uint64_t n = std::uint64_t(f.dims.x) * std::uint64_t(f.dims.y) * std::uint64_t(f.dims.z);
    checkMemoryBudget(set.source + ": distance field of " + std::to_string(f.dims.x) + "x" + std::to_string(f.dims.y) + "x" +
                          std::to_string(f.dims.z) + " samples",
                      saturatingMultiply(n, sizeof(float)), memoryBudget);
    f.values.assign(std::size_t(n), float(clampAt));
    for (const Sphere& s : set.spheres) {
        ivec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(0, int(std::floor((s.centre[a] - s.radius - clampAt - f.origin[a]) / h)));
            hi[a] = std::min(f.dims[a] - 1, int(std::ceil((s.centre[a] + s.radius + clampAt - f.origin[a]) / h)));
        }
        for (int k = lo.z; k <= hi.z; ++k)
            for (int j = lo.y; j <= hi.y; ++j)
                for (int i = lo.x; i <= hi.x; ++i) {
                    const dvec3 p = f.origin + dvec3(i, j, k) * h;
                    const double d = std::max(-clampAt, glm::length(p - s.centre) - s.radius);
                    float& v = f.values[f.index(i, j, k)];
                    v = std::min(v, float(d));
                }
    }
    f.notes = set.notes;
    f.notes.push_back("signed distance to the spheres, sample spacing " + std::to_string(h) + ", clamped to +-" + std::to_string(clampAt));
    return f;
}

namespace {

/// The spheres' centres in a uniform grid of cubic buckets (indices into the set).
class SphereBuckets {
public:
    explicit SphereBuckets(const SphereSet& set) : set_(set) {
        const Box3 b = set.bounds();
        double rmax = 0.0;
        for (const Sphere& s : set.spheres) rmax = std::max(rmax, s.radius);
        rmax_ = rmax;
        const double extent = std::max({b.size().x, b.size().y, b.size().z});
        side_ = std::max({2.0 * rmax, extent / 128.0, 1e-300});  // at most ~128^3 buckets
        lo_ = b.lo;
        for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, int(std::ceil(b.size()[a] / side_)));
        start_.assign(std::size_t(dims_.x) * dims_.y * dims_.z + 1, 0);
        std::vector<std::size_t> bucketOf(set.spheres.size());
        for (std::size_t i = 0; i < set.spheres.size(); ++i) ++start_[(bucketOf[i] = index(bucket(set.spheres[i].centre))) + 1];
        for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        items_.resize(set.spheres.size());
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        for (std::size_t i = 0; i < set.spheres.size(); ++i) items_[fill[bucketOf[i]]++] = std::uint32_t(i);  // in set order
    }

    /// The sphere whose surface is nearest p (the lowest index on a tie): rings of buckets
    /// around p's bucket, until no sphere further out can be nearer.
    std::uint32_t nearest(const dvec3& p) const {
        const ivec3 c = bucket(p);
        double best = std::numeric_limits<double>::infinity();
        std::uint32_t found = 0;
        const int maxRing = std::max({dims_.x, dims_.y, dims_.z});
        for (int ring = 0; ring <= maxRing; ++ring) {
            // Every centre within ring x side of p has been seen once this ring is done.
            for (int k = c.z - ring; k <= c.z + ring; ++k)
                for (int j = c.y - ring; j <= c.y + ring; ++j)
                    for (int i = c.x - ring; i <= c.x + ring; ++i) {
                        if (std::max({std::abs(i - c.x), std::abs(j - c.y), std::abs(k - c.z)}) != ring) continue;
                        if (i < 0 || j < 0 || k < 0 || i >= dims_.x || j >= dims_.y || k >= dims_.z) continue;
                        const std::size_t b = index(ivec3(i, j, k));
                        for (std::uint32_t q = start_[b]; q < start_[b + 1]; ++q) {
                            const Sphere& s = set_.spheres[items_[q]];
                            const double d = glm::length(p - s.centre) - s.radius;
                            if (d < best || (d == best && items_[q] < found)) best = d, found = items_[q];
                        }
                    }
            if (best < double(ring) * side_ - rmax_) break;  // strict: a tie further out is still seen
        }
        return found;
    }

private:
    ivec3 bucket(const dvec3& p) const {
        ivec3 c;
        for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor((p[a] - lo_[a]) / side_)), 0, dims_[a] - 1);
        return c;
    }
    std::size_t index(const ivec3& c) const { return std::size_t(c.x) + std::size_t(dims_.x) * (std::size_t(c.y) + std::size_t(dims_.y) * std::size_t(c.z)); }
    const SphereSet& set_;
    dvec3 lo_{0.0};
    double side_ = 1.0, rmax_ = 0.0;
    ivec3 dims_{1};
    std::vector<std::uint32_t> start_, items_;
};

}  // namespace

std::vector<std::uint32_t> sphereColoursAtVoxels(const Octree& tree, const SphereSet& set, int threads) {
    set.validate();
    const SphereBuckets buckets(set);
    std::vector<dvec3> centres(tree.voxels().size());
    const double h = tree.voxelSize();
    tree.forEachLeaf([&](const ivec3& cell, int shift, std::uint32_t v) {
        centres[v] = tree.cubeOrigin + (dvec3(cell) + 0.5 * double(1 << shift)) * h;
    });
    std::vector<std::uint32_t> colours(tree.voxels().size());
    const std::size_t chunk = 4096;
    parallelFor((colours.size() + chunk - 1) / chunk, threads, [&](std::size_t k) {
        for (std::size_t v = k * chunk; v < std::min(colours.size(), (k + 1) * chunk); ++v) {
            const vec3 c = set.spheres[buckets.nearest(centres[v])].colour;
            colours[v] = packColour(vec3(linearToSrgb8(c.r), linearToSrgb8(c.g), linearToSrgb8(c.b)) / 255.0f);
        }
    });
    return colours;
}

}  // namespace octrace
