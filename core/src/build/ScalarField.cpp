#include "octrace/build/ScalarField.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace octrace {

double ValueWindow::greyValue(double v, bool inverted) const {
    const double g = std::clamp((v - (centre - 0.5 * width)) / width, 0.0, 1.0);
    return inverted ? 1.0 - g : g;
}

ScalarField ScalarField::copy() const {
    ScalarField f;
    f.name = name, f.units = units, f.standardName = standardName, f.source = source;
    f.dims = dims, f.origin = origin, f.spacing = spacing, f.direction = direction, f.coords = coords;
    f.values = values, f.valid = valid;
    f.window = window, f.invertedGrey = invertedGrey, f.patientLps = patientLps, f.planar = planar, f.geographic = geographic;
    f.timeLabel = timeLabel;
    f.notes = notes;
    return f;
}

dvec3 ScalarField::worldFromGrid(int i, int j, int k) const {
    dvec3 local(axisPosition(0, i), axisPosition(1, j), axisPosition(2, k));
    return origin + direction * local;
}

Box3 ScalarField::worldBounds() const {
    Box3 b;
    b.lo = dvec3(std::numeric_limits<double>::infinity());
    b.hi = -b.lo;
    for (int c = 0; c < 8; ++c) {
        dvec3 p = worldFromGrid((c & 4) ? dims.x - 1 : 0, (c & 2) ? dims.y - 1 : 0, (c & 1) ? dims.z - 1 : 0);
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
    }
    return b;
}

std::size_t ScalarField::validCount() const {
    std::size_t n = 0;
    for (std::size_t i = 0; i < values.size(); ++i)
        if (isValid(i) && std::isfinite(values[i])) ++n;
    return n;
}

std::pair<float, float> ScalarField::validRange() const {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!isValid(i) || !std::isfinite(values[i])) continue;
        lo = std::min(lo, values[i]);
        hi = std::max(hi, values[i]);
    }
    if (lo > hi) throw EmptyResultError(source + ": variable '" + name + "' has no valid sample (all masked)");
    return {lo, hi};
}

void ScalarField::validate() const {
    validateGeometry();
    if (values.size() != sampleCount()) {
        std::ostringstream s;
        s << source << ": expected " << sampleCount() << " samples, got " << values.size();
        throw FileError(s.str());
    }
    if (!valid.empty() && valid.size() != values.size())
        throw FileError(source + ": validity mask size does not match the samples");
}

void ScalarField::validateGeometry() const {
    auto fail = [&](const std::string& what) { throw FileError(source + ": " + what); };
    if (dims.x < 2 || dims.y < 2 || (planar ? dims.z != 1 : dims.z < 2)) {
        std::ostringstream s;
        s << "grid of '" << name << "' must have at least 2 samples per axis" << (planar ? " across and 1 along z (a map)" : "")
          << ", has " << dims.x << "x" << dims.y << "x" << dims.z;
        fail(s.str());
    }
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(origin[a])) fail("origin is not finite");
        if (coords[a].empty()) {
            if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a])) {
                std::ostringstream s;
                s << "spacing along axis " << a << " must be positive and finite, is " << spacing[a];
                fail(s.str());
            }
        } else {
            if (coords[a].size() != std::size_t(dims[a])) fail("rectilinear axis length does not match the grid size");
            for (std::size_t n = 0; n < coords[a].size(); ++n) {
                if (!std::isfinite(coords[a][n])) fail("rectilinear coordinate is not finite");
                if (n > 0 && !(coords[a][n] > coords[a][n - 1])) fail("rectilinear coordinates must be strictly increasing");
            }
        }
    }
    // Geometry the octree, the camera and the rays can work with in double precision: world
    // coordinates within +-1e30, and an extent neither denormal nor lost in its position
    // (spacings of 1e-310 or an origin of 1e20 under a grid of 1 made the camera fail).
    const Box3 b = worldBounds();
    double side = 0.0, far = 0.0;
    for (int a = 0; a < 3; ++a) {
        side = std::max(side, b.hi[a] - b.lo[a]);
        far = std::max(far, std::max(std::abs(b.lo[a]), std::abs(b.hi[a])));
    }
    if (!std::isfinite(side) || !std::isfinite(far) || far > kMaxWorldCoordinate) {
        std::ostringstream s;
        s << "world bounds " << b.lo.x << ".." << b.hi.x << " x " << b.lo.y << ".." << b.hi.y << " x " << b.lo.z << ".."
          << b.hi.z << " go beyond the supported +-" << kMaxWorldCoordinate << " (origin or spacing absurd)";
        fail(s.str());
    }
    if (side < kMinWorldExtent || side < far * 1e-9) {
        std::ostringstream s;
        s << "world extent " << side << " is too small to place the grid (at least " << kMinWorldExtent
          << " and a billionth of its largest coordinate, " << far << ", are needed)";
        fail(s.str());
    }
    dmat3 g = glm::transpose(direction) * direction;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(direction[c][r]) || std::abs(g[c][r] - (r == c ? 1.0 : 0.0)) > 1e-4)
                fail("direction matrix is not orthonormal");
}

}  // namespace octrace
