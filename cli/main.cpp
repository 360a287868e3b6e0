// bleedsim: a thin command line over the library (core/simulation/simulation.h).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/runtime/build_info.h"
#include "core/runtime/input_error.h"
#include "core/study/study.h"

namespace {

using bleedsim::BackendChoice;
using bleedsim::SynthSpec;
using namespace bleedsim::cli;

// A subcommand, and what runs it once the command line has chosen it. The options it was given
// live with `run`, which CLI11 filled in while parsing.
struct Command {
  CLI::App* app;
  std::function<int()> run;
};

// The one of `commands` the command line chose.
int run_chosen(const std::vector<Command>& commands) {
  for (const Command& command : commands)
    if (*command.app) return command.run();
  return kExitFailed;
}

// --backend and --threads, shared by the commands that run a scene.
struct BackendOptions {
  std::string name = "auto";
  int threads = 0;

  BackendChoice choice() const {
    const BackendChoice::Want want = name == "cpu"    ? BackendChoice::Want::cpu
                                     : name == "cuda" ? BackendChoice::Want::cuda
                                                      : BackendChoice::Want::automatic;
    return BackendChoice{want, threads};
  }
};

void add_backend_options(CLI::App& command, BackendOptions& options) {
  command.add_option("-b,--backend", options.name, "auto (CUDA when a device is present), cpu or cuda")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
      ->capture_default_str();
  command.add_option("-j,--threads", options.threads,
                     "CPU threads for the cpu backend (0: one per hardware thread)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
}

// A seed as a plain decimal: CLI11 alone would read "-1" as 2^64 - 1 and "010" as octal 8.
std::string decimal_seed(std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    return "must be a whole number, 0 or more (got '" + text + "')";
  errno = 0;
  const unsigned long long seed = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return "must be at most " + std::to_string(seed) + " (got " + text + ")";
  text = std::to_string(seed);
  return "";
}

// The options of `bleedsim study` or `study merge`, and --no-plots beside them: CLI11 sets a flag's
// own bool, of which `plots` is the opposite.
template <class Options>
struct WithNoPlots {
  Options options;
  bool no_plots = false;

  const Options& parsed() {
    options.plots = !no_plots;
    return options;
  }
};

// What a command that failed says, in one line whatever a library put in its message. The readers
// and the run count their memory before allocating it; running out anyway is said plainly, naming
// the command (`command`: "bleedsim run"), not as a bare std::bad_alloc.
std::string failure_text(const std::exception& e, const std::string& command) {
  if (dynamic_cast<const std::bad_alloc*>(&e)) return "out of host memory while running '" + command + "'";
  std::string what = e.what();
  for (char& c : what)
    if (c == '\n' || c == '\r') c = ' ';
  return what;
}

// `bleedsim study` over the MPI ranks a launcher started (or this process alone): every rank runs
// its share of the jobs; an error ends every rank, and only rank 0 says it (every rank would say
// the same). The ranks end MPI together when Ranks goes.
int study_on_ranks(const StudyOptions& study) {
  if (study.scenario.empty()) throw bleedsim::InputError({}, "study", "needs a scenario file (or: bleedsim study merge SHARDS...)");
  bleedsim::Ranks ranks(study.backend != "cpu");
  try {
    return study_command(study, ranks);
  } catch (const bleedsim::InputError& e) {
    if (ranks.is_root()) std::cerr << "bleedsim: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    if (ranks.is_root()) std::cerr << "bleedsim: failed: " << failure_text(e, "bleedsim study") << "\n";
    return kExitFailed;
  }
}

// --set table.key=value, repeatable: a value over the scenario file's, checked as if written there
// (load_scenario's overrides; the Python module's dict). `what` says what it sets.
void add_set_option(CLI::App& command, std::vector<std::string>& overrides,
                    const std::string& what = "a value over the file's, checked as if written there; repeat for "
                                              "more (the Python module's overrides, docs/python.md)") {
  command.add_option("--set", overrides, "table.key=value (TOML): " + what)->allow_extra_args(false);
}

Command add_run_command(CLI::App& app) {
  struct Given {
    RunOptions run;
    BackendOptions backend;
    bool no_hdf5 = false;
  };
  const auto given = std::make_shared<Given>();
  RunOptions& run = given->run;
  CLI::App* command = app.add_subcommand("run", "run a scenario and write its frames (HDF5, PNG)");
  command->add_option("scenario", run.scenario, "scenario file (.toml)")->required();
  add_backend_options(*command, given->backend);
  command->add_option("-o,--out", run.out_dir, "output folder (default: the scenario's [output].dir)");
  command->add_option("--png-every", run.png_every, "write a PNG of frame 0, every Nth frame and the last (0: none)")
      ->check(CLI::Range(0, 1000000));
  command->add_option("--contact-sheet", run.contact_sheet,
                      "write contact_sheet.png: N frames from the first to the last in a grid (0: none)")
      ->check(CLI::Range(0, 64));
  command->add_flag("--no-hdf5", given->no_hdf5, "do not write frames.h5");
  command->add_option("--output-threads", run.output_threads,
                      "threads deflating and encoding the frames for the files (0: one per hardware thread)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_flag("-q,--quiet", run.quiet, "print nothing but errors");
  add_set_option(*command, run.overrides);
  return {command, [given] {
            given->run.backend = given->backend.choice();
            given->run.hdf5 = !given->no_hdf5;
            return run_command(given->run);
          }};
}

Command add_validate_command(CLI::App& app) {
  struct Given {
    std::string scenario;
    std::vector<std::string> overrides;
  };
  const auto given = std::make_shared<Given>();
  CLI::App* command = app.add_subcommand("validate", "check a scenario and describe it");
  command->add_option("scenario", given->scenario, "scenario file (.toml)")->required();
  add_set_option(*command, given->overrides);
  return {command, [given] { return validate_command(given->scenario, given->overrides); }};
}

Command add_hash_command(CLI::App& app) {
  struct Given {
    std::string scenario;
    BackendOptions backend;
    std::vector<std::string> overrides;
  };
  const auto given = std::make_shared<Given>();
  CLI::App* command =
      app.add_subcommand("hash", "print each frame's per-field FNV-1a 64 hashes (writes no files)");
  command->add_option("scenario", given->scenario, "scenario file (.toml)")->required();
  add_backend_options(*command, given->backend);
  add_set_option(*command, given->overrides);
  return {command, [given] { return hash_command(given->scenario, given->backend.choice(), given->overrides); }};
}

// "name1, name2, ...": every knob a study may climb, for --knob's help.
std::string knob_names() {
  std::string names;
  for (const bleedsim::Knob& knob : bleedsim::knobs()) names += std::string(names.empty() ? "" : ", ") + knob.name;
  return names;
}

Command add_study_merge_command(CLI::App& study) {
  const auto given = std::make_shared<WithNoPlots<StudyMergeOptions>>();
  StudyMergeOptions& merge = given->options;
  CLI::App* command = study.add_subcommand(
      "merge", "put the shard files of one study (--shard i/K) back together and analyse them, as one process would");
  command->add_option("shards", merge.shards, "the study's shard files (.bleedshard), in any order")->required();
  command->add_option("-o,--out", merge.out_dir, "output folder (default out/study/<scene>)");
  command->add_flag("--no-plots", given->no_plots, "write the files only (plot later with scripts/plot-study)");
  command->add_flag("-q,--quiet", merge.quiet, "print only the files written and errors");
  return {command, [given] { return study_merge_command(given->parsed()); }};
}

Command add_study_command(CLI::App& app) {
  const auto given = std::make_shared<WithNoPlots<StudyOptions>>();
  StudyOptions& study = given->options;
  CLI::App* command = app.add_subcommand(
      "study", "what accuracy costs in time, and whether the reference is converged: each accuracy knob "
               "climbed as a ladder, every setting an ensemble over seeds, timed and compared with the reference "
               "(docs/accuracy.md)");
  command->add_option("scenario", study.scenario, "scenario file (.toml)");
  command->add_option("-k,--knob", study.knobs,
                      "a knob and its ladder's levels, as name=v1,v2,...; the finest is the reference's; repeat "
                      "for more (default: every knob the scene has, at its default levels). Knobs: " + knob_names() +
                          " (the particle model has no solver iterations: one neighbour pass a sub-step)");
  command->add_option("-b,--backend", study.backend,
                      "auto (CUDA and the CPU where a device is, else the CPU), cpu, cuda or both")
      ->check(CLI::IsMember({"auto", "cpu", "cuda", "both"}))
      ->capture_default_str();
  command->add_option("-s,--seeds", study.seeds,
                      "runs of each setting, the scene's seed and the next ones (at least 2: a confidence "
                      "interval needs two)")
      ->capture_default_str();
  command->add_option("-j,--threads", study.threads, "CPU threads for the cpu backend (0: one per hardware thread)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_option("--duration-s", study.duration_s, "run each setting this long instead of the scene's duration")
      ->check(CLI::Range(0.001, 86400.0));
  command->add_option("-o,--out", study.out_dir, "output folder (default out/study/<scene>)");
  command->add_flag("--no-plots", given->no_plots,
                    "write study.csv, ladders.csv and study.h5 only (plot later with scripts/plot-study)");
  command->add_flag("-q,--quiet", study.quiet, "print only the files written and errors");
  command->add_option("--shard", study.shard,
                      "i/K: run only part i of K (0 <= i < K) and write OUT/shard-i-of-K.bleedshard, for a "
                      "cluster's job array; `bleedsim study merge` analyses the K files (docs/scale-out.md)");
  const Command merge = add_study_merge_command(*command);
  return {command, [given, merge] { return *merge.app ? merge.run() : study_on_ranks(given->parsed()); }};
}

Command add_info_command(CLI::App& app) {
  return {app.add_subcommand("info", "version, build flags and available backends"), info_command};
}

Command add_params_command(CLI::App& app) {
  const auto format = std::make_shared<std::string>("text");
  CLI::App* command = app.add_subcommand(
      "params", "every scenario table's keys: type, unit, default, bounds, rules (docs/scenario-format.md)");
  command->add_flag_callback("--json", [format] { *format = "json"; }, "as JSON, for tools");
  command->add_flag_callback("--markdown", [format] { *format = "markdown"; },
                             "as the tables docs/scenario-format.md holds (scripts/update-param-docs)");
  return {command, [format] { return params_command(*format); }};
}

Command add_trace_info_command(CLI::App& trace) {
  struct Given {
    std::string path;
    double repair_gap_ms = 0.0;
  };
  const auto given = std::make_shared<Given>();
  CLI::App* command = trace.add_subcommand("info", "check a trace and describe it: duration, rate, "
                                                   "workspace used, cuts, repairs");
  command->add_option("trace", given->path, "trace file (.csv)")->required();
  command->add_option("--repair-gap-ms", given->repair_gap_ms,
                      "fill dropouts up to this long by interpolation instead of refusing them (0: none)")
      ->check(CLI::Range(0.0, 1000.0));
  return {command, [given] { return trace_info_command(given->path, given->repair_gap_ms); }};
}

Command add_trace_quality_command(CLI::App& trace) {
  struct Given {
    std::vector<std::string> scenarios;
    std::vector<std::string> overrides;
  };
  const auto given = std::make_shared<Given>();
  CLI::App* command = trace.add_subcommand(
      "quality", "the force each scenario's trace renders, contact by contact: depth, rise time, force rate, power "
                 "above 30 Hz, overshoot, passivity margin D - W, ticks at the cap (docs/haptics.md)");
  command->add_option("scenarios", given->scenarios,
                      "scenario files (.toml) with a [haptics] trace: the scene gives the force (surface or mesh, "
                      "spring, damper, cap), the trace the motion")
      ->required();
  add_set_option(*command, given->overrides,
                 "over every scenario's, e.g. scene.duration_s=8 to play a trace to its end; repeat for more");
  return {command, [given] { return trace_quality_command(given->scenarios, given->overrides); }};
}

// Ranges are checked by synthesize_trace, which names the option at fault.
Command add_trace_synth_command(CLI::App& trace) {
  const auto synth = std::make_shared<SynthOptions>();
  SynthSpec& spec = synth->spec;
  CLI::App* command = trace.add_subcommand(
      "synth", "write a realistic synthetic trace: cutting strokes with a hand tremor, the same for the same seed");
  command->add_option("-o,--out", synth->out, "trace file to write (.csv)")->required();
  command->add_option("--seed", spec.seed, "draws the tremor")
      ->transform(CLI::Validator(decimal_seed, ""))
      ->capture_default_str();
  command->add_option("--stroke", synth->strokes,
                      "a stroke from (x0, y0) to (x1, y1), mm in the device frame (x right, y up), as "
                      "x0,y0,x1,y1[,buttons]: the grip buttons held along it, 1 (cut) unless given, 2 for the "
                      "suction's; repeat for more strokes (default: one cut, -10,0,10,0)")
      ->allow_extra_args(false);
  struct SynthNumber {
    const char* option;
    double* value;
    const char* help;
  };
  for (const SynthNumber& number : std::initializer_list<SynthNumber>{
           {"--surface-z-mm", &spec.surface_z_mm, "device z of the tissue surface"},
           {"--depth-mm", &spec.depth_mm, "how far below the surface a stroke cuts"},
           {"--hover-mm", &spec.hover_mm, "how far above the surface the tool waits"},
           {"--speed-mm-s", &spec.speed_mm_s, "speed along a stroke"},
           {"--approach-s", &spec.approach_s, "from hover down to the surface"},
           {"--press-s", &spec.press_s, "from the surface down to depth, button held"},
           {"--lift-s", &spec.lift_s, "from depth back up to hover, button released"},
           {"--pause-s", &spec.pause_s, "above the tissue before the first stroke, between strokes and after the last"},
           {"--tremor-um", &spec.tremor_um, "peak hand tremor per axis, 8-12 Hz (0: none)"},
           {"--rate-hz", &spec.rate_hz, "samples per second (900 to 1100)"}})
    command->add_option(number.option, *number.value, number.help)->capture_default_str();
  command->add_flag("--force", synth->force, "overwrite the file if it exists");
  return {command, [synth] { return trace_synth_command(*synth); }};
}

Command add_trace_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand("trace", "recorded Falcon stylus traces (docs/traces.md)");
  command->require_subcommand(1);
  const std::vector<Command> subcommands = {add_trace_info_command(*command), add_trace_quality_command(*command),
                                            add_trace_synth_command(*command)};
  return {command, [subcommands] { return run_chosen(subcommands); }};
}

// "bleedsim trace info": the program and the subcommands the command line chose.
std::string chosen_command(const CLI::App& app) {
  const std::vector<CLI::App*> chosen = app.get_subcommands();
  const std::string name = app.get_parent() ? app.get_name() : "bleedsim";
  return chosen.empty() ? name : name + " " + chosen_command(*chosen.front());
}

// The chosen command's exit code; an error it ends with is said in one line.
int run_reporting_errors(const std::vector<Command>& commands, const std::string& command) {
  try {
    return run_chosen(commands);
  } catch (const bleedsim::InputError& e) {
    std::cerr << "bleedsim: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "bleedsim: failed: " << failure_text(e, command) << "\n";
    return kExitFailed;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bleedsim: bleeding effects for endoscopic sinus surgery simulation"};
  app.set_version_flag("--version", std::string("bleedsim ") + bleedsim::version() + " (" +
                                        bleedsim::git_sha() + ")");
  app.require_subcommand(1);
  // In the order `bleedsim --help` lists them.
  const std::vector<Command> commands = {add_run_command(app),   add_validate_command(app), add_hash_command(app),
                                         add_study_command(app), add_info_command(app),     add_params_command(app),
                                         add_trace_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  // A file size limit (ulimit -f) must end a write with EFBIG, which the writers report, not kill
  // the process without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  return run_reporting_errors(commands, chosen_command(app));
}
