#pragma once
// The power spectrum of a sampled signal, for the oscillation metric of the force's quality
// (core/haptics/force_quality.h): the discrete Fourier transform of any length, exact up to
// floating-point rounding, in O(N log N) — radix-2 for a power of two, Bluestein's chirp-z
// otherwise — so that a contact of minutes costs milliseconds.
#include <complex>
#include <vector>

namespace bleedsim {

// X_k = Σ_n x_n · e^(−2πi·k·n/N), k = 0 … N−1.
std::vector<std::complex<double>> discrete_fourier_transform(const std::vector<double>& x);

// The share of the mean square in each bin: P_k = |X_k|² / N², so that Σ_k P_k = (1/N) Σ_n x_n²
// (Parseval). Bin k is the frequency min(k, N − k) / (N · sample period): a real signal's power
// at a frequency f > 0 lies half in bin k and half in bin N − k.
std::vector<double> power_spectrum(const std::vector<double>& x);

}  // namespace bleedsim
