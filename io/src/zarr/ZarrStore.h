#pragma once
// What a Zarr store is, from the metadata files at its root (internal, std types only).
//
// GDAL's multidimensional Zarr driver reads the store (netcdf/NetcdfFile.cpp); this decides
// beforehand whether a folder is a store and which layout it has, because GDAL 3.6 opens a
// store in the final Zarr v3 layout as an empty group instead of refusing it.
#include <optional>
#include <string>

namespace octrace::io::detail {

/// The metadata files found at a folder's root, as bytes (absent: nullopt).
struct ZarrMetadata {
    std::optional<std::string> zgroup;     ///< `.zgroup` (v2 group)
    std::optional<std::string> zarray;     ///< `.zarray` (v2 array)
    std::optional<std::string> zmetadata;  ///< `.zmetadata` (v2 consolidated metadata)
    std::optional<std::string> zarrJson;   ///< `zarr.json` (v3: the final layout, or the pre-final draft's entry point)

    bool any() const { return zgroup || zarray || zmetadata || zarrJson; }
};

enum class ZarrLayout { V2, V3Draft };

struct ZarrStoreInfo {
    ZarrLayout layout = ZarrLayout::V2;
    std::string description;  ///< "Zarr v2 store (consolidated metadata, .zmetadata: 6 arrays)", ...
};

/// Whether `folder` holds a Zarr metadata file at its root (`.zgroup`, `.zarray`, `.zmetadata`
/// or `zarr.json`). Never throws.
bool isZarrFolder(const std::string& folder);

/// io::zarrStoreOfMetadataFile (FieldReader.h): the folder of a store whose metadata file
/// `path` is, else "". Never throws.
std::string storeOfMetadataFile(const std::string& path);

/// Reads the metadata files at `folder`'s root. Throws FileError naming the file when one is
/// unreadable or larger than 256 MiB.
ZarrMetadata readZarrMetadata(const std::string& folder);

/// The layout the metadata describe; `store` names the store in messages. v2 metadata win over
/// a `zarr.json` beside them (GDAL reads them first). Throws FormatNotSupported for the final
/// Zarr v3 layout (`zarr.json` with `"zarr_format": 3`: GDAL 3.6 cannot read it; the message
/// says how to convert the store to v2) and for a `zarr_format` GDAL does not read; FileError
/// for metadata that are not a JSON object or lack their `zarr_format`.
ZarrStoreInfo classifyZarrMetadata(const std::string& store, const ZarrMetadata& metadata);

/// readZarrMetadata then classifyZarrMetadata on a folder; InputError "PATH: no such file" or
/// FormatNotSupported when the folder holds no Zarr metadata. Returns the description.
std::string checkZarrOnDisk(const std::string& folder);

}  // namespace octrace::io::detail
