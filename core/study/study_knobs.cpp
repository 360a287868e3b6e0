// The accuracy knobs of the study (core/study/study_knobs.h, docs/accuracy.md). Each is applied once,
// in this table's order, to a copy of the scene: those that scale (particle size, resolution, the
// blur's downsampling) scale what the knobs before them set.
#include "core/study/study_knobs.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/effects/blur/blur_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/io/scenario.h"
#include "core/io/tissue_png.h"
#include "core/physics/blur.h"
#include "core/runtime/message_text.h"
#include "core/runtime/tissue.h"
#include "core/study/ensemble_stats.h"
#include "core/study/study_metrics.h"

namespace bleedsim {
namespace {

bool has_particles(const Scene& s) { return s.effects.has<ParticleParams>(); }
bool has_blur(const Scene& s) { return s.effects.has<BlurParams>(); }
bool always(const Scene&) { return true; }

// `base` times each factor, rounded to a whole number of at least 1, without repeats, ascending.
std::vector<double> whole_multiples(double base, std::initializer_list<double> factors) {
  std::vector<double> values;
  for (const double f : factors) values.push_back(std::max(1.0, std::round(base * f)));
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

// The sub-steps the scene runs with: its own, or the fewest its contact allows.
double resolved_substeps(const Scene& s) { return double(resolve_particles(s).mechanics.substeps); }

void set_compression(Scene& s, double e) {
  pin_particle_model(s);
  s.effects.get<ParticleParams>().compression = e;
}

void set_substeps(Scene& s, double n) {
  pin_particle_model(s);
  s.effects.get<ParticleParams>().substeps = int(n);
}

// Particles f times the diameter carry f² the blood each, f⁻² as many for the same flow of blood:
// the film, the pile's area and the blood's volume stay; only how finely it is sampled changes. The
// compression stays, so the stiffness per unit mass follows as 1/d² (what the same compression
// means at another size), and the time step stays: a size whose contact it cannot hold is refused.
// A splat radius the scene gives stays what it says in mm, so that every size draws its blood with
// the same footprint (issue 36's ladder); one it leaves at 0 follows the diameter.
void set_particle_size(Scene& s, double f) {
  pin_particle_model(s);
  ParticleParams& p = s.effects.get<ParticleParams>();
  p.diameter_mm *= f;
  if (p.cell_mm > 0) p.cell_mm *= f;
  p.particle_volume_mm3 *= f * f;
  p.capacity = int(std::min(double(1 << 28), std::ceil(p.capacity / (f * f))));
}

// The blur's taps and width in downsampled pixels, scaled so its width on the panel stays.
void scale_blur_pixels(Scene& s, double factor) {
  BlurParams* blur = s.effects.find<BlurParams>();
  if (!blur) return;
  blur->radius_px = int(std::round(blur->radius_px * factor));
  blur->sigma_px *= factor;
}

// The panel's pixels; the tissue and the vessel map are the scene's, drawn or read again at the new
// size (the procedural ones from the scene's own seed, which a study's ensemble leaves alone).
void set_resolution(Scene& s, double f) {
  const int old_w = s.domain.width_px, old_h = s.domain.height_px;
  s.domain.width_px = resolution_pixels(old_w, f);
  s.domain.height_px = resolution_pixels(old_h, f);
  const int w = s.domain.width_px, h = s.domain.height_px;
  scale_blur_pixels(s, f);
  s.tissue = s.tissue_source == "procedural" ? procedural_tissue(w, h, s.seed)
                                             : load_tissue_png({s.tissue_source, "texture", "tissue.texture"}, w, h);
  if (!s.effects.has<VesselParams>()) return;
  if (s.effects.get<VesselParams>().map == "procedural") {
    s.vessel_density = procedural_vessel_density(w, h, s.seed);
  } else {
    const std::vector<double> resampled =
        area_resample(std::vector<double>(s.vessel_density.begin(), s.vessel_density.end()), old_w, old_h, w, h);
    s.vessel_density.assign(resampled.begin(), resampled.end());
  }
}

void set_blur_downsample(Scene& s, double d) {
  scale_blur_pixels(s, double(s.effects.get<BlurParams>().downsample) / d);
  s.effects.get<BlurParams>().downsample = int(d);
}

}  // namespace

int resolution_pixels(int pixels, double factor) { return std::max(1, int(std::round(pixels * factor))); }

int fewest_stable_substeps(const Scene& scene) {
  ParticleParams p = scene.effects.get<ParticleParams>();
  p.substeps = 0;
  return resolve_particles(p, scene).mechanics.substeps;
}

void pin_particle_model(Scene& s) {
  if (!s.effects.has<ParticleParams>()) return;
  const ParticleMechanics m = resolve_particles(s).mechanics;
  s.effects.get<ParticleParams>().substeps = m.substeps;
  s.effects.get<ParticleParams>().design_depth_mm = m.depth_mm;
}

const std::vector<Knob>& knobs() {
  static const std::vector<Knob> table = {
      {"compression",
       "the deepest pile's overlap as a fraction of the diameter, which sets the contact's stiffness: "
       "more lets blood compress",
       "the time step, the particles and the pile the contact is made for (a contact too stiff for the "
       "time step is refused)",
       false, false, kNaN, "particles.compression", has_particles,
       [](const Scene& s) { return s.effects.get<ParticleParams>().compression; },
       [](const Scene& s) {
         const double e = s.effects.get<ParticleParams>().compression;
         return std::vector<double>{4 * e, 2 * e, e};
       },
       set_compression},
      {"substeps",
       "physics steps per frame (the time step): more cost more and refine the time step",
       "the contact, the particles and everything else",
       true, true, kNaN, "particles.substeps", has_particles, resolved_substeps,
       [](const Scene& s) { return whole_multiples(resolved_substeps(s), {1, 2}); }, set_substeps},
      {"particle_size",
       "the particles' diameter, as a factor: larger particles are fewer and cheaper, and sample the "
       "flow and the film more coarsely",
       "the blood (its volume, flow and film), the compression, the surface tension and grip per unit "
       "length, a splat radius the scene gives, the time step (a size whose contact it cannot hold is "
       "refused)",
       false, false, kNaN, nullptr, has_particles, [](const Scene&) { return 1.0; },
       [](const Scene&) { return std::vector<double>{4.0, 2.0, 1.0}; }, set_particle_size},
      {"blur_radius",
       "the blur's taps either side: fewer cost less, and cut the Gaussian's tails off",
       "the Gaussian's width and the downsampling",
       true, true, kNaN, "blur.radius_px", has_blur,
       [](const Scene& s) { return double(s.effects.get<BlurParams>().radius_px); },
       [](const Scene& s) { return whole_multiples(s.effects.get<BlurParams>().radius_px, {0.25, 0.5, 1}); },
       [](Scene& s, double r) { s.effects.get<BlurParams>().radius_px = int(r); }},
      {"blur_downsample",
       "the blur's downsampling (1, 2 or 4): more is cheaper, and coarsens the film's edges (1: none, "
       "nothing to refine)",
       "the blur's width on the panel and where its taps cut the Gaussian (taps and width in "
       "downsampled pixels scale with it)",
       false, true, 1.0, "blur.downsample", has_blur,
       [](const Scene& s) { return double(s.effects.get<BlurParams>().downsample); },
       [](const Scene&) { return std::vector<double>(std::rbegin(kBlurFactors), std::rend(kBlurFactors)); },
       set_blur_downsample},
      {"resolution",
       "the panel's pixels, as a factor on width and height (the spread texture, the film, the frame): "
       "fewer are cheaper and blur every edge",
       "the panel in mm, the particles, the blur's width on the panel, the tissue and vessels (drawn "
       "again at the new size)",
       true, false, kNaN, nullptr, always, [](const Scene&) { return 1.0; },
       [](const Scene&) { return std::vector<double>{0.25, 0.5, 1.0}; }, set_resolution},
  };
  return table;
}

const Knob* find_knob(const std::string& name) {
  for (const Knob& knob : knobs())
    if (name == knob.name) return &knob;
  return nullptr;
}

std::string unknown_knob_message(const std::string& name) {
  std::string known;
  for (const Knob& k : knobs()) known += std::string(known.empty() ? "" : ", ") + k.name;
  const std::string why = name.find("iteration") != std::string::npos
                              ? ": the particle model has no solver iterations (each sub-step is one neighbour "
                                "pass, docs/particles.md); its time step is the substeps knob"
                              : "";
  return "no knob '" + name + "'" + why + " (known: " + known + ")";
}

double knob_step(const Knob& knob, double value) { return knob.finer_is_larger ? 1.0 / value : value; }

std::optional<double> refined_value(const Knob& knob, const std::vector<double>& levels) {
  const double finest = levels.back();
  const double ratio = levels.size() >= 2 ? finest / levels[levels.size() - 2] : (knob.finer_is_larger ? 2.0 : 0.5);
  double value = finest * ratio;
  if (knob.whole) {
    value = std::round(value);
    if (value == finest) value += knob.finer_is_larger ? 1 : -1;
  }
  if (!(value > 0) || !std::isfinite(value)) return std::nullopt;
  if (knob.param) {
    const ParamView& param = scenario_param(knob.param);
    if (range_problem(knob.param, param.type, param.range, value)) return std::nullopt;
  }
  return value;
}

}  // namespace bleedsim
