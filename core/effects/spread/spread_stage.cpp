// The spread effect: its stage, and its row (declared in spread_params.h).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/effects/effect.h"
#include "core/effects/spread/spread_params.h"
#include "core/effects/spread/spread_tiles.h"
#include "core/effects/stage.h"
#include "core/effects/surface/surface_stage.h"
#include "core/physics/pixel_kernels.h"
#include "core/physics/spread.h"

namespace bleedsim {

// (cuts, frame time) => spread/stain
// Each frame: the cuts' amplitudes at the frame time and the live cuts' tile table (host), then the
// stain field (backend). Cuts at the front of the list whose stains no longer change are folded,
// once, into the light they let through (SpreadSettle), so that a frame's cost follows the cuts
// still growing, not every cut made; and each pixel multiplies in only the live cuts its tile
// lists, so that its cost follows the cuts that overlap it.
class SpreadStage final : public Stage {
 public:
  SpreadStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  // The box of pixels that holds every pixel these cuts can stain.
  SpreadSettle settle_box(const Scene& scene, const SpreadCut* cuts, int count) const;

  Field& stain_;
  Buffer cuts_;                    // SpreadUpload's block: the cuts to settle, the live cuts, their tile table; grows
  Buffer settled_;                 // float per pixel: the light the settled cuts let through
  std::size_t settled_count_ = 0;  // cuts [0, settled_count_) of the list are folded into settled_
  double reach_per_mm_;            // spread_reach_per_mm
  std::vector<SpreadCut> host_;
  SpreadUpload upload_;
  std::vector<unsigned char> on_device_;  // the block as last copied into cuts_
};
namespace {

constexpr std::size_t kInitialCutCapacity = 16;

// The first block's size: room for the scene's cuts (at least a few) and an empty tile table.
std::size_t block_capacity_for(const Scene& scene) {
  return std::max(kInitialCutCapacity, scene.cuts.size()) * sizeof(SpreadCut) +
         (std::size_t(spread_tile_count(scene.domain.grid())) + 1) * sizeof(int);
}

// A cut whose stain will not change again: grown full (growth_per_s > 0 by its table).
bool settled(const Cut& cut, double t_s) { return cut_amplitude(cut.start_s, cut.growth_per_s, t_s) == 1.0f; }

SpreadCut spread_cut(const Cut& cut, float amplitude) {
  return {static_cast<float>(cut.x_mm), static_cast<float>(cut.y_mm), static_cast<float>(cut.radius_mm), amplitude};
}

}  // namespace

SpreadStage::SpreadStage(const StageKind& kind, const Scene& scene, const Resolved&, State& state, Backend& backend)
    : Stage(kind),
      stain_(add_field(scene, state, backend, "spread/stain")),
      cuts_(allocate(backend, block_capacity_for(scene))),
      settled_(allocate(backend, std::size_t(scene.domain.pixels().value()) * sizeof(float))),
      reach_per_mm_(spread_reach_per_mm(scene)) {
  // Nothing settled yet: every pixel lets all its light through.
  const std::vector<float> all_light(std::size_t(scene.domain.pixels().value()), 1.0f);
  backend.upload(settled_.data(), all_light.data(), settled_.bytes());
}

MemoryParts SpreadStage::memory_for(const Scene& scene, const Resolved&) {
  return {scene.domain.memory(sizeof(float)),
          {"cut", "the spread's cuts and tile table", Count(block_capacity_for(scene))},
          scene.domain.memory(sizeof(float))};
}

SpreadSettle SpreadStage::settle_box(const Scene& scene, const SpreadCut* cuts, int count) const {
  const PixelGrid grid = scene.domain.grid();
  PixelBox box{grid.width, 0, grid.height, 0};
  for (int c = 0; c < count; ++c) box = united(box, stain_box(host_[c], grid, reach_per_mm_));
  return {cuts, count, grid, settled_.as<float>(), {}, box.i0, box.j0, std::max(0, box.i1 - box.i0),
          std::max(0, box.j1 - box.j0)};
}

void SpreadStage::run(const Scene& scene, State& state, Backend& backend) {
  const double t = scene.frame_time_s(state.frames_done);
  // The cuts settling now, from the front of the list (the products must keep the list's order), then
  // the live ones. Cuts that add nothing (amplitude 0: 1 − 0 leaves the product exact) are left out.
  host_.clear();
  const std::size_t settled_before = settled_count_;
  while (settled_count_ < state.cuts.size() && settled(state.cuts[settled_count_], t)) ++settled_count_;
  for (std::size_t c = settled_before; c < settled_count_; ++c) {
    const float amplitude = cut_amplitude(state.cuts[c].start_s, state.cuts[c].growth_per_s, t);
    if (amplitude > 0.0f) host_.push_back(spread_cut(state.cuts[c], amplitude));
  }
  const int settling = static_cast<int>(host_.size());
  for (std::size_t c = settled_count_; c < state.cuts.size(); ++c) {
    const float amplitude = cut_amplitude(state.cuts[c].start_s, state.cuts[c].growth_per_s, t);
    if (amplitude > 0.0f) host_.push_back(spread_cut(state.cuts[c], amplitude));
  }
  // Cuts and tile table in one copy; none when the device holds these bytes already (every cut
  // settled: no live cut, an empty table, frame after frame).
  upload_.lay_out(host_, settling, scene.domain.grid(), reach_per_mm_);
  if (upload_.bytes() != on_device_) {
    if (upload_.bytes().size() > cuts_.bytes()) cuts_ = allocate(backend, 2 * upload_.bytes().size());
    backend.upload(cuts_.data(), upload_.bytes().data(), upload_.bytes().size());
    on_device_ = upload_.bytes();
  }

  const SurfaceMap surface = surface_map(scene, state);
  if (settling > 0) {
    SpreadSettle settle = settle_box(scene, cuts_.as<const SpreadCut>(), settling);
    settle.surface = surface;
    if (settle.box_width > 0 && settle.box_height > 0) launch(backend, settle);
  }
  launch(backend, upload_.pixel_work(cuts_.data(), stain_.data.as<float>(), surface, settled_.as<const float>()));
}

const Effect<SpreadParams>& spread_effect() {
  static const Effect<SpreadParams> row = [] {
    Effect<SpreadParams> e{spread_table};
    e.stages = {{"spread", "spread", declares<SpreadParams>,
                 {image_field("spread/stain", ElementType::f32, 1, "1",
                              "radial-spread stain: the share of a full stain (report 2.2.1), drawn as "
                              "stain_depth_mm of blood")},
                 surface_fields, SpreadStage::memory_for, make_stage<SpreadStage>}};
    return e;
  }();
  return row;
}

}  // namespace bleedsim
