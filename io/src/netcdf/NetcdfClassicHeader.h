#pragma once
// Walks the header of a NetCDF classic file (CDF-1, CDF-2, CDF-5) to learn where its data end
// (internal). libnetcdf reads a truncated classic file without complaint, filling the missing
// tail with zeros, so the readers check the file size against this first.
#include <cstdint>
#include <istream>
#include <string>

namespace octrace::io::detail {

/// Byte offset just past the last variable's data (records included), i.e. the smallest size
/// the file can have. Throws FileError naming the problem if the header is cut short or malformed.
std::uint64_t classicDataEnd(const std::string& path);

/// The same for a header read from `in` (positioned at the file's first byte) of a file of
/// `fileSize` bytes; `path` only names the file in messages.
std::uint64_t classicDataEnd(std::istream& in, std::uint64_t fileSize, const std::string& path);

}  // namespace octrace::io::detail
