#include "octrace/lighting/Bake.h"

#include "lighting/ShadowTracer.h"

#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace octrace {
namespace {

/// Unit directions on a Fibonacci spiral over the hemisphere around +z.
std::vector<dvec3> hemisphere(int n) {
    std::vector<dvec3> d;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (i + 0.5) / n;  // in (0, 1)
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * i;
        d.push_back(dvec3(r * std::cos(phi), r * std::sin(phi), z));
    }
    return d;
}

/// An orthonormal frame whose third axis is n.
dmat3 frameAround(const dvec3& n) {
    const dvec3 a = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
    return dmat3(t, b, n);
}

}  // namespace

BakeLight parseBakeLight(const std::string& spec) {
    const auto colon = spec.find(':');
    const std::string kind = colon == std::string::npos ? "" : spec.substr(0, colon);
    if (kind != "dir" && kind != "point")
        throw UsageError("light '" + spec + "': expected dir:X,Y,Z[,I] or point:X,Y,Z[,I]");
    std::vector<double> v;
    std::stringstream in(spec.substr(colon + 1));
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
            throw UsageError("light '" + spec + "': '" + item + "' is not a finite number");
        v.push_back(x);
    }
    if (v.size() != 3 && v.size() != 4) throw UsageError("light '" + spec + "': expected 3 or 4 numbers");
    BakeLight l;
    l.point = kind == "point";
    l.v = dvec3(v[0], v[1], v[2]);
    if (!l.point && !(glm::length(l.v) > 0.0)) throw UsageError("light '" + spec + "': the direction is zero");
    if (!l.point) l.v = glm::normalize(l.v);
    if (v.size() == 4) {
        if (!(v[3] >= 0.0)) throw UsageError("light '" + spec + "': the intensity must not be negative");
        l.intensity = float(v[3]);
    }
    return l;
}

void bakeLighting(Octree& tree, const BakeOptions& o, BakeReport* report) {
    if (tree.form != OctreeForm::Shell) throw UsageError("lighting is baked on the shell form (extract the shell first)");
    Timer timer;
    const double h = tree.voxelSize();
    const double aoDistance = o.aoDistance > 0.0 ? o.aoDistance : tree.cubeSide / 8.0;
    const std::vector<dvec3> dirs = hemisphere(std::max(o.aoRays, 0));
    // Cells by voxel index, so that voxels can be baked in parallel slices.
    std::vector<ivec3> cells(tree.voxels().size());
    tree.forEachVoxel([&](const ivec3& c, std::uint32_t v) { cells[v] = c; });
    std::vector<std::uint8_t> baked(tree.voxels().size(), 0);
    const detail::ShadowTracer tracer(tree);
    std::atomic<std::uint64_t> rays{0};
    const std::size_t n = cells.size(), chunk = 1024;
    parallelFor((n + chunk - 1) / chunk, o.threads, [&](std::size_t k) {
        std::uint64_t local = 0;
        for (std::size_t v = k * chunk; v < std::min(n, (k + 1) * chunk); ++v) {
            const ivec3 cell = cells[v];
            const dvec3 centre = tree.cubeOrigin + (dvec3(cell) + 0.5) * h;
            const dvec3 nrm = dvec3(decodeNormal(tree.voxels()[v].normal));
            double light = 0.0;
            for (const BakeLight& l : o.lights) {
                dvec3 dir = l.point ? l.v - centre : l.v;
                const double dist = l.point ? glm::length(dir) : INFINITY;
                if (!(glm::length(dir) > 0.0)) continue;
                dir = glm::normalize(dir);
                const double cosine = glm::dot(nrm, dir);
                if (cosine == 0.0) continue;
                if (o.shadows) {
                    const dvec3 side = cosine > 0.0 ? nrm : -nrm;
                    if (tracer.firstHit(centre + side * h, dir, cell, 0, local) < dist) continue;
                }
                light += double(l.intensity) * std::abs(cosine);
            }
            double ao = 1.0;
            if (!dirs.empty()) {
                ao = 0.0;
                for (double s : {1.0, -1.0}) {
                    const dmat3 f = frameAround(s * nrm);
                    int open = 0;
                    for (const dvec3& d : dirs)
                        open += tracer.firstHit(centre + s * nrm * h, f * d, cell, 0, local) >= aoDistance;
                    ao = std::max(ao, double(open) / double(dirs.size()));
                }
            }
            const double total = std::clamp(double(o.ambient) * ao + double(o.diffuse) * light, 0.0, 1.0);
            baked[v] = std::uint8_t(std::lround(total * 255.0));
        }
        rays += local;
    });
    tree.setBaked(std::move(baked));
    if (report) {
        report->bakeMs = timer.ms();
        report->rays = rays.load();
    }
}

}  // namespace octrace
