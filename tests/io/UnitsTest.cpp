// Units through UDUNITS-2 (octrace/io/Units.h): lengths of vertical axes, conversions of values
// given with a unit, the CF spellings UDUNITS-2 misreads, and a depth axis in centimetres read
// as the Levitus atlas in metres.
#include "IoTestSupport.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/io/Units.h"

#include <algorithm>
#include <thread>
#include <vector>

using namespace octrace;

TEST(Units, LengthsInAnySpellingUdunitsReadsAreMetres) {
    for (const char* m : {"m", "meter", "meters", "metre", "metres", "METERS", " m "}) EXPECT_DOUBLE_EQ(io::metresPer(m), 1.0) << m;
    for (const char* cm : {"cm", "centimeter", "centimeters", "centimetre", "centimetres"})
        EXPECT_DOUBLE_EQ(io::metresPer(cm), 0.01) << cm;
    for (const char* km : {"km", "kilometer", "kilometres"}) EXPECT_DOUBLE_EQ(io::metresPer(km), 1000.0) << km;
    EXPECT_DOUBLE_EQ(io::metresPer("feet"), 0.3048);
    // Not lengths: temperatures, angles, plain numbers, nothing, unknown words.
    for (const char* other : {"degC", "degrees_east", "1", "10", "", "dbar", "levels", "sigma"})
        EXPECT_EQ(io::metresPer(other), 0.0) << other;
}

TEST(Units, PressuresAreDecibarsWithTheOceanographicDb) {
    EXPECT_DOUBLE_EQ(io::decibarsPer("dbar"), 1.0);
    EXPECT_DOUBLE_EQ(io::decibarsPer("decibars"), 1.0);
    EXPECT_DOUBLE_EQ(io::decibarsPer("db"), 1.0);  // UDUNITS-2 alone: a decibarn (an area)
    EXPECT_DOUBLE_EQ(io::decibarsPer("bar"), 10.0);
    EXPECT_DOUBLE_EQ(io::decibarsPer("hPa"), 0.01);
    EXPECT_DOUBLE_EQ(io::decibarsPer("mbar"), 0.01);
    EXPECT_DOUBLE_EQ(io::decibarsPer("kPa"), 0.1);
    EXPECT_DOUBLE_EQ(io::decibarsPer("Pa"), 1e-4);
    EXPECT_EQ(io::decibarsPer("m"), 0.0);
}

TEST(Units, TemperaturesConvertWithTheirOffsets) {
    EXPECT_DOUBLE_EQ(*io::convertUnits(10.0, "degC", "K"), 283.15);
    EXPECT_NEAR(*io::convertUnits(283.15, "K", "degC"), 10.0, 1e-12);
    EXPECT_NEAR(*io::convertUnits(50.0, "degF", "degC"), 10.0, 1e-12);
    // CF spellings that UDUNITS-2 refuses ("deg C") or misreads ("degrees Celsius" would be an
    // angle times a temperature, 0.01745 K per unit) are the temperature.
    for (const char* c : {"DEG C", "deg C", "degrees Celsius", "degree_Celsius", "degrees_C", "Celsius", "°C"})
        EXPECT_NEAR(*io::convertUnits(10.0, c, "K"), 283.15, 1e-9) << c;
    EXPECT_DOUBLE_EQ(*io::convertUnits(283.15, "deg K", "K"), 283.15);
    EXPECT_EQ(io::normalizedUnits(" DEG C "), "degC");
    EXPECT_EQ(io::normalizedUnits("degrees_east"), "degrees_east");
}

TEST(Units, UnknownOrIncompatibleUnitsGiveNothing) {
    EXPECT_FALSE(io::knownUnits("furlongs per fortnightx"));
    EXPECT_FALSE(io::knownUnits(""));
    EXPECT_FALSE(io::knownUnits("PPT"));
    EXPECT_TRUE(io::knownUnits("degC"));
    EXPECT_FALSE(io::convertUnits(10.0, "m", "degC"));
    EXPECT_FALSE(io::convertUnits(10.0, "nonsense", "K"));
    EXPECT_FALSE(io::convertUnits(10.0, "K", ""));
    EXPECT_DOUBLE_EQ(*io::convertUnits(2.0, "km", "m"), 2000.0);
}

TEST(Units, ConversionsFromManyThreadsAgree) {
    // UDUNITS-2's parser is not thread-safe: the wrapper serialises it. Every thread must get
    // the same answers (and the sanitizer run, no race).
    std::vector<std::thread> threads;
    std::vector<int> wrong(8, 0);
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([t, &wrong] {
            for (int i = 0; i < 200; ++i) {
                if (io::metresPer("centimeters") != 0.01) ++wrong[std::size_t(t)];
                const auto k = io::convertUnits(double(i), "degC", "K");
                if (!k || std::abs(*k - (double(i) + 273.15)) > 1e-9) ++wrong[std::size_t(t)];
            }
        });
    for (auto& th : threads) th.join();
    EXPECT_EQ(std::count(wrong.begin(), wrong.end(), 0), 8);
}

TEST(Units, ADepthAxisInCentimetresReadsAsTheAtlasInMetres) {
    OCTRACE_SHARED_FILE_OR_SKIP(lev, "ocean/levitus_climatology.cdf");
    // tests/data/netcdf/levitus_cm.nc: the atlas's North Atlantic with depth * 100, "centimeters".
    const ScalarField cm = io::NetcdfReader::read(test::testData("netcdf/levitus_cm.nc"), {.variable = "TEMP"});
    const ScalarField m = io::NetcdfReader::read(lev, test::regionRequest("TEMP", 300, 340, 20, 60));
    ASSERT_EQ(cm.dims, m.dims);
    ASSERT_EQ(cm.coords[2].size(), m.coords[2].size());
    for (std::size_t k = 0; k < m.coords[2].size(); ++k) EXPECT_NEAR(cm.coords[2][k], m.coords[2][k], 1e-9) << k;
    EXPECT_DOUBLE_EQ(cm.geographic.verticalScale, m.geographic.verticalScale);
    EXPECT_EQ(cm.values, m.values);
    // The lowest level, 5000 m, is 5 km down times the vertical scale.
    EXPECT_NEAR(m.coords[2].front(), -5.0 * m.geographic.verticalScale, 1e-9);
    const bool said = std::any_of(cm.notes.begin(), cm.notes.end(), [](const std::string& n) {
        return n.find("in centimeters, converted to metres (0.01 m each") != std::string::npos;
    });
    EXPECT_TRUE(said) << "no note on the conversion";
}
