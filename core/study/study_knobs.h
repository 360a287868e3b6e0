#pragma once
// The accuracy study's knobs (docs/accuracy.md, "The knobs"): ways to trade accuracy for time. Each
// knob changes one thing and holds the rest: a value the model cannot run at the others' settings
// (a contact too stiff for the time step) is refused, never softened. The particle model has no
// solver iterations (one neighbour pass a sub-step, docs/particles.md): there is no such knob.
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace bleedsim {

struct Knob {
  const char* name;
  const char* trades;  // what it changes, and what the saving costs (docs, --help)
  const char* holds;   // what it keeps as it is
  bool finer_is_larger;
  bool whole;          // its values are whole numbers
  double exact;        // a level at which the knob has no error to refine (NaN: none)
  // The parameter it sets ("particles.substeps"), whose range (core/runtime/params.h) its values
  // must keep; null for a knob that is a factor on several (its values need only be positive).
  const char* param;
  bool (*applies)(const Scene&);
  double (*base)(const Scene&);                        // the scene's own setting
  // The levels a study tries when not told, coarse to fine. The time step's are the scene's
  // sub-steps and twice that: a study passes it the scene with the fewest sub-steps that the
  // stiffest contact it runs allows.
  std::vector<double> (*default_ladder)(const Scene&);
  void (*apply)(Scene&, double value);
};

const std::vector<Knob>& knobs();
// Null when there is none of that name.
const Knob* find_knob(const std::string& name);
// "no knob 'x' (known: ...)", and for a solver's iteration count, why the model has none.
std::string unknown_knob_message(const std::string& name);

// Writes in what the particle model derives when a scene leaves it to the model (sub-steps 0: the
// fewest the contact allows; design depth 0: what the panel and the ring allow), so that a knob
// changing the particles' size or stiffness keeps the time step and the pile the contact is made
// for. Nothing changes for the scene as it runs; the particle knobs do this first themselves.
void pin_particle_model(Scene& scene);

// The fewest sub-steps the scene's contact allows at its frame rate.
int fewest_stable_substeps(const Scene& scene);

// A panel's pixels along one side at a resolution factor: the resolution knob's rounding.
int resolution_pixels(int pixels, double factor);

// The knob's step size h at a value, for orders and extrapolation: the value where finer is smaller,
// its inverse where finer is larger (a time step is 1/sub-steps).
double knob_step(const Knob& knob, double value);

// One step finer than the finest of `levels` (coarse to fine), continuing the last two levels'
// ratio (a single level: twice as fine), rounded for a whole knob (and at least one finer); none
// where that value is outside the knob's range (blur_downsample past 1).
std::optional<double> refined_value(const Knob& knob, const std::vector<double>& levels);

}  // namespace bleedsim
