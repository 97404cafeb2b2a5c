#include "volume/VolumeGeometry.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <numbers>

namespace octrace::io::detail {

void setAxes(const dmat3& axes, ScalarField& f, const std::string& what) {
    for (int a = 0; a < 3; ++a) {
        const double len = glm::length(axes[a]);
        if (!(len > 0.0) || !std::isfinite(len))
            throw FileError(what + ": axis " + std::to_string(a) + " has a zero or non-finite step");
        f.spacing[a] = len;
        f.direction[a] = axes[a] / len;
    }
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3;
        const double c = glm::dot(f.direction[a], f.direction[b]);
        if (std::abs(c) > 1e-4) {
            const double deg = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
            throw FileError(what + " of axes " + std::to_string(std::min(a, b)) + " and " + std::to_string(std::max(a, b)) +
                            " are not perpendicular (" + num(deg) + " degrees): sheared grids are not supported");
        }
    }
}

}  // namespace octrace::io::detail

namespace octrace::io::detail {

void markNonFinite(ScalarField& f) {
    std::size_t bad = 0;
    for (float v : f.values) bad += std::isfinite(v) ? 0 : 1;
    if (bad == 0) return;
    f.valid.resize(f.values.size());
    for (std::size_t i = 0; i < f.values.size(); ++i) f.valid[i] = std::isfinite(f.values[i]) ? 1 : 0;
    f.notes.push_back(std::to_string(bad) + " NaN/inf samples marked invalid");
}

std::string exactNumber(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

void uniformGrid(const ScalarField& field, const std::string& path, const std::string& format, dvec3& origin, dvec3& spacing) {
    if (field.values.size() != field.sampleCount() || field.sampleCount() == 0)
        throw OutputError(path + ": field '" + field.name + "' has " + std::to_string(field.values.size()) + " samples for a " +
                          std::to_string(field.dims.x) + "x" + std::to_string(field.dims.y) + "x" + std::to_string(field.dims.z) +
                          " grid");
    origin = field.origin;
    for (int a = 0; a < 3; ++a) {
        spacing[a] = field.spacing[a];
        if (!field.isRectilinear(a)) continue;
        const auto& c = field.coords[std::size_t(a)];
        const double step = (c.back() - c.front()) / double(c.size() - 1);
        for (std::size_t n = 0; n < c.size(); ++n)
            if (std::abs(c[n] - (c.front() + double(n) * step)) > 1e-9 * std::max(1.0, std::abs(step) * double(c.size())))
                throw OutputError(path + ": " + format + " cannot store the uneven axis " + std::to_string(a) + " of '" +
                                  field.name + "' (rectilinear coordinates)");
        origin += field.direction[a] * c.front();
        spacing[a] = step;
    }
}

void appendFloatsLE(const ScalarField& field, std::vector<std::uint8_t>& out) {
    const std::size_t at = out.size();
    out.resize(at + field.values.size() * sizeof(float));
    std::uint8_t* samples = out.data() + at;
    for (std::size_t i = 0; i < field.values.size(); ++i) {
        const float v = field.isValid(i) ? field.values[i] : std::nanf("");
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
        std::memcpy(samples + 4 * i, &u, 4);
    }
}

}  // namespace octrace::io::detail
