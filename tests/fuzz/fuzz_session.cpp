// Fuzz target: the studio's session file parser (app/studio/Session.cpp: Qt's JSON reader and
// the member checks behind it). Any input either parses into a state or is refused with
// InputError; nothing else may escape, crash or leak.
#include "FuzzSupport.h"
#include "Session.h"
#include "octrace/util/Error.h"

#include <QByteArray>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const QByteArray bytes(reinterpret_cast<const char*>(data), qsizetype(size));
    try {
        octrace::studio::StudioState s = octrace::studio::parseSession(bytes, QStringLiteral("/base"));
        // What parses must write back to a file that parses to the same state.
        const octrace::studio::StudioState again = octrace::studio::parseSession(octrace::studio::sessionJson(s));
        if (again.input != s.input || again.depth != s.depth || again.renderer != s.renderer ||
            again.cameraSet != s.cameraSet || again.iso != s.iso || again.cut != s.cut || again.clip != s.clip ||
            again.lighting != s.lighting || again.ambient != s.ambient || again.bakeAo != s.bakeAo ||
            again.figure != s.figure || again.title != s.title || again.dpi != s.dpi || again.scaleBar != s.scaleBar ||
            again.colourTolerance != s.colourTolerance || again.branchUp != s.branchUp || again.missCoherence != s.missCoherence)
            __builtin_trap();
    } catch (const octrace::InputError&) {
    }
    return 0;
}
