#pragma once
// The accuracy study (docs/accuracy.md): a scene run at many settings of its accuracy knobs, each
// timed and compared frame by frame with a reference run at the finest settings of all of them.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/runtime/backend.h"
#include "core/runtime/scene.h"
#include "core/study/study_metrics.h"

namespace bleedsim {

// A way to trade accuracy for time. Its values are numbers; which end is finer is fixed.
struct Knob {
  const char* name;
  const char* trades;        // what it changes, and what the saving costs (docs, --help)
  bool finer_is_larger;
  // The parameter it sets ("particles.substeps"), whose range (core/runtime/params.h) its values
  // must keep; null for a knob that is a factor on several (its values need only be positive).
  const char* param;
  bool (*applies)(const Scene&);
  double (*base)(const Scene&);                        // the scene's own setting
  std::vector<double> (*default_sweep)(const Scene&);  // the values a study tries when not told
  void (*apply)(Scene&, double value);  // may leave the scene unrunnable: Simulation then refuses it
};

const std::vector<Knob>& knobs();
const Knob* find_knob(const std::string& name);  // null when there is none of that name

struct KnobSweep {
  const Knob* knob;
  std::vector<double> values;
};

struct StudySpec {
  std::vector<KnobSweep> sweeps;              // empty: every knob the scene has, its default values
  std::vector<BackendKind> backends;          // each setting is timed on each
  std::optional<double> duration_s;           // a shorter run than the scene's
};

// One setting of one knob (the others at the scene's own), or the reference, or its check.
struct StudySetting {
  std::string knob;  // the knob's name; "reference" or "reference_check"
  double value = 0;
  std::string role;  // "base", "sweep", "reference", "reference_check"
};

struct StudyRun {
  StudySetting setting;
  BackendKind backend = BackendKind::cpu;
  std::string status = "ok";            // or "refused: <why>"
  std::vector<double> frame_seconds;    // compute per frame: the step and the fields' copy to the host
  std::vector<FrameErrors> errors;      // per frame, against the reference (every knob at its finest)
  std::vector<FrameErrors> knob_errors; // per frame, against this knob at its finest (the others as
                                        // this run has them): the knob's own share of the error
};

class Study {
 public:
  // Throws InputError (naming the knob) for a knob the scene does not have or a value out of its
  // range, and when the reference itself cannot run.
  Study(const Scene& scene, const StudySpec& spec);

  const std::vector<StudySetting>& settings() const { return settings_; }
  std::string reference_description() const;  // "substeps 80, particle_size 0.7, ..."
  int grid_width() const { return grid_w_; }
  int grid_height() const { return grid_h_; }
  long frames_per_run() const;

  // Runs the reference, then every setting on every backend (each knob's finest first, as its own
  // reference). The runs come back in settings() order. `progress` hears each frame done.
  std::vector<StudyRun> run(const std::function<void(long frames_done)>& progress);

 private:
  Scene with(const StudySetting& setting) const;
  // Runs one setting; compares each frame with `reference` and with `knob_reference` (when given),
  // and keeps its frames in `keep` (when given: it is then its knob's reference).
  StudyRun run_one(const StudySetting& setting, BackendKind backend, const std::vector<GridFrame>& reference,
                   const std::vector<GridFrame>* knob_reference, std::vector<GridFrame>* keep,
                   const std::function<void()>& frame_done) const;
  double finest_value(const std::string& knob) const;

  Scene base_;
  StudySpec spec_;
  std::vector<StudySetting> settings_;
  int grid_w_ = 0, grid_h_ = 0;
};

}  // namespace bleedsim
