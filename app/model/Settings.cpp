#include "octrace/model/Settings.h"

#include "octrace/model/Slice.h"

#include "octrace/build/CtPresets.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parameter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace octrace::model {
namespace {

[[noreturn]] void refuse(const Option& o, const std::string& why) { throw UsageError(param(o.key) + ": " + why); }

std::vector<std::string> split(const std::string& text, char sep) {
    std::vector<std::string> parts(1);
    for (char c : text) {
        if (c == sep) parts.emplace_back();
        else parts.back() += c;
    }
    return parts;
}

/// Non-empty text, else "`key`: empty (give `what`)".
const std::string& nonEmpty(const Option& o, const std::string& text, const char* what) {
    if (text.empty()) refuse(o, std::string("empty (give ") + what + ")");
    return text;
}

using Setter = std::function<void(const std::string& text, const SettingTargets& t)>;
using SliceSetter = std::function<void(const std::string& text, SliceSpec& s)>;

struct Entry {
    SettingPart part;
    Setter set;
    bool shading = false;  ///< a surface setting that only applyColour or applyLighting reads
    SliceSetter slice;     ///< where the slice spec holds it (empty: not a setting of slices)
};

/// The request a setting of what to read lands in: the targets' own, else the surface's or the slice's.
io::FieldRequest* requestOf(const SettingTargets& t) {
    return t.request ? t.request : t.surface ? &t.surface->request : t.slice ? &t.slice->request : nullptr;
}
/// The figure settings' target: the targets' own, else the slice's.
FigureSettings* figureOf(const SettingTargets& t) { return t.figure ? t.figure : t.slice ? &t.slice->figure : nullptr; }

// Shorthands for the table below: a setter of the request, surface, render or figure part.
Entry request(std::function<void(const std::string&, io::FieldRequest&)> f) {
    return {SettingPart::Request, [f](const std::string& v, const SettingTargets& t) { f(v, *requestOf(t)); }};
}
Entry surface(std::function<void(const std::string&, SurfaceSpec&)> f, bool shading = false) {
    return {SettingPart::Surface, [f](const std::string& v, const SettingTargets& t) { f(v, *t.surface); }, shading};
}
/// A surface setting that only shading reads (applyColour, applyLighting): no rebuild.
Entry shading(std::function<void(const std::string&, SurfaceSpec&)> f) { return surface(std::move(f), true); }
Entry render(std::function<void(const std::string&, RenderSpec&)> f) {
    return {SettingPart::Render, [f](const std::string& v, const SettingTargets& t) { f(v, *t.render); }};
}
Entry figure(std::function<void(const std::string&, FigureSettings&)> f) {
    return {SettingPart::Figure, [f](const std::string& v, const SettingTargets& t) { f(v, *figureOf(t)); }};
}
/// A setting of slices only (`plane`, `at`, `index`).
Entry slice(SliceSetter f) { return {SettingPart::Slice, {}, false, std::move(f)}; }
/// `e`, a setting that the slice spec holds too, under the same member names: `f` is the one
/// setter of both (generic over the spec).
template <class F>
Entry andSlice(Entry e, F f) {
    e.slice = f;
    return e;
}
/// A text setting of a city input: not empty, marks a city setting given.
Entry cityText(const Option& o, std::string io::CityRequest::*field, const char* what) {
    return surface([&o, field, what](const std::string& v, SurfaceSpec& s) {
        s.city.*field = nonEmpty(o, v, what);
        s.cityGiven = true;
    });
}

/// Every setting the pipeline's specs hold, by key: what the CLI's flags, the sessions and
/// Python's keywords set.
const std::unordered_map<std::string_view, Entry>& setters() {
    static const std::unordered_map<std::string_view, Entry> table = [] {
        std::unordered_map<std::string_view, Entry> m;
        // What to read.
        m.emplace(opt::variable.key, request([](const std::string& v, io::FieldRequest& q) {
            q.variable = nonEmpty(opt::variable, v, "a variable name");
        }));
        m.emplace(opt::series.key, request([](const std::string& v, io::FieldRequest& q) {
            q.series = nonEmpty(opt::series, v, "a UID, an index or a description");
        }));
        m.emplace(opt::volume.key, request([](const std::string& v, io::FieldRequest& q) {
            q.volume = parseInteger(opt::volume, v);
        }));
        m.emplace(opt::region.key, request([](const std::string& v, io::FieldRequest& q) {
            const auto r = io::parseRegion(v);
            q.hasRegion = true;
            for (int i = 0; i < 4; ++i) q.region[i] = r[std::size_t(i)];
        }));
        m.emplace(opt::depthRange.key, request([](const std::string& v, io::FieldRequest& q) {
            const auto r = io::parseDepthRange(v);
            q.hasDepthRange = true;
            q.depthRange[0] = r[0];
            q.depthRange[1] = r[1];
        }));
        m.emplace(opt::mapProjection.key, request([](const std::string& v, io::FieldRequest& q) {
            const std::string c = parseChoice(opt::mapProjection, v);
            q.projection = c == "polar"    ? io::FieldRequest::Projection::Polar
                           : c == "lonlat" ? io::FieldRequest::Projection::LonLat
                                           : io::FieldRequest::Projection::Auto;
        }));
        m.emplace(opt::time.key, request([](const std::string& v, io::FieldRequest& q) {
            io::checkTimeText(v);
            q.time = v;
        }));
        m.emplace(opt::verticalScale.key, request([](const std::string& v, io::FieldRequest& q) {
            q.verticalScale = parseNumber(opt::verticalScale, v);
        }));
        const auto maxMemory = [](const std::string& v, auto& s) { s.maxMemory = parseByteSize(opt::maxMemory, v); };
        m.emplace(opt::maxMemory.key, andSlice(surface(maxMemory), maxMemory));
        // The surface.
        m.emplace(opt::iso.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.isoPreset.clear();
            s.iso.reset();
            s.isoUnit.clear();
            if (ctIsoPreset(v)) {
                s.isoPreset = v;
            } else {
                const Quantity q = parseQuantity(opt::iso, v);
                s.iso = q.value;
                s.isoUnit = q.unit;
            }
        }));
        m.emplace(opt::depth.key, surface([](const std::string& v, SurfaceSpec& s) {
            if (v == "auto") s.depth.reset();
            else s.depth = parseInteger(opt::depth, v);
            s.depthGiven = true;
        }));
        const auto threads = [](const std::string& v, auto& s) { s.threads = parseInteger(opt::threads, v); };
        m.emplace(opt::threads.key, andSlice(surface(threads), threads));
        m.emplace(opt::form.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.form = parseChoice(opt::form, v) == "volume" ? OctreeForm::Volume : OctreeForm::Shell;
            s.formGiven = true;
        }));
        m.emplace(opt::surface.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.surface = parseChoice(opt::surface, v) == "smooth" ? SurfaceMode::Smooth : SurfaceMode::Voxel;
        }));
        m.emplace(opt::inside.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.insideBelow = parseChoice(opt::inside, v) == "below";
            s.formGiven = true;
        }));
        m.emplace(opt::cut.key, surface([](const std::string& v, SurfaceSpec& s) {
            checkSolidArgument(v);
            s.cuts.emplace_back(v);
        }));
        m.emplace(opt::clip.key, surface([](const std::string&, SurfaceSpec& s) { s.clip = true; }));
        m.emplace(opt::extendDown.key, surface([](const std::string&, SurfaceSpec& s) { s.extendDown = true; }));
        // City inputs.
        m.emplace(opt::lodSelect.key, surface([](const std::string& v, SurfaceSpec& s) {
            if (v.empty() || v.find_first_not_of("0123456789.") != std::string::npos)
                refuse(opt::lodSelect, "expected a level of detail such as 1, 2 or 2.2, got '" + v + "'");
            s.city.lod = v;
            s.cityGiven = true;
        }));
        m.emplace(opt::terrainDepth.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.terrainDepth = parseInteger(opt::terrainDepth, v);
            s.cityGiven = true;
        }));
        m.emplace(opt::dem.key, cityText(opt::dem, &io::CityRequest::dem, "a raster file"));
        m.emplace(opt::texture.key, cityText(opt::texture, &io::CityRequest::texture, "a raster file"));
        m.emplace(opt::heightAttr.key, cityText(opt::heightAttr, &io::CityRequest::heightAttr, "an attribute name"));
        m.emplace(opt::baseAttr.key, cityText(opt::baseAttr, &io::CityRequest::baseAttr, "an attribute name"));
        m.emplace(opt::crs.key, cityText(opt::crs, &io::CityRequest::crs, "e.g. EPSG:28992"));
        // Baked lighting.
        m.emplace(opt::bake.key, surface([](const std::string&, SurfaceSpec& s) { s.bake = true; }));
        m.emplace(opt::bakeLight.key, surface([](const std::string& v, SurfaceSpec& s) {
            if (!s.bakeLightGiven) s.bakeOptions.lights.clear();
            s.bakeLightGiven = true;
            s.bakeOptions.lights.push_back(parseBakeLight(v));
        }));
        m.emplace(opt::bakeAo.key, surface([](const std::string& v, SurfaceSpec& s) { s.bakeOptions.aoRays = parseInteger(opt::bakeAo, v); }));
        m.emplace(opt::bakeAoDistance.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.bakeOptions.aoDistance = parseNumber(opt::bakeAoDistance, v);
        }));
        m.emplace(opt::bakeShadows.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.bakeOptions.shadows = parseChoice(opt::bakeShadows, v) == "on";
        }));
        m.emplace(opt::lighting.key, shading([](const std::string& v, SurfaceSpec& s) {
            s.lighting = parseChoice(opt::lighting, v) == "baked" ? SurfaceSpec::Lighting::Baked : SurfaceSpec::Lighting::Dynamic;
        }));
        m.emplace(opt::ambient.key, shading([](const std::string& v, SurfaceSpec& s) { s.ambient = float(parseNumber(opt::ambient, v)); }));
        m.emplace(opt::shadows.key, shading([](const std::string& v, SurfaceSpec& s) { s.shadows = parseChoice(opt::shadows, v) == "on"; }));
        // Colour.
        m.emplace(opt::colour.key, shading([](const std::string& v, SurfaceSpec& s) {
            s.colour = vec3(parseColour(opt::colour, v, false));
            s.colourGiven = true;
        }));
        const auto colourMap = [](const std::string& v, auto& s) {
            colormap(v, 0.0f);  // throws for an unknown name
            s.colormap = v;
        };
        m.emplace(opt::colormap.key, andSlice(shading(colourMap), colourMap));
        const auto window = [](const std::string& v, auto& s) {
            s.window = displayWindow(v);
            s.windowName = v;
        };
        m.emplace(opt::window.key, andSlice(surface(window), window));
        m.emplace(opt::colourBy.key, surface([](const std::string& v, SurfaceSpec& s) {
            s.colourBy = nonEmpty(opt::colourBy, v, "a variable name");
        }));
        const auto colourRange = [](const std::string& v, auto& s) {
            const auto [lo, hi] = parseQuantityRange(opt::colourRange, v);
            s.colourMin = float(lo.value);
            s.colourMax = float(hi.value);
            s.colourMinGiven = lo;
            s.colourMaxGiven = hi;
        };
        m.emplace(opt::colourRange.key, andSlice(shading(colourRange), colourRange));
        const auto maskedColour = [](const std::string& v, auto& s) { s.maskedColour = vec3(parseColour(opt::maskedColour, v, false)); };
        m.emplace(opt::maskedColour.key, andSlice(shading(maskedColour), maskedColour));
        m.emplace(opt::floorColour.key, shading([](const std::string& v, SurfaceSpec& s) {
            s.floorColour = vec3(parseColour(opt::floorColour, v, false));
        }));
        m.emplace(opt::floor.key, surface([](const std::string&, SurfaceSpec& s) { s.floor = true; }));
        // The view and the renderer.
        m.emplace(opt::renderer.key, render([](const std::string& v, RenderSpec& r) {
            (void)resolveRendererName(v);
            r.renderer = v;
        }));
        const auto size = [](const std::string& v, auto& s) { parseSize(opt::size, v, s.width, s.height); };
        m.emplace(opt::size.key, andSlice(render(size), size));
        m.emplace(opt::width.key, render([](const std::string& v, RenderSpec& r) { r.width = parseInteger(opt::width, v); }));
        m.emplace(opt::height.key, render([](const std::string& v, RenderSpec& r) { r.height = parseInteger(opt::height, v); }));
        m.emplace(opt::cameraPos.key, render([](const std::string& v, RenderSpec& r) { r.cameraPos = parseVec3(opt::cameraPos, v); }));
        m.emplace(opt::lookAt.key, render([](const std::string& v, RenderSpec& r) { r.lookAt = parseVec3(opt::lookAt, v); }));
        m.emplace(opt::up.key, render([](const std::string& v, RenderSpec& r) { r.up = parseVec3(opt::up, v); }));
        m.emplace(opt::fov.key, render([](const std::string& v, RenderSpec& r) { r.fov = parseNumber(opt::fov, v); }));
        m.emplace(opt::projection.key, render([](const std::string& v, RenderSpec& r) {
            r.ortho = v == "orthographic" || parseChoice(opt::projection, v) == "ortho";
        }));
        m.emplace(opt::orthoHeight.key, render([](const std::string& v, RenderSpec& r) { r.orthoHeight = parseNumber(opt::orthoHeight, v); }));
        const auto background = [](const std::string& v, auto& s) { s.background = parseColour(opt::background, v, true); };
        m.emplace(opt::background.key, andSlice(render(background), background));
        m.emplace(opt::light.key, render([](const std::string& v, RenderSpec& r) {
            const dvec3 l = parseVec3(opt::light, v);
            if (!(glm::length(l) > 0.0)) refuse(opt::light, "direction must not be zero");
            r.light = l;
        }));
        m.emplace(opt::lod.key, render([](const std::string& v, RenderSpec& r) { r.detail.lodPixels = parseNumber(opt::lod, v); }));
        m.emplace(opt::level.key, render([](const std::string& v, RenderSpec& r) { r.detail.level = parseInteger(opt::level, v); }));
        m.emplace(opt::colourCoherence.key, render([](const std::string&, RenderSpec& r) { r.coherence.colour = true; }));
        m.emplace(opt::colourFillBackground.key, render([](const std::string&, RenderSpec& r) { r.coherence.colourFillsBackground = true; }));
        m.emplace(opt::colourTolerance.key, render([](const std::string& v, RenderSpec& r) {
            r.coherence.colourTolerance = float(parseNumber(opt::colourTolerance, v));
        }));
        m.emplace(opt::tileSize.key, render([](const std::string& v, RenderSpec& r) { r.tileSize = parseInteger(opt::tileSize, v); }));
        m.emplace(opt::branchUp.key, render([](const std::string& v, RenderSpec& r) { r.coherence.branchUp = parseInteger(opt::branchUp, v); }));
        m.emplace(opt::missCoherence.key, render([](const std::string& v, RenderSpec& r) {
            r.coherence.miss = parseChoice(opt::missCoherence, v) == "on";
        }));
        m.emplace(opt::samples.key, render([](const std::string& v, RenderSpec& r) {
            const int n = parseInteger(opt::samples, v);
            const int side = int(std::lround(std::sqrt(double(n))));
            if (side * side != n) refuse(opt::samples, "must be a square number (1, 4, 9, 16, ...), got " + v);
            r.spheres.samples = n;
        }));
        m.emplace(opt::bounces.key, render([](const std::string& v, RenderSpec& r) { r.spheres.bounces = parseInteger(opt::bounces, v); }));
        // The figure.
        m.emplace(opt::figure.key, figure([](const std::string&, FigureSettings& f) { f.enabled = true; }));
        m.emplace(opt::title.key, figure([](const std::string& v, FigureSettings& f) { f.title = v; }));
        m.emplace(opt::caption.key, figure([](const std::string& v, FigureSettings& f) { f.caption = v; }));
        m.emplace(opt::dpi.key, figure([](const std::string& v, FigureSettings& f) { f.dpi = parseInteger(opt::dpi, v); }));
        m.emplace(opt::printSize.key, figure([](const std::string& v, FigureSettings& f) { f.printInches = parsePrintSize(opt::printSize, v); }));
        m.emplace(opt::scaleBar.key, figure([](const std::string&, FigureSettings& f) { f.scaleBar = true; }));
        m.emplace(opt::coastline.key, figure([](const std::string& v, FigureSettings& f) { f.coastline = parseCoastline(v); }));
        // Slices.
        m.emplace(opt::plane.key, slice([](const std::string& v, SliceSpec& s) {
            const std::string name = parseChoice(opt::plane, v);
            for (SlicePlane p : {SlicePlane::Axial, SlicePlane::Coronal, SlicePlane::Sagittal, SlicePlane::X, SlicePlane::Y, SlicePlane::Z})
                if (name == slicePlaneName(p)) s.plane = p;
        }));
        m.emplace(opt::at.key, slice([](const std::string& v, SliceSpec& s) { s.at = parseNumber(opt::at, v); }));
        m.emplace(opt::index.key, slice([](const std::string& v, SliceSpec& s) { s.index = parseInteger(opt::index, v); }));
        return m;
    }();
    return table;
}

}  // namespace

bool applySetting(const Option& o, const std::string& text, const SettingTargets& t) {
    const auto it = setters().find(o.key);
    const Entry* e = it == setters().end() ? nullptr : &it->second;
    if (e && e->slice && t.slice) {
        e->slice(text, *t.slice);
        return true;
    }
    if (o.key == std::string_view(opt::maxMemory.key) && !t.surface && t.request) {  // a command without a surface
        t.request->memoryBudget = parseByteSize(o, text);
        return true;
    }
    if (!e || e->part == SettingPart::Slice) return false;
    if ((e->part == SettingPart::Request && !requestOf(t)) || (e->part == SettingPart::Surface && !t.surface) ||
        (e->part == SettingPart::Render && !t.render) || (e->part == SettingPart::Figure && !figureOf(t)))
        return false;
    e->set(text, t);
    return true;
}

SettingPart settingPart(const Option& o) {
    const auto it = setters().find(o.key);
    return it == setters().end() ? SettingPart::None : it->second.part;
}

bool sliceSetting(const Option& o) {
    const auto it = setters().find(o.key);
    if (it == setters().end()) return false;
    const Entry& e = it->second;
    return e.slice || e.part == SettingPart::Request || (e.part == SettingPart::Figure && o.takenBy("slice"));
}

bool shadingSetting(const Option& o) {
    const auto it = setters().find(o.key);
    return it != setters().end() && it->second.shading;
}

char valueSeparator(const Option& o) {
    const std::string_view a = o.argument;
    const auto upper = [](char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; };
    const auto alnum = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
    for (std::size_t i = 1; i + 1 < a.size(); ++i) {
        if (a[i] == ',' && alnum(a[i - 1]) && alnum(a[i + 1])) return ',';          // "R,G,B", "LON0,LON1,..."
        if (a[i] == 'x' && upper(a[i - 1]) && upper(a[i + 1])) return 'x';          // "WxH"
    }
    return 0;
}

dvec3 parseVec3(const Option& o, const std::string& text) {
    const auto p = split(text, ',');
    if (p.size() != 3) refuse(o, "expected X,Y,Z, got '" + text + "'");
    return dvec3(parseFinite(o, p[0]), parseFinite(o, p[1]), parseFinite(o, p[2]));
}

vec4 parseColour(const Option& o, const std::string& text, bool allowAlpha) {
    const std::string expected = "expected R,G,B" + std::string(allowAlpha ? "[,A]" : "") + " in [0,1], #RRGGBB" +
                                 (allowAlpha ? "[AA]" : "") + " or a CSS colour name (e.g. steelblue)";
    if (!text.empty() && text[0] == '#') {
        const std::string hex = text.substr(1);
        const bool digits = std::all_of(hex.begin(), hex.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; });
        const std::size_t n = hex.size();
        if (!digits || !(n == 3 || n == 6 || (allowAlpha && n == 8))) refuse(o, expected + ", got '" + text + "'");
        vec4 c(1.0f);
        for (std::size_t i = 0; i < (n == 3 ? 3u : n / 2); ++i) {
            const std::string byte = n == 3 ? std::string(2, hex[i]) : hex.substr(2 * i, 2);
            c[int(i)] = float(std::stoi(byte, nullptr, 16)) / 255.0f;
        }
        return c;
    }
    if (!text.empty() && std::isalpha(static_cast<unsigned char>(text[0]))) {
        if (const auto named = namedColour(text)) return vec4(*named, 1.0f);
        refuse(o, "unknown colour name '" + text + "'; " + expected);
    }
    const auto p = split(text, ',');
    if (p.size() != 3 && !(allowAlpha && p.size() == 4)) refuse(o, expected + ", got '" + text + "'");
    vec4 c(1.0f);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double v = parseFinite(o, p[i]);
        if (v < 0.0 || v > 1.0) refuse(o, "component '" + p[i] + "' is outside [0,1]");
        c[int(i)] = float(v);
    }
    return c;
}

void parseSize(const Option& o, const std::string& text, int& w, int& h) {
    const auto x = text.find('x');
    if (x == std::string::npos) refuse(o, "expected WxH (e.g. 1600x1200), got '" + text + "'");
    w = parseInteger(opt::width, text.substr(0, x));
    h = parseInteger(opt::height, text.substr(x + 1));
}

dvec2 parsePrintSize(const Option& o, const std::string& text) {
    std::string t = text, unit;
    for (const char* u : {"mm", "cm", "in"}) {
        const std::string us(u);
        if (t.size() > us.size() && t.compare(t.size() - us.size(), us.size(), us) == 0) {
            unit = us;
            t.erase(t.size() - us.size());
            break;
        }
    }
    if (unit.empty()) refuse(o, "expected WxH with a unit mm, cm or in (e.g. 180x120mm), got '" + text + "'");
    const std::size_t x = t.find('x');
    if (x == std::string::npos) refuse(o, "expected WxH with a unit, got '" + text + "'");
    const double w = parseFinite(o, t.substr(0, x)), h = parseFinite(o, t.substr(x + 1));
    const double perInch = unit == "mm" ? 25.4 : unit == "cm" ? 2.54 : 1.0;
    if (!(w > 0.0 && h > 0.0) || w / perInch > 100.0 || h / perInch > 100.0)
        refuse(o, "width and height must be positive and at most 100 inches, got '" + text + "'");
    return dvec2(w / perInch, h / perInch);
}

dvec2 parseRange(const Option& o, const std::string& text) {
    const auto p = split(text, ',');
    if (p.size() != 2) refuse(o, "expected MIN,MAX, got '" + text + "'");
    const double lo = parseFinite(o, p[0]), hi = parseFinite(o, p[1]);
    if (!(lo < hi) || std::abs(lo) > 3e38 || std::abs(hi) > 3e38)
        refuse(o, "MIN must be below MAX, both finite, got '" + text + "'");
    return dvec2(lo, hi);
}

std::pair<Quantity, Quantity> parseQuantityRange(const Option& o, const std::string& text) {
    const auto p = split(text, ',');
    if (p.size() != 2) refuse(o, "expected MIN,MAX (each a number with an optional unit, e.g. 5degC,20degC), got '" + text + "'");
    const Quantity lo = parseQuantity(o, p[0]), hi = parseQuantity(o, p[1]);
    if (std::abs(lo.value) > 3e38 || std::abs(hi.value) > 3e38 || (lo.unit == hi.unit && !(lo.value < hi.value)))
        refuse(o, "MIN must be below MAX, both finite, got '" + text + "'");
    return {lo, hi};
}

std::uint64_t parseByteSize(const Option& o, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(b, &end);
    std::string suffix(end);
    for (char& c : suffix) c = char(std::tolower(static_cast<unsigned char>(c)));
    const auto bad = [&](const std::string& why) {
        refuse(o, "'" + text + "' " + why +
                      " (expected bytes with an optional K, M, G, T or KiB, MiB, GiB, TiB, e.g. 8G, or N% of the memory)");
    };
    if (text.empty() || end == b || errno == ERANGE || !std::isfinite(v) || std::isspace(static_cast<unsigned char>(*b)))
        bad("is not a memory size");
    if (!(v > 0.0)) bad("must be positive");
    double bytes = v;
    if (suffix == "%") {
        if (v > 100.0) bad("is more than 100%");
        const std::uint64_t physical = physicalMemoryBytes();
        if (physical == 0) bad("is a share of the physical memory, which cannot be read here");
        bytes = v / 100.0 * double(physical);
    } else {
        const char* units[] = {"", "k", "m", "g", "t"};
        int power = -1;
        for (int i = 0; i < 5; ++i)
            if (suffix == units[i] || (i > 0 && suffix == std::string(units[i]) + "ib")) power = i;
        if (power < 0) bad("has an unknown unit '" + std::string(end) + "'");
        bytes = std::ldexp(v, 10 * power);
    }
    if (bytes < 1.0) bad("is less than one byte");
    if (bytes >= 1.8e19) bad("is too large");
    return std::uint64_t(bytes);
}

}  // namespace octrace::model
