#include "core/effects/spread_stage.h"

#include <algorithm>

#include "core/effects/surface_stage.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

constexpr std::size_t kInitialCutCapacity = 16;

std::size_t cut_capacity_for(std::size_t cuts) { return std::max(kInitialCutCapacity, cuts); }

}  // namespace

SpreadStage::SpreadStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      stain_(add_field(scene, state, backend, "spread/stain")),
      cuts_(allocate(backend, cut_capacity_for(scene.cuts.size()) * sizeof(SpreadCut))) {}

MemoryParts SpreadStage::memory_for(const Scene& scene) {
  return {scene.domain.memory(sizeof(float)),
          {"cut", "the spread's cuts", Count(cut_capacity_for(scene.cuts.size())) * sizeof(SpreadCut)}};
}

void SpreadStage::run(const Scene& scene, State& state, Backend& backend) {
  // Cuts that have not started add nothing (1 − 0 leaves the product exact): leave them out.
  const double t = scene.frame_time_s(state.frames_done);
  active_.clear();
  for (const Cut& cut : state.cuts) {
    const float amplitude = cut_amplitude(cut.start_s, cut.growth_per_s, t);
    if (amplitude > 0.0f)
      active_.push_back({static_cast<float>(cut.x_mm), static_cast<float>(cut.y_mm),
                         static_cast<float>(cut.radius_mm), amplitude});
  }
  const std::size_t needed = active_.size() * sizeof(SpreadCut);
  if (needed > cuts_.bytes()) cuts_ = allocate(backend, 2 * needed);
  if (needed > 0) backend.upload(cuts_.data(), active_.data(), needed);
  launch(backend, SpreadPixel{cuts_.as<const SpreadCut>(), static_cast<int>(active_.size()), scene.domain.grid(),
                              stain_.data.as<float>(), surface_map(scene, state)});
}

}  // namespace bleedsim
