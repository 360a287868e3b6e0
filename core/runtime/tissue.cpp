#include "core/runtime/tissue.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/runtime/image.h"

namespace bleedsim {
namespace {

// ---- Procedural mucosa ------------------------------------------------------------------------
// Every step is an integer hash or a single IEEE float operation (+ − × ÷, floorf, comparisons),
// so the bytes are the same on every machine and at every optimisation level. A change to any
// constant here changes every golden frame drawn over procedural tissue.

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Each noise layer hashes its lattice with its own key, so layers are independent of each other.
enum class Layer : std::uint64_t {
  mottle_coarse = 1,
  mottle_fine,
  warp_x,
  warp_y,
  vessel_coarse,
  vessel_fine,
};

std::uint64_t layer_key(std::uint64_t seed, Layer layer) {
  return splitmix64(splitmix64(seed) + static_cast<std::uint64_t>(layer));
}

// A uniform value in [0, 1) at lattice point (ix, iy): the hash's top 24 bits, exact in a float.
float lattice_value(std::uint64_t key, std::int64_t ix, std::int64_t iy) {
  const std::uint64_t h =
      splitmix64(splitmix64(key ^ static_cast<std::uint64_t>(ix)) ^ static_cast<std::uint64_t>(iy));
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

float smoothstep01(float t) { return t * t * (3.0f - 2.0f * t); }

float lerp(float a, float b, float t) { return a + (b - a) * t; }

float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }

// Value noise in [0, 1) at (x, y) in lattice units: hashed corners, smoothstep-blended.
float value_noise(std::uint64_t key, float x, float y) {
  const float fx = floorf(x);
  const float fy = floorf(y);
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const float sx = smoothstep01(x - fx);
  const float sy = smoothstep01(y - fy);
  const float top = lerp(lattice_value(key, ix, iy), lattice_value(key, ix + 1, iy), sx);
  const float bottom = lerp(lattice_value(key, ix, iy + 1), lattice_value(key, ix + 1, iy + 1), sx);
  return lerp(top, bottom, sy);
}

// Ridged noise: 1 on the mid-level contour of a two-octave noise, which winds and forks like a
// vessel, falling off to either side. Raising it to a power narrows the ridge to a line.
float ridge(float n) {
  const float centred = 2.0f * n - 1.0f;
  return 1.0f - (centred < 0.0f ? -centred : centred);
}

float pow8(float v) {
  const float v2 = v * v;
  const float v4 = v2 * v2;
  return v4 * v4;
}

struct Rgb {
  float r, g, b;
};

constexpr Rgb kMucosa{0.80f, 0.45f, 0.45f};
constexpr Rgb kVessel{0.56f, 0.14f, 0.19f};
constexpr float kVesselStrength = 0.8f;  // a vessel's colour at its centre, mixed into the mucosa's

struct NoiseKeys {
  std::uint64_t mottle_coarse, mottle_fine, warp_x, warp_y, vessel_coarse, vessel_fine;
};

// How much of a vessel lies at (x, y), 0 to 1: the lattice is warped by a slow noise so that the
// vessels do not run along its axes, and a soft threshold keeps the ridges' faint flanks out.
float vessel_presence(const NoiseKeys& k, float x, float y) {
  const float wx = x * 2.1f + 0.6f * value_noise(k.warp_x, x * 2.0f, y * 2.0f);
  const float wy = y * 2.1f + 0.6f * value_noise(k.warp_y, x * 2.0f, y * 2.0f);
  const float n = 0.7f * value_noise(k.vessel_coarse, wx, wy) +
                  0.3f * value_noise(k.vessel_fine, wx * 2.7f, wy * 2.7f);
  return smoothstep01(clamp01((pow8(ridge(n)) - 0.35f) / 0.45f));
}

// The colour of the pixel whose centre is (x, y), in units of the image's longer side.
Rgb mucosa_colour(const NoiseKeys& k, float x, float y) {
  // Mottling: two octaves of value noise shade the pink base lighter and darker.
  const float mottle = 0.6f * value_noise(k.mottle_coarse, x * 3.0f, y * 3.0f) +
                       0.4f * value_noise(k.mottle_fine, x * 8.3f, y * 8.3f);
  const float shade = mottle - 0.5f;
  const Rgb base{kMucosa.r + 0.16f * shade, kMucosa.g + 0.14f * shade, kMucosa.b + 0.12f * shade};

  const float strength = kVesselStrength * vessel_presence(k, x, y);
  return Rgb{lerp(base.r, kVessel.r, strength), lerp(base.g, kVessel.g, strength),
             lerp(base.b, kVessel.b, strength)};
}

// The pixels of a width × height panel, each given f(keys, x, y) at its centre (in units of the
// longer side, so a texture looks the same at any resolution).
template <class F>
void for_each_pixel(int width, int height, std::uint64_t seed, F f) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("procedural_tissue: width and height must be positive (got " +
                                std::to_string(width) + " x " + std::to_string(height) + ")");
  }
  const NoiseKeys keys{layer_key(seed, Layer::mottle_coarse), layer_key(seed, Layer::mottle_fine),
                       layer_key(seed, Layer::warp_x),        layer_key(seed, Layer::warp_y),
                       layer_key(seed, Layer::vessel_coarse), layer_key(seed, Layer::vessel_fine)};
  const auto longer_side = static_cast<float>(std::max(width, height));
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      f(std::size_t(j) * std::size_t(width) + std::size_t(i), keys, (static_cast<float>(i) + 0.5f) / longer_side,
        (static_cast<float>(j) + 0.5f) / longer_side);
}

}  // namespace

Image procedural_tissue(int width, int height, std::uint64_t seed) {
  Image image{std::max(width, 0), std::max(height, 0), {}};
  image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
  for_each_pixel(width, height, seed, [&](std::size_t p, const NoiseKeys& keys, float x, float y) {
    const Rgb c = mucosa_colour(keys, x, y);
    std::uint8_t* pixel = &image.rgba[p * 4];
    pixel[0] = byte_from_unit(c.r);
    pixel[1] = byte_from_unit(c.g);
    pixel[2] = byte_from_unit(c.b);
    pixel[3] = 255;
  });
  return image;
}

std::vector<float> procedural_vessel_density(int width, int height, std::uint64_t seed) {
  std::vector<float> density(std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)));
  for_each_pixel(width, height, seed,
                 [&](std::size_t p, const NoiseKeys& keys, float x, float y) { density[p] = vessel_presence(keys, x, y); });
  return density;
}

}  // namespace bleedsim
