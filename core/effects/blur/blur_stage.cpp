#include "core/effects/blur/blur_stage.h"

#include <cmath>

#include "core/effects/blur/blur_params.h"
#include "core/effects/effect.h"
#include "core/effects/stage.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {

// (splat/thickness) => blur/thickness
// Each frame, in scenes with [blur]: the film downsampled, blurred across and down, and upsampled,
// which the blend then lays over the tissue instead of the raw film.
class BlurStage final : public Stage {
 public:
  BlurStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  BlurArgs args_{};
  Buffer weights_, low_, across_;
};
namespace {

int low_size(int size, int factor) { return (size + factor - 1) / factor; }

std::size_t low_pixels(const Scene& scene) {
  const int f = scene.effects.get<BlurParams>().downsample;
  return (Count(low_size(scene.domain.width_px, f)) * Count(low_size(scene.domain.height_px, f))).to<std::size_t>();
}

}  // namespace

std::vector<float> gaussian_weights(int radius, double sigma) {
  std::vector<double> w(2 * std::size_t(radius) + 1);
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) sum += w[k + radius] = std::exp(-0.5 * (k / sigma) * (k / sigma));
  std::vector<float> weights;
  for (double v : w) weights.push_back(static_cast<float>(v / sum));
  return weights;
}

BlurStage::BlurStage(const StageKind& kind, const Scene& scene, const Resolved&, State& state, Backend& backend)
    : Stage(kind),
      weights_(allocate(backend, (2 * std::size_t(scene.effects.get<BlurParams>().radius_px) + 1) * sizeof(float))),
      low_(allocate(backend, low_pixels(scene) * sizeof(float))),
      across_(allocate(backend, low_pixels(scene) * sizeof(float))) {
  const Field& film = input(scene, state, "splat/thickness");
  Field& blurred = add_field(scene, state, backend, "blur/thickness");
  const BlurParams& b = scene.effects.get<BlurParams>();
  const std::vector<float> weights = gaussian_weights(b.radius_px, b.sigma_px);
  backend.upload(weights_.data(), weights.data(), weights.size() * sizeof(float));
  args_.width = scene.domain.width_px;
  args_.height = scene.domain.height_px;
  args_.factor = b.downsample;
  args_.low_width = low_size(args_.width, b.downsample);
  args_.low_height = low_size(args_.height, b.downsample);
  args_.radius = b.radius_px;
  args_.weights = weights_.as<const float>();
  args_.film = film.data.as<const float>();
  args_.low = low_.as<float>();
  args_.across = across_.as<float>();
  args_.blurred = blurred.data.as<float>();
  state.film_downsample = args_;
}

MemoryParts BlurStage::memory_for(const Scene& scene, const Resolved&) {
  // The downsampled images are at most the panel's size: counted with it (low_pixels narrows only
  // once the panel has been found to fit).
  const int f = scene.effects.get<BlurParams>().downsample;
  const Count low = Count(low_size(scene.domain.width_px, f)) * Count(low_size(scene.domain.height_px, f));
  return {scene.domain.memory(sizeof(float)),
          {"scene.width_px", "the blur's downsampled images", low * (2 * sizeof(float))},
          {"blur.radius_px", "the blur's weights",
           (Count(2) * Count(scene.effects.get<BlurParams>().radius_px) + 1) * sizeof(float)}};
}

// The downsample ran in the splat's pass (its twin is given state.film_downsample).
void BlurStage::run(const Scene&, State&, Backend& backend) {
  blur_passes(args_).each([&](const auto& pass) { launch(backend, pass); }, false);
}

const Effect<BlurParams>& blur_effect() {
  static const Effect<BlurParams> row = [] {
    Effect<BlurParams> e{blur_table};
    e.stages = {{"blur", "blur", declares<BlurParams>,
                 {image_field("blur/thickness", ElementType::f32, 1, "mm",
                              "the film of blood downsampled, blurred and upsampled: what the blend lays over the "
                              "tissue")},
                 [](const Scene&) { return std::vector<std::string>{"splat/thickness"}; }, BlurStage::memory_for,
                 make_stage<BlurStage>}};
    return e;
  }();
  return row;
}

}  // namespace bleedsim
