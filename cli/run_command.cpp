// bleedsim run: a scenario from start to end, frames to HDF5 and PNG as they are made.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/output_folder.h"
#include "cli/output_queue.h"
#include "cli/progress.h"
#include "cli/run_files.h"
#include "core/runtime/build_info.h"
#include "core/io/contact_sheet.h"
#include "core/io/hdf5_writer.h"
#include "core/mesh/view_render.h"
#include "core/io/scenario.h"
#include "core/runtime/simulation.h"
#include "core/runtime/timing_summary.h"

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

std::vector<std::pair<std::string, std::string>> provenance(const Simulation& sim, const Scenario& scenario) {
  return {{"bleedsim_version", version()},
          {"git_sha", git_sha()},
          {"backend", to_string(sim.backend().kind())},
          {"device", sim.backend().device_name()},
          {"build_flags", build_flags()},
          {"scene_name", sim.scene().name},
          {"scenario_path", scenario.path},
          {"scenario_text", scenario.text}};
}

// What the replay will play: the trace, its repairs, and how its span meets the run's.
void describe_replay(const Scene& s) {
  const Trace& trace = *s.trace;
  const double span_s = trace.samples.back().t_s - trace.samples.front().t_s;
  std::printf("bleedsim: replaying %s: %zu samples over %.3f s through the 1 kHz haptic loop", trace.path.c_str(),
              trace.samples.size(), span_s);
  if (span_s < s.duration_s) std::printf(" (after it ends the stylus stays where the trace left it)");
  if (span_s > s.duration_s) std::printf(" (the run ends %.3f s before the trace)", span_s - s.duration_s);
  std::printf("\n");
  for (const std::string& repair : trace.repairs) std::printf("bleedsim: repaired %s\n", repair.c_str());
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
std::runtime_error write_failure(const std::exception& e, long frames_done, const RunFiles& files) {
  const std::string kept = frames_done == 0 ? "no frame was finished"
                                            : std::to_string(frames_done) + " finished frame" +
                                                  (frames_done == 1 ? "" : "s") + " kept in " +
                                                  files.partial("").string();
  return std::runtime_error(std::string(e.what()) + "; " + kept + ", the folder's last whole run left as it was");
}

}  // namespace

std::unique_ptr<Simulation> make_simulation(const Scenario& scenario, const BackendChoice& backend) {
  try {
    return std::make_unique<Simulation>(scenario.scene, backend);
  } catch (const InputError& e) {
    throw scenario.placed(e);  // the memory check names the key that sets the size: point at its line
  }
}

int run_command(const RunOptions& options) {
  Scenario scenario = load_scenario(options.scenario);
  OutputSpec& out = scenario.output;
  if (options.png_every) out.png_every = *options.png_every;
  if (options.contact_sheet) out.contact_sheet = *options.contact_sheet;
  if (options.out_dir) out.dir = *options.out_dir;
  const std::string dir_key = output_dir_key(options, scenario);
  const SourcePlace dir_place = options.out_dir ? SourcePlace{} : scenario.place_of(dir_key);

  const std::unique_ptr<Simulation> made = make_simulation(scenario, options.backend);
  Simulation& sim = *made;
  const Scene& s = sim.scene();
  const long frames = s.frame_count();
  const int png_every = out.png_every;

  // Everything about the input is checked; only now is anything made on disk: the folder, held by
  // this run alone, and in it the partial folder this run writes into (docs/reliability.md).
  OutputFolder folder(out.dir, dir_place, dir_key);
  RunFiles files(folder.path());
  folder.keep();
  const std::vector<FieldLayout> specs = fields_to_write(sim, out.fields);
  std::unique_ptr<ContactSheet> sheet, view_sheet;
  if (out.contact_sheet > 0)
    sheet = std::make_unique<ContactSheet>(frames, out.contact_sheet, s.domain.width_px, s.domain.height_px);
  const std::optional<ViewCamera>& view = scenario.view;
  if (out.contact_sheet > 0 && view)
    view_sheet = std::make_unique<ContactSheet>(frames, out.contact_sheet, view->width_px, view->height_px);
  // The mesh drawn with frame k's texture, from the scenario's endoscope.
  const auto view_of = [&](const std::uint8_t* frame) {
    const std::size_t bytes = std::size_t(s.domain.width_px) * std::size_t(s.domain.height_px) * 4;
    return render_view(s.mesh->mesh(),
                       Image{s.domain.width_px, s.domain.height_px, std::vector<std::uint8_t>(frame, frame + bytes)}, *view);
  };

  if (!options.quiet)
    std::printf("bleedsim: %s: %ld frames of %d x %d px on %s (%s; %s)\n", s.name.c_str(), frames,
                s.domain.width_px, s.domain.height_px, to_string(sim.backend().kind()),
                sim.backend().device_name().c_str(), sim.backend_reason().c_str());
  if (!options.quiet && s.trace) describe_replay(s);
  std::fflush(stdout);

  InterruptGuard guard;
  Progress progress(frames, !options.quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  double simulate_s = 0.0;
  std::vector<double> frame_seconds, tick_seconds;
  // Frames written so far: a write that fails (a full disk, a file size limit, an I/O error) ends the run
  // with the frames before it kept, and leaves the folder's last whole run as it was.
  long written = 0;
  long pngs = 0;  // PNG files written, counted on the output's writer thread
  try {
    std::unique_ptr<Hdf5FrameWriter> writer;
    if (options.hdf5)
      writer = std::make_unique<Hdf5FrameWriter>(files.partial("frames.h5").string(), specs,
                                                 provenance(sim, scenario), out.deflate_level, s.trace.has_value());
    if (png_every > 0) fs::create_directory(files.partial("png"));
    // Each frame's outputs, encoded on the output's workers and written on its writer thread, frame
    // after frame: the simulation goes on meanwhile.
    FrameOutputs outputs;
    outputs.hdf5 = writer.get();
    outputs.png_folder = files.partial("png");
    outputs.png_every = png_every;
    outputs.frames = frames;
    outputs.width = s.domain.width_px;
    outputs.height = s.domain.height_px;
    if (view) outputs.view = view_of;
    outputs.sheet = sheet.get();
    outputs.view_sheet = view_sheet.get();
    FrameOutput frame_output(std::move(outputs));
    const int workers = options.output_threads > 0 ? options.output_threads
                                                   : int(std::max(1u, std::thread::hardware_concurrency()));
    std::size_t frame_bytes = 0;
    for (const FieldLayout& spec : specs) frame_bytes += spec.bytes();
    {
      OutputQueue output(workers, frames_in_flight(workers, frame_bytes), frame_output.work());
      // A frame's fields go to the host while the next frame computes (on CUDA; the CPU copies at
      // once): two downloads in turn, into the backend's host memory; a frame is queued for its files
      // once its copies are whole, after the next frame has been computed.
      const std::unique_ptr<Download> downloads[2] = {sim.make_download(), sim.make_download()};
      const HostBytes empty_field{HostAllocator<std::uint8_t>(&sim.host_memory())};
      FrameJob in_transit;
      Download* carrying = nullptr;  // in_transit's download, while it has one
      const auto hand_over = [&] {
        if (!carrying) return;
        carrying->finish();
        carrying = nullptr;
        output.push(std::move(in_transit));
      };
      try {
        for (long k = 0; k < frames && !interrupted; ++k) {
          const Clock::time_point step_start = Clock::now();
          sim.step();
          FrameJob job = output.spare();
          job.fields.resize(specs.size(), empty_field);
          Download& download = *downloads[k % 2];
          for (std::size_t f = 0; f < specs.size(); ++f) {
            const FieldView field = sim.field(specs[f].name);
            job.fields[f].resize(field.field->bytes());
            download.add(job.fields[f].data(), field.data, field.field->bytes());
          }
          job.frame = k;
          job.time_s = sim.time_s();
          job.ticks = sim.haptic_ticks();
          hand_over();  // the frame before, whose copies ran while this one computed
          in_transit = std::move(job);
          carrying = &download;
          frame_seconds.push_back(seconds_since(step_start));
          simulate_s += frame_seconds.back();
          tick_seconds.insert(tick_seconds.end(), sim.haptic_tick_seconds().begin(), sim.haptic_tick_seconds().end());
          progress.update(k + 1);
        }
        // Every frame made is written, an interrupted run's too.
        hand_over();
        output.drain();
      } catch (...) {
        // What was made before the failure is written (or fails too) before the count is taken.
        try {
          hand_over();
        } catch (...) {
        }
        try {
          output.drain();
        } catch (...) {
        }
        written = output.written();
        throw;
      }
      written = output.written();
    }
    pngs = frame_output.pngs();
    progress.clear();
    if (writer) writer->finish(written == frames);
    // An interrupted run's sheet shows the frames it reached; the cells after stay dark.
    if (sheet) sheet->write(files.partial("contact_sheet.png").string());
    if (view_sheet) view_sheet->write(files.partial("view_contact_sheet.png").string());
  } catch (const std::exception& e) {
    progress.clear();
    throw write_failure(e, written, files);
  }
  // The run is whole (finished, or interrupted in order): it replaces the folder's last one.
  files.publish();
  const long done = sim.frames_done();
  const double wall_s = seconds_since(start);

  std::string wrote = options.hdf5 ? files.published("frames.h5").string() : std::string("no HDF5");
  if (pngs > 0) wrote += " and " + std::to_string(pngs) + " PNGs in " + files.published("png").string();
  if (sheet) wrote += " and " + files.published("contact_sheet.png").string();
  if (view_sheet) wrote += " and " + files.published("view_contact_sheet.png").string();
  if (interrupted) {
    std::fprintf(stderr, "bleedsim: interrupted after %ld of %ld frames; kept %s\n", done, frames,
                 wrote.c_str());
    return kExitInterrupted;
  }
  if (options.quiet) return 0;
  std::printf("bleedsim: %ld frames in %.2f s (%.2f ms/frame, simulation %.2f ms/frame) on %s (%s); wrote %s\n",
              done, wall_s, 1000.0 * wall_s / double(done), 1000.0 * simulate_s / double(done),
              to_string(sim.backend().kind()), sim.backend().device_name().c_str(), wrote.c_str());
  std::printf("bleedsim: frame compute %s\n",
              describe_against_budget(percentiles_of(frame_seconds), "frames", 1.0 / s.frame_rate_hz).c_str());
  if (s.trace)
    std::printf("bleedsim: haptic tick compute %s; %zu cuts made\n",
                describe_against_budget(percentiles_of(tick_seconds), "ticks", kHapticBudget_s).c_str(),
                sim.cuts().size() - s.cuts.size());
  return 0;
}

}  // namespace bleedsim::cli
