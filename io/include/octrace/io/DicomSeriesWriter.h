#pragma once
/// @file DicomSeriesWriter.h
/// Writes a ScalarField as a DICOM image series (one uncompressed file per slice, explicit VR
/// little endian, signed 16-bit pixels), with the geometry a test or a benchmark chooses:
/// file names in a shuffled order, instance numbers against the slice normal, a sheared
/// (gantry-tilted) stack, slopes and intercepts that change from slice to slice. DicomReader
/// reads it back to the same values at the same world positions. No GDCM type appears here.
#include "octrace/build/ScalarField.h"

#include <cstdint>
#include <functional>
#include <string>

namespace octrace::io {

struct DicomSeriesWriteOptions {
    std::string modality = "CT";  ///< Modality: CT (CT Image Storage), MR (MR Image Storage), or other
    std::string description;      ///< SeriesDescription (empty: none)
    int seriesNumber = 1;
    /// RescaleSlope / RescaleIntercept of slice k (in the field's z order): each value v is
    /// stored as (v - intercept) / slope, which must be an integer in the int16 range.
    /// Empty: (1, 0) for every slice.
    std::function<dvec2(int k)> rescale;
    /// InstanceNumber (and, unshuffled, file-name order) runs against the slice order.
    bool descending = false;
    /// Non-zero: file names in an order drawn from this seed instead of slice order.
    std::uint64_t shuffleSeed = 0;
    /// Gantry tilt: slice k is written k * shearRows rows further along the column direction
    /// than the field puts it (its samples unchanged), so the stack is sheared by
    /// atan(shearRows * row spacing / slice spacing). 0: no shear.
    double shearRows = 0.0;
    /// WindowCenter / WindowWidth (not written when invalid).
    ValueWindow window;
    /// PhotometricInterpretation MONOCHROME1 instead of MONOCHROME2.
    bool monochrome1 = false;
};

class DicomSeriesWriter {
public:
    /// Writes slice k of `field` to `folder`/NAME (the folder is created; files already there
    /// are left alone). The field's axes become ImageOrientationPatient (x: along a row, y:
    /// down a column), its spacing PixelSpacing, and the z position of slice k (uniform or
    /// rectilinear) ImagePositionPatient along the third axis; a left-handed direction is
    /// written as it is (the reader then orders the slices the other way round).
    /// @returns the file names written, in slice order.
    /// @throws OutputError "FOLDER: ..." for masked samples, values that are not integers in
    ///         int16 once rescaled, slices larger than 65535, or a file that cannot be written.
    static std::vector<std::string> write(const ScalarField& field, const std::string& folder,
                                          const DicomSeriesWriteOptions& options = {});
};

}  // namespace octrace::io
