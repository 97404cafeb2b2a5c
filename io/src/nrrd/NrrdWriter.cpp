#include "octrace/io/NrrdWriter.h"

#include "volume/VolumeGeometry.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"

#include <span>
#include <sstream>
#include <vector>

namespace octrace::io {
namespace {

std::string vector3(const dvec3& v) {
    return std::string("(") + detail::exactNumber(v.x) + "," + detail::exactNumber(v.y) + "," + detail::exactNumber(v.z) + ")";
}

// Header values must stay on one line.
std::string oneLine(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

}  // namespace

void NrrdWriter::write(const ScalarField& field, const std::string& path) {
    dvec3 origin, spacing;
    detail::uniformGrid(field, path, "NRRD", origin, spacing);

    std::ostringstream h;
    h << "NRRD0004\n# written by octrace\n";
    h << "type: float\ndimension: 3\nspace dimension: 3\n";
    h << "sizes: " << field.dims.x << " " << field.dims.y << " " << field.dims.z << "\n";
    h << "space directions:";
    for (int a = 0; a < 3; ++a) h << " " << vector3(field.direction[a] * spacing[a]);
    h << "\nkinds: domain domain domain\nendian: little\nencoding: raw\n";
    h << "space origin: " << vector3(origin) << "\n";
    if (!field.name.empty()) h << "content: " << oneLine(field.name) << "\n";
    if (!field.units.empty()) h << "units:=" << oneLine(field.units) << "\n";
    h << "\n";

    // One buffer of header and samples, written to a temporary name and renamed
    // (writeFileAtomically: also removed if the program is interrupted meanwhile).
    const std::string text = h.str();
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    detail::appendFloatsLE(field, bytes);
    writeFileAtomically(path, std::span<const std::uint8_t>(bytes));
}

}  // namespace octrace::io
