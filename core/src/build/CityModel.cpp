#include "octrace/build/CityModel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace {
namespace {

double cross(const dvec2& o, const dvec2& a, const dvec2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

double signedArea(const std::vector<dvec2>& r) {
    double a = 0.0;
    for (std::size_t i = 0, n = r.size(); i < n; ++i) a += r[i].x * r[(i + 1) % n].y - r[(i + 1) % n].x * r[i].y;
    return 0.5 * a;
}

/// Whether segments ab and cd cross at a point interior to both (touching ends do not count).
bool segmentsCross(const dvec2& a, const dvec2& b, const dvec2& c, const dvec2& d) {
    const double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// No two edges of the rings cross (edges that share an end point may touch).
bool edgesSimple(const std::vector<std::vector<dvec2>>& rings) {
    struct Edge { dvec2 a, b; double xlo, xhi; };
    std::vector<Edge> edges;
    for (const auto& r : rings)
        for (std::size_t i = 0; i < r.size(); ++i) {
            const dvec2 a = r[i], b = r[(i + 1) % r.size()];
            edges.push_back({a, b, std::min(a.x, b.x), std::max(a.x, b.x)});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& p, const Edge& q) { return p.xlo < q.xlo; });
    for (std::size_t i = 0; i < edges.size(); ++i)
        for (std::size_t j = i + 1; j < edges.size() && edges[j].xlo <= edges[i].xhi; ++j)
            if (segmentsCross(edges[i].a, edges[i].b, edges[j].a, edges[j].b)) return false;
    return true;
}

/// The rings without repeated points and without a closing point equal to the first.
template <class V>
std::vector<std::vector<V>> cleanRings(const std::vector<std::vector<V>>& in) {
    std::vector<std::vector<V>> rings;
    for (const auto& r : in) {
        std::vector<V> c;
        for (const auto& p : r)
            if (c.empty() || p != c.back()) c.push_back(p);
        while (c.size() > 1 && c.front() == c.back()) c.pop_back();
        rings.push_back(std::move(c));
    }
    return rings;
}

bool inTriangle(const dvec2& p, const dvec2& a, const dvec2& b, const dvec2& c) {
    return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

/// Box of the vertices of the triangles `keep` accepts.
template <class F>
Box3 boundsWhere(const CityModel& m, F keep) {
    Box3 b;
    b.lo = dvec3(std::numeric_limits<double>::infinity());
    b.hi = -b.lo;
    for (const auto& t : m.triangles)
        if (keep(t))
            for (auto i : t.v) {
                b.lo = glm::min(b.lo, m.vertices[i]);
                b.hi = glm::max(b.hi, m.vertices[i]);
            }
    return b;
}

}  // namespace

std::uint32_t CityTexture::at(double x, double y) const {
    if (rgba.empty()) return 0;
    const double fi = (x - origin.x) / pixel.x, fj = (origin.y - y) / pixel.y;
    if (!(fi >= 0.0 && fj >= 0.0 && fi < double(width) && fj < double(height))) return 0;
    return rgba[std::size_t(int(fj)) * std::size_t(width) + std::size_t(int(fi))];
}

Box3 CityModel::bounds() const { return boundsWhere(*this, [](const CityTriangle&) { return true; }); }

void CityModel::append(const CityModel& other) {
    const std::uint32_t v0 = std::uint32_t(vertices.size()), o0 = std::uint32_t(objects.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    objects.insert(objects.end(), other.objects.begin(), other.objects.end());
    for (CityTriangle t : other.triangles) {
        for (auto& i : t.v) i += v0;
        t.object += o0;
        triangles.push_back(t);
    }
    notes.insert(notes.end(), other.notes.begin(), other.notes.end());
}

Box3 CityModel::bounds(CityRole role) const {
    return boundsWhere(*this, [&](const CityTriangle& t) { return objects[t.object].role == role; });
}

std::size_t CityModel::objectCount(CityRole role) const {
    return std::size_t(std::count_if(objects.begin(), objects.end(), [&](const CityObject& o) { return o.role == role; }));
}

bool triangulatePolygon(const std::vector<std::vector<dvec2>>& rings, std::vector<std::array<std::uint32_t, 3>>& out) {
    if (rings.empty() || rings[0].size() < 3) return false;
    if (!edgesSimple(rings)) return false;
    // Points with their original indices; the outer ring counter-clockwise, holes clockwise.
    struct P { dvec2 p; std::uint32_t index; };
    std::vector<std::vector<P>> loops;
    std::uint32_t base = 0;
    for (std::size_t r = 0; r < rings.size(); ++r) {
        std::vector<P> loop;
        for (std::size_t i = 0; i < rings[r].size(); ++i) loop.push_back({rings[r][i], base + std::uint32_t(i)});
        base += std::uint32_t(rings[r].size());
        const double area = signedArea(rings[r]);
        if (r == 0 && !(std::abs(area) > 0.0)) return false;
        if (loop.size() < 3 || area == 0.0) continue;  // a degenerate hole cuts nothing out
        if ((r == 0) != (area > 0.0)) std::reverse(loop.begin(), loop.end());
        loops.push_back(std::move(loop));
    }
    std::vector<P> poly = loops[0];
    // Join the holes, rightmost first, to a vertex of the outer polygon they can see (Eberly's
    // method: cast a ray towards +x from the hole's rightmost point).
    std::vector<std::size_t> order;
    for (std::size_t h = 1; h < loops.size(); ++h) order.push_back(h);
    auto rightmost = [&](std::size_t h) {
        return std::size_t(std::max_element(loops[h].begin(), loops[h].end(), [](const P& a, const P& b) { return a.p.x < b.p.x; }) -
                           loops[h].begin());
    };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return loops[a][rightmost(a)].p.x > loops[b][rightmost(b)].p.x; });
    for (std::size_t h : order) {
        const std::vector<P>& hole = loops[h];
        const std::size_t mi = rightmost(h);
        const dvec2 m = hole[mi].p;
        double best = std::numeric_limits<double>::infinity();
        std::size_t edge = poly.size();
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const dvec2 a = poly[i].p, b = poly[(i + 1) % poly.size()].p;
            if (std::min(a.y, b.y) > m.y || std::max(a.y, b.y) < m.y || a.y == b.y) continue;
            const double x = a.x + (m.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x >= m.x && x < best) {
                best = x;
                edge = i;
            }
        }
        if (edge == poly.size()) return false;  // the hole is not inside the outer ring
        const dvec2 hit(best, m.y);
        std::size_t pi = poly[edge].p.x > poly[(edge + 1) % poly.size()].p.x ? edge : (edge + 1) % poly.size();
        if (poly[pi].p != hit) {
            // A reflex vertex inside the triangle (m, hit, P) would block the bridge: take the
            // one at the smallest angle to the ray instead.
            const dvec2 pp = poly[pi].p;
            double bestAngle = std::numeric_limits<double>::infinity();
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const dvec2 q = poly[i].p;
                const dvec2 prev = poly[(i + poly.size() - 1) % poly.size()].p, next = poly[(i + 1) % poly.size()].p;
                if (cross(prev, q, next) >= 0.0 || q == pp) continue;  // convex
                const bool inside = hit.y <= pp.y ? inTriangle(q, m, hit, pp) : inTriangle(q, m, pp, hit);
                if (!inside) continue;
                const double angle = std::abs(std::atan2(q.y - m.y, q.x - m.x));
                if (angle < bestAngle) {
                    bestAngle = angle;
                    pi = i;
                }
            }
        }
        std::vector<P> joined(poly.begin(), poly.begin() + std::ptrdiff_t(pi) + 1);
        for (std::size_t k = 0; k <= hole.size(); ++k) joined.push_back(hole[(mi + k) % hole.size()]);
        joined.push_back(poly[pi]);
        joined.insert(joined.end(), poly.begin() + std::ptrdiff_t(pi) + 1, poly.end());
        poly = std::move(joined);
    }
    // Ear clipping.
    std::vector<std::array<std::uint32_t, 3>> tris;
    std::vector<std::size_t> next(poly.size()), prev(poly.size());
    for (std::size_t i = 0; i < poly.size(); ++i) {
        next[i] = (i + 1) % poly.size();
        prev[i] = (i + poly.size() - 1) % poly.size();
    }
    std::size_t remaining = poly.size(), i = 0, stall = 0;
    auto isEar = [&](std::size_t v) {
        const dvec2 a = poly[prev[v]].p, b = poly[v].p, c = poly[next[v]].p;
        if (cross(a, b, c) <= 0.0) return false;
        for (std::size_t k = next[next[v]]; k != prev[v]; k = next[k]) {
            const dvec2 q = poly[k].p;
            if (q == a || q == b || q == c) continue;
            if (cross(poly[prev[k]].p, q, poly[next[k]].p) > 0.0) continue;  // only reflex vertices can block
            if (inTriangle(q, a, b, c)) return false;
        }
        return true;
    };
    while (remaining > 3) {
        const std::size_t a = prev[i], c = next[i];
        const bool degenerate = cross(poly[a].p, poly[i].p, poly[c].p) == 0.0 && stall > remaining;
        if (isEar(i) || degenerate) {
            if (!degenerate) tris.push_back({poly[a].index, poly[i].index, poly[c].index});
            next[a] = c;
            prev[c] = a;
            --remaining;
            i = c;
            stall = 0;
            continue;
        }
        i = next[i];
        if (++stall > 2 * remaining) return false;
    }
    if (cross(poly[prev[i]].p, poly[i].p, poly[next[i]].p) > 0.0) tris.push_back({poly[prev[i]].index, poly[i].index, poly[next[i]].index});
    if (tris.empty()) return false;
    out.insert(out.end(), tris.begin(), tris.end());
    return true;
}

bool CityModel::addPolygon(const std::vector<std::vector<dvec3>>& ringsIn, std::uint32_t object) {
    const std::vector<std::vector<dvec3>> rings = cleanRings(ringsIn);
    if (rings.empty() || rings[0].size() < 3) return false;
    // Newell's normal of the outer ring, relative to its first point (large coordinates).
    const dvec3 o = rings[0][0];
    dvec3 n(0.0);
    for (std::size_t i = 0; i < rings[0].size(); ++i) {
        const dvec3 a = rings[0][i] - o, b = rings[0][(i + 1) % rings[0].size()] - o;
        n += dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    if (!(glm::length(n) > 0.0)) return false;
    // Project onto the plane of the two axes that the normal is least along.
    const dvec3 an = glm::abs(n);
    const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    std::vector<std::vector<dvec2>> flat;
    for (const auto& r : rings) {
        std::vector<dvec2> f;
        for (const auto& p : r) f.push_back(dvec2(p[u] - o[u], p[v] - o[v]));
        flat.push_back(std::move(f));
    }
    std::vector<std::array<std::uint32_t, 3>> tris;
    if (!triangulatePolygon(flat, tris)) return false;
    const std::uint32_t first = std::uint32_t(vertices.size());
    for (const auto& r : rings) vertices.insert(vertices.end(), r.begin(), r.end());
    for (const auto& t : tris) triangles.push_back({{first + t[0], first + t[1], first + t[2]}, object});
    return true;
}

bool CityModel::addPrism(const std::vector<std::vector<dvec2>>& ringsIn, double base, double top, std::uint32_t object) {
    if (!(top > base)) return false;
    const std::vector<std::vector<dvec2>> rings = cleanRings(ringsIn);
    if (rings.empty() || rings[0].size() < 3) return false;
    const dvec2 o = rings[0][0];
    std::vector<std::vector<dvec2>> local;
    for (const auto& r : rings) {
        std::vector<dvec2> l;
        for (const auto& p : r) l.push_back(p - o);
        local.push_back(std::move(l));
    }
    std::vector<std::array<std::uint32_t, 3>> tris;
    if (!triangulatePolygon(local, tris)) return false;
    const std::uint32_t floor = std::uint32_t(vertices.size());
    for (const auto& r : rings)
        for (const auto& p : r) vertices.push_back(dvec3(p, base));
    const std::uint32_t roof = std::uint32_t(vertices.size());
    for (const auto& r : rings)
        for (const auto& p : r) vertices.push_back(dvec3(p, top));
    for (const auto& t : tris) {
        triangles.push_back({{floor + t[0], floor + t[2], floor + t[1]}, object});
        triangles.push_back({{roof + t[0], roof + t[1], roof + t[2]}, object});
    }
    std::uint32_t start = 0;
    for (const auto& r : rings) {
        const std::uint32_t n = std::uint32_t(r.size());
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = start + i, b = start + (i + 1) % n;
            triangles.push_back({{floor + a, floor + b, roof + b}, object});
            triangles.push_back({{floor + a, roof + b, roof + a}, object});
        }
        start += n;
    }
    return true;
}

}  // namespace octrace
