#include "octrace/build/AutoDepth.h"

#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace octrace {
namespace {

std::string lengthText(double v, const std::string& unit) {
    std::ostringstream s;
    s.precision(4);
    s << v;
    if (!unit.empty()) s << " " << unit;
    return s.str();
}

/// The world unit of a field's coordinates, for messages.
std::string worldUnit(const ScalarField& f) { return f.geographic.valid ? "km" : f.patientLps ? "mm" : ""; }

}  // namespace

double medianSpacing(const ScalarField& f, int axis) {
    const int n = f.dims[axis];
    if (n < 2) throw Error(f.source + ": axis " + std::to_string(axis) + " has " + std::to_string(n) + " sample(s), no spacing");
    if (!f.isRectilinear(axis)) return f.spacing[axis];
    std::vector<double> steps(std::size_t(n - 1));
    for (int i = 0; i + 1 < n; ++i) steps[std::size_t(i)] = f.axisPosition(axis, i + 1) - f.axisPosition(axis, i);
    const auto mid = steps.begin() + std::ptrdiff_t(steps.size() / 2);
    std::nth_element(steps.begin(), mid, steps.end());
    if (steps.size() % 2 == 1) return *mid;
    // Even count: the mean of the two middle steps.
    const double upper = *mid;
    const double lower = *std::max_element(steps.begin(), mid);
    return 0.5 * (lower + upper);
}

double cubeSideOf(const ScalarField& f) {
    const dvec3 e = f.worldBounds().size();
    return std::max({e.x, e.y, e.z});
}

int shallowestDepthFor(double cubeSide, double voxel) {
    for (int d = 1; d <= Octree::kMaxDepth; ++d)
        if (cubeSide / double(1 << d) <= voxel * (1.0 + 1e-9)) return d;
    return Octree::kMaxDepth;
}

DepthChoice depthForField(const ScalarField& f) {
    const double side = cubeSideOf(f);
    const char* names = "xyz";
    int finest = -1;
    double spacing = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (f.dims[a] < 2) continue;  // a planar field's one level
        const double s = medianSpacing(f, a);
        if (finest < 0 || s < spacing) {
            finest = a;
            spacing = s;
        }
    }
    if (finest < 0) throw Error(f.source + ": no axis with two samples, no depth to choose");
    DepthChoice c;
    c.depth = shallowestDepthFor(side, spacing);
    const std::string unit = worldUnit(f);
    c.reason = "voxel " + lengthText(side / double(1 << c.depth), unit) + " <= median sample spacing " + lengthText(spacing, unit) +
               " along " + names[finest] + " (cube " + lengthText(side, unit) + ")";
    return c;
}

DepthChoice depthForPixel(double cubeSide, double pixel, const std::string& unit) {
    if (!(cubeSide > 0.0) || !(pixel > 0.0) || !std::isfinite(cubeSide / pixel))
        throw Error("depth for a pixel: cube side " + lengthText(cubeSide, unit) + " and pixel " + lengthText(pixel, unit) +
                    " must be positive");
    DepthChoice c;
    c.depth = std::clamp(int(std::lround(std::log2(cubeSide / pixel))), 1, Octree::kMaxDepth);
    c.reason = "voxel " + lengthText(cubeSide / double(1 << c.depth), unit) + " ~ one pixel of the view, " + lengthText(pixel, unit) +
               " (cube " + lengthText(cubeSide, unit) + ")";
    return c;
}

}  // namespace octrace
