// The channel frequency class filter of SAE J211/1 (rev. 2014, appendix C; also ISO 6487): a
// second-order Butterworth low-pass run forwards then backwards over the record, which makes it
// a four-pole filter with no phase shift. Crash tests report forces filtered this way (CFC 600
// or 1000 for loads), so that a simulated crushing force can be read against a load cell's.
#pragma once

#include <vector>

namespace shard {

struct CfcCoefficients {
  double a0 = 0, a1 = 0, a2 = 0, b1 = 0, b2 = 0;
};

/// The coefficients of one pass for channel class `cfc` (60, 180, 600, 1000) at sample period T:
/// ω_d = 2π·CFC·2.0775, ω_a = tan(ω_d T/2), a0 = ω_a²/(1 + √2 ω_a + ω_a²), a1 = 2a0, a2 = a0,
/// b1 = −2(ω_a² − 1)/(1 + √2 ω_a + ω_a²), b2 = (−1 + √2 ω_a − ω_a²)/(1 + √2 ω_a + ω_a²).
CfcCoefficients cfc_coefficients(double cfc, double sample_period);

/// The record filtered forwards and backwards, y_t = a0 x_t + a1 x_t−1 + a2 x_t−2 + b1 y_t−1 +
/// b2 y_t−2, each pass started from the record's end value held constant (no start-up step).
std::vector<double> cfc_filter(const std::vector<double>& samples, double cfc, double sample_period);

/// A record sampled at irregular times resampled at period T by linear interpolation, from the
/// first time to the last.
std::vector<double> resample(const std::vector<double>& times, const std::vector<double>& values, double period);

}  // namespace shard
