#pragma once
/// @file CityReader.h
/// One entry point for city inputs (terrain and buildings), read into a CityModel in one
/// projected CRS: CityJSON (.json, .city.json), building footprints with heights through OGR
/// (.geojson, .shp, .gpkg, .fgb, or a .json GeoJSON FeatureCollection), a DEM raster through GDAL (.tif, .tiff, .dem,
/// .asc, .img, .hgt, .bil, .vrt) as terrain; optionally a second DEM under it and a colour
/// raster draped on the terrain.
#include "octrace/build/CityModel.h"

#include <string>

namespace octrace::io {

struct CityRequest {
    /// CityJSON: the level of detail to use ("1", "2.2", ...; a prefix such as "2" also takes
    /// "2.2"); empty: each object's highest.
    std::string lod;
    /// Target CRS (anything OSR's SetFromUserInput takes: "EPSG:28992", a WKT, a PROJ string);
    /// empty: the input's own CRS when it is projected, else the UTM zone of its centre.
    std::string crs;
    /// A DEM raster to add as terrain (any GDAL raster, any CRS: reprojected); empty: none.
    std::string dem;
    /// A colour raster (any GDAL raster, any CRS) draped on the terrain; empty: none.
    std::string texture;
    /// Footprints: the attribute holding a building's height (default: the first of height,
    /// HEIGHT, hauteur, HAUTEUR, measuredHeight present), and the one holding its base (ground
    /// height; default: the lowest DEM height under its corners with `dem`, else 0).
    std::string heightAttr, baseAttr;
    /// Most DEM samples and texture pixels read per edge (the octree resolves no more).
    int maxSamples = 4097;
};

/// Whether `path` is read as a city input: by its extension (.json, among them .scene.json
/// scene files, CityGML's, a footprint format's or a DEM raster's). Does not open the file.
bool isCityInput(const std::string& path);

/// Reads `path` into a model in the request's CRS. What cannot be used (an open shell, a
/// polygon that is self-intersecting or has no area, an unknown geometry type) is left out or
/// kept as it is and said in CityModel::notes; the rest loads.
/// @throws InputError "PATH: no such file"; FormatNotSupported when it is not a city format;
///         FileError for a broken file (not JSON, no vertices, an index out of range, ...);
///         InputError for an unknown or unusable CRS (--crs), EmptyResultError when nothing
///         with area is left (e.g. no geometry of the chosen LoD).
CityModel readCityModel(const std::string& path, const CityRequest& req = {});

/// The text `octrace info` prints for a city input: format, CRS, objects per type, levels of
/// detail, triangles, bounds, and the reader's notes.
std::string describeCityInput(const std::string& path, const CityRequest& req = {});

}  // namespace octrace::io
