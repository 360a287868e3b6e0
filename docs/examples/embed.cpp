// A host simulator embedding bleedsim: a scene built in code, cuts fed as the tool makes them,
// one step per rendered frame, and each frame read where the backend keeps it.
// Built as `embed_example` and run by ctest, so this file stays true.
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/effects/cuts.h"
#include "core/effects/spread/spread_params.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"

int main() {
  using namespace bleedsim;

  // Everything read-only about the run. A scenario file gives the same through load_scenario().
  Scene scene;
  scene.name = "embedded";
  scene.domain = Domain{320, 240, 32.0, 24.0};  // pixels, then millimetres
  scene.frame_rate_hz = 30.0;
  scene.duration_s = 2.0;
  scene.tissue = procedural_tissue(320, 240, 42);
  scene.tissue_source = "procedural";
  scene.effects.set(SpreadParams{5.0, 0.8});  // the scene calls for the radial spread

  Simulation sim(scene);  // auto: CUDA when a device is present, else the CPU reference
  std::printf("backend %s: %s (%s)\n", to_string(sim.backend().kind()),
              sim.backend().device_name().c_str(), sim.backend_reason().c_str());

  std::vector<std::uint8_t> rgba(sim.field("frame").field->bytes());
  for (int frame = 0; frame < sim.scene().frame_count(); ++frame) {
    // The host's tool cut the tissue at (16, 12) mm a third of a second in: bleed from now on.
    if (frame == 10) sim.add_cut(cut_at(sim.scene(), 16.0, 12.0, sim.time_s()));
    sim.step();
    // In place: a device pointer on CUDA (hand it to the renderer), a host pointer on the CPU.
    const FieldView in_place = sim.field("frame");
    (void)in_place.data;
    // Or a host copy into memory the host owns.
    sim.copy_field("frame", rgba.data());
  }

  // The stain under the cut after two seconds: green gone from the tissue there.
  const std::size_t centre = 4 * (std::size_t(120) * 320 + 160);
  std::printf("after %.2f s: tissue green %d, frame green %d at the cut\n", sim.time_s(),
              scene.tissue.rgba[centre + 1], rgba[centre + 1]);
  for (const StageReport& stage : sim.pipeline_report())
    std::printf("stage %-6s %8zu bytes, %llu launches\n", stage.name.c_str(), stage.bytes,
                static_cast<unsigned long long>(stage.launches));
  return rgba[centre + 1] < scene.tissue.rgba[centre + 1] ? 0 : 1;
}
