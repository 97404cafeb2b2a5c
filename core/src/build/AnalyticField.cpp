#include "octrace/build/AnalyticField.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
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

std::vector<std::string> analyticFieldNames() { return {"sphere", "torus", "gyroid", "noise", "spheres"}; }

std::string analyticFieldList() {
    std::string s;
    for (const std::string& n : analyticFieldNames()) s += (s.empty() ? "" : ", ") + n;
    return s;
}

namespace {

struct Ball {
    dvec3 centre;
    double radius;
};

/// A number in [0, 1) from the generator's raw 32-bit output (which the standard fixes for
/// mt19937), so that a seed gives the same spheres with every standard library.
double unit(std::mt19937& rng) { return double(rng() >> 8) * (1.0 / 16777216.0); }

/// 60 disjoint balls inside [-1,1]^3 with radii from 0.04 to 0.3, log-uniform, placed largest
/// first at random positions at least 0.02 apart (a position that touches an earlier ball is drawn again).
std::vector<Ball> disjointBalls(std::uint32_t seed) {
    const int count = 60;
    const double rmin = 0.04, rmax = 0.3, gap = 0.02;
    std::mt19937 rng(seed);
    std::vector<double> radii(count);
    for (double& r : radii) r = rmin * std::pow(rmax / rmin, unit(rng));
    std::sort(radii.begin(), radii.end(), std::greater<>());
    std::vector<Ball> balls;
    for (double r : radii) {
        for (int attempt = 0; attempt < 10000; ++attempt) {
            const dvec3 c(-1.0 + r + (2.0 - 2.0 * r) * unit(rng), -1.0 + r + (2.0 - 2.0 * r) * unit(rng),
                          -1.0 + r + (2.0 - 2.0 * r) * unit(rng));
            const bool apart = std::all_of(balls.begin(), balls.end(), [&](const Ball& b) {
                return glm::length(b.centre - c) >= b.radius + r + gap;
            });
            if (apart) {
                balls.push_back({c, r});
                break;
            }
        }
    }
    return balls;
}

}  // namespace

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
    if (name == "spheres") {
        const std::vector<Ball> balls = disjointBalls(seed);
        ScalarField s = sampleFunction(name, dims, origin, spacing, [&](const dvec3& p) {
            // max over the balls of radius - distance: iso 0 is their union. A ball can beat
            // the best so far only if its distance is below radius - best: compare squares first.
            double best = -std::numeric_limits<double>::infinity();
            for (const Ball& b : balls) {
                const dvec3 d = p - b.centre;
                const double d2 = glm::dot(d, d), reach = b.radius - best;
                if (reach > 0.0 && d2 < reach * reach) best = std::max(best, b.radius - std::sqrt(d2));
            }
            return float(best);
        });
        s.source = "analytic:spheres(seed " + std::to_string(seed) + ")";
        return s;
    }
    throw UsageError("unknown analytic field '" + name + "' (choose one of: " + analyticFieldList() + ")");
}

}  // namespace octrace
