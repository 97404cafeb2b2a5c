#pragma once
// --stats: the pipeline's figures (model::Stats) as the CLI writes them, its texts naming
// settings by their flags.
#include "octrace/model/OptionTable.h"
#include "octrace/model/Stats.h"

#include <string>

namespace octrace::cli {

class StatsJson : public model::Stats {
public:
    std::string text() const { return json(model::sayForCli); }
};

}  // namespace octrace::cli
