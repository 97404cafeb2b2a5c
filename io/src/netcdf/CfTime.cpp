#include "netcdf/CfTime.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <cmath>
#include <cstdio>
#include <regex>

namespace octrace::io::detail {
namespace {

std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }

bool gregorianLeap(std::int64_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }
bool julianLeap(std::int64_t y) { return y % 4 == 0; }

// A calendar without the standard calendar's switch: day numbers count from its 0001-01-01.
enum class Plain { Gregorian, Julian, NoLeap, AllLeap, Day360 };

bool leap(Plain c, std::int64_t y) {
    switch (c) {
        case Plain::Gregorian: return gregorianLeap(y);
        case Plain::Julian: return julianLeap(y);
        case Plain::AllLeap: return true;
        default: return false;
    }
}

int monthLength(Plain c, std::int64_t y, int m) {
    if (c == Plain::Day360) return 30;
    static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && leap(c, y) ? 29 : days[m - 1];
}

std::int64_t daysBeforeYear(Plain c, std::int64_t y) {
    const std::int64_t n = y - 1;
    switch (c) {
        case Plain::Gregorian: return 365 * n + floorDiv(n, 4) - floorDiv(n, 100) + floorDiv(n, 400);
        case Plain::Julian: return 365 * n + floorDiv(n, 4);
        case Plain::NoLeap: return 365 * n;
        case Plain::AllLeap: return 366 * n;
        case Plain::Day360: return 360 * n;
    }
    return 0;
}

std::int64_t dayNumber(Plain c, std::int64_t y, int m, int d) {
    std::int64_t n = daysBeforeYear(c, y);
    for (int k = 1; k < m; ++k) n += monthLength(c, y, k);
    return n + d - 1;
}

void fromDayNumber(Plain c, std::int64_t n, DateTime& out) {
    const double yearLength = c == Plain::Day360 ? 360.0 : c == Plain::NoLeap ? 365.0 : c == Plain::AllLeap ? 366.0 : 365.25;
    std::int64_t y = std::int64_t(std::floor(double(n) / yearLength)) + 1;
    while (daysBeforeYear(c, y) > n) --y;
    while (daysBeforeYear(c, y + 1) <= n) ++y;
    std::int64_t rest = n - daysBeforeYear(c, y);
    int m = 1;
    while (rest >= monthLength(c, y, m)) rest -= monthLength(c, y, m++);
    out.year = y;
    out.month = m;
    out.day = int(rest) + 1;
}

// The standard calendar: Julian up to 1582-10-04, Gregorian from 1582-10-15, in proleptic
// Gregorian day numbers (Julian 0001-01-01 is Gregorian 0000-12-30, two days earlier).
const std::int64_t kGregorianStart = 577735;  // dayNumber(Gregorian, 1582, 10, 15)

Plain plain(Calendar c) {
    switch (c) {
        case Calendar::Julian: return Plain::Julian;
        case Calendar::NoLeap: return Plain::NoLeap;
        case Calendar::AllLeap: return Plain::AllLeap;
        case Calendar::Day360: return Plain::Day360;
        default: return Plain::Gregorian;
    }
}

std::int64_t absoluteDay(Calendar c, std::int64_t y, int m, int d) {
    if (c != Calendar::Standard) return dayNumber(plain(c), y, m, d);
    std::int64_t g = dayNumber(Plain::Gregorian, y, m, d);
    return g >= kGregorianStart ? g : dayNumber(Plain::Julian, y, m, d) - 2;
}

void fromAbsoluteDay(Calendar c, std::int64_t n, DateTime& out) {
    if (c != Calendar::Standard) return fromDayNumber(plain(c), n, out);
    if (n >= kGregorianStart) return fromDayNumber(Plain::Gregorian, n, out);
    fromDayNumber(Plain::Julian, n + 2, out);
}

bool exists(Calendar c, const DateTime& d) {
    if (d.month < 1 || d.month > 12 || d.day < 1) return false;
    if (c == Calendar::Standard) {
        if (d.year == 1582 && d.month == 10 && d.day > 4 && d.day < 15) return false;
        Plain p = dayNumber(Plain::Gregorian, d.year, d.month, d.day) >= kGregorianStart ? Plain::Gregorian : Plain::Julian;
        return d.day <= monthLength(p, d.year, d.month);
    }
    return d.day <= monthLength(plain(c), d.year, d.month);
}

double secondsOf(const DateTime& d) { return d.hour * 3600.0 + d.minute * 60.0 + d.second; }

const std::regex& dateTimePattern() {
    // YYYY-M-D, then optionally [T ]H:M[:S[.f]], then optionally Z, UTC or a numeric offset.
    static const std::regex r(R"(^\s*(-?\d{1,8})-(\d{1,2})-(\d{1,2})(?:[T ]+(\d{1,2}):(\d{1,2})(?::(\d{1,2}(?:\.\d*)?))?)?)"
                              R"(\s*(Z|UTC|[+-]\d{1,2}(?::?\d{2})?)?\s*$)",
                              std::regex::icase);
    return r;
}

bool parseDateTime(const std::string& text, DateTime& d, double& offsetSeconds) {
    std::smatch m;
    if (!std::regex_match(text, m, dateTimePattern())) return false;
    d.year = std::stoll(m[1]);
    d.month = std::stoi(m[2]);
    d.day = std::stoi(m[3]);
    d.hour = m[4].matched ? std::stoi(m[4]) : 0;
    d.minute = m[5].matched ? std::stoi(m[5]) : 0;
    d.second = m[6].matched ? std::stod(m[6]) : 0.0;
    offsetSeconds = 0.0;
    std::string tz = m[7].matched ? std::string(m[7]) : std::string();
    if (!tz.empty() && (tz[0] == '+' || tz[0] == '-')) {
        std::string digits;
        for (char c : tz.substr(1))
            if (c != ':') digits += c;
        int hh = std::stoi(digits.substr(0, digits.size() > 2 ? digits.size() - 2 : digits.size()));
        int mm = digits.size() > 2 ? std::stoi(digits.substr(digits.size() - 2)) : 0;
        offsetSeconds = (tz[0] == '-' ? -1.0 : 1.0) * (hh * 3600.0 + mm * 60.0);
    }
    return d.hour < 24 && d.minute < 60 && d.second < 61.0;
}

}  // namespace

bool isTimeUnits(const std::string& units) { return lower(units).find(" since ") != std::string::npos; }

TimeUnits parseTimeUnits(const std::string& units, const std::string& calendar, const std::string& what) {
    TimeUnits u;
    std::string cal = lower(trim(calendar));
    u.calendarName = cal.empty() ? "standard" : cal;
    if (cal.empty() || cal == "standard" || cal == "gregorian") u.calendar = Calendar::Standard;
    else if (cal == "proleptic_gregorian") u.calendar = Calendar::ProlepticGregorian;
    else if (cal == "julian") u.calendar = Calendar::Julian;
    else if (cal == "noleap" || cal == "365_day") u.calendar = Calendar::NoLeap;
    else if (cal == "all_leap" || cal == "366_day") u.calendar = Calendar::AllLeap;
    else if (cal == "360_day") u.calendar = Calendar::Day360;
    else
        throw FileError(what + ": calendar '" + calendar + "' is not one of standard, gregorian, proleptic_gregorian, julian, "
                        "noleap, 365_day, all_leap, 366_day, 360_day");
    std::string l = lower(trim(units));
    auto since = l.find(" since ");
    if (since == std::string::npos) throw FileError(what + ": time units '" + units + "' are not 'UNIT since DATE'");
    std::string unit = trim(l.substr(0, since));
    if (unit == "second" || unit == "seconds" || unit == "sec" || unit == "secs" || unit == "s") u.secondsPerUnit = 1.0;
    else if (unit == "minute" || unit == "minutes" || unit == "min" || unit == "mins") u.secondsPerUnit = 60.0;
    else if (unit == "hour" || unit == "hours" || unit == "hr" || unit == "hrs" || unit == "h") u.secondsPerUnit = 3600.0;
    else if (unit == "day" || unit == "days" || unit == "d") u.secondsPerUnit = 86400.0;
    else
        throw FileError(what + ": time unit '" + unit + "' in '" + units +
                        "' is not seconds, minutes, hours or days (CF months and years have no fixed length)");
    double offset = 0.0;
    if (!parseDateTime(l.substr(since + 7), u.epoch, offset) || !exists(u.calendar, u.epoch))
        throw FileError(what + ": reference date in time units '" + units + "' is not a date of the " + u.calendarName +
                        " calendar");
    // A zone offset moves the epoch to UTC.
    u.epoch.second -= offset;
    return u;
}

DateTime parseIsoDate(const std::string& text, const std::string& what) {
    DateTime d;
    double offset = 0.0;
    if (!parseDateTime(text, d, offset) || offset != 0.0)
        throw UsageError(what + ": '" + text + "' is neither a time index nor a date YYYY-MM-DD[THH:MM[:SS]]");
    return d;
}

DateTime decodeTime(const TimeUnits& u, double value) {
    double seconds = value * u.secondsPerUnit + secondsOf(u.epoch);
    if (!std::isfinite(seconds) || std::abs(seconds) > 86400.0 * 366.0 * 1e8)
        throw FileError("time value " + num(value) + " is out of range");
    double dayShift = std::floor(seconds / 86400.0);
    double rest = seconds - dayShift * 86400.0;
    rest = std::round(rest * 1000.0) / 1000.0;  // millisecond resolution
    if (rest >= 86400.0) {
        rest -= 86400.0;
        dayShift += 1.0;
    }
    DateTime d;
    fromAbsoluteDay(u.calendar, absoluteDay(u.calendar, u.epoch.year, u.epoch.month, u.epoch.day) + std::int64_t(dayShift), d);
    d.hour = int(rest / 3600.0);
    d.minute = int((rest - d.hour * 3600.0) / 60.0);
    d.second = rest - d.hour * 3600.0 - d.minute * 60.0;
    return d;
}

double encodeTime(const TimeUnits& u, const DateTime& date, const std::string& what) {
    if (!exists(u.calendar, date))
        throw InputError(what + ": " + formatDate(date) + " is not a date of the " + u.calendarName + " calendar");
    double days = double(absoluteDay(u.calendar, date.year, date.month, date.day) -
                         absoluteDay(u.calendar, u.epoch.year, u.epoch.month, u.epoch.day));
    return (days * 86400.0 + secondsOf(date) - secondsOf(u.epoch)) / u.secondsPerUnit;
}

std::string formatDate(const DateTime& d) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%04lld-%02d-%02d", static_cast<long long>(d.year), d.month, d.day);
    std::string s = buf;
    if (d.hour || d.minute || d.second != 0.0) {
        std::snprintf(buf, sizeof buf, "T%02d:%02d:%02d", d.hour, d.minute, int(d.second));
        s += buf;
        double frac = d.second - std::floor(d.second);
        if (frac >= 0.0005) {
            std::snprintf(buf, sizeof buf, "%.3f", frac);
            s += buf + 1;
        }
    }
    return s;
}

}  // namespace octrace::io::detail
