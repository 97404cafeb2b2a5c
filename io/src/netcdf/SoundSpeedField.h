#pragma once
// Sound speed derived from a CF dataset's temperature and salinity (internal, no GDAL types):
// `--var sound_speed` on a file that has T and S but no sound-speed variable.
#include "netcdf/CfSource.h"

#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <string>

namespace octrace::io::detail {

/// True when `name` asks for sound speed: "sound_speed" or the CF standard name
/// "speed_of_sound_in_sea_water" (any case).
bool isSoundSpeedName(const std::string& name);

/// The variables sound speed is derived from.
struct SoundSpeedSources {
    const VariableInfo* temperature = nullptr;
    const VariableInfo* salinity = nullptr;
    bool potential = false;  ///< the temperature is potential temperature (referred to 0 dbar)
    std::string problem;     ///< why sound speed cannot be derived (empty when both were found)
};

/// Temperature and salinity among the 3-D variables of `file`: by CF standard_name
/// (sea_water_temperature, sea_water_potential_temperature; sea_water_salinity,
/// sea_water_practical_salinity), else by name (TEMP, temperature, thetao, SALT, salinity, so, ...)
/// or long_name.
SoundSpeedSources soundSpeedSources(const CfSource& file);

/// Sound speed in m/s at every sample where both T and S are valid, on T's layout for `req`:
/// UNESCO 1983 (Chen and Millero 1977, seawater::soundSpeed) at the pressure of each depth level
/// and latitude (seawater::pressureFromDepth; a pressure axis is used as it is). Potential
/// temperature is first brought to in-situ temperature (seawater::adiabaticTemperature);
/// temperature in kelvin is converted to degrees Celsius. Says on the log (info) which
/// variables were used. @throws InputError when T or S is missing, they lie on different
/// grids or the grid has no depth axis; otherwise as NetcdfReader::read.
ScalarField deriveSoundSpeed(const std::string& path, const CfSource& file, const FieldRequest& req);

}  // namespace octrace::io::detail
