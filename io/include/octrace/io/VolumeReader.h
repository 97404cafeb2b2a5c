#pragma once
/// @file VolumeReader.h
/// Reads the image volume formats VTK decodes besides NRRD: MetaImage (.mhd with a data file,
/// .mha), NIfTI-1/2 (.nii, .nii.gz, .hdr/.img) and VTK XML image data (.vti), into a
/// ScalarField with the file's direction matrix. No VTK type appears here.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

class VolumeReader {
public:
    enum class Format { MetaImage, Nifti, Vti };

    /// Reads a 3-D single-component volume; samples become float, NaN and inf are marked
    /// invalid. Geometry (sample (i,j,k) at origin + direction * (i*sx, j*sy, k*sz)):
    /// - MetaImage: Offset, ElementSpacing and TransformMatrix (three values per axis: that
    ///   axis' world direction, as ITK writes it), parsed by octrace (VTK 9.1 ignores the
    ///   matrix) and checked before VTK reads the samples. Coordinates as in the file.
    /// - NIfTI: the sform when sform_code > 0, else the qform when qform_code > 0 (qfac
    ///   honoured), else the grid axes scaled by pixdim; NIfTI's RAS world is turned into
    ///   LPS (x and y negated) so that it matches DICOM and NRRD volumes. scl_slope/scl_inter
    ///   applied when the slope is not 0.
    /// - VTI: Origin, Spacing and Direction of the ImageData, the extent's start included;
    ///   the active point scalars (else the first point array).
    /// `name` is the array name (VTI), else the file name without extension; `units` empty.
    /// @throws InputError if missing; FormatNotSupported if not one of these formats;
    ///         FileError naming the file for a broken or unsupported one (not 3-D, several
    ///         components or time points, sheared directions, truncated or undecodable data);
    ///         LimitError when decoding would need more than `memoryBudget` bytes (0 = no
    ///         limit), found from the header before the samples are allocated.
    ///
    /// A 4-D NIfTI image (dim[4] > 1: time points, diffusion directions) is a series of
    /// volumes: `volume` (0-based) chooses one; -1 reads volume 0 and says (log::info) how many
    /// there are. Other formats hold one volume and refuse a `volume` (InputError). Only the
    /// volume asked for is decoded: a file cut after it reads, one cut inside it is refused
    /// (FileError "NIfTI data truncated", naming the volume); a .nii.gz is inflated up to its
    /// end, the volumes before it skipped.
    /// `hooks`: NIfTI reports progress per slice and is cancelled between slices
    /// (CancelledError); the other formats read in one step and do not report.
    static ScalarField read(const std::string& path, Format format, std::uint64_t memoryBudget = 0, int volume = -1,
                            const ReadHooks& hooks = {});

    /// The volumes in the file, from its header: dim[4] of a 4-D NIfTI image, else one. Each is
    /// labelled by its time ("time 1.5 s": toffset + v * pixdim[4] in xyzt_units' time unit)
    /// when the header gives one, else "".
    static std::vector<std::string> volumeLabels(const std::string& path, Format format);

    /// `octrace info` text: format line, then the volume as NrrdReader::describe prints it.
    static std::string describe(const std::string& path, Format format, std::uint64_t memoryBudget = 0, int volume = -1);

    /// "MetaImage", "NIfTI", "VTK image data".
    static const char* formatName(Format format);
};

}  // namespace octrace::io
