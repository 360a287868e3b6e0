// A host simulator with a live stylus: a 1 kHz haptic thread ticks a HapticLoop with each device
// sample and sends back its force; the cuts it makes cross to the render thread, which gives them
// to the Simulation and steps one frame each 33 ms. The haptic path touches no frame stage.
// Built as `live_stylus_example` and run by ctest (with a scripted stand-in for the Falcon), so
// this file stays true.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "core/effects/spread/spread_params.h"
#include "core/haptics/haptics.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"

namespace {

// Stands in for libnifalcon's runIOLoop() + getPosition() + button state: the tip presses 2 mm
// into the tissue (its surface at z = 120 mm) over 50 ms with button 0x1, draws 12 mm to the
// right and lifts.
bleedsim::DeviceSample read_falcon(double t_s) {
  const double x_mm = -6.0 + 12.0 * std::fmin(t_s / 1.2, 1.0);
  const double z_mm = t_s > 1.2 ? 125.0 : 125.0 - 7.0 * std::fmin(std::fmax((t_s - 0.2) / 0.05, 0.0), 1.0);
  return {Eigen::Vector3d(x_mm, 0.0, z_mm) / 1000.0, std::uint8_t(z_mm < 120.0 ? 0x1 : 0)};
}

void send_force(const Eigen::Vector3d&) {}  // libnifalcon's setForce() on a real device

}  // namespace

int main() {
  using namespace bleedsim;
  using Clock = std::chrono::steady_clock;

  Scene scene;
  scene.name = "live-stylus";
  scene.domain = Domain{320, 240, 32.0, 24.0};
  scene.duration_s = 1.5;
  scene.tissue = procedural_tissue(320, 240, 7);
  scene.tissue_source = "procedural";
  scene.effects.set(SpreadParams{2.0, 2.0});
  HapticParams stylus;  // the defaults: surface at z = 120 mm, k = 500 N/m, a cut every 1 mm
  stylus.origin_x_mm = 16.0;
  stylus.origin_y_mm = 12.0;
  scene.haptics = stylus;

  Simulation sim(scene);
  std::mutex mailbox_lock;
  std::vector<Cut> mailbox;  // cuts on their way from the haptic thread to the render thread
  std::atomic<bool> done{false};
  double peak_force_N = 0;

  // The haptic thread: its own loop, one tick a millisecond of wall time.
  std::thread haptics([&] {
    HapticLoop loop(scene);
    const Clock::time_point start = Clock::now();
    while (!done) {
      const double t_s = double(loop.ticks_done()) / kHapticRate_hz;
      const HapticStep step = loop.tick(read_falcon(t_s));
      send_force(step.record.force_N);
      peak_force_N = std::fmax(peak_force_N, step.record.force_N.z());
      if (step.cut) {
        const std::lock_guard<std::mutex> hold(mailbox_lock);
        mailbox.push_back(*step.cut);
      }
      std::this_thread::sleep_until(start + std::chrono::milliseconds(loop.ticks_done()));
    }
  });

  // The render thread: the cuts so far, then a frame, at 30 Hz of wall time.
  std::size_t cuts = 0;
  const Clock::time_point start = Clock::now();
  for (int frame = 0; frame < sim.scene().frame_count(); ++frame) {
    {
      const std::lock_guard<std::mutex> hold(mailbox_lock);
      for (const Cut& cut : mailbox) sim.add_cut(cut);
      cuts += mailbox.size();
      mailbox.clear();
    }
    sim.step();
    std::this_thread::sleep_until(start + std::chrono::microseconds(33'333 * (frame + 1)));
  }
  done = true;
  haptics.join();

  // The stroke's middle, (16, 12) mm: pixel (160, 120). Its stain took the green from the tissue.
  const std::vector<std::uint8_t> rgba = sim.copy_field("frame");
  const std::size_t middle = 4 * (std::size_t(120) * 320 + 160);
  std::printf("%zu cuts from the stylus; peak force %.2f N; green at the stroke's middle %d (tissue %d)\n",
              cuts, peak_force_N, rgba[middle + 1], scene.tissue.rgba[middle + 1]);
  return cuts >= 5 && peak_force_N > 0.5 && rgba[middle + 1] < scene.tissue.rgba[middle + 1] ? 0 : 1;
}
