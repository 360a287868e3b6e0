#include "tests/golden/frame_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/blend.h"
#include "core/png_writer.h"

namespace bleedsim::golden {
namespace {

double element(const FieldLayout& layout, const std::vector<std::uint8_t>& bytes, std::size_t i) {
  if (layout.type == ElementType::u8) return bytes[i];
  float value;
  std::memcpy(&value, bytes.data() + 4 * i, 4);
  return value;
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
  const double peak = layout.type == ElementType::u8 ? 255.0 : 1.0;
  double squared = 0.0;
  for (std::size_t i = 0; i < stats.values; ++i) {
    const double e = element(layout, expected, i), a = element(layout, actual, i);
    const bool differ = layout.type == ElementType::u8 ? e != a : ulp_distance(float(e), float(a)) != 0;
    if (!differ) continue;
    if (stats.differing++ == 0) {
      stats.first = i;
      stats.expected = e;
      stats.actual = a;
      stats.ulps = layout.type == ElementType::f32 ? ulp_distance(float(e), float(a)) : 0;
    }
    stats.max_abs_error = std::max(stats.max_abs_error, std::fabs(e - a));
    squared += (e - a) * (e - a);
  }
  const double mse = squared / double(stats.values);
  stats.psnr_db = mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
  return stats;
}

std::string describe(const FieldLayout& layout, const DiffStats& stats) {
  const std::size_t pixel = stats.first / layout.channels;
  char text[400];
  std::snprintf(text, sizeof text,
                "%zu of %zu values differ, max abs error %.6g, PSNR %.2f dB; first at (x %zu, y %zu, channel %zu): "
                "got %.9g expected %.9g",
                stats.differing, stats.values, stats.max_abs_error, stats.psnr_db, pixel % layout.width,
                pixel / layout.width, stats.first % layout.channels, stats.actual, stats.expected);
  std::string line = text;
  if (layout.type == ElementType::f32) line += " (" + std::to_string(stats.ulps) + " ulp)";
  return line;
}

void write_diff_images(const std::string& prefix, const FieldLayout& layout,
                       const std::vector<std::uint8_t>& expected, const std::vector<std::uint8_t>& actual) {
  const double unit = layout.type == ElementType::u8 ? 1.0 / 255.0 : 1.0;
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
