#include "Commands.h"
#include "octrace/model/Input.h"
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <cstdio>

namespace octrace::cli {

int runInfo(const std::vector<std::string>& args) {
    bool help = false;
    io::FieldRequest request;
    OptionParser p("info", "octrace info INPUT... [--var NAME] [--region ...] [--depth-range Z0,Z1] [--time INDEX|DATE] [--series ...] [--volume N] [--crs CRS] [--lod-select LOD] [--dem RASTER] [--texture RASTER]");
    addVariableOption(p, request);
    addGeographicOptions(p, request);
    addSeriesOption(p, request);
    SurfaceArgs city;
    addCityOptions(p, city);
    p.add(settingOption(model::opt::maxMemory, {.request = &request},
                      "here for reading each input"));
    p.add({"help", "", "show this help and exit", [&](const std::string&) { help = true; }});
    auto inputs = p.parse(args);
    if (help) {
        std::fputs(p.help().c_str(), stdout);
        return 0;
    }
    if (inputs.empty()) throw UsageError("info needs at least one INPUT");
    if (request.memoryBudget == 0) request.memoryBudget = defaultMemoryBudget();
    // Batch: a bad input is reported and the others still described.
    int status = 0;
    for (const auto& in : inputs) {
        try {
            std::fputs(model::sayForCli(describe(in, request, city.city)).c_str(), stdout);
        } catch (const UsageError&) {
            throw;
        } catch (const Error& e) {
            std::fprintf(stderr, "octrace: error: %s\n", model::sayForCli(e.what()).c_str());
            status = 1;
        }
    }
    return status;
}

}  // namespace octrace::cli
