#pragma once
// The bleedsim subcommands. Each returns the process exit code: 0 done, 1 failed while running,
// 2 bad input (a scenario, texture, option or output path), 130 interrupted.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/scenario.h"
#include "core/io/trace_synth.h"
#include "core/runtime/backend.h"
#include "core/scaleout/ranks.h"
#include "core/simulation/simulation.h"
#include "core/study/study.h"

namespace bleedsim::cli {

constexpr int kExitFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInterrupted = 130;

struct RunOptions {
  std::string scenario;
  BackendChoice backend;
  std::optional<std::string> out_dir;  // overrides [output].dir
  std::optional<int> png_every;        // overrides [output].png_every
  std::optional<int> contact_sheet;    // overrides [output].contact_sheet
  bool hdf5 = true;
  bool quiet = false;
  int output_threads = 0;              // threads encoding the frames; 0: one per hardware thread
  std::vector<std::string> overrides;  // --set: load_scenario's ("table.key=value" each)
};

int run_command(const RunOptions& options);
// The scenario's simulation on the backend asked for; an InputError placed in the scenario file. The
// scene is moved into it, not copied (a trace's samples can be most of it): scenario.scene is left empty.
std::unique_ptr<Simulation> make_simulation(Scenario& scenario, const BackendChoice& backend);

struct StudyOptions {
  std::string scenario;
  std::vector<std::string> knobs;      // "substeps=10,20,40"; none: every knob the scene has
  std::string backend = "auto";        // auto (CUDA and CPU where a device is, else CPU), cpu, cuda, both
  std::optional<double> duration_s;    // a shorter run than the scene's
  std::optional<std::string> out_dir;  // default out/study/<scene>
  int seeds = kDefaultSeeds;           // each setting's ensemble
  int threads = 0;                     // the CPU backend's threads; 0: one per hardware thread
  std::optional<std::string> shard;    // "i/K": run part i of K and write its shard file
  bool plots = true;
  bool quiet = false;
};

// The study's jobs are shared among `ranks` (MPI, or this process alone); rank 0 writes.
int study_command(const StudyOptions& options, const Ranks& ranks);

struct StudyMergeOptions {
  std::vector<std::string> shards;     // the shard files of one study
  std::optional<std::string> out_dir;  // default out/study/<scene>
  bool plots = true;
  bool quiet = false;
};

int study_merge_command(const StudyMergeOptions& options);
// `overrides` as load_scenario's.
int validate_command(const std::string& scenario, const std::vector<std::string>& overrides);
// `overrides`: load_scenario's ("table.key=value" each).
int hash_command(const std::string& scenario, const BackendChoice& backend, const std::vector<std::string>& overrides);
int info_command();
// "text", "json" or "markdown".
int params_command(const std::string& format);
int trace_info_command(const std::string& path, double max_repair_gap_ms);
// Each scenario's trace through its haptic loop, contact by contact (docs/haptics.md, "Force quality");
// `overrides` as load_scenario's.
int trace_quality_command(const std::vector<std::string>& scenarios, const std::vector<std::string>& overrides);

struct SynthOptions {
  std::string out;
  SynthSpec spec;                    // its strokes replaced by `strokes` when any are given
  std::vector<std::string> strokes;  // each --stroke as given: x0,y0,x1,y1 in mm
  bool force = false;                // overwrite `out` if it exists
};

int trace_synth_command(const SynthOptions& options);

}  // namespace bleedsim::cli
