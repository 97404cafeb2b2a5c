#include "octrace/build/AnalyticField.h"

#include "octrace/util/Error.h"

#include <cmath>
#include <random>

namespace octrace {

ScalarField sampleFunction(const std::string& name, ivec3 dims, dvec3 origin, dvec3 spacing,
                           const std::function<float(const dvec3&)>& f) {
    ScalarField s;
    s.name = name;
    s.source = "analytic:" + name;
    s.dims = dims;
    s.origin = origin;
    s.spacing = spacing;
    s.values.resize(s.sampleCount());
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) s.values[s.index(i, j, k)] = f(s.worldFromGrid(i, j, k));
    return s;
}

std::vector<std::string> analyticFieldNames() { return {"sphere", "torus", "gyroid", "noise"}; }

ScalarField makeAnalyticField(const std::string& name, int n, std::uint32_t seed) {
    if (n < 2) throw UsageError("analytic field needs at least 2 samples per axis");
    const ivec3 dims(n);
    const dvec3 origin(-1.0), spacing(2.0 / (n - 1));
    if (name == "sphere")
        return sampleFunction(name, dims, origin, spacing, [](const dvec3& p) { return float(0.7 - glm::length(p)); });
    if (name == "torus")
        return sampleFunction(name, dims, origin, spacing, [](const dvec3& p) {
            double q = std::sqrt(p.x * p.x + p.y * p.y) - 0.6;
            return float(0.25 - std::sqrt(q * q + p.z * p.z));
        });
    if (name == "gyroid")
        return sampleFunction(name, dims, origin, spacing, [](const dvec3& p) {
            dvec3 q = p * (2.0 * M_PI);
            return float(std::sin(q.x) * std::cos(q.y) + std::sin(q.y) * std::cos(q.z) + std::sin(q.z) * std::cos(q.x));
        });
    if (name == "noise") {
        // Value noise on a coarse lattice, trilinearly upsampled: blobs and thin sheets.
        const int g = 9;
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        std::vector<float> lattice(std::size_t(g) * g * g);
        for (auto& v : lattice) v = u(rng);
        auto at = [&](int i, int j, int k) { return lattice[std::size_t(i) + std::size_t(g) * (std::size_t(j) + std::size_t(g) * k)]; };
        ScalarField s = sampleFunction(name, dims, origin, spacing, [&](const dvec3& p) {
            dvec3 q = (p + 1.0) * 0.5 * double(g - 1);
            ivec3 i0 = glm::clamp(ivec3(glm::floor(q)), ivec3(0), ivec3(g - 2));
            dvec3 t = q - dvec3(i0);
            double v = 0.0;
            for (int c = 0; c < 8; ++c) {
                int dx = (c >> 2) & 1, dy = (c >> 1) & 1, dz = c & 1;
                double w = (dx ? t.x : 1 - t.x) * (dy ? t.y : 1 - t.y) * (dz ? t.z : 1 - t.z);
                v += w * at(i0.x + dx, i0.y + dy, i0.z + dz);
            }
            return float(v);
        });
        s.source = "analytic:noise(seed " + std::to_string(seed) + ")";
        return s;
    }
    throw UsageError("unknown analytic field '" + name + "' (choose one of: sphere, torus, gyroid, noise)");
}

}  // namespace octrace
