#include "netcdf/SeaWater.h"

#include <cmath>
#include <numbers>

namespace octrace::io::detail::seawater {

double soundSpeed(double s, double t, double pressureDbar) {
    // Coefficients of Chen and Millero (1977) as printed by Fofonoff and Millard (1983), p. 46-47.
    const double p = pressureDbar / 10.0;  // bars
    const double sr = std::sqrt(std::abs(s));
    const double d = 1.727e-3 - 7.9836e-6 * p;  // S^2 term
    const double b1 = 7.3637e-5 + 1.7945e-7 * t;  // S^(3/2) term
    const double b0 = -1.922e-2 - 4.42e-5 * t;
    const double b = b0 + b1 * p;
    const double a3 = (-3.389e-13 * t + 6.649e-12) * t + 1.100e-10;  // S term
    const double a2 = ((7.988e-12 * t - 1.6002e-10) * t + 9.1041e-9) * t - 3.9064e-7;
    const double a1 = (((-2.0122e-10 * t + 1.0507e-8) * t - 6.4885e-8) * t - 1.2580e-5) * t + 9.4742e-5;
    const double a0 = (((-3.21e-8 * t + 2.006e-6) * t + 7.164e-5) * t - 1.262e-2) * t + 1.389;
    const double a = ((a3 * p + a2) * p + a1) * p + a0;
    const double c3 = (-2.3643e-12 * t + 3.8504e-10) * t - 9.7729e-9;  // pure water
    const double c2 = (((1.0405e-12 * t - 2.5335e-10) * t + 2.5974e-8) * t - 1.7107e-6) * t + 3.1260e-5;
    const double c1 = (((-6.1185e-10 * t + 1.3621e-7) * t - 8.1788e-6) * t + 6.8982e-4) * t + 0.153563;
    const double c0 = ((((3.1464e-9 * t - 1.47800e-6) * t + 3.3420e-4) * t - 5.80852e-2) * t + 5.03711) * t + 1402.388;
    const double c = ((c3 * p + c2) * p + c1) * p + c0;
    return c + (a + b * sr + d * s) * s;
}

namespace {
// Local gravity (m/s^2) with the pressure correction, and the specific-volume integral of the
// standard ocean, Fofonoff and Millard (1983) p. 28.
double gravity(double p, double latitudeDeg) {
    const double x = std::pow(std::sin(latitudeDeg * std::numbers::pi / 180.0), 2);
    return 9.780318 * (1.0 + (5.2788e-3 + 2.36e-5 * x) * x) + 1.092e-6 * p;
}
double geopotential(double p) { return (((-1.82e-15 * p + 2.279e-10) * p - 2.2512e-5) * p + 9.72659) * p; }
double geopotentialSlope(double p) { return ((-4.0 * 1.82e-15 * p + 3.0 * 2.279e-10) * p - 2.0 * 2.2512e-5) * p + 9.72659; }
}  // namespace

double depthFromPressure(double p, double latitudeDeg) { return geopotential(p) / gravity(p, latitudeDeg); }

double pressureFromDepth(double depthM, double latitudeDeg) {
    double p = depthM;  // 1 dbar ~ 1 m: a start within 3 %
    for (int n = 0; n < 20; ++n) {
        const double g = gravity(p, latitudeDeg);
        const double f = geopotential(p) / g - depthM;
        const double df = (geopotentialSlope(p) * g - geopotential(p) * 1.092e-6) / (g * g);
        const double step = f / df;
        p -= step;
        if (std::abs(step) < 1e-9) break;
    }
    return p;
}

double adiabaticLapseRate(double s, double t, double p) {
    const double ds = s - 35.0;
    return (((-2.1687e-16 * t + 1.8676e-14) * t - 4.6206e-13) * p +
            ((2.7759e-12 * t - 1.1351e-10) * ds + ((-5.4481e-14 * t + 8.733e-12) * t - 6.7795e-10) * t + 1.8741e-8)) *
               p +
           (-4.2393e-8 * t + 1.8932e-6) * ds + ((6.6228e-10 * t - 6.836e-8) * t + 8.5258e-6) * t + 3.5803e-5;
}

double adiabaticTemperature(double s, double t0, double p0, double pr) {
    // Runge-Kutta step of Fofonoff (1977) with the constants of Fofonoff and Millard (1983) p. 44.
    double p = p0, t = t0;
    const double h = pr - p;
    double xk = h * adiabaticLapseRate(s, t, p);
    t += 0.5 * xk;
    double q = xk;
    p += 0.5 * h;
    xk = h * adiabaticLapseRate(s, t, p);
    t += 0.29289322 * (xk - q);
    q = 0.58578644 * xk + 0.121320344 * q;
    xk = h * adiabaticLapseRate(s, t, p);
    t += 1.707106781 * (xk - q);
    q = 3.414213562 * xk - 4.121320344 * q;
    p += 0.5 * h;
    xk = h * adiabaticLapseRate(s, t, p);
    return t + (xk - 2.0 * q) / 6.0;
}

}  // namespace octrace::io::detail::seawater
