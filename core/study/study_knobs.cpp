// The accuracy knobs of the study (core/study/study.h, docs/accuracy.md). Each knob is applied once, in
// this table's order, to a copy of the scene: those that scale (particle size, resolution, the blur's
// downsampling) scale what the knobs before them set.
#include <algorithm>
#include <cmath>

#include "core/study/study.h"
#include "core/effects/particle_model.h"
#include "core/io/scenario.h"
#include "core/io/tissue_png.h"
#include "core/runtime/tissue.h"

namespace bleedsim {
namespace {

bool has_particles(const Scene& s) { return s.particles.has_value(); }
bool has_blur(const Scene& s) { return s.blur.has_value(); }
bool always(const Scene&) { return true; }

// `base` times each factor, rounded to a whole number of at least 1, without repeats, ascending.
std::vector<double> whole_multiples(double base, std::initializer_list<double> factors) {
  std::vector<double> values;
  for (const double f : factors) values.push_back(std::max(1.0, std::round(base * f)));
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

// The scene's sub-steps: its own, or the fewest its contact allows (substeps = 0).
double resolved_substeps(const Scene& s) {
  return double(particle_mechanics(*s.particles, s.domain, s.frame_rate_hz).substeps);
}

// Particles f times the diameter carry f² the blood each, f⁻² as many for the same flow of blood:
// the film, the pile's area and the blood's volume stay; only how finely it is sampled changes
// (the contact's stiffness and the sub-steps follow, as the model derives them).
void set_particle_size(Scene& s, double f) {
  ParticleParams& p = *s.particles;
  p.diameter_mm *= f;
  if (p.cell_mm > 0) p.cell_mm *= f;
  if (p.splat_radius_mm > 0) p.splat_radius_mm *= f;
  p.particle_volume_mm3 *= f * f;
  p.capacity = int(std::min(double(1 << 28), std::ceil(p.capacity / (f * f))));
}

// The blur's taps and width in downsampled pixels, scaled so its width on the panel stays.
void scale_blur_pixels(Scene& s, double factor) {
  if (!s.blur) return;
  s.blur->radius_px = int(std::round(s.blur->radius_px * factor));
  s.blur->sigma_px *= factor;
}

void set_resolution(Scene& s, double f) {
  s.domain.width_px = std::max(1, int(std::round(s.domain.width_px * f)));
  s.domain.height_px = std::max(1, int(std::round(s.domain.height_px * f)));
  scale_blur_pixels(s, f);
  s.tissue = s.tissue_source == "procedural"
                 ? procedural_tissue(s.domain.width_px, s.domain.height_px, s.seed)
                 : load_tissue_png(s.tissue_source, s.domain.width_px, s.domain.height_px, {}, "tissue.texture");
}

void set_blur_downsample(Scene& s, double d) {
  scale_blur_pixels(s, double(s.blur->downsample) / d);
  s.blur->downsample = int(d);
}

}  // namespace

const std::vector<Knob>& knobs() {
  static const std::vector<Knob> table = {
      {"compression",
       "the deepest pile's overlap as a fraction of the diameter, which sets the contact's stiffness: "
       "more lets blood compress, and needs fewer sub-steps",
       false, "particles.compression", has_particles, [](const Scene& s) { return s.particles->compression; },
       [](const Scene& s) {
         const double e = s.particles->compression;
         return std::vector<double>{e / 2, e, 2 * e, 4 * e};
       },
       [](Scene& s, double e) { s.particles->compression = e; }},
      {"substeps",
       "physics steps per frame (the time step), from the fewest the contact allows up: more cost more "
       "and refine the time step alone",
       true, "particles.substeps", has_particles, resolved_substeps,
       [](const Scene& s) { return whole_multiples(resolved_substeps(s), {1, 2, 4}); },
       [](Scene& s, double v) { s.particles->substeps = int(v); }},
      {"particle_size",
       "the particles' diameter, as a factor (the blood's volume kept): larger particles are fewer "
       "and cheaper, but sample the flow and the film more coarsely",
       false, nullptr, has_particles, [](const Scene&) { return 1.0; },
       [](const Scene&) { return std::vector<double>{0.7, 1.0, 1.4, 2.0}; }, set_particle_size},
      {"blur_radius",
       "the blur's taps either side (its Gaussian's width kept): fewer cost less, and cut the "
       "Gaussian's tails off",
       true, "blur.radius_px", has_blur, [](const Scene& s) { return double(s.blur->radius_px); },
       [](const Scene& s) { return whole_multiples(s.blur->radius_px, {0.25, 0.5, 1, 2}); },
       [](Scene& s, double r) { s.blur->radius_px = int(r); }},
      {"blur_downsample",
       "the blur's downsampling (1, 2 or 4; its width on the panel kept): more is cheaper, and "
       "coarsens the film's edges",
       false, "blur.downsample", has_blur, [](const Scene& s) { return double(s.blur->downsample); },
       [](const Scene&) { return scenario_param("blur.downsample").range.only; }, set_blur_downsample},
      {"resolution",
       "the panel's pixels, as a factor on width and height (the spread texture, the film, the "
       "frame): fewer are cheaper and blur every edge",
       true, nullptr, always, [](const Scene&) { return 1.0; },
       [](const Scene&) { return std::vector<double>{0.25, 0.5, 1.0}; }, set_resolution},
  };
  return table;
}

const Knob* find_knob(const std::string& name) {
  for (const Knob& knob : knobs())
    if (name == knob.name) return &knob;
  return nullptr;
}

}  // namespace bleedsim
