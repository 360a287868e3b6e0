// The parameter tables (core/runtime/params.h) are the one source of every range and rule: a value
// outside a key's range is refused by the check of scenes built in code (check_params, which
// Simulation runs) and by the scenario reader, with the same key and the same message, for every
// numeric key of every table. The tables also say what `bleedsim params` and the docs show.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <variant>

#include "core/effects/blur/blur_params.h"
#include "core/effects/cuts.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/io/scenario.h"
#include "core/runtime/message_text.h"
#include "core/simulation/simulation.h"
#include "tests/io/scenario_text.h"
#include "tests/runtime/scenes_in_code.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

const std::string kScene =
    "[scene]\nwidth_px = 64\nheight_px = 48\nwidth_mm = 16.0\nheight_mm = 12.0\nduration_s = 0.5\n";

// How to write one table of a scenario: what comes before it, its header, and the keys it needs.
struct TableText {
  std::string preamble;
  std::string header;
  std::map<std::string, std::string> required;  // key → a valid value, as TOML
};

// A value below `range`: at its excluded bottom, or under it; none for a range without a bottom.
std::optional<double> below(const Range& range) {
  if (!std::isfinite(range.low)) return std::nullopt;
  return range.above ? range.low : range.low - std::max(1.0, std::abs(range.low));
}

std::string toml_number(double v, ParamType type) {
  return type == ParamType::integer ? std::to_string(static_cast<long long>(v)) : format_number(v);
}

// Every numeric key of `table`, set below its range in `valid` and in a file: both refuse it.
template <class P>
void expect_each_range_refused_both_ways(const ParamTable<P>& table, const P& valid, const Scene& scene,
                                         const TableText& text, const std::string& at) {
  int tested = 0;
  for (const Param<P>& param : table.params) {
    const bool has_range =
        param.type == ParamType::integer || param.type == ParamType::number || param.type == ParamType::vector ||
        param.type == ParamType::vector3;
    const std::optional<double> bad = below(param.range);
    if (!has_range || !bad) continue;
    P params = valid;
    bool numeric = true;
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          if constexpr (std::is_same_v<F, VectorRef (*)(P&)>) {
            field(params).y = *bad;
          } else if constexpr (std::is_same_v<F, double& (*)(P&)> || std::is_same_v<F, int& (*)(P&)> ||
                               std::is_same_v<F, std::uint8_t& (*)(P&)> || std::is_same_v<F, std::uint64_t& (*)(P&)>) {
            // An integer member cannot hold every value below its range (a seed below 0): those are
            // refused by the reader alone, which checks before it narrows.
            using T = std::remove_reference_t<decltype(field(params))>;
            if (std::is_integral_v<T> && std::is_unsigned_v<T> && *bad < 0) numeric = false;
            else field(params) = static_cast<T>(*bad);
          } else {
            numeric = false;
          }
        },
        param.field);
    const bool vector = param.type == ParamType::vector || param.type == ParamType::vector3;
    const std::string key = at + "." + param.key + (vector ? ".y" : "");
    const std::string message = range_problem(key, param.type, param.range, *bad).message;
    if (numeric) {
      const ParamProblem in_code = check_params(table, params, scene, at);
      EXPECT_EQ(in_code.key, key);
      EXPECT_EQ(in_code.message, message) << key;
    }
    // In a file: the table's required keys, then this one.
    std::string file = text.preamble + text.header + "\n";
    int line = 1 + int(std::count(file.begin(), file.end(), '\n'));
    for (const auto& [k, v] : text.required)
      if (k != param.key) file += k + " = " + v + "\n", ++line;
    const std::string value = toml_number(*bad, param.type);
    const std::string third = param.type == ParamType::vector3 ? ", 0]" : "]";
    file += std::string(param.key) + " = " + (vector ? "[0, " + value + third : value) + "\n";
    EXPECT_TRUE(test::refused_at(file, line, key, message)) << file;
    ++tested;
  }
  EXPECT_GT(tested, 0) << table.name;
}

std::string trace_path() {
  return (std::filesystem::path(test::source_dir()) / "scenarios" / "traces" / "single-stroke.csv").string();
}

TEST(ParamTables, EveryRangeIsRefusedAlikeInCodeAndInAFile) {
  const Scene scene = test::scene_in_code(true);
  expect_each_range_refused_both_ways(
      scene_table(), scene, scene,
      {"", "[scene]", {{"width_px", "64"}, {"height_px", "48"}, {"width_mm", "16.0"}, {"height_mm", "12.0"}, {"duration_s", "0.5"}}},
      "scene");
  expect_each_range_refused_both_ways(spread_table(), SpreadParams{}, scene, {kScene, "[spread]", {}}, "spread");
  expect_each_range_refused_both_ways(particle_table(), ParticleParams{}, scene, {kScene, "[particles]", {}},
                                      "particles");
  expect_each_range_refused_both_ways(blur_table(), BlurParams{}, scene, {kScene + "[particles]\n", "[blur]", {}},
                                      "blur");
  expect_each_range_refused_both_ways(haptic_table(), HapticParams{}, scene,
                                      {kScene, "[haptics]", {{"trace", "\"" + trace_path() + "\""}}}, "haptics");
  expect_each_range_refused_both_ways(cut_table(), cut_at(scene, 8, 6, 0), scene,
                                      {kScene + "[spread]\n", "[[cut]]", {{"x_mm", "8.0"}, {"y_mm", "6.0"}}}, "cut[0]");
  expect_each_range_refused_both_ways(output_table(), OutputSpec{}, scene, {kScene, "[output]", {}}, "output");
}

TEST(ParamTables, ARuleRefusesAlikeInCodeAndInAFile) {
  // fade_s ≤ lifetime_s, a rule between two keys of [particles].
  Scene scene = test::scene_in_code(true);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().lifetime_s = 5;
  scene.effects.get<ParticleParams>().fade_s = 6;
  try {
    Simulation sim(scene);
    ADD_FAILURE() << "a fade longer than the lifetime was accepted in code";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "particles.fade_s: must be at most lifetime_s, 5 s (got 6)");
  }
  EXPECT_TRUE(test::refused_at(kScene + "[particles]\nlifetime_s = 5\nfade_s = 6\n", 9, "particles.fade_s",
                               "must be at most lifetime_s, 5 s (got 6)"));
}

TEST(ParamTables, ZeroMeansTheDiameterForTheCellAndTheSplat) {
  const Scenario s = parse_scenario(kScene + "[particles]\ncell_mm = 0\nsplat_radius_mm = 0\n", test::kPath);
  EXPECT_EQ(s.scene.effects.get<ParticleParams>().cell_mm, 0.0);
  EXPECT_EQ(s.scene.effects.get<ParticleParams>().splat_radius_mm, 0.0);
}

TEST(ParamTables, TheDocumentedDefaultsAreTheStructsOwn) {
  // What `bleedsim params` shows as a default is what a default-constructed struct holds; a default
  // that follows from other keys is said in words.
  EXPECT_EQ(scenario_param("particles.capacity").default_text(), std::to_string(ParticleParams{}.capacity));
  EXPECT_EQ(scenario_param("particles.substeps").default_text(),
            "0: the fewest inside the limit (with film_depth, and under half a diameter a step at max_speed_mm_s)");
  EXPECT_EQ(std::get<double>(scenario_param("haptics.max_force_N").default_value), HapticParams{}.max_force_N);
  EXPECT_EQ(scenario_param("particles.gravity_mm_s2").default_text(), "[0, 1000]");
  EXPECT_EQ(scenario_param("blur.sigma_px").default_text(), "max(0.5, radius_px / 2)");
  EXPECT_EQ(scenario_param("blur.downsample").allowed_text(), "1, 2 or 4");
  EXPECT_EQ(scenario_param("scene.width_px").default_text(), "required");
  EXPECT_THROW(scenario_param("particles.nothing"), std::out_of_range);
}

}  // namespace
}  // namespace bleedsim