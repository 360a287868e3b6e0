#include "core/effects/vessels/vessel_params.h"

#include "core/bleeding/vessel_density.h"
#include "core/effects/effect.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

ParamProblem bleeding_needs_particles(const VesselParams&, const Scene& scene) {
  if (scene.effects.has<ParticleParams>()) return {};
  return {"map", "has no effect: this scene declares no [particles]"};
}

std::string describe_vessels(const Scene& scene, const Resolved&, const RunOutline&) {
  std::string line =
      "  vessels    each wound's flow times the map's mean along it; map " + scene.effects.get<VesselParams>().map;
  if (!scene.cuts.empty()) line += "; the cuts' means";
  for (const Cut& cut : scene.cuts) {
    const Cut bleeding = with_vessels(scene, cut);
    line += " " + format_significant(bleeding.vessel_density, 3) + (bleeding.arterial ? " (arterial)" : "");
  }
  return line + "\n";
}

}  // namespace

Cut with_vessels(const Scene& scene, Cut cut) {
  if (!scene.effects.has<VesselParams>()) return cut;
  cut.vessel_density = wound_vessel_density(scene, cut);
  const PulseParams* pulse = scene.effects.find<PulseParams>();
  if (pulse && cut.vessel_density >= pulse->arterial_density) cut.arterial = true;
  return cut;
}

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

const Effect<VesselParams>& vessel_effect() {
  static const Effect<VesselParams> row = [] {
    Effect<VesselParams> e{vessel_table};
    e.as_made = with_vessels;
    e.describe = describe_vessels;
    return e;
  }();
  return row;
}

}  // namespace bleedsim
