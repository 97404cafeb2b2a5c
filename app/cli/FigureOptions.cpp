#include "FigureOptions.h"

#include "octrace/io/ImageWriter.h"
#include "octrace/util/Error.h"

#include <cmath>

namespace octrace::cli {

void checkImageOutput(const std::string& output) {
    const std::string ext = model::lowerExtension(output);
    bool known = false;
    for (const auto& e : io::imageExtensions()) known = known || e == ext;
    if (!known) throw UsageError("-o " + output + ": unknown image format '" + ext + "' (use " + joinNames(io::imageExtensions()) + ")");
}

void checkFigureOptions(const FigureArgs& f, const std::string& output) {
    if (!f.enabled && (!f.title.empty() || f.printInches || f.scaleBar))
        throw UsageError(std::string(f.printInches ? "--print-size" : f.scaleBar ? "--scale-bar" : "--title") + " needs --figure");
    if (!f.enabled && !f.coastline.empty()) throw UsageError("--coastline needs --figure");
    if (f.enabled) checkFigureFormat(output);
}

void addFigureOptions(OptionParser& p, FigureArgs& f, const std::string& shows) {
    const model::SettingTargets into{.figure = &f};
    p.add(settingOption(model::opt::figure, into,
                        shows.empty() ? "a colour bar with units, the variable, the region and labelled longitude/latitude/depth "
                                        "ticks on the bounding box"
                                      : shows));
    for (const model::Option* o : {&model::opt::title, &model::opt::dpi, &model::opt::printSize, &model::opt::scaleBar, &model::opt::coastline})
        p.add(settingOption(*o, into));
}

}  // namespace octrace::cli
