// bleedsim validate: check a scenario and say what a run of it would do.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/memory.h"
#include "core/pipeline.h"
#include "core/scenario.h"

namespace bleedsim::cli {

int validate_command(const std::string& scenario) {
  const Scene scene = load_scenario(scenario);
  const Domain& d = scene.domain;
  std::string stages;
  for (const std::string& name : Pipeline::stage_names(scene)) stages += (stages.empty() ? "" : ", ") + name;
  std::printf("%s: valid\n", scenario.c_str());
  std::printf("  scene      %s\n", scene.name.c_str());
  std::printf("  domain     %d x %d px, %g x %g mm\n", d.width_px, d.height_px, d.width_mm, d.height_mm);
  std::printf("  time       %g s at %g Hz: %d frames\n", scene.duration_s, scene.frame_rate_hz,
              scene.frame_count());
  std::printf("  tissue     %s\n", scene.tissue_source.c_str());
  std::printf("  cuts       %zu\n", scene.cuts.size());
  std::printf("  stages     %s\n", stages.c_str());
  std::printf("  memory     %s on the backend\n", human_bytes(double(Pipeline::backend_bytes(scene))).c_str());
  std::printf("  output     %s (HDF5 %s, PNG %s)\n", scene.output.dir.c_str(),
              scene.output.hdf5 ? "on" : "off",
              scene.output.png_every > 0 ? ("every " + std::to_string(scene.output.png_every)).c_str() : "off");
  return 0;
}

}  // namespace bleedsim::cli
