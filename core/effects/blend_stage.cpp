#include "core/effects/blend_stage.h"

#include <cmath>

#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

std::size_t rgba_bytes(const Scene& scene) { return std::size_t(scene.domain.pixel_count()) * 4; }

std::size_t transmission_bytes(const Scene& scene) {
  return scene.particles ? kTransmissionEntries * sizeof(float) : 0;
}

}  // namespace

void fill_transmission_table(float* table) {
  for (int k = 0; k < kTransmissionEntries; ++k)
    table[k] = static_cast<float>(std::exp(-double(k) / kTransmissionStepsPerUnit));
}

BlendStage::BlendStage(const Scene& scene, State& state, Backend& backend)
    : Stage("blend"),
      frame_(add_field(state, backend,
                       image_field(scene, "frame", ElementType::u8, 4, "sRGB 8-bit",
                                   "the rendered frame: blood composited over the tissue (RGBA)"))),
      tissue_(allocate(backend, rgba_bytes(scene))),
      transmission_(allocate(backend, transmission_bytes(scene))) {
  backend.upload(tissue_.data(), scene.tissue.rgba.data(), rgba_bytes(scene));
  if (transmission_.bytes() == 0) return;
  float table[kTransmissionEntries];
  fill_transmission_table(table);
  backend.upload(transmission_.data(), table, sizeof table);
}

std::size_t BlendStage::bytes_for(const Scene& scene) { return 2 * rgba_bytes(scene) + transmission_bytes(scene); }

void BlendStage::run(const Scene& scene, State& state, Backend& backend) {
  const Field* stain = state.find("spread/stain");
  // The blurred film when the scene blurs it, the raw splat otherwise.
  const Field* thickness = state.find("blur/thickness");
  if (!thickness) thickness = state.find("splat/thickness");
  launch(backend, BlendPixel{tissue_.as<const std::uint8_t>(), stain ? stain->data.as<const float>() : nullptr,
                             thickness ? thickness->data.as<const float>() : nullptr,
                             transmission_.as<const float>(), scene.domain.grid(), frame_.data.as<std::uint8_t>()});
}

}  // namespace bleedsim
