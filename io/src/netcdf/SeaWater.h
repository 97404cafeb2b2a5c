#pragma once
// Properties of sea water from the UNESCO 1983 algorithms (internal, no file access):
//   N. P. Fofonoff and R. C. Millard Jr, "Algorithms for computation of fundamental properties
//   of seawater", Unesco Technical Papers in Marine Science 44, UNESCO 1983.
// Units as there: salinity on the Practical Salinity Scale 1978, temperature in degrees Celsius
// (IPTS-68; ITS-90 values differ by a factor 1.00024, under 0.01 degC in the ocean), pressure in
// decibars (sea pressure, 0 at the surface), depth in metres (positive down), latitude in degrees.

namespace octrace::io::detail::seawater {

/// Speed of sound in m/s: Chen and Millero (1977), J. Acoust. Soc. Am. 62, 1129-1135, in the
/// form of Fofonoff and Millard (1983) section 9 ("SVEL"). Valid for 0..40 degC, 0..40 PSS-78,
/// 0..10000 dbar. Check value: 1731.995 m/s for S = 40, T = 40 degC, P = 10000 dbar.
double soundSpeed(double salinity, double temperature, double pressureDbar);

/// Depth in metres from pressure, Fofonoff and Millard (1983) section 8 ("DEPTH"; Saunders and
/// Fofonoff 1976, standard ocean of 0 degC and 35 PSS-78). Check value: 9712.653 m for
/// P = 10000 dbar at 30 degrees latitude.
double depthFromPressure(double pressureDbar, double latitudeDeg);

/// Pressure in dbar at `depthM`: the inverse of depthFromPressure (Newton iteration to 1e-9
/// dbar), so the pair is consistent to the check value above.
double pressureFromDepth(double depthM, double latitudeDeg);

/// Adiabatic lapse rate in degC per dbar, Fofonoff and Millard (1983) section 6 ("ATG";
/// Bryden 1973). Check value: 3.255976e-4 for S = 40, T = 40 degC, P = 10000 dbar.
double adiabaticLapseRate(double salinity, double temperature, double pressureDbar);

/// Temperature of a parcel moved adiabatically from `pressureDbar` to `referenceDbar`,
/// Fofonoff and Millard (1983) section 7 ("THETA"; Fofonoff 1977, fourth-order Runge-Kutta).
/// Potential temperature: referenceDbar = 0; in-situ temperature from potential temperature:
/// pressureDbar = 0, referenceDbar = the in-situ pressure. Check value: 36.89073 degC for
/// S = 40, T = 40 degC, P = 10000 dbar, reference 0.
double adiabaticTemperature(double salinity, double temperature, double pressureDbar, double referenceDbar);

}  // namespace octrace::io::detail::seawater
