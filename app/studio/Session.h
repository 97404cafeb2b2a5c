#pragma once
// Session files of the studio: StudioState as JSON (inputs, surface, renderers, camera,
// shading, export), written atomically. The format is documented in docs/user/studio.md.
#include "StudioState.h"

#include <QByteArray>
#include <QString>

namespace octrace::studio {

/// The state as a session file's text (UTF-8 JSON, indented).
QByteArray sessionJson(const StudioState& state);

/// Parses a session file's text. Every member is optional (missing ones keep the defaults of
/// StudioState); a member of the wrong type or out of range is refused. A relative input path
/// is taken relative to `baseFolder` (the session file's folder; empty: as it is).
/// @throws InputError naming the member and the problem (not JSON, not an object, another
///         format version, wrong type, unknown renderer or colour map, out-of-range number).
StudioState parseSession(const QByteArray& json, const QString& baseFolder = {});

/// Writes `state` to `path` atomically (io::writeFileAtomically), a file input as an absolute
/// path; throws OutputError.
void saveSession(const StudioState& state, const QString& path);
/// Reads and parses `path`; throws InputError ("PATH: no such file", "PATH: ...problem").
StudioState loadSession(const QString& path);

}  // namespace octrace::studio
