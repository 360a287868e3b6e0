#pragma once
// Compositing the blood over the tissue into the frame (report §2.2.1, its HLSL pass): the stain
// is taken out of the tissue's green and blue, so stained tissue reads red with the stain's soft
// edge; red and alpha pass through. The particles' film of blood (core/physics/splat.h) then lies over it. Bytes map to [0, 1] as v/255 and back with round-half-up.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

BLEEDSIM_HD inline float unit_from_byte(std::uint8_t v) { return static_cast<float>(v) / 255.0f; }

BLEEDSIM_HD inline std::uint8_t byte_from_unit(float v) {
  // Clamp before converting: float→int of out-of-range values differs between CPU and GPU.
  const float clamped = fminf(fmaxf(v, 0.0f), 1.0f);
  return static_cast<std::uint8_t>(clamped * 255.0f + 0.5f);
}

// Light crossing a film of blood h mm thick keeps exp(−a_c·h) of channel c (Beer–Lambert): blood
// absorbs green and blue strongly and red weakly, so a thin film reads bright red over the tissue
// and a pool darkens towards black.
constexpr float kBloodAbsorbsRedPerMm = 4.0f, kBloodAbsorbsGreenPerMm = 40.0f, kBloodAbsorbsBluePerMm = 45.0f;

// exp(−x) from a table computed once on the host (fill_transmission_table()), linearly interpolated:
// expf differs between the host's libm and the device, a table read the same way does not.
constexpr int kTransmissionStepsPerUnit = 64;
constexpr int kTransmissionEntries = 32 * kTransmissionStepsPerUnit + 1;  // x in [0, 32]

BLEEDSIM_HD inline float transmitted(const float* table, float optical_depth) {
  const float s = optical_depth * float(kTransmissionStepsPerUnit);
  if (!(s < float(kTransmissionEntries - 1))) return table[kTransmissionEntries - 1];
  const float k = floorf(s);
  const int i = int(k);
  return table[i] + (table[i + 1] - table[i]) * (s - k);
}

BLEEDSIM_HD inline void blend_pixel(const std::uint8_t* tissue_rgba, float stain, float thickness_mm,
                                    const float* transmission, std::uint8_t* frame_rgba) {
  const float green = unit_from_byte(tissue_rgba[1]) - stain;
  const float blue = unit_from_byte(tissue_rgba[2]) - stain;
  if (thickness_mm > 0.0f) {
    const auto through_film = [&](float below, float absorbs_per_mm) {
      return byte_from_unit(below * transmitted(transmission, absorbs_per_mm * thickness_mm));
    };
    frame_rgba[0] = through_film(unit_from_byte(tissue_rgba[0]), kBloodAbsorbsRedPerMm);
    frame_rgba[1] = through_film(fmaxf(green, 0.0f), kBloodAbsorbsGreenPerMm);
    frame_rgba[2] = through_film(fmaxf(blue, 0.0f), kBloodAbsorbsBluePerMm);
  } else {
    // No film: exactly the stained tissue (scenes without particles keep their bytes).
    frame_rgba[0] = tissue_rgba[0];
    frame_rgba[1] = byte_from_unit(green);
    frame_rgba[2] = byte_from_unit(blue);
  }
  frame_rgba[3] = tissue_rgba[3];
}

// The table transmitted() reads: exp(−k / kTransmissionStepsPerUnit), in double, rounded once.
void fill_transmission_table(float* table);

// The stage's work, pixel by pixel (core/physics/pixel_kernels.h runs it). stain and thickness_mm
// may be null: a scene without that effect shows none of it. transmission is needed with thickness_mm.
struct BlendPixel {
  const std::uint8_t* tissue_rgba;
  const float* stain;
  const float* thickness_mm;
  const float* transmission;  // kTransmissionEntries, with thickness_mm
  PixelGrid grid;
  std::uint8_t* frame_rgba;

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    blend_pixel(tissue_rgba + 4 * p, stain ? stain[p] : 0.0f, thickness_mm ? thickness_mm[p] : 0.0f, transmission,
                frame_rgba + 4 * p);
  }
};

}  // namespace bleedsim
