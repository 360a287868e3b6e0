// bleedsim run: a scenario from start to end, frames to HDF5 and PNG as they are made.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/output_files.h"
#include "cli/output_folder.h"
#include "cli/output_queue.h"
#include "cli/progress.h"
#include "core/effects/particles/particle_model.h"
#include "core/haptics/contact_quality.h"
#include "core/io/contact_sheet.h"
#include "core/io/hdf5_haptic_quality.h"
#include "core/io/hdf5_writer.h"
#include "core/io/scenario.h"
#include "core/io/xdmf_writer.h"
#include "core/mesh/view_render.h"
#include "core/runtime/build_info.h"
#include "core/runtime/timing_summary.h"
#include "core/simulation/simulation.h"

namespace bleedsim::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Ctrl-C or SIGTERM ends the run after the frame being made: every frame so far stays written.
// A second signal takes the default action at once.
std::atomic<bool> interrupted{false};

void on_interrupt(int signal) {
  interrupted = true;
  std::signal(signal, SIG_DFL);
}

struct InterruptGuard {
  InterruptGuard() {
    interrupted = false;
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
  }
  ~InterruptGuard() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
};

// The fields a run writes: the frame first (PNGs are made from it), then those [output].fields
// names, or when it names none, all but the large per-particle arrays.
std::vector<FieldLayout> fields_to_write(const Simulation& sim, const std::vector<std::string>& wanted) {
  std::vector<FieldLayout> specs = {*sim.field("frame").field};
  for (const std::string& name : sim.field_names()) {
    const bool listed = std::find(wanted.begin(), wanted.end(), name) != wanted.end();
    const FieldLayout& field = *sim.field(name).field;
    if (name != "frame" && (wanted.empty() ? !field.on_request : listed)) specs.push_back(field);
  }
  return specs;
}

// `overrides`: the --set lines the scenario was read with (its text is the file's, without them).
std::vector<std::pair<std::string, std::string>> provenance(const Simulation& sim, const Scenario& scenario,
                                                            const std::vector<std::string>& overrides) {
  std::string sets;
  for (const std::string& set : overrides) sets += set + "\n";
  return {{"bleedsim_version", version()},
          {"git_sha", git_sha()},
          {"backend", to_string(sim.backend().kind())},
          {"device", sim.backend().device_name()},
          {"build_flags", build_flags()},
          {"scene_name", sim.scene().name},
          {"scenario_path", scenario.path},
          {"scenario_text", scenario.text},
          {"scenario_overrides", sets}};
}

// What the replay will play: the samples read of the trace (as far as the run goes), their repairs,
// and whether the trace ends before the run.
void describe_replay(const Scene& s) {
  const Trace& trace = *s.trace;
  const double span_s = trace.samples.back().t_s - trace.samples.front().t_s;
  const double played_s = double(s.haptic_ticks_through_frame(s.frame_count() - 1) - 1) / kHapticRate_hz;
  std::printf("bleedsim: replaying %s: %zu samples over %.3f s through the 1 kHz haptic loop%s\n", trace.path.c_str(),
              trace.samples.size(), span_s,
              span_s < played_s ? " (after it ends the stylus stays where the trace left it)"
                                : " (read as far as the run goes)");
  for (const std::string& repair : trace.repairs) std::printf("bleedsim: repaired %s\n", repair.c_str());
  if (trace.repairs_made > trace.repairs.size())
    std::printf("bleedsim: repaired %llu more dropouts\n",
                static_cast<unsigned long long>(trace.repairs_made - trace.repairs.size()));
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The key that named the output folder: --out, [output].dir, or (when neither did) the scene's
// name, from which the folder out/<name> was made.
std::string output_dir_key(const RunOptions& options, const Scenario& scenario) {
  if (options.out_dir) return "--out";
  return scenario.places.count("output.dir") ? "output.dir" : "scene.name";
}

// What the frames the output holds may take: their fields' copies and, about as large at most,
// their encodings.
constexpr std::size_t kOutputMemoryBytes = std::size_t(1) << 30;

// Frames the output holds at once: one for each worker to encode, the one being written and the
// next, within kOutputMemoryBytes; at least two, so that one is encoded while the other is written.
// The simulation runs at most this far ahead of the files.
std::size_t frames_in_flight(int workers, std::size_t frame_bytes) {
  const std::size_t by_memory = kOutputMemoryBytes / std::max<std::size_t>(1, 2 * frame_bytes);
  return std::max<std::size_t>(2, std::min(std::size_t(workers) + 2, by_memory));
}

// A failure while writing: the frames finished so far stay in the partial folder, and the last
// whole run in the folder is untouched. One line, as every failure is.
std::runtime_error write_failure(const std::exception& e, long frames_done, const OutputFiles& files) {
  const std::string kept = frames_done == 0 ? "no frame was finished"
                                            : std::to_string(frames_done) + " finished frame" +
                                                  (frames_done == 1 ? "" : "s") + " kept in " +
                                                  files.partial("").string();
  return std::runtime_error(std::string(e.what()) + "; " + kept + ", the folder's last whole run left as it was");
}

// The scenario with what the command line says over its [output] table.
Scenario scenario_for_run(const RunOptions& options) {
  Scenario scenario = load_scenario(options.scenario, ReadTissue::draw, options.overrides);
  OutputSpec& out = scenario.output;
  if (options.png_every) out.png_every = *options.png_every;
  if (options.contact_sheet) out.contact_sheet = *options.contact_sheet;
  if (options.out_dir) out.dir = *options.out_dir;
  return scenario;
}

void announce(const Simulation& sim) {
  const Scene& s = sim.scene();
  const long frames = s.frame_count();
  std::printf("bleedsim: %s: %ld frames of %d x %d px on %s (%s; %s)\n", s.name.c_str(), frames,
              s.domain.width_px, s.domain.height_px, to_string(sim.backend().kind()),
              sim.backend().device_name().c_str(), sim.backend_reason().c_str());
  if (s.trace) describe_replay(s);
}

// The contact sheets a run fills, when [output].contact_sheet asks for them: the panel's and, for a
// scene with a [view], the endoscope's.
struct ContactSheets {
  std::unique_ptr<ContactSheet> panel, view;
};

ContactSheets contact_sheets(const Scene& s, const Scenario& scenario) {
  ContactSheets sheets;
  const int cells = scenario.output.contact_sheet;
  if (cells > 0)
    sheets.panel = std::make_unique<ContactSheet>(s.frame_count(), cells, s.domain.width_px, s.domain.height_px);
  if (cells > 0 && scenario.view)
    sheets.view = std::make_unique<ContactSheet>(s.frame_count(), cells, scenario.view->width_px,
                                                 scenario.view->height_px);
  return sheets;
}

// The particles' lifetime in steps, which tells the description which slots hold particles; 0 in a
// scene without them.
std::uint32_t lifetime_steps(const Simulation& sim) {
  const ParticleSettings* particles = sim.resolved().find<ParticleSettings>();
  return particles ? particles->lifetime.steps : 0;
}

// Where each frame goes: the HDF5 file (when there is one), the PNGs, the sheets and, for a scene
// with a [view], the mesh drawn with the frame's texture from the scenario's endoscope.
FrameOutputs frame_outputs(const Scene& s, const Scenario& scenario, const OutputFiles& files, Hdf5FrameWriter* hdf5,
                           XdmfWriter* xdmf, ContactSheets& sheets) {
  FrameOutputs outputs;
  outputs.hdf5 = hdf5;
  outputs.xdmf = xdmf;
  outputs.png_folder = files.partial("png");
  outputs.png_every = scenario.output.png_every;
  outputs.frames = s.frame_count();
  outputs.width = s.domain.width_px;
  outputs.height = s.domain.height_px;
  if (scenario.view)
    outputs.view = [&s, &view = *scenario.view](const std::uint8_t* frame) {
      const std::size_t bytes = std::size_t(s.domain.width_px) * std::size_t(s.domain.height_px) * 4;
      return render_view(s.mesh->mesh(),
                         Image{s.domain.width_px, s.domain.height_px, std::vector<std::uint8_t>(frame, frame + bytes)},
                         view);
    };
  outputs.sheet = sheets.panel.get();
  outputs.view_sheet = sheets.view.get();
  return outputs;
}

// The threads encoding the frames: --output-threads, or one per hardware thread.
int output_workers(const RunOptions& options) {
  return options.output_threads > 0 ? options.output_threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

std::size_t frame_bytes(const std::vector<FieldLayout>& specs) {
  std::size_t bytes = 0;
  for (const FieldLayout& spec : specs) bytes += spec.bytes();
  return bytes;
}

// A frame's fields go to the host while the next frame computes (on CUDA; the CPU copies at
// once): two downloads in turn, into the backend's host memory; a frame is queued for its files
// once its copies are whole, after the next frame has been computed.
class FramesToHost {
 public:
  FramesToHost(Simulation& sim, const std::vector<FieldLayout>& specs, OutputQueue& output)
      : sim_(sim),
        specs_(specs),
        output_(output),
        downloads_{sim.make_download(), sim.make_download()},
        empty_field_{HostAllocator<std::uint8_t>(&sim.host_memory())} {}

  // Starts the copies of frame k, just computed, and queues the frame before, whose copies ran
  // while this one computed.
  void copy(long k) {
    FrameJob job = output_.spare();
    job.fields.resize(specs_.size(), empty_field_);
    Download& download = *downloads_[k % 2];
    for (std::size_t f = 0; f < specs_.size(); ++f) {
      const FieldView field = sim_.field(specs_[f].name);
      job.fields[f].resize(field.field->bytes());
      download.add(job.fields[f].data(), field.data, field.field->bytes());
    }
    job.frame = k;
    job.time_s = sim_.time_s();
    job.ticks = sim_.haptic_ticks();
    hand_over();
    in_transit_ = std::move(job);
    carrying_ = &download;
  }

  // Queues the frame whose copies are under way, once they are whole.
  void hand_over() {
    if (!carrying_) return;
    carrying_->finish();
    carrying_ = nullptr;
    output_.push(std::move(in_transit_));
  }

 private:
  Simulation& sim_;
  const std::vector<FieldLayout>& specs_;
  OutputQueue& output_;
  const std::unique_ptr<Download> downloads_[2];
  const HostBytes empty_field_;
  FrameJob in_transit_;
  Download* carrying_ = nullptr;  // in_transit_'s download, while it has one
};

// What a run made: its frames' and haptic ticks' compute times, and what it wrote.
struct RunTally {
  double simulate_s = 0.0;
  std::vector<double> frame_seconds, tick_seconds;
  // Frames written so far: a write that fails (a full disk, a file size limit, an I/O error) ends the run
  // with the frames before it kept, and leaves the folder's last whole run as it was.
  long written = 0;
  long pngs = 0;  // PNG files written, counted on the output's writer thread
  // The force's quality over the ticks made, for a scene that replays a trace: /haptics/quality.
  std::optional<ContactQualityMeter> quality;
};

// The frames, one after another until the last or an interrupt, each queued for its files as it is
// made; returns once every frame made is written, with `tally.written` counting them, a failure's
// too.
void make_frames(Simulation& sim, const std::vector<FieldLayout>& specs, OutputQueue& output, Progress& progress,
                 RunTally& tally) {
  const long frames = sim.scene().frame_count();
  FramesToHost to_host(sim, specs, output);
  try {
    for (long k = 0; k < frames && !interrupted; ++k) {
      const Clock::time_point step_start = Clock::now();
      sim.step();
      to_host.copy(k);
      tally.frame_seconds.push_back(seconds_since(step_start));
      tally.simulate_s += tally.frame_seconds.back();
      if (tally.quality)
        for (const HapticTick& tick : sim.haptic_ticks()) tally.quality->add(tick);
      tally.tick_seconds.insert(tally.tick_seconds.end(), sim.haptic_tick_seconds().begin(),
                                sim.haptic_tick_seconds().end());
      progress.update(k + 1);
    }
    // Every frame made is written, an interrupted run's too.
    to_host.hand_over();
    output.drain();
  } catch (...) {
    // What was made before the failure is written (or fails too) before the count is taken.
    try {
      to_host.hand_over();
    } catch (...) {
    }
    try {
      output.drain();
    } catch (...) {
    }
    tally.written = output.written();
    throw;
  }
  tally.written = output.written();
}

// The run's files in the partial folder: the frames as they are made, into frames.h5 and the PNGs,
// and then the contact sheets.
RunTally write_run(const RunOptions& options, const Scenario& scenario, Simulation& sim, const OutputFiles& files,
                   ContactSheets& sheets, Progress& progress) {
  const Scene& s = sim.scene();
  const long frames = s.frame_count();
  const std::vector<FieldLayout> specs = fields_to_write(sim, scenario.output.fields);
  RunTally tally;
  if (s.trace && options.hdf5) tally.quality.emplace(*s.haptics);
  try {
    std::unique_ptr<Hdf5FrameWriter> writer;
    std::unique_ptr<XdmfWriter> xdmf;
    if (options.hdf5) {
      writer = std::make_unique<Hdf5FrameWriter>(files.partial("frames.h5").string(), specs,
                                                 provenance(sim, scenario, options.overrides), scenario.output.deflate_level,
                                                 s.trace.has_value());
      xdmf = std::make_unique<XdmfWriter>("frames.h5", specs, s.domain.grid(), lifetime_steps(sim));
    }
    if (scenario.output.png_every > 0) fs::create_directory(files.partial("png"));
    // Each frame's outputs, encoded on the output's workers and written on its writer thread, frame
    // after frame: the simulation goes on meanwhile.
    FrameOutput frame_output(frame_outputs(s, scenario, files, writer.get(), xdmf.get(), sheets));
    const int workers = output_workers(options);
    {
      OutputQueue output(workers, frames_in_flight(workers, frame_bytes(specs)), frame_output.work());
      make_frames(sim, specs, output, progress, tally);
    }
    tally.pngs = frame_output.pngs();
    progress.clear();
    if (writer) writer->finish(tally.written == frames);
    if (xdmf) xdmf->write(files.partial("frames.xmf").string());
    if (tally.quality) {
      tally.quality->finish();
      write_haptic_quality(files.partial("frames.h5").string(), *tally.quality);
    }
    // An interrupted run's sheet shows the frames it reached; the cells after stay dark.
    if (sheets.panel) sheets.panel->write(files.partial("contact_sheet.png").string());
    if (sheets.view) sheets.view->write(files.partial("view_contact_sheet.png").string());
  } catch (const std::exception& e) {
    progress.clear();
    throw write_failure(e, tally.written, files);
  }
  return tally;
}

// What this run writes, by name in its folder (docs/output-format.md).
std::vector<std::string> run_file_names(const RunOptions& options, const Scenario& scenario, const ContactSheets& sheets) {
  std::vector<std::string> names;
  if (options.hdf5) names.insert(names.end(), {"frames.h5", "frames.xmf"});
  if (scenario.output.png_every > 0) names.push_back("png");
  if (sheets.panel) names.push_back("contact_sheet.png");
  if (sheets.view) names.push_back("view_contact_sheet.png");
  return names;
}

// The longest paths a run writes, as OutputFiles::longest_path takes them: a file under its
// temporary name (NAME.partial for frames.h5, NAME.tmp for frames.xmf and a PNG), a frame's PNG in png/
// (png_name in cli/frame_output.cpp).
const std::string& longest_run_path() {
  static const std::string longest = OutputFiles::longest_path(
      {"frames.h5.partial", "frames.xmf.tmp", "png/view_000000.png.tmp", "contact_sheet.png.tmp", "view_contact_sheet.png.tmp"});
  return longest;
}

// What the run wrote, where it is now that it is published.
std::string files_written(const RunOptions& options, const OutputFiles& files, const RunTally& tally,
                          const ContactSheets& sheets) {
  std::string wrote = options.hdf5 ? files.published("frames.h5").string() + " and " + files.published("frames.xmf").string()
                                   : std::string("no HDF5");
  if (tally.pngs > 0) wrote += " and " + std::to_string(tally.pngs) + " PNGs in " + files.published("png").string();
  if (sheets.panel) wrote += " and " + files.published("contact_sheet.png").string();
  if (sheets.view) wrote += " and " + files.published("view_contact_sheet.png").string();
  return wrote;
}

// How long the run took, its frames' and haptic ticks' compute against their budgets, and what it
// wrote.
void print_summary(const Simulation& sim, const RunTally& tally, double wall_s, const std::string& wrote) {
  const Scene& s = sim.scene();
  const long done = sim.frames_done();
  std::printf("bleedsim: %ld frames in %.2f s (%.2f ms/frame, simulation %.2f ms/frame) on %s (%s); wrote %s\n",
              done, wall_s, 1000.0 * wall_s / double(done), 1000.0 * tally.simulate_s / double(done),
              to_string(sim.backend().kind()), sim.backend().device_name().c_str(), wrote.c_str());
  std::printf("bleedsim: frame compute %s\n",
              describe_against_budget(percentiles_of(tally.frame_seconds), "frames", 1.0 / s.frame_rate_hz).c_str());
  if (s.trace)
    std::printf("bleedsim: haptic tick compute %s; %zu cuts made\n",
                describe_against_budget(percentiles_of(tally.tick_seconds), "ticks", kHapticBudget_s).c_str(),
                sim.cuts().size() - s.cuts.size());
}

}  // namespace

std::unique_ptr<Simulation> make_simulation(Scenario& scenario, const BackendChoice& backend) {
  try {
    return std::make_unique<Simulation>(std::move(scenario.scene), backend);
  } catch (const InputError& e) {
    throw scenario.placed(e);  // the memory check names the key that sets the size: point at its line
  }
}

int run_command(const RunOptions& options) {
  Scenario scenario = scenario_for_run(options);
  const std::string dir_key = output_dir_key(options, scenario);
  const SourcePlace dir_place = options.out_dir ? SourcePlace{} : scenario.place_of(dir_key);
  const std::unique_ptr<Simulation> made = make_simulation(scenario, options.backend);
  Simulation& sim = *made;

  // Everything about the input is checked; only now is anything made on disk: the folder, held by
  // this run alone, and in it the partial folder this run writes into (docs/reliability.md).
  OutputFolder folder(scenario.output.dir, longest_run_path(), dir_place, dir_key);
  ContactSheets sheets = contact_sheets(sim.scene(), scenario);
  OutputFiles files(folder, run_file_names(options, scenario, sheets));
  folder.keep();
  if (!options.quiet) announce(sim);
  std::fflush(stdout);

  const long frames = sim.scene().frame_count();
  InterruptGuard guard;
  Progress progress(frames, !options.quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  const RunTally tally = write_run(options, scenario, sim, files, sheets, progress);
  // The run is whole (finished, or interrupted in order): it replaces the folder's last one.
  files.publish();
  const double wall_s = seconds_since(start);
  const std::string wrote = files_written(options, files, tally, sheets);
  if (interrupted) {
    std::fprintf(stderr, "bleedsim: interrupted after %ld of %ld frames; kept %s\n", long(sim.frames_done()), frames,
                 wrote.c_str());
    return kExitInterrupted;
  }
  if (!options.quiet) print_summary(sim, tally, wall_s, wrote);
  return 0;
}

}  // namespace bleedsim::cli
