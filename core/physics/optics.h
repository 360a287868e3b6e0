#pragma once
// The endoscope's view of blood on the mucosa (docs/optics.md): light in linear units, absorbed by
// haemoglobin on its way down to the tissue and back up (Beer–Lambert, twice the depth), from a
// headlight at the lens, with the specular highlight wet blood shows where its surface faces the
// lens. Every function is one IEEE operation at a time, with the tables made on the host
// (optics_tables(), core/physics/optics_tables.h), so both backends give the same bytes.
#include <cmath>
#include <cstdint>

#include "core/physics/hd.h"

namespace bleedsim {

// exp(−x) from a table, linearly interpolated: expf differs between the host's libm and the device,
// a table read the same way does not.
constexpr int kTransmissionStepsPerUnit = 64;
constexpr int kTransmissionEntries = 32 * kTransmissionStepsPerUnit + 1;  // x in [0, 32]

BLEEDSIM_HD inline float transmitted(const float* table, float optical_depth) {
  const float s = optical_depth * float(kTransmissionStepsPerUnit);
  if (!(s < float(kTransmissionEntries - 1))) return table[kTransmissionEntries - 1];
  const float k = floorf(s);
  const int i = int(k);
  return table[i] + (table[i + 1] - table[i]) * (s - k);
}

// sRGB bytes to linear light and back (IEC 61966-2-1). Decoding is a table of the 256 bytes;
// encoding rounds to the nearest byte by counting the byte boundaries a value reaches: boundary k
// is the linear value of the code (k + ½)/255, so the byte of v is the number of boundaries ≤ v.
// A table of the count at the start of each of kSrgbBuckets equal steps of [0, 1) gives a start no
// higher than the answer (v ≥ its step's start, exactly: v · 4096 and its floor are exact), and
// one comparison with the next boundary finishes it: no step holds more than one boundary (the
// next step's count is at most one more, Srgb.EncodesToTheNearestByte), and v lies below the next
// step's start, so the answer is the start's count or one more. encode(decode(b)) = b for every byte.
constexpr int kSrgbBytes = 256;
constexpr int kSrgbBuckets = 4096;
struct SrgbTables {
  const float* to_linear;     // kSrgbBytes
  const float* boundaries;    // kSrgbBytes − 1, increasing
  const float* bucket_start;  // kSrgbBuckets: boundaries ≤ k / kSrgbBuckets, as floats (whole numbers)
};

BLEEDSIM_HD inline float linear_from_srgb(const SrgbTables& t, std::uint8_t byte) { return t.to_linear[byte]; }

BLEEDSIM_HD inline std::uint8_t srgb_from_linear(const SrgbTables& t, float v) {
  if (!(v > 0.0f)) return 0;  // also not a number
  if (v >= 1.0f) return kSrgbBytes - 1;
  const int byte = int(t.bucket_start[int(v * float(kSrgbBuckets))]);
  return std::uint8_t(byte < kSrgbBytes - 1 && v >= t.boundaries[byte] ? byte + 1 : byte);
}

// An integer power by repeated squaring: the same multiplications, in the same order, everywhere.
BLEEDSIM_HD inline float integer_power(float x, int n) {
  float result = 1.0f;
  while (n > 0) {
    if (n & 1) result *= x;
    x *= x;
    n >>= 1;
  }
  return result;
}

// The light and the lens at one point, `height_mm` above (x, y) on the panel: the endoscope's tip.
struct Headlight {
  float x_mm, y_mm, height_mm;
  int falloff;      // 1: the light falls off as a point source's, cos θ / r², normalised to 1 below it
  float specular;   // the blood's highlight at the mirror point (linear light; 0: none)
  int shininess;    // the lobe's exponent
  float sheen;      // the wet tissue's own highlight (0: none) ...
  int sheen_shininess;  // ... and its lobe's exponent
};

// The point source's irradiance at a point of the panel r away, at angle θ to the panel's normal,
// relative to the point below it: (h/r)² · (h/r) = (h² / (h² + ρ²))^(3/2).
BLEEDSIM_HD inline float headlight_falloff(const Headlight& l, float x_mm, float y_mm) {
  const float dx = x_mm - l.x_mm, dy = y_mm - l.y_mm;
  const float c = l.height_mm * l.height_mm / (l.height_mm * l.height_mm + dx * dx + dy * dy);
  return c * sqrtf(c);
}

// What the surface at (x, y, z) with slope (∂z/∂x, ∂z/∂y) reflects towards the lens from the light
// at the lens: the wet tissue's sheen, a lobe about the panel's normal (0, 0, 1), and the blood's
// highlight, the Blinn–Phong lobe (n·v)^p about the blood surface's normal n — with the light at
// the lens the half vector is the view vector v — less the lobe the flat tissue plane already
// gives there: blood adds only what its relief turns towards the lens, so a flat film shows no
// highlight of its own, and a bump shows one where its normal points at the lens.
BLEEDSIM_HD inline float reflected_to_lens(const Headlight& l, float x_mm, float y_mm, float z_mm, float slope_x,
                                           float slope_y) {
  const float vx = l.x_mm - x_mm, vy = l.y_mm - y_mm, vz = l.height_mm - z_mm;
  const float v_inverse = 1.0f / sqrtf(vx * vx + vy * vy + vz * vz);
  const float upright = vz * v_inverse;  // n·v for the panel's own normal
  float relief = 0.0f;
  // Where the film is level its facing is, to the bit, upright (the slopes' products are zeros and
  // n_inverse is 1), so its relief is exactly 0: most of a frame skips the lobes' work.
  if (slope_x != 0.0f || slope_y != 0.0f) {
    const float n_inverse = 1.0f / sqrtf(slope_x * slope_x + slope_y * slope_y + 1.0f);
    const float facing = (vz - slope_x * vx - slope_y * vy) * v_inverse * n_inverse;
    if (facing > 0.0f) relief = integer_power(facing, l.shininess) - integer_power(upright, l.shininess);
  }
  return l.sheen * integer_power(upright, l.sheen_shininess) + l.specular * max_float(relief, 0.0f);
}

}  // namespace bleedsim
