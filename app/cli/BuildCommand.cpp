// octrace build: read a field, build the octree of an isosurface (shell) or of the solid it
// bounds (volume), and write it to an octree file (.oct) that every command reads as INPUT.
#include "Commands.h"
#include "octrace/model/Input.h"
#include "Options.h"
#include "OctreeOutput.h"
#include "StatsJson.h"
#include "SurfaceOptions.h"

#include "octrace/build/Volume.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Timer.h"

#include <sstream>

namespace octrace::cli {
namespace {

using BuildArgs = OctreeFileArgs;

OptionParser makeParser(BuildArgs& a) {
    OptionParser p("build", "octrace build INPUT -o OUT.oct [options]");
    p.add({"o", "FILE", "output octree file (.oct; written atomically) (required)", [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    addBakeOptions(p, a);
    addOctreeFileOptions(p, a);
    addCityOptions(p, a);
    return p;
}

}  // namespace

int runBuild(const std::vector<std::string>& args) {
    BuildArgs a;
    a.keepVolume = true;
    if (!parseCommandLine(makeParser(a), args, a, a.output, "an output file: -o OUT.oct")) return 0;
    Surface s = buildSurface(a);
    const OctreeOutput out = writeOctreeOutput(s.tree, a.output, a.level);
    if (!a.statsPath.empty()) {
        StatsJson js;
        js.set("input", a.input);
        js.set("output", a.output);
        js.set("load_ms", s.loadMs);
        js.set("build_ms", s.report.buildMs);
        js.set("bake_ms", s.bake.bakeMs);
        js.set("bake_rays", s.bake.rays);
        setOctreeStats(js, s.tree, out, a.level);
        io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    }
    return 0;
}

}  // namespace octrace::cli
