// bleedsim study: what accuracy costs in time. The scene at each setting of its accuracy knobs, on
// each backend, timed and compared frame by frame with the reference at the finest settings;
// study.csv, study.h5 and the plots (scripts/plot-study) in the output folder (docs/accuracy.md).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output_folder.h"
#include "cli/progress.h"
#include "core/runtime/build_info.h"
#include "core/runtime/input_error.h"
#include "core/runtime/message_text.h"
#include "core/io/scenario.h"
#include "core/study/study_output.h"

namespace bleedsim::cli {
namespace {

namespace fs = std::filesystem;

// "substeps=10,20,40" as a knob and its values.
KnobSweep parse_knob(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const Knob* knob = find_knob(name);
  if (!knob) {
    std::string known;
    for (const Knob& k : knobs()) known += std::string(known.empty() ? "" : ", ") + k.name;
    throw InputError({}, "--knob", "no knob '" + name + "' (known: " + known + ")");
  }
  if (equals == std::string::npos || equals + 1 == text.size())
    throw InputError({}, "--knob", "write it as " + name + "=v1,v2,... (got '" + text + "')");
  KnobSweep sweep{knob, {}};
  std::size_t at = equals + 1;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string value = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0')
      throw InputError({}, std::string("--knob ") + name, "expected numbers separated by commas, got '" + value + "'");
    sweep.values.push_back(v);
    at = comma + 1;
  }
  return sweep;
}

std::vector<BackendKind> backends_for(const std::string& which) {
  std::string why_not;
  const bool cuda = cuda_device_available(&why_not);
  if (which == "cpu") return {BackendKind::cpu};
  if (which == "cuda" || which == "both") {
    if (!cuda) throw InputError({}, "--backend", "no CUDA device to time on: " + why_not);
    return which == "cuda" ? std::vector<BackendKind>{BackendKind::cuda}
                           : std::vector<BackendKind>{BackendKind::cuda, BackendKind::cpu};
  }
  // auto: the GPU when there is one (and so the reference runs there), the CPU always.
  return cuda ? std::vector<BackendKind>{BackendKind::cuda, BackendKind::cpu} : std::vector<BackendKind>{BackendKind::cpu};
}

// scripts/plot-study from the working folder or the source tree, with Debian's Python (or the one
// BLEEDSIM_PYTHON names, as the tests do).
std::string plot_command(const fs::path& folder) {
  const fs::path here = "scripts/plot-study";
  const fs::path script = fs::exists(here) ? here : fs::path(BLEEDSIM_SOURCE_DIR) / here;
  const char* python = std::getenv("BLEEDSIM_PYTHON");
  return "'" + std::string(python ? python : "/usr/bin/python3") + "' '" + script.string() + "' '" + folder.string() + "'";
}

// Three significant digits, or nothing where there is no number.
std::string short_number(double v, bool shown = true) {
  if (!shown || std::isnan(v)) return "";
  return format_significant(v, 3);
}

void print_table(const std::vector<StudyRun>& runs) {
  // The errors against the reference (all knobs finest), then against this knob's finest alone.
  std::printf("%-16s %8s %-16s %-5s %10s %12s %10s %12s %10s  %s\n", "knob", "value", "role", "on", "ms/frame",
              "film L1 mm", "PSNR dB", "own L1 mm", "own PSNR", "status");
  for (const StudyRun& run : runs) {
    const StudySummary s = summarize(run);
    const bool ok = run.status == "ok";
    const bool own = ok && !run.knob_errors.empty();
    std::printf("%-16s %8s %-16s %-5s %10s %12s %10s %12s %10s  %s\n", run.setting.knob.c_str(),
                short_number(run.setting.value, run.setting.role.rfind("reference", 0) != 0).c_str(),
                run.setting.role.c_str(), to_string(run.backend), short_number(s.ms_p50, ok).c_str(),
                short_number(s.mean.film_l1_mm, ok).c_str(), short_number(s.psnr_db, ok).c_str(),
                short_number(s.knob_mean.film_l1_mm, own).c_str(), short_number(s.knob_psnr_db, own).c_str(),
                run.status.c_str());
  }
}

}  // namespace

int study_command(const StudyOptions& options) {
  const Scenario scenario = load_scenario(options.scenario);
  const Scene& scene = scenario.scene;
  StudySpec spec;
  for (const std::string& text : options.knobs) spec.sweeps.push_back(parse_knob(text));
  spec.backends = backends_for(options.backend);
  if (options.duration_s) spec.duration_s = *options.duration_s;
  Study study(scene, spec);

  const fs::path dir = options.out_dir ? fs::path(*options.out_dir) : fs::path("out/study") / scene.name;
  OutputFolder folder(dir, {}, "--out");
  const long runs_to_do = long(study.settings().size() * spec.backends.size()) + 1;
  if (!options.quiet)
    std::printf("bleedsim study: %s: %zu settings on %zu backend(s), %ld frames each; reference: %s; compared on "
                "%d x %d cells\n",
                scene.name.c_str(), study.settings().size(), spec.backends.size(), study.frames_per_run(),
                study.reference_description().c_str(), study.grid_width(), study.grid_height());
  std::fflush(stdout);
  Progress progress(runs_to_do * study.frames_per_run(), !options.quiet && isatty(STDERR_FILENO));
  const std::vector<StudyRun> runs = study.run([&](long frames) { progress.update(frames); });
  progress.clear();

  const fs::path csv = folder.path() / "study.csv", h5 = folder.path() / "study.h5";
  write_study_csv(csv.string(), scene.name, runs);
  write_study_hdf5(h5.string(), study, runs,
                   {{"bleedsim_version", version()}, {"git_sha", git_sha()}, {"build_flags", build_flags()},
                    {"scene_name", scene.name}, {"scenario_path", scenario.path}, {"scenario_text", scenario.text}});
  folder.keep();
  if (!options.quiet) print_table(runs);
  std::printf("bleedsim study: wrote %s and %s\n", csv.string().c_str(), h5.string().c_str());
  if (options.plots) {
    if (std::system(plot_command(folder.path()).c_str()) != 0)
      std::fprintf(stderr, "bleedsim study: plots not drawn (they need Debian's python3-matplotlib); draw them "
                           "where it is installed with: scripts/plot-study %s\n", folder.path().string().c_str());
  }
  return 0;
}

}  // namespace bleedsim::cli
