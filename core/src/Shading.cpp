#include "octrace/render/Shading.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace {
namespace {
struct Map {
    const char* name;
    std::vector<vec3> stops;  // sRGB control points, evenly spaced
};
const std::vector<Map>& maps() {
    static const std::vector<Map> m = {
        {"viridis", {{0.267f, 0.005f, 0.329f}, {0.283f, 0.141f, 0.458f}, {0.254f, 0.265f, 0.530f}, {0.207f, 0.372f, 0.553f},
                     {0.164f, 0.471f, 0.558f}, {0.128f, 0.567f, 0.551f}, {0.135f, 0.659f, 0.518f}, {0.267f, 0.749f, 0.441f},
                     {0.478f, 0.821f, 0.318f}, {0.741f, 0.873f, 0.150f}, {0.993f, 0.906f, 0.144f}}},
        {"coolwarm", {{0.230f, 0.299f, 0.754f}, {0.552f, 0.690f, 0.996f}, {0.866f, 0.866f, 0.866f}, {0.956f, 0.604f, 0.486f},
                      {0.706f, 0.016f, 0.150f}}},
        {"grey", {{0.1f, 0.1f, 0.1f}, {0.95f, 0.95f, 0.95f}}},
    };
    return m;
}
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
}  // namespace

std::vector<std::string> colormapNames() {
    std::vector<std::string> n;
    for (const auto& m : maps()) n.push_back(m.name);
    return n;
}

vec3 colormap(const std::string& name, float t) {
    for (const auto& m : maps()) {
        if (name != m.name) continue;
        t = std::clamp(t, 0.0f, 1.0f) * float(m.stops.size() - 1);
        std::size_t i = std::min(std::size_t(t), m.stops.size() - 2);
        float f = t - float(i);
        vec3 c = m.stops[i] * (1.0f - f) + m.stops[i + 1] * f;
        return vec3(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z));
    }
    throw UsageError("unknown colour map '" + name + "'");
}

Albedo::Albedo(const Octree& tree, const RenderSettings& settings)
    : colour_(settings.colour), window_(settings.window), inverted_(settings.invertedGrey), colormap_(settings.colormap) {
    for (int i = 0; i < 256; ++i) linear_[i] = srgbToLinear(float(i) / 255.0f);
    if (window_.valid() && !tree.voxelValues.empty() && tree.voxelValues.size() == tree.voxels.size()) {
        values_ = &tree.voxelValues;
        return;
    }
    if (colormap_.empty()) {
        if (tree.hasColours() && settings.voxelColours) colours_ = &tree.colours;
        return;
    }
    colormap(colormap_, 0.0f);  // validate the name once
    ivec3 lo, hi;
    tree.occupiedCells(lo, hi);
    zLo_ = lo.z;
    zHi_ = std::max(hi.z, lo.z);
}

vec3 Albedo::at(std::uint32_t voxel, float zCells) const {
    if (values_) return vec3(srgbToLinear(window_.grey((*values_)[voxel], inverted_)));
    if (colours_) {
        const std::uint32_t c = (*colours_)[voxel];
        return vec3(linear_[c & 0xFFu], linear_[(c >> 8) & 0xFFu], linear_[(c >> 16) & 0xFFu]);
    }
    if (colormap_.empty()) return colour_;
    // Colour by height (world z) over the surface's extent until a second field can be mapped.
    const float t = (zCells - float(zLo_)) / float(zHi_ - zLo_ + 1);
    return colormap(colormap_, t);
}

Shader::Shader(const Octree& tree, const Camera& camera, const RenderSettings& settings)
    : tree_(tree), settings_(settings), albedo_(tree, settings) {
    dvec3 right, up, back;
    camera.basis(right, up, back);
    dvec3 l = settings.lightCamera;
    if (!(glm::length(l) > 0.0)) l = dvec3(0.4, 0.6, 1.0);
    l = glm::normalize(l);
    light_ = vec3(glm::normalize(l.x * right + l.y * up + l.z * back));
}

vec4 Shader::shade(std::uint32_t voxel, const ivec3& cell) const {
    return shadeNormal(decodeNormal(tree_.voxels[voxel].normal), voxel, float(cell.z) + 0.5f);
}

vec4 Shader::shadeNode(std::uint32_t node) const {
    const NodeSummary& s = tree_.summaries[node];
    return shadeNormal(decodeNormal(s.normal), s.firstVoxel, s.meanZ);
}

vec4 Shader::shadeNormal(vec3 n, std::uint32_t voxel, float zCells) const {
    float lambert = std::abs(glm::dot(n, light_));
    float intensity = settings_.ambient + settings_.diffuse * lambert;
    return vec4(albedo_.at(voxel, zCells) * intensity, 1.0f);
}

float Shader::distance(const Ray& ray, const ivec3& cell) const { return distanceToBox(ray, tree_.voxelBox(cell)); }

float Shader::distance(const Ray& ray, const TraversalHit& hit) const {
    if (!hit.nodeHit()) return distance(ray, hit.cell);
    const double side = tree_.cubeSide / double(1u << hit.level);
    Box3 b;
    b.lo = tree_.cubeOrigin + dvec3(hit.cell) * side;
    b.hi = b.lo + dvec3(side);
    return distanceToBox(ray, b);
}

float Shader::distanceToBox(const Ray& ray, const Box3& b) const {
    double tin = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0) continue;
        double t0 = (b.lo[a] - ray.origin[a]) / ray.direction[a];
        double t1 = (b.hi[a] - ray.origin[a]) / ray.direction[a];
        tin = std::max(tin, std::min(t0, t1));
    }
    return float(tin);
}

}  // namespace octrace
