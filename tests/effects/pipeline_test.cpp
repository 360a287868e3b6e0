// Only the effects a scene calls for: a stage the scene does not declare is never built, so it
// allocates nothing and the backend never runs it.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blur/blur_params.h"
#include "core/effects/cuts.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pipeline.h"
#include "core/effects/resolved.h"
#include "core/effects/spread/spread_params.h"
#include "core/physics/optics_tables.h"
#include "core/simulation/simulation.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

const BackendChoice kCpu{BackendChoice::Want::cpu, 2};

// The in-code scene with particles from a cut at (8, 4) mm, and with [blur] when asked.
Scene particle_scene(bool blurred) {
  Scene scene = test::scene_in_code(false);
  scene.effects.set(ParticleParams{});
  scene.effects.get<ParticleParams>().capacity = 256;
  scene.cuts = {cut_at(scene, 8.0, 4.0, 0.0)};
  if (blurred) scene.effects.set(BlurParams{});
  return scene;
}

TEST(Pipeline, ASceneWithoutTheSpreadHasNoneOfItsCost) {
  Simulation sim(test::scene_in_code(false), kCpu);
  for (int k = 0; k < 5; ++k) sim.step();

  EXPECT_EQ(Pipeline::stage_names(sim.scene()), std::vector<std::string>({"blend"}));
  const std::vector<StageReport> report = sim.pipeline_report();
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].name, "blend");
  EXPECT_EQ(report[0].launches, 5u);
  // The backend itself never ran the spread, and holds only the tissue, the frame and the blend's
  // optical tables.
  EXPECT_EQ(sim.backend().launches("spread"), 0u);
  EXPECT_EQ(sim.backend().bytes_in_use(), 2u * 64 * 48 * 4 + kOpticsTableFloats * sizeof(float));
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
    EXPECT_EQ(Pipeline::backend_bytes(scene, resolve(scene)), sim.backend().bytes_in_use()) << "spread " << spread;
  }
}

// The screen-space stages follow the scene: particles bring the splat; only [blur] brings the blur;
// the blend lays over the tissue whichever film the scene makes.
TEST(Pipeline, TheFilmsStagesRunOnlyWhenTheSceneCallsForThem) {
  const Scene particles = particle_scene(false), blurred = particle_scene(true);

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
  EXPECT_EQ(Pipeline::backend_bytes(spread.scene(), spread.resolved()), spread.backend().bytes_in_use());
}

// Every field has one writer, and the list says which scenario table calls for it.
TEST(StageKinds, EachFieldHasOneWriterAndTheTableThatCallsForIt) {
  std::map<std::string, int> writers;
  for (const StageKind& kind : stage_kinds())
    for (const FieldLayout& field : kind.writes) ++writers[field.name];
  for (const auto& [field, count] : writers) EXPECT_EQ(count, 1) << field;
  ASSERT_NE(stage_writing("blur/thickness"), nullptr);
  EXPECT_STREQ(stage_writing("blur/thickness")->table, "blur");
  EXPECT_STREQ(stage_writing("splat/thickness")->name, "splat");
  EXPECT_STREQ(stage_writing("splat/thickness")->table, "particles");
  EXPECT_STREQ(stage_writing("frame")->table, "");
  EXPECT_EQ(stage_writing("glare"), nullptr);
}

// The run order follows the reads (the film after the particles, the blend after all): it fixes
// the order of State's fields, and so of every frame's hash.
TEST(Pipeline, RunsEachStageAfterTheStagesWhoseFieldsItReads) {
  Scene scene = particle_scene(true);
  scene.effects.set(SpreadParams{});
  EXPECT_EQ(Pipeline::stage_names(scene),
            (std::vector<std::string>{"spread", "particles", "splat", "blur", "blend"}));
  const Simulation sim(scene, kCpu);
  EXPECT_EQ(sim.field_names(),
            (std::vector<std::string>{"spread/stain", "particles/position", "particles/velocity", "particles/age",
                                      "particles/rest", "particles/anchor", "particles/accounting",
                                      "splat/thickness", "blur/thickness", "frame"}));
}

// The blend reads the stain and the film the scene makes, and nothing it does not.
TEST(Pipeline, TheBlendReadsTheFieldsTheSceneMakes) {
  const Scene bare = test::scene_in_code(false), stained = test::scene_in_code(true);
  const Scene raw = particle_scene(false), soft = particle_scene(true);
  EXPECT_EQ(blend_stain_field(bare), nullptr);
  EXPECT_STREQ(blend_stain_field(stained), "spread/stain");
  EXPECT_EQ(blend_film_field(stained), nullptr);
  EXPECT_STREQ(blend_film_field(raw), "splat/thickness");
  EXPECT_STREQ(blend_film_field(soft), "blur/thickness");
  EXPECT_EQ(stage_writing("frame")->reads(soft), std::vector<std::string>{"blur/thickness"});
}

// A stage whose input no stage of the scene writes is refused before anything is allocated, with
// the stage, the field, its writer and the table that calls for the writer.
TEST(Pipeline, RefusesAStageWhoseInputNoStageOfTheSceneWrites) {
  Scene scene = test::scene_in_code(false);
  scene.effects.set(BlurParams{});  // and no [particles]: nothing makes the film it blurs
  std::unique_ptr<Backend> cpu = make_cpu_backend(1);
  State state;
  try {
    Pipeline pipeline(scene, resolve(scene), state, *cpu);
    FAIL() << "built";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "blur: the blur stage reads splat/thickness, which the splat stage writes; a scene calls for "
                           "that stage with a [particles] table, and this one has none");
  }
  EXPECT_EQ(cpu->bytes_in_use(), 0u);
  EXPECT_TRUE(state.fields.empty());
  EXPECT_THROW(Pipeline::backend_bytes(scene, resolve(scene)), std::invalid_argument);
}

TEST(State, AMissingInputIsABug) {
  const State state;
  EXPECT_THROW(state.require("spread/stain"), std::logic_error);
}

}  // namespace
}  // namespace bleedsim