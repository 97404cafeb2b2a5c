#pragma once
// DICOM series assembly without GDCM (internal to octrace_io): what the headers of a series'
// images say, their ordering along the slice normal, the slice spacing, gantry-tilt shear,
// and the resampling of a sheared stack onto an orthogonal grid.
#include "octrace/util/Math.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// The attributes that may tell the volumes of one series apart (several images at one
/// position: time points, echoes, diffusion directions, magnitude and phase), in the order the
/// volumes are sorted and labelled by.
enum VolumeAttribute : int {
    kTemporalPosition,   ///< TemporalPositionIndex (enhanced) or TemporalPositionIdentifier
    kTriggerTime,        ///< NominalCardiacTriggerDelayTime (enhanced) or TriggerTime: cardiac phases
    kStack,              ///< StackID (enhanced)
    kEchoNumber,         ///< EchoNumbers
    kEchoTime,           ///< EffectiveEchoTime (enhanced) or EchoTime, ms
    kBValue,             ///< DiffusionBValue
    kGradientDirection,  ///< DiffusionGradientOrientation
    kImageType,          ///< FrameType (enhanced) or ImageType: M, P, R, I, field maps
    kComplexComponent,   ///< ComplexImageComponent: MAGNITUDE, PHASE, REAL, IMAGINARY
    kDimensionIndex,     ///< DimensionIndexValues without the spatial indices (stack, in-stack position, position)
    kVolumeAttributeCount
};

/// The numbers of a DS, IS or multi-valued numeric text, separated by backslashes; nothing when
/// a part is not a finite number.
std::optional<std::vector<double>> dicomNumbers(const std::string& text);

/// How a message and `octrace info` name a VolumeAttribute.
const char* volumeAttributeName(int attribute);

/// Where one image (a frame of a file) lies and how its stored values map to real values.
struct DicomFrame {
    bool hasPosition = false;
    dvec3 position{0.0};                ///< ImagePositionPatient: centre of the first pixel, mm (LPS)
    bool hasOrientation = false;
    dvec3 rowDir{1.0, 0.0, 0.0};        ///< ImageOrientationPatient[0..2]: along a row (column index grows)
    dvec3 colDir{0.0, 1.0, 0.0};        ///< ImageOrientationPatient[3..5]: down a column (row index grows)
    bool hasPixelSpacing = false;
    dvec2 pixelSpacing{1.0};            ///< PixelSpacing: (between rows, between columns), mm
    double slope = 1.0, intercept = 0.0;  ///< RescaleSlope / RescaleIntercept
    double windowCentre = 0.0, windowWidth = 0.0;  ///< WindowCenter / WindowWidth (the first pair); width 0: none
    /// The values of the VolumeAttributes as the file gives them (trimmed; "" when absent).
    std::array<std::string, kVolumeAttributeCount> volumeKey;
    /// FrameAcquisitionDateTime, AcquisitionDateTime or AcquisitionTime ("" when absent): orders
    /// the repeats at one position when no VolumeAttribute tells them apart.
    std::string acquired;
};

/// The header of one DICOM image file: the attributes octrace uses, checked for sanity.
struct DicomHeader {
    std::string file;
    std::string seriesUid, modality, description;
    int seriesNumber = 0;
    int rows = 0, columns = 0;
    int bitsAllocated = 0;
    bool monochrome1 = false;   ///< PhotometricInterpretation MONOCHROME1: low values displayed bright
    double sliceSpacing = 0.0;  ///< SpacingBetweenSlices, else SliceThickness; 0 when absent
    /// The keywords of the attributes the kDimensionIndex values index (the DimensionIndexPointers
    /// that are not spatial, "InversionTimes"; comma-separated), which its volume label names.
    std::string dimensionNames;
    std::vector<DicomFrame> frames;  ///< NumberOfFrames entries
};

/// One slice of the assembled volume: which file and frame, and its shift in plane (mm along
/// the row and column directions) relative to the first slice; non-zero only for a sheared
/// (gantry-tilted) stack.
struct SliceRef {
    std::size_t header = 0;
    int frame = 0;
    dvec2 shift{0.0};
};

/// The geometry of a series once its slices are ordered.
struct SeriesLayout {
    ivec3 sliceDims{0};          ///< columns, rows, slices of the stored images
    dvec3 origin{0.0};           ///< position of the first slice
    dmat3 direction{1.0};        ///< columns: row direction, column direction, slice normal
    dvec2 spacing{1.0};          ///< x (between columns), y (between rows), mm
    std::vector<double> z;       ///< slice positions along the normal, from 0, increasing
    bool uniform = true;         ///< slice distances equal within 1%
    /// One image (one file of one frame): z = {0}, no slice distance, never tilted. A volume
    /// needs at least 2 slices; the reader reads it as a 2-D field (ScalarField::planar).
    bool single = false;
    std::vector<SliceRef> slices;  ///< in z order
    bool tilted = false;         ///< in-plane shifts present (gantry tilt)
    double tiltDegrees = 0.0;
    std::vector<std::string> warnings;  ///< each one line, without the path
};

/// One volume of a series: what tells it apart from the others and its images.
struct SeriesVolume {
    std::string label;             ///< "temporal position 2", "echo time 4.92, complex component PHASE"; "" when alone
    std::vector<SliceRef> images;  ///< (header, frame) of each image, shift 0
};

/// Splits the images of one series into volumes. A series where no two images lie at the same
/// position along the slice normal is one volume. Otherwise the images are grouped by the
/// VolumeAttributes, each taken (in their order) only when it splits the groups further and
/// leaves no more groups than there are images at one position; images that still share a
/// position within a group are told apart by their acquisition time (then file and frame
/// order): the first acquired at each position is in the first repeat. Volumes are sorted by
/// their attributes' values (numerically where both are numbers).
/// Every volume must hold the same slices: checked with checkVolumesAlike.
std::vector<SeriesVolume> splitVolumes(const std::vector<DicomHeader>& headers);

/// Refuses volumes that do not hold the same slices, naming the volume: one missing a slice
/// (a position the others have, inside its own first..last), or one with a different number
/// of slices. `what` prefixes the message. @throws FileError.
void checkVolumesAlike(const std::vector<DicomHeader>& headers, const std::vector<SeriesVolume>& volumes,
                       const std::string& what);

/// Orders the images of one series (all `headers` belong to it) and derives its geometry.
/// Every image must have the same size, orientation and pixel spacing; positions must be
/// finite and distinct. A single image gives a layout with `single` set. Images without ImagePositionPatient are allowed only as the frames of
/// one multi-frame file, stacked in frame order `sliceSpacing` apart (with a warning).
/// @throws FileError "WHAT: ..." naming the offending file when it is not the same for all.
/// `images` (non-empty) restricts it to those images (one volume of splitVolumes).
SeriesLayout layoutSeries(const std::vector<DicomHeader>& headers, const std::string& what,
                          const std::vector<SliceRef>& images = {});

/// Samples of the orthogonal grid of a sheared stack: `stored` holds the slices (x fastest,
/// `layout.sliceDims`, already in z order and rescaled); returns the grid of `outDims` whose
/// sample (i,j,k) lies `outOffset` + (i, j) * spacing in plane from the first slice's
/// position, bilinear in slice k. `valid` gets 0 where the point falls outside slice k.
std::vector<float> resampleSheared(const std::vector<float>& stored, const SeriesLayout& layout, ivec3 outDims,
                                   dvec2 outOffset, std::vector<std::uint8_t>& valid);

/// The in-plane extent of a sheared stack: grid size and offset of its first sample from the
/// first slice's position (mm along row and column directions), covering every slice.
void shearedGrid(const SeriesLayout& layout, ivec3& outDims, dvec2& outOffset);

}  // namespace octrace::io::detail
