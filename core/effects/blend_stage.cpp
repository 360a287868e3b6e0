#include "core/effects/blend_stage.h"

#include <cmath>

#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

std::size_t rgba_bytes(const Scene& scene) { return scene.domain.pixels().to<std::size_t>() * 4; }

std::size_t transmission_bytes(const Scene& scene) {
  return blend_film_field(scene) ? kTransmissionEntries * sizeof(float) : 0;
}

}  // namespace

const char* blend_stain_field(const Scene& scene) { return scene.spread ? "spread/stain" : nullptr; }

const char* blend_film_field(const Scene& scene) {
  return scene.blur ? "blur/thickness" : scene.particles ? "splat/thickness" : nullptr;
}

void fill_transmission_table(float* table) {
  for (int k = 0; k < kTransmissionEntries; ++k)
    table[k] = static_cast<float>(std::exp(-double(k) / kTransmissionStepsPerUnit));
}

BlendStage::BlendStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      tissue_(allocate(backend, rgba_bytes(scene))),
      transmission_(allocate(backend, transmission_bytes(scene))) {
  const auto input_or_null = [&](const char* name) {
    return name ? input(scene, state, name).data.as<const float>() : nullptr;
  };
  Field& frame = add_field(scene, state, backend, "frame");
  work_ = BlendPixel{tissue_.as<const std::uint8_t>(), input_or_null(blend_stain_field(scene)),
                     input_or_null(blend_film_field(scene)), transmission_.as<const float>(), scene.domain.grid(),
                     frame.data.as<std::uint8_t>()};
  backend.upload(tissue_.data(), scene.tissue.rgba.data(), rgba_bytes(scene));
  if (transmission_.bytes() == 0) return;
  float table[kTransmissionEntries];
  fill_transmission_table(table);
  backend.upload(transmission_.data(), table, sizeof table);
}

MemoryParts BlendStage::memory_for(const Scene& scene) {
  return {scene.domain.memory(2 * 4), {"scene.width_px", "the blend's transmission table", transmission_bytes(scene)}};
}

void BlendStage::run(const Scene&, State&, Backend& backend) { launch(backend, work_); }

}  // namespace bleedsim
