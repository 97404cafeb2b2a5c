#include "octrace/csg/Solid.h"

#include "octrace/csg/Relief.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

namespace octrace {
namespace {

struct KindName {
    Solid::Kind kind;
    const char* name;
    std::size_t count;
    const char* form;
};
constexpr KindName kKinds[] = {
    {Solid::Kind::Box, "box", 6, "box:X0,Y0,Z0,X1,Y1,Z1"},
    {Solid::Kind::Sphere, "sphere", 4, "sphere:X,Y,Z,R"},
    {Solid::Kind::Cylinder, "cylinder", 7, "cylinder:X0,Y0,Z0,X1,Y1,Z1,R"},
    {Solid::Kind::HalfSpace, "halfspace", 6, "halfspace:X,Y,Z,NX,NY,NZ"},
};

const KindName* kindOf(const std::string& spec) {
    const auto colon = spec.find(':');
    if (colon == std::string::npos) return nullptr;
    const std::string name = spec.substr(0, colon);
    for (const auto& k : kKinds)
        if (name == k.name) return &k;
    return nullptr;
}

/// Distance from p to the segment's infinite cylinder axis and the position along it.
void cylinderCoords(const Solid& s, const dvec3& p, double& radial, double& along, double& half, dvec3& axis, dvec3& centre) {
    const dvec3 d = s.b - s.a;
    half = 0.5 * glm::length(d);
    axis = d / (2.0 * half);
    centre = 0.5 * (s.a + s.b);
    const dvec3 q = p - centre;
    along = glm::dot(q, axis);
    radial = glm::length(q - along * axis);
}

}  // namespace

bool isSolidSpec(const std::string& spec) { return kindOf(spec) != nullptr; }

bool isReliefSpec(const std::string& spec) { return spec.rfind("relief:", 0) == 0; }

std::string reliefPath(const std::string& spec) {
    std::string path = isReliefSpec(spec) ? spec.substr(7) : std::string();
    if (path.empty()) throw UsageError("relief: give the relief raster's file, relief:FILE (e.g. relief:etopo20.cdf)");
    return path;
}

Solid Solid::below(std::shared_ptr<const Relief> r) {
    Solid s;
    s.kind = Kind::Relief;
    s.relief = std::move(r);
    return s;
}

SolidCover Solid::classify(const dvec3& lo, const dvec3& hi) const {
    if (kind == Kind::Relief) {
        double zmin, zmax;
        bool complete;
        relief->zRange(lo.x, hi.x, lo.y, hi.y, zmin, zmax, complete);
        if (zmin > zmax || lo.z > zmax) return SolidCover::Outside;
        return complete && hi.z <= zmin ? SolidCover::Inside : SolidCover::Mixed;
    }
    bool all = true;
    for (int q = 0; q < 8 && all; ++q)
        all = distance(dvec3(q & 4 ? hi.x : lo.x, q & 2 ? hi.y : lo.y, q & 1 ? hi.z : lo.z)) <= 0.0;
    if (all) return SolidCover::Inside;  // convex: the whole box is inside
    return distance(0.5 * (lo + hi)) > 0.5 * glm::length(hi - lo) ? SolidCover::Outside : SolidCover::Mixed;
}

Solid parseSolid(const std::string& spec) {
    const KindName* k = kindOf(spec);
    if (!k) throw UsageError("'" + spec + "' is not a solid (box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R, cylinder:X0,Y0,Z0,X1,Y1,Z1,R, halfspace:X,Y,Z,NX,NY,NZ)");
    std::vector<double> v;
    std::stringstream in(spec.substr(spec.find(':') + 1));
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
            throw UsageError(std::string(k->name) + ": '" + item + "' is not a finite number (expected " + k->form + ")");
        v.push_back(x);
    }
    if (v.size() != k->count)
        throw UsageError(std::string(k->name) + ": expected " + std::to_string(k->count) + " numbers, got " + std::to_string(v.size()) +
                         " (" + k->form + ")");
    Solid s;
    s.kind = k->kind;
    s.a = dvec3(v[0], v[1], v[2]);
    if (k->count >= 6) s.b = dvec3(v[3], v[4], v[5]);
    switch (s.kind) {
    case Solid::Kind::Box:
        for (int i = 0; i < 3; ++i)
            if (!(s.a[i] < s.b[i])) throw UsageError("box: each minimum must be below its maximum (" + std::string(k->form) + ")");
        break;
    case Solid::Kind::Sphere:
        s.r = v[3];
        break;
    case Solid::Kind::Cylinder:
        s.r = v[6];
        if (!(glm::length(s.b - s.a) > 0.0)) throw UsageError("cylinder: its two axis points are the same");
        break;
    case Solid::Kind::HalfSpace:
        if (!(glm::length(s.b) > 0.0)) throw UsageError("halfspace: the normal is zero");
        s.b = glm::normalize(s.b);
        break;
    case Solid::Kind::Relief: break;  // kindOf() knows no relief: it needs a file (isReliefSpec)
    }
    if ((s.kind == Solid::Kind::Sphere || s.kind == Solid::Kind::Cylinder) && !(s.r > 0.0))
        throw UsageError(std::string(k->name) + ": the radius must be positive");
    return s;
}

double Solid::distance(const dvec3& p) const {
    switch (kind) {
    case Kind::Box: {
        const dvec3 c = 0.5 * (a + b), h = 0.5 * (b - a);
        const dvec3 q = glm::abs(p - c) - h;
        return glm::length(glm::max(q, dvec3(0.0))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
    }
    case Kind::Sphere: return glm::length(p - a) - r;
    case Kind::Cylinder: {
        double radial, along, half;
        dvec3 axis, centre;
        cylinderCoords(*this, p, radial, along, half, axis, centre);
        const double dr = radial - r, da = std::abs(along) - half;
        return std::min(std::max(dr, da), 0.0) + std::hypot(std::max(dr, 0.0), std::max(da, 0.0));
    }
    case Kind::HalfSpace: return glm::dot(p - a, b);
    case Kind::Relief: {
        const double z = relief->surfaceZ(p.x, p.y);
        return std::isnan(z) ? std::numeric_limits<double>::infinity() : p.z - z;
    }
    }
    return 0.0;
}

dvec3 Solid::normal(const dvec3& p) const {
    switch (kind) {
    case Kind::Box: {
        // The face whose plane is nearest (inside) or the direction out of the box (outside).
        const dvec3 c = 0.5 * (a + b), h = 0.5 * (b - a), d = p - c;
        const dvec3 q = glm::abs(d) - h;
        const dvec3 out = glm::max(q, dvec3(0.0));
        if (glm::length(out) > 0.0) return glm::normalize(out * glm::sign(d));
        int i = 0;
        for (int k = 1; k < 3; ++k)
            if (q[k] > q[i]) i = k;
        dvec3 n(0.0);
        n[i] = d[i] < 0.0 ? -1.0 : 1.0;
        return n;
    }
    case Kind::Sphere: {
        const dvec3 d = p - a;
        const double l = glm::length(d);
        return l > 0.0 ? d / l : dvec3(0, 0, 1);
    }
    case Kind::Cylinder: {
        double radial, along, half;
        dvec3 axis, centre;
        cylinderCoords(*this, p, radial, along, half, axis, centre);
        const dvec3 q = p - centre - along * axis;
        const dvec3 radialDir = radial > 0.0 ? q / radial : dvec3(0.0);
        const dvec3 capDir = along < 0.0 ? -axis : axis;
        const double dr = radial - r, da = std::abs(along) - half;
        if (dr > 0.0 && da > 0.0) return glm::normalize(dr * radialDir + da * capDir);
        if (da > dr || radial == 0.0) return capDir;
        return radialDir;
    }
    case Kind::HalfSpace: return b;
    case Kind::Relief: return relief->normal(p.x, p.y);
    }
    return dvec3(0, 0, 1);
}

std::string Solid::describe() const {
    if (kind == Kind::Relief) return "relief:" + (relief ? relief->raster().source : std::string());
    std::ostringstream s;
    s.precision(10);
    const KindName& k = kKinds[int(kind)];
    s << k.name << ":" << a.x << "," << a.y << "," << a.z;
    if (kind != Kind::Sphere) s << "," << b.x << "," << b.y << "," << b.z;
    if (kind == Kind::Sphere || kind == Kind::Cylinder) s << "," << r;
    return s.str();
}

}  // namespace octrace
