#pragma once
// DICOM series assembly without GDCM (internal to octrace_io): what the headers of a series'
// images say, their ordering along the slice normal, the slice spacing, gantry-tilt shear,
// and the resampling of a sheared stack onto an orthogonal grid.
#include "octrace/util/Math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

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

/// Orders the images of one series (all `headers` belong to it) and derives its geometry.
/// Every image must have the same size, orientation and pixel spacing; positions must be
/// finite and distinct. A single image gives a layout with `single` set. Images without ImagePositionPatient are allowed only as the frames of
/// one multi-frame file, stacked in frame order `sliceSpacing` apart (with a warning).
/// @throws FileError "WHAT: ..." naming the offending file when it is not the same for all.
SeriesLayout layoutSeries(const std::vector<DicomHeader>& headers, const std::string& what);

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
