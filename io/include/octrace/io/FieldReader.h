#pragma once
/// @file FieldReader.h
/// One entry point for scalar-field inputs: picks the reader from the file's content.
#include "octrace/build/ScalarField.h"
#include "octrace/io/DicomReader.h"
#include "octrace/io/FieldRequest.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

/// Reads a scalar field from `path`, choosing the reader by the file's first bytes
/// ("CDF\x01|\x02|\x05" NetCDF classic, HDF5 signature for NetCDF-4, "NRRD", "DICM" at
/// byte 128), then by extension (.nc .cdf .nc4 .nrrd .nhdr .dcm, DICOMDIR); a folder by its
/// content: a Zarr store (`.zgroup`, `.zarray`, `.zmetadata` or `zarr.json` at its root, read
/// by NetcdfReader through GDAL's Zarr driver; the final Zarr v3 layout is refused with
/// FormatNotSupported), else DICOM (DicomReader).
/// NRRD and DICOM hold one field: a non-empty `req.variable` must equal its name, and a
/// region is refused (InputError); `req.verticalScale` is ignored there with a warning.
/// `req.series` is refused (InputError) for anything but DICOM.
/// @throws InputError "PATH: no such file" when missing; FormatNotSupported naming the
///         supported formats; FileError "PATH: file is empty (0 bytes)"; otherwise as the
///         format's reader (NetcdfReader::read, NrrdReader::read, DicomReader::read), LimitError
///         when the samples would need more than `req.memoryBudget` (NRRD, NetCDF). The result
///         is validated.
ScalarField readField(const std::string& path, const FieldRequest& req = {});

/// What a chooser (the studio's) can offer for an input: the 3-D variables of a NetCDF file
/// (NetcdfReader::volumeVariables) and the image series of a DICOM input (listSeries); both
/// empty for the formats that hold one field. Throws as readField() for an input that cannot
/// be opened. A DICOM folder's headers are scanned with `hooks` (DicomReader::listSeries:
/// CancelledError when cancelled).
struct InputChoices {
    std::vector<std::string> variables;
    std::vector<DicomSeriesInfo> series;
};
InputChoices listInputChoices(const std::string& path, const ReadHooks& hooks = {});

/// The text `octrace info INPUT` prints: format, variables with units, dims and valid value
/// range, dims, spacing or axes, origin and world bounds; for DICOM every series, then the
/// one `req.series` chooses. What would need more than `req.memoryBudget` bytes (0 = no
/// limit) to read is left out of the text (NetCDF) or refused (NRRD, LimitError). Only
/// `series` and `memoryBudget` of the request are used. Throws as readField().
std::string describeInput(const std::string& path, const FieldRequest& req = {});

/// The Zarr store a metadata file belongs to: for a file named `.zgroup`, `.zarray`, `.zattrs`,
/// `.zmetadata` or `zarr.json` in a folder that is a Zarr store, that folder; else "". A store
/// is read by its folder (readField refuses the file, naming the folder); a chooser that picks
/// files (the studio's Open dialog) opens the folder instead. Never throws.
std::string zarrStoreOfMetadataFile(const std::string& path);

}  // namespace octrace::io
