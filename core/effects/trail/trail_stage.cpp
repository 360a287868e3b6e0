#include "core/effects/trail/trail_stage.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/effects/effect.h"
#include "core/effects/stage.h"
#include "core/effects/suction/suction_hook.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/trail/trail_params.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {

// (splat/thickness, the suction's path) => trail/residue
// Each frame, in scenes with [trail]: the residue of the blood that ran over each pixel, drying,
// and none where the suction passed. The stage readies the frame's pass (the suction's path) and
// leaves it in State for the blend, which runs it in its own pass over the pixels (TrailThenBlend).
class TrailStage final : public Stage {
 public:
  TrailStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  TrailPixel work_{};
  Buffer sweep_;  // the suction's path this frame, uploaded; grows with it
};

float trail_decay_per_frame(const TrailParams& trail, double frame_rate_hz) {
  return static_cast<float>(std::exp(-1.0 / (frame_rate_hz * trail.drying_s)));
}

void sweep_trail(TrailPixel& work, const float* on_backend, const std::vector<float>& segments, int count,
                 double reach_mm) {
  work.sweep = on_backend;
  work.sweep_segments = count;
  work.reach_sq = float(reach_mm * reach_mm);
  double low[2] = {HUGE_VAL, HUGE_VAL}, high[2] = {-HUGE_VAL, -HUGE_VAL};
  for (int k = 0; k < 4 * count; ++k) {
    low[k % 2] = std::min(low[k % 2], double(segments[k]));
    high[k % 2] = std::max(high[k % 2], double(segments[k]));
  }
  // Grown by the reach and a margin far beyond float32's rounding of a distance there (a few units
  // in the last place of the coordinates): the bounds only skip pixels no segment reaches.
  const double margin = reach_mm + 1e-3 + 1e-4 * (reach_mm + std::max({std::fabs(low[0]), std::fabs(low[1]),
                                                                          std::fabs(high[0]), std::fabs(high[1])}));
  for (int a = 0; a < 2; ++a) {
    work.sweep_box[a] = float(low[a] - margin);
    work.sweep_box[2 + a] = float(high[a] + margin);
  }
}

TrailStage::TrailStage(const StageKind& kind, const Scene& scene, const Resolved&, State& state, Backend& backend)
    : Stage(kind) {
  const Field& film = input(scene, state, "splat/thickness");
  Field& residue = add_field(scene, state, backend, "trail/residue");
  const std::vector<float> dry(scene.domain.pixels().to<std::size_t>(), 0.0f);
  backend.upload(residue.data.data(), dry.data(), dry.size() * sizeof(float));
  const TrailParams& trail = scene.effects.get<TrailParams>();
  work_ = TrailPixel{film.data.as<const float>(), residue.data.as<float>(), float(trail.residue),
                     trail_decay_per_frame(trail, scene.frame_rate_hz), scene.domain.grid()};
}

MemoryParts TrailStage::memory_for(const Scene& scene, const Resolved&) { return {scene.domain.memory(sizeof(float))}; }

void TrailStage::run(const Scene& scene, State& state, Backend& backend) {
  if (const SuctionParams* suction = scene.effects.find<SuctionParams>()) {
    const std::vector<float> sweep = suction_sweep(scene, state, double(state.frames_done) / scene.frame_rate_hz,
                                                   scene.frame_time_s(state.frames_done));
    const std::size_t bytes = sweep.size() * sizeof(float);
    if (bytes > sweep_.bytes()) sweep_ = allocate(backend, 2 * bytes);
    if (bytes > 0) backend.upload(sweep_.data(), sweep.data(), bytes);
    sweep_trail(work_, sweep_.as<const float>(), sweep, int(sweep.size() / 4), suction->radius_mm);
  }
  // Run by the blend, in its pass: it reads the residue at its own pixel only, after this.
  state.trail_pass = work_;
}

const Effect<TrailParams>& trail_effect() {
  static const Effect<TrailParams> row = [] {
    Effect<TrailParams> e{trail_table};
    e.stages = {{"trail", "trail", declares<TrailParams>,
                 {image_field("trail/residue", ElementType::f32, 1, "mm",
                              "the blood that ran over each pixel, left behind as an equivalent film and drying")},
                 [](const Scene&) { return std::vector<std::string>{"splat/thickness"}; }, TrailStage::memory_for,
                 make_stage<TrailStage>}};
    return e;
  }();
  return row;
}

}  // namespace bleedsim
