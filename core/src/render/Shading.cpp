#include "octrace/render/Shading.h"

#include "lighting/ShadowTracer.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <climits>
#include <cctype>
#include <cmath>
#include <limits>
#include <mutex>

namespace octrace {
namespace {
#include "render/ColormapTables.inc"

struct Map {
    const char* name;
    const float (*table)[3];  // sRGB control points, evenly spaced
    std::size_t size;
};
// coolwarm: Moreland's diverging map (2009), five of its control points.
constexpr float kCoolwarm[5][3] = {{0.230f, 0.299f, 0.754f}, {0.552f, 0.690f, 0.996f}, {0.866f, 0.866f, 0.866f},
                                   {0.956f, 0.604f, 0.486f}, {0.706f, 0.016f, 0.150f}};
const std::vector<Map>& maps() {
    static const std::vector<Map> m = {
        {"viridis", k_viridis, 256}, {"thermal", k_thermal, 256}, {"haline", k_haline, 256},
        {"speed", k_speed, 256},     {"grey", k_gray, 256},       {"coolwarm", kCoolwarm, 5},
    };
    return m;
}
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}
bool contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }
}  // namespace

std::vector<std::string> colormapNames() {
    std::vector<std::string> n;
    for (const auto& m : maps()) n.push_back(m.name);
    return n;
}

namespace {
/// A map's colours in linear RGB at k equal steps of each interval between its control points,
/// k = ceil(4096 / intervals) (sRGB interpolated, then linearised), built once per map. Linear
/// interpolation between neighbouring steps differs from the exact conversion by less than 1e-6 (the conversion's
/// curvature over a step of at most a 4096th of the map), a thousandth of an 8-bit step.
struct LinearMap {
    std::vector<vec3> colours;
    std::size_t steps = 0;  // colours.size() - 1
};
const LinearMap& linearMap(std::size_t index) {
    static std::vector<std::once_flag> once(maps().size());
    static std::vector<LinearMap> linear(maps().size());
    const Map& m = maps()[index];
    std::call_once(once[index], [&] {
        const std::size_t k = (4096 + m.size - 2) / (m.size - 1);  // steps per interval
        LinearMap& l = linear[index];
        l.steps = (m.size - 1) * k;
        l.colours.resize(l.steps + 1);
        for (std::size_t j = 0; j <= l.steps; ++j) {
            const std::size_t i = std::min(j / k, m.size - 2);
            const float f = float(j - i * k) / float(k);
            const float* a = m.table[i];
            const float* b = m.table[i + 1];
            l.colours[j] = vec3(srgbToLinear(a[0] * (1.0f - f) + b[0] * f), srgbToLinear(a[1] * (1.0f - f) + b[1] * f),
                                srgbToLinear(a[2] * (1.0f - f) + b[2] * f));
        }
    });
    return linear[index];
}
}  // namespace

Colormap::Colormap(const std::string& nameIn) {
    const std::string name = nameIn == "gray" ? "grey" : nameIn;
    for (std::size_t index = 0; index < maps().size(); ++index) {
        if (name != maps()[index].name) continue;
        const LinearMap& l = linearMap(index);
        linear_ = l.colours.data();
        steps_ = l.steps;
        return;
    }
    throw UsageError("unknown colour map '" + nameIn + "' (choose one of: viridis, thermal, haline, speed, grey, coolwarm)");
}

vec3 Colormap::operator()(float t) const {
    t = std::clamp(std::isnan(t) ? 0.0f : t, 0.0f, 1.0f) * float(steps_);
    const std::size_t i = std::min(std::size_t(t), steps_ - 1);
    const float f = t - float(i);
    return linear_[i] * (1.0f - f) + linear_[i + 1] * f;
}

vec3 colormap(const std::string& name, float t) { return Colormap(name)(t); }

std::string defaultColormap(const std::string& standardName, const std::string& name) {
    const std::string sn = lower(standardName), n = lower(name);
    if (!sn.empty()) {
        if (contains(sn, "speed_of_sound")) return "speed";
        if (contains(sn, "temperature")) return "thermal";
        if (contains(sn, "salinity")) return "haline";
    }
    if (contains(n, "sound") || n == "svel" || n == "c") return "speed";
    if (contains(n, "temp") || n == "t" || n == "thetao" || n == "theta" || n == "pt" || n == "sst" || n == "tos") return "thermal";
    if (contains(n, "sal") || n == "s" || n == "so" || n == "psal") return "haline";
    return "viridis";
}

Albedo::Albedo(const Octree& tree, const RenderSettings& settings)
    : tree_(tree), colour_(settings.colour), masked_(settings.maskedColour), floor_(settings.floorColour),
      window_(settings.window), inverted_(settings.invertedGrey), colormap_(settings.colormap) {
    for (int i = 0; i < 256; ++i) linear_[i] = srgbToLinear(float(i) / 255.0f);
    const bool hasValues = !tree.voxelValues().empty();  // then one per voxel (Octree.h)
    if (hasValues && window_.valid()) {
        values_ = &tree.voxelValues();
        return;
    }
    if (hasValues && !colormap_.empty()) {
        values_ = &tree.voxelValues();
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (std::size_t i = 0; i < values_->size(); ++i) {
            const float v = (*values_)[i];
            if (std::isfinite(v) && tree.material(std::uint32_t(i)) == VoxelMaterial::Surface) {
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
        if (!(lo <= hi)) lo = hi = 0.0f;
        lo_ = std::isnan(settings.colourMin) ? lo : settings.colourMin;
        hi_ = std::isnan(settings.colourMax) ? hi : settings.colourMax;
    }
    if (colormap_.empty()) {
        if (tree.hasColours() && settings.voxelColours) colours_ = &tree.colours();
        return;
    }
    map_.emplace(colormap_);  // throws for an unknown name
    if (std::isfinite(settings.colourMin) && std::isfinite(settings.colourMax) && settings.colourMin != settings.colourMax) {
        hLo_ = float((double(settings.colourMin) - tree.cubeOrigin.z) / tree.voxelSize());
        hHi_ = float((double(settings.colourMax) - tree.cubeOrigin.z) / tree.voxelSize());
        return;
    }
    ivec3 lo, hi;
    if (tree.voxelMaterials().empty()) {
        tree.occupiedCells(lo, hi);
    } else {
        // With a sea floor (Layers.h) the map spans the isosurface's layers only: the floor is
        // drawn in its own colour, and its depth range would flatten the surface's colours.
        lo = ivec3(INT_MAX), hi = ivec3(INT_MIN);
        tree.forEachLeaf([&](const ivec3& cell, int shift, std::uint32_t v) {
            if (tree.material(v) != VoxelMaterial::Surface) return;
            lo = glm::min(lo, cell);
            hi = glm::max(hi, cell + ((1 << shift) - 1));
        });
        if (lo.z > hi.z) tree.occupiedCells(lo, hi);  // no isosurface voxel: the floor's range
    }
    hLo_ = float(lo.z);
    hHi_ = float(std::max(hi.z, lo.z) + 1);
}

vec3 Albedo::at(std::uint32_t voxel, float zCells) const {
    if (!tree_.voxelMaterials().empty() && tree_.material(voxel) == VoxelMaterial::Floor) return floor_;
    if (values_) {
        const float v = (*values_)[voxel];
        if (window_.valid()) return vec3(srgbToLinear(window_.grey(v, inverted_)));
        if (std::isnan(v)) return masked_;
        return (*map_)(hi_ != lo_ ? (v - lo_) / (hi_ - lo_) : 0.5f);
    }
    if (colours_) {
        const std::uint32_t c = (*colours_)[voxel];
        return vec3(linear_[c & 0xFFu], linear_[(c >> 8) & 0xFFu], linear_[(c >> 16) & 0xFFu]);
    }
    if (colormap_.empty()) return colour_;
    // Colour by height (world z) over the surface's extent or the range given.
    const float t = (zCells - hLo_) / (hHi_ - hLo_);
    return (*map_)(t);
}

Shader::Shader(const Octree& tree, const Camera& camera, const RenderSettings& settings)
    : tree_(tree), settings_(settings), albedo_(tree, settings), smooth_(tree, settings) {
    dvec3 right, up, back;
    camera.basis(right, up, back);
    dvec3 l = settings.lightCamera;
    if (!(glm::length(l) > 0.0)) l = dvec3(0.4, 0.6, 1.0);
    l = glm::normalize(l);
    light_ = vec3(glm::normalize(l.x * right + l.y * up + l.z * back));
    if (settings.baked && !tree.baked().empty()) baked_ = &tree.baked();
    shadows_ = settings.shadows.value_or(false) && !baked_ && tree.form == OctreeForm::Shell;
}

vec4 Shader::shade(std::uint32_t voxel, const ivec3& cell, int leafShift, std::uint64_t* shadowRays) const {
    return shadeNormal(voxel, cell, baked_ ? vec3(0.0f) : decodeNormal(tree_.voxels()[voxel].normal), shadowRays, leafShift);
}

void Albedo::prefetch(std::uint32_t voxel) const {
    if (!tree_.voxelMaterials().empty()) __builtin_prefetch(tree_.voxelMaterials().data() + voxel);
    if (colours_) __builtin_prefetch(colours_->data() + voxel);
    if (values_) __builtin_prefetch(values_->data() + voxel);
}

void Shader::prefetch(std::uint32_t voxel, bool normal) const {
    if (baked_) __builtin_prefetch(baked_->data() + voxel);
    else if (normal) __builtin_prefetch(tree_.voxels().data() + voxel);
    albedo_.prefetch(voxel);
}

vec4 Shader::shadeNormal(std::uint32_t voxel, const ivec3& cell, vec3 n, std::uint64_t* shadowRays, int leafShift, float zCells) const {
    if (std::isnan(zCells)) zCells = float(cell.z) + 0.5f;
    if (baked_) return vec4(albedo_.at(voxel, zCells) * (float((*baked_)[voxel]) * (1.0f / 255.0f)), 1.0f);
    float lambert = std::abs(glm::dot(n, light_));
    if (shadows_ && lambert > 0.0f) {
        std::uint64_t rays = 0;
        if (!detail::ShadowTracer(tree_).seesDirectionalLight(cell, leafShift, dvec3(n), dvec3(light_), rays)) lambert = 0.0f;
        if (shadowRays) *shadowRays += rays;
    }
    return shadeLambert(voxel, zCells, lambert);
}

vec4 Shader::shadeNode(std::uint32_t node) const {
    const NodeSummary& s = tree_.summaries()[node];
    return shadeLambert(s.firstVoxel, s.meanZ, std::abs(glm::dot(decodeNormal(s.normal), light_)));
}

/// ambient + diffuse x lambert (|n . l|, 0 in shadow), times the surface colour.
vec4 Shader::shadeLambert(std::uint32_t voxel, float zCells, float lambert) const {
    float intensity = settings_.ambient + settings_.diffuse * lambert;
    return vec4(albedo_.at(voxel, zCells) * intensity, 1.0f);
}

float Shader::distance(const Ray& ray, const ivec3& cell) const { return distanceToBox(ray, tree_.voxelBox(cell)); }

float Shader::distance(const Ray& ray, const TraversalHit& hit) const {
    if (hit.smooth) return float(hit.distance);
    if (!hit.nodeHit() && hit.leafShift == 0) return distance(ray, hit.cell);
    const int level = hit.nodeHit() ? hit.level : tree_.depth - hit.leafShift;
    const double side = tree_.cubeSide / double(1u << level);
    Box3 b;
    b.lo = tree_.cubeOrigin + dvec3(hit.nodeHit() ? hit.cell : hit.cell >> hit.leafShift) * side;
    b.hi = b.lo + dvec3(side);
    return distanceToBox(ray, b);
}

float Shader::distanceToBox(const Ray& ray, const Box3& b) const {
    double tin = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0) continue;
        // The plane the ray enters by along this axis: the nearer one's distance is the smaller
        // of the two (rounding is monotone), so the other division is not needed.
        const double plane = ray.direction[a] > 0.0 ? b.lo[a] : b.hi[a];
        tin = std::max(tin, (plane - ray.origin[a]) / ray.direction[a]);
    }
    return float(tin);
}

}  // namespace octrace
