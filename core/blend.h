#pragma once
// Compositing the blood over the tissue into the frame (report §2.2.1, its HLSL pass): the stain
// is taken out of the tissue's green and blue, so stained tissue reads red with the stain's soft
// edge. Red and alpha pass through. Bytes map to [0, 1] as v/255 and back with round-half-up.
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

BLEEDSIM_HD inline void blend_pixel(const std::uint8_t* tissue_rgba, float stain,
                                    std::uint8_t* frame_rgba) {
  frame_rgba[0] = tissue_rgba[0];
  frame_rgba[1] = byte_from_unit(unit_from_byte(tissue_rgba[1]) - stain);
  frame_rgba[2] = byte_from_unit(unit_from_byte(tissue_rgba[2]) - stain);
  frame_rgba[3] = tissue_rgba[3];
}

// The stage's twins. stain may be null: a scene without a spread shows the bare tissue.
struct BlendArgs {
  const std::uint8_t* tissue_rgba;
  const float* stain;
  int width;
  int height;
  std::uint8_t* frame_rgba;
};
void blend_cpu(const BlendArgs& args, int threads);
void blend_cuda(const BlendArgs& args);

}  // namespace bleedsim
