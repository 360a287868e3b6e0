#include "core/effects/vessels/vessel_params.h"

#include "core/scene/scene.h"

namespace bleedsim {
namespace {

ParamProblem bleeding_needs_particles(const VesselParams&, const Scene& scene) {
  if (scene.particles) return {};
  return {"map", "has no effect: this scene declares no [particles]"};
}

}  // namespace

const ParamTable<VesselParams>& vessel_table() {
  using P = VesselParams;
  static const ParamTable<P> table{
      "vessels",
      "declares vessel-driven bleeding: each cut bleeds in proportion to the vessel density along its wound "
      "(needs [particles])",
      {{"map", ParamType::text, BLEEDSIM_MEMBER(P, map), "", {},
        "\"procedural\": the vessels the procedural tissue draws; else a PNG file (relative to the scenario "
        "file), its red channel (a grey PNG's grey) the density from 0 to 255, resampled to the panel's pixels"}},
      {{"the scene has [particles]", bleeding_needs_particles}}};
  return table;
}

}  // namespace bleedsim
