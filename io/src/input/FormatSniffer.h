#pragma once
// Tells input formats apart by their first bytes (internal).
#include <string>

namespace octrace::io::detail {

enum class FileKind { NetCdf, Zarr, Nrrd, Dicom, MetaImage, Nifti, Vti, Unknown };

struct Sniffed {
    FileKind kind = FileKind::Unknown;
    std::string description;  ///< e.g. "NetCDF-3 classic (CDF-1)"; for Unknown the first bytes, quoted
};

/// Requires a readable, non-empty file (InputError "PATH: no such file", FileError
/// "PATH: file is empty (0 bytes)"), then looks at its signature only (not the extension).
Sniffed sniffFormat(const std::string& path);

/// A folder by its content: a Zarr store when a Zarr metadata file (`.zgroup`, `.zarray`,
/// `.zmetadata`, `zarr.json`) lies at its root (description as checkZarrOnDisk gives it; throws
/// as that does, e.g. FormatNotSupported for the final Zarr v3 layout), else a DICOM folder.
Sniffed sniffFolder(const std::string& path);

}  // namespace octrace::io::detail
