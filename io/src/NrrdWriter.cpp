#include "octrace/io/NrrdWriter.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <sstream>
#include <vector>

namespace octrace::io {
namespace {

std::string exact(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string vec(const dvec3& v) {
    std::string s = "(";
    s.append(exact(v.x)).append(",").append(exact(v.y)).append(",").append(exact(v.z)).append(")");
    return s;
}

// Header values must stay on one line.
std::string oneLine(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

// Folds an evenly spaced rectilinear axis into origin + spacing; refuses an uneven one.
void uniformAxis(const ScalarField& f, int a, const std::string& path, dvec3& origin, double& spacing) {
    spacing = f.spacing[a];
    if (!f.isRectilinear(a)) return;
    const auto& c = f.coords[std::size_t(a)];
    double step = (c.back() - c.front()) / double(c.size() - 1);
    for (std::size_t n = 0; n < c.size(); ++n)
        if (std::abs(c[n] - (c.front() + double(n) * step)) > 1e-9 * std::max(1.0, std::abs(step) * double(c.size())))
            throw OutputError(path + ": NRRD cannot store the uneven axis " + std::to_string(a) + " of '" + f.name +
                              "' (rectilinear coordinates)");
    origin += f.direction[a] * c.front();
    spacing = step;
}

}  // namespace

void NrrdWriter::write(const ScalarField& field, const std::string& path) {
    if (field.values.size() != field.sampleCount() || field.sampleCount() == 0)
        throw OutputError(path + ": field '" + field.name + "' has " + std::to_string(field.values.size()) +
                          " samples for a " + std::to_string(field.dims.x) + "x" + std::to_string(field.dims.y) + "x" +
                          std::to_string(field.dims.z) + " grid");
    dvec3 origin = field.origin;
    dvec3 spacing;
    for (int a = 0; a < 3; ++a) uniformAxis(field, a, path, origin, spacing[a]);

    std::ostringstream h;
    h << "NRRD0004\n# written by octrace\n";
    h << "type: float\ndimension: 3\nspace dimension: 3\n";
    h << "sizes: " << field.dims.x << " " << field.dims.y << " " << field.dims.z << "\n";
    h << "space directions:";
    for (int a = 0; a < 3; ++a) h << " " << vec(field.direction[a] * spacing[a]);
    h << "\nkinds: domain domain domain\nendian: little\nencoding: raw\n";
    h << "space origin: " << vec(origin) << "\n";
    if (!field.name.empty()) h << "content: " << oneLine(field.name) << "\n";
    if (!field.units.empty()) h << "units:=" << oneLine(field.units) << "\n";
    h << "\n";

    // One buffer of header and samples, written to a temporary name and renamed
    // (writeFileAtomically: also removed if the program is interrupted meanwhile).
    const std::string text = h.str();
    std::vector<std::uint8_t> bytes(text.size() + field.values.size() * sizeof(float));
    std::memcpy(bytes.data(), text.data(), text.size());
    std::uint8_t* samples = bytes.data() + text.size();
    for (std::size_t i = 0; i < field.values.size(); ++i) {
        float v = field.isValid(i) ? field.values[i] : std::nanf("");
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
        std::memcpy(samples + 4 * i, &u, 4);
    }
    writeFileAtomically(path, std::span<const std::uint8_t>(bytes));
}

}  // namespace octrace::io
