// The UNESCO 1983 algorithms against the check values printed with them in Fofonoff and
// Millard (1983), Unesco Technical Papers in Marine Science 44.
#include "netcdf/SeaWater.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace octrace::io::detail;

TEST(SeaWater, SoundSpeedMatchesTheChenMilleroCheckValue) {
    EXPECT_NEAR(seawater::soundSpeed(40.0, 40.0, 10000.0), 1731.995, 0.0005);
    // Fresh water at the surface is Chen and Millero's pure-water term alone: C0(T) at P = 0.
    EXPECT_NEAR(seawater::soundSpeed(0.0, 0.0, 0.0), 1402.388, 1e-9);
}

TEST(SeaWater, SoundSpeedOfTypicalSeaWaterIsNearFifteenHundred) {
    // Plausibility, not a check value: S = 35, T = 10 degC at the surface is about 1490 m/s by
    // every sea-water equation; speed rises with pressure (about 1.6 m/s per 100 dbar).
    EXPECT_NEAR(seawater::soundSpeed(35.0, 10.0, 0.0), 1490.0, 1.0);
    EXPECT_NEAR(seawater::soundSpeed(35.0, 10.0, 1000.0) - seawater::soundSpeed(35.0, 10.0, 0.0), 16.5, 1.0);
}

TEST(SeaWater, DepthFromPressureMatchesTheCheckValue) {
    EXPECT_NEAR(seawater::depthFromPressure(10000.0, 30.0), 9712.653, 0.0005);
    EXPECT_EQ(seawater::depthFromPressure(0.0, 30.0), 0.0);
}

TEST(SeaWater, PressureFromDepthInvertsTheDepthFormula) {
    EXPECT_NEAR(seawater::pressureFromDepth(9712.653, 30.0), 10000.0, 0.001);
    for (double lat : {-75.0, 0.0, 45.0, 89.0})
        for (double z : {0.0, 10.0, 500.0, 5000.0})
            EXPECT_NEAR(seawater::depthFromPressure(seawater::pressureFromDepth(z, lat), lat), z, 1e-6);
    // Pressure grows faster than depth, more so toward the poles (stronger gravity).
    EXPECT_GT(seawater::pressureFromDepth(5000.0, 60.0), seawater::pressureFromDepth(5000.0, 0.0));
    // Independent cross-check: Saunders (1981), J. Phys. Oceanogr. 11, 573-574,
    // p = ((1 - c1) - sqrt((1 - c1)^2 - 8.84e-6 z)) / 4.42e-6, c1 = (5.92 + 5.25 sin^2 lat) 1e-3,
    // which he states agrees with the UNESCO formula to about 0.1 %.
    for (double lat : {0.0, 30.0, 45.0, 70.0})
        for (double z : {100.0, 1000.0, 5000.0}) {
            double s2 = std::pow(std::sin(lat * std::numbers::pi / 180.0), 2);
            double c1 = (5.92 + 5.25 * s2) * 1e-3;
            double saunders = ((1.0 - c1) - std::sqrt((1.0 - c1) * (1.0 - c1) - 8.84e-6 * z)) / 4.42e-6;
            EXPECT_NEAR(seawater::pressureFromDepth(z, lat), saunders, 1e-3 * saunders) << lat << " " << z;
        }
}

TEST(SeaWater, AdiabaticLapseRateAndPotentialTemperatureMatchTheCheckValues) {
    EXPECT_NEAR(seawater::adiabaticLapseRate(40.0, 40.0, 10000.0), 3.255976e-4, 5e-11);
    EXPECT_NEAR(seawater::adiabaticTemperature(40.0, 40.0, 10000.0, 0.0), 36.89073, 0.000005);
    // Back again: the in-situ temperature from the potential temperature.
    EXPECT_NEAR(seawater::adiabaticTemperature(40.0, 36.89073, 0.0, 10000.0), 40.0, 0.0001);
}
