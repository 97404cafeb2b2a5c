#pragma once
/// @file NrrdWriter.h
/// Writes a ScalarField as a NRRD file that NrrdReader (and VTK, Slicer, teem) read back.
#include "octrace/build/ScalarField.h"

#include <string>

namespace octrace::io {

class NrrdWriter {
public:
    /// Writes `field` to `path` as NRRD0004: one file, raw little-endian float, with
    /// `space origin` and `space directions` (direction columns times spacing), `content`
    /// = field.name and `units:=` = field.units. Invalid samples are written as NaN (which
    /// NrrdReader reads back as invalid). A rectilinear axis is accepted only when its
    /// coordinates are evenly spaced (it is then stored as origin + spacing).
    /// The file is written under a temporary name and renamed, so `path` is never partial.
    /// @throws OutputError (uneven rectilinear axis, inconsistent field, I/O failure).
    static void write(const ScalarField& field, const std::string& path);
};

}  // namespace octrace::io
