#include "core/effects/pipeline.h"

#include <algorithm>
#include <stdexcept>

namespace bleedsim {
namespace {

bool written_by_any(const std::vector<const StageKind*>& kinds, const std::string& field) {
  return std::any_of(kinds.begin(), kinds.end(), [&](const StageKind* kind) { return kind->written(field); });
}

// Why a scene that calls for `reader` but not for the stage that writes `field` cannot run, blamed
// on the table that calls for the reader.
ParamProblem missing_input(const StageKind& reader, const std::string& field) {
  const std::string reads = std::string("the ") + reader.name + " stage reads " + field;
  const StageKind* writer = stage_writing(field);
  if (!writer) throw std::logic_error(reads + ", which no stage writes");
  return {reader.table, reads + ", which the " + writer->name + " stage writes; a scene calls for that stage with a [" +
                            writer->table + "] table, and this one has none"};
}

std::vector<const StageKind*> wanted_by(const Scene& scene) {
  std::vector<const StageKind*> wanted;
  for (const StageKind& kind : stage_kinds())
    if (kind.wanted(scene)) wanted.push_back(&kind);
  return wanted;
}

// Whether the stage of `kind` added to State, from fields[first] on, exactly the fields its kind
// declares, in that order: what others read from the list (the fields' order, their names) holds.
bool added_as_declared(const StageKind& kind, const State& state, std::size_t first) {
  if (state.fields.size() - first != kind.writes.size()) return false;
  for (std::size_t k = 0; k < kind.writes.size(); ++k)
    if (state.fields[first + k].name != kind.writes[k].name) return false;
  return true;
}

}  // namespace

ParamProblem Pipeline::wiring_problem(const Scene& scene) {
  const std::vector<const StageKind*> wanted = wanted_by(scene);
  for (const StageKind* kind : wanted)
    for (const std::string& field : kind->reads(scene))
      if (!written_by_any(wanted, field)) return missing_input(*kind, field);
  return {};
}

std::vector<const StageKind*> Pipeline::plan(const Scene& scene) {
  if (const ParamProblem problem = wiring_problem(scene)) throw std::invalid_argument(problem.text());
  const std::vector<const StageKind*> wanted = wanted_by(scene);
  // Again and again, the first stage not yet placed whose inputs the placed ones all write.
  std::vector<const StageKind*> order;
  while (order.size() < wanted.size()) {
    const auto ready = std::find_if(wanted.begin(), wanted.end(), [&](const StageKind* kind) {
      const std::vector<std::string> reads = kind->reads(scene);
      return std::find(order.begin(), order.end(), kind) == order.end() &&
             std::all_of(reads.begin(), reads.end(),
                         [&](const std::string& field) { return written_by_any(order, field); });
    });
    if (ready == wanted.end())
      throw std::logic_error("the stages this scene calls for read each other's fields in a circle");
    order.push_back(*ready);
  }
  return order;
}

Pipeline::Pipeline(const Scene& scene, const Resolved& resolved, State& state, Backend& backend) {
  for (const StageKind* kind : plan(scene)) {
    const std::size_t first = state.fields.size();
    stages_.push_back(kind->make(*kind, scene, resolved, state, backend));
    if (!added_as_declared(*kind, state, first))
      throw std::logic_error(std::string("the ") + kind->name + " stage did not add the fields its kind declares");
  }
}

void Pipeline::run_frame(const Scene& scene, State& state, Backend& backend) {
  for (const auto& stage : stages_) stage->run(scene, state, backend);
}

std::vector<StageReport> Pipeline::report(const Backend& backend) const {
  std::vector<StageReport> rows;
  for (const auto& stage : stages_)
    rows.push_back({stage->name(), stage->bytes(), backend.launches(stage->name())});
  return rows;
}

std::vector<std::string> Pipeline::stage_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const StageKind* kind : plan(scene)) names.push_back(kind->name);
  return names;
}

MemoryParts Pipeline::memory(const Scene& scene, const Resolved& resolved) {
  MemoryParts parts;
  for (const StageKind* kind : plan(scene))
    for (MemoryPart& part : kind->memory_for(scene, resolved)) parts.push_back(std::move(part));
  return parts;
}

std::size_t Pipeline::backend_bytes(const Scene& scene, const Resolved& resolved) {
  return total_bytes(memory(scene, resolved)).to<std::size_t>();
}

}  // namespace bleedsim
