// Only the effects a scene calls for: a stage the scene does not declare is never built, so it
// allocates nothing and the backend never runs it.
#include <gtest/gtest.h>

#include "core/effects/pipeline.h"
#include "core/runtime/simulation.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

TEST(Pipeline, ASceneWithoutTheSpreadHasNoneOfItsCost) {
  Simulation sim(test::scene_in_code(false), kCpu);
  for (int k = 0; k < 5; ++k) sim.step();

  EXPECT_EQ(Pipeline::stage_names(sim.scene()), std::vector<std::string>({"blend"}));
  const std::vector<StageReport> report = sim.pipeline_report();
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].name, "blend");
  EXPECT_EQ(report[0].launches, 5u);
  // The backend itself never ran the spread, and holds only the tissue and the frame.
  EXPECT_EQ(sim.backend().launches("spread"), 0u);
  EXPECT_EQ(sim.backend().bytes_in_use(), 2u * 64 * 48 * 4);
  EXPECT_EQ(sim.field_names(), std::vector<std::string>({"frame"}));
  EXPECT_THROW(sim.field("spread/stain"), std::out_of_range);
}

TEST(Pipeline, ASceneWithTheSpreadRunsItOncePerFrame) {
  Simulation sim(test::scene_in_code(true), kCpu);
  for (int k = 0; k < 5; ++k) sim.step();

  const std::vector<StageReport> report = sim.pipeline_report();
  ASSERT_EQ(report.size(), 2u);
  EXPECT_EQ(report[0].name, "spread");
  EXPECT_EQ(report[0].launches, 5u);
  EXPECT_GE(report[0].bytes, 64u * 48 * sizeof(float));
  EXPECT_EQ(report[1].name, "blend");
  EXPECT_EQ(sim.backend().bytes_in_use(), report[0].bytes + report[1].bytes);
}

TEST(Pipeline, EstimatesExactlyWhatItAllocates) {
  for (const bool spread : {false, true}) {
    const Scene scene = test::scene_in_code(spread);
    Simulation sim(scene, kCpu);
    EXPECT_EQ(Pipeline::backend_bytes(scene), sim.backend().bytes_in_use()) << "spread " << spread;
  }
}

// The screen-space stages follow the scene: particles bring the splat; only [blur] brings the blur;
// the blend lays over the tissue whichever film the scene makes.
TEST(Pipeline, TheFilmsStagesRunOnlyWhenTheSceneCallsForThem) {
  Scene particles = test::scene_in_code(false);
  particles.particles = ParticleParams{};
  particles.particles->capacity = 256;
  particles.cuts = {particles.cut_at(8.0, 4.0, 0.0)};
  Scene blurred = particles;
  blurred.blur = BlurParams{};

  Simulation raw(particles, kCpu), soft(blurred, kCpu);
  for (int k = 0; k < 3; ++k) raw.step(), soft.step();
  EXPECT_EQ(Pipeline::stage_names(particles), (std::vector<std::string>{"particles", "splat", "blend"}));
  EXPECT_EQ(Pipeline::stage_names(blurred), (std::vector<std::string>{"particles", "splat", "blur", "blend"}));
  EXPECT_EQ(raw.backend().launches("splat"), 3u);
  EXPECT_EQ(raw.backend().launches("blur"), 0u);
  EXPECT_EQ(soft.backend().launches("blur"), 3u * 4);  // four passes a frame
  EXPECT_THROW(raw.field("blur/thickness"), std::out_of_range);
  // Both make the same film; only the blurred scene's frame shows it softened.
  EXPECT_EQ(raw.copy_field("splat/thickness"), soft.copy_field("splat/thickness"));
  EXPECT_NE(raw.copy_field("frame"), soft.copy_field("frame"));
  // A spread-only scene allocates nothing for a film: no splat, blur or Beer–Lambert table.
  Simulation spread(test::scene_in_code(true), kCpu);
  EXPECT_EQ(spread.backend().launches("splat"), 0u);
  EXPECT_EQ(Pipeline::backend_bytes(test::scene_in_code(true)), spread.backend().bytes_in_use());
}

}  // namespace
}  // namespace bleedsim
