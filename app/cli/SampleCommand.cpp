#include "Commands.h"
#include "Options.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/io/NrrdWriter.h"
#include "octrace/util/Error.h"

#include <cstdio>

namespace octrace::cli {

int runSample(const std::vector<std::string>& args) {
    bool help = false;
    std::string out;
    int samples = 65;
    int seed = 1;
    OptionParser p("sample", "octrace sample NAME -o OUT.nrrd [--samples N] [--seed S]");
    p.add({"o", "FILE", "output NRRD file (required)", [&](const std::string& v) { out = v; }});
    p.add({"samples", "N", "samples per axis over [-1,1]^3 (default 65)",
           [&](const std::string& v) { samples = parseInt("samples", v, 2, 1024); }});
    p.add({"seed", "S", "random seed of the 'noise' field (default 1)",
           [&](const std::string& v) { seed = parseInt("seed", v, 0, 1 << 30); }});
    p.add({"help", "", "show this help and exit", [&](const std::string&) { help = true; }});
    auto pos = p.parse(args);
    if (help) {
        std::fputs(p.help().c_str(), stdout);
        std::fputs("\nNAME: sphere (iso 0 = sphere of radius 0.7), torus, gyroid, noise\n", stdout);
        return 0;
    }
    if (pos.size() != 1) throw UsageError("sample needs exactly one NAME");
    if (out.empty()) throw UsageError("sample needs an output file: -o OUT.nrrd");
    ScalarField f = makeAnalyticField(pos[0], samples, std::uint32_t(seed));
    io::NrrdWriter::write(f, out);
    return 0;
}

}  // namespace octrace::cli
