#pragma once
// The part of `octrace info` every volume reader prints the same way (internal).
#include "octrace/build/ScalarField.h"

#include <string>
#include <vector>

namespace octrace::io::detail {

/// Lines "variables:", "dims:", "spacing:" (or the rectilinear axes), "origin:", "direction
/// (columns):" when not the identity, "world bounds:" and one "note:" per note of `f`.
std::string describeVolume(const ScalarField& f);

/// Lines "volumes: N (choose with `volume`, from 0)" and "volume v: <label>, K slices" for a
/// series of `labels.size()` volumes of `slices` slices each (a DICOM series, a 4-D NIfTI
/// image); an empty label leaves the volume's index alone. Nothing for a single volume.
std::string describeVolumeList(const std::vector<std::string>& labels, std::size_t slices);

}  // namespace octrace::io::detail
