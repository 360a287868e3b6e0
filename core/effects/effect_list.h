#pragma once
// The one list of effects. Each line is an effect's row (core/effects/effect.h), defined in the
// effect's own folder; everything that enumerates effects reads this list: the stages and hooks a
// scene runs, the settings it resolves, the cuts' rules, the scene's check (core/simulation/),
// the scenario reader (core/io/scenario.cpp), `bleedsim validate` and `params`, and so the docs'
// tables, the golden check's defaults and the tests' list of tables. The order is the tables'
// order in docs and messages, the order rules and hooks run in, and breaks ties in the stages'
// run order (core/effects/pipeline.h).
#include <string>
#include <type_traits>
#include <vector>

#include "core/effects/blend/optics_params.h"
#include "core/effects/blur/blur_params.h"
#include "core/effects/contact/contact_params.h"
#include "core/effects/effect.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/trail/trail_params.h"
#include "core/effects/vessels/vessel_params.h"

namespace bleedsim {

// Calls visit(row) for each effect's row, in the list's order: a generic lambda sees each row's
// own parameter type (Effect<P>).
template <class Visit>
void for_each_effect(Visit&& visit) {
  visit(spread_effect());
  visit(particle_effect());
  visit(blur_effect());
  visit(trail_effect());
  visit(optics_effect());
  visit(pulse_effect());
  visit(vessel_effect());
  visit(suction_effect());
  visit(contact_effect());
}

// Calls visit(row, params) for each effect the scene declares, in the list's order.
template <class Visit>
void for_each_declared_effect(const Scene& scene, Visit&& visit) {
  for_each_effect([&](const auto& effect) {
    using P = typename std::decay_t<decltype(effect)>::Params;
    if (const P* params = scene.effects.find<P>()) visit(effect, *params);
  });
}

// The first problem of the effects a scene declares, each against its table (keys named under the
// table's name).
ParamProblem effects_problem(const Scene& scene);

// A cut as it bleeds in this scene: the rules of the effects it declares, applied in order.
Cut cut_as_made(const Scene& scene, Cut cut);

// The tables of the effects with hooks in the particle step ("suction", "contact"), which act
// through the instrument; and whether a scene declares any of them.
std::vector<std::string> hook_tables();
bool declares_a_hook(const Scene& scene);

// What `bleedsim validate` says of the effects a scene declares, in order.
std::string describe_effects(const Scene& scene, const Resolved& resolved, const RunOutline& run);

// Every effect's table, as people read it.
std::vector<TableView> effect_tables();

}  // namespace bleedsim
