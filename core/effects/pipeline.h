#pragma once
// The pipeline is built from the scene: only the stages it calls for (core/effects/stage_kinds.h),
// each after the stages that write what it reads.
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
  // Builds the stages from the scene and its settings, resolved once (resolve(scene)). Throws
  // std::invalid_argument, before anything is allocated, as plan() does.
  Pipeline(const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  void run_frame(const Scene& scene, State& state, Backend& backend);
  std::vector<StageReport> report(const Backend& backend) const;

  // The stage kinds a scene calls for, in the order they run: each after the stages that write
  // the fields it reads, ties in stage_kinds()'s order. Since State keeps fields in the order
  // stages add them, this is also the order of the fields (and of a frame's hash). Throws
  // std::invalid_argument when a stage reads a field that none of them writes.
  static std::vector<const StageKind*> plan(const Scene& scene);
  // Why this scene's stages cannot be wired (a stage reads a field no stage it calls for writes),
  // blamed on the table that calls for the reader ("blur"); none when they can.
  static ParamProblem wiring_problem(const Scene& scene);
  // Their names, without building them.
  static std::vector<std::string> stage_names(const Scene& scene);
  // Backend memory those stages will allocate, by the key that sets each part's size, and in all.
  static MemoryParts memory(const Scene& scene, const Resolved& resolved);
  static std::size_t backend_bytes(const Scene& scene, const Resolved& resolved);

 private:
  std::vector<std::unique_ptr<Stage>> stages_;
};

}  // namespace bleedsim
