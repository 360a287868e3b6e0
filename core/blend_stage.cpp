#include "core/blend_stage.h"

namespace bleedsim {
namespace {

std::size_t rgba_bytes(const Scene& scene) { return std::size_t(scene.domain.pixel_count()) * 4; }

}  // namespace

BlendStage::BlendStage(const Scene& scene, State& state, Backend& backend)
    : Stage("blend"),
      frame_(add_field(state, backend,
                       image_field(scene, "frame", ElementType::u8, 4, "sRGB 8-bit",
                                   "the rendered frame: blood composited over the tissue (RGBA)"))),
      tissue_(allocate(backend, rgba_bytes(scene))) {
  backend.upload(tissue_.data(), scene.tissue.rgba.data(), rgba_bytes(scene));
}

std::size_t BlendStage::bytes_for(const Scene& scene) { return 2 * rgba_bytes(scene); }

void BlendStage::run(const Scene& scene, State& state, Backend& backend) {
  const Field* stain = state.find("spread/stain");
  const Field* cover = state.find("particles/cover");
  backend.blend(BlendArgs{tissue_.as<const std::uint8_t>(),
                          stain ? stain->data.as<const float>() : nullptr,
                          cover ? cover->data.as<const float>() : nullptr, scene.domain.width_px, scene.domain.height_px,
                          frame_.data.as<std::uint8_t>()});
}

}  // namespace bleedsim
