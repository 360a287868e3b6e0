#include "core/haptics/power_spectrum.h"

#include <cmath>
#include <cstddef>
#include <utility>

namespace bleedsim {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

bool power_of_two(std::size_t n) { return n != 0 && (n & (n - 1)) == 0; }

// In place, iterative Cooley–Tukey over a power-of-two length; `sign` −1 forward, +1 backward
// (unscaled). Each twiddle is computed from its angle, not by repeated multiplication, so the error
// stays that of Higham's Theorem 24.2 (Accuracy and Stability of Numerical Algorithms, 2nd ed.).
void radix2(std::vector<Complex>& a, int sign) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t length = 2; length <= n; length <<= 1) {
    const double angle = sign * 2 * kPi / double(length);
    for (std::size_t k = 0; k < length / 2; ++k) {
      const Complex w = std::polar(1.0, angle * double(k));
      for (std::size_t start = 0; start < n; start += length) {
        const Complex u = a[start + k], v = a[start + k + length / 2] * w;
        a[start + k] = u + v;
        a[start + k + length / 2] = u - v;
      }
    }
  }
}

// Bluestein: k·n = (k² + n² − (k − n)²) / 2 turns the transform into a convolution with the chirp
// w_m = e^(iπm²/N), done by power-of-two transforms of length M ≥ 2N − 1.
std::vector<Complex> bluestein(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::size_t m = 1;
  while (m < 2 * n - 1) m <<= 1;
  // m² mod 2N keeps the angle small, so that the chirp is as accurate as sin and cos are.
  std::vector<Complex> chirp(n);
  for (std::size_t j = 0; j < n; ++j) {
    const unsigned long long square = (static_cast<unsigned long long>(j) * j) % (2ULL * n);
    chirp[j] = std::polar(1.0, kPi * double(square) / double(n));
  }
  std::vector<Complex> a(m), b(m);
  for (std::size_t j = 0; j < n; ++j) a[j] = x[j] * std::conj(chirp[j]);
  b[0] = chirp[0];
  for (std::size_t j = 1; j < n; ++j) b[j] = b[m - j] = chirp[j];
  radix2(a, -1);
  radix2(b, -1);
  for (std::size_t j = 0; j < m; ++j) a[j] *= b[j];
  radix2(a, +1);
  std::vector<Complex> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = std::conj(chirp[k]) * a[k] / double(m);
  return out;
}

}  // namespace

std::vector<Complex> discrete_fourier_transform(const std::vector<double>& x) {
  if (x.empty()) return {};
  if (!power_of_two(x.size())) return bluestein(x);
  std::vector<Complex> a(x.begin(), x.end());
  radix2(a, -1);
  return a;
}

std::vector<double> power_spectrum(const std::vector<double>& x) {
  const std::vector<Complex> transform = discrete_fourier_transform(x);
  const double n = double(x.size());
  std::vector<double> power(transform.size());
  for (std::size_t k = 0; k < transform.size(); ++k) power[k] = std::norm(transform[k]) / (n * n);
  return power;
}

}  // namespace bleedsim
