#pragma once
/// @file Relief.h
/// A relief surface (land height / sea floor depth) over a regular raster, as a CSG solid: the
/// solid is everything below the surface (csg/Solid.h, Solid::Kind::Relief).
///
/// Spaces. Raster space (u, v, h): sample (i, j) sits at u = u0 + i du, v = v0 + j dv (degrees
/// of longitude and latitude for a geographic relief), its height h in the raster's units
/// (metres). World space: x = sx (u - uc), y = sy (v - vc), z = sz h, a separable linear map
/// (ReliefMapping). Between samples the height is bilinear. The geographic mapping is the
/// project's coordinate contract (ARCHITECTURE.md): the same world as an ocean field's.
#include "octrace/build/ScalarField.h"
#include "octrace/util/Math.h"

#include <memory>
#include <string>
#include <vector>

namespace octrace {

namespace detail {
class MinMaxPyramid;
}

/// Heights on a regular grid in raster space; NaN where the raster has no value.
struct ReliefRaster {
    int nx = 0, ny = 0;
    double u0 = 0.0, du = 1.0, v0 = 0.0, dv = 1.0;  ///< du, dv > 0
    std::vector<float> heights;                      ///< nx * ny, u fastest
    std::string source;                              ///< what it was read from, for messages
    float at(int i, int j) const { return heights[std::size_t(i) + std::size_t(nx) * std::size_t(j)]; }
};

/// World from raster space: x = scale.x (u - centre.x), y = scale.y (v - centre.y), z = scale.z h.
struct ReliefMapping {
    dvec3 scale{1.0};   ///< each > 0
    dvec2 centre{0.0};
};

class Relief {
public:
    /// Throws UsageError for an empty raster (fewer than 2 samples along an axis), a size that
    /// does not match, a step or scale not positive, or no valid height.
    Relief(ReliefRaster raster, ReliefMapping mapping);
    ~Relief();
    Relief(const Relief&) = delete;
    Relief& operator=(const Relief&) = delete;

    /// A longitude/latitude raster (heights in metres, up) in the world of a geographic field
    /// (ScalarField::Geographic): x = R (lon - lon0) cos(lat0), y = R (lat - lat0), z =
    /// h/1000 * verticalScale. Longitudes are unwrapped around lon0: a global raster (it spans
    /// 360 degrees) is laid out over lon0 - 180 .. lon0 + 180, any other is shifted by whole
    /// turns to lie nearest lon0. Throws UsageError as the constructor, or when `g` is not valid.
    static std::shared_ptr<const Relief> geographic(ReliefRaster lonLat, const ScalarField::Geographic& g);

    /// World z of the surface at world (x, y); NaN outside the raster or next to a missing height.
    double surfaceZ(double x, double y) const;
    /// Upward unit normal of the (bilinear) surface at world (x, y), in world space; +z where
    /// the surface is not defined.
    dvec3 normal(double x, double y) const;
    /// The range of surfaceZ over the world rectangle [x0, x1] x [y0, y1]: exact for the
    /// bilinear surface over a few raster cells, else conservative (the range of the samples
    /// around it, from a min/max pyramid). `complete` is false when part of the rectangle has
    /// no surface (outside the raster, missing heights). zmin > zmax when none of it has one.
    void zRange(double x0, double x1, double y0, double y1, double& zmin, double& zmax, bool& complete) const;

    const ReliefRaster& raster() const { return r_; }
    const ReliefMapping& mapping() const { return m_; }

private:
    double uOf(double x) const { return (m_.centre.x + x / m_.scale.x - r_.u0) / r_.du; }  // continuous column
    double vOf(double y) const { return (m_.centre.y + y / m_.scale.y - r_.v0) / r_.dv; }  // continuous row
    /// Bilinear height at continuous raster index (s, t); NaN outside or next to a missing one.
    double heightAt(double s, double t) const;

    ReliefRaster r_;
    ReliefMapping m_;
    std::unique_ptr<detail::MinMaxPyramid> pyramid_;
};

}  // namespace octrace
