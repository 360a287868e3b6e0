// bleedsim study: what accuracy costs in time, and whether the reference is converged. The scene's
// knobs each climbed as a ladder, every setting an ensemble over seeds, run as independent jobs
// (shared among MPI ranks, or split into shards that `bleedsim study merge` puts back together:
// docs/scale-out.md), analysed from their records; study.csv, ladders.csv, jobs.csv, study.h5 and
// the plots (scripts/plot-study) in the output folder (docs/accuracy.md).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/output_folder.h"
#include "cli/progress.h"
#include "cli/study_description.h"
#include "core/runtime/build_info.h"
#include "core/runtime/input_error.h"
#include "core/runtime/input_file.h"
#include "core/runtime/message_text.h"
#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/scaleout/job_assignment.h"
#include "core/scaleout/run_jobs.h"
#include "core/scaleout/shard_file.h"
#include "core/study/study_output.h"

namespace bleedsim::cli {
namespace {

namespace fs = std::filesystem;

std::vector<BackendKind> backends_for(const std::string& which) {
  if (which == "cpu") return {BackendKind::cpu};
  std::string why_not;
  const bool cuda = cuda_device_available(&why_not);
  if (which == "cuda" || which == "both") {
    if (!cuda) throw InputError({}, "--backend", "no CUDA device to time on: " + why_not);
    return which == "cuda" ? std::vector<BackendKind>{BackendKind::cuda}
                           : std::vector<BackendKind>{BackendKind::cuda, BackendKind::cpu};
  }
  // auto: the GPU when there is one, the CPU always.
  return cuda ? std::vector<BackendKind>{BackendKind::cuda, BackendKind::cpu} : std::vector<BackendKind>{BackendKind::cpu};
}

// scripts/plot-study from the working folder or the source tree (the one BLEEDSIM_SOURCE_DIR names,
// as the tests do where the tree is not where it was built, else the build's), with Debian's Python
// (or the one BLEEDSIM_PYTHON names).
std::string plot_command(const fs::path& folder) {
  const fs::path here = "scripts/plot-study";
  const char* source = std::getenv("BLEEDSIM_SOURCE_DIR");
  const fs::path tree = source && *source ? source : BLEEDSIM_SOURCE_DIR;
  const fs::path script = fs::exists(here) ? here : tree / here;
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

// Names one study: what it runs (Study::key: the scene, its settings, seeds, backends and grid), the
// scenario's text, the bytes of every file it names (the key hashes the tissue's pixels, not a trace,
// a mesh or a vessel map) and the build that ran it (shards of another build must not mix).
std::string fingerprint_of(const Study& study, const Scenario& scenario) {
  std::string text = hex64(study.key()) + "\n" + scenario.text + "\n" + git_sha();
  for (const InputFile& file : scenario.files) text += "\n" + file.key + " " + hex64(hash_of_file(file));
  return hex64(fnv1a64(text.data(), text.size()));
}

std::vector<double> job_costs(const Study& study) {
  std::vector<double> costs(study.job_count());
  for (std::size_t j = 0; j < costs.size(); ++j) costs[j] = study.job_cost(j);
  return costs;
}

// jobs.csv: which rank, host and device ran each job, and how long it took: provenance, apart from
// the data (it differs from run to run).
void write_jobs_csv(const fs::path& path, const Study& study, const std::vector<JobResult>& results) {
  const fs::path partial = path.string() + ".partial";
  FILE* f = std::fopen(partial.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write '" + partial.string() + "': " + std::strerror(errno));
  std::fprintf(f, "job,knob,value,role,seed,backend,rank,host,cuda_device,seconds\n");
  for (const JobResult& r : results) {
    const Study::Job job = study.job(r.job);
    const StudySetting& s = study.settings()[job.setting];
    std::fprintf(f, "%zu,%s,%s,%s,%llu,%s,%d,%s,%d,%.6f\n", r.job, s.knob.c_str(), format_number(s.value).c_str(),
                 s.role.c_str(), static_cast<unsigned long long>(study.seed_of(job.seed_index)), to_string(job.backend),
                 r.origin.rank, r.origin.host.c_str(), r.origin.cuda_device, r.origin.seconds);
  }
  const bool written = std::fflush(f) == 0 && std::ferror(f) == 0;
  const int reason = errno;  // the failed write's (EFBIG, ENOSPC), or the close's
  if (std::fclose(f) != 0 || !written) {
    std::error_code ignored;  // the failure being reported matters more than this one
    fs::remove(partial, ignored);
    throw std::runtime_error("cannot write '" + partial.string() + "': " + std::strerror(written ? errno : reason));
  }
  fs::rename(partial, path);
}

// Each rank's share: the jobs it ran, their time and its device.
void print_ranks(const std::vector<JobResult>& results) {
  struct Share {
    std::string host;
    int device = -1;
    long jobs = 0;
    double seconds = 0;
  };
  std::vector<Share> shares;
  for (const JobResult& r : results) {
    if (shares.size() <= std::size_t(r.origin.rank)) shares.resize(std::size_t(r.origin.rank) + 1);
    Share& share = shares[std::size_t(r.origin.rank)];
    share.host = r.origin.host;
    share.device = r.origin.cuda_device;
    ++share.jobs;
    share.seconds += r.origin.seconds;
  }
  if (shares.size() < 2) return;
  for (std::size_t rank = 0; rank < shares.size(); ++rank) {
    const Share& s = shares[rank];
    const std::string device = s.device >= 0 ? "CUDA device " + std::to_string(s.device) : "no CUDA device";
    std::printf("bleedsim study: rank %zu on %s, %s: %ld jobs in %.1f s\n", rank, s.host.c_str(), device.c_str(), s.jobs,
                s.seconds);
  }
}

// What a study writes, by name in its folder: its files and the plots drawn from them.
const std::vector<std::string>& study_file_names() {
  static const std::vector<std::string> names = {"study.csv", "ladders.csv", "jobs.csv", "study.h5", "plots"};
  return names;
}

// The analysis of every job's record, in job order, and the files and plots from it, written into
// the partial folder and swapped in together.
int analyse_and_write(const Study& study, const Scenario& scenario, const std::vector<JobResult>& results,
                      OutputFiles& files, bool plots, bool quiet) {
  std::vector<std::vector<std::uint8_t>> records;
  records.reserve(results.size());
  for (const JobResult& r : results) records.push_back(r.record);
  const StudyResult result = analyse(study, records);
  const Scene& scene = study.scene();
  write_study_files(files.partial("").string(), study, result,
                    {{"bleedsim_version", version()}, {"git_sha", git_sha()}, {"build_flags", build_flags()},
                     {"scene_name", scene.name}, {"scenario_path", scenario.path}, {"scenario_text", scenario.text}});
  write_jobs_csv(files.partial("jobs.csv"), study, results);
  const bool plotted = plots && std::system(plot_command(files.partial("")).c_str()) == 0;
  files.publish();
  if (!quiet) {
    print_results(study, result);
    print_ranks(results);
  }
  std::printf("bleedsim study: wrote %s, %s, %s and %s\n", files.published("study.csv").string().c_str(),
              files.published("ladders.csv").string().c_str(), files.published("jobs.csv").string().c_str(),
              files.published("study.h5").string().c_str());
  if (plots && !plotted)
    std::fprintf(stderr, "bleedsim study: plots not drawn (they need Debian's python3-matplotlib and python3-h5py); "
                         "draw them where they are installed with: scripts/plot-study %s\n",
                 files.published("").string().c_str());
  return 0;
}

// The longest path a study makes in its folder: in the partial folder, its files under their
// temporary names or a plot as scripts/plot-study writes it (plots/.NAME.png.tmp, one per knob);
// or a shard as shard_file.cpp writes it (NAME.partial-PID; 4194304 is the largest pid Linux gives).
std::string longest_study_path(const Study& study, const std::optional<ShardId>& shard) {
  if (shard) return shard_file_name(*shard) + ".partial-4194304";
  std::vector<std::string> paths = {"study.csv.partial", "ladders.csv.partial", "jobs.csv.partial", "study.h5.partial",
                                    "plots/.distributions.png.tmp", "plots/.pareto.png.tmp"};
  for (const StudyLadder& ladder : study.ladders()) paths.push_back(std::string("plots/.") + ladder.knob->name + ".png.tmp");
  return OutputFiles::longest_path(paths);
}

fs::path out_dir_for(const std::optional<std::string>& out_dir, const Scene& scene) {
  return out_dir ? fs::path(*out_dir) : fs::path("out/study") / scene.name;
}

}  // namespace

int study_command(const StudyOptions& options, const Ranks& ranks) {
  // Every rank reads the same input and so refuses the same bad input, before any rank runs a job.
  const Scenario scenario = load_scenario(options.scenario);
  const Scene& scene = scenario.scene;
  StudySpec spec;
  for (const std::string& text : options.knobs) spec.knobs.push_back(parse_knob(text));
  spec.backends = backends_for(options.backend);
  spec.duration_s = options.duration_s;
  spec.seeds = options.seeds;
  spec.cpu_threads = options.threads;
  const Study study(scene, spec);
  const std::optional<ShardId> shard = options.shard ? std::optional<ShardId>(parse_shard(*options.shard)) : std::nullopt;
  const fs::path dir = out_dir_for(options.out_dir, scene);

  // Rank 0 alone takes the output folder (a shard's shares its folder with the other shards' files,
  // written whole under their own names); every rank hears whether it could.
  std::optional<OutputFolder> folder;
  std::optional<OutputFiles> files;
  std::exception_ptr refused;
  if (ranks.is_root()) {
    try {
      if (shard) {
        check_room_for_paths(dir, longest_study_path(study, shard), SourcePlace{}, "--out");
        fs::create_directories(dir);
      } else {
        folder.emplace(dir, longest_study_path(study, shard), SourcePlace{}, "--out");
        files.emplace(*folder, study_file_names());
        folder->keep();
      }
    } catch (const fs::filesystem_error& e) {
      refused = std::make_exception_ptr(InputError({}, "--out", "cannot make " + dir.string() + ": " + e.code().message()));
    } catch (...) {
      refused = std::current_exception();
    }
  }
  if (!ranks.all_ok(!refused)) {
    if (refused) std::rethrow_exception(refused);
    return kExitBadInput;
  }

  const std::vector<double> costs = job_costs(study);
  std::vector<std::size_t> jobs;
  if (shard) jobs = jobs_of_part(assign_jobs(costs, shard->count), shard->index);
  else for (std::size_t j = 0; j < costs.size(); ++j) jobs.push_back(j);
  if (!options.quiet && ranks.is_root())
    std::printf("bleedsim study: %s: %zu settings x %d seeds on %zu backend(s), %zu runs of %d frames%s%s; "
                "reference: %s; compared on %d x %d cells at %zu snapshot frames\n",
                scene.name.c_str(), study.settings().size(), study.seeds(), study.backends().size(), jobs.size(),
                study.frames_per_run(), shard ? (" (shard " + *options.shard + ")").c_str() : "",
                ranks.size() > 1 ? (" over " + std::to_string(ranks.size()) + " ranks").c_str() : "",
                study.reference_description().c_str(), study.grid_width(), study.grid_height(),
                study.snapshot_frames().size());
  std::fflush(stdout);
  // The progress bar follows this process's own jobs (all of them in one process).
  long frames_here = 0;
  const std::vector<int> owners = assign_jobs([&] {
    std::vector<double> c;
    for (const std::size_t j : jobs) c.push_back(costs[j]);
    return c;
  }(), ranks.size());
  for (std::size_t k = 0; k < jobs.size(); ++k) frames_here += owners[k] == ranks.rank() ? study.frames_per_run() : 0;
  Progress progress(frames_here, !options.quiet && ranks.is_root() && isatty(STDERR_FILENO));
  long frames = 0;
  const int device = std::max(0, ranks.cuda_device());
  const std::vector<JobResult> results = run_jobs(ranks, costs, jobs, [&](std::size_t j) {
    return study.run_job(j, study.job(j).backend, device, [&] { progress.update(++frames); });
  });
  progress.clear();
  if (!ranks.is_root()) return 0;

  if (shard) {
    const fs::path path = dir / shard_file_name(*shard);
    write_shard(path.string(),
                {fingerprint_of(study, scenario), describe_study(scenario, options.knobs, spec), costs.size(), *shard, results});
    std::printf("bleedsim study: wrote %s (%zu of %zu jobs); merge the %d shards with: bleedsim study merge\n",
                path.string().c_str(), results.size(), costs.size(), shard->count);
    return 0;
  }
  return analyse_and_write(study, scenario, results, *files, options.plots, options.quiet);
}

int study_merge_command(const StudyMergeOptions& options) {
  // Every shard is read and checked before anything is made.
  const MergedShards merged = merge_shards(options.shards);
  const std::string& first = options.shards.front();
  const DescribedStudy described = read_study_description(merged.study, first);
  // The scenario as the shards ran it, wherever this runs: its text from the shard, the files it names
  // beside its absolute path.
  const Scenario scenario = parse_scenario(described.scenario_text, described.scenario_path);
  const Study study(scenario.scene, described.spec);
  if (fingerprint_of(study, scenario) != merged.fingerprint)
    throw InputError({}, first,
                     "its study is not the one " + described.scenario_path + "'s text and this build make now (a "
                     "file it names or bleedsim changed since the shards were written)");
  OutputFolder folder(out_dir_for(options.out_dir, study.scene()), longest_study_path(study, std::nullopt), SourcePlace{},
                      "--out");
  OutputFiles files(folder, study_file_names());
  folder.keep();
  if (!options.quiet)
    std::printf("bleedsim study merge: %s: %zu shards, %zu jobs\n", study.scene().name.c_str(), merged.shard_count,
                merged.results.size());
  return analyse_and_write(study, scenario, merged.results, files, options.plots, options.quiet);
}

}  // namespace bleedsim::cli
