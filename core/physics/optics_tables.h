#pragma once
// The tables the blend reads (core/physics/optics.h), one after another, made on the host in double
// and rounded once to float, so both backends read the same bytes: sRGB's 256 bytes in linear
// light; the 255 boundaries between them (the linear value of code (k + ½)/255); exp(−k /
// kTransmissionStepsPerUnit) for the Beer–Lambert transmission; the encoding's bucket starts
// (SrgbTables). The blend uploads them; the endoscope's view (core/mesh/view_render.cpp) reads the
// sRGB part on the host. Host code: no device function here.
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/physics/optics.h"

namespace bleedsim {

constexpr std::size_t kOpticsTableFloats = kSrgbBytes + (kSrgbBytes - 1) + kTransmissionEntries + kSrgbBuckets;

// IEC 61966-2-1: the sRGB code value c ∈ [0, 1] as linear light.
inline double linear_from_code(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

inline std::vector<float> optics_tables() {
  std::vector<float> t;
  for (int b = 0; b < kSrgbBytes; ++b) t.push_back(float(linear_from_code(b / 255.0)));
  for (int k = 0; k + 1 < kSrgbBytes; ++k) t.push_back(float(linear_from_code((k + 0.5) / 255.0)));
  for (int k = 0; k < kTransmissionEntries; ++k) t.push_back(float(std::exp(-double(k) / kTransmissionStepsPerUnit)));
  // Indexed, not through a pointer: the push_back below may move the table.
  const std::size_t boundaries = kSrgbBytes;
  int reached = 0;
  for (int k = 0; k < kSrgbBuckets; ++k) {
    const float start = float(k) / float(kSrgbBuckets);  // exact
    while (reached < kSrgbBytes - 1 && t[boundaries + reached] <= start) ++reached;
    t.push_back(float(reached));
  }
  return t;
}

// The parts of optics_tables() at `tables`: the transmission's, and the sRGB tables.
inline const float* transmission_table(const float* tables) { return tables + 2 * kSrgbBytes - 1; }
inline SrgbTables srgb_tables(const float* tables) {
  return {tables, tables + kSrgbBytes, transmission_table(tables) + kTransmissionEntries};
}

}  // namespace bleedsim
