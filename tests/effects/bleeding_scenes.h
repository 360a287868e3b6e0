#pragma once
// Small bleeding scenes built in code (tests/effects/bleeding_test.cpp, instrument_test.cpp): a
// panel of procedural tissue with particles, the cuts added one by one, and the particles'
// accounting as a run reports it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/effects/cuts.h"
#include "core/effects/particles/particle_accounting.h"
#include "core/effects/particles/particle_params.h"
#include "core/runtime/tissue.h"
#include "core/scene/scene.h"
#include "core/simulation/simulation.h"
#include "tests/runtime/field_values.h"

namespace bleedsim::test {

// `domain` on the procedural tissue (seed 1) for `duration_s`, with a ring of 4096 particles made
// for a shallow pile (design depth 0.5 mm: a soft contact, few sub-steps) that live `lifetime_s`,
// fading over the last `fade_s` of it (by default 30 s: none expires in a short test).
inline Scene bleeding_scene(const std::string& name, const Domain& domain, double duration_s,
                            double lifetime_s = ParticleParams{}.lifetime_s, double fade_s = ParticleParams{}.fade_s) {
  Scene scene;
  scene.name = name;
  scene.domain = domain;
  scene.duration_s = duration_s;
  scene.tissue = procedural_tissue(domain.width_px, domain.height_px, 1);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().capacity = 4096;
  scene.effects.get<ParticleParams>().lifetime_s = lifetime_s;
  scene.effects.get<ParticleParams>().fade_s = fade_s;
  scene.effects.get<ParticleParams>().design_depth_mm = 0.5;
  return scene;
}

// A cut at (x, y) from `start_s` bleeding `flow` mm³/s a mm of wound for `bleed_s`; the scene's own,
// for the test to shape further.
inline Cut& add_cut(Scene& scene, double x_mm, double y_mm, double start_s, double flow_mm3_per_s_per_mm,
                    double bleed_s) {
  Cut cut = cut_at(scene, x_mm, y_mm, start_s);
  cut.flow_mm3_per_s_per_mm = flow_mm3_per_s_per_mm;
  cut.bleed_s = bleed_s;
  scene.cuts.push_back(cut);
  return scene.cuts.back();
}

// The particles/accounting field; aspirated is 0 in a scene without [suction].
inline ParticleCounts particle_counts(const Simulation& sim) {
  const std::vector<std::uint64_t> c = field_values<std::uint64_t>(sim, "particles/accounting");
  return {c[0], c[1], c[2], c[3], c.size() > 4 ? c[4] : 0};
}

}  // namespace bleedsim::test
