#include "core/effects/contact/contact_hook.h"

#include <memory>

#include "core/effects/contact/contact_params.h"
#include "core/effects/effect.h"
#include "core/effects/tips.h"
#include "core/physics/particle_kernels.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

void resolve_contact(const Scene& scene, Resolved& resolved) {
  resolved.set(ContactSettings{tip_body_mm(scene.effects.get<ContactParams>(), scene.effects.get<ParticleParams>())});
}

std::string describe_contact(const Scene& scene, const Resolved& resolved, const RunOutline&) {
  return "  contact    " + instrument_words(scene) + ": particle centres kept " +
         format_significant(resolved.get<ContactSettings>().body_mm, 6) +
         " mm from the tip (its radius and a particle's)\n";
}

}  // namespace

ContactHook::ContactHook(const Scene& scene, const Resolved& resolved, Backend&, int)
    : path_(scripted_tool(scene.tips)) {
  args_.tip.body_mm = float(resolved.get<ContactSettings>().body_mm);
}

MemoryParts ContactHook::memory_for(const Scene&, const Resolved&) { return {}; }

void ContactHook::act(const Scene& scene, State& state, Backend& backend, const ParticleArgs& particles, double t0,
                      double t1) {
  const std::optional<ToolSample> at = instrument_at(scene, path_, state, t1);
  if (at && at->contact) act_at(backend, particles, *at, instrument_at(scene, path_, state, t0), t1 - t0);
}

void ContactHook::act_at(Backend& backend, const ParticleArgs& particles, const ToolSample& at,
                         const std::optional<ToolSample>& before, double dt_s) {
  if (particles.live_count == 0) return;
  args_.model = particles.model;
  args_.arrays = particles.arrays;
  args_.first_live_slot = particles.first_live_slot;
  args_.live_count = particles.live_count;
  args_.tip.x_mm = float(at.x_mm);
  args_.tip.y_mm = float(at.y_mm);
  args_.tip.vx_mm_s = before ? float((at.x_mm - before->x_mm) / dt_s) : 0.0f;
  args_.tip.vy_mm_s = before ? float((at.y_mm - before->y_mm) / dt_s) : 0.0f;
  backend.run("contact", KeepOutOfTip{args_});
}

const Effect<ContactParams>& contact_effect() {
  static const Effect<ContactParams> row = [] {
    Effect<ContactParams> e{contact_table};
    e.hooks = {{"contact", ContactHook::memory_for, make_hook<ContactHook>}};
    e.resolve = resolve_contact;
    e.describe = describe_contact;
    return e;
  }();
  return row;
}

}  // namespace bleedsim
