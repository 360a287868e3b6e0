#include "core/effects/effect_list.h"

#include "core/effects/surface/surface_stage.h"

namespace bleedsim {

const std::vector<StageKind>& stage_kinds() {
  static const std::vector<StageKind> kinds = [] {
    std::vector<StageKind> all{surface_stage_kind()};
    for_each_effect([&](const auto& effect) { all.insert(all.end(), effect.stages.begin(), effect.stages.end()); });
    return all;
  }();
  return kinds;
}

Resolved resolve(const Scene& scene) {
  Resolved resolved;
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) {
    if (effect.resolve) effect.resolve(scene, resolved);
  });
  return resolved;
}

std::vector<std::unique_ptr<ParticleHook>> make_particle_hooks(const Scene& scene, const Resolved& resolved,
                                                               Backend& backend, int capacity) {
  std::vector<std::unique_ptr<ParticleHook>> hooks;
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) {
    for (const HookKind& hook : effect.hooks) hooks.push_back(hook.make(scene, resolved, backend, capacity));
  });
  return hooks;
}

MemoryParts particle_hooks_memory(const Scene& scene, const Resolved& resolved) {
  MemoryParts parts;
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) {
    for (const HookKind& hook : effect.hooks)
      for (MemoryPart& part : hook.memory_for(scene, resolved)) parts.push_back(std::move(part));
  });
  return parts;
}

ParamProblem effects_problem(const Scene& scene) {
  ParamProblem first;
  for_each_declared_effect(scene, [&](const auto& effect, const auto& params) {
    if (!first) first = check_params(effect.table(), params, scene);
  });
  return first;
}

Cut cut_as_made(const Scene& scene, Cut cut) {
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) {
    if (effect.as_made) cut = effect.as_made(scene, cut);
  });
  return cut;
}

std::vector<std::string> hook_tables() {
  std::vector<std::string> tables;
  for_each_effect([&](const auto& effect) {
    if (!effect.hooks.empty()) tables.push_back(effect.table().name);
  });
  return tables;
}

bool declares_a_hook(const Scene& scene) {
  bool any = false;
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) { any = any || !effect.hooks.empty(); });
  return any;
}

std::string describe_effects(const Scene& scene, const Resolved& resolved, const RunOutline& run) {
  std::string text;
  for_each_declared_effect(scene, [&](const auto& effect, const auto&) {
    if (effect.describe) text += effect.describe(scene, resolved, run);
  });
  return text;
}

std::vector<TableView> effect_tables() {
  std::vector<TableView> tables;
  for_each_effect([&](const auto& effect) { tables.push_back(describe(effect.table())); });
  return tables;
}

}  // namespace bleedsim
