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

/// Refuses, before any long work, an output whose folder does not exist or is not a folder.
/// @throws OutputError as writeFileAtomically would after the work.
void checkOutputFolder(const std::string& path);

/// Makes SIGINT, SIGTERM and SIGHUP first remove the temporaries of the
/// writeFileAtomically() calls in progress, then end the process as the signal's default
/// action would (so its exit status still names the signal: a shell reports 130 for SIGINT,
/// 143 for SIGTERM). Signals that are ignored when it is called (e.g. under nohup) stay
/// ignored; a second signal during the clean-up ends the process at once.
/// For programs only: a library must not change how its host handles signals, so octrace
/// calls it from the CLI's main() alone. Call it once, early, before other threads start.
/// The handler only reads fixed buffers (no locks, no allocation) and calls unlink() and
/// raise(), which are async-signal-safe. A temporary whose name is longer than 4095 bytes,
/// or beyond the 16th written at the same time, is not removed on a signal.
void removeTemporariesOnSignals();

}  // namespace octrace::io
