#include "Commands.h"
#include "Options.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/io/NrrdWriter.h"
#include "octrace/util/Error.h"

#include <cstdio>

namespace octrace::cli {

int runSample(const std::vector<std::string>& args) {
    bool help = false;
    std::string out;
    int samples = int(model::opt::sampleCount.defaultValue);
    int seed = int(model::opt::seed.defaultValue);
    OptionParser p("sample", "octrace sample NAME -o OUT.nrrd [--samples N] [--seed S]");
    p.add({"o", "FILE", "output NRRD file (required)", [&](const std::string& v) { out = v; }});
    p.add(tableOption(model::opt::sampleCount, [&](const std::string& v) { samples = tableInt(model::opt::sampleCount, v); }));
    p.add(tableOption(model::opt::seed, [&](const std::string& v) { seed = tableInt(model::opt::seed, v); }));
    p.add({"help", "", "show this help and exit", [&](const std::string&) { help = true; }});
    auto pos = p.parse(args);
    if (help) {
        std::fputs(p.help().c_str(), stdout);
        std::fputs(("\nNAME: " + analyticFieldList() + " (iso 0 of each; sphere: radius 0.7; spheres: 60 of radii 0.04 to 0.3)\n").c_str(), stdout);
        return 0;
    }
    if (pos.size() != 1) throw UsageError("sample needs exactly one NAME");
    if (out.empty()) throw UsageError("sample needs an output file: -o OUT.nrrd");
    io::checkOutputFolder(out);
    ScalarField f = makeAnalyticField(pos[0], samples, std::uint32_t(seed));
    io::NrrdWriter::write(f, out);
    return 0;
}

}  // namespace octrace::cli
