#pragma once
// Small checks every reader makes before opening a file (internal to octrace_io).
#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// Most points octrace reads along one grid axis or dimension: 2^24. The finest octree has
/// 2^14 cells per edge, so a longer axis is of no use to it, and its coordinates alone would
/// take 128 MiB; a header announcing one (10^9, say) is refused before anything is read.
constexpr std::uint64_t kMaxAxisPoints = std::uint64_t(1) << 24;

/// Throws InputError "PATH: no such file", "PATH: is a directory" or "PATH: cannot be opened".
void requireReadableFile(const std::string& path);

/// Size in bytes (0 if it cannot be determined).
std::uintmax_t fileSize(const std::string& path);

/// Up to `n` first bytes of the file.
std::string readPrefix(const std::string& path, std::size_t n);

/// `bytes` made safe to quote in a one-line message (non-printable bytes as \xNN).
std::string quoteBytes(const std::string& bytes);

/// Shortest round-trippable-enough text for messages and notes (%.6g).
std::string num(double v);

/// Lower case ASCII copy.
std::string lower(std::string s);

/// The words of `s` separated by blanks, tabs or new lines (e.g. a CF `coordinates` attribute).
std::vector<std::string> words(const std::string& s);

/// Copy without leading and trailing white space.
std::string trim(const std::string& s);

}  // namespace octrace::io::detail
