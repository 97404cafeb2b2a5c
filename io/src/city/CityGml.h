#pragma once
// CityGML into a CityModel (internal to octrace_io). GML text is parsed with GDAL's small XML
// parser (cpl_minixml), namespaces stripped, so CityGML 1.0, 2.0 and 3.0 read alike.
#include "octrace/build/CityModel.h"

#include <string>

namespace octrace::io::detail {

/// Parses CityGML text into a model in the file's own CRS ("EPSG:N" from the first srsName,
/// else empty). Every city object (a cityObjectMember's child: Building, ReliefFeature, Road,
/// WaterBody, ...) takes the polygons of its chosen level of detail (`lod` as
/// CityRequest::lod; default its highest), from every `lodN...` geometry property below it
/// (boundedBy surfaces, building parts and installations included; xlink references to
/// polygons elsewhere in the file resolved). A building's RoofSurface polygons become an object
/// of their own (type RoofSurface) so that roofs get their colour. Throws FormatNotSupported
/// (no CityModel element) and FileError (not XML); broken polygons are noted and left out.
CityModel parseCityGml(const std::string& text, const std::string& name, const std::string& lod);

/// Whether the path's extension is a CityGML one (.gml, .citygml).
bool isCityGmlExtension(const std::string& path);

}  // namespace octrace::io::detail
