#include "tests/golden/frame_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/runtime/image.h"
#include "core/io/png_writer.h"

namespace bleedsim::golden {
namespace {

bool is_integer(ElementType type) { return type != ElementType::f32; }

// An integer field's element exactly (u64 does not fit a double).
std::uint64_t integer(const FieldLayout& layout, const std::vector<std::uint8_t>& bytes, std::size_t i) {
  switch (layout.type) {
    case ElementType::u8: return bytes[i];
    case ElementType::u32: {
      std::uint32_t value;
      std::memcpy(&value, bytes.data() + 4 * i, 4);
      return value;
    }
    case ElementType::u64: {
      std::uint64_t value;
      std::memcpy(&value, bytes.data() + 8 * i, 8);
      return value;
    }
    case ElementType::f32: break;
  }
  return 0;
}

double element(const FieldLayout& layout, const std::vector<std::uint8_t>& bytes, std::size_t i) {
  if (is_integer(layout.type)) return double(integer(layout, bytes, i));
  float value;
  std::memcpy(&value, bytes.data() + 4 * i, 4);
  return value;
}

// What counts as full scale: 255 for bytes, 1 for floats, the largest value seen for wider integers.
double peak_of(const FieldLayout& layout, const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (layout.type == ElementType::u8) return 255.0;
  if (layout.type == ElementType::f32) return 1.0;
  double peak = 1.0;
  const std::size_t values = std::size_t(layout.width) * layout.height * layout.channels;
  for (std::size_t i = 0; i < values; ++i) peak = std::max({peak, element(layout, a, i), element(layout, b, i)});
  return peak;
}

// A field as an RGBA8 picture: bytes as they are, floats in [0, 1] as grey.
std::vector<std::uint8_t> picture(const FieldLayout& layout, const std::vector<std::uint8_t>& bytes,
                                  double scale) {
  const std::size_t pixels = std::size_t(layout.width) * layout.height;
  std::vector<std::uint8_t> rgba(4 * pixels, 255);
  for (std::size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < std::min(layout.channels, 3); ++c) {
      const double v = element(layout, bytes, p * layout.channels + c) * scale;
      const std::uint8_t shown = byte_from_unit(float(v));
      if (layout.channels == 1)
        rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = shown;
      else
        rgba[4 * p + c] = shown;
    }
  return rgba;
}

}  // namespace

std::int64_t ulp_distance(float a, float b) {
  const auto ordered = [](float f) {
    std::int32_t bits;
    std::memcpy(&bits, &f, 4);
    return bits < 0 ? std::int64_t(std::numeric_limits<std::int32_t>::min()) - bits : std::int64_t(bits);
  };
  return std::llabs(ordered(a) - ordered(b));
}

DiffStats diff_field(const FieldLayout& layout, const std::vector<std::uint8_t>& expected,
                     const std::vector<std::uint8_t>& actual) {
  DiffStats stats;
  stats.values = std::size_t(layout.width) * layout.height * layout.channels;
  const double peak = peak_of(layout, expected, actual);
  double squared = 0.0;
  for (std::size_t i = 0; i < stats.values; ++i) {
    const double e = element(layout, expected, i), a = element(layout, actual, i);
    // Integers compare and subtract exactly: two u64 near 2^64 that differ by 1 are equal as doubles.
    const std::uint64_t ei = integer(layout, expected, i), ai = integer(layout, actual, i);
    const bool differ = is_integer(layout.type) ? ei != ai : ulp_distance(float(e), float(a)) != 0;
    if (!differ) continue;
    const double error = is_integer(layout.type) ? double(std::max(ei, ai) - std::min(ei, ai)) : std::fabs(e - a);
    if (stats.differing++ == 0) {
      stats.first = i;
      stats.expected = e;
      stats.actual = a;
      stats.expected_integer = ei;
      stats.actual_integer = ai;
      stats.ulps = layout.type == ElementType::f32 ? ulp_distance(float(e), float(a)) : 0;
    }
    stats.max_abs_error = std::max(stats.max_abs_error, error);
    squared += error * error;
  }
  const double mse = squared / double(stats.values);
  stats.psnr_db = mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
  return stats;
}

std::string describe(const FieldLayout& layout, const DiffStats& stats) {
  const std::size_t pixel = stats.first / layout.channels;  // or element, when not an image
  const std::size_t channel = stats.first % layout.channels;
  char where[120];
  if (layout.image)
    std::snprintf(where, sizeof where, "x %zu, y %zu, channel %zu", pixel % layout.width, pixel / layout.width,
                  channel);
  else
    std::snprintf(where, sizeof where, "element %zu, component %zu", pixel, channel);
  char values[120];
  if (is_integer(layout.type))
    std::snprintf(values, sizeof values, "got %llu expected %llu", (unsigned long long)stats.actual_integer,
                  (unsigned long long)stats.expected_integer);
  else
    std::snprintf(values, sizeof values, "got %.9g expected %.9g", stats.actual, stats.expected);
  char text[400];
  std::snprintf(text, sizeof text, "%zu of %zu values differ, max abs error %.6g, PSNR %.2f dB; first at (%s): %s",
                stats.differing, stats.values, stats.max_abs_error, stats.psnr_db, where, values);
  std::string line = text;
  if (layout.type == ElementType::f32) line += " (" + std::to_string(stats.ulps) + " ulp)";
  return line;
}

void write_diff_images(const std::string& prefix, const FieldLayout& layout,
                       const std::vector<std::uint8_t>& expected, const std::vector<std::uint8_t>& actual) {
  if (!layout.image) return;  // particle state, counters: describe() says where they differ
  const double unit = 1.0 / peak_of(layout, expected, actual);
  write_png_rgba(prefix + "expected.png", layout.width, layout.height, picture(layout, expected, unit).data());
  write_png_rgba(prefix + "actual.png", layout.width, layout.height, picture(layout, actual, unit).data());
  // |expected − actual| scaled so the largest difference is white.
  double largest = 0.0;
  const std::size_t values = std::size_t(layout.width) * layout.height * layout.channels;
  std::vector<double> abs_diff(values);
  for (std::size_t i = 0; i < values; ++i) {
    abs_diff[i] = std::fabs(element(layout, expected, i) - element(layout, actual, i));
    largest = std::max(largest, abs_diff[i]);
  }
  FieldLayout grey = layout;
  grey.type = ElementType::f32;
  std::vector<std::uint8_t> as_float(values * 4);
  for (std::size_t i = 0; i < values; ++i) {
    const float v = largest > 0 ? float(abs_diff[i] / largest) : 0.0f;
    std::memcpy(as_float.data() + 4 * i, &v, 4);
  }
  write_png_rgba(prefix + "diff.png", layout.width, layout.height, picture(grey, as_float, 1.0).data());
}

}  // namespace bleedsim::golden
