#include "core/effects/pipeline.h"

#include "core/effects/blend_stage.h"
#include "core/effects/blur_stage.h"
#include "core/effects/particle_stage.h"
#include "core/effects/splat_stage.h"
#include "core/effects/spread_stage.h"

namespace bleedsim {
namespace {

// Every stage bleedsim knows, in frame order; adding an effect adds one row.
struct StageKind {
  const char* name;
  bool (*wanted)(const Scene&);
  std::size_t (*bytes_for)(const Scene&);
  std::unique_ptr<Stage> (*make)(const Scene&, State&, Backend&);
};

template <class S>
std::unique_ptr<Stage> make_stage(const Scene& scene, State& state, Backend& backend) {
  return std::make_unique<S>(scene, state, backend);
}

const StageKind kStages[] = {
    {"spread", [](const Scene& s) { return s.spread.has_value(); }, SpreadStage::bytes_for,
     make_stage<SpreadStage>},
    {"particles", [](const Scene& s) { return s.particles.has_value(); }, ParticleStage::bytes_for,
     make_stage<ParticleStage>},
    {"splat", [](const Scene& s) { return s.particles.has_value(); }, SplatStage::bytes_for, make_stage<SplatStage>},
    {"blur", [](const Scene& s) { return s.particles && s.blur; }, BlurStage::bytes_for, make_stage<BlurStage>},
    {"blend", [](const Scene&) { return true; }, BlendStage::bytes_for, make_stage<BlendStage>},
};

}  // namespace

Pipeline::Pipeline(const Scene& scene, State& state, Backend& backend) {
  for (const StageKind& kind : kStages)
    if (kind.wanted(scene)) stages_.push_back(kind.make(scene, state, backend));
}

void Pipeline::run_frame(const Scene& scene, State& state, Backend& backend) {
  for (const auto& stage : stages_) stage->run(scene, state, backend);
}

std::vector<StageReport> Pipeline::report(const Backend& backend) const {
  std::vector<StageReport> rows;
  for (const auto& stage : stages_)
    rows.push_back({stage->name(), stage->bytes(), backend.launches(stage->name())});
  return rows;
}

std::vector<std::string> Pipeline::stage_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const StageKind& kind : kStages)
    if (kind.wanted(scene)) names.push_back(kind.name);
  return names;
}

std::size_t Pipeline::backend_bytes(const Scene& scene) {
  std::size_t bytes = 0;
  for (const StageKind& kind : kStages)
    if (kind.wanted(scene)) bytes += kind.bytes_for(scene);
  return bytes;
}

}  // namespace bleedsim
