// bleedsim validate: check a scenario and say what a run of it would do.
#include <algorithm>
#include <cmath>
#include <vector>
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/runtime/memory.h"
#include "core/haptics/haptics.h"
#include "core/effects/pipeline.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/surface/surface_stage.h"
#include "core/io/scenario.h"
#include "core/haptics/trace_replay.h"
#include "core/runtime/message_text.h"
#include "core/bleeding/vessel_density.h"

namespace bleedsim::cli {
namespace {

// The stylus: its contact parameters, and what replaying the trace over the run would do (the
// haptic loop alone is cheap: no frame is computed).
std::int64_t describe_haptics(const Scene& scene) {
  const HapticParams& h = *scene.haptics;
  const std::string tissue = scene.mesh ? "the tissue mesh (a proxy on its surface, force bounded by energy)"
                                         : "surface z = " + format_number(h.surface_z_mm) + " mm";
  std::printf("  haptics    %s; k %g N/m, b %g N·s/m, cap %g N; passive: k·T/2 + |b| = %g < %g N·s/m\n", tissue.c_str(),
              h.stiffness_N_per_m, h.damping_Ns_per_m, h.max_force_N, passivity_demand_Ns_per_m(h),
              h.device_damping_Ns_per_m);
  const Trace& trace = *scene.trace;
  HapticLoop loop(scene);
  const std::int64_t ticks = scene.haptic_ticks_through_frame(scene.frame_count() - 1);
  std::int64_t contact = 0, cutting = 0, cuts = 0;
  double peak_N = 0;
  for (std::int64_t n = 0; n < ticks; ++n) {
    const HapticStep step = loop.tick(trace_sample_at_tick(trace, n));
    contact += step.record.contact;
    cutting += step.record.cutting;
    cuts += step.cut.has_value();
    peak_N = std::max(peak_N, step.record.force_N.norm());
  }
  std::printf("  trace      %s: %zu samples over %.3f s%s\n", trace.path.c_str(), trace.samples.size(),
              trace.samples.back().t_s - trace.samples.front().t_s,
              trace.repairs.empty() ? "" : (", " + std::to_string(trace.repairs.size()) + " dropouts repaired").c_str());
  std::printf("  stylus     %lld ticks: in contact %lld, cutting %lld; %lld cuts; peak force %.3g N\n",
              static_cast<long long>(ticks), static_cast<long long>(contact), static_cast<long long>(cutting),
              static_cast<long long>(cuts), peak_N);
  return cuts;
}

// The particle model as the parameters make it (docs/particles.md): the contact, the time step, the
// largest drop the mucosa holds, and whether the ring can hold all the blood the cuts give.
void describe_particles(const Scene& scene, std::int64_t stylus_cuts) {
  const ParticleParams& p = *scene.particles;
  const ParticleMechanics m = particle_mechanics(p, scene.domain, scene.frame_rate_hz);
  std::printf("  particles  stiffness %.3g/s² (a %.3g mm pile at %.3g compression), %d sub-steps of %.3g ms "
              "(limit %.3g ms)\n",
              m.stiffness_per_s2, m.depth_mm, p.compression, m.substeps, m.dt_s * 1e3, m.step_limit_s * 1e3);
  const DropLimit drop = critical_drop(p, scene.domain, scene.frame_rate_hz);
  if (drop.holds_any)
    std::printf("  film       %.3g mm thick; the mucosa holds any drop against gravity\n", m.film_mm);
  else if (drop.volume_mm3 == 0)
    std::printf("  film       %.3g mm thick; the mucosa holds no drop against gravity (no pinning)\n", m.film_mm);
  else
    std::printf("  film       %.3g mm thick; the mucosa holds drops up to %.3g mm³ (radius %.3g mm) against gravity\n",
                m.film_mm, drop.volume_mm3, drop.radius_mm);
  // The ring overwrites live blood when more can be alive at once than it has slots: a cut has at
  // most what it bleeds in its first lifetime alive (its flow only falls).
  // A scripted cut bleeds by the vessels along its wound; a stylus' cut is counted at its full flow.
  std::vector<Cut> cuts;
  for (const Cut& cut : scene.cuts) cuts.push_back(with_vessels(scene, cut));
  for (std::int64_t i = 0; i < stylus_cuts; ++i) {
    cuts.push_back(scene.cut_at(0, 0, 0));
    cuts.back().wound_mm = scene.haptics->cut_spacing_mm;
  }
  double alive = 0;
  const PulseParams* pulse = scene.pulse ? &*scene.pulse : nullptr;
  for (const Cut& cut : cuts)
    alive += std::floor(cut_blood_mm3(cut, cut.start_s + p.lifetime_s, pulse) / p.particle_volume_mm3);
  if (alive > p.capacity)
    std::printf("warning: the cuts can have up to %.0f particles alive at once (what each bleeds within a %.3g s "
                "lifetime), more than the ring's %d slots: it will overwrite live blood; raise "
                "[particles].capacity or shorten lifetime_s\n",
                alive, p.lifetime_s, p.capacity);
}

// Where and how hard the wounds bleed, and the instrument (docs/bleeding.md).
void describe_bleeding(const Scene& scene) {
  if (scene.vessels) {
    std::printf("  vessels    each wound's flow times the map's mean along it; map %s", scene.vessels->map.c_str());
    if (!scene.cuts.empty()) std::printf("; the cuts' means");
    for (const Cut& cut : scene.cuts) {
      const Cut bleeding = with_vessels(scene, cut);
      std::printf(" %.3g%s", bleeding.vessel_density, bleeding.arterial ? " (arterial)" : "");
    }
    std::printf("\n");
  }
  if (scene.pulse) {
    const PulseParams& q = *scene.pulse;
    std::printf("  pulse      %g beats a minute, w(t) = 1 + %g sin(2πft) + %g sin(4πft); arterial: cuts marked so%s\n",
                q.heart_rate_per_min, q.systolic, q.dicrotic,
                scene.vessels ? (", and wounds of mean vessel density ≥ " + format_number(q.arterial_density)).c_str()
                              : "");
  }
  if (!scene.suction && !scene.contact) return;
  const std::string instrument =
      scene.tips.empty()
          ? "the stylus"
          : "a scripted tip, " + std::to_string(scene.tips.size()) + " points from " +
                format_number(scene.tips.front().t_s) + " s to " + format_number(scene.tips.back().t_s) + " s";
  if (scene.suction) {
    const SuctionParams& s = *scene.suction;
    std::printf("  suction    %s: reach %g mm, up to %g mm³/s (%.3g particles a sub-step)", instrument.c_str(),
                s.radius_mm, s.max_flow_mm3_per_s,
                s.max_flow_mm3_per_s / particle_steps_per_s(scene) / scene.particles->particle_volume_mm3);
    if (scene.tips.empty()) std::printf(", in contact with a button of 0x%x held", unsigned(s.buttons));
    std::printf("\n");
  }
  if (scene.contact)
    std::printf("  contact    %s: particle centres kept %g mm from the tip (its radius and a particle's)\n",
                instrument.c_str(), scene.contact->tip_radius_mm + scene.particles->diameter_mm / 2.0);
}

}  // namespace

int validate_command(const std::string& scenario) {
  // The tissue is not drawn, but a vessel map is read: the cuts' bleeding depends on it.
  Scenario file = load_scenario(scenario, ReadTissue::header_only);
  if (file.scene.vessels) file = load_scenario(scenario);
  const Scene& scene = file.scene;
  const OutputSpec& out = file.output;
  const Domain& d = scene.domain;
  std::string stages;
  for (const std::string& name : Pipeline::stage_names(scene)) stages += (stages.empty() ? "" : ", ") + name;
  std::printf("%s: valid\n", scenario.c_str());
  std::printf("  scene      %s\n", scene.name.c_str());
  std::printf("  domain     %d x %d px, %g x %g mm\n", d.width_px, d.height_px, d.width_mm, d.height_mm);
  std::printf("  time       %g s at %g Hz: %d frames\n", scene.duration_s, scene.frame_rate_hz,
              scene.frame_count());
  std::printf("  tissue     %s\n", scene.tissue_source.c_str());
  if (scene.mesh) {
    // How the texture stretches over it: surface mm per panel mm, least and greatest.
    const TissueMesh& mesh = scene.mesh->mesh();
    const PanelStretch stretch = panel_stretch(mesh, texture_panel(scene.domain));
    std::printf("  mesh       %s: %zu triangles, %.1f mm²; a panel mm is %.3g to %.3g mm of its surface\n",
                scene.mesh_source.c_str(), mesh.triangles.size(), mesh.area_mm2(), stretch.least, stretch.greatest);
  }
  std::printf("  cuts       %zu%s\n", scene.cuts.size(), scene.trace ? " scripted, and the stylus' (below)" : "");
  std::printf("  stages     %s\n", stages.c_str());
  const std::int64_t stylus_cuts = scene.trace ? describe_haptics(scene) : 0;
  if (scene.particles) describe_particles(scene, stylus_cuts);
  describe_bleeding(scene);
  std::printf("  memory     %s on the backend\n", human_bytes(double(Pipeline::backend_bytes(scene))).c_str());
  std::printf("  output     %s (HDF5 %s, PNG %s)\n", out.dir.c_str(), out.hdf5 ? "on" : "off",
              out.png_every > 0 ? ("every " + std::to_string(out.png_every)).c_str() : "off");
  return 0;
}

}  // namespace bleedsim::cli
