#pragma once
// Particles placed by hand in a box and stepped on the CPU reference, one physics step at a time
// (on the scene's tissue mesh, when it has one):
// for the tests that need a known start (a lone particle, a drop, a deep pile, a mirrored pair of
// blobs) rather than what a cut emits. It runs the same phases, in the same order, as the particle
// stage does; there is no emission.
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/effects/particles/particle_buffers.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/surface/surface_stage.h"
#include "core/mesh/surface_bake.h"
#include "core/runtime/backend.h"
#include "core/scene/scene.h"

namespace bleedsim::test {

struct Point {
  double x, y;
};

// A scene of `width` × `height` mm with the default particles, `sub_steps` of them per frame at
// 30 Hz (0: the fewest the contact allows). The box's panel is the scene's.
inline Scene box_scene(double width_mm, double height_mm, const ParticleParams& params = {}) {
  Scene scene;
  scene.domain = Domain{int(std::ceil(width_mm)), int(std::ceil(height_mm)), width_mm, height_mm};
  scene.frame_rate_hz = 30.0;
  scene.effects.set(params);
  return scene;
}

// Hexagonal rows from the floor up: `columns` across (odd rows shifted half a diameter, one fewer),
// `rows` high, the first row resting on the floor, starting `left_mm` from the left wall; each
// centre `spacing` diameters from its neighbours.
inline std::vector<Point> hex_block(const Scene& scene, int columns, int rows, double left_mm = 0.0,
                                    double spacing = 1.0) {
  const double d = scene.effects.get<ParticleParams>().diameter_mm * spacing, row = d * std::sqrt(3.0) / 2.0;
  std::vector<Point> points;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns - r % 2; ++c)
      points.push_back({left_mm + (c + 0.5 + 0.5 * (r % 2)) * d, scene.domain.height_mm - d / 2 - r * row});
  return points;
}

// A round drop of about n particles in a hexagonal packing, centred at (x, y).
inline std::vector<Point> hex_disc(const Scene& scene, int n, double x, double y) {
  const double d = scene.effects.get<ParticleParams>().diameter_mm, row = d * std::sqrt(3.0) / 2.0;
  std::vector<std::pair<double, Point>> all;
  const int reach = int(std::ceil(std::sqrt(double(n)))) + 2;
  for (int r = -reach; r <= reach; ++r)
    for (int c = -reach; c <= reach; ++c) {
      const Point p{x + (c + 0.5 * (r & 1)) * d, y + r * row};
      all.push_back({std::hypot(p.x - x, p.y - y), p});
    }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Point> points;
  for (int i = 0; i < n; ++i) points.push_back(all[std::size_t(i)].second);
  return points;
}

class ParticleBox {
 public:
  // Particles at `points`, at rest, old enough that their forces are at full strength.
  ParticleBox(const Scene& scene, const std::vector<Point>& points)
      : scene_(scene), model_(resolve_particles(scene).model), cpu_(make_cpu_backend(1)), n_(int(points.size())) {
    if (scene.mesh) {
      maps_ = bake_surface_maps(scene.mesh->mesh(), texture_panel(scene.domain), device_gravity_mm_s2(scene));
      model_.surface = {maps_.frame.data(), maps_.gravity.data(), scene.domain.grid()};
    }
    ParticleArrays& a = args_.arrays;
    a.capacity = n_;
    position_ = cpu_->allocate(2 * n_ * sizeof(float));
    velocity_ = cpu_->allocate(2 * n_ * sizeof(float));
    age_ = cpu_->allocate(n_ * sizeof(std::uint32_t));
    rest_ = cpu_->allocate(n_ * sizeof(std::uint32_t));
    anchor_ = cpu_->allocate(2 * n_ * sizeof(float));
    a.position = position_.as<float>();
    a.velocity = velocity_.as<float>();
    a.age = age_.as<std::uint32_t>();
    a.rest = rest_.as<std::uint32_t>();
    a.anchor = anchor_.as<float>();
    scratch_ = cpu_->allocate(particle_scratch_bytes(cell_count(model_), line_node_count(model_), n_, 0));
    point_particle_scratch(a, cell_count(model_), line_node_count(model_), scratch_.data(), 0);
    clear_particles(*cpu_, a);
    for (int i = 0; i < n_; ++i) {
      a.position[2 * i] = float(points[std::size_t(i)].x);
      a.position[2 * i + 1] = float(points[std::size_t(i)].y);
      a.age[i] = std::uint32_t(model_.birth_steps);
    }
    args_.model = model_;
    args_.live_count = n_;
    args_.first_live_slot = 0;
  }

  const ParticleModel& model() const { return args_.model; }
  // Gravity changed under the particles (a tilted panel), from the next step on.
  void set_gravity(float x_mm_s2, float y_mm_s2) {
    args_.model.gravity_x = x_mm_s2;
    args_.model.gravity_y = y_mm_s2;
  }
  const ParticleArrays& arrays() const { return args_.arrays; }
  int size() const { return n_; }
  double dt() const { return model_.dt_s; }

  // The bin alone: sorted copies, a film with depth's depths and contact line's grid.
  void bin() { cpu_twin(ParticlePhase::bin, args_, 1); }
  // One physics step: bin, collide, integrate.
  void step() {
    for (ParticlePhase phase : {ParticlePhase::bin, ParticlePhase::collide, ParticlePhase::integrate})
      cpu_twin(phase, args_, 1);
  }
  void run_for(double seconds) {
    const long steps = std::lround(seconds / double(model_.dt_s));
    for (long s = 0; s < steps; ++s) step();
  }

  Point position(int i) const { return {args_.arrays.position[2 * i], args_.arrays.position[2 * i + 1]}; }
  Point velocity(int i) const { return {args_.arrays.velocity[2 * i], args_.arrays.velocity[2 * i + 1]}; }
  double speed(int i) const { return std::hypot(velocity(i).x, velocity(i).y); }
  Point centre() const {
    Point c{0, 0};
    for (int i = 0; i < n_; ++i) c.x += position(i).x / n_, c.y += position(i).y / n_;
    return c;
  }

 private:
  Scene scene_;
  ParticleModel model_;
  std::unique_ptr<Backend> cpu_;
  int n_;
  SurfaceMaps maps_;
  Buffer position_, velocity_, age_, rest_, anchor_, scratch_;
  ParticleArgs args_{};
};

}  // namespace bleedsim::test
