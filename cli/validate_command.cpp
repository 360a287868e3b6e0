// bleedsim validate: check a scenario and say what a run of it would do.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/effects/cuts.h"
#include "core/effects/effect_list.h"
#include "core/effects/pipeline.h"
#include "core/effects/resolved.h"
#include "core/effects/surface/surface_stage.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/haptics/haptics.h"
#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "core/io/trace_csv.h"
#include "core/runtime/memory.h"
#include "core/runtime/message_text.h"

namespace bleedsim::cli {
namespace {

// The whole trace file, checked a line at a time as the run's reading is (the run reads only what it
// plays): its samples, counted and not kept, and their span.
void describe_trace(const Scenario& file) {
  const InputFile& trace_file =
      *std::find_if(file.files.begin(), file.files.end(), [](const InputFile& f) { return f.key == "haptics.trace"; });
  TraceOptions whole = file.trace_options;
  whole.keep_s = std::numeric_limits<double>::infinity();
  std::uint64_t samples = 0;
  double first_s = 0, last_s = 0;
  const Trace trace = read_trace(trace_file, whole, [&](const TraceSample& s) {
    if (samples++ == 0) first_s = s.t_s;
    last_s = s.t_s;
    return true;
  });
  std::printf("  trace      %s: %llu samples over %.3f s%s; the run reads the first %zu\n", trace.path.c_str(),
              static_cast<unsigned long long>(samples), last_s - first_s,
              trace.repairs_made == 0 ? ""
                                      : (", " + std::to_string(trace.repairs_made) + " dropouts repaired").c_str(),
              file.scene.trace->samples.size());
}

// The stylus: its contact parameters, and what replaying the trace over the run would do (the
// haptic loop alone is cheap: no frame is computed).
std::int64_t describe_haptics(const Scenario& file) {
  const Scene& scene = file.scene;
  const HapticParams& h = *scene.haptics;
  const std::string tissue = scene.mesh ? "the tissue mesh (a proxy on its surface, force bounded by energy)"
                                         : "surface z = " + format_number(h.surface_z_mm) + " mm";
  std::printf("  haptics    %s; k %g N/m, b %g N·s/m, cap %g N; passive: k·T/2 + |b| = %g < %g N·s/m\n", tissue.c_str(),
              h.stiffness_N_per_m, h.damping_Ns_per_m, h.max_force_N, passivity_demand_Ns_per_m(h),
              h.device_damping_Ns_per_m);
  describe_trace(file);
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
  std::printf("  stylus     %lld ticks: in contact %lld, cutting %lld; %lld cuts; peak force %.3g N\n",
              static_cast<long long>(ticks), static_cast<long long>(contact), static_cast<long long>(cutting),
              static_cast<long long>(cuts), peak_N);
  return cuts;
}

// The cuts the run will make: the scene's as they bleed there, and the stylus' (each counted at its
// full flow, a wound of cut_spacing_mm).
RunOutline outline(const Scene& scene, std::int64_t stylus_cuts) {
  RunOutline run;
  for (const Cut& cut : scene.cuts) run.cuts.push_back(cut_as_made(scene, cut));
  for (std::int64_t i = 0; i < stylus_cuts; ++i) {
    run.cuts.push_back(cut_at(scene, 0, 0, 0));
    run.cuts.back().wound_mm = scene.haptics->cut_spacing_mm;
  }
  return run;
}

// The backend's memory, and the host memory its files take as they are read, each file's part named
// (the numbers the run checks before it reads them).
std::string memory_line(const Scene& scene, const Resolved& resolved, const MemoryParts& inputs) {
  std::string line = human_bytes(double(Pipeline::backend_bytes(scene, resolved))) + " on the backend";
  if (inputs.empty()) return line;
  std::string parts;
  for (const MemoryPart& part : merged(inputs))
    parts += (parts.empty() ? "" : ", ") + human_bytes(part.bytes.as_double()) + " for " + part.what;
  return line + "; " + human_bytes(total_bytes(inputs).as_double()) + " of host memory at the most to read its files (" +
         parts + ")";
}

}  // namespace

int validate_command(const std::string& scenario, const std::vector<std::string>& overrides) {
  // The tissue is not drawn, but a vessel map is read: the cuts' bleeding depends on it.
  Scenario file = load_scenario(scenario, ReadTissue::header_only, overrides);
  if (file.scene.effects.has<VesselParams>()) file = load_scenario(scenario, ReadTissue::draw, overrides);
  const Scene& scene = file.scene;
  const Resolved resolved = resolve(scene);
  const OutputSpec& out = file.output;
  const Domain& d = scene.domain;
  std::string stages;
  for (const std::string& name : Pipeline::stage_names(scene)) stages += (stages.empty() ? "" : ", ") + name;
  std::printf("%s: valid\n", scenario.c_str());
  for (const std::string& set : overrides) std::printf("  --set      %s\n", set.c_str());
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
  const std::int64_t stylus_cuts = scene.trace ? describe_haptics(file) : 0;
  std::printf("%s", describe_effects(scene, resolved, outline(scene, stylus_cuts)).c_str());
  std::printf("  memory     %s\n", memory_line(scene, resolved, file.input_memory).c_str());
  std::printf("  output     %s (HDF5 %s, PNG %s)\n", out.dir.c_str(), out.hdf5 ? "on" : "off",
              out.png_every > 0 ? ("every " + std::to_string(out.png_every)).c_str() : "off");
  return 0;
}

}  // namespace bleedsim::cli
