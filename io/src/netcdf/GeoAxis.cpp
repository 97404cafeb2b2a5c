#include "netcdf/GeoAxis.h"

#include "input/InputFile.h"
#include "octrace/io/Units.h"

#include <algorithm>
#include <sstream>

namespace octrace::io::detail {
namespace {

std::string squeeze(const std::string& s) {  // "Degrees_East" -> "degreeseast"
    std::string out;
    for (char c : lower(s))
        if (c != '_' && c != ' ' && c != '-') out += c;
    return out;
}

bool isOneOf(const std::string& s, std::initializer_list<const char*> list) {
    return std::any_of(list.begin(), list.end(), [&](const char* x) { return s == x; });
}

bool isLonUnits(const std::string& u) {
    return isOneOf(squeeze(u), {"degreeseast", "degreeeast", "degreese", "degreee", "degreeeast"});
}
bool isLatUnits(const std::string& u) {
    return isOneOf(squeeze(u), {"degreesnorth", "degreenorth", "degreesn", "degreen"});
}

// dbar per unit for pressure units (dbar, db, bar, hPa, mbar, Pa, kPa, ...; UDUNITS-2); 0 when
// not a pressure.
double pressureToDbar(const std::string& units) { return decibarsPer(units); }

// km per unit for length units (any UDUNITS-2 reads: m, METERS, centimeters, km, feet, ...);
// 0 when not a length. A pressure is placed at ~1 m per dbar (1 % off at 5000 m).
double lengthToKm(const std::string& units) {
    if (const double dbar = pressureToDbar(units); dbar > 0.0) return 0.001 * dbar;
    return 0.001 * metresPer(units);
}

bool nameIs(const std::string& name, std::initializer_list<const char*> list) { return isOneOf(lower(name), list); }

AxisClass vertical(const AxisInfo& a) {
    AxisClass c;
    c.role = AxisRole::Vertical;
    std::string pos = lower(trim(a.positive));
    std::string sn = lower(a.standardName);
    std::string name = lower(a.name);
    c.toDbar = pressureToDbar(a.units);
    if (pos == "down" || pos == "up") {
        c.positiveDown = pos == "down";
    } else if (a.gdalDirection == "DOWN" || a.gdalDirection == "UP") {
        c.positiveDown = a.gdalDirection == "DOWN";
    } else if (c.toDbar > 0.0 || sn.find("pressure") != std::string::npos ||
               sn.find("depth") != std::string::npos || name.find("depth") != std::string::npos) {
        c.positiveDown = true;  // CF: pressure increases downward without a `positive` attribute
    } else if (sn.find("height") != std::string::npos || sn.find("altitude") != std::string::npos ||
               name.find("height") != std::string::npos || name.find("alt") == 0 || name.find("elev") == 0) {
        c.positiveDown = false;
    } else {
        c.note = "vertical axis '" + a.name + "' has no 'positive' attribute: taken as depth (positive down)";
    }
    c.toKm = lengthToKm(a.units);
    if (c.toKm == 0.0) {
        c.toKm = 0.001;
        std::string why = "vertical axis '" + a.name + "' units '" + a.units + "' taken as metres";
        c.note = c.note.empty() ? why : c.note + "; " + why;
    } else if (c.toKm != 0.001 && c.toDbar == 0.0) {
        std::ostringstream why;
        why << "vertical axis '" << a.name << "' in " << a.units << ", converted to metres (" << 1000.0 * c.toKm
            << " m each, UDUNITS-2)";
        c.note = c.note.empty() ? why.str() : c.note + "; " + why.str();
    }
    if (c.toDbar > 0.0) {
        c.toKm = 0.001 * c.toDbar;  // 1 dbar ~ 1 m of sea water (1 % off at 5000 m)
        c.note = "vertical axis '" + a.name + "' is pressure in " + a.units + ", placed at 1 m per dbar";
    }
    return c;
}

AxisClass role(AxisRole r) {
    AxisClass c;
    c.role = r;
    return c;
}

}  // namespace

AxisClass classifyAxis(const AxisInfo& a) {
    std::string units = lower(a.units);
    std::string sn = lower(a.standardName);
    std::string axis = lower(trim(a.axis));
    // Units are the most reliable signal (CF and Ferret files both set them).
    if (units.find(" since ") != std::string::npos || a.gdalType == "TEMPORAL" || sn == "time" || axis == "t")
        return role(AxisRole::Time);
    if (isLonUnits(a.units)) return role(AxisRole::Longitude);
    if (isLatUnits(a.units)) return role(AxisRole::Latitude);
    if (sn == "longitude" || sn == "grid_longitude") return role(AxisRole::Longitude);
    if (sn == "latitude" || sn == "grid_latitude") return role(AxisRole::Latitude);
    // GDAL's VERTICAL type alone is not enough: it calls any axis in metres vertical.
    // CF parametric vertical coordinates (Appendix D: ocean_sigma_coordinate, ...) are vertical
    // whatever their units; VerticalFormula.h turns them into depths.
    const bool parametric = sn.rfind("ocean_", 0) == 0 && sn.find("coordinate") != std::string::npos;
    if (parametric || sn == "depth" || sn == "altitude" || sn == "height" || sn == "sea_water_pressure" || axis == "z" ||
        !trim(a.positive).empty() || pressureToDbar(a.units) > 0.0 ||
        a.gdalDirection == "UP" || a.gdalDirection == "DOWN")
        return vertical(a);
    bool degrees = squeeze(a.units).rfind("degree", 0) == 0;
    if (degrees && (axis == "x" || a.gdalType == "HORIZONTAL_X")) return role(AxisRole::Longitude);
    if (degrees && (axis == "y" || a.gdalType == "HORIZONTAL_Y")) return role(AxisRole::Latitude);
    // Names as a last resort.
    if (nameIs(a.name, {"lon", "long", "longitude", "lons", "nav_lon", "x_lon", "xlon"})) return role(AxisRole::Longitude);
    if (nameIs(a.name, {"lat", "latitude", "lats", "nav_lat", "y_lat", "ylat"})) return role(AxisRole::Latitude);
    if (nameIs(a.name, {"depth", "depths", "deptht", "depthu", "depthv", "lev", "level", "levels", "z", "zlev", "height",
                        "altitude", "elevation"}))
        return vertical(a);
    if (lengthToKm(a.units) > 0.0 && lower(a.name).find("dep") != std::string::npos) return vertical(a);
    if (nameIs(a.name, {"time", "t"})) return role(AxisRole::Time);
    return role(AxisRole::Other);
}

const char* roleName(AxisRole r) {
    switch (r) {
        case AxisRole::Longitude: return "longitude";
        case AxisRole::Latitude: return "latitude";
        case AxisRole::Vertical: return "vertical";
        case AxisRole::Time: return "time";
        default: return "other";
    }
}

}  // namespace octrace::io::detail
