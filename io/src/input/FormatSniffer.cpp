#include "input/FormatSniffer.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "zarr/ZarrStore.h"

#include <algorithm>
#include <cstdint>

namespace octrace::io::detail {

Sniffed sniffFormat(const std::string& path) {
    requireReadableFile(path);
    std::string head = readPrefix(path, 4096);
    if (head.empty()) throw FileError(path + ": file is empty (0 bytes)");
    if (head.size() >= 4 && head.compare(0, 3, "CDF") == 0) {
        if (head[3] == '\x01') return {FileKind::NetCdf, "NetCDF-3 classic (CDF-1)"};
        if (head[3] == '\x02') return {FileKind::NetCdf, "NetCDF-3 64-bit offset (CDF-2)"};
        if (head[3] == '\x05') return {FileKind::NetCdf, "NetCDF-3 64-bit data (CDF-5)"};
    }
    static const std::string hdf5("\x89HDF\r\n\x1a\n", 8);
    for (std::size_t at : {0u, 512u, 1024u, 2048u})  // HDF5 allows a user block before the signature
        if (head.size() >= at + 8 && head.compare(at, 8, hdf5) == 0) return {FileKind::NetCdf, "NetCDF-4 / HDF5"};
    if (head.compare(0, 4, "NRRD") == 0) return {FileKind::Nrrd, "NRRD"};
    if (head.size() >= 132 && head.compare(128, 4, "DICM") == 0) return {FileKind::Dicom, "DICOM"};
    // NIfTI-1 (sizeof_hdr 348, magic "n+1" or "ni1" at 344) and NIfTI-2 (540, "n+2" at 4), either byte order.
    const auto int32At0 = [&](std::uint32_t v) {
        const std::uint32_t be = (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
        std::uint32_t x = 0;
        for (int i = 0; i < 4; ++i) x |= std::uint32_t(static_cast<unsigned char>(head[std::size_t(i)])) << (8 * i);
        return x == v || x == be;
    };
    if (head.size() >= 348 && int32At0(348) && (head.compare(344, 4, std::string("n+1\0", 4)) == 0 || head.compare(344, 4, std::string("ni1\0", 4)) == 0))
        return {FileKind::Nifti, "NIfTI-1"};
    if (head.size() >= 540 && int32At0(540) && head.compare(4, 3, "n+2") == 0) return {FileKind::Nifti, "NIfTI-2"};
    if ((head.compare(0, 5, "<?xml") == 0 || head.compare(0, 8, "<VTKFile") == 0) &&
        head.find("type=\"ImageData\"") != std::string::npos)
        return {FileKind::Vti, "VTK XML image data"};
    // MetaImage: text starting with one of the keys that open such headers.
    const std::string first = lower(trim(head.substr(0, std::min(head.find('='), std::size_t(32)))));
    if (head.find('=') != std::string::npos && (first == "objecttype" || first == "ndims" || first == "comment"))
        return {FileKind::MetaImage, "MetaImage"};
    return {FileKind::Unknown, quoteBytes(head.substr(0, 8))};
}

Sniffed sniffFolder(const std::string& path) {
    if (isZarrFolder(path)) return {FileKind::Zarr, checkZarrOnDisk(path)};
    return {FileKind::Dicom, "a folder of DICOM files"};
}

}  // namespace octrace::io::detail
