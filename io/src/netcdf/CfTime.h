#pragma once
// CF time coordinates (internal, no file access): "UNIT since EPOCH" units in the calendars of
// the CF conventions (section 4.4.1), decoded to dates and back.
#include <cstdint>
#include <string>

namespace octrace::io::detail {

enum class Calendar { Standard, ProlepticGregorian, Julian, NoLeap, AllLeap, Day360 };

struct DateTime {
    std::int64_t year = 1;
    int month = 1, day = 1, hour = 0, minute = 0;
    double second = 0.0;
};

/// A decoded time unit: value * secondsPerUnit seconds after `epoch` in `calendar`.
struct TimeUnits {
    double secondsPerUnit = 86400.0;
    DateTime epoch;
    Calendar calendar = Calendar::Standard;
    std::string calendarName = "standard";
};

/// True when `units` has the CF form "UNIT since DATE".
bool isTimeUnits(const std::string& units);

/// Parses CF time units and a calendar name (empty = "standard"; "gregorian", "noleap",
/// "365_day", "all_leap", "366_day", "360_day", "julian", "proleptic_gregorian"). Months and
/// years are refused (no fixed length in CF). @throws FileError naming `what` and the problem.
TimeUnits parseTimeUnits(const std::string& units, const std::string& calendar, const std::string& what);

/// Parses an ISO 8601 date "YYYY-MM-DD", "YYYY-MM-DDTHH:MM[:SS]" (a space may replace the T);
/// no check against a calendar. @throws UsageError naming `what`.
DateTime parseIsoDate(const std::string& text, const std::string& what);

/// Date of a time coordinate value. @throws FileError if the value is not finite or is
/// beyond +-10^8 years.
DateTime decodeTime(const TimeUnits& u, double value);

/// The coordinate value of `date`. @throws InputError if `date` does not exist in the calendar
/// (2001-02-29 anywhere, 2000-02-29 in noleap, 2000-02-31 outside 360_day, 1582-10-10 in standard).
double encodeTime(const TimeUnits& u, const DateTime& date, const std::string& what);

/// "1990-01-15", or "1990-01-15T12:00:00" when the time of day is not midnight.
std::string formatDate(const DateTime& d);

}  // namespace octrace::io::detail
