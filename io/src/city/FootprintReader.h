#pragma once
// Building footprints with heights through OGR (GeoJSON, Shapefile, GeoPackage, ...), extruded
// into prisms (internal to octrace_io).
#include "octrace/build/CityModel.h"
#include "octrace/io/CityReader.h"

#include <string>

namespace octrace::io::detail {

/// Whether the extension is one of the vector formats read as footprints (.geojson, .shp,
/// .gpkg, .fgb).
bool isFootprintExtension(const std::string& path);

/// Appends every polygon feature of every layer of `path` to `model` as a building prism,
/// in the layer's CRS (model.crs set from it): height from req.heightAttr (default: the first
/// of height, HEIGHT, hauteur, HAUTEUR, measuredHeight present), base from req.baseAttr, else
/// the lowest DEM height (req.dem) under the footprint's corners, else 0. A footprint without a
/// usable height or base, self-intersecting or without area is left out and said in the notes.
/// `name` is used in messages (the path, or the fuzz target's name).
/// @throws FormatNotSupported (OGR cannot open it as vectors), FileError (no layer, no
///         polygon), InputError (no height attribute: naming the fields there are).
void addFootprints(CityModel& model, const std::string& path, const CityRequest& req);

}  // namespace octrace::io::detail
