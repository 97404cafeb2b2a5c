#include "netcdf/SoundSpeedField.h"

#include "input/InputFile.h"
#include "netcdf/NetcdfLayout.h"
#include "netcdf/SeaWater.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace octrace::io::detail {
namespace {

bool oneOf(const std::string& s, std::initializer_list<const char*> list) {
    return std::any_of(list.begin(), list.end(), [&](const char* x) { return s == x; });
}

enum class Kind { None, Temperature, PotentialTemperature, Salinity, Unusable };

// What a variable holds, by standard_name first, then by name, then by long_name.
Kind kindOf(const VariableInfo& v, std::string& unusable) {
    const std::string sn = lower(v.standardName), name = lower(v.shortName), ln = lower(trim(v.longName));
    if (oneOf(sn, {"sea_water_temperature"})) return Kind::Temperature;
    if (oneOf(sn, {"sea_water_potential_temperature"})) return Kind::PotentialTemperature;
    if (oneOf(sn, {"sea_water_salinity", "sea_water_practical_salinity"})) return Kind::Salinity;
    if (oneOf(sn, {"sea_water_conservative_temperature", "sea_water_absolute_salinity"})) {
        unusable = v.shortName + " is " + sn + " (TEOS-10), the UNESCO 1983 equation needs in-situ or potential "
                                               "temperature and practical salinity";
        return Kind::Unusable;
    }
    if (!sn.empty()) return Kind::None;
    if (oneOf(name, {"temp", "temperature", "t", "t_an", "t_mn", "water_temp", "sea_water_temperature"}) ||
        oneOf(ln, {"temperature", "in situ temperature", "in-situ temperature", "sea water temperature"}))
        return Kind::Temperature;
    if (oneOf(name, {"thetao", "theta", "ptemp", "potemp", "pottmp", "pot_temp"}) ||
        oneOf(ln, {"potential temperature", "sea water potential temperature"}))
        return Kind::PotentialTemperature;
    if (oneOf(name, {"salt", "salinity", "sal", "s", "so", "psal", "s_an", "s_mn"}) ||
        oneOf(ln, {"salinity", "sea water salinity", "practical salinity"}))
        return Kind::Salinity;
    return Kind::None;
}

std::string listNames(const std::vector<const VariableInfo*>& vars) {
    std::string s;
    for (const auto* v : vars) s += (s.empty() ? "" : ", ") + v->shortName;
    return s;
}

bool isKelvin(const std::string& units) { return oneOf(lower(trim(units)), {"k", "kelvin", "degrees_kelvin", "degk"}); }

std::string unitsText(const VariableInfo& v) { return v.units.empty() ? std::string("no units") : "'" + v.units + "'"; }

}  // namespace

bool isSoundSpeedName(const std::string& name) {
    return oneOf(lower(name), {"sound_speed", "speed_of_sound_in_sea_water"});
}

SoundSpeedSources soundSpeedSources(const CfSource& file) {
    std::vector<const VariableInfo*> temps, sals;
    std::vector<bool> potential;
    std::string unusable;
    for (const auto& v : file.variables()) {
        if (!v.numeric || v.coordinate || v.auxiliary || v.extent() < 3) continue;
        Kind k = kindOf(v, unusable);
        if (k == Kind::Temperature || k == Kind::PotentialTemperature) {
            temps.push_back(&v);
            potential.push_back(k == Kind::PotentialTemperature);
        }
        if (k == Kind::Salinity) sals.push_back(&v);
    }
    SoundSpeedSources s;
    auto need = [&](const char* what, const std::vector<const VariableInfo*>& found) {
        if (found.size() == 1) return true;
        s.problem = found.empty() ? std::string("no ") + what + " variable"
                                  : std::string("several ") + what + " variables (" + listNames(found) + ")";
        if (found.empty() && !unusable.empty()) s.problem += ": " + unusable;
        return false;
    };
    if (!need("temperature", temps) || !need("salinity", sals)) return s;
    s.temperature = temps[0];
    s.salinity = sals[0];
    s.potential = potential[0];
    return s;
}

ScalarField deriveSoundSpeed(const std::string& path, const CfSource& file, const FieldRequest& req) {
    SoundSpeedSources src = soundSpeedSources(file);
    if (!src.problem.empty())
        throw InputError(path + ": no sound-speed variable, and it cannot be derived from temperature and salinity: " +
                         src.problem);
    const VariableInfo& tv = *src.temperature;
    const VariableInfo& sv = *src.salinity;
    if (tv.dimNames != sv.dimNames || tv.dimSizes != sv.dimSizes)
        throw InputError(path + ": sound speed needs temperature and salinity on one grid: " + tv.signature() +
                         " and " + sv.signature() + " differ");
    Layout L = layoutFor(path, file, tv, req);
    if (!L.geographic)
        throw InputError(path + ": sound speed needs depth and latitude: " + tv.signature() +
                         " is not on a longitude/latitude/depth grid");
    // Both fields are read before sound speed replaces the temperature samples.
    ScalarField f = shapeField(path, tv, L, req, 2 * kReadBytesPerSample);
    ScalarField salinity = shapeField(path, sv, L, req, 0);
    readSamples(file, tv, L, file.rules(tv), f);
    readSamples(file, sv, L, file.rules(sv), salinity);

    const bool kelvin = isKelvin(tv.units);
    const std::size_t nx = std::size_t(f.dims.x), ny = std::size_t(f.dims.y), nz = std::size_t(f.dims.z);
    std::vector<double> pressure(ny * nz);  // dbar per (latitude, level)
    for (std::size_t k = 0; k < nz; ++k)
        for (std::size_t j = 0; j < ny; ++j)
            pressure[k * ny + j] = L.levelDbar.empty() ? seawater::pressureFromDepth(std::max(0.0, L.depthM[k]), L.latitudeDeg[j])
                                                       : std::max(0.0, L.levelDbar[k]);
    std::size_t outside = 0;
    for (std::size_t k = 0; k < nz; ++k)
        for (std::size_t j = 0; j < ny; ++j)
            for (std::size_t i = 0; i < nx; ++i) {
                std::size_t idx = f.index(int(i), int(j), int(k));
                if (!f.isValid(idx) || !salinity.isValid(idx)) {
                    f.valid[idx] = 0;
                    continue;
                }
                const double p = pressure[k * ny + j];
                const double s = salinity.values[idx];
                double t = f.values[idx] - (kelvin ? 273.15 : 0.0);
                if (src.potential) t = seawater::adiabaticTemperature(s, t, 0.0, p);
                if (t < -2.5 || t > 40.0 || s < 0.0 || s > 42.0) ++outside;
                float c = float(seawater::soundSpeed(s, t, p));
                f.values[idx] = c;
                f.valid[idx] = std::isfinite(c) ? 1 : 0;
            }
    f.name = "sound_speed";
    f.units = "m/s";
    f.standardName = "speed_of_sound_in_sea_water";
    const std::string how = std::string("sound_speed derived from ") + tv.shortName + " (" + unitsText(tv) +
                            (src.potential ? ", potential temperature brought to in-situ" : ", in-situ temperature") +
                            (kelvin ? ", kelvin to degC" : "") + ") and " + sv.shortName + " (" + unitsText(sv) +
                            ", practical salinity), pressure from depth '" + L.verticalAxis + "' and latitude '" +
                            L.latitudeAxis + "'" + (L.levelDbar.empty() ? " (Saunders-Fofonoff)" : " (pressure axis)") +
                            "; UNESCO 1983 sound speed (Chen and Millero 1977)";
    log::info(path + ": " + how);
    f.notes.push_back(how);
    if (outside)
        f.notes.push_back(std::to_string(outside) + " sample(s) outside -2.5..40 degC or 0..42 salinity, beyond the "
                                                    "equation's published range (computed all the same)");
    f.notes.insert(f.notes.end(), L.notes.begin(), L.notes.end());
    f.timeLabel = L.timeLabel;
    return f;
}

}  // namespace octrace::io::detail
