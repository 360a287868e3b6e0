// Scenario files (core/io/scenario.cpp): a valid file gives every Scene field, defaults included,
// and every kind of bad input is refused with a message that names the file, the line, the
// dotted key and what is wrong (docs/scenario-format.md, "Errors").
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/effects/blur/blur_params.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/io/scenario.h"
#include "core/runtime/input_error.h"
#include "core/runtime/tissue.h"
#include "tests/io/scenario_text.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

// A folder of its own for each test (tests may run in parallel), removed afterwards.
class ScratchFolder {
 public:
  ScratchFolder() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("bleedsim-" + std::string(test->test_suite_name()) + "." +
                                         test->name() + "-" + std::to_string(getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A 2 × 2 RGBA PNG of four different colours.
void write_small_png(const fs::path& path) {
  const std::uint8_t rgba[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  ASSERT_NE(stbi_write_png(path.string().c_str(), 2, 2, 4, rgba, 2 * 4), 0) << path;
}

// ---- Valid scenarios --------------------------------------------------------------------------

// Every key set, one per line (line numbers in the comments, checked through Scene::places).
const std::string kFull =
    "# A scene that sets every key.\n"  //  1
    "[scene]\n"                         //  2
    "name = \"full-probe\"\n"           //  3
    "width_px = 80\n"                   //  4
    "height_px = 60\n"                  //  5
    "width_mm = 20.0\n"                 //  6
    "height_mm = 15.0\n"                //  7
    "duration_s = 2.0\n"                //  8
    "frame_rate_hz = 25\n"              //  9  an integer where a number is asked: accepted
    "seed = 42\n"                       // 10
    "\n"                                // 11
    "[spread]\n"                        // 12
    "radius_mm = 3.5\n"                 // 13
    "growth_per_s = 0.25\n"             // 14
    "\n"                                // 15
    "[[cut]]\n"                         // 16  takes its size from [spread]
    "x_mm = 5.0\n"                      // 17
    "y_mm = 4.0\n"                      // 18
    "\n"                                // 19
    "[[cut]]\n"                         // 20  gives its own, on the panel's far corner
    "x_mm = 20.0\n"                     // 21
    "y_mm = 15.0\n"                     // 22
    "start_s = 1.25\n"                  // 23
    "radius_mm = 6\n"                   // 24
    "growth_per_s = 2.0\n"              // 25
    "\n"                                // 26
    "[output]\n"                        // 27
    "dir = \"results/full\"\n"          // 28
    "hdf5 = false\n"                    // 29
    "png_every = 5\n"                   // 30
    "deflate = 0\n"                     // 31
    "fields = [\"spread/stain\"]\n";    // 32

TEST(ScenarioParse, ReadsEverySceneField) {
  const Scenario scenario = parse_scenario(kFull, kPath);
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.name, "full-probe");
  EXPECT_EQ(scenario.path, kPath);
  EXPECT_EQ(scenario.text, kFull);  // recorded whole, for provenance in every output
  EXPECT_EQ(scene.domain.width_px, 80);
  EXPECT_EQ(scene.domain.height_px, 60);
  EXPECT_EQ(scene.domain.width_mm, 20.0);
  EXPECT_EQ(scene.domain.height_mm, 15.0);
  EXPECT_EQ(scene.duration_s, 2.0);
  EXPECT_EQ(scene.frame_rate_hz, 25.0);
  EXPECT_EQ(scene.frame_count(), 50);
  EXPECT_EQ(scene.frame_time_s(0), 1.0 / 25.0);  // the end of frame 0's period
  EXPECT_EQ(scene.seed, 42u);

  ASSERT_TRUE(scene.effects.has<SpreadParams>());
  EXPECT_EQ(scene.effects.get<SpreadParams>().radius_mm, 3.5);
  EXPECT_EQ(scene.effects.get<SpreadParams>().growth_per_s, 0.25);

  ASSERT_EQ(scene.cuts.size(), 2u);
  EXPECT_EQ(scene.cuts[0].x_mm, 5.0);
  EXPECT_EQ(scene.cuts[0].y_mm, 4.0);
  EXPECT_EQ(scene.cuts[0].start_s, 0.0);
  EXPECT_EQ(scene.cuts[0].radius_mm, 3.5);       // from [spread]
  EXPECT_EQ(scene.cuts[0].growth_per_s, 0.25);   // from [spread]
  EXPECT_EQ(scene.cuts[1].x_mm, 20.0);
  EXPECT_EQ(scene.cuts[1].y_mm, 15.0);
  EXPECT_EQ(scene.cuts[1].start_s, 1.25);
  EXPECT_EQ(scene.cuts[1].radius_mm, 6.0);
  EXPECT_EQ(scene.cuts[1].growth_per_s, 2.0);

  EXPECT_EQ(scenario.output.dir, "results/full");
  EXPECT_FALSE(scenario.output.hdf5);
  EXPECT_EQ(scenario.output.png_every, 5);
  EXPECT_EQ(scenario.output.deflate_level, 0);
  EXPECT_EQ(scenario.output.fields, std::vector<std::string>{"spread/stain"});

  // No [tissue]: the procedural mucosa of the scene's size and seed.
  EXPECT_EQ(scene.tissue_source, "procedural");
  EXPECT_EQ(scene.tissue.width, 80);
  EXPECT_EQ(scene.tissue.height, 60);
  EXPECT_EQ(scene.tissue.rgba, procedural_tissue(80, 60, 42).rgba);
}

TEST(ScenarioParse, RecordsWhereEachKeyWasWritten) {
  const Scenario scenario = parse_scenario(kFull, kPath);
  const auto expect_line = [&](const std::string& key, int line) {
    const SourcePlace place = scenario.place_of(key);
    EXPECT_EQ(place.file, kPath) << key;
    EXPECT_EQ(place.line, line) << key;
  };
  expect_line("scene", 2);
  expect_line("scene.width_px", 4);
  expect_line("scene.seed", 10);
  expect_line("spread.growth_per_s", 14);
  expect_line("cut[1]", 20);
  expect_line("cut[1].start_s", 23);
  expect_line("output.fields", 32);
  // A place points at the value, after `key = `.
  EXPECT_EQ(scenario.place_of("scene.width_px").column, 12);
  EXPECT_EQ(scenario.place_of("output.dir").column, 7);
  // A key the file does not write is placed at the file as a whole.
  expect_line("tissue.texture", 0);
}

TEST(ScenarioParse, FillsInDefaultsWhenOptionalTablesAreAbsent) {
  const std::string text =
      "[scene]\n"
      "width_px = 32\n"
      "height_px = 24\n"
      "width_mm = 8.0\n"
      "height_mm = 6.0\n"
      "duration_s = 1.0\n"
      "[[cut]]\n"
      "x_mm = 4.0\n"
      "y_mm = 3.0\n";
  const Scenario scenario = parse_scenario(text, "some/folder/minimal-probe.toml");
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.name, "minimal-probe");  // the file's stem
  EXPECT_EQ(scene.frame_rate_hz, 30.0);
  EXPECT_EQ(scene.frame_count(), 30);
  EXPECT_EQ(scene.seed, 0u);
  EXPECT_FALSE(scene.effects.has<SpreadParams>());  // no effect declared, so none is run
  EXPECT_FALSE(scene.effects.has<ParticleParams>());
  EXPECT_FALSE(scene.effects.has<BlurParams>());
  EXPECT_EQ(scenario.output.dir, "out/minimal-probe");
  EXPECT_TRUE(scenario.output.hdf5);
  EXPECT_EQ(scenario.output.png_every, 0);
  EXPECT_EQ(scenario.output.deflate_level, 4);
  EXPECT_TRUE(scenario.output.fields.empty());
  EXPECT_EQ(scene.tissue_source, "procedural");
  // A cut that gives no size takes SpreadParams' own defaults when there is no [spread].
  ASSERT_EQ(scene.cuts.size(), 1u);
  EXPECT_EQ(scene.cuts[0].start_s, 0.0);
  EXPECT_EQ(scene.cuts[0].radius_mm, SpreadParams{}.radius_mm);
  EXPECT_EQ(scene.cuts[0].growth_per_s, SpreadParams{}.growth_per_s);
}

TEST(ScenarioParse, AcceptsTheBaseTextThatTheBadInputTestsBreak) {
  // The bad-input tests trust kBase to be valid and kEnd to follow its last line.
  ASSERT_EQ(int(lines_of(kBase).size()), kEnd - 1);
  const Scenario scenario = parse_scenario(kBase, kPath);
  const Scene& scene = scenario.scene;
  EXPECT_EQ(scene.name, "x");
  EXPECT_EQ(scene.cuts.size(), 2u);
  // Text appended to kBase lands in [output].
  EXPECT_EQ(parse_scenario(kBase + "deflate = 7\n", kPath).output.deflate_level, 7);
}

TEST(ScenarioParse, ResolvesATextureRelativeToTheScenarioFolder) {
  const ScratchFolder scratch;
  fs::create_directories(scratch.path() / "textures");
  write_small_png(scratch.path() / "textures" / "tex.png");
  const std::string scenario = (scratch.path() / "scenes" / "textured.toml").string();
  const Scene scene =
      parse_scenario(kBase + "[tissue]\ntexture = \"../textures/tex.png\"\n", scenario).scene;
  EXPECT_EQ(scene.tissue_source, (scratch.path() / "textures" / "tex.png").lexically_normal().string());
  // Resampled from 2 × 2 to the panel.
  EXPECT_EQ(scene.tissue.width, 64);
  EXPECT_EQ(scene.tissue.height, 48);
  EXPECT_EQ(scene.tissue.rgba.size(), std::size_t{64} * 48 * 4);
}

// ---- Bad input: each names the file, the line, the key and what is wrong ----------------------

TEST(ScenarioBadInput, TomlSyntaxErrorIsPlacedAtItsLine) {
  EXPECT_TRUE(refused_at(with_line(kBase, 8, "[spread"), 8, "", "expected ']'"));
}

TEST(ScenarioBadInput, UnknownKeySuggestsTheNearestKnownOne) {
  EXPECT_TRUE(refused_at(with_line(kBase, 3, "hieght_px = 48"), 3, "scene.hieght_px",
                         "unknown key; did you mean 'height_px'?"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "raduis_mm = 2.0"), 16, "cut[1].raduis_mm",
                         "did you mean 'radius_mm'?"));
}

TEST(ScenarioBadInput, UnknownKeyFarFromAnyListsTheKnownOnes) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "colour = \"red\""), 7, "scene.colour",
                         "unknown key (known here: name width_px height_px width_mm height_mm "
                         "duration_s frame_rate_hz seed)"));
}

TEST(ScenarioBadInput, UnknownTopLevelTable) {
  // Every table the reader knows, in scenario_tables()'s order: the list of effects among them.
  std::string known;
  for (const TableView& table : scenario_tables()) known += " " + table.name;
  EXPECT_TRUE(
      refused_at(kBase + "[lighting]\nlamps = 3\n", kEnd, "lighting", "unknown table (known here:" + known + ")"));
  EXPECT_TRUE(refused_at(kBase + "[sprad]\n", kEnd, "sprad", "unknown table; did you mean 'spread'?"));
  EXPECT_TRUE(refused_at(kBase + "[particle]\n", kEnd, "particle", "unknown table; did you mean 'particles'?"));
  EXPECT_TRUE(refused_at(kBase + "[blurr]\n", kEnd, "blurr", "unknown table; did you mean 'blur'?"));
}

TEST(ScenarioBadInput, StringForAnInteger) {
  EXPECT_TRUE(refused_at(with_line(kBase, 2, "width_px = \"wide\""), 2, "scene.width_px",
                         "expected an integer, got a string"));
}

TEST(ScenarioBadInput, FloatForAnInteger) {
  EXPECT_TRUE(refused_at(with_line(kBase, 2, "width_px = 64.0"), 2, "scene.width_px",
                         "expected an integer, got a floating-point number"));
}

TEST(ScenarioBadInput, StringForANumber) {
  EXPECT_TRUE(refused_at(with_line(kBase, 4, "width_mm = \"16\""), 4, "scene.width_mm",
                         "expected a number, got a string"));
}

TEST(ScenarioBadInput, NumberForABoolean) {
  EXPECT_TRUE(refused_at(kBase + "hdf5 = 1\n", kEnd, "output.hdf5", "expected true or false, got an integer"));
}

TEST(ScenarioBadInput, ZeroOrNegativePixelSize) {
  EXPECT_TRUE(refused_at(with_line(kBase, 3, "height_px = 0"), 3, "scene.height_px",
                         "must be between 1 and 65535 (got 0)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 2, "width_px = -64"), 2, "scene.width_px",
                         "must be between 1 and 65535 (got -64)"));
}

TEST(ScenarioBadInput, ZeroOrNegativeMillimetreSize) {
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "height_mm = 0.0"), 5, "scene.height_mm",
                         "must be greater than 0 and at most 10000 (got 0)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 5, "height_mm = -12.0"), 5, "scene.height_mm",
                         "must be greater than 0 and at most 10000 (got -12)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 16, "radius_mm = 0"), 16, "cut[1].radius_mm",
                         "must be greater than 0"));
  EXPECT_TRUE(refused_at(with_line(kBase, 9, "radius_mm = -1.0"), 9, "spread.radius_mm",
                         "must be greater than 0"));
}

TEST(ScenarioBadInput, SizesAboveTheirLimits) {
  EXPECT_TRUE(refused_at(with_line(kBase, 2, "width_px = 65536"), 2, "scene.width_px",
                         "must be between 1 and 65535 (got 65536)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 4, "width_mm = 10000.5"), 4, "scene.width_mm",
                         "at most 10000 (got 10000.5)"));
}

TEST(ScenarioBadInput, FrameRateOfZero) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "frame_rate_hz = 0"), 7, "scene.frame_rate_hz",
                         "must be greater than 0 and at most 1000 (got 0)"));
}

TEST(ScenarioBadInput, DeflateLevelAboveNine) {
  EXPECT_TRUE(refused_at(kBase + "deflate = 10\n", kEnd, "output.deflate", "must be between 0 and 9 (got 10)"));
}

TEST(ScenarioBadInput, NegativePngEvery) {
  EXPECT_TRUE(refused_at(with_line(kBase, 18, "png_every = -1"), 18, "output.png_every",
                         "must be between 0 and 1000000 (got -1)"));
}

TEST(ScenarioBadInput, CutOutsideThePanel) {
  EXPECT_TRUE(refused_at(with_line(kBase, 11, "x_mm = 16.5"), 11, "cut[0].x_mm",
                         "must be between 0 and 16 (got 16.5)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 15, "y_mm = -0.5"), 15, "cut[1].y_mm",
                         "must be between 0 and 12 (got -0.5)"));
}

TEST(ScenarioBadInput, NegativeSeed) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "seed = -1"), 7, "scene.seed",
                         "must be between 0 and 9223372036854775807 (got -1)"));
}

TEST(ScenarioBadInput, NanOrInfinity) {
  EXPECT_TRUE(refused_at(with_line(kBase, 4, "width_mm = nan"), 4, "scene.width_mm",
                         "must be a finite number (got nan)"));
  EXPECT_TRUE(refused_at(with_line(kBase, 9, "radius_mm = inf"), 9, "spread.radius_mm",
                         "must be a finite number (got inf)"));
}

TEST(ScenarioBadInput, MissingRequiredKeyIsPlacedAtItsTable) {
  EXPECT_TRUE(refused_at(without_lines(kBase, 4, 4), 1, "scene.width_mm", "missing (required)"));
  EXPECT_TRUE(refused_at(without_lines(kBase, 15, 15), 13, "cut[1].y_mm", "missing (required)"));
}

TEST(ScenarioBadInput, MissingSceneTableNamesTheFile) {
  EXPECT_TRUE(refused_at("[spread]\nradius_mm = 4.0\n", 0, "scene", "missing the [scene] table (required)"));
}

TEST(ScenarioBadInput, SceneNameWithCharactersAFolderNameShouldNotHave) {
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "name = \"my scene\""), 7, "scene.name",
                         "'my scene' must start with a letter or digit and hold only letters, digits, '.', '_' and '-'"));
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "name = \"../up\""), 7, "scene.name", "'../up' must start with"));
  // "." and ".." are made of allowed characters but would name the output folder's parent.
  EXPECT_TRUE(refused_at(with_line(kBase, 7, "name = \"..\""), 7, "scene.name", "'..' must start with"));
}

TEST(ScenarioParse, NamesAnUnnamedSceneAfterItsFileWithUnsafeCharactersReplaced) {
  EXPECT_EQ(parse_scenario(kBase, "scenarios/my scene.toml").scene.name, "my-scene");
  EXPECT_EQ(parse_scenario(kBase, "scenarios/..toml").scene.name, "scene.");
}

TEST(ScenarioParse, TakesAnEmptyCutListAsNoCuts) {
  EXPECT_TRUE(parse_scenario(without_lines(kBase, 10, 16), kPath).scene.cuts.empty());
  // A top-level key must come before the first table header.
  const std::string empty_list = "cut = []\n" + without_lines(kBase, 10, 16);
  EXPECT_TRUE(parse_scenario(empty_list, kPath).scene.cuts.empty());
}

TEST(ScenarioBadInput, ValueJustOutOfRangeIsPrintedInFullNotRoundedIntoRange) {
  EXPECT_TRUE(refused_at(with_line(kBase, 11, "x_mm = 16.0000001"), 11, "cut[0].x_mm",
                         "must be between 0 and 16 (got 16.0000001)"));
}

TEST(ScenarioBadInput, DurationThatGivesNoFrames) {
  EXPECT_TRUE(refused_at(with_line(kBase, 6, "duration_s = 0.01"), 6, "scene.duration_s",
                         "gives 0 frames at 30 Hz; a run needs between 1 and 10000000"));
}

TEST(ScenarioBadInput, DurationThatGivesTooManyFrames) {
  EXPECT_TRUE(refused_at(with_line(with_line(kBase, 7, "frame_rate_hz = 1000"), 6, "duration_s = 86400"), 6,
                         "scene.duration_s", "gives 86400000 frames at 1000 Hz"));
}

TEST(ScenarioBadInput, CutWrittenAsASingleTable) {
  EXPECT_TRUE(refused_at(with_line(without_lines(kBase, 13, 16), 10, "[cut]"), 10, "cut",
                         "expected [[cut]] tables, got a table"));
}

TEST(ScenarioBadInput, OutputFieldWithAnUnknownName) {
  EXPECT_TRUE(refused_at(kBase + "fields = [\n  \"spread/stain\",\n  \"spread/blood\",\n]\n", kEnd + 2,
                         "output.fields[1]",
                         "unknown field 'spread/blood' (known: surface/frame, surface/gravity, spread/stain, particles/position, particles/velocity, particles/age, "
                         "particles/rest, particles/anchor, particles/accounting, splat/thickness, blur/thickness, trail/residue; the frame is always written)"));
}

TEST(ScenarioBadInput, OutputFieldOfAnEffectTheSceneDoesNotDeclare) {
  EXPECT_TRUE(refused_at(without_lines(kBase, 8, 9) + "fields = [\"spread/stain\"]\n", kEnd,
                         "output.fields[0]",
                         "'spread/stain' needs the [spread] effect, which this scene does not declare"));
}

TEST(ScenarioBadInput, AViewWithoutATissueMesh) {
  EXPECT_TRUE(refused_at(kBase + "[view]\neye_mm = [0, 0, 130]\nlook_at_mm = [0, 0, 100]\n", kEnd, "view",
                         "draws the tissue mesh from an endoscope; this scene has no tissue.mesh"));
}

TEST(ScenarioBadInput, OutputFieldOfTheSurfaceWithoutATissueMesh) {
  EXPECT_TRUE(refused_at(kBase + "fields = [\"surface/frame\"]\n", kEnd, "output.fields[0]",
                         "'surface/frame' needs a tissue mesh (tissue.mesh), which this scene does not have"));
}

TEST(ScenarioBadInput, OutputFieldListedTwice) {
  EXPECT_TRUE(refused_at(kBase + "fields = [\n  \"spread/stain\",\n  \"spread/stain\",\n]\n", kEnd + 2,
                         "output.fields[1]", "'spread/stain' is listed twice"));
}

TEST(ScenarioBadInput, EmptyOutputDir) {
  EXPECT_TRUE(refused_at(kBase + "dir = \"\"\n", kEnd, "output.dir", "must not be empty"));
}

// Issue 13, item 3: a path the file system cannot hold is refused by validate, at its key.
TEST(ScenarioBadInput, OutputDirWithANameTooLongForAFileSystem) {
  EXPECT_TRUE(refused_at(kBase + "dir = \"out/" + std::string(256, 'x') + "\"\n", kEnd, "output.dir",
                         "holds a name of 256 characters; a file system holds at most 255"));
  EXPECT_NO_THROW(parse_scenario(kBase + "dir = \"out/" + std::string(255, 'x') + "\"\n", kPath));
}

// A letter outside a string that toml++ 3.3.0 took into __builtin_unreachable() (core/io/toml.h):
// it is refused as a syntax error, with its place (the sanitizer build stops on the old behaviour).
TEST(ScenarioBadInput, NonAsciiCharactersOutsideStringsAreSyntaxErrors) {
  for (const std::string& text : {kBase + "a = 1\xc3\xa9\n", kBase + "a\xc2\xb5 = 1\n", kBase + "\xc3\xa9\n"}) {
    try {
      parse_scenario(text, kPath);
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, kEnd) << e.what();
      EXPECT_EQ(e.key(), "") << e.what();
    }
  }
}

TEST(ScenarioBadInput, MissingTexture) {
  const ScratchFolder scratch;
  const std::string texture = (scratch.path() / "nowhere.png").string();
  EXPECT_TRUE(refused_at(kBase + "[tissue]\ntexture = \"" + texture + "\"\n", kEnd + 1, "tissue.texture",
                         "cannot read texture '" + texture + "': " + std::strerror(ENOENT)));
}

TEST(ScenarioBadInput, TextureThatIsNotAPng) {
  const ScratchFolder scratch;
  const fs::path texture = scratch.path() / "notes.png";
  write_text(texture, "these are notes, not pixels\n");
  EXPECT_TRUE(refused_at(kBase + "[tissue]\ntexture = \"" + texture.string() + "\"\n", kEnd + 1,
                         "tissue.texture", "cannot decode texture '" + texture.string() + "' as a PNG"));
}

// ---- load_scenario: the file itself -----------------------------------------------------------

TEST(LoadScenario, RefusesAMissingFileWithTheSystemsReason) {
  const ScratchFolder scratch;
  const std::string path = (scratch.path() / "nowhere.toml").string();
  try {
    load_scenario(path);
    FAIL() << "loaded a file that does not exist";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot read scenario file: " + std::strerror(ENOENT));
  }
}

TEST(LoadScenario, RefusesAFolder) {
  const ScratchFolder scratch;
  try {
    load_scenario(scratch.path().string());
    FAIL() << "loaded a folder";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              scratch.path().string() + ": cannot read scenario file: it is a directory, not a regular file");
  }
}

TEST(LoadScenario, PlacesErrorsInTheFileItRead) {
  const ScratchFolder scratch;
  const fs::path file = scratch.path() / "bad.toml";
  write_text(file, with_line(kBase, 3, "height_px = 0"));
  try {
    load_scenario(file.string());
    FAIL() << "loaded a bad scenario";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ":3:", 0), 0u) << e.what();
  }
}

TEST(LoadScenario, LoadsEveryScenarioInTheRepository) {
  const fs::path root = fs::path(test::source_dir()) / "scenarios";
  int loaded = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    try {
      const Scenario scenario = load_scenario(entry.path().string());
  const Scene& scene = scenario.scene;
      EXPECT_EQ(scene.tissue.width, scene.domain.width_px);
      EXPECT_EQ(scene.tissue.height, scene.domain.height_px);
      EXPECT_FALSE(scene.tissue.rgba.empty());
      EXPECT_EQ(scene.tissue.rgba.size(), scene.domain.pixels().to<std::size_t>() * 4);
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
    }
    ++loaded;
  }
  // default, tissue-only and the three golden scenes at the time of writing.
  EXPECT_GE(loaded, 5);
}

}  // namespace
}  // namespace bleedsim