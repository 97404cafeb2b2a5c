#pragma once
// One DICOM file through GDCM (internal to octrace_io; GDCM stays in DicomFile.cpp): its
// header without the pixel data, then its decoded frames.
#include "dicom/DicomSeries.h"

#include <optional>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// True when the file starts with the DICOM preamble ("DICM" at byte 128) or is named *.dcm /
/// *.dicom (files without a preamble); cheap, for searching folders.
bool looksLikeDicom(const std::string& file);

/// True when the file is a DICOMDIR (its name, or its media storage SOP class).
bool isDicomDir(const std::string& file);

/// Reads the attributes octrace uses, stopping before the pixel data. Returns nothing when the
/// file is not DICOM or not an image (no Rows/Columns: a DICOMDIR, a report...), with the
/// reason in `whyNot`. Per-frame geometry and rescale come from the Per-frame Functional
/// Groups, then the Shared Functional Groups, then the top-level attributes. The file's
/// structure is checked by validateDicomFile() (DicomValidator.h) before GDCM opens it.
/// @throws FileError "FILE: DICOM structure broken at byte N: ..." for a broken structure;
///         FileError "FILE: ..." for an image header octrace refuses (absurd sizes or frame
///         counts, pixel data that cannot fit in the file, zero/negative or non-finite pixel
///         spacing, non-finite positions, colour images): before any large allocation.
std::optional<DicomHeader> readDicomHeader(const std::string& file, std::string& whyNot);

/// Stored values of every frame of `h.file` (frame after frame, x fastest), decoded whatever
/// the transfer syntax. The rescale is not applied. The structure is checked again (the file
/// is opened anew) before GDCM reads it.
/// @throws FileError "FILE: ..." when the pixel data are missing, truncated or cannot be
///         decoded, or do not match the header.
std::vector<float> decodeDicomFrames(const DicomHeader& h);

}  // namespace octrace::io::detail
