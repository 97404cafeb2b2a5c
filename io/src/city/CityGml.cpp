#include "city/CityGml.h"

#include "city/CityJson.h"
#include "input/GdalSupport.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <cpl_minixml.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

namespace octrace::io::detail {
namespace {

struct XmlFree {
    void operator()(CPLXMLNode* n) const { CPLDestroyXMLNode(n); }
};

bool is(const CPLXMLNode* n, const char* name) { return n && n->eType == CXT_Element && std::string(n->pszValue) == name; }

const char* attribute(const CPLXMLNode* n, const char* name) {
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && std::string(c->pszValue) == name && c->psChild) return c->psChild->pszValue;
    return nullptr;
}

/// The element's text (its text children joined).
std::string text(const CPLXMLNode* n) {
    std::string s;
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text && c->pszValue) s += c->pszValue;
    return s;
}

/// "lod2MultiSurface" -> "2"; empty when the name is not a geometry property of a level.
std::string lodOf(const char* name) {
    const std::string s(name);
    if (s.size() < 5 || s.compare(0, 3, "lod") != 0 || !std::isdigit(static_cast<unsigned char>(s[3]))) return "";
    return s.substr(3, 1);
}

struct Polygon {
    const CPLXMLNode* node;
    bool roof;
};

class Parser {
public:
    explicit Parser(const std::string& lod) : lod_(lod) {}

    /// Indexes the ids and finds the first srsName below `n`. Throws FileError for nesting
    /// deeper than any CityGML file has (the walks recurse per level).
    void index(const CPLXMLNode* n, const std::string& name, int depth = 0) {
        if (depth > kMaxNesting) throw FileError(name + ": elements nested more than " + std::to_string(kMaxNesting) + " deep");
        for (; n; n = n->psNext) {
            if (n->eType != CXT_Element) continue;
            if (const char* id = attribute(n, "id")) ids_.emplace(id, n);
            if (crs_.empty())
                if (const char* srs = attribute(n, "srsName")) crs_ = srs;
            index(n->psChild, name, depth + 1);
        }
    }

    void object(const CPLXMLNode* o) {
        const char* idAttr = attribute(o, "id");
        const std::string id = idAttr ? idAttr : std::string(o->pszValue) + " #" + std::to_string(model.objects.size() + 1);
        std::string type = o->pszValue;
        if (type == "ReliefFeature" || type == "TINRelief") type = "TINRelief";
        // The polygons of every level below the object.
        std::map<std::string, std::vector<Polygon>> byLod;
        collect(o->psChild, "", false, byLod, 0);
        const std::vector<Polygon>* pick = nullptr;
        for (const auto& [l, polys] : byLod)  // ascending: the last match is the highest
            if (lod_.empty() || lodMatches(l, lod_)) pick = &polys;
        if (byLod.empty()) {
            notes.add("objects without polygons (points, lines, implicit geometry), left out", id);
            return;
        }
        if (!pick) {
            notes.add("objects without a geometry of LoD " + lod_ + ", left out", id);
            return;
        }
        ++chosen;
        std::uint32_t body = kNone, roof = kNone;
        for (const Polygon& p : *pick) {
            std::uint32_t& target = p.roof ? roof : body;
            if (target == kNone) {
                const std::string t = p.roof ? "RoofSurface" : type;
                model.objects.push_back({id, t, cityTypeRole(type), cityObjectColour(t, id)});
                target = std::uint32_t(model.objects.size() - 1);
            }
            polygon(p.node, target, id);
        }
    }

    CityModel model;
    CityNotes notes;
    std::string crs_;
    std::size_t chosen = 0;

private:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    static constexpr int kMaxNesting = 256;

    /// Gathers the polygons below `n`, each under the level of its nearest lodN property;
    /// `roof`: inside a RoofSurface. Follows xlink:href to polygons (depth-limited).
    void collect(const CPLXMLNode* n, const std::string& lod, bool roof, std::map<std::string, std::vector<Polygon>>& out,
                 int hops) {
        for (; n; n = n->psNext) {
            if (n->eType != CXT_Element) continue;
            std::string l = lodOf(n->pszValue);
            if (l.empty()) l = lod;
            const bool r = roof || is(n, "RoofSurface");
            if (is(n, "Polygon") || is(n, "Triangle")) {
                if (!l.empty()) out[l].push_back({n, r});
                continue;
            }
            if (const char* href = attribute(n, "href"); href && !l.empty() && hops < 4) {
                auto it = ids_.find(href[0] == '#' ? href + 1 : href);
                if (it != ids_.end()) {
                    if (is(it->second, "Polygon") || is(it->second, "Triangle")) out[l].push_back({it->second, r});
                    else collect(it->second->psChild, l, r, out, hops + 1);
                }
            }
            collect(n->psChild, l, r, out, hops);
        }
    }

    /// The coordinates of a LinearRing (posList, pos, coordinates); false when broken.
    bool ring(const CPLXMLNode* ringNode, std::vector<dvec3>& pts) const {
        for (const CPLXMLNode* c = ringNode->psChild; c; c = c->psNext) {
            if (c->eType != CXT_Element) continue;
            int dim = 3;
            if (const char* d = attribute(c, "srsDimension")) dim = std::atoi(d);
            std::string t = text(c);
            if (is(c, "coordinates"))
                for (char& ch : t)
                    if (ch == ',') ch = ' ';
            if (!(is(c, "posList") || is(c, "pos") || is(c, "coordinates"))) continue;
            if (dim != 2 && dim != 3) return false;
            std::vector<double> v;
            const char* s = t.c_str();
            char* end = nullptr;
            for (double x = std::strtod(s, &end); end != s; x = std::strtod(s, &end)) {
                if (!std::isfinite(x)) return false;
                v.push_back(x);
                s = end;
            }
            while (*s && std::isspace(static_cast<unsigned char>(*s))) ++s;
            if (*s || v.size() % std::size_t(dim) != 0) return false;
            for (std::size_t i = 0; i < v.size(); i += std::size_t(dim)) pts.push_back({v[i], v[i + 1], dim == 3 ? v[i + 2] : 0.0});
        }
        if (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();  // GML repeats the first point
        return pts.size() >= 3;
    }

    void polygon(const CPLXMLNode* p, std::uint32_t object, const std::string& id) {
        std::vector<std::vector<dvec3>> rings;
        bool ok = true;
        for (const CPLXMLNode* c = p->psChild; c && ok; c = c->psNext) {
            if (!is(c, "exterior") && !is(c, "interior") && !is(c, "outerBoundaryIs") && !is(c, "innerBoundaryIs")) continue;
            for (const CPLXMLNode* r = c->psChild; r && ok; r = r->psNext) {
                if (!is(r, "LinearRing")) continue;
                std::vector<dvec3> pts;
                ok = ring(r, pts);
                if (is(c, "exterior") || is(c, "outerBoundaryIs")) rings.insert(rings.begin(), std::move(pts));
                else rings.push_back(std::move(pts));
            }
        }
        if (!ok || rings.empty()) {
            notes.add("polygons with broken coordinates, left out", id);
            return;
        }
        if (!model.addPolygon(rings, object)) notes.add("polygons without area or self-intersecting, left out", id);
    }

    const std::string& lod_;
    std::map<std::string, const CPLXMLNode*> ids_;
};

const CPLXMLNode* findCityModel(const CPLXMLNode* n) {
    for (; n; n = n->psNext)
        if (is(n, "CityModel")) return n;
    return nullptr;
}

}  // namespace

bool isCityGmlExtension(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    return ext == ".gml" || ext == ".citygml";
}

CityModel parseCityGml(const std::string& text, const std::string& name, const std::string& lod) {
    GdalMessages messages;
    std::unique_ptr<CPLXMLNode, XmlFree> root(CPLParseXMLString(text.c_str()));
    if (!root) throw FileError(name + ": not well-formed XML (" + GdalMessages::last() + ")");
    CPLStripXMLNamespace(root.get(), nullptr, TRUE);
    const CPLXMLNode* city = findCityModel(root.get());
    if (!city) throw FormatNotSupported(name + ": not CityGML (no CityModel element)");
    Parser p(lod);
    p.index(city->psChild, name);
    p.model.source = name;
    p.model.format = "CityGML";
    // German AdV names, "urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH": ETRS89 / UTM zone N is EPSG:258NN.
    if (const auto at = p.crs_.find("ETRS89_UTM"); at != std::string::npos && at + 12 <= p.crs_.size() &&
        std::isdigit(static_cast<unsigned char>(p.crs_[at + 10])) && std::isdigit(static_cast<unsigned char>(p.crs_[at + 11])))
        p.crs_ = "EPSG:258" + p.crs_.substr(at + 10, 2);
    // A compound "urn:ogc:def:crs,crs:EPSG::25833,crs:EPSG::5783": its first EPSG part.
    for (std::size_t a = 0, b = 0; a < p.crs_.size(); a = b + 1) {
        b = std::min(p.crs_.find(',', a), p.crs_.size());
        const std::string part = p.crs_.substr(a, b - a);
        if (part.find("EPSG") != std::string::npos || b == p.crs_.size()) {
            p.model.crs = crsFromReference(part);
            break;
        }
    }
    for (const CPLXMLNode* m = city->psChild; m; m = m->psNext)
        if (is(m, "cityObjectMember") || is(m, "featureMember"))
            for (const CPLXMLNode* o = m->psChild; o; o = o->psNext)
                if (o->eType == CXT_Element) p.object(o);
    p.notes.appendTo(p.model.notes, name);
    requireSurfaces(p.model, name, lod, p.chosen);
    return std::move(p.model);
}

}  // namespace octrace::io::detail
