#pragma once
// Compositing the blood over the tissue into the frame (report §2.2.1, its HLSL pass): the stain
// is taken out of the tissue's green and blue, so stained tissue reads red with the stain's soft
// edge; red and alpha pass through. Particles then cover it. Bytes map to [0, 1] as v/255 and back with round-half-up.
#include <cmath>
#include <cstdint>

#include "core/hd.h"

namespace bleedsim {

BLEEDSIM_HD inline float unit_from_byte(std::uint8_t v) { return static_cast<float>(v) / 255.0f; }

BLEEDSIM_HD inline std::uint8_t byte_from_unit(float v) {
  // Clamp before converting: float→int of out-of-range values differs between CPU and GPU.
  const float clamped = fminf(fmaxf(v, 0.0f), 1.0f);
  return static_cast<std::uint8_t>(clamped * 255.0f + 0.5f);
}

// Particles, drawn plainly until the screen-space stages give blood its real look: flat blood red
// over the stained tissue, as opaque as the cover (a particle's fade).
constexpr float kParticleRed = 0.45f, kParticleGreen = 0.02f, kParticleBlue = 0.03f;

BLEEDSIM_HD inline std::uint8_t over(float below, float blood, float cover) {
  return byte_from_unit(below * (1.0f - cover) + blood * cover);
}

BLEEDSIM_HD inline void blend_pixel(const std::uint8_t* tissue_rgba, float stain, float cover,
                                    std::uint8_t* frame_rgba) {
  const float green = unit_from_byte(tissue_rgba[1]) - stain;
  const float blue = unit_from_byte(tissue_rgba[2]) - stain;
  if (cover > 0.0f) {
    frame_rgba[0] = over(unit_from_byte(tissue_rgba[0]), kParticleRed, cover);
    frame_rgba[1] = over(fmaxf(green, 0.0f), kParticleGreen, cover);
    frame_rgba[2] = over(fmaxf(blue, 0.0f), kParticleBlue, cover);
  } else {
    frame_rgba[0] = tissue_rgba[0];
    frame_rgba[1] = byte_from_unit(green);
    frame_rgba[2] = byte_from_unit(blue);
  }
  frame_rgba[3] = tissue_rgba[3];
}

// The stage's twins. stain and cover may be null: a scene without that effect shows none of it.
struct BlendArgs {
  const std::uint8_t* tissue_rgba;
  const float* stain;
  const float* cover;
  int width;
  int height;
  std::uint8_t* frame_rgba;
};
void blend_cpu(const BlendArgs& args, int threads);
void blend_cuda(const BlendArgs& args);

}  // namespace bleedsim
