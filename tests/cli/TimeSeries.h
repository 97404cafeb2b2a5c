#pragma once
// A small CF time series written for the animation and figure tests.
#include "../io/CfFileWriter.h"

#include <cmath>
#include <string>
#include <vector>

namespace octrace::testcli {

/// Three monthly steps (2000-01-01, 2000-02-01, 2000-03-01; days since 2000-01-01) of TEMP on a
/// 16 x 16 degree, 8-level geographic grid: the distance from the grid's centre, scaled so that
/// the surface `iso` 0.8 is a ball that shrinks step after step; SAL is 30 + step everywhere.
inline void writeTimeSeries(const std::string& path, int steps = 3) {
    octrace::test::CfFileWriter w(path);
    std::vector<double> lon, lat, depth, time;
    for (int i = 0; i < 16; ++i) lon.push_back(i), lat.push_back(i);
    for (int k = 0; k < 8; ++k) depth.push_back(100.0 * k);
    const double days[] = {0.0, 31.0, 60.0, 91.0};
    for (int t = 0; t < steps; ++t) time.push_back(days[t]);
    w.coordinate("time", time, {{"units", "days since 2000-01-01"}, {"calendar", "standard"}, {"axis", "T"}});
    w.coordinate("depth", depth, {{"units", "m"}, {"positive", "down"}});
    w.coordinate("lat", lat, {{"units", "degrees_north"}});
    w.coordinate("lon", lon, {{"units", "degrees_east"}});
    std::vector<double> temp, sal;
    for (int t = 0; t < steps; ++t)
        for (int k = 0; k < 8; ++k)
            for (int j = 0; j < 16; ++j)
                for (int i = 0; i < 16; ++i) {
                    const double x = (i - 7.5) / 7.5, y = (j - 7.5) / 7.5, z = (k - 3.5) / 3.5;
                    temp.push_back(std::sqrt(x * x + y * y + z * z) * (1.0 + 0.35 * t));
                    sal.push_back(30.0 + t);
                }
    w.variable("TEMP", {"time", "depth", "lat", "lon"}, GDT_Float32, temp, {{"units", "degC"}});
    w.variable("SAL", {"time", "depth", "lat", "lon"}, GDT_Float32, sal, {{"units", "psu"}});
    w.close();
}

}  // namespace octrace::testcli
