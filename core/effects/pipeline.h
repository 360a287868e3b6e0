#pragma once
// The pipeline is built from the scene: only the stages it calls for, in frame order.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/effects/stage.h"

namespace bleedsim {

// What one stage costs: proof that a stage a scene does not declare costs nothing.
struct StageReport {
  std::string name;
  std::size_t bytes = 0;       // backend memory it holds
  std::uint64_t launches = 0;  // times the backend ran its work
};

class Pipeline {
 public:
  Pipeline(const Scene& scene, State& state, Backend& backend);
  void run_frame(const Scene& scene, State& state, Backend& backend);
  std::vector<StageReport> report(const Backend& backend) const;

  // The stages a scene calls for, by name, without building them.
  static std::vector<std::string> stage_names(const Scene& scene);
  // Backend memory those stages will allocate.
  static std::size_t backend_bytes(const Scene& scene);

 private:
  std::vector<std::unique_ptr<Stage>> stages_;
};

}  // namespace bleedsim
