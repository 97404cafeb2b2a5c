#include "octrace/model/SolidSpec.h"

#include "octrace/csg/Relief.h"
#include "octrace/io/ReliefReader.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <sstream>

namespace octrace::model {

bool isSolidArgument(const std::string& spec) { return isSolidSpec(spec) || isReliefSpec(spec); }

void checkSolidArgument(const std::string& spec) {
    if (isReliefSpec(spec)) reliefPath(spec);
    else parseSolid(spec);
}

Solid resolveSolid(const std::string& spec, const ScalarField::Geographic& world, const std::string& worldName,
                   std::uint64_t memoryBudget) {
    if (!isReliefSpec(spec)) return parseSolid(spec);
    const std::string path = reliefPath(spec);
    if (!world.valid)
        throw InputError(spec + ": a relief is laid out in longitude and latitude, but " + worldName +
                         " is not a geographic field (give the NetCDF ocean file itself, not an octree file or a non-geographic grid)");
    auto relief = Relief::geographic(io::readRelief(path, memoryBudget), world);
    const ReliefRaster& r = relief->raster();
    std::ostringstream m;
    m << "relief " << path << ": " << r.nx << " x " << r.ny << " heights, longitude " << r.u0 << " .. " << r.u0 + (r.nx - 1) * r.du
      << ", latitude " << r.v0 << " .. " << r.v0 + (r.ny - 1) * r.dv << ", step " << r.du << " x " << r.dv
      << " degrees, in the world of " << worldName << " (vertical scale " << world.verticalScale << ")";
    log::debug(m.str());
    return Solid::below(std::move(relief));
}

Solid resolveSolid(const SolidArgument& arg, const ScalarField::Geographic& world, const std::string& worldName,
                   std::uint64_t memoryBudget) {
    return arg.solid ? *arg.solid : resolveSolid(arg.spec, world, worldName, memoryBudget);
}

}  // namespace octrace::model
