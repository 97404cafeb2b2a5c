#pragma once
/// @file VolumeWriter.h
/// Writes a ScalarField as MetaImage, NIfTI-1 or VTK image data, so that VolumeReader (and
/// ITK, 3D Slicer, ParaView) read back the same samples at the same world positions.
#include "octrace/build/ScalarField.h"

#include <string>

namespace octrace::io {

struct VolumeWriteOptions {
    /// NIfTI: write the sform (sform_code 2) and the qform (qform_code 1; only when the
    /// direction is a rotation, NIfTI's qform cannot hold a reflection). VolumeReader prefers
    /// the sform; tests turn one off to check the other.
    bool niftiSform = true;
    bool niftiQform = true;
};

class VolumeWriter {
public:
    /// The format follows the extension of `path`: .mhd (header + PATH-without-.mhd.raw data
    /// file), .mha (one file), .nii or .nii.gz (NIfTI-1, through VTK), .vti (VTK XML image
    /// data, through VTK, zlib-compressed). Samples are float32, invalid ones NaN; geometry
    /// as VolumeReader reads it (MetaImage: Offset, ElementSpacing, TransformMatrix at full
    /// precision; NIfTI: LPS turned into RAS; VTI: Origin, Spacing, Direction). Every file is
    /// written under a temporary name in the target's folder and renamed when complete.
    /// @throws OutputError (unknown extension, uneven rectilinear axis, I/O failure).
    static void write(const ScalarField& field, const std::string& path, const VolumeWriteOptions& options = {});
};

}  // namespace octrace::io
