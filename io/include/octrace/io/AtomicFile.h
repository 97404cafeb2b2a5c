#pragma once
/// @file AtomicFile.h
/// "Never a partial output file": outputs are written to a temporary name in the target's
/// folder and renamed over the target only once complete. A reader of the target sees
/// either the old file (or none) or the new one, never a half-written one.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace octrace::io {

/// Writes `bytes` to `path + ".tmp-<pid>-<n>"`, flushes it to disk, and renames it over `path`
/// (replacing an existing file). Thread-safe; concurrent calls use distinct temporaries.
/// @throws OutputError naming `path` and the reason (folder missing, permission, disk full,
///         target is a folder, ...). On failure the temporary is removed and whatever was at
///         `path` before is left untouched.
void writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes);

/// Same, for text (e.g. the stats JSON).
void writeFileAtomically(const std::string& path, std::string_view text);

}  // namespace octrace::io
