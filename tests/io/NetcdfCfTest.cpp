// CF interpretation on files written by GDAL in the test (tests/io/CfFileWriter.h): packing and
// masking, depth positive up or down, depth ranges, time steps in CF calendars (curvilinear
// grids: CurvilinearGridTest.cpp), grids without coordinate variables, and sound speed derived from T and S.
#include "CfFileWriter.h"
#include "IoTestSupport.h"
#include "netcdf/SeaWater.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>

using namespace octrace;
using test::CfFileWriter;

namespace {

const std::vector<double> kLon = {10, 20, 30, 40}, kLat = {-10, 0, 10}, kDepth = {0, 100, 500};

// Longitude, latitude and a vertical axis (`levels` with `positive`) on `w`.
void horizontalAndVertical(CfFileWriter& w, const std::string& vertical, const std::vector<double>& levels,
                           const std::string& positive) {
    w.coordinate("lon", kLon, {{"units", "degrees_east"}, {"standard_name", "longitude"}});
    w.coordinate("lat", kLat, {{"units", "degrees_north"}, {"standard_name", "latitude"}});
    std::map<std::string, std::string> attrs = {{"units", "m"}, {"axis", "Z"}};
    if (!positive.empty()) attrs["positive"] = positive;
    w.coordinate(vertical, levels, attrs);
}

// 100 k + 10 j + i over (level k, lat j, lon i), plus `base`.
std::vector<double> ramp(double base = 0.0) {
    std::vector<double> v;
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) v.push_back(base + 100 * k + 10 * j + i);
    return v;
}

io::FieldRequest var(const std::string& name) {
    io::FieldRequest r;
    r.variable = name;
    return r;
}

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

}  // namespace

// Packed int16: _FillValue and missing_value mark cells, valid_range / valid_min / valid_max are
// compared with the packed numbers (before scale_factor and add_offset), the rest is unpacked.
TEST(NetcdfCf, PackedShortsAreMaskedBeforeUnpackingThenUnpacked) {
    test::TempDir dir;
    const std::string path = dir.file("packed.nc");
    {
        CfFileWriter w(path);
        horizontalAndVertical(w, "depth", kDepth, "down");
        std::vector<double> raw = ramp();
        raw[0] = -32767;  // _FillValue           (k 0, j 0, i 0)
        raw[1] = -32000;  // missing_value        (k 0, j 0, i 1)
        raw[2] = 3500;    // beyond valid_range as packed; 45 once unpacked, inside it
        raw[3] = -3001;   // below valid_range
        auto t = w.variable("temp", {"depth", "lat", "lon"}, GDT_Int16, raw,
                            {{"units", "degC"}, {"standard_name", "sea_water_temperature"}});
        t->SetNoDataValue(-32767.0);
        t->SetScale(0.01);
        t->SetOffset(10.0);
        CfFileWriter::numbers(*t, "missing_value", GDT_Int16, {-32000});
        CfFileWriter::numbers(*t, "valid_range", GDT_Int16, {-3000, 3000});
        // The same numbers with valid_min / valid_max instead of valid_range.
        auto s = w.variable("salt", {"depth", "lat", "lon"}, GDT_Int16, raw, {{"units", "1e-3"}});
        s->SetNoDataValue(-32767.0);
        s->SetScale(0.01);
        s->SetOffset(10.0);
        CfFileWriter::numbers(*s, "missing_value", GDT_Int16, {-32000});
        CfFileWriter::numbers(*s, "valid_min", GDT_Int16, {-3000});
        CfFileWriter::numbers(*s, "valid_max", GDT_Int16, {3000});
    }
    for (const char* name : {"temp", "salt"}) {
        SCOPED_TRACE(name);
        ScalarField f = io::NetcdfReader::read(path, var(name));
        ASSERT_EQ(f.dims, ivec3(4, 3, 3));
        const int top = 2;  // stored level 0 (0 m) is the highest z
        for (int i = 0; i < 4; ++i) EXPECT_FALSE(f.isValid(f.index(i, 0, top))) << i;
        EXPECT_EQ(f.validCount(), 36u - 4u);
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 4; ++i) {
                    std::size_t idx = f.index(i, j, 2 - k);
                    if (f.isValid(idx)) {
                        EXPECT_EQ(f.values[idx], float((100 * k + 10 * j + i) * 0.01 + 10.0)) << k << j << i;
                    }
                }
    }
    // --var also takes the CF standard_name.
    EXPECT_EQ(io::NetcdfReader::read(path, var("sea_water_temperature")).name, "temp");
    std::string info = io::NetcdfReader::describe(path);
    for (const char* s : {"standard_name sea_water_temperature", "_FillValue -32767", "missing_value -32000",
                          "valid_range -3000 3000", "scale_factor 0.01", "add_offset 10", "valid_min -3000",
                          "valid_max 3000"})
        EXPECT_NE(info.find(s), std::string::npos) << "missing '" << s << "' in:\n" << info;
}

TEST(NetcdfCf, EveryMaskedSampleIsRefusedAsEmptyNamingTheAttributes) {
    test::TempDir dir;
    const std::string path = dir.file("all_masked.nc");
    {
        CfFileWriter w(path);
        horizontalAndVertical(w, "depth", kDepth, "down");
        auto t = w.variable("temp", {"depth", "lat", "lon"}, GDT_Int16, std::vector<double>(36, 5000));
        CfFileWriter::numbers(*t, "valid_max", GDT_Int16, {4000});
    }
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), EmptyResultError,
                      "has no valid sample (all missing_value/_FillValue, outside valid_min/valid_max/valid_range");
}

// The same ocean stored as depth positive down and as height positive up (negative below the
// surface) reads identically; --depth-range selects in metres below the surface either way.
TEST(NetcdfCf, DepthPositiveDownAndHeightPositiveUpGiveTheSameField) {
    test::TempDir dir;
    const std::string down = dir.file("down.nc"), up = dir.file("up.nc");
    {
        CfFileWriter w(down);
        horizontalAndVertical(w, "depth", kDepth, "down");
        w.variable("temp", {"depth", "lat", "lon"}, GDT_Float32, ramp());
    }
    {
        CfFileWriter w(up);
        horizontalAndVertical(w, "z", {0, -100, -500}, "up");
        w.variable("temp", {"z", "lat", "lon"}, GDT_Float32, ramp());
    }
    io::FieldRequest scaled;
    scaled.verticalScale = 10;
    ScalarField a = io::NetcdfReader::read(down, scaled), b = io::NetcdfReader::read(up, scaled);
    EXPECT_EQ(a.values, b.values);
    EXPECT_EQ(a.coords[2], (std::vector<double>{-5.0, -1.0, 0.0}));  // km * 10, deepest first
    EXPECT_EQ(b.coords[2], a.coords[2]);
    EXPECT_EQ(a.values[a.index(3, 2, 0)], 200.0f + 20.0f + 3.0f);  // 500 m, lat 10, lon 40

    // A vertical axis whose `positive` says up but whose values grow downward would be drawn
    // upside down: the attribute decides, as CF says.
    {
        CfFileWriter w(dir.file("up_positive_values.nc"));
        horizontalAndVertical(w, "depth", kDepth, "up");
        w.variable("temp", {"depth", "lat", "lon"}, GDT_Float32, ramp());
    }
    ScalarField c = io::NetcdfReader::read(dir.file("up_positive_values.nc"), scaled);
    EXPECT_EQ(c.coords[2], (std::vector<double>{0.0, 1.0, 5.0}));  // 500 m above the surface at the top
    EXPECT_EQ(c.values[c.index(3, 2, 2)], 223.0f);

    for (const auto& path : {down, up}) {
        io::FieldRequest r = scaled;
        r.hasDepthRange = true;
        r.depthRange[0] = 50;
        r.depthRange[1] = 600;
        ScalarField f = io::NetcdfReader::read(path, r);
        ASSERT_EQ(f.dims.z, 2) << path;
        EXPECT_EQ(f.origin.z, -5.0);
        EXPECT_EQ(f.spacing.z, 4.0);
        EXPECT_EQ(f.values[f.index(0, 0, 1)], 100.0f);
        EXPECT_TRUE(hasNote(f, "2 levels 100 .. 500 m (depth range 50,600 m)"));
        r.depthRange[0] = 200;
        EXPECT_THROW_WITH(io::NetcdfReader::read(path, r), EmptyResultError,
                          "depth range 200,600 m holds 1 level(s), need at least 2 (the file's levels run 0 .. 500 m)");
    }
}

namespace {

// temp(time, depth, lat, lon) = 1000 * step + ramp, time in days since 2000-01-01 in `calendar`.
void timeFile(const std::string& path, const std::string& calendar, const std::vector<double>& days) {
    CfFileWriter w(path);
    w.coordinate("time", days, {{"units", "days since 2000-01-01"}, {"calendar", calendar}, {"standard_name", "time"}});
    horizontalAndVertical(w, "depth", kDepth, "down");
    std::vector<double> v;
    for (std::size_t t = 0; t < days.size(); ++t)
        for (double x : ramp(1000.0 * double(t))) v.push_back(x);
    w.variable("temp", {"time", "depth", "lat", "lon"}, GDT_Float32, v);
}

float surfaceCorner(const ScalarField& f) { return f.values[f.index(0, 0, f.dims.z - 1)]; }

io::FieldRequest at(const std::string& time) {
    io::FieldRequest r;
    r.time = time;
    return r;
}

}  // namespace

// 365_day: day 59 after 2000-01-01 is 1 March 2000 (no 29 February); in the standard calendar
// it would be 29 February.
TEST(NetcdfCf, TimeStepsByIndexOrDateIn365DayCalendar) {
    test::TempDir dir;
    const std::string path = dir.file("noleap.nc");
    timeFile(path, "365_day", {0, 59, 424});
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(path, at("2"))), 2000.0f);
    ScalarField march = io::NetcdfReader::read(path, at("2000-03-01"));
    EXPECT_EQ(surfaceCorner(march), 1000.0f);
    EXPECT_TRUE(hasNote(march, "`time` 2000-03-01: nearest step 1 of 3 (2000-03-01, calendar 365_day)"));
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(path, at("2001-02-20"))), 2000.0f);  // nearest: 2001-03-01
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, at("2000-02-29")), InputError,
                      "2000-02-29 is not a date of the 365_day calendar");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, at("3")), InputError,
                      "dimension 'time' (time) has 3 step(s), indices 0..2; `time` 3 is beyond them");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, at("March")), UsageError, "neither a time index nor a date");
    {
        test::LogCapture log;
        ScalarField first = io::NetcdfReader::read(path, {});
        EXPECT_EQ(surfaceCorner(first), 0.0f);
        ASSERT_EQ(log.warnings.size(), 1u);
        EXPECT_NE(log.warnings[0].find("first of 3 steps used (2000-01-01, calendar 365_day); choose one with `time`"),
                  std::string::npos)
            << log.warnings[0];
    }
    {
        test::LogCapture log;
        (void)io::NetcdfReader::read(path, at("2010-01-01"));
        ASSERT_EQ(log.warnings.size(), 1u);
        EXPECT_NE(log.warnings[0].find("the date lies outside the time axis 2000-01-01 .. 2001-03-01"), std::string::npos);
    }
    test::LogCapture log;  // the grid part reads the first step
    std::string info = io::NetcdfReader::describe(path);
    EXPECT_NE(info.find("time = 3: time, units 'days since 2000-01-01', 0 .. 424, calendar 365_day: 2000-01-01 .. 2001-03-01"),
              std::string::npos)
        << info;
}

TEST(NetcdfCf, TimeStepsIn360DayAndStandardCalendars) {
    test::TempDir dir;
    timeFile(dir.file("d360.nc"), "360_day", {0, 59, 60});
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(dir.file("d360.nc"), at("2000-02-30"))), 1000.0f);  // day 59
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(dir.file("d360.nc"), at("2000-03-01"))), 2000.0f);  // day 60
    timeFile(dir.file("standard.nc"), "standard", {0, 59, 60});
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(dir.file("standard.nc"), at("2000-02-29"))), 1000.0f);
    EXPECT_EQ(surfaceCorner(io::NetcdfReader::read(dir.file("standard.nc"), at("2000-03-01"))), 2000.0f);
    EXPECT_THROW_WITH(io::NetcdfReader::read(dir.file("standard.nc"), at("2000-02-30")), InputError,
                      "is not a date of the standard calendar");
}

TEST(NetcdfCf, TimeOnAVariableWithoutTimeAxisIsRefused) {
    test::TempDir dir;
    const std::string path = dir.file("no_time.nc");
    {
        CfFileWriter w(path);
        horizontalAndVertical(w, "depth", kDepth, "down");
        w.variable("temp", {"depth", "lat", "lon"}, GDT_Float32, ramp());
    }
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, at("0")), InputError,
                      "`time` 0: variable temp(depth, lat, lon) has no time axis");
}

// No coordinate variable at all: the grid indices are the world coordinates, with a warning.
TEST(NetcdfCf, GridWithoutCoordinateVariablesUsesIndicesWithAWarning) {
    test::TempDir dir;
    const std::string path = dir.file("bare.nc");
    {
        CfFileWriter w(path);
        w.dimension("k", 3);
        w.dimension("j", 3);
        w.dimension("i", 4);
        w.variable("density", {"k", "j", "i"}, GDT_Float32, ramp());
    }
    test::LogCapture log;
    ScalarField f = io::NetcdfReader::read(path, {});
    ASSERT_EQ(log.warnings.size(), 1u);
    EXPECT_NE(log.warnings[0].find("variable 'density': no coordinate variable for dimension(s) 'i', 'j', 'k': grid "
                                   "indices used as world units"),
              std::string::npos)
        << log.warnings[0];
    EXPECT_EQ(f.dims, ivec3(4, 3, 3));
    EXPECT_EQ(f.origin, dvec3(0.0, 0.0, 0.0));
    EXPECT_EQ(f.spacing, dvec3(1.0, 1.0, 1.0));
    EXPECT_EQ(f.values[f.index(3, 2, 1)], 123.0f);
    io::FieldRequest region = var("density");
    region.hasDepthRange = true;
    region.depthRange[1] = 100;
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, region), InputError,
                      "a depth range needs a longitude/latitude/depth grid");
}

// Sound speed from T and S where the file has none: UNESCO 1983 at the pressure of each depth
// and latitude; potential temperature in kelvin is brought to in-situ degrees Celsius first.
TEST(NetcdfCf, SoundSpeedIsDerivedFromTemperatureAndSalinity) {
    test::TempDir dir;
    for (bool potential : {false, true}) {
        const std::string path = dir.file(potential ? "theta.nc" : "insitu.nc");
        std::vector<double> t, s;
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 4; ++i) {
                    t.push_back(20.0 - 5.0 * k + 0.5 * i + (potential ? 273.15 : 0.0));
                    s.push_back(34.0 + 0.2 * j);
                }
        {
            CfFileWriter w(path);
            horizontalAndVertical(w, "depth", kDepth, "down");
            if (potential)
                w.variable("thetao", {"depth", "lat", "lon"}, GDT_Float64, t,
                           {{"units", "K"}, {"standard_name", "sea_water_potential_temperature"}});
            else
                w.variable("TEMP", {"depth", "lat", "lon"}, GDT_Float64, t, {{"units", "degC"}});
            w.variable("so", {"depth", "lat", "lon"}, GDT_Float64, s,
                       {{"units", "1e-3"}, {"standard_name", "sea_water_salinity"}});
        }
        SCOPED_TRACE(path);
        test::LogCapture log;
        io::FieldRequest r = var("sound_speed");
        r.verticalScale = 1;
        ScalarField f = io::NetcdfReader::read(path, r);
        EXPECT_EQ(f.name, "sound_speed");
        EXPECT_EQ(f.units, "m/s");
        EXPECT_TRUE(hasNote(f, std::string("sound_speed derived from ") + (potential ? "thetao" : "TEMP")));
        EXPECT_TRUE(hasNote(f, "and so ('1e-3', practical salinity), pressure from depth 'depth' and latitude 'lat'"));
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 4; ++i) {
                    const double p = io::detail::seawater::pressureFromDepth(kDepth[std::size_t(k)], kLat[std::size_t(j)]);
                    const double sal = 34.0 + 0.2 * j;
                    double temp = 20.0 - 5.0 * k + 0.5 * i;
                    if (potential) temp = io::detail::seawater::adiabaticTemperature(sal, temp, 0.0, p);
                    EXPECT_NEAR(f.values[f.index(i, j, 2 - k)], io::detail::seawater::soundSpeed(sal, temp, p), 1e-3)
                        << k << j << i;
                }
        // Sound speed grows with depth at a fixed temperature: the pressure term is there.
        EXPECT_GT(io::detail::seawater::pressureFromDepth(500.0, 10.0), 500.0);
        // The standard name asks for it too.
        EXPECT_EQ(io::NetcdfReader::read(path, var("speed_of_sound_in_sea_water")).values, f.values);
    }
}

TEST(NetcdfCf, SoundSpeedWithoutSalinityNamesWhatIsMissing) {
    test::TempDir dir;
    const std::string path = dir.file("t_only.nc");
    {
        CfFileWriter w(path);
        horizontalAndVertical(w, "depth", kDepth, "down");
        w.variable("temp", {"depth", "lat", "lon"}, GDT_Float32, ramp(), {{"standard_name", "sea_water_temperature"}});
        w.variable("salt_ca", {"depth", "lat", "lon"}, GDT_Float32, ramp(),
                   {{"standard_name", "sea_water_absolute_salinity"}});
    }
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, var("sound_speed")), InputError,
                      "no sound-speed variable, and it cannot be derived from temperature and salinity: no salinity "
                      "variable: salt_ca is sea_water_absolute_salinity (TEOS-10)");
}

// Levitus: sound speed 1500 m/s lies within the North Pacific's range (a minimum near 1480 m/s
// around 1000 m, warm surface water above 1530 m/s).
TEST(NetcdfCf, LevitusSoundSpeedOverTheNorthPacific) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    io::FieldRequest r = var("sound_speed");
    r.hasRegion = true;
    r.region[0] = 120;
    r.region[1] = 180;
    r.region[2] = 10;
    r.region[3] = 60;
    test::LogCapture log;
    ScalarField c = io::NetcdfReader::read(path, r);
    r.variable = "TEMP";
    ScalarField t = io::NetcdfReader::read(path, r);
    EXPECT_EQ(c.dims, ivec3(60, 50, 20));
    EXPECT_EQ(c.valid, t.valid);  // T and S are masked alike in Levitus
    auto [lo, hi] = c.validRange();
    EXPECT_GT(lo, 1440.0f);
    EXPECT_LT(lo, 1490.0f);
    EXPECT_GT(hi, 1530.0f);
    EXPECT_LT(hi, 1560.0f);
}
