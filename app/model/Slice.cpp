#include "octrace/model/Slice.h"

#include "octrace/model/Input.h"
#include "octrace/model/Surface.h"

#include "octrace/build/CtPresets.h"
#include "octrace/io/CityReader.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parameter.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>
#include <vector>

namespace octrace::model {
namespace {

/// Refuses `at` off a geographic grid in the user's terms, degrees east or north and metres of
/// depth, before makeSliceView would in world kilometres (on other grids world units are the
/// file's own, and its message says them). The same range: slicePositionRange.
void checkGeographicAt(const ScalarField& f, const SliceSpec& a, SlicePlane plane, double position) {
    if (!f.geographic.valid || !a.at) return;
    const auto [lo, hi] = slicePositionRange(f, plane);
    const double tolerance = 1e-9 * (1.0 + std::abs(position));
    if (position >= lo - tolerance && position <= hi + tolerance) return;
    const GeoAxes g{f.geographic};
    const Box3 b = f.worldBounds();
    const int n = sliceNormalAxis(plane);
    const std::string at = param(opt::at.key) + " " + numberText(*a.at);
    std::string why;
    if (n == 2 && f.planar)
        why = "'" + f.name + "' is a 2-D field, a map at " + numberText(g.depthM(b.hi.z)) + " m depth: leave " +
              param(opt::at.key) + " out";
    else if (n == 2)
        why = (*a.at < 0.0 ? numberText(-*a.at) + " m above the sea surface" : numberText(*a.at) + " m depth") +
              " lies outside the grid, whose levels run " + numberText(g.depthM(b.hi.z)) + " .. " + numberText(g.depthM(b.lo.z)) +
              " m depth";
    else if (f.geographic.polar())
        why = std::string(n == 0 ? "x" : "y") + " (km in the polar stereographic plane) outside the grid, which spans " +
              numberText(n == 0 ? b.lo.x : b.lo.y) + " .. " + numberText(n == 0 ? b.hi.x : b.hi.y) + " km";
    else if (n == 0)
        why = "longitude outside the grid, which spans " + numberText(g.lon(b.lo.x)) + " .. " + numberText(g.lon(b.hi.x)) +
              " degrees east (-180..180 and 0..360 both accepted)";
    else
        why = "latitude outside the grid, which spans " + numberText(g.lat(b.lo.y)) + " .. " + numberText(g.lat(b.hi.y)) +
              " degrees north";
    throw InputError(a.input + ": " + at + ": " + why);
}

/// The world axis a planar field's one plane is normal to: z for a map, the patient axis
/// nearest the normal of a single image (ImageOrientationPatient's row x column).
int planarNormalAxis(const ScalarField& f) {
    const dvec3& n = f.direction[2];
    return std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0 : std::abs(n.y) >= std::abs(n.z) ? 1 : 2;
}

/// A planar field's own plane: the patient plane of a single image, z for a map.
SlicePlane planarPlane(const ScalarField& f) {
    constexpr SlicePlane patient[3] = {SlicePlane::Sagittal, SlicePlane::Coronal, SlicePlane::Axial};
    constexpr SlicePlane world[3] = {SlicePlane::X, SlicePlane::Y, SlicePlane::Z};
    return (f.patientLps ? patient : world)[planarNormalAxis(f)];
}

/// A single image (a planar field in patient coordinates) has one plane, its own: any other
/// plane would cut it along a line, and a position off it would miss it. An oblique image
/// (its normal off the patient axis) is refused: slices are patient-aligned, and one image
/// has no neighbours to resample from. Returns the plane's position, the image's own; an
/// `at` within a micrometre of it (DICOM positions carry 6 to 16 digits) is taken as it.
double singleImagePosition(const ScalarField& f, const SliceSpec& a, SlicePlane plane) {
    const SlicePlane own = planarPlane(f);
    const std::string what = a.input + ": a single " + slicePlaneName(own) + " image";
    if (sliceNormalAxis(plane) != sliceNormalAxis(own))
        throw InputError(what + " has one slice, its own plane: " + param(opt::plane.key) + " " + slicePlaneName(plane) +
                         " would cut it along a line; leave " + param(opt::plane.key) + " out (or give " + slicePlaneName(own) +
                         "); a series of slices or a multi-frame image can be cut in any plane");
    const int n = planarNormalAxis(f);
    const double cosine = std::abs(f.direction[2][n]);
    if (cosine < 1.0 - 5e-9) {  // 1e-4 radians, the reader's tolerance for "the same orientation"
        const double degrees = std::acos(std::min(cosine, 1.0)) * 180.0 / 3.14159265358979323846;
        throw InputError(what + " is oblique: its normal is " + numberText(degrees, 3) + " degrees from the " +
                         slicePlaneName(own) + " plane's; slices are patient-aligned and a single image has no neighbours to "
                         "resample it from, so it is not drawn");
    }
    const double ownPosition = f.origin[n];
    if (a.index && *a.index != 0)
        throw InputError(what + " has one slice: " + param(opt::index.key) + " " + std::to_string(*a.index) +
                         " is beyond it; leave " + param(opt::index.key) + " out (or give 0)");
    if (a.at && std::abs(*a.at - ownPosition) > 1e-3)
        throw InputError(what + " lies at " + std::string(1, char('x' + n)) + " = " + numberText(ownPosition) + " mm: " +
                         param(opt::at.key) + " " + numberText(*a.at) + " is off it (there is one slice); leave " +
                         param(opt::at.key) + " out");
    return ownPosition;
}

SliceColour chooseColouring(const SliceSpec& a, const ScalarField& f, const SliceValues& values) {
    SliceColour out;
    SliceColouring& c = out.colouring;
    const bool mapGiven = !a.colormap.empty() || !std::isnan(a.colourMin);
    if (a.window.valid()) {
        if (mapGiven)
            throw UsageError(param(opt::window.key) + " and " + param(opt::colormap.key) + "/" + param(opt::colourRange.key) +
                             " both colour the slice: give one of them");
        if (ctWindowPreset(a.windowName)) requireHounsfield(f, a.input, param(opt::window.key) + " " + a.windowName);
        c.window = a.window;
        out.source = param(opt::window.key) + " " + a.windowName;
    } else if (a.windowName.empty() && !mapGiven && f.window.valid()) {
        c.window = f.window;
        out.source = "the file's display window";
    } else if (a.windowName.empty() && !mapGiven && f.patientLps) {
        const auto [lo, hi] = f.validRange();
        c.window = {0.5 * (double(lo) + double(hi)), std::max(double(hi) - double(lo), 1e-30)};
        out.source = "the volume's value range";
    }
    c.invertedGrey = c.window.valid() && f.invertedGrey;
    if (!c.window.valid()) {
        c.colormap = a.colormap.empty() ? defaultColormap(f.standardName, f.name) : a.colormap;
        if (!std::isnan(a.colourMin)) {
            std::tie(c.low, c.high) = colourRangeIn(a.colourMinGiven, a.colourMaxGiven, f.units,
                                                    a.input + ": variable '" + f.name + "'");
            out.source = param(opt::colourRange.key);
        } else {
            const auto [lo, hi] = values.range();
            c.low = std::isnan(lo) ? 0.0 : lo;
            c.high = std::isnan(hi) ? 1.0 : hi;
            out.source = "the slice's range of values";
        }
    }
    c.masked = displayToLinear(vec4(a.maskedColour, 1.0f));
    c.outside = displayToLinear(a.background.value_or(a.figure.enabled ? vec4(0.0f) : vec4(0.0f, 0.0f, 0.0f, 1.0f)));
    return out;
}

/// The letter of a patient direction (LPS world axis vector): L/R, P/A, S/I.
const char* patientLetter(const dvec3& d) {
    if (d.x > 0.5) return "L";
    if (d.x < -0.5) return "R";
    if (d.y > 0.5) return "P";
    if (d.y < -0.5) return "A";
    return d.z > 0.5 ? "S" : "I";
}

/// The world axis of a screen direction (a signed world axis).
int worldAxisOf(const dvec3& d) { return std::abs(d.x) > 0.5 ? 0 : std::abs(d.y) > 0.5 ? 1 : 2; }



/// Bands (label heights) between the plot's edges and the slice: left, top, right, bottom.
struct Bands {
    double left, top, right, bottom;
};
Bands figureBands(const ScalarField& f, bool scaleBar) {
    if (f.patientLps) return {1.8, 1.8, 1.8, 3.6};
    return {5.0, 1.0, 1.8, scaleBar ? 5.0 : 2.4};
}

/// Text of a world coordinate along world axis `a` (longitude, latitude, depth on a geographic
/// grid, else "x 1.5"), and the tick values (world) on [lo, hi].
struct AxisTicks {
    std::vector<double> world;
    std::vector<std::string> text;
};
/// Tick values in degrees on [lo, hi]: every 1, 2, 5, 10, 15, 20, 30, 45, 60 or 90 degrees,
/// the finest step that gives about `count` ticks, as maps mark longitudes and latitudes (a
/// global map every 60 and 30 degrees); spans under 2 degrees by niceTicks.
std::vector<double> degreeTicks(double lo, double hi, int count) {
    if (hi - lo >= 2.0)
        for (double step : {1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0, 90.0}) {
            if ((hi - lo) / step > count + 1) continue;
            std::vector<double> t;
            for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) t.push_back(v);
            return t;
        }
    return io::niceTicks(lo, hi, count);
}

AxisTicks axisTicks(const ScalarField& f, int a, double lo, double hi, int count) {
    AxisTicks t;
    if (!f.geographic.valid) {
        for (double v : io::niceTicks(lo, hi, count)) t.world.push_back(v), t.text.push_back(numberText(v, 4));
        return t;
    }
    const GeoAxes g{f.geographic};
    if (a != 2 && f.geographic.polar()) {  // the polar plane: km
        for (double v : io::niceTicks(lo, hi, count)) t.world.push_back(v), t.text.push_back(numberText(v) + " km");
    } else if (a == 0) {
        for (double lon : degreeTicks(g.lon(lo), g.lon(hi), count)) t.world.push_back(g.x(lon)), t.text.push_back(longitudeText(lon));
    } else if (a == 1) {
        for (double lat : degreeTicks(g.lat(lo), g.lat(hi), count)) t.world.push_back(g.y(lat)), t.text.push_back(latitudeText(lat));
    } else {
        for (double d : io::niceTicks(g.depthM(hi), g.depthM(lo), count)) t.world.push_back(g.z(d)), t.text.push_back(numberText(d) + " m");
    }
    return t;
}

/// The figure around a slice: the frame of the grid, orientation letters and a scale bar
/// (patient volumes) or labelled ticks (longitude, latitude, depth; world x, y, z), the grey
/// or colour bar, and the subtitle. `offset`: where the slice image lies in the plot.
io::FigureSpec sliceFigureSpec(const SliceSpec& a, const ScalarField& f, const SliceView& v, const SliceColouring& c, dvec2 offset) {
    io::FigureSpec spec;
    spec.title = a.figure.title;
    // The content's edges in the plot (whose pixel x spans [x, x + 1)).
    const dvec2 lo = offset + v.gridMin + dvec2(0.5 - v.margin), hi = offset + v.gridMax + dvec2(0.5 + v.margin);
    spec.lines = {{{lo.x, lo.y}, {hi.x, lo.y}}, {{hi.x, lo.y}, {hi.x, hi.y}}, {{hi.x, hi.y}, {lo.x, hi.y}}, {{lo.x, hi.y}, {lo.x, lo.y}}};
    const dvec3 R = v.screenRight(), U = v.screenUp();
    const dvec2 mid = 0.5 * (lo + hi);
    if (f.patientLps) {
        // Each letter its own axis: none is thinned away for another.
        spec.labels.push_back({{hi.x, mid.y}, sliceDirectionName(f, R), 0.9, 0.0, 10});
        spec.labels.push_back({{lo.x, mid.y}, sliceDirectionName(f, -R), -0.9, 0.0, 11});
        spec.labels.push_back({{mid.x, lo.y}, sliceDirectionName(f, U), 0.0, -0.9, 12});
        spec.labels.push_back({{mid.x, hi.y}, sliceDirectionName(f, -U), 0.0, 0.9, 13});
    } else {
        const int aR = worldAxisOf(R), aU = worldAxisOf(U);
        const dvec3 tl = v.world(v.gridMin.x, v.gridMin.y), br = v.world(v.gridMax.x, v.gridMax.y);
        const double r0 = std::min(tl[aR], br[aR]), r1 = std::max(tl[aR], br[aR]);
        const double u0 = std::min(tl[aU], br[aU]), u1 = std::max(tl[aU], br[aU]);
        const AxisTicks xt = axisTicks(f, aR, r0, r1, 6), yt = axisTicks(f, aU, u0, u1, 5);
        for (std::size_t i = 0; i < xt.world.size(); ++i) {
            const double px = offset.x + v.gridMin.x + 0.5 + (xt.world[i] - tl[aR]) * R[aR] / v.pixelSize;
            spec.labels.push_back({{px, hi.y}, xt.text[i], 0.0, 1.0, 0});
        }
        for (std::size_t i = 0; i < yt.world.size(); ++i) {
            const double py = offset.y + v.gridMin.y + 0.5 + (tl[aU] - yt.world[i]) * U[aU] / v.pixelSize;
            spec.labels.push_back({{lo.x, py}, yt.text[i], -(0.5 * io::labelWidthEstimate(yt.text[i]) + 0.6), 0.0, 1});
        }
        // A map (a depth slice of a geographic grid): its coastlines, clipped to the grid.
        if (f.geographic.valid && sliceNormalAxis(v.plane) == 2 && a.figure.coastline != "none") {
            const GeoAxes g{f.geographic};
            const Box3 box{dvec3(r0, u0, 0.0), dvec3(r1, u1, 0.0)};
            const auto coast = figureCoastlines(a.figure.coastline, lonLatBox(f.geographic, box));
            std::vector<dvec2> line;
            for (const auto& lonLat : coast->lines) {
                line.clear();
                for (const dvec2& p : lonLat) {
                    const dvec3 w(g.world(p.x, p.y), 0.0);
                    line.push_back({offset.x + v.gridMin.x + 0.5 + (w[aR] - tl[aR]) * R[aR] / v.pixelSize,
                                    offset.y + v.gridMin.y + 0.5 + (tl[aU] - w[aU]) * U[aU] / v.pixelSize});
                }
                clipPolyline(line, lo, hi, spec.coastlines);
            }
        } else {
            warnCoastlineUnused(a.figure.coastline, f.geographic.valid ? "only a depth slice (plane z) is a map"
                                                                       : "the field is not on a longitude/latitude grid");
        }
    }
    // The scale bar (the figure's own, in the plot's lower left corner under the slice):
    // always for patient volumes, with `scale_bar` for other grids.
    const SliceScaleBar bar = sliceScaleBar(f, v, a.figure.scaleBar);
    if (bar.length > 0.0) {
        spec.scaleBarPx = bar.pixels;
        spec.scaleBarLabel = bar.label;
    }
    // The bar and the subtitle.
    const std::string units = f.units.empty() ? "" : " (" + f.units + ")";
    spec.barLabel = f.name + units;
    const bool surfaceMap = f.planar && (!f.geographic.valid || GeoAxes{f.geographic}.depthM(v.position) == 0.0);
    std::string sub = f.patientLps                  ? f.name + ", " + slicePlaneName(v.plane) + " at " + slicePositionText(f, v)
                      : surfaceMap                   ? f.name  // a map: no plane to place
                      : !f.geographic.valid          ? f.name + ", " + slicePlaneName(v.plane) + " plane at " + slicePositionText(f, v)
                      : sliceNormalAxis(v.plane) == 2 ? f.name + " at " + slicePositionText(f, v)
                                                      : f.name + ", section at " + slicePositionText(f, v);
    if (c.window.valid()) {
        spec.greyRamp = true;
        spec.invertedGrey = c.invertedGrey;
        spec.low = c.window.centre - 0.5 * c.window.width;
        spec.high = c.window.centre + 0.5 * c.window.width;
        sub += ", window " + numberText(c.window.centre) + "/" + numberText(c.window.width);
        if (!a.windowName.empty() && ctWindowPreset(a.windowName)) sub += " (" + a.windowName + ")";
    } else {
        spec.colormap = c.colormap;
        spec.low = c.low;
        spec.high = c.high;
    }
    const std::string& time = f.timeLabel;
    spec.subtitle = time.empty() ? sub : time + "; " + sub;
    return spec;
}

}  // namespace

std::string sliceDirectionName(const ScalarField& f, const dvec3& d) {
    if (f.patientLps) return patientLetter(d);
    const int a = worldAxisOf(d);
    return std::string(d[a] > 0.0 ? "+" : "-") + char('x' + a);
}

SliceScaleBar sliceScaleBar(const ScalarField& f, const SliceView& v, bool requested) {
    SliceScaleBar bar;
    if (!f.patientLps && !requested) return bar;
    bar.length = io::scaleBarLength(v.pixelSize, v.width);
    if (!(bar.length > 0.0)) return {};
    bar.pixels = bar.length / v.pixelSize;
    bar.label = numberText(bar.length) + (f.patientLps ? " mm" : f.geographic.valid ? " km" : "");
    return bar;
}

ValueWindow quantileWindow(const ScalarField& f, double lowFraction, double highFraction) {
    std::vector<float> v;
    v.reserve(f.validCount());
    for (std::size_t i = 0; i < f.values.size(); ++i)
        if (f.isValid(i) && std::isfinite(f.values[i])) v.push_back(f.values[i]);
    if (v.empty()) throw EmptyResultError(f.source + ": '" + f.name + "' has no valid value to take a window from");
    const auto rank = [&](double q) {
        const auto k = std::size_t(std::clamp(std::llround(q * double(v.size() - 1)), 0LL, (long long)(v.size() - 1)));
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
        return double(v[k]);
    };
    const double lo = rank(lowFraction), hi = rank(highFraction);
    return {0.5 * (lo + hi), std::max(hi - lo, 1e-30)};
}

double sliceWorldOfAt(const ScalarField& f, SlicePlane plane, double at) {
    // A longitude in -180..180 or 0..360 alike, as `region` takes it: the grid is unwrapped
    // within half a turn of lon0, so the longitude is taken there.
    if (!f.geographic.valid) return at;
    const GeoAxes g{f.geographic};
    const int n = sliceNormalAxis(plane);
    if (n != 2 && f.geographic.polar()) return at;  // the polar plane's x and y: world km
    if (n == 0) return g.x(f.geographic.lon0 + std::remainder(at - f.geographic.lon0, 360.0));
    return n == 2 ? g.z(at) : g.y(at);
}

double sliceAtOfWorld(const ScalarField& f, SlicePlane plane, double world) {
    if (!f.geographic.valid) return world;
    const GeoAxes g{f.geographic};
    const int n = sliceNormalAxis(plane);
    if (n != 2 && f.geographic.polar()) return world;
    return n == 0 ? g.lon(world) : n == 1 ? g.lat(world) : g.depthM(world);
}

std::pair<double, double> sliceAtRange(const ScalarField& f, SlicePlane plane) {
    const auto [lo, hi] = slicePositionRange(f, plane);
    const double a = sliceAtOfWorld(f, plane, lo), b = sliceAtOfWorld(f, plane, hi);
    return {std::min(a, b), std::max(a, b)};
}

std::string slicePositionText(const ScalarField& f, const SliceView& v) {
    const int n = sliceNormalAxis(v.plane);
    if (f.geographic.valid) {
        const GeoAxes g{f.geographic};
        if (n != 2 && f.geographic.polar()) return std::string(1, char('x' + n)) + " = " + numberText(v.position, 5) + " km";
        return n == 2 ? numberText(g.depthM(v.position), 5) + " m depth"
               : n == 0 ? longitudeText(g.lon(v.position))
                        : latitudeText(g.lat(v.position));
    }
    return std::string(1, char('x' + n)) + " = " + numberText(v.position, 5) + (f.patientLps ? " mm" : "");
}

std::uint64_t memoryBudget(const SliceSpec& spec) { return spec.maxMemory ? spec.maxMemory : defaultMemoryBudget(); }

void checkSliceSpec(const SliceSpec& a) {
    if (a.at && a.index) throw UsageError(param(opt::at.key) + " and " + param(opt::index.key) + " both place the plane: give one of them");
    if (isOctreeInput(a.input))
        throw UsageError("slice samples a field, and the octree file " + a.input + " keeps only its surface: give the field it was built from");
    if (io::isCityInput(a.input)) throw UsageError("slice samples a field; the city input " + a.input + " is a surface model");
}

SliceResult renderSlice(const ScalarField& field, const SliceSpec& a) {
    checkSliceSpec(a);
    SliceResult r;
    const SlicePlane plane =
        a.plane.value_or(field.planar ? planarPlane(field) : field.patientLps ? SlicePlane::Axial : SlicePlane::Z);
    if (!field.patientLps && (plane == SlicePlane::Axial || plane == SlicePlane::Coronal || plane == SlicePlane::Sagittal))
        throw UsageError(param(opt::plane.key) + " " + slicePlaneName(plane) + ": " + a.input +
                         " is not in patient coordinates (DICOM, NIfTI, NRRD in LPS space); use x, y or z");
    const bool singleImage = field.planar && field.patientLps;
    if (field.planar && !singleImage && sliceNormalAxis(plane) != 2)
        throw InputError(a.input + ": " + param(opt::plane.key) + " " + slicePlaneName(plane) + ": '" + field.name +
                         "' is a 2-D field (a map): only its z plane, the map itself, can be drawn; leave " + param(opt::plane.key) + " out");
    const double position = singleImage ? singleImagePosition(field, a, plane)
                            : a.at      ? sliceWorldOfAt(field, plane, *a.at)
                                        : slicePositionOfIndex(field, plane, a.index.value_or(field.dims[sliceGridAxis(field, plane)] / 2));
    checkGeographicAt(field, a, plane, position);
    // A figure: the slice fills the plot that its layout leaves (`size` or `print_size` is the
    // whole figure), less bands around it for the letters, ticks and scale bar. The layout is
    // made again for the room the text measures (fitFigureLayout), from a first sampling.
    int width = a.width, height = a.height;
    auto plotFor = [&](const io::FigureLayout& l) {
        const Bands b = figureBands(field, a.figure.scaleBar);
        const double lp = l.labelPx;
        r.offset = dvec2(double(std::lround(b.left * lp)), double(std::lround(b.top * lp)));
        width = l.plotW - int(r.offset.x) - int(std::lround(b.right * lp));
        height = l.plotH - int(r.offset.y) - int(std::lround(b.bottom * lp));
        if (width < 16 || height < 16)
            throw UsageError(param(opt::figure.key) + ": " + std::to_string(l.width) + "x" + std::to_string(l.height) + " pixels at " +
                             std::to_string(l.dpi) + " dpi leave no room for the slice (make it larger or lower the dpi)");
    };
    if (a.figure.enabled) {
        r.layout = figureLayout(a.figure, a.width ? a.width : 1200, a.height ? a.height : 1000, true);
        r.layout = fitFigureLayout(*r.layout, [&](const io::FigureLayout& l) {
            plotFor(l);
            const SliceView view = makeSliceView(field, plane, position, width, height);
            const SliceValues values = sampleSlice(field, view, a.threads);
            return sliceFigureSpec(a, field, view, chooseColouring(a, field, values).colouring, r.offset);
        });
        plotFor(*r.layout);
    }
    r.view = makeSliceView(field, plane, position, width, height);
    const SliceView& view = r.view;
    checkMemoryBudget(a.input + ": a slice of " + std::to_string(view.width) + "x" + std::to_string(view.height) + " pixels",
                      Frame::bytesFor(view.width, view.height) + std::uint64_t(view.width) * std::uint64_t(view.height) * 29,
                      memoryBudget(a));
    SliceValues values = sampleSlice(field, view, a.threads);
    r.colour = chooseColouring(a, field, values);
    for (SliceSample s : values.state) r.validPixels += s == SliceSample::Valid, r.maskedPixels += s == SliceSample::Masked;
    Frame slice = colourSlice(values, r.colour.colouring);
    r.values = std::move(values);
    r.dpi = a.figure.dpi;
    if (!r.layout) {
        r.image = std::move(slice);
        return r;
    }
    Frame plot(r.layout->plotW, r.layout->plotH);
    std::fill(plot.rgba.begin(), plot.rgba.end(), vec4(0.0f));  // the paper
    for (int y = 0; y < slice.height; ++y)
        for (int x = 0; x < slice.width; ++x)
            plot.rgba[plot.pixel(int(r.offset.x) + x, int(r.offset.y) + y)] = slice.rgba[slice.pixel(x, y)];
    r.image = io::composeFigure(plot, sliceFigureSpec(a, field, view, r.colour.colouring, r.offset), *r.layout);
    r.dpi = r.layout->dpi;
    return r;
}

std::string sliceSummary(const ScalarField& field, const SliceResult& r, const std::string& output) {
    const SliceView& view = r.view;
    const SliceColouring& c = r.colour.colouring;
    std::ostringstream s;
    s << output << ": " << slicePlaneName(view.plane) << " slice of " << field.name << " at " << slicePositionText(field, view) << " (sample "
      << numberText(view.gridIndex, 4) << " of " << field.dims[view.gridAxis] << " along grid axis " << view.gridAxis << "), "
      << view.width << "x" << view.height << " pixels of " << numberText(view.pixelSize, 4) << (field.patientLps ? " mm" : "") << ", ";
    if (c.window.valid())
        s << "window centre " << numberText(c.window.centre) << " width " << numberText(c.window.width) << " (" << r.colour.source
          << (c.invertedGrey ? ", MONOCHROME1: inverted" : "") << ")";
    else
        s << c.colormap << " over " << numberText(c.low) << " .. " << numberText(c.high) << " (" << r.colour.source << ")";
    if (r.maskedPixels) s << ", " << r.maskedPixels << " masked pixels";
    return s.str();
}

Stats sliceStats(const ScalarField& field, const SliceResult& r, const std::string& input, double loadMs) {
    const SliceView& view = r.view;
    const SliceColouring& c = r.colour.colouring;
    Stats js;
    js.set("input", input);
    js.set("variable", field.name);
    js.set("units", field.units);
    js.set("plane", slicePlaneName(view.plane));
    js.set("position", view.position);
    js.set("grid_axis", view.gridAxis);
    js.set("grid_index", view.gridIndex);
    js.set("width", view.width);
    js.set("height", view.height);
    js.set("pixel_size", view.pixelSize);
    js.set("patient_lps", field.patientLps);
    js.set("screen_right", sliceDirectionName(field, view.screenRight()));
    js.set("screen_up", sliceDirectionName(field, view.screenUp()));
    if (r.layout) {
        js.set("figure_width", r.layout->width);
        js.set("figure_height", r.layout->height);
        js.set("figure_dpi", r.layout->dpi);
        js.set("figure_slice", std::to_string(r.layout->plotX + int(r.offset.x)) + "," + std::to_string(r.layout->plotY + int(r.offset.y)) +
                                   "," + std::to_string(view.width) + "," + std::to_string(view.height));
    }
    if (c.window.valid()) {
        js.set("window_centre", c.window.centre);
        js.set("window_width", c.window.width);
        js.set("window_inverted", c.invertedGrey);
    } else {
        js.set("colormap", c.colormap);
        js.set("colour_min", c.low);
        js.set("colour_max", c.high);
    }
    js.set("colour_source", r.colour.source);
    js.set("valid_pixels", r.validPixels);
    js.set("masked_pixels", r.maskedPixels);
    js.set("load_ms", loadMs);
    return js;
}

}  // namespace octrace::model
