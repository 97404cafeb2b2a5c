// octrace csg A OP B -o OUT.oct: union, intersection or difference of two solids, each a
// field (its volume octree is built), a volume octree file, a primitive solid or the ground
// under a relief raster (laid into the world of the other operand, a geographic field).
#include "Commands.h"
#include "octrace/model/Input.h"
#include "OctreeOutput.h"
#include "Options.h"
#include "StatsJson.h"
#include "octrace/model/SolidSpec.h"
#include "SurfaceOptions.h"

#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Timer.h"

#include <cstdio>
#include <optional>

namespace octrace::cli {
namespace {

using CsgArgs = OctreeFileArgs;

OptionParser makeParser(CsgArgs& a) {
    OptionParser p("csg", "octrace csg A union|intersection|difference B -o OUT.oct [options]\n"
                          "A, B: a field input, a volume octree file (.oct) or a solid: box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R,\n"
                          "  cylinder:X0,Y0,Z0,X1,Y1,Z1,R, halfspace:X,Y,Z,NX,NY,NZ (world units) or relief:FILE (the ground\n"
                          "  under a relief raster, laid into the other operand's geographic world); not two solids");
    p.add({"o", "FILE", "output octree file (.oct, volume form; written atomically) (required)",
           [&](const std::string& v) { a.output = v; }});
    addSurfaceOptions(p, a);
    addInsideOption(p, a, "field operands");
    addExtendDownOption(p, a);
    addOctreeFileOptions(p, a);
    return p;
}

/// One operand: a solid, or the volume octree of an octree file or a field.
struct Operand {
    std::optional<Solid> solid;
    Octree tree;
    ScalarField::Geographic world;  ///< a field operand's geographic mapping (a relief is laid into it)
    double loadMs = 0.0, buildMs = 0.0;
    CsgOperand operand() const { return solid ? CsgOperand::of(*solid) : CsgOperand::of(tree); }
};

/// A tree operand (a solid is resolved once the other operand is loaded: resolveSolid).
Operand loadOperand(const CsgArgs& a, const std::string& input) {
    Operand o;
    if (isOctreeInput(input)) {
        Timer t;
        o.tree = loadOctree(input, memoryBudget(a));
        o.loadMs = t.ms();
        if (o.tree.form != OctreeForm::Volume)
            throw InputError(input + ": a shell octree; CSG needs the volume form (octrace build --form volume)");
        return o;
    }
    SurfaceArgs field = a;  // the field options apply to each field operand
    field.input = input;
    field.formGiven = false;
    field.form = OctreeForm::Volume;
    field.keepVolume = true;
    Surface s = buildSurface(field);
    o.tree = std::move(s.tree);
    o.world = s.field.geographic;
    o.loadMs = s.loadMs;
    o.buildMs = s.report.buildMs;
    return o;
}

}  // namespace

int runCsg(const std::vector<std::string>& args) {
    CsgArgs a;
    const OptionParser parser = makeParser(a);
    const std::vector<std::string> positional = parser.parse(args);
    if (a.help) {
        std::fputs(parser.help().c_str(), stdout);
        return 0;
    }
    if (positional.size() != 3)
        throw UsageError("csg needs A OP B (got " + std::to_string(positional.size()) + " arguments)");
    if (a.output.empty()) throw UsageError("csg needs an output file: -o OUT.oct");
    const CsgOp op = parseCsgOp(positional[1]);
    for (int i : {0, 2})
        if (isSolidArgument(positional[std::size_t(i)])) checkSolidArgument(positional[std::size_t(i)]);  // usage errors first
    if (isSolidArgument(positional[0]) && isSolidArgument(positional[2]))
        throw UsageError("csg: at least one operand must be a field or an octree file (two solids have no voxels to share)");
    const bool solidFirst = isSolidArgument(positional[0]);
    const std::string& treeInput = positional[solidFirst ? 2 : 0];
    const std::string& solidInput = positional[solidFirst ? 0 : 2];
    Operand tree = loadOperand(a, treeInput), other;
    if (isSolidArgument(solidInput)) other.solid = resolveSolid(solidInput, tree.world, treeInput, memoryBudget(a));
    else other = loadOperand(a, solidInput);
    const Operand& lhs = solidFirst ? other : tree;
    const Operand& rhs = solidFirst ? tree : other;
    Timer t;
    const Octree result = csg(lhs.operand(), op, rhs.operand());
    const double csgMs = t.ms();
    const OctreeOutput out = writeOctreeOutput(result, a.output, a.level);
    if (!a.statsPath.empty()) {
        StatsJson js;
        js.set("a", positional[0]);
        js.set("operation", csgOpName(op));
        js.set("b", positional[2]);
        js.set("output", a.output);
        js.set("load_ms", lhs.loadMs + rhs.loadMs);
        js.set("build_ms", lhs.buildMs + rhs.buildMs);
        js.set("csg_ms", csgMs);
        setOctreeStats(js, result, out, a.level);
        const VoxelCount n = countVoxels(result);
        js.set("interior_voxels", n.interior);
        js.set("volume_voxels", n.volume());
        io::writeFileAtomically(a.statsPath, std::string_view(js.text()));
    }
    return 0;
}

}  // namespace octrace::cli
