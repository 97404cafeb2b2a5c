#include "netcdf/CfTime.h"
#include "IoTestSupport.h"

#include "octrace/util/Error.h"

using namespace octrace;
using namespace octrace::io::detail;

namespace {
std::string decoded(const std::string& units, const std::string& calendar, double value) {
    return formatDate(decodeTime(parseTimeUnits(units, calendar, "t"), value));
}
double encoded(const std::string& units, const std::string& calendar, const std::string& date) {
    return encodeTime(parseTimeUnits(units, calendar, "t"), parseIsoDate(date, "--time"), "--time");
}
}  // namespace

TEST(CfTime, StandardCalendarIsGregorianFromItsSwitchAndJulianBefore) {
    EXPECT_EQ(decoded("days since 1900-01-01 00:00:00", "", 0.0), "1900-01-01");
    EXPECT_EQ(decoded("days since 1970-01-01", "gregorian", 19358.5), "2023-01-01T12:00:00");  // Unix day 19358
    EXPECT_EQ(decoded("hours since 1990-1-1 0:0:0", "standard", 24.0 * 59.0), "1990-03-01");
    // 1582-10-04 (Julian) is followed by 1582-10-15 (Gregorian); 1500 was a Julian leap year.
    EXPECT_EQ(decoded("days since 1582-10-04", "standard", 1.0), "1582-10-15");
    EXPECT_EQ(decoded("days since 1500-02-28", "standard", 1.0), "1500-02-29");
    EXPECT_EQ(decoded("days since 1500-02-28", "proleptic_gregorian", 1.0), "1500-03-01");
    EXPECT_EQ(decoded("days since 1582-10-04", "proleptic_gregorian", 1.0), "1582-10-05");
    EXPECT_EQ(decoded("days since 1582-10-04", "julian", 1.0), "1582-10-05");
    EXPECT_THROW_WITH(encoded("days since 1900-01-01", "standard", "1582-10-10"), InputError,
                      "1582-10-10 is not a date of the standard calendar");
}

TEST(CfTime, ModelCalendars) {
    EXPECT_EQ(decoded("days since 2000-01-01", "noleap", 59.0), "2000-03-01");
    EXPECT_EQ(decoded("days since 2000-01-01", "365_day", 365.0), "2001-01-01");
    EXPECT_EQ(decoded("days since 2001-01-01", "all_leap", 59.0), "2001-02-29");
    EXPECT_EQ(decoded("days since 2001-01-01", "366_day", 366.0), "2002-01-01");
    EXPECT_EQ(decoded("days since 2000-01-01", "360_day", 59.0), "2000-02-30");
    EXPECT_EQ(decoded("days since 2000-01-01", "360_day", 360.0 * 10 + 15.5), "2010-01-16T12:00:00");
    EXPECT_EQ(encoded("days since 2000-01-01", "360_day", "2000-02-30"), 59.0);
    EXPECT_EQ(encoded("days since 2000-01-01", "noleap", "2003-01-01"), 3 * 365.0);
    EXPECT_THROW_WITH(encoded("days since 2000-01-01", "noleap", "2000-02-29"), InputError,
                      "2000-02-29 is not a date of the noleap calendar");
    EXPECT_THROW_WITH(encoded("days since 2000-01-01", "standard", "2000-02-31"), InputError, "not a date");
}

TEST(CfTime, UnitsOffsetsAndRoundTrips) {
    EXPECT_EQ(decoded("seconds since 1970-01-01T00:00:00Z", "", 86400.0 * 365 + 3661), "1971-01-01T01:01:01");
    EXPECT_EQ(decoded("minutes since 2020-02-28 23:30", "", 60.0), "2020-02-29T00:30:00");
    EXPECT_EQ(decoded("days since 2000-01-01 00:00 +06:00", "", 0.0), "1999-12-31T18:00:00");
    EXPECT_EQ(decoded("days since 0001-01-01", "proleptic_gregorian", -1.0), "0000-12-31");
    EXPECT_EQ(encoded("hours since 1800-01-01", "standard", "1800-01-02T06:00"), 30.0);
    for (const char* cal : {"standard", "proleptic_gregorian", "julian", "noleap", "all_leap", "360_day"})
        for (double v : {-100000.0, -1.0, 0.0, 31.0, 365.25, 12345.0, 800000.0}) {
            TimeUnits u = parseTimeUnits("days since 1850-01-01", cal, "t");
            EXPECT_NEAR(encodeTime(u, decodeTime(u, v), "t"), v, 1e-6) << cal << " " << v;
        }
}

TEST(CfTime, RefusesWhatCfDoesNotDefine) {
    EXPECT_THROW_WITH(parseTimeUnits("months since 2000-01-01", "", "f.nc: time"), FileError,
                      "f.nc: time: time unit 'months'");
    EXPECT_THROW_WITH(parseTimeUnits("days since 2000-01-01", "lunar", "f.nc: time"), FileError, "calendar 'lunar'");
    EXPECT_THROW_WITH(parseTimeUnits("days since yesterday", "", "f.nc: time"), FileError, "reference date");
    EXPECT_THROW_WITH(parseIsoDate("2000/01/01", "--time"), UsageError, "neither a time index nor a date");
    EXPECT_THROW_WITH(parseIsoDate("2000-01-01T25:00", "--time"), UsageError, "neither");
}
