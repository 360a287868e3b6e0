#pragma once
// How far the computed discrete Fourier transform (core/haptics/power_spectrum.h) may be from the
// exact one, as a share of the exact transform's 2-norm ||X|| = √N·||x|| — the bound the spectrum's
// and the oscillation's tests allow, derived here once.
#include <cmath>
#include <cstddef>
#include <limits>

namespace bleedsim::test {

// Higham, Accuracy and Stability of Numerical Algorithms (2nd ed.), Theorem 24.2: a radix-2 transform
// of length M computed with twiddles accurate to μ is within log2(M)·η / (1 − log2(M)·η) of the exact
// one in relative 2-norm, η = μ + γ4·(√2 + μ), γ4 = 4ε/(1 − 4ε). std::polar's twiddles are within
// μ = 2ε (cos and sin each within an ulp).
inline double radix2_error(std::size_t m) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double mu = 2 * eps, gamma4 = 4 * eps / (1 - 4 * eps), eta = mu + gamma4 * (std::sqrt(2.0) + mu);
  const double l = std::log2(double(m));
  return l * eta / (1 - l * eta);
}

// The relative error of the transform of length N. A power of two is one radix-2 transform. Any other
// N goes through Bluestein's convolution c = IFFT(A·B)/M of a = x·w* with the chirp b (2N − 1 unit
// entries), A and B their transforms of length M, and X_k = w_k*·c_k. With r = radix2_error(M) + 3ε
// (each transform's error, and the chirp's own: an entry within 2ε, its product within ε more):
//   ||δA|| ≤ r·||A|| = r·√M·||a||,  ||δB|| ≤ r·√M·√(2N − 1),  max|B| ≤ 2N − 1,  max|A| ≤ √N·||a||
//   (1/√M)·||δ(A·B)|| ≤ (1/√M)·(||δA||·max|B| + max|A|·||δB|| + ε·||A·B||) ≤ ((1 + √2)·r + ε)·2N·||a||
//   ||δc|| ≤ r·||c|| + (1/√M)·||δ(A·B)||, with ||c|| ≤ max|B|·||a|| ≤ 2N·||a||
// so ||δX|| ≤ (4r + ε)·2N·||x|| + 2ε·||X|| (||a|| = ||x||; the last chirp product), and relative to
// ||X|| = √N·||x||: (4r + ε)·2√N + 2ε.
inline double transform_error(std::size_t n) {
  const double eps = std::numeric_limits<double>::epsilon();
  if ((n & (n - 1)) == 0) return radix2_error(n);
  std::size_t m = 1;
  while (m < 2 * n - 1) m <<= 1;
  const double r = radix2_error(m) + 3 * eps;
  return (4 * r + eps) * 2 * std::sqrt(double(n)) + 2 * eps;
}

}  // namespace bleedsim::test
