#pragma once
// Sizes — cells, pixels, samples, steps, bytes — counted without wrapping (docs/reliability.md,
// "Limits"). A Count is a 64-bit unsigned number that saturates: a product or a sum past 2^64 − 1,
// a negative integer, or a double that is NaN, negative or too large becomes Count::uncountable(),
// which is larger than every limit. So a size is computed as a Count, compared with its limit, and
// only then narrowed with to<T>(): no cast ever meets a value its type cannot hold.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace bleedsim {

class Count {
 public:
  constexpr Count() = default;
  // Any integer: a negative one counts nothing real, and is uncountable.
  template <class I, std::enable_if_t<std::is_integral_v<I>, int> = 0>
  constexpr Count(I n) : n_(std::uint64_t(n)) {  // NOLINT: implicit, so sizes read as arithmetic
    if constexpr (std::is_signed_v<I>)
      if (n < 0) n_ = kUncountable;
  }
  static constexpr Count uncountable() { return Count(kUncountable); }
  // ⌈x⌉ and ⌊x⌋ of a double, or uncountable (NaN, negative, 2^64 or more).
  static Count ceil_of(double x) { return of_whole(std::ceil(x)); }
  static Count floor_of(double x) { return of_whole(std::floor(x)); }

  constexpr bool countable() const { return n_ != kUncountable; }
  constexpr std::uint64_t value() const { return n_; }
  // As a double, for messages and for limits stated as doubles; uncountable is infinite.
  double as_double() const { return countable() ? double(n_) : std::numeric_limits<double>::infinity(); }

  // The count as T, once a check has shown that it fits: a count that does not is a bug in that
  // check, not bad input.
  template <class T>
  T to() const {
    if (!countable() || n_ > std::uint64_t(std::numeric_limits<T>::max()))
      throw std::logic_error("a count of " + (countable() ? std::to_string(n_) : std::string("more than 2^64")) +
                             " reached a narrowing its limit check should have stopped");
    return T(n_);
  }

  friend constexpr Count operator*(Count a, Count b) {
    std::uint64_t product = 0;
    if (!a.countable() || !b.countable() || __builtin_mul_overflow(a.n_, b.n_, &product) || product == kUncountable)
      return uncountable();
    return Count(product);
  }
  friend constexpr Count operator+(Count a, Count b) {
    std::uint64_t sum = 0;
    if (!a.countable() || !b.countable() || __builtin_add_overflow(a.n_, b.n_, &sum) || sum == kUncountable)
      return uncountable();
    return Count(sum);
  }
  Count& operator*=(Count other) { return *this = *this * other; }
  Count& operator+=(Count other) { return *this = *this + other; }

  friend constexpr bool operator==(Count a, Count b) { return a.n_ == b.n_; }
  friend constexpr bool operator!=(Count a, Count b) { return a.n_ != b.n_; }
  friend constexpr bool operator<(Count a, Count b) { return a.n_ < b.n_; }
  friend constexpr bool operator>(Count a, Count b) { return a.n_ > b.n_; }
  friend constexpr bool operator<=(Count a, Count b) { return a.n_ <= b.n_; }
  friend constexpr bool operator>=(Count a, Count b) { return a.n_ >= b.n_; }

 private:
  static constexpr std::uint64_t kUncountable = std::numeric_limits<std::uint64_t>::max();
  // A whole double as a count: it must be a number, 0 or more, and below 2^64 (the cast is checked
  // before it is made).
  static Count of_whole(double whole) {
    if (!(whole >= 0.0) || !(whole < 18446744073709551616.0)) return uncountable();
    return Count(std::uint64_t(whole));
  }

  std::uint64_t n_ = 0;
};

}  // namespace bleedsim
