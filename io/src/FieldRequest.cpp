#include "octrace/io/FieldRequest.h"

#include "InputFile.h"
#include "octrace/util/Error.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace octrace::io {

std::array<double, 4> parseRegion(const std::string& text) {
    std::array<double, 4> r{};
    std::stringstream in(text);
    std::string item;
    int n = 0;
    while (std::getline(in, item, ',')) {
        item = detail::trim(item);
        char* end = nullptr;
        double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(v))
            throw UsageError("region '" + text + "': '" + item + "' is not a number (expected LON0,LON1,LAT0,LAT1 in degrees)");
        if (n < 4) r[std::size_t(n)] = v;
        ++n;
    }
    if (n != 4)
        throw UsageError("region '" + text + "': expected 4 values LON0,LON1,LAT0,LAT1 in degrees, got " + std::to_string(n));
    checkRegion(r.data(), "region '" + text + "'");
    return r;
}

void checkRegion(const double region[4], const std::string& what) {
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(region[i])) throw UsageError(what + ": region values must be finite numbers");
    double lon0 = region[0], lon1 = region[1], lat0 = region[2], lat1 = region[3];
    if (lon1 < lon0) lon1 += 360.0;  // crosses the dateline
    if (lon1 == lon0)
        throw UsageError(what + ": longitude range " + detail::num(region[0]) + ".." + detail::num(region[1]) + " is empty");
    if (lon1 - lon0 > 360.0)
        throw UsageError(what + ": longitude range " + detail::num(region[0]) + ".." + detail::num(region[1]) +
                         " spans " + detail::num(lon1 - lon0) + " degrees, at most 360 allowed");
    if (lat0 < -90.0 || lat1 > 90.0)
        throw UsageError(what + ": latitudes must lie in -90..90, got " + detail::num(lat0) + ".." + detail::num(lat1));
    if (!(lat0 < lat1))
        throw UsageError(what + ": LAT0 must be less than LAT1, got " + detail::num(lat0) + " and " + detail::num(lat1));
}

}  // namespace octrace::io
