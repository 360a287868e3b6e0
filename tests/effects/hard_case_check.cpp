#include "tests/effects/hard_case_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <utility>

#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/io/scenario.h"
#include "core/physics/instrument.h"
#include "tests/runtime/field_values.h"
#include "tests/test_paths.h"

namespace bleedsim::test {

namespace fs = std::filesystem;

std::string hard_scenario(const std::string& name) {
  return (fs::path(source_dir()) / "scenarios" / "hard" / (name + ".toml")).string();
}

Scene load_hard(const std::string& name) { return load_scenario(hard_scenario(name)).scene; }

Particles::Particles(const Simulation& sim)
    : position(field_values<float>(sim, "particles/position")),
      velocity(field_values<float>(sim, "particles/velocity")),
      age(field_values<std::uint32_t>(sim, "particles/age")),
      t_s(sim.time_s()) {
  const std::vector<std::uint64_t> c = field_values<std::uint64_t>(sim, "particles/accounting");
  counts = {c.at(0), c.at(1), c.at(2), c.at(3), c.size() > 4 ? c[4] : 0};
}

double Particles::speed(int s) const { return std::hypot(double(velocity[2 * s]), double(velocity[2 * s + 1])); }

double kinetic_energy(const ParticleModel& m, const Particles& p) {
  double sum = 0.0;
  for (int s = 0; s < p.slots(); ++s)
    if (is_alive(m, p.age[s])) {
      const double vx = p.velocity[2 * s], vy = p.velocity[2 * s + 1];
      sum += 0.5 * (vx * vx + vy * vy);
    }
  return sum;
}

Crowding measure_crowding(const ParticleModel& m, const Particles& p, std::uint32_t min_age) {
  const double d = m.diameter_mm;
  const double x0 = m.min_x, y0 = m.min_y;
  const int nx = int((double(m.max_x) - x0) / d) + 1, ny = int((double(m.max_y) - y0) / d) + 1;
  const auto cell_of = [&](int s) {
    const int cx = std::clamp(int(std::floor((p.position[2 * s] - x0) / d)), 0, nx - 1);
    const int cy = std::clamp(int(std::floor((p.position[2 * s + 1] - y0) / d)), 0, ny - 1);
    return cy * nx + cx;
  };
  std::vector<int> start(std::size_t(nx) * ny + 1, 0);
  std::vector<int> chosen;
  for (int s = 0; s < p.slots(); ++s)
    if (is_alive(m, p.age[s]) && p.age[s] >= min_age) chosen.push_back(s), ++start[cell_of(s) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<int> order(chosen.size());
  std::vector<int> cursor(start.begin(), start.end() - 1);
  for (const int s : chosen) order[cursor[cell_of(s)]++] = s;

  Crowding out;
  const auto pair = [&](int a, int b) {
    const double dx = double(p.position[2 * a]) - p.position[2 * b];
    const double dy = double(p.position[2 * a + 1]) - p.position[2 * b + 1];
    const double r2 = dx * dx + dy * dy;
    if (r2 < d * d) out.max_overlap_mm = std::max(out.max_overlap_mm, d - std::sqrt(r2));
  };
  for (int cy = 0; cy < ny; ++cy)
    for (int cx = 0; cx < nx; ++cx) {
      const int c = cy * nx + cx;
      for (int k = start[c]; k < start[c + 1]; ++k) {
        // The rest of its own cell, then the cells right, below-left, below and below-right: each
        // pair of neighbouring cells once.
        for (int j = k + 1; j < start[c + 1]; ++j) pair(order[k], order[j]);
        for (const auto& [ox, oy] : {std::pair{1, 0}, std::pair{-1, 1}, std::pair{0, 1}, std::pair{1, 1}}) {
          if (cx + ox < 0 || cx + ox >= nx || cy + oy >= ny) continue;
          const int n = (cy + oy) * nx + cx + ox;
          for (int j = start[n]; j < start[n + 1]; ++j) pair(order[k], order[j]);
        }
      }
    }

  // Occupancy of the library's cells: floor(position / cell_mm), every live particle.
  std::vector<int> per_cell(std::size_t(m.cells_x) * m.cells_y, 0);
  for (int s = 0; s < p.slots(); ++s) {
    if (!is_alive(m, p.age[s])) continue;
    const int cx = std::clamp(int(std::floor(p.position[2 * s] / double(m.cell_mm))), 0, m.cells_x - 1);
    const int cy = std::clamp(int(std::floor(p.position[2 * s + 1] / double(m.cell_mm))), 0, m.cells_y - 1);
    out.max_per_cell = std::max(out.max_per_cell, ++per_cell[std::size_t(cy) * m.cells_x + cx]);
  }
  return out;
}

double wall_reach_mm(const Scene& scene) {
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  return p.compression * p.diameter_mm + p.max_speed_mm_s / std::sqrt(double(resolve_particles(scene).model.wall_stiffness));
}

double deepest_into_a_wall_mm(const ParticleModel& m, const Particles& p) {
  double deepest = 0.0;
  for (int s = 0; s < p.slots(); ++s) {
    if (!is_alive(m, p.age[s])) continue;
    const double x = p.position[2 * s], y = p.position[2 * s + 1];
    deepest = std::max({deepest, m.min_x - x, x - m.max_x, m.min_y - y, y - m.max_y});
  }
  return deepest;
}

std::string frame_problem(const ParticleModel& m, const Particles& p, double wall_reach_mm) {
  std::ostringstream why;
  int live = 0;
  for (int s = 0; s < p.slots(); ++s) {
    const float x = p.position[2 * s], y = p.position[2 * s + 1];
    const float vx = p.velocity[2 * s], vy = p.velocity[2 * s + 1];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(vx) || !std::isfinite(vy)) {
      why << "slot " << s << " (age " << p.age[s] << ") is not finite: position (" << x << ", " << y << "), velocity ("
          << vx << ", " << vy << ")";
      return why.str();
    }
    if (!is_alive(m, p.age[s])) continue;
    ++live;
    // In float, as the kernel's backstop is: reach = wall_give is exactly where it stops a centre.
    const float reach = float(wall_reach_mm);
    if (!(x >= m.min_x - reach && x <= m.max_x + reach && y >= m.min_y - reach && y <= m.max_y + reach)) {
      why << "slot " << s << " at (" << x << ", " << y << ") is past a wall by more than " << reach << " mm (walls at ["
          << m.min_x << ", " << m.max_x << "] x [" << m.min_y << ", " << m.max_y << "])";
      return why.str();
    }
  }
  const ParticleCounts& c = p.counts;
  if (c.emitted != c.alive + c.expired + c.overwritten + c.aspirated) {
    why << "accounting: emitted " << c.emitted << " != alive " << c.alive << " + expired " << c.expired
        << " + overwritten " << c.overwritten << " + aspirated " << c.aspirated;
    return why.str();
  }
  if (std::uint64_t(live) != c.alive) {
    why << "accounting says " << c.alive << " alive, but " << live << " slots have an age below the lifetime";
    return why.str();
  }
  return "";
}

std::optional<ToolSample> tip_after_steps(const Scene& scene, std::uint64_t steps_done) {
  if (scene.tips.empty() || steps_done == 0) return std::nullopt;
  return tool_at(scripted_tool(scene.tips), double(steps_done) / resolve_particles(scene).steps_per_s, false);
}

float tip_body_mm(const Scene& scene) {
  return float(scene.effects.get<ContactParams>().tip_radius_mm +
               scene.effects.get<ParticleParams>().diameter_mm / 2.0);
}

std::string inside_tip_problem(const ParticleModel& m, const Particles& p, const ToolSample& tip, float body_mm) {
  for (int s = 0; s < p.slots(); ++s) {
    if (!is_alive(m, p.age[s]) ||
        outside_disc(p.position[2 * s], p.position[2 * s + 1], float(tip.x_mm), float(tip.y_mm), body_mm))
      continue;
    std::ostringstream why;
    why.precision(9);
    why << "slot " << s << " at (" << p.position[2 * s] << ", " << p.position[2 * s + 1] << ") is "
        << std::hypot(p.position[2 * s] - tip.x_mm, p.position[2 * s + 1] - tip.y_mm) << " mm from the tip at ("
        << float(tip.x_mm) << ", " << float(tip.y_mm) << "), inside its body of " << body_mm << " mm";
    return why.str();
  }
  return "";
}

double left_alone_s(const Scene& scene) {
  double end = 0.0;
  for (const Cut& cut : scene.cuts)
    if (cut.wound_mm * cut.flow_mm3_per_s_per_mm > 0.0) end = std::max(end, cut.start_s + cut.bleed_s);
  if (scene.effects.has<ContactParams>() && !scene.tips.empty()) end = std::max(end, scene.tips.back().t_s);
  return end;
}

namespace {

std::string describe(const std::string& name, const Scene& scene, const ParticleModel& m, const RunSummary& r,
                     const Expect& e) {
  const ParticleCounts& c = r.final_counts;
  const ParticleParams& pp = scene.effects.get<ParticleParams>();
  const ParticleMechanics mech = resolve_particles(pp, scene).mechanics;
  const double d = m.diameter_mm;
  char unbounded[120] = "";
  if (e.overlap_unbounded_until_s > 0.0)
    std::snprintf(unbounded, sizeof unbounded, ", and %.1f%% unbounded until %.4g s",
                  100.0 * r.unbounded_overlap_mm / d, e.overlap_unbounded_until_s);
  char text[1800];
  std::snprintf(
      text, sizeof text,
      "[hard/%s] %llu particles emitted, at most %llu alive; %llu steps (%lld frames), dt %.4g ms = %.3f of the "
      "limit %.4g ms\n"
      "  max overlap %.1f%% of d (frame %lld; bound %.0f%%)%s; at rest %.1f%% (bound %.0f%%)\n"
      "  KE when left alone %.4g, at end %.4g (ratio %.3g, bound %.3g); max KE first/last quarter after "
      "%.4g / %.4g\n"
      "  end: emitted %llu = alive %llu + expired %llu + overwritten %llu + aspirated %llu; max per cell %d; "
      "fastest %.4g mm/s; deepest into a wall %.2f%% of d; %d frames checked against the tip; %.2f s",
      name.c_str(), (unsigned long long)c.emitted, (unsigned long long)r.max_alive, (unsigned long long)r.steps,
      (long long)r.frames, m.dt_s * 1e3, m.dt_s / mech.step_limit_s, 1e3 * mech.step_limit_s,
      100.0 * r.max_overlap_mm / d, (long long)r.max_overlap_frame, 100.0 * kPassThrough, unbounded,
      100.0 * r.rest_overlap_mm / d, 100.0 * e.at_rest, r.energy_at_stop, r.energy_at_end,
      r.energy_at_end / r.energy_at_stop, e.end_energy_ratio, r.first_quarter_max, r.last_quarter_max,
      (unsigned long long)c.emitted, (unsigned long long)c.alive, (unsigned long long)c.expired,
      (unsigned long long)c.overwritten, (unsigned long long)c.aspirated, r.max_per_cell_at_end, r.max_speed,
      100.0 * r.into_wall_mm / d, r.tip_frames, r.seconds);
  return text;
}

}  // namespace

void run_and_check(const std::string& name, Scene scene, const Expect& expect, RunSummary* out,
                   const std::function<void(const Particles&)>& each_frame) {
  const auto began = std::chrono::steady_clock::now();
  const ParticleModel m = resolve_particles(scene).model;
  const double reach = wall_reach_mm(scene);
  const double alone_s = left_alone_s(scene);
  const ParticleMechanics mech = resolve_particles(scene.effects.get<ParticleParams>(), scene).mechanics;
  const std::uint32_t settled_age = std::uint32_t(m.birth_steps) + std::uint32_t(mech.substeps);  // born, and a frame
  const double terminal_speed = std::hypot(m.gravity_x, m.gravity_y) / scene.effects.get<ParticleParams>().drag_per_s;
  const std::int64_t frames = scene.frame_count();
  const double frame_rate = scene.frame_rate_hz;
  const bool tip_body = scene.effects.has<ContactParams>() && !scene.tips.empty();
  const float body_mm = tip_body ? tip_body_mm(scene) : 0.0f;
  // The frames from the one the particles are left alone in: the last quarter of them is "at rest".
  const std::int64_t first_alone = std::int64_t(std::ceil(alone_s * frame_rate - 1e-9)) - 1;
  const std::int64_t alone = frames - std::max<std::int64_t>(first_alone, 0);
  ASSERT_GE(alone, 8) << name << ": too few frames after the particles are left alone at " << alone_s << " s";
  const std::int64_t rest_from = frames - alone / 4;
  const Scene copy = scene;
  Simulation sim(std::move(scene), BackendChoice{BackendChoice::Want::cpu, 2});
  RunSummary r;
  std::vector<double> energy_alone;  // one per frame from the one the particles were left alone in
  for (std::int64_t k = 0; k < frames; ++k) {
    sim.step();
    const Particles p(sim);
    // While a case lifts the pass-through bound (something outside the particles' physics, the tip,
    // moves them), it lifts the walls' too: only the backstop holds then.
    const std::string problem = frame_problem(m, p, p.t_s < expect.overlap_unbounded_until_s ? m.wall_give : reach);
    r.into_wall_mm = std::max(r.into_wall_mm, deepest_into_a_wall_mm(m, p));
    ASSERT_EQ(problem, "") << name << ", frame " << k << " (t = " << p.t_s << " s)";
    if (tip_body) {
      if (const std::optional<ToolSample> tip = tip_after_steps(copy, std::uint64_t(k + 1) * mech.substeps)) {
        ASSERT_EQ(inside_tip_problem(m, p, *tip, body_mm), "") << name << ", frame " << k << " (t = " << p.t_s << " s)";
        ++r.tip_frames;
      }
    }
    const Crowding crowd = measure_crowding(m, p, settled_age);
    if (p.t_s < expect.overlap_unbounded_until_s) {
      r.unbounded_overlap_mm = std::max(r.unbounded_overlap_mm, crowd.max_overlap_mm);
    } else {
      if (crowd.max_overlap_mm > r.max_overlap_mm) r.max_overlap_mm = crowd.max_overlap_mm, r.max_overlap_frame = k;
      ASSERT_LT(crowd.max_overlap_mm, kPassThrough * m.diameter_mm)
          << name << ", frame " << k << " (t = " << p.t_s << " s): overlap of " << crowd.max_overlap_mm / m.diameter_mm
          << " diameters";
    }
    if (k >= rest_from) {
      r.rest_overlap_mm = std::max(r.rest_overlap_mm, crowd.max_overlap_mm);
      ASSERT_LT(crowd.max_overlap_mm, expect.at_rest * m.diameter_mm)
          << name << ", frame " << k << " (t = " << p.t_s << " s), at rest: overlap of "
          << crowd.max_overlap_mm / m.diameter_mm << " diameters";
    }
    for (int s = 0; s < p.slots(); ++s)
      if (is_alive(m, p.age[s])) r.max_speed = std::max(r.max_speed, p.speed(s));
    if (expect.burst) {
      ASSERT_LT(r.max_speed, 2.0 * terminal_speed) << name << ", frame " << k << " (t = " << p.t_s << " s)";
    }
    if (each_frame) {
      each_frame(p);
      if (testing::Test::HasFatalFailure()) return;
    }
    r.max_alive = std::max(r.max_alive, p.counts.alive);
    const double ke = kinetic_energy(m, p);
    if (k >= first_alone) energy_alone.push_back(ke);
    if (k == frames - 1) {
      r.final_counts = p.counts;
      r.max_per_cell_at_end = crowd.max_per_cell;
    }
  }
  r.frames = frames;
  r.steps = std::uint64_t(frames) * std::uint64_t(mech.substeps);

  // The energy once the particles are left alone: nothing feeds them but gravity, while drag and
  // the dashpots take energy out, so a stable run settles into a resting pile (or its particles
  // expire or are taken) and the kinetic energy falls towards zero; an instability feeds it
  // instead. So: the energy at the end a small fraction of the energy when they were left alone,
  // and no late growth — the most over the last quarter of those frames below the most over the
  // first.
  const std::size_t n = energy_alone.size(), quarter = n / 4;
  r.energy_at_stop = energy_alone.front();
  r.energy_at_end = energy_alone.back();
  r.first_quarter_max = *std::max_element(energy_alone.begin(), energy_alone.begin() + quarter);
  r.last_quarter_max = *std::max_element(energy_alone.end() - quarter, energy_alone.end());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  *out = r;
  std::cout << describe(name, copy, m, r, expect) << std::endl;

  // Against the most there was once they were left alone (a burst still lies still when its cut
  // stops).
  const double reference = std::max(r.energy_at_stop, r.first_quarter_max);
  EXPECT_GT(reference, 0.0) << name << ": nothing moving once left alone; the decay means nothing";
  EXPECT_LE(r.energy_at_end, expect.end_energy_ratio * reference) << name;
  EXPECT_LE(r.last_quarter_max, r.first_quarter_max) << name;
  if (expect.max_per_cell_at_end > 0) {
    EXPECT_LE(r.max_per_cell_at_end, expect.max_per_cell_at_end) << name;
  }
}

}  // namespace bleedsim::test
