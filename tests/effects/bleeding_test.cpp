// Bleeding from vessels and with a pulse (docs/bleeding.md): a cut's blood follows the vessel map's
// integral along its wound, a wound where the map is 0 does not bleed, and an arterial wound's flow
// beats at the heart rate about its stated mean; the pulse's closed form against quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "core/bleeding/cut_flow.h"
#include "core/bleeding/heartbeat.h"
#include "core/effects/cuts.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/runtime/tissue.h"
#include "core/simulation/simulation.h"
#include "tests/effects/bleeding_scenes.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};
constexpr double kPi = 3.14159265358979323846;

// A 40 × 32 mm panel of 0.2 mm pixels whose vessel density is density(y) at each pixel's centre,
// with particles that live a few steps (only their count is asked, so few need be alive) and cuts that bleed for bleed_s.
Scene vessel_scene(double (*density)(double y_mm), double duration_s) {
  Scene scene = test::bleeding_scene("vessels", Domain{200, 160, 40.0, 32.0}, duration_s, 0.05, 0.01);
  scene.effects.set(VesselParams{});
  for (int j = 0; j < 160; ++j)
    for (int i = 0; i < 200; ++i) scene.vessel_density.push_back(float(density((j + 0.5) * 0.2)));
  return scene;
}

std::uint64_t emitted(const Simulation& sim) { return test::particle_counts(sim).emitted; }

double gradient(double y_mm) { return y_mm / 32.0; }

// The density rises linearly down the panel, ρ = y / 32 mm. The map holds it at pixel centres and
// is read bilinearly, so along any wound inside the centres' hull it is exactly linear, and the
// midpoint rule integrates a linear function exactly: a wound centred at y_c has mean density y_c/32
// whatever its direction. Each cut bleeds alone for 0.5 s in its own second; the particles it
// emits are ⌊flow · wound · ρ̄ · 0.5 s / V⌋ (V the particle's volume), so within one particle of
// the map's integral, which at ~1,000 particles a cut is 0.1 %: well inside the 1 % asked.
TEST(Vessels, EachCutBleedsTheMapsIntegralAlongItsWound) {
  struct Wound { double x, y, length, angle; };
  const std::vector<Wound> wounds = {{10, 4, 4, 0}, {20, 16, 4, 90}, {30, 28, 6, 45}, {8, 12, 2, -30}, {32, 22, 8, 135}};
  Scene scene = vessel_scene(gradient, double(wounds.size()));
  for (std::size_t k = 0; k < wounds.size(); ++k) {
    Cut& cut = test::add_cut(scene, wounds[k].x, wounds[k].y, double(k), 10.0, 0.5);
    cut.wound_mm = wounds[k].length;
    cut.wound_angle_deg = wounds[k].angle;
  }
  Simulation sim(scene, kCpu);
  std::uint64_t before = 0;
  for (std::size_t k = 0; k < wounds.size(); ++k) {
    while (sim.time_s() < double(k) + 0.9) sim.step();
    const std::uint64_t bled = emitted(sim) - before;
    before = emitted(sim);
    const double integral_mm = wounds[k].length * gradient(wounds[k].y);  // ∫ρ ds along the wound
    const double expected =
        std::floor(10.0 * integral_mm * 0.5 / scene.effects.get<ParticleParams>().particle_volume_mm3);
    EXPECT_NEAR(double(bled), expected, 1.0) << "wound " << k;
    EXPECT_NEAR(double(bled), expected, 0.01 * expected) << "wound " << k;
  }
}

// A map of no vessels above y = 16 mm and full density below, its step between the pixel centres
// at 15.9 and 16.1 mm: a wound entirely above does not bleed, one entirely below bleeds its full
// flow, and a vertical one from 14 to 18 mm has mean density (1.9 + 0.2/2) / 4 = 0.5 exactly.
TEST(Vessels, AWoundWithoutVesselsDoesNotBleed) {
  Scene scene = vessel_scene([](double y) { return y < 16.0 ? 0.0 : 1.0; }, 1.0);
  const Cut above = with_vessels(scene, cut_at(scene, 20, 10, 0));
  EXPECT_EQ(above.vessel_density, 0.0);
  EXPECT_EQ(cut_blood_mm3(above, 1.0, nullptr), 0.0);
  Cut across = cut_at(scene, 20, 16, 0);
  across.wound_mm = 4.0;
  across.wound_angle_deg = 90.0;
  EXPECT_NEAR(with_vessels(scene, across).vessel_density, 0.5, 1e-12);
  EXPECT_EQ(with_vessels(scene, cut_at(scene, 20, 20, 0)).vessel_density, 1.0);

  test::add_cut(scene, 20, 10, 0, 50.0, scene.effects.get<ParticleParams>().bleed_s);
  Simulation sim(scene, kCpu);
  while (sim.frames_done() < scene.frame_count()) sim.step();
  EXPECT_EQ(emitted(sim), 0u);
}

// The procedural map is the procedural tissue's vessels: where the map is densest the tissue is at
// its darkest red (the vessel colour mixed in at 0.8 of its strength), and where it is 0 no vessel
// colour is mixed in at all (so the green channel is the mucosa's, above the vessel's 0.14).
TEST(Vessels, TheProceduralMapIsWhereTheTissueDrawsVessels) {
  const int w = 160, h = 120;
  const Image tissue = procedural_tissue(w, h, 7);
  const std::vector<float> map = procedural_vessel_density(w, h, 7);
  ASSERT_EQ(map.size(), std::size_t(w * h));
  double green_in = 0, green_out = 0;
  int in = 0, out = 0;
  for (std::size_t p = 0; p < map.size(); ++p) {
    ASSERT_TRUE(map[p] >= 0.0f && map[p] <= 1.0f);
    if (map[p] > 0.9f) green_in += tissue.rgba[4 * p + 1], ++in;
    if (map[p] == 0.0f) green_out += tissue.rgba[4 * p + 1], ++out;
  }
  ASSERT_GT(in, 0);
  ASSERT_GT(out, 0);
  // kVessel green 0.14 mixed at ≥ 0.8·0.9 against a mucosa green of 0.45 ± 0.07: at most
  // 0.72·0.14 + 0.28·0.52 = 0.246 inside, at least 0.38 outside (in bytes, 63 and 96).
  EXPECT_LT(green_in / in, 0.246 * 255 + 1);
  EXPECT_GT(green_out / out, 0.38 * 255 - 1);
}

// ∫ e^{−u/τ} w(t₀ + u) du over [0, s], the closed form against composite Simpson with 20,000
// intervals: the integrand's fourth derivative is at most (2ω)⁴·(1 + a₁ + a₂) (its highest
// harmonic), so Simpson's error is at most s·h⁴·(2ω)⁴·1.9/180 ≈ 1e-10 here.
TEST(Pulse, TheClosedFormIsTheIntegralOfTheWaveform) {
  const PulseParams pulse;
  for (const double clot_s : {0.0, 0.7, 5.0})
    for (const double opened : {0.0, 0.31, 2.5}) {
      const double s = 3.3, tau_k = clot_s > 0 ? 1.0 / clot_s : 0.0;
      const int n = 20000;
      const double h = s / n;
      double simpson = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double u = i * h, f = std::exp(-tau_k * u) * pulse_waveform(pulse, opened + u);
        simpson += f * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
      }
      simpson *= h / 3.0;
      EXPECT_NEAR(pulsed_flowing_s(pulse, opened, s, clot_s), simpson, 1e-9) << clot_s << " " << opened;
    }
}

// An arterial cut bleeding 20 s at 72 beats a minute (24 whole beats) with no clotting: the volume
// it emits frame by frame has its spectrum's peak (the DC term aside) at 1.2 Hz, the frequency bin
// k = 24 of 20 s, and its mean flow is the stated one within 1 %: over whole beats the waveform's
// sines integrate to 0, so the emitted particles are ⌊Q̄ T / V⌋ up to the floor's one particle
// (of 10,000: 0.01 %). A venous cut beside it oozes: its spectrum holds no peak at the heart rate.
TEST(Pulse, AnArterialCutBeatsAtTheHeartRateAboutItsMeanFlow) {
  for (const bool arterial : {true, false}) {
    Scene scene = test::bleeding_scene("pulse", Domain{100, 80, 20.0, 16.0}, 20.0, 0.3, 0.1);
    scene.effects.set(PulseParams{});
    // 2 mm³/s over 1 mm of wound: 500 particles a second.
    test::add_cut(scene, 10, 4, 0, 2.0, 20.0).arterial = arterial;
    Simulation sim(scene, kCpu);
    std::vector<double> per_frame;
    std::uint64_t before = 0;
    while (sim.frames_done() < scene.frame_count()) {
      sim.step();
      per_frame.push_back(double(emitted(sim) - before) * scene.effects.get<ParticleParams>().particle_volume_mm3);
      before = emitted(sim);
    }
    const double mean_flow =
        double(before) * scene.effects.get<ParticleParams>().particle_volume_mm3 / scene.duration_s;
    EXPECT_NEAR(mean_flow, 2.0, 0.02) << (arterial ? "arterial" : "venous");
    // |DFT|² at bins 1 … 150 (up to 7.5 Hz); the heart rate is bin 24.
    const std::size_t n = per_frame.size();
    std::vector<double> power(151, 0.0);
    for (std::size_t k = 1; k < power.size(); ++k) {
      std::complex<double> sum = 0.0;
      for (std::size_t t = 0; t < n; ++t) sum += per_frame[t] * std::polar(1.0, -2.0 * kPi * double(k * t) / double(n));
      power[k] = std::norm(sum);
    }
    std::size_t peak = 1;
    for (std::size_t k = 2; k < power.size(); ++k)
      if (power[k] > power[peak]) peak = k;
    // Whole particles: a frame emits ⌊C(t₁)/V⌋ − ⌊C(t₀)/V⌋ = ΔC/V + r₀ − r₁ (r the fractional
    // parts), so the rounding's DFT is V Σ (r_t − r_{t+1}) e^{−iωt}, which summation by parts
    // bounds by V (n · |1 − e^{iω}| + 2) = V (2n sin(πk/n) + 2) at bin k.
    const double rounding =
        scene.effects.get<ParticleParams>().particle_volume_mm3 * (2.0 * n * std::sin(kPi * 24.0 / n) + 2.0);
    if (arterial) {
      EXPECT_EQ(peak, 24u);
      // A sine of amplitude A per frame has |X| = nA/2; the frame's volume averages a₁ Q̄ sin over
      // 1/30 s, which scales it by sinc(1.2/30); then the rounding above.
      const double frame_average = std::sin(kPi * 1.2 / 30.0) / (kPi * 1.2 / 30.0);
      const double fundamental = n * 0.6 * (2.0 / 30.0) * frame_average / 2.0;
      EXPECT_NEAR(std::sqrt(power[24]), fundamental, rounding);
    } else {
      // A steady flow's ΔC is the same every frame, whose DFT at bin 24 of whole samples is 0: all
      // that is left is the rounding, a twentieth of the arterial cut's line.
      EXPECT_LE(std::sqrt(power[24]), rounding);
    }
  }
}

}  // namespace
}  // namespace bleedsim