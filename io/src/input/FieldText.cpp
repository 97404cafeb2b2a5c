#include "input/FieldText.h"

#include "input/InputFile.h"

#include <sstream>

namespace octrace::io::detail {

std::string describeVolume(const ScalarField& f) {
    std::ostringstream s;
    auto [lo, hi] = f.validRange();
    s << "variables:\n  " << f.name << " (" << f.dims.x << " x " << f.dims.y << " x " << f.dims.z << ")"
      << (f.units.empty() ? std::string() : ", units '" + f.units + "'") << ": valid range " << num(lo) << " .. " << num(hi)
      << " (" << f.validCount() << " of " << f.sampleCount() << " samples valid)\n";
    s << "dims: " << f.dims.x << " x " << f.dims.y << " x " << f.dims.z << "\n";
    s << "spacing:";
    for (int a = 0; a < 3; ++a) {
        s << (a ? " x " : " ");
        if (f.dims[a] == 1) s << "none (one sample)";  // a map's or a single image's: no neighbour, no distance
        else if (f.isRectilinear(a)) s << "rectilinear " << num(f.coords[a].front()) << " .. " << num(f.coords[a].back());
        else s << num(f.spacing[a]);
    }
    s << "\norigin: (" << num(f.origin.x) << ", " << num(f.origin.y) << ", " << num(f.origin.z) << ")\n";
    if (f.direction != dmat3(1.0)) {
        s << "direction (columns):";
        for (int a = 0; a < 3; ++a) {
            const dvec3& d = f.direction[a];
            s << " (" << num(d.x) << ", " << num(d.y) << ", " << num(d.z) << ")";
        }
        s << "\n";
    }
    Box3 b = f.worldBounds();
    s << "world bounds: (" << num(b.lo.x) << ", " << num(b.lo.y) << ", " << num(b.lo.z) << ") .. (" << num(b.hi.x) << ", "
      << num(b.hi.y) << ", " << num(b.hi.z) << ")\n";
    for (const auto& n : f.notes) s << "note: " << n << "\n";
    return s.str();
}

std::string describeVolumeList(const std::vector<std::string>& labels, std::size_t slices) {
    if (labels.size() <= 1) return {};
    std::ostringstream s;
    s << "volumes: " << labels.size() << " (choose with `volume`, from 0)\n";
    for (std::size_t v = 0; v < labels.size(); ++v)
        s << "volume " << v << ": " << (labels[v].empty() ? std::string() : labels[v] + ", ") << slices << " slices\n";
    return s.str();
}

}  // namespace octrace::io::detail
