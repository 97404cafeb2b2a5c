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
    if (f.enabled) checkFigureFormat(output);
}

dvec2 parsePrintSize(const std::string& option, const std::string& text) {
    std::string t = text, unit;
    for (const char* u : {"mm", "cm", "in"}) {
        const std::string us(u);
        if (t.size() > us.size() && t.compare(t.size() - us.size(), us.size(), us) == 0) {
            unit = us;
            t.erase(t.size() - us.size());
            break;
        }
    }
    if (unit.empty()) throw UsageError("--" + option + ": expected WxH with a unit mm, cm or in (e.g. 180x120mm), got '" + text + "'");
    const std::size_t x = t.find('x');
    if (x == std::string::npos) throw UsageError("--" + option + ": expected WxH with a unit, got '" + text + "'");
    const double w = parseNumber(option, t.substr(0, x)), h = parseNumber(option, t.substr(x + 1));
    const double perInch = unit == "mm" ? 25.4 : unit == "cm" ? 2.54 : 1.0;
    if (!(w > 0.0 && h > 0.0) || w / perInch > 100.0 || h / perInch > 100.0)
        throw UsageError("--" + option + ": width and height must be positive and at most 100 inches, got '" + text + "'");
    return dvec2(w / perInch, h / perInch);
}

void addFigureOptions(OptionParser& p, FigureArgs& f, const std::string& shows) {
    p.add(tableOption(model::opt::figure, [&](const std::string&) { f.enabled = true; },
                      shows.empty() ? "a colour bar with units, the variable, the region and labelled longitude/latitude/depth "
                                      "ticks on the bounding box"
                                    : shows));
    p.add(tableOption(model::opt::title, [&](const std::string& v) { f.title = v; }));
    p.add(tableOption(model::opt::dpi, [&](const std::string& v) { f.dpi = tableInt(model::opt::dpi, v); }));
    p.add(tableOption(model::opt::printSize, [&](const std::string& v) { f.printInches = parsePrintSize(model::opt::printSize.flag, v); }));
    p.add(tableOption(model::opt::scaleBar, [&](const std::string&) { f.scaleBar = true; }));
}

}  // namespace octrace::cli
