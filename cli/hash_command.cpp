// bleedsim hash: the per-frame fingerprints of a run, for checking that two runs (two backends,
// two machines, two thread counts) gave the same bytes.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/simulation/frame_hash.h"

namespace bleedsim::cli {

int hash_command(const std::string& scenario, const BackendChoice& backend, const std::vector<std::string>& overrides) {
  Scenario file = load_scenario(scenario, ReadTissue::draw, overrides);
  const std::unique_ptr<Simulation> made = make_simulation(file, backend);
  Simulation& sim = *made;
  std::fprintf(stderr, "bleedsim: hashing on %s (%s)\n", to_string(sim.backend().kind()),
               sim.backend().device_name().c_str());
  std::uint64_t run_hash = fnv1a64(nullptr, 0);
  for (int k = 0; k < sim.scene().frame_count(); ++k) {
    sim.step();
    std::printf("%d", k);
    for (const auto& [name, hash] : hash_fields(sim)) {
      std::printf(" %s=%s", name.c_str(), hex64(hash).c_str());
      run_hash = fnv1a64(&hash, sizeof hash, run_hash);
    }
    std::printf("\n");
  }
  std::printf("run %s\n", hex64(run_hash).c_str());
  return 0;
}

}  // namespace bleedsim::cli
