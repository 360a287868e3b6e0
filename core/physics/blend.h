#pragma once
// Compositing the blood over the tissue into the frame (report §2.2.1 and §2.2.2.5; docs/optics.md):
// in linear light, the tissue's colour times the light that crosses the blood over it twice, down
// and back up (Beer–Lambert), every absorber drawn as an equivalent film of whole blood — the film
// the particles leave, the stain the spread takes into the tissue, the residue of blood that ran
// there. A scene with [optics] is also lit by the endoscope's headlight: its falloff, and the
// highlights wet blood and tissue show towards the lens.
#include <cstddef>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/optics.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

// Blood as an absorber: μ_c (1/mm) for red, green and blue, and the film a full stain stands for.
struct BloodOptics {
  float absorption_per_mm[3];
  float stain_depth_mm;
};

// What the headlight gives a pixel that the scene alone fixes: its irradiance (1 without falloff),
// and what it reflects to the lens while nothing stands on it — reflected_to_lens over the bare,
// level tissue, which is also its value under a film at height 0 with no slope.
constexpr int kFixedLightChannels = 2;

BLEEDSIM_HD inline float headlight_irradiance(const Headlight& l, float x_mm, float y_mm) {
  return l.falloff ? headlight_falloff(l, x_mm, y_mm) : 1.0f;
}

// The fixed light of every pixel, made once per run (BlendStage): a frame reads two floats where
// it would compute a falloff and a lobe, which are most of a lit pixel's arithmetic.
struct FixedLightPixel {
  Headlight light;
  PixelGrid grid;
  float* fixed;  // kFixedLightChannels a pixel: irradiance, the bare tissue's highlight

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const float x = pixel_centre_x_mm(grid, i), y = pixel_centre_y_mm(grid, j);
    float* out = fixed + kFixedLightChannels * (std::size_t(j) * grid.width + i);
    out[0] = headlight_irradiance(light, x, y);
    out[1] = reflected_to_lens(light, x, y, 0.0f, 0.0f, 0.0f);
  }
};

// The stage's work, pixel by pixel (core/physics/pixel_kernels.h runs it). stain, film_mm and
// residue_mm may be null: a scene without that effect shows none of it; transmission is needed
// with any of them. lit: the scene has [optics], so the headlight's falloff and highlights apply;
// fixed_light, FixedLightPixel's field then (or null: computed here, the same bits).
struct BlendPixel {
  const std::uint8_t* tissue_rgba;
  const float* stain;
  const float* film_mm;
  const float* residue_mm;
  const float* transmission;  // kTransmissionEntries
  SrgbTables srgb;
  BloodOptics blood;
  int lit;
  Headlight light;
  float half_inverse_pitch_x, half_inverse_pitch_y;  // 1 / (2 · the pixel's size in mm): the slope's step
  PixelGrid grid;
  std::uint8_t* frame_rgba;
  const float* fixed_light = nullptr;

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }

  // The blood over pixel p, as a depth of whole blood (mm): film, then stain, then residue.
  BLEEDSIM_HD float blood_depth_mm(std::size_t p) const {
    float depth = film_mm ? film_mm[p] : 0.0f;
    if (stain) depth += stain[p] * blood.stain_depth_mm;
    if (residue_mm) depth += residue_mm[p];
    return depth;
  }

  // The film's slope at (i, j): central differences, the edge pixel standing in for one off the panel.
  BLEEDSIM_HD float film_at(int i, int j) const {
    return film_mm[std::size_t(clamp_index(j, grid.height)) * grid.width + clamp_index(i, grid.width)];
  }

  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    const std::uint8_t* tissue = tissue_rgba + 4 * p;
    float light_c[3] = {linear_from_srgb(srgb, tissue[0]), linear_from_srgb(srgb, tissue[1]),
                        linear_from_srgb(srgb, tissue[2])};
    const float depth = blood_depth_mm(p);
    if (depth > 0.0f)
      for (int c = 0; c < 3; ++c) light_c[c] *= transmitted(transmission, 2.0f * blood.absorption_per_mm[c] * depth);
    if (lit) {
      const float x = pixel_centre_x_mm(grid, i), y = pixel_centre_y_mm(grid, j);
      float z = 0.0f, slope_x = 0.0f, slope_y = 0.0f;
      if (film_mm) {
        z = film_mm[p];
        slope_x = (film_at(i + 1, j) - film_at(i - 1, j)) * half_inverse_pitch_x;
        slope_y = (film_at(i, j + 1) - film_at(i, j - 1)) * half_inverse_pitch_y;
      }
      // Bare and level (±0 compare equal to 0, as they do in reflected_to_lens): the fixed light's
      // highlight is this pixel's, bit for bit.
      const bool bare = z == 0.0f && slope_x == 0.0f && slope_y == 0.0f;
      const float* fixed = fixed_light ? fixed_light + kFixedLightChannels * p : nullptr;
      const float highlight = fixed && bare ? fixed[1] : reflected_to_lens(light, x, y, z, slope_x, slope_y);
      const float irradiance = fixed ? fixed[0] : headlight_irradiance(light, x, y);
      for (int c = 0; c < 3; ++c) light_c[c] = (light_c[c] + highlight) * irradiance;
    }
    std::uint8_t* frame = frame_rgba + 4 * p;
    for (int c = 0; c < 3; ++c) frame[c] = srgb_from_linear(srgb, light_c[c]);
    frame[3] = tissue[3];
  }
};

}  // namespace bleedsim
