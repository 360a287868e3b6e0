// The 1 kHz haptic loop on wall time, on a thread of its own, while a simulation computes frames on
// the same machine (docs/haptics.md, "The live loop under load"; docs/benchmarks.md, "The live loop").
//
// The loop ticks falcon-stroke's HapticLoop with that scene's recorded stroke played over and over
// (the call a host's loop makes: contact, force, cuts; the cuts go nowhere, so the load stays the
// same), 10,000 ticks at absolute deadlines (run_ticks), asking for SCHED_FIFO unless the case says
// normal_priority. The load is a thread stepping scenarios/default.toml's frames back to back, each
// copied to the host (a fresh Simulation when its frames run out):
//   HapticLoop/idle                                        no simulation
//   HapticLoop/under_load/cpu                              the CPU backend, a thread per hardware thread
//   HapticLoop/under_load/cpu/leave_one                    one thread fewer
//   HapticLoop/under_load/cpu/pinned                       every thread; the loop pinned to the last CPU
//   HapticLoop/under_load/cpu/normal_priority              every thread; the loop as where FIFO is refused
//   HapticLoop/under_load/cpu/normal_priority/leave_one    one thread fewer, at normal priority
//   HapticLoop/under_load/cuda                             the CUDA backend (skipped, saying why, without one)
// Counters: the tick period (start to start), the tick's compute and its lateness (deadline to
// start), p50/p99/max in µs; missed deadlines per 10,000 ticks (ticks that ended after the next
// tick's deadline); fifo (1 where granted); the simulation's threads, frames and mean frame time
// during the loop; the 1-minute load average when the case began, and the share of the machine's
// CPU time other processes took while the loop ran (others_cpu_%). The label says what priority
// the loop got (and why not SCHED_FIFO), where it ran and on what the simulation ran.
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_util.h"
#include "core/haptics/haptics.h"
#include "core/haptics/live_loop.h"
#include "core/haptics/loop_stats.h"
#include "core/haptics/realtime_priority.h"
#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "core/simulation/simulation.h"

namespace bleedsim {
namespace {

constexpr std::int64_t kLoopTicks = 10'000;

enum class Load { none, cpu, cuda };

struct LoopCase {
  Load load = Load::none;
  int leave_free = 0;  // hardware threads the CPU simulation leaves to the loop
  bool fifo = true;    // ask for SCHED_FIFO
  bool pin = false;    // pin the loop to the last CPU
};

// A thread computing a scene's frames back to back until destroyed. Once constructed, its first
// frame is done (or it has failed): the load is on before the loop starts.
class FrameLoad {
 public:
  FrameLoad(const Scene& scene, const BackendChoice& choice) : thread_([this, &scene, choice] { run(scene, choice); }) {
    while (frames_ == 0 && !failed_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~FrameLoad() {
    stop_ = true;
    thread_.join();
  }
  FrameLoad(const FrameLoad&) = delete;
  FrameLoad& operator=(const FrameLoad&) = delete;

  std::int64_t frames() const { return frames_; }
  bool failed() const { return failed_; }
  const std::string& failure() const { return failure_; }  // once failed()
  const std::string& device() const { return device_; }    // once constructed

 private:
  void run(const Scene& scene, const BackendChoice& choice) {
    try {
      while (!stop_) {
        Simulation sim(scene, choice);
        std::vector<std::uint8_t> rgba(sim.field("frame").field->bytes());
        if (device_.empty()) device_ = sim.backend().device_name();
        while (!stop_ && sim.frames_done() < scene.frame_count()) {
          sim.step();
          sim.copy_field("frame", rgba.data());  // the host has the frame: the GPU's work is done
          ++frames_;
        }
      }
    } catch (const std::exception& e) {
      failure_ = e.what();
      failed_ = true;
    }
  }

  std::atomic<bool> stop_{false}, failed_{false};
  std::atomic<std::int64_t> frames_{0};
  std::string device_, failure_;
  std::thread thread_;  // last: it starts once the members above exist
};

double load_average_1m() {
  std::ifstream in("/proc/loadavg");
  double one_minute = -1;
  in >> one_minute;
  return one_minute;
}

// CPU time the whole machine and this process have run so far, in seconds (/proc/stat's busy
// columns: user, nice, system, irq, softirq; getrusage's user and system time).
struct CpuSeconds {
  double machine = 0, process = 0;
};

CpuSeconds cpu_seconds_now() {
  std::ifstream in("/proc/stat");
  std::string cpu;
  long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0;
  in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq;
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) / 1e6; };
  return {double(user + nice + system + irq + softirq) / double(sysconf(_SC_CLK_TCK)),
          seconds(self.ru_utime) + seconds(self.ru_stime)};
}

// Pins the calling thread to one CPU; what became of it, for the label.
std::string pin_to_cpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  const int error = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
  const std::string which = "CPU " + std::to_string(cpu);
  return error == 0 ? "pinned to " + which : "not pinned to " + which + " (" + std::strerror(error) + ")";
}

// What the loop's thread got, and its ticks' times.
struct LoopRun {
  ThreadPriority priority;
  std::string pinned;  // where it was pinned, when the case asks
  std::vector<TickTimes> times;
};

// kLoopTicks ticks of `haptics` on a thread of its own, with the trace's stroke played over and over.
LoopRun run_loop(const LoopCase& c, int pin_cpu, HapticLoop& haptics, const Trace& trace) {
  const std::int64_t trace_ticks =
      std::llround((trace.samples.back().t_s - trace.samples.front().t_s) * kHapticRate_hz) + 1;
  LoopRun run;
  std::thread loop_thread([&] {
    if (c.pin) run.pinned = pin_to_cpu(pin_cpu);
    run.priority = c.fifo ? request_fifo_priority(kHapticFifoPriority)
                          : ThreadPriority{false, 0, "normal priority (SCHED_FIFO not asked for)"};
    run.times = run_ticks(monotonic_tick_clock(), kLoopTicks, [&](std::int64_t n) {
      benchmark::DoNotOptimize(haptics.tick(trace_sample_at_tick(trace, n % trace_ticks)));
    });
  });
  loop_thread.join();
  return run;
}

void set_loop_counters(benchmark::State& state, const LoopStats& stats) {
  const std::pair<const char*, const Percentiles*> spans[] = {{"period", &stats.period}, {"compute", &stats.compute}};
  for (const auto& [name, p] : spans) {
    state.counters[std::string(name) + "_p50_us"] = 1e6 * p->p50;
    state.counters[std::string(name) + "_p99_us"] = 1e6 * p->p99;
    state.counters[std::string(name) + "_max_us"] = 1e6 * p->max;
  }
  state.counters["late_p99_us"] = 1e6 * stats.late.p99;
  state.counters["late_max_us"] = 1e6 * stats.late.max;
  state.counters["missed_per_10k"] = stats.missed_per_10k();
}

void time_live_loop(benchmark::State& state, const LoopCase& c) {
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  const int sim_threads = hardware - c.leave_free;
  std::string why_not;
  if (c.load == Load::cpu && sim_threads < 1) {
    state.SkipWithError("one hardware thread: none to leave free");
    return;
  }
  if (c.load == Load::cuda && !cuda_device_available(&why_not)) {
    state.SkipWithError(("CUDA not measured: " + why_not).c_str());
    return;
  }
  const Scenario stroke = load_scenario(scenario_path("falcon-stroke"));
  const Scenario frames = load_scenario(scenario_path("default"));
  const double load_1m = load_average_1m();
  const BackendChoice choice{c.load == Load::cuda ? BackendChoice::Want::cuda : BackendChoice::Want::cpu, sim_threads};

  for (auto _ : state) {
    std::optional<FrameLoad> load;
    if (c.load != Load::none) load.emplace(frames.scene, choice);
    HapticLoop haptics(stroke.scene);
    const std::int64_t frames_before = load ? load->frames() : 0;
    const CpuSeconds cpu_before = cpu_seconds_now();
    const LoopRun run = load && load->failed() ? LoopRun{} : run_loop(c, hardware - 1, haptics, *stroke.scene.trace);
    const CpuSeconds cpu_after = cpu_seconds_now();
    const std::int64_t frames_during = load ? load->frames() - frames_before : 0;
    if (load && load->failed()) {
      state.SkipWithError(("the simulation failed: " + load->failure()).c_str());
      break;
    }
    const double elapsed_s = double(run.times.back().end_ns - run.times.front().deadline_ns) / 1e9;
    state.SetIterationTime(elapsed_s);
    set_loop_counters(state, loop_stats(run.times));
    state.counters["fifo"] = run.priority.fifo ? 1 : 0;
    state.counters["load_1m"] = load_1m;
    state.counters["others_cpu_%"] = 100.0 *
        ((cpu_after.machine - cpu_before.machine) - (cpu_after.process - cpu_before.process)) /
        (elapsed_s * hardware);
    std::string label = run.priority.text + (run.pinned.empty() ? "" : "; " + run.pinned);
    if (load) {
      if (c.load == Load::cpu) state.counters["sim_threads"] = sim_threads;
      state.counters["frames"] = double(frames_during);
      if (frames_during > 0) state.counters["frame_ms"] = 1e3 * elapsed_s / double(frames_during);
      label += "; default scene on " + load->device();
    } else {
      label += "; no simulation";
    }
    state.SetLabel(label);
  }
}

}  // namespace

void register_live_loop_benchmarks() {
  const std::pair<const char*, LoopCase> cases[] = {
      {"HapticLoop/idle", {Load::none, 0, true, false}},
      {"HapticLoop/under_load/cpu", {Load::cpu, 0, true, false}},
      {"HapticLoop/under_load/cpu/leave_one", {Load::cpu, 1, true, false}},
      {"HapticLoop/under_load/cpu/pinned", {Load::cpu, 0, true, true}},
      {"HapticLoop/under_load/cpu/normal_priority", {Load::cpu, 0, false, false}},
      {"HapticLoop/under_load/cpu/normal_priority/leave_one", {Load::cpu, 1, false, false}},
      {"HapticLoop/under_load/cuda", {Load::cuda, 0, true, false}},
  };
  for (const auto& [name, c] : cases)
    benchmark::RegisterBenchmark(name, [c = c](benchmark::State& state) { time_live_loop(state, c); })
        ->UseManualTime()
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
}

}  // namespace bleedsim
