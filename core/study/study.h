#pragma once
// The accuracy study (docs/accuracy.md): a scene's accuracy knobs each climbed as a convergence
// ladder, every other knob at the reference (every knob at its finest); each level, the reference,
// its next refinement along each knob and the scene's own settings run as ensembles over seeds.
// The study is a list of independent jobs (one setting, one seed, one backend), each of which
// returns a self-contained record (core/study/job_record.h); core/study/study_analysis.h turns the
// records into the results. Nothing here compares one job with another.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/runtime/backend.h"
#include "core/scene/scene.h"
#include "core/study/study_knobs.h"

namespace bleedsim {

// The seeds a study runs each setting with, unless told (`--seeds`); an interval needs two.
constexpr int kDefaultSeeds = 8;
// Frames of each run whose fields are kept for the comparisons (spaced evenly, the last among them).
constexpr int kSnapshots = 8;

struct KnobLevels {
  const Knob* knob;
  std::vector<double> levels;  // any order; the study sorts them coarse to fine
};

struct StudySpec {
  std::vector<KnobLevels> knobs;      // empty: every knob the scene has, at its default levels
  std::vector<BackendKind> backends;  // each job runs on each (their data must agree to the bit)
  std::optional<double> duration_s;   // a shorter run than the scene's
  int seeds = kDefaultSeeds;
  int cpu_threads = 0;                // the CPU backend's threads; 0: one per hardware thread
};

// One setting: the reference, the scene as it is, or one knob at one level with the others at the
// reference's.
struct StudySetting {
  std::string knob;  // the knob's name; "reference" or "scene"
  double value = 0;  // the knob's level (0 for the reference and the scene)
  std::string role;  // "reference", "scene", "ladder" (a coarser level) or "refinement" (one finer)
};

// A knob's ladder: its levels coarse to fine, the finest the reference's, then (where the knob can
// be refined) one finer: the reference's next refinement along it.
struct StudyLadder {
  const Knob* knob;
  std::vector<double> values;
  std::vector<std::size_t> settings;  // each level's setting (the reference's is setting 0)
  bool refined = false;               // the last level is the refinement
  std::string not_refined;            // why there is none
};
// The ladder's level at the reference: its finest but the refinement.
double reference_value(const StudyLadder& ladder);

class Study {
 public:
  // Throws InputError (naming the knob or option) for a knob the scene does not have, a value out
  // of its range, fewer than two seeds, and when the reference itself cannot run.
  Study(const Scene& scene, const StudySpec& spec);

  const std::vector<StudySetting>& settings() const { return settings_; }
  const std::vector<StudyLadder>& ladders() const { return ladders_; }
  const std::vector<BackendKind>& backends() const { return spec_.backends; }
  int seeds() const { return spec_.seeds; }
  // Seed index i runs with the scene's seed + i (mod 2⁶³): index 0 is the scene's own run. The seed
  // moves the physics' randomness only; the tissue and the vessel map stay the scene's.
  std::uint64_t seed_of(int seed_index) const;
  const Scene& scene() const { return base_; }  // the scene as the study runs it (its duration)
  std::string reference_description() const;   // "compression 0.02, substeps 632, ..."
  int grid_width() const { return grid_w_; }
  int grid_height() const { return grid_h_; }
  int frames_per_run() const { return base_.frame_count(); }
  const std::vector<int>& snapshot_frames() const { return snapshots_; }
  // A fingerprint of what the study runs (the scene's name, panel, time, seed, cuts and tissue; the
  // settings, seeds, backends and grid): a record made by another study is refused by it.
  std::uint64_t key() const { return key_; }

  // The scene a setting runs with one seed.
  Scene scene_for(std::size_t setting, int seed_index) const;

  // The jobs: every setting with every seed on every backend, setting after setting.
  struct Job {
    std::size_t setting;
    int seed_index;
    BackendKind backend;
  };
  std::size_t job_count() const { return settings_.size() * std::size_t(spec_.seeds) * spec_.backends.size(); }
  Job job(std::size_t j) const;
  // A rough relative cost, for sharing jobs out: frames × (particle steps a frame × capacity + pixels).
  double job_cost(std::size_t j) const;
  // Runs job j on `backend` (on CUDA device `cuda_device`: Ranks::cuda_device() under MPI, else 0) and returns its
  // record's bytes. A setting the model refuses (a contact too stiff for the time step) is a record
  // whose status says why. `frame_done` hears each frame (a refused job's all at once).
  std::vector<std::uint8_t> run_job(std::size_t j, BackendKind backend, int cuda_device,
                                    const std::function<void()>& frame_done = {}) const;

 private:
  Scene base_;
  StudySpec spec_;
  std::vector<StudySetting> settings_;
  std::vector<StudyLadder> ladders_;
  std::vector<int> snapshots_;
  int grid_w_ = 0, grid_h_ = 0;
  std::uint64_t key_ = 0;
  std::vector<double> setting_costs_;  // job_cost() of each setting's jobs

  // The base scene with every knob of the study at its finest but `knob` at `value` (none: all).
  Scene at_reference_but(const Knob* knob, double value) const;
};

// Every job of the study in turn, in this process, on the backend each names: the records in job
// order, as analyse() takes them. The one place a runner that spreads the jobs out replaces.
std::vector<std::vector<std::uint8_t>> run_all_jobs(const Study& study, const std::function<void()>& frame_done = {});

}  // namespace bleedsim
