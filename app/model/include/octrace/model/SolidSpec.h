#pragma once
// The solids the command line names (render --cut, csg operands): the primitives of
// csg/Solid.h and relief:FILE, the ground under a relief raster (csg/Relief.h).
#include "octrace/build/ScalarField.h"
#include "octrace/csg/Solid.h"

#include <cstdint>
#include <optional>
#include <string>

namespace octrace::model {

/// A solid as a command names it: already made (a primitive; implicit, so a parsed Solid can
/// be given where one is expected), or a spec still to resolve (relief:FILE needs the field).
struct SolidArgument {
    std::string spec;
    std::optional<Solid> solid;
    SolidArgument(const Solid& s) : spec(s.describe()), solid(s) {}  // NOLINT: implicit on purpose
    explicit SolidArgument(std::string text) : spec(std::move(text)) {}
};

/// Whether `spec` names a solid (a primitive or relief:FILE) rather than an input file.
bool isSolidArgument(const std::string& spec);
/// Checks `spec` as the command line is parsed: UsageError for a malformed primitive or an
/// empty relief path (the relief's file is read later, by resolveSolid).
void checkSolidArgument(const std::string& spec);
/// The solid `spec` names. A relief is read (io/ReliefReader.h) and laid into the world of the
/// geographic field `world` (the field it cuts: same longitude/latitude centre and vertical
/// scale); `worldName` names that field for messages. Throws UsageError as checkSolidArgument,
/// InputError when `world` is not geographic (an octree file, a CT) and as readRelief.
Solid resolveSolid(const std::string& spec, const ScalarField::Geographic& world, const std::string& worldName,
                   std::uint64_t memoryBudget);
/// The solid itself when it is made, else resolveSolid of its spec.
Solid resolveSolid(const SolidArgument& arg, const ScalarField::Geographic& world, const std::string& worldName,
                   std::uint64_t memoryBudget);

}  // namespace octrace::model
