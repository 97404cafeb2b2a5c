#include "octrace/io/NetcdfReader.h"

#include "input/FormatSniffer.h"
#include "netcdf/GeoAxis.h"
#include "netcdf/GeoGrid.h"
#include "input/InputFile.h"
#include "netcdf/NetcdfClassicHeader.h"
#include "netcdf/CfTime.h"
#include "netcdf/NetcdfFile.h"
#include "netcdf/NetcdfInterpretation.h"
#include "netcdf/NetcdfLayout.h"
#include "netcdf/SoundSpeedField.h"
#include "netcdf/VerticalFormula.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "zarr/ZarrStore.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace octrace::io {

std::string detail::checkNetcdfOnDisk(const std::string& path) {
    Sniffed s = sniffFormat(path);
    if (s.kind != FileKind::NetCdf)
        throw FormatNotSupported(path + ": not a NetCDF file: it starts with '" + quoteBytes(readPrefix(path, 8)) +
                                 "', expected 'CDF\\x01', 'CDF\\x02', 'CDF\\x05' or the HDF5 signature");
    if (s.description.rfind("NetCDF-3", 0) == 0) {
        std::uint64_t need = classicDataEnd(path), have = fileSize(path);
        if (have < need)
            throw FileError(path + ": NetCDF data truncated: the header places data up to byte " + std::to_string(need) +
                            ", the file has " + std::to_string(have) + " bytes");
    }
    return s.description;
}

detail::CfOnDisk detail::checkCfOnDisk(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return {checkZarrOnDisk(path), GdalDriver::Zarr};
    return {checkNetcdfOnDisk(path), GdalDriver::NetCdf};
}

namespace {

using namespace detail;

std::string listOf(const std::vector<const VariableInfo*>& vars) {
    std::string s;
    for (const auto* v : vars) s += (s.empty() ? "" : ", ") + v->signature();
    return s.empty() ? std::string("none") : s;
}

// Why `v` is not a field to draw, empty when it is one: the cell bounds another variable names
// by its CF `bounds` attribute (lon_bnds(y, x, 4) of a 2-D longitude too), a coordinate
// variable, a coordinate another names by its `coordinates` attribute, or a longitude or
// latitude by its units or standard_name (1-D or 2-D, e.g. a curvilinear grid's nav_lat).
std::string notAField(const CfSource& file, const VariableInfo& v) {
    for (const auto& w : file.variables())
        if (&w != &v && w.bounds == v.shortName) return "the cell bounds of '" + w.shortName + "' (named by its `bounds` attribute)";
    if (v.coordinate) return "the coordinate variable of dimension '" + v.shortName + "'";
    for (const auto& w : file.variables()) {
        const auto named = words(w.coordinates);
        if (&w != &v && std::find(named.begin(), named.end(), v.shortName) != named.end())
            return "a coordinate of '" + w.shortName + "' (named by its `coordinates` attribute)";
    }
    AxisInfo a;  // units and standard_name only: a field may be called "lat" without being one
    a.units = v.units;
    a.standardName = v.standardName;
    const AxisRole r = classifyAxis(a).role;
    if (r == AxisRole::Longitude || r == AxisRole::Latitude)
        return std::string("a ") + roleName(r) + " coordinate (units '" + v.units + "'" +
               (v.standardName.empty() ? "" : ", standard_name " + v.standardName) + ")";
    return {};
}

// The numeric variables that are fields (not coordinates or cell bounds), whatever their shape.
std::vector<const VariableInfo*> dataVariables(const CfSource& file) {
    std::vector<const VariableInfo*> out;
    for (const auto& v : file.variables())
        if (v.numeric && notAField(file, v).empty()) out.push_back(&v);
    return out;
}

// Dimensions of `v` longer than 1 that are not time (an axis the interpretation cannot read
// counts: reading the variable says why).
int spatialExtent(const CfSource& file, const VariableInfo& v) {
    int n = 0;
    for (std::size_t d = 0; d < v.dimSizes.size(); ++d) {
        if (v.dimSizes[d] < 2) continue;
        try {
            n += classifyAxis(file.axis(v, d)).role != AxisRole::Time;
        } catch (const InputError&) {
            ++n;
        }
    }
    return n;
}

// Fields with at least 3 spatial dimensions (a 4-D one is read at its first time step), but the
// terms of a parametric vertical coordinate (zeta(time, y, x) is no volume).
std::vector<const VariableInfo*> volumes(const CfSource& file) {
    std::vector<const VariableInfo*> out;
    const auto terms = formulaTermVariables(file);
    for (const auto* v : dataVariables(file))
        if (spatialExtent(file, *v) >= 3 && std::find(terms.begin(), terms.end(), v->shortName) == terms.end()) out.push_back(v);
    return out;
}

// Fields with 2 spatial dimensions: maps, drawn by slice (FieldRequest::acceptPlanar).
std::vector<const VariableInfo*> maps(const CfSource& file) {
    std::vector<const VariableInfo*> out;
    for (const auto* v : dataVariables(file))
        if (spatialExtent(file, *v) == 2) out.push_back(v);
    return out;
}

std::string namesOf(const std::vector<const VariableInfo*>& vars) {
    std::string names;
    for (const auto* v : vars) names += (names.empty() ? "" : ", ") + v->shortName;
    return names;
}

// The variable `wanted` names: its name, its full name or, failing those, its CF standard_name;
// without one, the only 3-D field, else (`acceptPlanar`) the only 2-D one. Coordinates and cell
// bounds are refused by name. Null when `wanted` asks for sound speed and the file has none (it
// is then derived).
const VariableInfo* chooseVariable(const std::string& path, const CfSource& file, const std::string& wanted,
                                   bool acceptPlanar) {
    auto data = dataVariables(file);
    if (wanted.empty()) {
        auto vols = volumes(file);
        if (vols.size() == 1) return vols[0];
        if (vols.size() > 1) throw InputError(path + ": several 3-D variables (" + namesOf(vols) + "); choose one with `var`");
        auto flat = maps(file);
        if (flat.empty())
            throw InputError(path + ": no 3-D variable, nor a 2-D one to draw as a map (variables: " + listOf(data) + ")");
        if (!acceptPlanar)
            throw InputError(path + ": no 3-D variable (variables: " + listOf(data) + "): a surface needs a 3-D field; draw the 2-D " +
                             namesOf(flat) + " with slice");
        if (flat.size() == 1) return flat[0];
        throw InputError(path + ": several 2-D variables (" + namesOf(flat) + "); choose one with `var`");
    }
    std::vector<const VariableInfo*> hits;
    for (const auto& v : file.variables())
        if (v.name == wanted || v.shortName == wanted) hits.push_back(&v);
    if (hits.empty())
        for (const auto* v : data)
            if (!v->standardName.empty() && (v->standardName == wanted ||
                                             (isSoundSpeedName(wanted) && isSoundSpeedName(v->standardName))))
                hits.push_back(v);
    if (hits.empty() && isSoundSpeedName(wanted)) return nullptr;
    if (hits.empty()) throw InputError(path + ": no variable '" + wanted + "' (variables: " + listOf(data) + ")");
    if (hits.size() > 1)
        throw InputError(path + ": variable name '" + wanted + "' is ambiguous, use its full name (" + hits[0]->name +
                         ", ...)");
    if (!hits[0]->numeric) throw InputError(path + ": variable '" + wanted + "' is not numeric");
    const std::string why = notAField(file, *hits[0]);
    if (!why.empty())
        throw InputError(path + ": variable " + hits[0]->signature() + " is " + why + ", not a field to draw (fields: " +
                         listOf(data) + ")");
    return hits[0];
}

std::string regionText(const FieldRequest& req) {
    return num(req.region[0]) + "," + num(req.region[1]) + "," + num(req.region[2]) + "," + num(req.region[3]);
}

// Refuses a field without valid samples; drops the mask when every sample is valid.
ScalarField finish(const std::string& path, ScalarField f, const FieldRequest& req) {
    std::size_t valid = f.validCount();
    if (valid == 0)
        throw EmptyResultError(path + ": variable '" + f.name + "' has no valid sample" +
                               (req.hasRegion ? " in region " + regionText(req) : std::string()) +
                               (req.hasDepthRange ? " in depth range " + num(req.depthRange[0]) + "," +
                                                        num(req.depthRange[1]) + " m"
                                                  : std::string()) +
                               " (all missing_value/_FillValue, outside valid_min/valid_max/valid_range or non-finite)");
    if (valid == f.sampleCount()) f.valid.clear();
    f.validate();
    return f;
}

ScalarField readVariable(const std::string& path, const CfSource& file, const VariableInfo& var,
                         const FieldRequest& req) {
    Layout L = layoutFor(path, file, var, req);
    ScalarField f = shapeField(path, var, L, req, kReadBytesPerSample);
    readSamples(file, var, L, file.rules(var), f);
    if (!var.longName.empty()) f.notes.push_back(var.shortName + ": " + var.longName);
    f.notes.insert(f.notes.end(), L.notes.begin(), L.notes.end());
    f.timeLabel = L.timeLabel;
    return finish(path, std::move(f), req);
}

// The field `req` asks for: a variable of the file, or sound speed derived from T and S.
ScalarField readRequested(const std::string& path, const CfSource& file, const FieldRequest& req) {
    if (const VariableInfo* var = chooseVariable(path, file, req.variable, req.acceptPlanar))
        return readVariable(path, file, *var, req);
    return finish(path, deriveSoundSpeed(path, file, req), req);
}

// ", calendar 365_day: 2001-01-01 .. 2001-12-27" for a time axis with CF units.
void describeTimeRange(std::ostringstream& s, const AxisInfo& a) {
    if (!isTimeUnits(a.units)) return;
    try {
        TimeUnits u = parseTimeUnits(a.units, a.calendar, a.name);
        auto [lo, hi] = std::minmax_element(a.values.begin(), a.values.end());
        s << ", calendar " << u.calendarName << (a.calendar.empty() ? " (by default)" : "") << ": "
          << formatDate(decodeTime(u, *lo)) << " .. " << formatDate(decodeTime(u, *hi));
    } catch (const Error& e) {
        s << ", time not decoded: " << e.what();
    }
}

void describeAxes(std::ostringstream& s, const CfSource& file) {
    s << "dimensions:\n";
    std::vector<std::string> seen;
    for (const auto& v : file.variables())
        for (std::size_t d = 0; d < v.dimNames.size(); ++d) {
            if (std::find(seen.begin(), seen.end(), v.dimNames[d]) != seen.end()) continue;
            seen.push_back(v.dimNames[d]);
            AxisInfo a = file.axis(v, d);
            AxisClass c = classifyAxis(a);
            s << "  " << a.name << " = " << a.size << ": " << roleName(c.role);
            if (c.role == AxisRole::Vertical) s << (c.positiveDown ? " (positive down)" : " (positive up)");
            if (c.role == AxisRole::Vertical && !a.coordinateVariable.empty())
                for (const auto& cv : file.variables()) {
                    const std::string ft = cv.shortName == a.coordinateVariable ? file.attributeText(cv, "formula_terms") : "";
                    if (!ft.empty())
                        s << ", parametric: " << (a.standardName.empty() ? "no standard_name" : a.standardName)
                          << ", formula_terms '" << ft << "' (depths per column: see the grid's notes)";
                }
            if (!a.units.empty()) s << ", units '" << a.units << "'";
            if (a.values.empty()) {
                s << ", no coordinate variable\n";
                continue;
            }
            s << ", " << num(a.values.front()) << " .. " << num(a.values.back());
            if (c.role == AxisRole::Time) describeTimeRange(s, a);
            if (a.values.size() > 1)
                s << (isUniform(a.values) ? ", uniform step " + num((a.values.back() - a.values.front()) / double(a.values.size() - 1))
                                        : std::string(", uneven"));
            s << "\n";
        }
}

void describeVariable(std::ostringstream& s, const CfSource& file, const VariableInfo& v, std::uint64_t budget) {
    s << "  " << v.signature() << " " << v.dataType << " [";
    for (std::size_t d = 0; d < v.dimSizes.size(); ++d) s << (d ? " x " : "") << v.dimSizes[d];
    s << "]";
    if (!v.units.empty()) s << ", units '" << v.units << "'";
    if (!v.longName.empty()) s << ", '" << v.longName << "'";
    if (!v.standardName.empty()) s << ", standard_name " << v.standardName;
    for (const char* attr : {"_FillValue", "missing_value", "valid_min", "valid_max", "valid_range", "scale_factor",
                             "add_offset"}) {
        std::string text = file.attributeText(v, attr);
        if (!text.empty()) s << ", " << attr << " " << text;
    }
    if (!v.coordinates.empty()) s << ", coordinates '" << v.coordinates << "'";
    const int extent = spatialExtent(file, v);
    if (extent == 2) s << ", 2-D: a map, drawn by slice only";
    else if (extent < 2) s << ", " << extent << "-D: not drawn";
    auto curvilinear = curvilinearCoordinates(file, v);
    if (!curvilinear.empty()) {
        s << ", curvilinear (2-D";
        for (const auto* c : curvilinear) s << " " << c->shortName;
        s << ": resampled onto a regular lattice)";
    }
    std::uint64_t total = 1;
    for (auto n : v.dimSizes) total = saturatingMultiply(total, n);
    if (total > 200'000'000u || (budget && saturatingMultiply(total, sizeof(double)) > budget)) {
        s << ", value range not computed (" << total << " samples" << (total > 200'000'000u ? "" : ", over the memory budget")
          << ")\n";
        return;
    }
    std::vector<std::uint64_t> start(v.dimSizes.size(), 0);
    std::vector<double> raw = file.read(v, start, v.dimSizes);
    SampleRules r = file.rules(v);
    double lo = INFINITY, hi = -INFINITY;
    std::size_t valid = 0;
    for (double x : raw) {
        if (!r.isValid(x)) continue;
        double y = x * r.scale + r.offset;
        lo = std::min(lo, y);
        hi = std::max(hi, y);
        ++valid;
    }
    if (valid == 0) s << ": no valid sample";
    else s << ": valid range " << num(lo) << " .. " << num(hi);
    s << " (" << valid << " of " << total << " samples valid)\n";
}

// The geometry of the field `req` asks for (default: the only, or first, 3-D variable). Without
// a choice in `req`, what keeps it from being read is said in the text; with one, it is thrown.
void describeGrid(std::ostringstream& s, const std::string& path, const CfSource& file, FieldRequest req) {
    const bool chosen = !req.variable.empty() || req.hasRegion || req.hasDepthRange || !req.time.empty();
    req.acceptPlanar = true;  // a map is described as slice reads it
    auto vols = volumes(file);
    if (vols.empty()) vols = maps(file);
    if (vols.empty() && req.variable.empty()) {
        s << "no 3-D or 2-D variable: nothing to draw\n";
        return;
    }
    if (req.variable.empty()) {
        const bool map = spatialExtent(file, *vols[0]) == 2;
        s << (vols.size() == 1 ? (map ? "grid of the map " : "grid of ") : (map ? "grid of the first map, " : "grid of the first 3-D variable, "))
          << vols[0]->shortName;
        req.variable = vols[0]->name;
    } else {
        s << "grid of " << req.variable;
    }
    s << (req.hasRegion ? " in region " + regionText(req) : std::string(" (whole grid)")) << ":\n";
    ScalarField f;
    try {
        f = readRequested(path, file, req);
    } catch (const EmptyResultError& e) {
        s << "  " << e.what() << "\n";
        return;
    } catch (const LimitError& e) {
        s << "  " << e.what() << "\n";
        return;
    } catch (const FileError&) {
        throw;
    } catch (const InputError& e) {
        if (chosen) throw;
        s << "  cannot be drawn: " << e.what() << "\n";
        return;
    }
    if (chosen) {
        auto [lo, hi] = f.validRange();
        s << "  values: " << num(lo) << " .. " << num(hi) << (f.units.empty() ? "" : " " + f.units) << " ("
          << f.validCount() << " of " << f.sampleCount() << " samples valid)\n";
    }
    s << "  dims: " << f.dims.x << " x " << f.dims.y << " x " << f.dims.z << "\n";
    for (int a = 0; a < 3; ++a) {
        s << "  " << "xyz"[a] << ": ";
        if (f.isRectilinear(a))
            s << "rectilinear, " << f.dims[a] << " values " << num(f.coords[std::size_t(a)].front()) << " .. "
              << num(f.coords[std::size_t(a)].back()) << "\n";
        else
            s << "uniform, spacing " << num(f.spacing[a]) << ", from " << num(f.origin[a]) << "\n";
    }
    s << "  origin: (" << num(f.origin.x) << ", " << num(f.origin.y) << ", " << num(f.origin.z) << ")\n";
    Box3 b = f.worldBounds();
    s << "  world bounds: (" << num(b.lo.x) << ", " << num(b.lo.y) << ", " << num(b.lo.z) << ") .. (" << num(b.hi.x)
      << ", " << num(b.hi.y) << ", " << num(b.hi.z) << ")\n";
    for (const auto& n : f.notes) s << "  note: " << n << "\n";
}

}  // namespace

namespace detail {

void checkFieldRequest(const std::string& source, const FieldRequest& req) {
    if (req.hasRegion) checkRegion(req.region, source);
    if (!(req.verticalScale >= 0.0) || !std::isfinite(req.verticalScale))
        throw UsageError(source + ": vertical scale must be positive (0 = default), got " + num(req.verticalScale));
}

ScalarField interpretCf(const std::string& source, const CfSource& data, const FieldRequest& req) {
    return readRequested(source, data, req);
}

std::string describeCf(const std::string& source, const std::string& formatLine, const CfSource& data,
                       const FieldRequest& req) {
    std::ostringstream s;
    s << source << "\n" << formatLine << "\n";
    describeAxes(s, data);
    s << "variables:\n";
    bool hasSoundSpeed = false;
    for (const auto* v : dataVariables(data)) {
        describeVariable(s, data, *v, req.memoryBudget);
        hasSoundSpeed = hasSoundSpeed || isSoundSpeedName(v->shortName) || isSoundSpeedName(v->standardName);
    }
    bool heading = false;  // coordinates beyond the dimensions' own, and cell bounds
    for (const auto& v : data.variables()) {
        const std::string why = notAField(data, v);
        if (why.empty() || v.coordinate) continue;
        if (!heading) s << "coordinates and cell bounds (not fields):\n";
        heading = true;
        s << "  " << v.signature() << ": " << why << "\n";
    }
    SoundSpeedSources src = soundSpeedSources(data);
    if (!hasSoundSpeed && src.problem.empty())
        s << "  sound_speed: derived from " << src.temperature->shortName << " and " << src.salinity->shortName
          << " with `var` sound_speed (UNESCO 1983)\n";
    describeGrid(s, source, data, req);
    return s.str();
}

std::vector<std::string> cfVolumeNames(const CfSource& data) {
    std::vector<std::string> names;
    for (const auto* v : volumes(data)) names.push_back(v->shortName);
    return names;
}

ScalarField interpretNetcdf(const std::string& path, const FieldRequest& req, GdalDriver driver) {
    checkFieldRequest(path, req);
    NetcdfFile file(path, driver);
    return interpretCf(path, file, req);
}

std::string describeNetcdf(const std::string& path, const std::string& format, const FieldRequest& req,
                           GdalDriver driver) {
    NetcdfFile file(path, driver);
    return describeCf(path, "format: " + format + ", read through GDAL's " + gdalDriverName(driver) + " driver", file,
                      req);
}

}  // namespace detail

ScalarField NetcdfReader::read(const std::string& path, const FieldRequest& req) {
    return interpretNetcdf(path, req, checkCfOnDisk(path).driver);
}

std::string NetcdfReader::describe(const std::string& path, std::uint64_t memoryBudget) {
    FieldRequest req;
    req.memoryBudget = memoryBudget;
    return describe(path, req);
}

std::string NetcdfReader::describe(const std::string& path, const FieldRequest& req) {
    if (req.hasRegion) checkRegion(req.region, path);
    const CfOnDisk onDisk = checkCfOnDisk(path);
    return describeNetcdf(path, onDisk.format, req, onDisk.driver);
}

TimeAxis NetcdfReader::timeAxis(const std::string& path, const FieldRequest& req) {
    NetcdfFile file(path, checkCfOnDisk(path).driver);
    const VariableInfo* var = chooseVariable(path, file, req.variable, req.acceptPlanar);
    if (!var) {  // sound speed, derived: its steps are the temperature's
        const SoundSpeedSources src = soundSpeedSources(file);
        if (!src.problem.empty()) throw InputError(path + ": " + src.problem);
        var = src.temperature;
    }
    TimeAxis t;
    t.path = path;
    for (std::size_t d = 0; d < var->dimNames.size(); ++d) {
        AxisInfo a = file.axis(*var, d);
        if (classifyAxis(a).role != AxisRole::Time) continue;
        t.name = a.name;
        t.size = a.size;
        t.units = a.units;
        t.values = a.values;
        if (isTimeUnits(a.units) && a.values.size() == a.size) {
            try {
                const std::string what = path + ": time axis '" + a.name + "'";
                t.calendar = parseTimeUnits(a.units, a.calendar, what).calendarName;
                t.dates = timeDates(a.values, a.units, a.calendar, what);
            } catch (const Error& e) {
                log::warning(std::string(e.what()) + ": its steps are not dated");
                t.calendar.clear();
                t.dates.clear();
            }
        }
        if (t.dates.empty()) t.dates.assign(t.size, std::string());
        break;
    }
    return t;
}

std::vector<std::string> timeDates(const std::vector<double>& values, const std::string& units, const std::string& calendar,
                                   const std::string& what) {
    std::vector<std::string> dates(values.size());
    if (!isTimeUnits(units)) return dates;
    const TimeUnits u = parseTimeUnits(units, calendar, what);
    for (std::size_t i = 0; i < values.size(); ++i) dates[i] = formatDate(decodeTime(u, values[i]));
    return dates;
}

double TimeAxis::valueOf(const std::string& isoDate) const {
    const std::string what = path + ": time axis '" + name + "'";
    const DateTime date = parseIsoDate(isoDate, "date " + isoDate);
    if (!dated()) throw InputError(what + ": units '" + units + "' are not 'UNIT since DATE': give steps as indices");
    const TimeUnits u = parseTimeUnits(units, calendar, what);
    return encodeTime(u, date, "date " + isoDate);
}

std::vector<std::string> NetcdfReader::volumeVariables(const std::string& path) {
    return cfVolumeNames(NetcdfFile(path, checkCfOnDisk(path).driver));
}

}  // namespace octrace::io
