#include "netcdf/NetcdfLayout.h"

#include "netcdf/CfTime.h"
#include "netcdf/GeoAxis.h"
#include "input/InputFile.h"
#include "octrace/build/PolarStereographic.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>

namespace octrace::io::detail {
namespace {

bool isDigits(const std::string& s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos; }

/// The date of step `index` and its calendar's name; empty when the axis tells no date.
std::pair<std::string, std::string> stepDate(const AxisInfo& axis, std::size_t index) {
    if (index >= axis.values.size() || !isTimeUnits(axis.units)) return {};
    try {
        TimeUnits u = parseTimeUnits(axis.units, axis.calendar, axis.name);
        return {formatDate(decodeTime(u, axis.values[index])), u.calendarName};
    } catch (const Error&) {
        return {};
    }
}

std::string sayTime(const AxisInfo& axis, std::size_t index) {
    const auto [date, calendar] = stepDate(axis, index);
    return date.empty() ? std::string() : " (" + date + ", calendar " + calendar + ")";
}

/// What a figure's subtitle says of step `index`: its date, else "time step N of M".
std::string timeLabel(const AxisInfo& axis, std::size_t index) {
    const std::string date = stepDate(axis, index).first;
    return date.empty() ? "time step " + std::to_string(index) + " of " + std::to_string(axis.size) : date;
}

// The step of a time dimension that `req.time` asks for: an index, or the step nearest to a date
// in the axis's calendar. Adds a note (and, for the default first step, a warning).
std::size_t selectTime(const std::string& path, const VariableInfo& var, const AxisInfo& axis, const FieldRequest& req,
                       std::vector<std::string>& notes, std::string& label) {
    const std::string what = path + ": variable '" + var.shortName + "': dimension '" + axis.name + "' (time)";
    if (req.time.empty()) {
        std::string msg = "dimension '" + axis.name + "' (time): first of " + std::to_string(axis.size) +
                          " steps used" + sayTime(axis, 0) + "; choose one with `time`";
        if (axis.size > 1) log::warning(path + ": variable '" + var.shortName + "': " + msg);
        notes.push_back(msg);
        label = timeLabel(axis, 0);
        return 0;
    }
    if (isDigits(req.time)) {
        checkTimeText(req.time);
        std::size_t n = std::stoul(req.time);
        if (n >= axis.size)
            throw InputError(what + " has " + std::to_string(axis.size) + " step(s), indices 0.." +
                             std::to_string(axis.size - 1) + "; `time` " + req.time + " is beyond them");
        notes.push_back("time step " + std::to_string(n) + " of " + std::to_string(axis.size) + sayTime(axis, n));
        label = timeLabel(axis, n);
        return n;
    }
    DateTime date = parseIsoDate(req.time, "`time`");
    if (axis.values.empty()) throw InputError(what + " has no coordinate variable: give `time` as an index");
    if (!isTimeUnits(axis.units))
        throw InputError(what + ": units '" + axis.units + "' are not 'UNIT since DATE': give `time` as an index");
    TimeUnits u = parseTimeUnits(axis.units, axis.calendar, path + ": time axis '" + axis.name + "'");
    double wanted = encodeTime(u, date, "`time` " + req.time);
    std::size_t best = 0;
    for (std::size_t n = 1; n < axis.values.size(); ++n)
        if (std::abs(axis.values[n] - wanted) < std::abs(axis.values[best] - wanted)) best = n;
    auto [lo, hi] = std::minmax_element(axis.values.begin(), axis.values.end());
    std::string msg = "`time` " + req.time + ": nearest step " + std::to_string(best) + " of " +
                      std::to_string(axis.size) + sayTime(axis, best);
    if (wanted < *lo || wanted > *hi) {
        msg += "; the date lies outside the time axis " + formatDate(decodeTime(u, *lo)) + " .. " +
               formatDate(decodeTime(u, *hi));
        log::warning(path + ": variable '" + var.shortName + "': " + msg);
    }
    notes.push_back(msg);
    label = timeLabel(axis, best);
    return best;
}

bool isLonLat(const VariableInfo& v) {
    AxisInfo a;
    a.name = v.shortName;
    a.units = v.units;
    a.standardName = v.standardName;
    AxisRole r = classifyAxis(a).role;
    return r == AxisRole::Longitude || r == AxisRole::Latitude;
}

// 1-D axes in a rotated pole's coordinates (CF 5.6: grid_longitude, grid_latitude).
bool isRotatedPole(const AxisInfo& lon, const AxisInfo& lat) {
    return lon.standardName == "grid_longitude" || lat.standardName == "grid_latitude";
}

bool hasAllDims(const VariableInfo& var, const VariableInfo& c) {
    for (const auto& d : c.dimNames)
        if (std::find(var.dimNames.begin(), var.dimNames.end(), d) == var.dimNames.end()) return false;
    return true;
}

// The lattice (km, positive down) the columns of a parametric vertical coordinate are
// resampled onto, chosen from `forLattice` (the columns of the region): fills L.columns with
// `columns`, L.latticeM and the notes.
std::vector<double> parametricLattice(const std::string& path, const ParametricVertical& p,
                                      std::shared_ptr<const ColumnDepths> columns, const ColumnDepths& forLattice,
                                      Layout& L) {
    L.latticeM = chooseLattice(path, forLattice);
    double smallest = INFINITY, largest = 0.0;
    for (std::size_t n = 1; n < L.latticeM.size(); ++n) {
        smallest = std::min(smallest, L.latticeM[n] - L.latticeM[n - 1]);
        largest = std::max(largest, L.latticeM[n] - L.latticeM[n - 1]);
    }
    L.notes.push_back("vertical: parametric, " + p.text() + ", depths computed per column (CF Appendix D)");
    L.notes.push_back("vertical: " + std::to_string(columns->nk) + " native levels per column resampled onto " +
                      std::to_string(L.latticeM.size()) + " levels " + num(L.latticeM.front()) + " .. " +
                      num(L.latticeM.back()) + " m, steps " + num(smallest) + " .. " + num(largest) +
                      " m (the median level spacing of the columns at each depth); linear within each column, "
                      "masked above its surface and below its floor and next to masked levels");
    if (columns->badColumns)
        L.notes.push_back("vertical: " + std::to_string(columns->badColumns) +
                          " column(s) masked: their depths are not finite or not monotonic");
    std::vector<double> km;
    for (double d : L.latticeM) km.push_back(d / 1000.0 + 0.0);
    L.columns = std::move(columns);
    return km;
}

// On 1-D longitude/latitude: the columns of the region are evaluated first (the horizontal
// selection does not depend on the vertical axis). L.dim and L.fixedIndex are set.
std::vector<double> regularParametricLattice(const std::string& path, const CfSource& file, const VariableInfo& var,
                                             const ParametricVertical& p, const FieldRequest& req,
                                             const std::vector<double>& lon, const std::vector<double>& lat,
                                             Layout& L) {
    FieldRequest horizontal = req;
    horizontal.hasDepthRange = false;
    GeoMapping h = mapGeographic(path, lon, lat, {0.0, 0.001}, horizontal);
    ColumnSelection sel{L.dim, L.fixedIndex, h.x.stored, h.y.stored};
    auto columns = std::make_shared<ColumnDepths>(evaluateColumns(path, file, var, p, sel, req.memoryBudget));
    return parametricLattice(path, p, columns, *columns, L);
}

// On a curvilinear grid: every source column is evaluated (readSamples resamples their depths
// onto the horizontal lattice with the field's weights); the vertical lattice is chosen from
// the source columns within a few cells of the horizontal lattice's box. L.dim and
// L.fixedIndex are set.
std::vector<double> curvilinearParametricLattice(const std::string& path, const CfSource& file,
                                                 const VariableInfo& var, const ParametricVertical& p,
                                                 const FieldRequest& req, const CurvilinearGrid& g,
                                                 const CurvilinearGrid::Lattice& lattice, Layout& L) {
    // readCurvilinearColumns holds every native level of the source (value, validity) and of the
    // lattice (value, validity, depth) besides the columns evaluateColumns counts.
    const std::uint64_t nk = var.dimSizes.at(L.dim[2]), lattice2d = lattice.lon.size() * lattice.lat.size();
    checkMemoryBudget(path + ": resampling the " + std::to_string(nk) + " levels of '" + var.shortName +
                          "' and their depths onto the lattice",
                      saturatingMultiply(nk, saturatingMultiply(g.ny * g.nx + lattice2d, 2 * sizeof(double) + 1)),
                      req.memoryBudget);
    ColumnSelection sel{L.dim, L.fixedIndex, {}, {}};
    for (std::size_t i = 0; i < g.nx; ++i) sel.x.push_back(i);
    for (std::size_t j = 0; j < g.ny; ++j) sel.y.push_back(j);
    auto columns = std::make_shared<ColumnDepths>(evaluateColumns(path, file, var, p, sel, req.memoryBudget));
    ColumnDepths inside = *columns;
    const double margin = 2.0 * std::max(lattice.lonStep, lattice.latStep) + g.medianStepDeg();
    const double lonMid = 0.5 * (lattice.lon.front() + lattice.lon.back());
    const double lonHalf = 0.5 * (lattice.lon.back() - lattice.lon.front()) + margin;
    for (std::size_t col = 0; col < g.ny * g.nx; ++col) {
        const double lo = g.lon()[col], la = g.lat()[col];
        if (la < lattice.lat.front() - margin || la > lattice.lat.back() + margin ||
            (lonHalf < 180.0 && std::abs(std::remainder(lo - lonMid, 360.0)) > lonHalf))
            inside.top[col] = inside.bottom[col] = NAN;
    }
    std::vector<double> km = parametricLattice(path, p, columns, inside, L);
    L.notes.push_back("vertical: each column's depths resampled onto the horizontal lattice with the field's "
                      "weights (ocean corners only), so each lattice column keeps its own depths");
    return km;
}

}  // namespace

std::vector<const VariableInfo*> curvilinearCoordinates(const CfSource& file, const VariableInfo& var) {
    std::vector<const VariableInfo*> out;
    if (var.auxiliary || isLonLat(var)) return out;  // a coordinate itself
    const auto named = words(var.coordinates);
    for (const auto& c : file.variables()) {
        if (&c == &var || !c.numeric || c.extent() < 2 || !isLonLat(c)) continue;
        bool listed = std::find(named.begin(), named.end(), c.shortName) != named.end();
        if (listed || (named.empty() && hasAllDims(var, c))) out.push_back(&c);
    }
    return out;
}

Layout layoutFor(const std::string& path, const CfSource& file, const VariableInfo& var, const FieldRequest& req) {
    std::vector<std::size_t> spread;  // dimensions with more than one sample
    for (std::size_t d = 0; d < var.dimSizes.size(); ++d)
        if (var.dimSizes[d] > 1) spread.push_back(d);

    std::vector<AxisInfo> info(var.dimSizes.size());
    std::vector<AxisClass> cls(var.dimSizes.size());
    for (std::size_t d = 0; d < var.dimSizes.size(); ++d)
        if (var.dimSizes[d] > 1 || !req.time.empty()) {
            info[d] = file.axis(var, d);
            cls[d] = classifyAxis(info[d]);
        }
    auto find = [&](AxisRole r) {
        std::vector<std::size_t> hits;
        for (std::size_t d : spread)
            if (cls[d].role == r) hits.push_back(d);
        return hits;
    };
    auto lon = find(AxisRole::Longitude), lat = find(AxisRole::Latitude), vert = find(AxisRole::Vertical);
    const bool horizontal = lon.size() == 1 && lat.size() == 1 && !info[lon[0]].values.empty() &&
                            !info[lat[0]].values.empty();
    std::optional<ParametricVertical> parametric;
    if (horizontal && vert.size() == 1) parametric = findParametricVertical(path, file, var, vert[0]);
    bool geographic = horizontal && vert.size() == 1 && (!info[vert[0]].values.empty() || parametric);

    std::vector<std::size_t> across;  // dimensions longer than 1 that are not time
    for (std::size_t d : spread)
        if (cls[d].role != AxisRole::Time) across.push_back(d);

    // A curvilinear grid: 2-D longitude/latitude and no 1-D ones but rotated-pole axes
    // (grid_longitude/grid_latitude), which the 2-D true coordinates then replace.
    std::shared_ptr<CurvilinearGrid> curvi;
    if (auto coords = curvilinearCoordinates(file, var);
        !coords.empty() && !(lon.size() == 1 && lat.size() == 1 && !info[lon[0]].values.empty() &&
                             !info[lat[0]].values.empty() && !isRotatedPole(info[lon[0]], info[lat[0]]))) {
        curvi = std::make_shared<CurvilinearGrid>(CurvilinearGrid::read(path, file, var, coords));
        auto others = [&](const std::vector<std::size_t>& v) {
            std::vector<std::size_t> out;
            for (std::size_t d : v)
                if (d != curvi->xDim && d != curvi->yDim) out.push_back(d);
            return out;
        };
        vert = others(vert);
        lon = {curvi->xDim};
        lat = {curvi->yDim};
        if (vert.size() == 1) parametric = findParametricVertical(path, file, var, vert[0]);
        geographic = vert.size() == 1 && (!info[vert[0]].values.empty() || parametric);
        if (!geographic && across.size() != 2)  // a map (2-D field) needs no vertical axis
            throw InputError(path + ": variable " + var.signature() + " is on a curvilinear grid (" + curvi->lonName +
                             ", " + curvi->latName + ") but has " + std::to_string(vert.size()) +
                             " vertical axes with coordinates; one is needed for a 3-D field");
    }
    // A 2-D field (SST, bathymetry, OISST's sst(time, zlev = 1, lat, lon)) is a map.
    const bool planar = across.size() == 2;
    if (across.size() < 2)
        throw InputError(path + ": variable " + var.signature() + " has " + std::to_string(across.size()) +
                         " dimension(s) longer than 1 besides time: nothing to draw (a map needs 2, a surface 3)");
    if (planar && !req.acceptPlanar)
        throw InputError(path + ": variable " + var.signature() + " is a 2-D field (a map over " +
                         var.dimNames[across[0]] + " and " + var.dimNames[across[1]] +
                         "): a surface needs a 3-D field; draw a 2-D field with slice");
    // A map on longitude and latitude: at the level of its vertical dimension of length 1 if
    // it has one (OISST's zlev), else at the surface.
    std::optional<std::size_t> level;
    if (planar) {
        geographic = curvi || (lon.size() == 1 && lat.size() == 1 && !info[lon[0]].values.empty() &&
                               !info[lat[0]].values.empty());
        for (std::size_t d = 0; d < var.dimSizes.size() && geographic && !level; ++d) {
            if (var.dimSizes[d] != 1) continue;
            if (info[d].name.empty()) info[d] = file.axis(var, d), cls[d] = classifyAxis(info[d]);
            if (cls[d].role == AxisRole::Vertical && info[d].values.size() == 1) level = d;
        }
    }

    std::vector<std::size_t> spatial;
    if (planar) spatial = across;
    else if (geographic) spatial = {vert[0], lat[0], lon[0]};
    else {  // the three fastest-varying dimensions that are not time
        for (auto d = across.rbegin(); d != across.rend() && spatial.size() < 3; ++d) spatial.push_back(*d);
    }
    std::sort(spatial.begin(), spatial.end());

    Layout L;
    L.planar = planar;
    L.fixedIndex.assign(var.dimSizes.size(), 0);
    bool timeChosen = false;
    for (std::size_t d = 0; d < var.dimSizes.size(); ++d) {
        if (std::find(spatial.begin(), spatial.end(), d) != spatial.end()) continue;
        if (cls[d].role == AxisRole::Time && !timeChosen && (var.dimSizes[d] > 1 || !req.time.empty())) {
            L.fixedIndex[d] = selectTime(path, var, info[d], req, L.notes, L.timeLabel);
            timeChosen = true;
        } else if (var.dimSizes[d] > 1) {
            std::string msg = "dimension '" + var.dimNames[d] + "' (" + roleName(cls[d].role) + "): first of " +
                              std::to_string(var.dimSizes[d]) + " steps used";
            log::warning(path + ": variable '" + var.shortName + "': " + msg);
            L.notes.push_back(msg);
        }
    }
    if (!req.time.empty() && !timeChosen)
        throw InputError(path + ": `time` " + req.time + ": variable " + var.signature() + " has no time axis");

    if (geographic) {
        // The vertical axis: the field's, a map's level, or the sea surface for a map without one.
        const std::optional<std::size_t> vd = planar ? level : std::optional<std::size_t>(vert[0]);
        const AxisClass vc = vd ? cls[*vd] : AxisClass{};
        const std::vector<double> levels = vd ? info[*vd].values : std::vector<double>{0.0};
        // Near a pole, the polar stereographic mapping (docs/dev/ocean.md, "Polar regions"):
        // any grid is then resampled onto a lattice in the projected plane.
        const auto [latLo, latHi] = curvi ? curvi->latitudeRange()
                                          : std::pair<double, double>(*std::min_element(info[lat[0]].values.begin(), info[lat[0]].values.end()),
                                                                      *std::max_element(info[lat[0]].values.begin(), info[lat[0]].values.end()));
        int pole = polarPole(req, latLo, latHi);
        if (pole && parametric) {
            if (req.projection == FieldRequest::Projection::Polar)
                throw InputError(path + ": variable " + var.signature() + " has a parametric vertical coordinate (" +
                                 parametric->text() + "); its per-column depths are computed on the lon/lat mapping only: "
                                 "use `map_projection` lonlat or auto");
            L.notes.push_back("polar mapping not used: per-column depths (parametric vertical coordinate) are computed "
                              "on the lon/lat mapping only");
            pole = 0;
        }
        CurvilinearGrid::Lattice lattice;  // the lon/lat lattice (not used on the polar mapping)
        if (curvi && !pole) lattice = curvi->lattice(path, req, req.horizontalSamples);
        std::vector<double> depthKm;
        if (parametric) {
            L.dim = {lon[0], lat[0], vert[0]};
            depthKm = curvi ? curvilinearParametricLattice(path, file, var, *parametric, req, *curvi, lattice, L)
                            : regularParametricLattice(path, file, var, *parametric, req, info[lon[0]].values,
                                                       info[lat[0]].values, L);
        } else {
            for (double v : levels) depthKm.push_back(v * vc.toKm * (vc.positiveDown ? 1.0 : -1.0) + 0.0);  // + 0.0: no -0
        }
        GeoMapping m;
        if (pole) {
            if (!curvi)
                curvi = std::make_shared<CurvilinearGrid>(CurvilinearGrid::fromAxes(
                    path + ": variable " + var.signature(), info[lon[0]].values, info[lat[0]].values, lon[0], lat[0],
                    info[lon[0]].name, info[lat[0]].name));
            if (req.hasRegion) checkRegion(req.region, path);
            const CurvilinearGrid::PlaneLattice plane = curvi->planeLattice(path, req, pole, req.horizontalSamples);
            m = mapPolar(path, plane.x, plane.y, depthKm, req, planar ? 1 : 2);
            curvi->buildPlaneLookup(plane);
            m.lon0 = plane.lon0;
            m.lat0 = 90.0 * pole;
            const std::string mapping =
                "geographic: polar stereographic, " + std::string(pole > 0 ? "north" : "south") + " pole, true scale at " +
                num(ScalarField::Geographic::kPolarStandardParallel) + (pole > 0 ? " N" : " S") + ", central meridian " +
                num(plane.lon0) + " (" + polarReason(req, pole) + "); world units km, x = rho sin(lon - lon0) - x0, y = " +
                (pole > 0 ? "-" : "") + "rho cos(lon - lon0) - y0, rho = R (1 + sin 71) tan(45 " +
                (pole > 0 ? "- lat" : "+ lat") + "/2), R = 6371, x0=" + num(plane.x0) + " y0=" + num(plane.y0);
            log::info(path + ": " + mapping);
            m.notes.insert(m.notes.begin(), mapping);
            m.notes.push_back(curvi->planeDescription(plane));
            L.pole = pole;
            L.x0 = plane.x0;
            L.y0 = plane.y0;
            for (double y : m.y.world)  // each row's latitude where it crosses the lattice's middle column
                L.latitudeDeg.push_back(polar::lonLatFromPlane(pole, plane.lon0, plane.x0, y + plane.y0).y);
        } else {
            m = mapGeographic(path, curvi ? lattice.lon : info[lon[0]].values,
                              curvi ? lattice.lat : info[lat[0]].values, depthKm, req, planar ? 1 : 2);
            if (curvi) {
                std::vector<double> lonOut, latOut;  // the lattice in output order
                for (std::size_t i : m.x.stored) lonOut.push_back(lattice.lon[i]);
                for (std::size_t j : m.y.stored) latOut.push_back(lattice.lat[j]);
                for (std::size_t i = 1; i < lonOut.size(); ++i)  // unwrapped as the mapping sees it
                    lonOut[i] = lonOut[i - 1] + std::remainder(lonOut[i] - lonOut[i - 1], 360.0);
                curvi->buildLookup(lonOut, latOut);
                m.notes.push_back(curvi->description(lattice, lonOut.size(), latOut.size()));
                // From here x and y index the lattice in output order.
                std::iota(m.x.stored.begin(), m.x.stored.end(), std::size_t(0));
                std::iota(m.y.stored.begin(), m.y.stored.end(), std::size_t(0));
            }
            for (std::size_t j : m.y.stored)
                L.latitudeDeg.push_back(curvi ? m.lat0 + m.y.world[j] / (kEarthRadiusKm * std::numbers::pi / 180.0)
                                              : info[lat[0]].values[j]);
        }
        L.geographic = true;
        L.lon0 = m.lon0;
        L.lat0 = m.lat0;
        L.verticalScale = m.verticalScale;
        L.dim = {lon[0], lat[0], planar ? kNoDimension : *vd};
        L.curvilinear = std::move(curvi);
        for (std::size_t k : m.z.stored) {
            L.depthM.push_back(depthKm[k] * 1000.0);
            if (vd && vc.toDbar > 0.0 && !parametric) L.levelDbar.push_back(levels[k] * vc.toDbar * (vc.positiveDown ? 1.0 : -1.0));
        }
        L.latitudeAxis = info[lat[0]].name;
        if (vd) L.verticalAxis = info[*vd].name;
        L.axes = {std::move(m.x), std::move(m.y), std::move(m.z)};
        if (planar)
            L.notes.push_back("2-D field: read as a map at " +
                              (vd ? num(L.depthM[0]) + " m depth (the one level of '" + info[*vd].name + "')"
                                  : std::string("the surface (no vertical dimension)")) +
                              "; drawn by slice, not as a surface");
        L.notes.insert(L.notes.end(), m.notes.begin(), m.notes.end());
        if (vd && !vc.note.empty() && !parametric) L.notes.push_back(vc.note);
        return L;
    }

    for (const char* option : {req.hasRegion ? "a region" : nullptr, req.hasDepthRange ? "a depth range" : nullptr})
        if (option)
            throw InputError(path + ": " + option + " needs a longitude/latitude/depth grid; variable " + var.signature() +
                             " has axes " + roleName(cls[spatial[0]].role) + ", " + roleName(cls[spatial[1]].role) +
                             (planar ? std::string() : std::string(", ") + roleName(cls[spatial[2]].role)));
    if (req.verticalScale != 0.0)
        log::warning(path + ": vertical scale ignored, variable '" + var.shortName + "' is not on a geographic grid");
    // x varies fastest; a map has one sample along z, at 0.
    L.dim = planar ? std::array<std::size_t, 3>{spatial[1], spatial[0], kNoDimension}
                   : std::array<std::size_t, 3>{spatial[2], spatial[1], spatial[0]};
    if (planar) {
        L.axes[2] = AxisSelection{{0}, {0.0}};
        L.notes.push_back("2-D field: read as a map (one sample along z, at 0); drawn by slice, not as a surface");
    }
    std::string axes, indexed;
    for (int a = 0; a < (planar ? 2 : 3); ++a) {
        const AxisInfo& ai = info[L.dim[std::size_t(a)]];
        std::vector<double> values = ai.values;
        if (values.empty()) {
            for (std::size_t n = 0; n < ai.size; ++n) values.push_back(double(n));
            indexed += (indexed.empty() ? "'" : ", '") + ai.name + "'";
        }
        L.axes[std::size_t(a)] = increasingAxis(path, ai.name, values);
        axes += std::string(a ? ", " : "") + "xyz"[a] + " = " + ai.name +
                (ai.values.empty() ? " (index)" : ai.units.empty() ? "" : " (" + ai.units + ")");
    }
    if (!indexed.empty())
        L.warning = path + ": variable '" + var.shortName + "': no coordinate variable for dimension(s) " + indexed +
                    ": grid indices used as world units";
    L.notes.push_back("not a geographic grid: world units are the file's coordinates: " + axes);
    return L;
}

ScalarField shapeField(const std::string& path, const VariableInfo& var, const Layout& L, const FieldRequest& req,
                       std::uint64_t bytesPerSample) {
    ScalarField f;
    f.source = path;
    f.name = var.shortName;
    f.units = var.units;
    f.standardName = var.standardName;
    f.planar = L.planar;
    if (L.geographic) f.geographic = {true, L.lon0, L.lat0, L.verticalScale, L.pole, L.x0, L.y0};
    for (int a = 0; a < 3; ++a) {
        const auto& w = L.axes[std::size_t(a)].world;
        f.dims[a] = int(w.size());
        if (w.size() == 1) {  // a map's one level: a spacing is needed, never used
            f.origin[a] = w.front();
            f.spacing[a] = 1.0;
        } else if (isUniform(w)) {
            f.origin[a] = w.front();
            f.spacing[a] = (w.back() - w.front()) / double(w.size() - 1);
        } else {
            f.origin[a] = 0.0;
            f.coords[std::size_t(a)] = w;
        }
    }
    if (double(f.dims.x) * double(f.dims.y) * double(f.dims.z) > 4294967296.0)
        throw InputError(path + ": variable '" + var.shortName + "' has more than the supported 2^32 samples" +
                         " in the requested grid; choose a smaller region");
    f.validateGeometry();
    checkMemoryBudget(path + ": reading '" + var.shortName + "' (" + std::to_string(f.dims.x) + "x" +
                          std::to_string(f.dims.y) + "x" + std::to_string(f.dims.z) + " samples)",
                      saturatingMultiply(f.sampleCount(), bytesPerSample), req.memoryBudget);
    if (!L.warning.empty()) log::warning(L.warning);
    return f;
}

namespace {

// A curvilinear grid: each level's whole horizontal plane, resampled onto the lattice.
void readCurvilinearSamples(const CfSource& file, const VariableInfo& var, const Layout& L, const SampleRules& rules,
                            ScalarField& f) {
    const CurvilinearGrid& g = *L.curvilinear;
    std::vector<std::uint64_t> start = L.fixedIndex;
    std::vector<std::size_t> count(var.dimSizes.size(), 1);
    count[g.yDim] = g.ny;
    count[g.xDim] = g.nx;
    start[g.yDim] = start[g.xDim] = 0;
    f.values.assign(f.sampleCount(), 0.0f);
    f.valid.assign(f.sampleCount(), 0);
    const std::size_t plane = std::size_t(f.dims.x) * std::size_t(f.dims.y);
    const auto& sz = L.axes[2].stored;
    for (std::size_t k = 0; k < sz.size(); ++k) {
        if (L.dim[2] != kNoDimension) start[L.dim[2]] = sz[k];  // a map has no vertical dimension
        std::vector<double> raw = file.read(var, start, count);
        g.resample(raw, rules, f.values.data() + k * plane, f.valid.data() + k * plane);
    }
}

// Each column (j, i) of `c`, its native samples values/valid[k * ny * nx + j * nx + i], onto
// the vertical lattice levels the output keeps, into f (x = i, y = j).
void columnsOntoLattice(const ColumnDepths& c, const double* values, const std::uint8_t* valid, const Layout& L,
                        ScalarField& f) {
    f.values.assign(f.sampleCount(), 0.0f);
    f.valid.assign(f.sampleCount(), 0);
    std::vector<double> depths, out(L.axes[2].stored.size());
    std::vector<std::uint8_t> outValid(out.size());
    for (std::size_t k : L.axes[2].stored) depths.push_back(L.latticeM[k]);
    for (std::size_t j = 0; j < c.ny; ++j)
        for (std::size_t i = 0; i < c.nx; ++i) {
            const std::size_t col = j * c.nx + i;
            resampleColumn(c, j, i, values + col, valid + col, c.ny * c.nx, depths, out.data(), outValid.data());
            for (std::size_t k = 0; k < out.size(); ++k) {
                if (!outValid[k]) continue;
                std::size_t idx = f.index(int(i), int(j), int(k));
                f.values[idx] = float(out[k]);
                f.valid[idx] = 1;
            }
        }
}

// A curvilinear grid with a parametric vertical coordinate: every native level's plane and
// every source column's depths are resampled onto the horizontal lattice with the same
// weights (ocean corners only: a source column counts where its depths are defined and the
// field has a valid sample in it), then each lattice column onto the vertical lattice.
void readCurvilinearColumns(const CfSource& file, const VariableInfo& var, const Layout& L, const SampleRules& rules,
                            ScalarField& f) {
    const CurvilinearGrid& g = *L.curvilinear;
    const ColumnDepths& src = *L.columns;  // ny x nx source columns
    const std::size_t n = g.ny * g.nx, plane = std::size_t(f.dims.x) * std::size_t(f.dims.y), nk = src.nk;
    std::vector<std::uint64_t> start = L.fixedIndex;
    std::vector<std::size_t> count(var.dimSizes.size(), 1);
    count[g.yDim] = g.ny;
    count[g.xDim] = g.nx;
    start[g.yDim] = start[g.xDim] = 0;
    std::vector<double> values(nk * n, 0.0);
    std::vector<std::uint8_t> valid(nk * n, 0), ocean(n, 0);
    for (std::size_t k = 0; k < nk; ++k) {
        start[L.dim[2]] = k;
        std::vector<double> raw = file.read(var, start, count);
        for (std::size_t p = 0; p < n; ++p) {
            if (!rules.isValid(raw[p])) continue;
            double v = raw[p] * rules.scale + rules.offset;
            if (!std::isfinite(float(v))) continue;
            values[k * n + p] = v;
            valid[k * n + p] = 1;
            if (std::isfinite(src.top[p])) ocean[p] = 1;
        }
    }
    // The lattice's columns: depths, surface and floor resampled like the field.
    ColumnDepths c;
    c.nk = nk;
    c.ny = std::size_t(f.dims.y);
    c.nx = std::size_t(f.dims.x);
    c.depth.assign(nk * plane, NAN);
    c.top.assign(plane, NAN);
    c.bottom.assign(plane, NAN);
    std::vector<double> latticeValues(nk * plane, 0.0);
    std::vector<std::uint8_t> latticeValid(nk * plane, 0), ok(plane, 0), columnOk(plane, 0);
    g.resample(src.top.data(), ocean.data(), c.top.data(), columnOk.data());
    g.resample(src.bottom.data(), ocean.data(), c.bottom.data(), ok.data());
    for (std::size_t k = 0; k < nk; ++k) {
        g.resample(src.depth.data() + k * n, ocean.data(), c.depth.data() + k * plane, ok.data());
        g.resample(values.data() + k * n, valid.data() + k * n, latticeValues.data() + k * plane,
                   latticeValid.data() + k * plane);
    }
    for (std::size_t p = 0; p < plane; ++p)
        if (!columnOk[p]) c.top[p] = c.bottom[p] = NAN;
    columnsOntoLattice(c, latticeValues.data(), latticeValid.data(), L, f);
}

// Reads one hyperslab per run of consecutive stored x indices (a region across the file's
// longitude seam is two runs) at the levels `sz`; calls put(i, j, k, raw) per sample.
template <class Put>
void readRuns(const CfSource& file, const VariableInfo& var, const Layout& L, const std::vector<std::size_t>& sz,
              Put&& put) {
    const std::size_t nd = var.dimSizes.size();
    std::vector<std::uint64_t> start = L.fixedIndex;
    std::vector<std::size_t> count(nd, 1);
    for (int a = 1; a < 3; ++a) {
        if (L.dim[std::size_t(a)] == kNoDimension) continue;  // a map's z
        const auto& s = a == 2 ? sz : L.axes[std::size_t(a)].stored;
        auto [lo, hi] = std::minmax_element(s.begin(), s.end());
        start[L.dim[std::size_t(a)]] = *lo;
        count[L.dim[std::size_t(a)]] = *hi - *lo + 1;
    }
    const auto& sx = L.axes[0].stored;
    const auto& sy = L.axes[1].stored;
    for (std::size_t i0 = 0; i0 < sx.size();) {
        std::size_t i1 = i0;
        while (i1 + 1 < sx.size() && (sx[i1 + 1] == sx[i1] + 1 || sx[i1 + 1] + 1 == sx[i1]) &&
               (i1 == i0 || (sx[i1 + 1] > sx[i1]) == (sx[i1] > sx[i1 - 1])))
            ++i1;
        std::size_t xlo = std::min(sx[i0], sx[i1]);
        start[L.dim[0]] = xlo;
        count[L.dim[0]] = i1 - i0 + 1;
        std::vector<double> buf = file.read(var, start, count);
        std::vector<std::size_t> stride(nd, 1);
        for (std::size_t d = nd - 1; d > 0; --d) stride[d - 1] = stride[d] * count[d];
        for (std::size_t k = 0; k < sz.size(); ++k)
            for (std::size_t j = 0; j < sy.size(); ++j)
                for (std::size_t i = i0; i <= i1; ++i) {
                    std::size_t at = (sx[i] - xlo) * stride[L.dim[0]] + (sy[j] - start[L.dim[1]]) * stride[L.dim[1]] +
                                     (L.dim[2] == kNoDimension ? 0 : (sz[k] - start[L.dim[2]]) * stride[L.dim[2]]);
                    put(i, j, k, buf[at]);
                }
        i0 = i1 + 1;
    }
}

}  // namespace

void readSamples(const CfSource& file, const VariableInfo& var, const Layout& L, const SampleRules& rules,
                 ScalarField& f) {
    if (L.curvilinear && L.columns) return readCurvilinearColumns(file, var, L, rules, f);
    if (L.curvilinear) return readCurvilinearSamples(file, var, L, rules, f);
    f.values.assign(f.sampleCount(), 0.0f);
    f.valid.assign(f.sampleCount(), 0);
    if (!L.columns) {
        readRuns(file, var, L, L.axes[2].stored, [&](std::size_t i, std::size_t j, std::size_t k, double raw) {
            if (!rules.isValid(raw)) return;
            std::size_t idx = f.index(int(i), int(j), int(k));
            float v = float(raw * rules.scale + rules.offset);
            f.values[idx] = v;
            f.valid[idx] = std::isfinite(v) ? 1 : 0;
        });
        return;
    }
    // A parametric vertical coordinate: every native level of each column, then each column
    // resampled onto the lattice levels the output keeps.
    const ColumnDepths& c = *L.columns;
    const std::size_t columns = c.ny * c.nx;
    std::vector<std::size_t> levels(c.nk);
    for (std::size_t k = 0; k < c.nk; ++k) levels[k] = k;
    std::vector<double> native(c.nk * columns, 0.0);
    std::vector<std::uint8_t> nativeValid(c.nk * columns, 0);
    readRuns(file, var, L, levels, [&](std::size_t i, std::size_t j, std::size_t k, double raw) {
        if (!rules.isValid(raw)) return;
        double v = raw * rules.scale + rules.offset;
        std::size_t at = k * columns + j * c.nx + i;
        native[at] = v;
        nativeValid[at] = std::isfinite(float(v)) ? 1 : 0;
    });
    columnsOntoLattice(c, native.data(), nativeValid.data(), L, f);
}

}  // namespace octrace::io::detail
