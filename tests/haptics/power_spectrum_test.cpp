// The discrete Fourier transform of any length (core/haptics/power_spectrum.cpp) against the
// definition summed in long double, and the power spectrum against Parseval's theorem.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "core/haptics/power_spectrum.h"
#include "tests/haptics/transform_error_bound.h"

namespace bleedsim {
namespace {

// A deterministic signal with every frequency in it: a linear congruential generator's values in [−1, 1).
std::vector<double> rough_signal(std::size_t n) {
  std::vector<double> x(n);
  std::uint64_t state = 12345;
  for (double& v : x) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = double(state >> 11) / double(1ULL << 52) - 1.0;
  }
  return x;
}

// X_k = Σ_n x_n e^(−2πikn/N), summed in long double with the angle reduced exactly (k·n mod N).
std::vector<std::complex<long double>> defining_sum(const std::vector<double>& x) {
  const std::size_t n = x.size();
  const long double pi = 3.141592653589793238462643383279502884L;
  std::vector<std::complex<long double>> out(n);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j) {
      const long double angle = -2 * pi * (long double)((k * j) % n) / (long double)n;
      out[k] += (long double)x[j] * std::complex<long double>(std::cos(angle), std::sin(angle));
    }
  return out;
}

TEST(PowerSpectrum, TheTransformIsTheDefiningSumToItsErrorBound) {
  // 1024: radix-2; 1000 and the prime 997: Bluestein.
  for (const std::size_t n : {std::size_t(1024), std::size_t(1000), std::size_t(997), std::size_t(1)}) {
    const std::vector<double> x = rough_signal(n);
    const std::vector<std::complex<double>> got = discrete_fourier_transform(x);
    const std::vector<std::complex<long double>> want = defining_sum(x);
    ASSERT_EQ(got.size(), n);
    long double error2 = 0, norm2 = 0;
    for (std::size_t k = 0; k < n; ++k) {
      error2 += std::norm(std::complex<long double>(got[k].real(), got[k].imag()) - want[k]);
      norm2 += std::norm(want[k]);
    }
    // The long double sum is exact to about N·2⁻⁶⁴ relative, far inside the bound.
    EXPECT_LE(double(std::sqrt(error2)), test::transform_error(n) * double(std::sqrt(norm2))) << "N = " << n;
  }
}

TEST(PowerSpectrum, ItsBinsSumToTheMeanSquare) {
  // Parseval: Σ_k |X_k|²/N² = (1/N) Σ_n x_n². With ||δX|| ≤ ρ·||X|| the computed sum is within
  // (2ρ + ρ²)·(1/N)Σx² of it, plus N·ε of the summation.
  for (const std::size_t n : {std::size_t(1024), std::size_t(997)}) {
    const std::vector<double> x = rough_signal(n);
    double mean_square = 0;
    for (double v : x) mean_square += v * v / double(n);
    double total = 0;
    for (double p : power_spectrum(x)) total += p;
    const double rho = test::transform_error(n);
    EXPECT_NEAR(total, mean_square, (2 * rho + rho * rho + 2 * double(n) * 2.3e-16) * mean_square) << "N = " << n;
  }
}

TEST(PowerSpectrum, NothingHasNoSpectrum) { EXPECT_TRUE(power_spectrum({}).empty()); }

}  // namespace
}  // namespace bleedsim
