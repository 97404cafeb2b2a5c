#pragma once
/// @file Units.h
/// Units of measure through UDUNITS-2, the library the CF conventions name: a vertical axis in
/// any length unit, and a value given with a unit (`iso` 10degC) brought into a field's units.
/// No UDUNITS type appears here.
///
/// UDUNITS-2's unit database (its XML files, at the library's default path or the one the
/// environment variable UDUNITS2_XML_PATH names) is read once per process, on first use, and
/// UDUNITS-2's own messages on stderr are silenced. Every function is thread-safe (UDUNITS-2's
/// parser is not: calls are serialised). Each throws octrace::Error when the database cannot be
/// read, with a message that says where it was looked for.
#include <optional>
#include <string>

namespace octrace::io {

/// `units` as UDUNITS-2 reads it, after the spellings CF files use that it would misread or
/// lacks: "deg C", "DEG C", "degrees Celsius" (UDUNITS reads "degree" times "Celsius", an angle
/// times a temperature) are degC, "deg K" K, "deg F" degF. Surrounding blanks are ignored.
std::string normalizedUnits(const std::string& units);

/// Whether UDUNITS-2 knows `units` (after normalizedUnits). Empty text is no unit: false.
bool knownUnits(const std::string& units);

/// `value` in `from` expressed in `to`, or nothing when either is unknown or they do not
/// convert (degC to m). Offsets are applied (10 degC is 283.15 K).
std::optional<double> convertUnits(double value, const std::string& from, const std::string& to);

/// Metres per `units` when they are a length (1 for m, 0.01 for centimeters, 1000 for km,
/// 0.3048 for feet), else 0.
double metresPer(const std::string& units);

/// Decibars per `units` when they are a pressure (1 for dbar, 0.01 for hPa), else 0. The
/// oceanographic "db" is a decibar here (UDUNITS-2 reads it as a decibarn, an area).
double decibarsPer(const std::string& units);

}  // namespace octrace::io
