// bleedsim study: what accuracy costs in time, and whether the reference is converged. The scene's
// knobs each climbed as a ladder, every setting an ensemble over seeds, run as independent jobs,
// analysed from their records; study.csv, ladders.csv, study.h5 and the plots (scripts/plot-study)
// in the output folder (docs/accuracy.md).
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

// "substeps=10,20,40" as a knob and its levels.
KnobLevels parse_knob(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const Knob* knob = find_knob(name);
  if (!knob) throw InputError({}, "--knob", unknown_knob_message(name));
  if (equals == std::string::npos || equals + 1 == text.size())
    throw InputError({}, "--knob", "write it as " + name + "=v1,v2,... (got '" + text + "')");
  KnobLevels levels{knob, {}};
  std::size_t at = equals + 1;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string value = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0')
      throw InputError({}, std::string("--knob ") + name, "expected numbers separated by commas, got '" + value + "'");
    levels.levels.push_back(v);
    at = comma + 1;
  }
  return levels;
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
  // auto: the GPU when there is one, the CPU always.
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
std::string short_number(double v) { return std::isnan(v) ? "" : format_significant(v, 3); }
std::string plus_minus(const Estimate& e) {
  if (std::isnan(e.value)) return "";
  return short_number(e.value) + (std::isnan(e.lo) ? "" : " ±" + short_number(e.half_width()));
}

std::size_t metric_index(Metric m) {
  for (std::size_t i = 0; i < metrics().size(); ++i)
    if (metrics()[i].metric == m) return i;
  return 0;
}

void print_results(const Study& study, const StudyResult& result) {
  // The primary field: the film where the scene has one, else the stain.
  const bool film = !std::isnan(result.seed_spread[metric_index(Metric::film)].value);
  const std::size_t primary = metric_index(film ? Metric::film : Metric::stain);
  const char* unit = metrics()[primary].unit;
  std::printf("%-16s %8s %-10s %-5s %10s %16s %14s %18s  %s\n", "knob", "value", "role", "on", "ms/frame",
              film ? "film L1 mm" : "stain L1", "PSNR dB", (std::string("mean dist ") + unit).c_str(), "status");
  for (const SettingResult& s : result.settings) {
    const RunDistances& d = s.against_reference;
    const std::string value = s.setting.role == "reference" || s.setting.role == "scene" ? "" : short_number(s.setting.value);
    for (const SettingTiming& t : s.timing)
      std::printf("%-16s %8s %-10s %-5s %10s %16s %14s %18s  %s\n", s.setting.knob.c_str(), value.c_str(),
                  s.setting.role.c_str(), to_string(t.backend), short_number(t.ms_p50).c_str(),
                  plus_minus(film ? d.film_l1_mm : d.stain_l1).c_str(), plus_minus(d.frame_psnr_db).c_str(),
                  plus_minus(s.distance[primary].rms).c_str(), s.status.c_str());
  }
  const RunDistances& f = result.noise_floor;
  std::printf("%-16s %8s %-10s %-5s %10s %16s %14s %18s  %s\n", "reference", "", "noise", "", "",
              plus_minus(film ? f.film_l1_mm : f.stain_l1).c_str(), plus_minus(f.frame_psnr_db).c_str(),
              plus_minus(result.seed_spread[primary]).c_str(), "two seeds' runs; one run's seed spread");
  for (std::size_t l = 0; l < result.ladders.size(); ++l) {
    const LadderResult& ladder = result.ladders[l];
    std::string levels;
    for (const double v : ladder.values) levels += (levels.empty() ? "" : ", ") + short_number(v);
    std::printf("ladder %s (%s): %s: %s\n", ladder.knob.c_str(), levels.c_str(), metrics()[primary].name,
                ladder.per_metric[primary].fit.statement.c_str());
  }
  std::printf("reference (%s): %s\n", study.reference_description().c_str(), result.check.verdict.c_str());
}

}  // namespace

int study_command(const StudyOptions& options) {
  const Scenario scenario = load_scenario(options.scenario);
  const Scene& scene = scenario.scene;
  StudySpec spec;
  for (const std::string& text : options.knobs) spec.knobs.push_back(parse_knob(text));
  spec.backends = backends_for(options.backend);
  spec.duration_s = options.duration_s;
  spec.seeds = options.seeds;
  spec.cpu_threads = options.threads;
  const Study study(scene, spec);

  const fs::path dir = options.out_dir ? fs::path(*options.out_dir) : fs::path("out/study") / scene.name;
  OutputFolder folder(dir, {}, "--out");
  if (!options.quiet)
    std::printf("bleedsim study: %s: %zu settings x %d seeds on %zu backend(s), %zu runs of %d frames; reference: %s; "
                "compared on %d x %d cells at %zu snapshot frames\n",
                scene.name.c_str(), study.settings().size(), study.seeds(), study.backends().size(), study.job_count(),
                study.frames_per_run(), study.reference_description().c_str(), study.grid_width(), study.grid_height(),
                study.snapshot_frames().size());
  std::fflush(stdout);
  Progress progress(long(study.job_count()) * study.frames_per_run(), !options.quiet && isatty(STDERR_FILENO));
  long frames = 0;
  const std::vector<std::vector<std::uint8_t>> records = run_all_jobs(study, [&] { progress.update(++frames); });
  progress.clear();
  const StudyResult result = analyse(study, records);

  write_study_files(folder.path().string(), study, result,
                    {{"bleedsim_version", version()}, {"git_sha", git_sha()}, {"build_flags", build_flags()},
                     {"scene_name", scene.name}, {"scenario_path", scenario.path}, {"scenario_text", scenario.text}});
  folder.keep();
  if (!options.quiet) print_results(study, result);
  std::printf("bleedsim study: wrote %s, %s and %s\n", (folder.path() / "study.csv").string().c_str(),
              (folder.path() / "ladders.csv").string().c_str(), (folder.path() / "study.h5").string().c_str());
  if (options.plots) {
    if (std::system(plot_command(folder.path()).c_str()) != 0)
      std::fprintf(stderr, "bleedsim study: plots not drawn (they need Debian's python3-matplotlib and python3-h5py); "
                           "draw them where they are installed with: scripts/plot-study %s\n",
                   folder.path().string().c_str());
  }
  return 0;
}

}  // namespace bleedsim::cli
