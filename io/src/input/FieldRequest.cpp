#include "octrace/io/FieldRequest.h"

#include "netcdf/CfTime.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace octrace::io {

void ReadHooks::checkCancelled(const std::string& what) const {
    if (cancelled && cancelled()) throw CancelledError(what + ": read cancelled");
}

namespace {

// "A,B,..." as exactly N finite numbers; `what` names the option, `form` the expected text.
template <std::size_t N>
std::array<double, N> parseNumbers(const std::string& text, const std::string& what, const std::string& form) {
    std::array<double, N> r{};
    std::stringstream in(text);
    std::string item;
    std::size_t n = 0;
    while (std::getline(in, item, ',')) {
        item = detail::trim(item);
        char* end = nullptr;
        double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(v))
            throw UsageError(what + " '" + text + "': '" + item + "' is not a number (expected " + form + ")");
        if (n < N) r[n] = v;
        ++n;
    }
    if (n != N)
        throw UsageError(what + " '" + text + "': expected " + std::to_string(N) + " values " + form + ", got " +
                         std::to_string(n));
    return r;
}

}  // namespace

std::array<double, 4> parseRegion(const std::string& text) {
    auto r = parseNumbers<4>(text, "region", "LON0,LON1,LAT0,LAT1 in degrees");
    checkRegion(r.data(), "region '" + text + "'");
    return r;
}

std::array<double, 2> parseDepthRange(const std::string& text) {
    auto r = parseNumbers<2>(text, "depth range", "Z0,Z1 in metres");
    if (!(r[0] < r[1]))
        throw UsageError("depth range '" + text + "': Z0 must be less than Z1 (metres, positive down)");
    return r;
}

void checkTimeText(const std::string& text) {
    if (text.empty()) throw UsageError("`time`: empty (give a time index or a date YYYY-MM-DD)");
    if (text.find_first_not_of("0123456789") == std::string::npos) {
        if (text.size() > 9) throw UsageError("`time`: index " + text + " is too large");
        return;
    }
    (void)detail::parseIsoDate(text, "`time`");
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
