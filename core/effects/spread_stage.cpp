#include "core/effects/spread_stage.h"

#include <algorithm>
#include <cmath>

#include "core/effects/surface_stage.h"
#include "core/mesh/surface_bake.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

constexpr std::size_t kInitialCutCapacity = 16;

std::size_t cut_capacity_for(std::size_t cuts) { return std::max(kInitialCutCapacity, cuts); }

// A cut whose stain will not change again: grown full (growth_per_s > 0 by its table).
bool settled(const Cut& cut, double t_s) { return cut_amplitude(cut.start_s, cut.growth_per_s, t_s) == 1.0f; }

SpreadCut spread_cut(const Cut& cut, float amplitude) {
  return {static_cast<float>(cut.x_mm), static_cast<float>(cut.y_mm), static_cast<float>(cut.radius_mm), amplitude};
}

}  // namespace

SpreadStage::SpreadStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      stain_(add_field(scene, state, backend, "spread/stain")),
      cuts_(allocate(backend, cut_capacity_for(scene.cuts.size()) * sizeof(SpreadCut))),
      settled_(allocate(backend, std::size_t(scene.domain.pixels().value()) * sizeof(float))) {
  // Nothing settled yet: every pixel lets all its light through.
  const std::vector<float> all_light(std::size_t(scene.domain.pixels().value()), 1.0f);
  backend.upload(settled_.data(), all_light.data(), settled_.bytes());
  // On a mesh a stain of radius r reaches r / σ panel mm, σ the texture's least stretch (its frames
  // are its triangles', to float rounding: a thousandth to spare).
  if (scene.mesh) reach_per_mm_ = 1.001 / panel_stretch(scene.mesh->mesh(), texture_panel(scene.domain)).least;
}

MemoryParts SpreadStage::memory_for(const Scene& scene) {
  return {scene.domain.memory(sizeof(float)),
          {"cut", "the spread's cuts", Count(cut_capacity_for(scene.cuts.size())) * sizeof(SpreadCut)},
          scene.domain.memory(sizeof(float))};
}

SpreadSettle SpreadStage::settle_box(const Scene& scene, const SpreadCut* cuts, int count) const {
  const PixelGrid grid = scene.domain.grid();
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (int c = 0; c < count; ++c) {
    const double reach = host_[c].radius_mm * reach_per_mm_;
    x0 = std::min(x0, host_[c].x_mm - reach), x1 = std::max(x1, host_[c].x_mm + reach);
    y0 = std::min(y0, host_[c].y_mm - reach), y1 = std::max(y1, host_[c].y_mm + reach);
  }
  // Pixel i's centre is (i + ½)·mm_per_px: those within the span, and one more either side for rounding.
  const auto first = [](double from_mm, double mm_per_px, int n) {
    return int(std::clamp(std::floor(from_mm / mm_per_px - 0.5) - 1.0, 0.0, double(n)));
  };
  const auto end = [](double to_mm, double mm_per_px, int n) {
    return int(std::clamp(std::ceil(to_mm / mm_per_px - 0.5) + 2.0, 0.0, double(n)));
  };
  const int i0 = first(x0, grid.mm_per_px_x, grid.width), i1 = end(x1, grid.mm_per_px_x, grid.width);
  const int j0 = first(y0, grid.mm_per_px_y, grid.height), j1 = end(y1, grid.mm_per_px_y, grid.height);
  return {cuts, count, grid, settled_.as<float>(), {}, i0, j0, std::max(0, i1 - i0), std::max(0, j1 - j0)};
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
  const std::size_t needed = host_.size() * sizeof(SpreadCut);
  if (needed > cuts_.bytes()) cuts_ = allocate(backend, 2 * needed);
  if (needed > 0) backend.upload(cuts_.data(), host_.data(), needed);

  const SurfaceMap surface = surface_map(scene, state);
  const SpreadCut* cuts = cuts_.as<const SpreadCut>();
  if (settling > 0) {
    SpreadSettle settle = settle_box(scene, cuts, settling);
    settle.surface = surface;
    if (settle.box_width > 0 && settle.box_height > 0) launch(backend, settle);
  }
  launch(backend, SpreadPixel{cuts + settling, static_cast<int>(host_.size()) - settling, scene.domain.grid(),
                              stain_.data.as<float>(), surface, settled_.as<const float>()});
}

}  // namespace bleedsim
