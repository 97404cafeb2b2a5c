#include "FormatSniffer.h"

#include "InputFile.h"
#include "octrace/util/Error.h"

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
    return {FileKind::Unknown, quoteBytes(head.substr(0, 8))};
}

}  // namespace octrace::io::detail
