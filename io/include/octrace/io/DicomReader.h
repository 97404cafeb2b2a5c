#pragma once
/// @file DicomReader.h
/// Reads DICOM image series (CT, MR, ...; any transfer syntax GDCM decodes: uncompressed
/// little or big endian, JPEG baseline/lossless, JPEG-LS, JPEG 2000, RLE; single- or
/// multi-frame) into a ScalarField. No GDCM type appears here.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

/// One series found under an input, as `octrace info` lists it.
struct DicomSeriesInfo {
    std::string uid;          ///< SeriesInstanceUID
    std::string modality;     ///< "CT", "MR", ...
    std::string description;  ///< SeriesDescription (may be empty)
    int seriesNumber = 0;     ///< SeriesNumber (0 when absent)
    int columns = 0, rows = 0;
    int slices = 0;           ///< images of one volume (of the largest when they differ)
    int files = 0;
    int volumes = 1;          ///< volumes (time points, echoes, ...) at the same slices; see read()
    /// columns * rows * slices * volumes: the measure of "the largest series".
    double samples() const { return double(columns) * double(rows) * double(slices) * double(volumes); }
};

class DicomReader {
public:
    /// Every image series under `path`, in the order `--series INDEX` counts them (1-based):
    /// by SeriesNumber, then UID. `path` is a DICOM file, a folder (searched recursively; files
    /// starting with the DICOM preamble "DICM" at byte 128, or named *.dcm, are read) or a
    /// DICOMDIR (the folder it sits in is searched). Only headers are read.
    /// @throws InputError if `path` does not exist; FileError "no DICOM image" when nothing
    ///         under it is a DICOM image; FileError for a broken single file; CancelledError
    ///         when hooks.cancelled says so (asked before each file; progress is reported too).
    static std::vector<DicomSeriesInfo> listSeries(const std::string& path, const ReadHooks& hooks = {});

    /// The index in `list` (listSeries' order, 0-based) of the series `series` chooses, as
    /// read() chooses it: a SeriesInstanceUID, a 1-based index or a SeriesDescription; empty =
    /// the largest. A front end shows with it which series was read.
    /// @throws InputError naming `path` and the series for a `series` that matches none.
    static std::size_t chooseSeries(const std::vector<DicomSeriesInfo>& list, const std::string& series,
                                    const std::string& path);

    /// Reads one series as a volume. `series` chooses it: a SeriesInstanceUID, an index of
    /// listSeries() (1-based) or a SeriesDescription; empty = the largest series (said with
    /// log::info when there are several).
    ///
    /// Slices are ordered by ImagePositionPatient projected on the slice normal (row x column
    /// direction of ImageOrientationPatient), never by file name or InstanceNumber; their
    /// spacing comes from the positions. Geometry is LPS patient space in mm: origin = the
    /// first slice's position, direction columns = row direction, column direction, normal,
    /// spacing = PixelSpacing (column spacing along x) and the slice distance. Uneven slice
    /// distances (a missing slice) are kept as a rectilinear z axis, with a warning. A stack
    /// sheared by gantry tilt is resampled slice by slice onto the orthogonal grid (bilinear
    /// in plane; points outside a slice are masked), with a warning. Multi-frame images take
    /// per-frame positions, orientation, spacing and rescale from the Per-frame / Shared
    /// Functional Groups. CT values are Hounsfield units (RescaleSlope/Intercept of each
    /// image; units "HU"); other modalities keep their stored values. The field's name is
    /// the modality.
    ///
    /// A single image (one file of one frame) is a 2-D field in its own plane
    /// (ScalarField::planar: one sample along the normal, at the image's position, and no
    /// slice spacing, none being invented) when `acceptPlanar` (slices ask for it); otherwise
    /// it is refused with InputError: a surface needs a volume.
    /// @throws InputError for an unknown `series`, or a single image without `acceptPlanar`; FileError naming the file for a broken
    ///         or unsupported series (undecodable or truncated pixel data, mixed sizes or
    ///         orientations, absurd headers: checked before any large allocation).
    ///         LimitError when the slices, the volume and the largest file's decoding buffers
    ///         would need more than `memoryBudget` bytes (0 = no limit), found from the headers
    ///         before any of it is allocated.
    /// Thread-safe (no shared state).
    ///
    /// Several volumes in one series (images at the same position: time points, echoes,
    /// cardiac phases, diffusion directions, magnitude and phase) are told apart by their
    /// attributes: TemporalPositionIndex / TemporalPositionIdentifier, cardiac trigger delay,
    /// StackID, EchoNumbers, (Effective)EchoTime, DiffusionBValue and gradient direction,
    /// FrameType / ImageType, ComplexImageComponent, DimensionIndexValues (spatial indices
    /// left out), in that order, each used only when it splits the images further; repeats
    /// that nothing tells apart by their acquisition time. `volume` (0-based) chooses one; -1
    /// reads volume 0 and says (log::info) how many there are. The field's volumeLabel says
    /// what tells the volume read apart.
    /// @throws InputError for a `volume` beyond the last; FileError naming the volume when the
    ///         volumes do not hold the same slices (one missing a slice, different counts).
    ///
    /// `hooks` (ReadHooks): progress over the headers scanned (the first tenth) and the files
    /// decoded (only those of the volume read), cancellation asked before each file
    /// (CancelledError).
    static ScalarField read(const std::string& path, const std::string& series = {}, std::uint64_t memoryBudget = 0,
                            int volume = -1, bool acceptPlanar = false, const ReadHooks& hooks = {});

    /// The labels of the volumes of the series `series` chooses (one "" for a series of one
    /// volume), from the headers only. @throws as read().
    static std::vector<std::string> listVolumes(const std::string& path, const std::string& series = {});

    /// `octrace info` text: the series list, the chosen series' volumes, then the chosen
    /// volume as read() (a single image too, with a note that says it is one).
    static std::string describe(const std::string& path, const std::string& series = {}, std::uint64_t memoryBudget = 0,
                                int volume = -1);
};

}  // namespace octrace::io
