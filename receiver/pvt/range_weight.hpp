#pragma once
// One model of how far a code pseudorange can be trusted, shared by the PVT's weighted
// least squares and every aided mode (tight rows, ultra-tight discriminator rows), so a
// satellite low in the sky weighs the same in each and the modes differ only in what
// they add, not in which satellites they believe.
//
//   sigma^2 = a^2 + (b / sin el)^2 + c^2 10^(-(C/N0)/10)
//
// a: what is left of the orbit, clock and ionosphere models at any elevation; b / sin el:
// what grows with the path through the atmosphere and with ground multipath near the
// horizon (RTKLIB's error model, a = b = 0.5 m); c^2 10^(-(C/N0)/10): the code tracking
// noise of a scalar DLL (c^2 = 3e3 m^2 Hz: 0.3 m at 45 dB-Hz). A channel whose
// discriminator noise is known from its own integration (ultra-tight) puts that in place
// of the last term. sin el is floored at 0.1 (about 6 deg).
//
// The a and b terms are not white: what the models leave changes over minutes. They are
// stated for one pseudorange per satellite per second (the PVT's and tight coupling's
// pace); a filter that takes rows more often (ultra-tight: one per 10 ms integration)
// gets the same error in every row of that second, so each row carries the model variance
// times the rows per second (model_variance_per_row_m2). Taken as white at 100 Hz, the
// model terms would be averaged down a hundredfold against the code noise, every satellite
// would weigh nearly the same, and the low ones, whose model errors are largest, would
// pull the solution (measured: ultra-tight 1.8 m horizontal against tight's 0.6 m with the
// troposphere missing from the signal).
namespace deepnav {

struct RangeErrorModel {
  double floor_m = 0.5;       ///< a
  double elevation_m = 0.5;   ///< b
  double thermal_m2hz = 3e3;  ///< c^2
  double min_sin_elevation = 0.1;

  /// Variance (m^2) of what the range models leave: a^2 + (b / sin el)^2.
  double model_variance_m2(double elevation_rad) const;
  /// The same for one of several rows a second that share it: row_interval_s apart.
  double model_variance_per_row_m2(double elevation_rad, double row_interval_s) const;
  /// Variance (m^2) of a scalar DLL's code noise at C/N0.
  double thermal_variance_m2(double cn0_dbhz) const;
  /// Both together: the variance of a scalar channel's pseudorange.
  double pseudorange_variance_m2(double elevation_rad, double cn0_dbhz) const {
    return model_variance_m2(elevation_rad) + thermal_variance_m2(cn0_dbhz);
  }
};

}  // namespace deepnav
