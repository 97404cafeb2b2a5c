// The angular error of octrace's quantized normals (encodeNormal / decodeNormal: octahedral,
// 16 + 16 bits): over uniformly random unit vectors (seeded), and over the exact normals of a
// sphere's boundary voxels. Prints one JSON object; bench/lighting.py keeps it and reports it.
#include "octrace/octree/Octree.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace octrace;

namespace {
double angleDeg(const dvec3& a, const dvec3& b) { return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b))); }

struct Stats {
    double max = 0.0, mean = 0.0, p99 = 0.0;
    std::size_t count = 0;
};

Stats measure(const std::vector<dvec3>& normals) {
    std::vector<double> e;
    e.reserve(normals.size());
    for (const dvec3& n : normals) e.push_back(angleDeg(n, dvec3(decodeNormal(encodeNormal(vec3(n))))));
    Stats s;
    s.count = e.size();
    for (double x : e) s.mean += x / double(e.size());
    std::sort(e.begin(), e.end());
    s.max = e.back();
    s.p99 = e[std::size_t(0.99 * double(e.size() - 1))];
    return s;
}
}  // namespace

int main() {
    std::mt19937_64 rng(20261124);
    std::normal_distribution<double> g;
    std::vector<dvec3> random(1000000);
    for (dvec3& n : random) {
        do n = dvec3(g(rng), g(rng), g(rng));
        while (glm::length(n) < 1e-9);
        n = glm::normalize(n);
    }
    // Boundary voxels of the sphere of radius 100 voxels at the origin: the exact normal at each
    // voxel's centre.
    std::vector<dvec3> sphere;
    for (int x = -101; x <= 101; ++x)
        for (int y = -101; y <= 101; ++y)
            for (int z = -101; z <= 101; ++z) {
                const dvec3 c(x + 0.5, y + 0.5, z + 0.5);
                if (std::abs(glm::length(c) - 100.0) < 0.5) sphere.push_back(glm::normalize(c));
            }
    const Stats r = measure(random), s = measure(sphere);
    std::printf("{\"random_count\": %zu, \"random_max_deg\": %.6g, \"random_mean_deg\": %.6g, \"random_p99_deg\": %.6g, "
                "\"sphere_count\": %zu, \"sphere_max_deg\": %.6g, \"sphere_mean_deg\": %.6g, \"sphere_p99_deg\": %.6g}\n",
                r.count, r.max, r.mean, r.p99, s.count, s.max, s.mean, s.p99);
    return 0;
}
