#pragma once
// CityJSON into a CityModel, and what the city readers share (internal to octrace_io).
#include "octrace/build/CityModel.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// Parses CityJSON text (1.0, 1.1, 2.0) into a model in the file's own CRS ("EPSG:N" from
/// metadata.referenceSystem, else empty), `transform` applied. `lod` as CityRequest::lod.
/// `name` is used in messages. Throws FormatNotSupported (not CityJSON), FileError (broken).
CityModel parseCityJson(const std::string& text, const std::string& name, const std::string& lod);

/// "https://www.opengis.net/def/crs/EPSG/0/7415", "urn:ogc:def:crs:EPSG::7415" -> "EPSG:7415";
/// anything else unchanged.
std::string crsFromReference(const std::string& ref);
/// Whether level of detail `lod` ("2.2") is the `wanted` one or, for a wanted "2", a sublevel.
bool lodMatches(const std::string& lod, const std::string& wanted);
/// Throws EmptyResultError when the model has no triangle: why (no object of LoD `lod` when
/// none of them was `chosen`, else the first note).
void requireSurfaces(const CityModel& model, const std::string& name, const std::string& lod, std::size_t chosen);

/// The default colour of a city object type (sRGB), and whether it is terrain.
vec3 cityTypeColour(const std::string& type);
CityRole cityTypeRole(const std::string& type);
/// A building's colour: the type's colour, varied a little by a hash of its id so that
/// neighbours can be told apart (the same id always gets the same colour).
std::uint32_t cityObjectColour(const std::string& type, const std::string& id);

/// Collects what a reader left out or repaired, per kind, and turns it into one note per kind
/// with the count and the first few objects ("3 polygons self-intersecting, left out: b1, b2").
class CityNotes {
public:
    void add(const std::string& kind, const std::string& object);
    void appendTo(std::vector<std::string>& notes, const std::string& name) const;

private:
    std::map<std::string, std::pair<std::size_t, std::vector<std::string>>> kinds_;
};

/// Whether every edge of the triangles [first, end) of the model is shared by exactly two of
/// them (a closed, watertight surface).
bool isClosedSurface(const CityModel& model, std::size_t first, std::size_t end);

}  // namespace octrace::io::detail
