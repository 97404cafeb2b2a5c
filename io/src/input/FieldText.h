#pragma once
// The part of `octrace info` every volume reader prints the same way (internal).
#include "octrace/build/ScalarField.h"

#include <string>

namespace octrace::io::detail {

/// Lines "variables:", "dims:", "spacing:" (or the rectilinear axes), "origin:", "direction
/// (columns):" when not the identity, "world bounds:" and one "note:" per note of `f`.
std::string describeVolume(const ScalarField& f);

}  // namespace octrace::io::detail
