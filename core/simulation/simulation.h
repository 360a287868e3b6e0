#pragma once
// The library's front door. A host simulator (or the bleedsim CLI) makes a Simulation from a
// Scene, feeds it the cuts its tool makes, steps it one frame at a time and reads each frame and
// field: as a host copy, or in place (device memory on the CUDA backend, for zero-copy use).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/effects/pipeline.h"
#include "core/effects/resolved.h"
#include "core/haptics/haptics.h"
#include "core/runtime/backend.h"
#include "core/scene/scene.h"
#include "core/scene/state.h"

namespace bleedsim {

// A field where the backend keeps it: host memory (cpu) or device memory (cuda).
struct FieldView {
  const Field* field;  // name, element type, channels, width, height, unit, bytes()
  const void* data;
  BackendKind location;
};

class Simulation {
 public:
  // Throws InputError when the scene does not fit in memory, std::invalid_argument when a scene
  // built in code is inconsistent, std::runtime_error when the asked-for backend is unavailable.
  explicit Simulation(Scene scene, const BackendChoice& choice = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const Scene& scene() const { return scene_; }
  // What its effects resolved to, once (core/effects/resolved.h).
  const Resolved& resolved() const { return resolved_; }
  const Backend& backend() const { return *backend_; }
  // Why this backend ("auto: CUDA device found", "auto: no CUDA device (...)").
  const std::string& backend_reason() const { return backend_reason_; }

  // A cut the host's tool made; the scene's effects answer it from cut.start_s on.
  // Throws std::invalid_argument for a cut cut_table() refuses (off the panel, a non-positive
  // radius or growth, a value that is not finite), naming the key.
  void add_cut(const Cut& cut);
  const std::vector<Cut>& cuts() const { return state_.cuts; }

  // A sample of the host's stylus, for a scene with [haptics] and no trace: where its tip is on the
  // panel, whether it touches the tissue and which grip buttons are held (the suction is on in
  // contact with one of [suction].buttons). The instrument ([suction], [contact]) follows the samples (in straight lines between them, staying at the last); give
  // them up to the end of each frame before stepping it. Throws std::invalid_argument for a scene
  // whose stylus is not the host's, a sample not later than the one before, or a value that is not
  // finite.
  void add_stylus_sample(const ToolSample& sample);

  // Computes the next frame. A scene with a trace first replays the haptic ticks up to the
  // frame's end (Scene::haptic_ticks_through_frame), whose cuts the frame then shows.
  void step();
  std::int64_t frames_done() const { return state_.frames_done; }
  // Simulated time of the last computed frame; 0 before the first.
  double time_s() const;

  // The fields this scene produces ("frame" always), in the order stages make them.
  std::vector<std::string> field_names() const;
  // Throws std::out_of_range for a name the scene does not produce.
  FieldView field(const std::string& name) const;
  // Waits until the device has finished what step() launched, so that code on another stream (a
  // renderer's, a DLPack consumer's) reads field(name).data whole. Nothing to wait for on the cpu.
  void synchronize() { backend_->synchronize(); }
  std::vector<std::uint8_t> copy_field(const std::string& name) const;
  void copy_field(const std::string& name, void* host_destination) const;
  // For copying fields out while the next frames compute (Download::add of field(name).data into
  // host_memory()'s buffers): the backend's, which must not outlive this Simulation.
  HostMemory& host_memory() { return backend_->host_memory(); }
  std::unique_ptr<Download> make_download() { return backend_->make_download(); }

  std::vector<StageReport> pipeline_report() const { return pipeline_->report(*backend_); }

  // The haptic ticks replayed for the last frame (none without a trace), and the compute time of
  // each, in seconds. A host that drives the stylus live runs its own HapticLoop instead.
  const std::vector<HapticTick>& haptic_ticks() const { return frame_ticks_; }
  const std::vector<double>& haptic_tick_seconds() const { return tick_seconds_; }

 private:
  Scene scene_;
  Resolved resolved_;
  std::unique_ptr<Backend> backend_;  // declared before state_ and pipeline_: outlives their memory
  std::string backend_reason_;
  State state_;
  std::unique_ptr<Pipeline> pipeline_;
  std::optional<HapticLoop> haptics_;  // the trace's replay
  std::vector<HapticTick> frame_ticks_;
  std::vector<double> tick_seconds_;

  void replay_haptic_ticks();
};

}  // namespace bleedsim
