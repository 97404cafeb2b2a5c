#include "octrace/model/Figure.h"

#include "octrace/build/PolarStereographic.h"

#include "octrace/io/CityReader.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Parameter.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>

namespace octrace::model {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Projects world points into the plot; false behind a perspective camera.
struct Projector {
    explicit Projector(const Camera& c) : rays(c) {}
    bool operator()(const dvec3& p, dvec2& out) const {
        const dvec3 d = p - rays.eye();
        const double cz = glm::dot(d, rays.back());
        if (!rays.orthographic() && !(cz < 0.0)) return false;
        rays.toPixel(glm::dot(d, rays.right()), glm::dot(d, rays.up()), cz, out.x, out.y);
        return std::isfinite(out.x) && std::isfinite(out.y);
    }
    RayGenerator rays;
};

/// Liang-Barsky: the part of segment a-b inside [lo, hi] as parameters t0 <= t1; false if none.
bool clipSegment(dvec2 a, dvec2 b, dvec2 lo, dvec2 hi, double& t0, double& t1) {
    t0 = 0.0, t1 = 1.0;
    const dvec2 d = b - a;
    const double p[4] = {-d.x, d.x, -d.y, d.y}, q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return false;
        } else {
            const double t = q[i] / p[i];
            if (p[i] < 0.0) t0 = std::max(t0, t);
            else t1 = std::min(t1, t);
        }
    }
    return t0 <= t1;
}

/// The coastlines of a 3-D figure: each line on the horizontal plane z = `z` (world) within the
/// grid's box, sampled about every pixel and kept where no rendered surface lies in front
/// (`plot`'s depth, with `tolerance` world units so that a surface at the plane itself does
/// not hide its own coast).
void coastlinesIn3d(const io::Coastlines& coast, const GeoAxes& g, const Box3& box, double z, const Frame& plot,
                    const Projector& project, double tolerance, std::vector<std::vector<dvec2>>& out) {
    std::vector<std::vector<dvec2>> world;
    std::vector<dvec2> xy;
    for (const auto& line : coast.lines) {
        xy.clear();
        for (const dvec2& p : line) xy.push_back(g.world(p.x, p.y));
        clipPolyline(xy, dvec2(box.lo), dvec2(box.hi), world);
    }
    const RayGenerator& rays = project.rays;
    auto visible = [&](const dvec3& p, dvec2& px) {
        if (!project(p, px)) return false;
        const int ix = int(std::floor(px.x)), iy = int(std::floor(px.y));
        if (ix < 0 || iy < 0 || ix >= plot.width || iy >= plot.height) return false;
        const double d = plot.depth.empty() ? std::numeric_limits<double>::infinity() : double(plot.depth[plot.pixel(ix, iy)]);
        const double dist = rays.orthographic() ? -glm::dot(p - rays.eye(), rays.back()) : glm::length(p - rays.eye());
        return !(d < dist - tolerance);
    };
    for (const auto& line : world) {
        std::vector<dvec2> piece;
        auto flush = [&] {
            if (piece.size() >= 2) out.push_back(std::move(piece));
            piece.clear();
        };
        for (std::size_t i = 1; i < line.size(); ++i) {
            const dvec3 a(line[i - 1], z), b(line[i], z);
            dvec2 pa, pb;
            const int steps = project(a, pa) && project(b, pb) ? std::clamp(int(std::ceil(glm::length(pb - pa))), 1, 4096) : 64;
            for (int s = (i == 1 ? 0 : 1); s <= steps; ++s) {
                dvec2 px;
                if (visible(a + (b - a) * (double(s) / steps), px)) piece.push_back(px);
                else flush();
            }
        }
        flush();
    }
}

/// Round tick values over [lo, hi], about `count` of them and at least 3 when the range has any,
/// none within 15% of the range from `skip` (a vertical edge's end at the top corner, where the
/// horizontal edges' labels are).
std::vector<double> ticksOf(double lo, double hi, int count, double skip = std::numeric_limits<double>::quiet_NaN()) {
    std::vector<double> t;
    for (int c = count; c <= count * 8 && t.size() < 3; c *= 2) {
        t = io::niceTicks(lo, hi, c);
        std::erase_if(t, [&](double v) { return std::abs(v - skip) < 0.15 * std::abs(hi - lo); });
    }
    return t;
}

/// The patient's letters for the plot's sides (left, top, right, bottom): for each side, the
/// end of the LPS axis whose direction on the screen points most nearly that way (R/L on x,
/// A/P on y, I/S on z); none where no axis points within 60 degrees of it.
std::array<std::string, 4> patientLetters(const Projector& project, const Box3& box) {
    std::array<std::string, 4> out;
    const dvec3 c = box.centre();
    const double reach = 0.25 * glm::length(box.hi - box.lo);
    dvec2 pc;
    if (!(reach > 0.0) || !project(c, pc)) return out;
    const char* names[3][2] = {{"R", "L"}, {"A", "P"}, {"I", "S"}};
    std::array<dvec2, 3> dir{};
    for (int a = 0; a < 3; ++a) {
        dvec3 e(0.0);
        e[a] = reach;
        dvec2 p;
        if (project(c + e, p) && glm::length(p - pc) > 1e-6) dir[std::size_t(a)] = glm::normalize(p - pc);
    }
    const dvec2 sides[4] = {{-1.0, 0.0}, {0.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};  // plot pixels: y down
    for (int side = 0; side < 4; ++side) {
        double best = 0.5;
        for (int a = 0; a < 3; ++a)
            for (int sign : {-1, 1}) {
                const double d = double(sign) * glm::dot(dir[std::size_t(a)], sides[side]);
                if (d > best) best = d, out[std::size_t(side)] = names[a][sign > 0 ? 1 : 0];
            }
    }
    return out;
}

/// The ticks of each axis (the labels of spec.labels, at the world points `at`, each on one
/// edge along its axis) also on the axis's three other parallel box edges (FigureLabel::edge
/// 1, 2, 3, those whose middle projects farthest from the box's centre first: the outer
/// ones), each moved off its edge the way that points away from the box (across both faces
/// that meet there) looks in the picture, as ParaView's cube axes choose among the edges.
/// io::composeFigure draws one edge per axis.
void alternativeEdges(io::FigureSpec& spec, const std::vector<dvec3>& at, const Box3& box, const Projector& project) {
    dvec2 centre(0.0);
    for (int c = 0; c < 8; ++c) {
        dvec2 p;
        if (!project(dvec3((c & 4) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 1) ? box.hi.z : box.lo.z), p))
            return;  // the camera inside or behind the box: its edges have no outside
        centre += p / 8.0;
    }
    const std::size_t given = spec.labels.size();
    for (int a = 0; a < 3; ++a) {
        std::vector<std::size_t> of;
        for (std::size_t i = 0; i < given; ++i)
            if (spec.labels[i].axis == a && spec.labels[i].edge == 0) of.push_back(i);
        if (of.empty()) continue;
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        // The other edges: the corners of the box's face across the axis, but the given one.
        struct Edge {
            dvec3 corner, out;  // the edge's point at the axis's low end; away from the box
            double reach = 0.0;
        };
        std::vector<Edge> edges;
        const dvec3& p0 = at[of.front()];
        for (int k = 0; k < 4; ++k) {
            dvec3 q(0.0), out(0.0);
            q[a] = box.lo[a];
            q[b] = (k & 1) ? box.hi[b] : box.lo[b];
            q[c] = (k & 2) ? box.hi[c] : box.lo[c];
            if (q[b] == p0[b] && q[c] == p0[c]) continue;
            // Away from the box, across both faces that meet at the edge (a 20th of the box).
            out[b] = ((k & 1) ? 0.05 : -0.05) * (box.hi[b] - box.lo[b]);
            out[c] = ((k & 2) ? 0.05 : -0.05) * (box.hi[c] - box.lo[c]);
            dvec3 r = q;
            r[a] = box.hi[a];
            dvec2 pq, pr;
            if (!project(q, pq) || !project(r, pr)) continue;
            edges.push_back({q, out, glm::length(0.5 * (pq + pr) - centre)});
        }
        std::stable_sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.reach > y.reach; });
        for (std::size_t k = 0; k < edges.size(); ++k)
            for (std::size_t i : of) {
                dvec3 p = edges[k].corner;
                p[a] = at[i][a];
                io::FigureLabel lab = spec.labels[i];
                dvec2 beyond;
                if (!project(p, lab.at) || !project(p + edges[k].out, beyond) || glm::length(beyond - lab.at) < 1e-9) continue;
                // The label's centre off the edge, the way away from the box looks: half its
                // extent that way and a gap.
                const dvec2 n = glm::normalize(beyond - lab.at);
                const double off = 0.5 * io::labelWidthEstimate(lab.text) * std::abs(n.x) + 0.5 * std::abs(n.y) + 0.9;
                lab.dx = n.x * off, lab.dy = n.y * off;
                lab.edge = int(k) + 1;
                spec.labels.push_back(lab);
            }
    }
}

}  // namespace

std::string numberText(double v, int precision) {
    std::ostringstream s;
    s.precision(precision);
    s << (v == 0.0 ? 0.0 : v);
    return s.str();
}

std::string longitudeText(double lon) {
    lon = std::fmod(lon, 360.0);
    if (lon > 180.0) lon -= 360.0;
    if (lon <= -180.0) lon += 360.0;
    const long r = std::lround(lon);
    if (r == 0 || r == 180 || r == -180) return std::to_string(std::labs(r)) + "\u00b0";
    return std::to_string(std::labs(r)) + (r > 0 ? "\u00b0E" : "\u00b0W");
}

std::string latitudeText(double lat) {
    const long r = std::lround(lat);
    if (r == 0) return "0\u00b0";
    return std::to_string(std::labs(r)) + (r > 0 ? "\u00b0N" : "\u00b0S");
}

dvec2 GeoAxes::world(double lonDeg, double latDeg) const {
    return g.polar() ? polar::worldFromLonLat(g, lonDeg, latDeg) : dvec2(x(lonDeg), y(latDeg));
}
dvec2 GeoAxes::lonLat(double wx, double wy) const {
    return g.polar() ? polar::lonLatFromWorld(g, wx, wy) : dvec2(lon(wx), lat(wy));
}
double GeoAxes::lon(double x) const { return g.lon0 + x / (ScalarField::Geographic::kEarthRadiusKm * std::cos(g.lat0 * kPi / 180.0)) * 180.0 / kPi; }
double GeoAxes::lat(double y) const { return g.lat0 + y / ScalarField::Geographic::kEarthRadiusKm * 180.0 / kPi; }
double GeoAxes::depthM(double z) const { return -z / g.verticalScale * 1000.0; }
double GeoAxes::x(double lonDeg) const { return ScalarField::Geographic::kEarthRadiusKm * std::cos(g.lat0 * kPi / 180.0) * (lonDeg - g.lon0) * kPi / 180.0; }
double GeoAxes::y(double latDeg) const { return ScalarField::Geographic::kEarthRadiusKm * (latDeg - g.lat0) * kPi / 180.0; }
double GeoAxes::z(double depthM) const { return -depthM / 1000.0 * g.verticalScale; }

std::string lowerExtension(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    std::string ext = path.substr(dot == std::string::npos ? path.size() : dot);
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void checkFigureFormat(const std::string& output) {
    const std::string ext = lowerExtension(output);
    if (ext != ".png" && ext != ".tif" && ext != ".tiff")
        throw UsageError("a figure is written as PNG or TIFF: " + output + " must end in .png, .tif or .tiff");
}

bool figureHasColourBar(const model::SurfaceSpec& a) { return !a.colourBy.empty() || !a.colormap.empty(); }

FigureSubject figureSubject(const Surface& s, const std::string& input) {
    FigureSubject out;
    out.name = s.field.name;
    out.geographic = s.field.geographic;
    if (!s.field.values.empty()) out.gridBounds = s.field.worldBounds();
    out.iso = s.iso;
    out.lengthUnit = s.field.geographic.valid ? "km" : io::isCityInput(input) ? "m" : "";
    out.patientLps = s.field.patientLps;
    out.time = s.field.timeLabel;
    return out;
}

std::pair<double, double> gridHeightRange(const ScalarField& grid) {
    const Box3 b = grid.worldBounds();
    if (!grid.geographic.valid) return {b.lo.z, b.hi.z};
    const GeoAxes g{grid.geographic};
    return {-g.depthM(b.lo.z), -g.depthM(b.hi.z)};
}

void warnCoastlineUnused(const std::string& coastline, const std::string& why) {
    if (coastline.empty() || coastline == "none") return;
    static std::once_flag said;
    std::call_once(said, [&] { log::warning(param(opt::coastline.key) + " " + coastline + " is not drawn: " + why); });
}

std::string parseCoastline(const std::string& text) {
    if (text.empty()) throw UsageError(param(opt::coastline.key) + ": give auto, none, crude, low, intermediate, high or a file");
    if (text == "auto") return "";
    return text;
}

io::LonLatBox lonLatBox(const ScalarField::Geographic& geographic, const Box3& box) {
    const GeoAxes g{geographic};
    if (geographic.polar()) {
        // The box's horizontal face sampled; the whole circle when it holds the pole (or when
        // its longitudes wrap behind it).
        double lonLo = INFINITY, lonHi = -INFINITY, latLo = INFINITY, latHi = -INFINITY;
        for (int j = 0; j <= 64; ++j)
            for (int i = 0; i <= 64; ++i) {
                const dvec2 p = g.lonLat(box.lo.x + (box.hi.x - box.lo.x) * i / 64.0, box.lo.y + (box.hi.y - box.lo.y) * j / 64.0);
                lonLo = std::min(lonLo, p.x), lonHi = std::max(lonHi, p.x), latLo = std::min(latLo, p.y), latHi = std::max(latHi, p.y);
            }
        const dvec2 pole = polar::worldFromLonLat(geographic, 0.0, 90.0 * geographic.pole);
        if ((pole.x >= box.lo.x && pole.x <= box.hi.x && pole.y >= box.lo.y && pole.y <= box.hi.y) || lonHi - lonLo > 300.0) {
            lonLo = geographic.lon0 - 180.0, lonHi = geographic.lon0 + 180.0;
            (geographic.pole > 0 ? latHi : latLo) = 90.0 * geographic.pole;
        }
        return {lonLo, lonHi, latLo, latHi};
    }
    return {std::min(g.lon(box.lo.x), g.lon(box.hi.x)), std::max(g.lon(box.lo.x), g.lon(box.hi.x)),
            std::min(g.lat(box.lo.y), g.lat(box.hi.y)), std::max(g.lat(box.lo.y), g.lat(box.hi.y))};
}

std::shared_ptr<const io::Coastlines> figureCoastlines(const std::string& coastline, const io::LonLatBox& region) {
    static std::mutex mutex;
    static std::string lastKey;
    static std::shared_ptr<const io::Coastlines> last;
    if (coastline == "none") return std::make_shared<const io::Coastlines>();
    const std::string key = coastline + "|" + numberText(region.lonMin, 12) + "|" + numberText(region.lonMax, 12) + "|" +
                            numberText(region.latMin, 12) + "|" + numberText(region.latMax, 12);
    std::lock_guard<std::mutex> lock(mutex);
    if (last && key == lastKey) return last;
    std::shared_ptr<const io::Coastlines> out;
    const std::array<std::pair<const char*, io::GshhgResolution>, 4> levels{{{"crude", io::GshhgResolution::Crude},
                                                                              {"low", io::GshhgResolution::Low},
                                                                              {"intermediate", io::GshhgResolution::Intermediate},
                                                                              {"high", io::GshhgResolution::High}}};
    if (coastline.empty()) {
        const io::GshhgResolution r = io::gshhgResolutionFor(region);
        try {
            out = std::make_shared<const io::Coastlines>(io::readGshhg(r, region));
        } catch (const FileError& e) {
            static std::once_flag said;
            std::call_once(said, [&] { log::warning(std::string(e.what()) + "; the figure has no coastlines"); });
            out = std::make_shared<const io::Coastlines>();
        }
    } else {
        for (const auto& [name, r] : levels)
            if (coastline == name) out = std::make_shared<const io::Coastlines>(io::readGshhg(r, region));
        if (!out) out = std::make_shared<const io::Coastlines>(io::readVectorCoastlines(coastline, region));
    }
    if (!out->source.empty()) log::debug("coastlines: " + std::to_string(out->lines.size()) + " lines from " + out->source);
    lastKey = key;
    last = out;
    return out;
}

void clipPolyline(const std::vector<dvec2>& points, dvec2 lo, dvec2 hi, std::vector<std::vector<dvec2>>& out) {
    std::vector<dvec2> piece;
    for (std::size_t i = 1; i < points.size(); ++i) {
        double t0, t1;
        const dvec2 a = points[i - 1], b = points[i];
        if (!clipSegment(a, b, lo, hi, t0, t1)) {
            if (piece.size() >= 2) out.push_back(std::move(piece));
            piece.clear();
            continue;
        }
        const dvec2 p0 = a + (b - a) * t0, p1 = a + (b - a) * t1;
        if (piece.empty() || t0 > 0.0) {
            if (piece.size() >= 2) out.push_back(std::move(piece));
            piece.assign({p0});
        }
        piece.push_back(p1);
        if (t1 < 1.0) {
            out.push_back(std::move(piece));
            piece.clear();
        }
    }
    if (piece.size() >= 2) out.push_back(std::move(piece));
}

void writeFigure(const Frame& plot, const FigureSettings& f, const io::FigureLayout& layout, const FigureSubject& subject,
                 const Octree& tree, const Camera& camera, const RenderSettings& rs, const std::string& path) {
    const io::FigureSpec spec = figureSpec(plot, f, subject, tree, camera, rs);
    io::ImageWriteOptions options;
    options.dpi = layout.dpi;
    io::writeImage(io::composeFigure(plot, spec, layout), path, options);
}

io::FigureLayout fitFigureLayout(const io::FigureLayout& first, const std::function<io::FigureSpec(const io::FigureLayout&)>& specFor) {
    io::FigureLayout l = first;
    io::FigureRoom room;
    for (int round = 0; round < 4; ++round) {
        io::FigureRoom next = io::figureRoom(specFor(l), l);
        if (round > 0) {
            // Grow only: a smaller plot frames its box a little differently.
            next.left = std::max(next.left, room.left), next.top = std::max(next.top, room.top);
            next.right = std::max(next.right, room.right), next.bottom = std::max(next.bottom, room.bottom);
            next.letter = std::max(next.letter, room.letter), next.panel = std::max(next.panel, room.panel);
            if (next == room) break;
        }
        room = next;
        try {
            l = io::layoutFigure(l.width, l.height, l.dpi, l.barW > 0, room);
        } catch (const UsageError&) {
            // The room the text asks for leaves no plot (a small figure): keep the last layout
            // that has one (at first, figureLayout's); its text is thinned and shortened to fit
            // (io::composeFigure).
            break;
        }
    }
    return l;
}

io::FigureLayout fitFigureLayout(const io::FigureLayout& first, const FigureSettings& f, const FigureSubject& subject, const Octree& tree,
                                 const RenderSettings& rs, const RenderSpec& view, const Box3& bounds, SceneView sceneView) {
    FigureSettings text = f;
    text.coastline = "none";
    return fitFigureLayout(first, [&](const io::FigureLayout& l) {
        RenderSpec sized = view;
        sized.width = l.plotW, sized.height = l.plotH;
        return figureSpec(Frame(), text, subject, tree, frameCamera(sized, bounds, sceneView), rs);
    });
}

io::FigureLayout figureLayout(const FigureSettings& f, int width, int height, bool colourBar) {
    const int dpi = f.dpi ? f.dpi : kDefaultDpi;
    if (f.printInches) {
        width = int(std::lround(f.printInches->x * dpi));
        height = int(std::lround(f.printInches->y * dpi));
        if (std::uint64_t(width) * std::uint64_t(height) > (std::uint64_t(1) << 28))
            throw UsageError(param("print_size") + " at " + std::to_string(dpi) + " dpi makes a figure of " + std::to_string(width) +
                             "x" + std::to_string(height) + " pixels; at most 2^28 pixels");
    }
    return io::layoutFigure(width, height, dpi, colourBar);
}

io::FigureSpec figureSpec(const Frame& plot, const FigureSettings& f, const FigureSubject& subject, const Octree& tree, const Camera& camera,
                          const RenderSettings& rs) {
    io::FigureSpec spec;
    spec.title = f.title;
    const ScalarField::Geographic& geographic = subject.geographic;
    std::string sub = (tree.fieldName().empty() ? subject.name : tree.fieldName()) + " = " + numberText(subject.iso) +
                      (tree.fieldUnits().empty() ? "" : " " + tree.fieldUnits());
    const Albedo albedo(tree, rs);
    if (albedo.byValue()) {
        sub += ", coloured by " + tree.valueName();
        spec.colormap = albedo.colormapName();
        spec.low = albedo.low();
        spec.high = albedo.high();
        spec.barLabel = tree.valueName() + (tree.valueUnits().empty() ? "" : " (" + tree.valueUnits() + ")");
    } else if (albedo.byHeight()) {
        // Coloured by height: the bar spans the surface's cell layers, in metres above the sea
        // surface for a geographic field (negative below it), else in world z.
        const bool given = std::isfinite(rs.colourMin) && std::isfinite(rs.colourMax) && rs.colourMin != rs.colourMax;
        const double z0 = given ? double(rs.colourMin) : tree.cubeOrigin.z + double(albedo.heightLow()) * tree.voxelSize();
        const double z1 = given ? double(rs.colourMax) : tree.cubeOrigin.z + double(albedo.heightHigh()) * tree.voxelSize();
        spec.colormap = albedo.colormapName();
        if (geographic.valid) {
            const GeoAxes g{geographic};
            spec.low = -g.depthM(z0);
            spec.high = -g.depthM(z1);
            // Below the sea surface throughout: the bar reads depth, positive down.
            spec.barPositiveDown = spec.high <= 0.0;
            spec.barLabel = spec.barPositiveDown ? "depth (m)" : "height (m)";
        } else {
            spec.low = z0;
            spec.high = z1;
            spec.barLabel = "height (world z)";
        }
    }
    if (!tree.voxelMaterials().empty()) sub += ", sea floor and land";

    // The bounding box: the field's grid (the region read), or the octree's surface.
    const Box3 box = subject.gridBounds ? *subject.gridBounds : tree.occupiedBounds();
    const Projector project(camera);
    std::array<dvec3, 8> corner;
    for (int c = 0; c < 8; ++c)
        corner[std::size_t(c)] = dvec3((c & 4) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 1) ? box.hi.z : box.lo.z);
    for (int a = 0; a < 8; ++a)
        for (int bit : {1, 2, 4}) {
            if (a & bit) continue;
            dvec2 pa, pb;
            if (project(corner[std::size_t(a)], pa) && project(corner[std::size_t(a | bit)], pb)) spec.lines.push_back({pa, pb});
        }

    // Coastlines on the sea surface, or on the top of a grid that starts below it.
    if (geographic.valid && f.coastline != "none") {
        const GeoAxes g{geographic};
        const auto coast = figureCoastlines(f.coastline, lonLatBox(geographic, box));
        coastlinesIn3d(*coast, g, box, std::min(g.z(0.0), box.hi.z), plot, project, 1.5 * tree.voxelSize(), spec.coastlines);
    } else if (!geographic.valid) {
        warnCoastlineUnused(f.coastline, "the field is not on a longitude/latitude grid");
    }

    // Ticks on three edges that meet at the south-east corner of the top: along x at y = lo,
    // along y at x = hi, along z at (hi, lo).
    int axis = 0;  // the axis the next ticks belong to (their labels are thinned together)
    std::vector<dvec3> tickAt;  // the world point of each label, to move it to the other edges
    auto tick = [&](const dvec3& p, const std::string& text, double dx, double dy, const std::string& bare = {}) {
        dvec2 at;
        if (!project(p, at)) return;
        spec.labels.push_back({at, text, dx, dy, axis, 0, bare});
        tickAt.push_back(p);
    };
    if (geographic.valid && geographic.polar()) {
        // The polar plane: ticks in km along x and y, the latitudes covered in the subtitle.
        const GeoAxes g{geographic};
        const io::LonLatBox ll = lonLatBox(geographic, box);
        const double d0 = g.depthM(box.hi.z), d1 = g.depthM(box.lo.z);
        for (double x : ticksOf(box.lo.x, box.hi.x, 5)) tick({x, box.lo.y, box.hi.z}, numberText(x) + " km", 0.0, 1.4);
        axis = 1;
        for (double y : ticksOf(box.lo.y, box.hi.y, 5)) tick({box.hi.x, y, box.hi.z}, numberText(y) + " km", 2.2, 0.0);
        axis = 2;
        for (double d : ticksOf(d0, d1, 4, d0)) tick({box.hi.x, box.lo.y, g.z(d)}, numberText(d) + " m", 2.6, 0.0);
        sub += "; polar stereographic, " + latitudeText(ll.latMin) + "\u2013" + latitudeText(ll.latMax) + ", " +
               numberText(std::round(d0)) + "\u2013" + numberText(std::round(d1)) + " m";
    } else if (geographic.valid) {
        const GeoAxes g{geographic};
        const double lon0 = g.lon(box.lo.x), lon1 = g.lon(box.hi.x), lat0 = g.lat(box.lo.y), lat1 = g.lat(box.hi.y);
        const double d0 = g.depthM(box.hi.z), d1 = g.depthM(box.lo.z);
        for (double lon : ticksOf(lon0, lon1, 6)) tick({g.x(lon), box.lo.y, box.hi.z}, longitudeText(lon), 0.0, 1.4);
        axis = 1;
        for (double lat : ticksOf(lat0, lat1, 5)) tick({box.hi.x, g.y(lat), box.hi.z}, latitudeText(lat), 2.2, 0.0);
        axis = 2;
        for (double d : ticksOf(d0, d1, 4, d0)) tick({box.hi.x, box.lo.y, g.z(d)}, numberText(d) + " m", 2.6, 0.0);
        sub += "; " + longitudeText(lon0) + "\u2013" + longitudeText(lon1) + ", " + latitudeText(lat0) + "\u2013" +
               latitudeText(lat1) + ", " + numberText(std::round(d0)) + "\u2013" + numberText(std::round(d1)) + " m";
    } else if (subject.patientLps) {
        // Patient LPS in mm; the patient's letters go outside the plot, one a side (io).
        spec.sideLetters = patientLetters(project, box);
        // An axis with no room for 3 labels in mm drops the unit (the subtitle names it).
        const auto mm = [&](const dvec3& p, double v, double dx, double dy) { tick(p, numberText(v, 4) + " mm", dx, dy, numberText(v, 4)); };
        for (double x : ticksOf(box.lo.x, box.hi.x, 5)) mm({x, box.lo.y, box.hi.z}, x, 0.0, 1.4);
        axis = 1;
        for (double y : ticksOf(box.lo.y, box.hi.y, 5)) mm({box.hi.x, y, box.hi.z}, y, 2.6, 0.0);
        axis = 2;
        for (double z : ticksOf(box.lo.z, box.hi.z, 4, box.hi.z)) mm({box.hi.x, box.lo.y, z}, z, 3.0, 0.0);
        sub += "; patient LPS, mm";
    } else {
        // World coordinates: metres for a city (km over 5 km), else the field's own units. Where
        // they are large beside the box (a city's projected metres), ticks count from its low
        // corner, told in the subtitle.
        const bool metres = subject.lengthUnit == "m";
        std::string from;
        auto axisTicks = [&](int a, int count, const std::function<dvec3(double)>& at, double dx, double dy) {
            axis = a;
            const double lo = box.lo[a], hi = box.hi[a];
            const double unit = metres && hi - lo >= 5000.0 ? 1000.0 : 1.0;
            // The corner: the low end rounded down to a round step of the box's span.
            const std::vector<double> span = io::niceTicks(0.0, (hi - lo) / unit, count);
            const double step = span.size() > 1 ? (span[1] - span[0]) * unit : 1.0;
            const bool offset = std::max(std::abs(lo), std::abs(hi)) >= 1e4;
            const double base = offset ? std::floor(lo / step) * step : 0.0;
            const std::string name = metres ? "" : std::string(1, char('x' + a)) + " ";
            const std::string suffix = !metres ? "" : unit > 1.0 ? " km" : " m";
            const double skip = a == 2 ? (hi - base) / unit : std::numeric_limits<double>::quiet_NaN();  // the top corner
            for (double v : ticksOf((lo - base) / unit, (hi - base) / unit, count, skip))
                tick(at(base + v * unit), name + (offset && v > 0.0 ? "+" : "") + numberText(v, 4) + suffix, dx, dy);
            if (offset) from += std::string(from.empty() ? "" : ", ") + char('x' + a) + " " + numberText(base, 12);
        };
        axisTicks(0, 5, [&](double x) { return dvec3(x, box.lo.y, box.hi.z); }, 0.0, 1.4);
        axisTicks(1, 5, [&](double y) { return dvec3(box.hi.x, y, box.hi.z); }, 2.2, 0.0);
        axisTicks(2, 4, [&](double z) { return dvec3(box.hi.x, box.lo.y, z); }, 2.6, 0.0);
        if (!from.empty()) sub += "; ticks from " + from + (metres ? " m" : "");
    }
    alternativeEdges(spec, tickAt, box, project);
    // The caption (an animation frame's date) or else the time step first: a subtitle too long
    // for the figure drops its last parts (io::composeFigure).
    const std::string& first = f.caption.empty() ? subject.time : f.caption;
    spec.subtitle = first.empty() ? sub : first + (sub.empty() ? "" : "; " + sub);

    if (f.scaleBar) {
        // World units per plot pixel across the view at the look-at point.
        const double height = camera.orthographic()
                                  ? camera.orthoHeight
                                  : 2.0 * glm::length(camera.position - camera.lookAt) * std::tan(camera.fovYDegrees * kPi / 360.0);
        const double perPixel = height / double(std::max(1, camera.height));
        const double length = io::scaleBarLength(perPixel, camera.width);
        if (length > 0.0) {
            spec.scaleBarPx = length / perPixel;
            spec.scaleBarLabel = numberText(length) + (subject.lengthUnit.empty() ? "" : " " + subject.lengthUnit);
        }
    }
    return spec;
}

}  // namespace octrace::model
