#pragma once
/// @file CityModel.h
/// A city scene as the readers (io/CityReader.h) hand it to the voxelizer (CityVoxelizer.h):
/// triangles in one projected coordinate reference system (world units: the CRS's, metres for
/// the usual ones), each belonging to a city object (a building, a piece of terrain) that
/// carries a colour; optionally a texture raster draped on the terrain.
#include "octrace/util/Math.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

/// What a city object is for the octree: terrain is voxelized to the terrain depth, solids
/// (buildings, bridges) to the full depth.
enum class CityRole : std::uint8_t { Terrain = 0, Solid = 1 };

struct CityObject {
    std::string id;           ///< the source's identifier (CityJSON key, feature id, gml:id)
    std::string type;         ///< e.g. "Building", "Road", "TINRelief"
    CityRole role = CityRole::Solid;
    std::uint32_t colour = 0; ///< packColour (Octree.h)
    /// Per-source depth (scene files): the deepest level this object is voxelized to; nodes
    /// that only such objects cross stop there as coarse leaves (CityVoxelizer.h). 0: the
    /// build's depth (terrain: its terrain depth).
    int depth = 0;
};

struct CityTriangle {
    std::array<std::uint32_t, 3> v{};  ///< indices into CityModel::vertices
    std::uint32_t object = 0;          ///< index into CityModel::objects
};

/// A georeferenced colour raster in the model's CRS (north-up): pixel (i, j) covers
/// [origin.x + i*pixel.x, +pixel.x) x [origin.y - (j+1)*pixel.y, origin.y - j*pixel.y).
struct CityTexture {
    dvec2 origin{0.0};   ///< world x, y of the top-left corner
    dvec2 pixel{1.0};    ///< pixel width and height in world units (both > 0)
    int width = 0, height = 0;
    std::vector<std::uint32_t> rgba;  ///< packColour per pixel, row-major from the top; alpha 0 = no data
    bool empty() const { return rgba.empty(); }
    /// Colour at world (x, y), or 0 (alpha 0) outside the raster or where it has no data.
    std::uint32_t at(double x, double y) const;
};

struct CityModel {
    std::vector<dvec3> vertices;
    std::vector<CityTriangle> triangles;
    std::vector<CityObject> objects;
    CityTexture texture;       ///< draped on terrain triangles where it has data; may be empty
    std::string crs;           ///< e.g. "EPSG:7415"; empty: unknown
    std::string source;        ///< the file(s) it was read from, for messages
    std::string format;        ///< what the reader read, e.g. "CityJSON", for info
    /// What the readers repaired or left out (an open shell, a self-intersecting polygon, a
    /// footprint without height), one line each, for the log and `octrace info`.
    std::vector<std::string> notes;

    /// Box of every vertex that a triangle uses (lo > hi when there is none); with `role`, only
    /// the triangles of objects of that role.
    Box3 bounds() const;
    Box3 bounds(CityRole role) const;
    /// Appends another model's objects, triangles and notes (the same CRS is the caller's
    /// business); the texture is kept.
    void append(const CityModel& other);
    std::size_t objectCount(CityRole role) const;

    /// Appends a planar polygon of `object`: `rings[0]` the outer ring, the others holes (any
    /// orientation; a closing point equal to the first is ignored), triangulated by ear
    /// clipping in the polygon's best-fitting plane. Returns false and adds nothing when the
    /// polygon has no area or cannot be triangulated (self-intersecting, holes outside, ...):
    /// the caller reports it.
    bool addPolygon(const std::vector<std::vector<dvec3>>& rings, std::uint32_t object);
    /// Appends a vertical prism: the footprint polygon (outer ring and holes, z ignored)
    /// extruded from z = base to z = top, with floor, roof and walls. False as addPolygon.
    bool addPrism(const std::vector<std::vector<dvec2>>& rings, double base, double top, std::uint32_t object);
};

/// Triangulates a simple polygon with holes given in 2-D (ear clipping after joining each hole
/// to the outer ring). Indices refer to the rings' points concatenated in order (closing
/// duplicates must already be removed). Returns false when the rings do not form a simple
/// polygon with area (self-intersecting outer ring, a hole crossing it, fewer than 3 points).
bool triangulatePolygon(const std::vector<std::vector<dvec2>>& rings, std::vector<std::array<std::uint32_t, 3>>& out);

}  // namespace octrace
