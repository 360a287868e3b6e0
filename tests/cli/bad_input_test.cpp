// Bad input is a feature: each kind gives a message naming the file, line and key, exit code 2,
// and leaves no output behind.
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

// A valid scenario with one line replaced or added; `line` 0 appends.
std::string scenario_with(const std::string& replace, const std::string& by) {
  std::string text =
      "[scene]\n"              // line 1
      "width_px = 64\n"        // 2
      "height_px = 48\n"       // 3
      "width_mm = 16.0\n"      // 4
      "height_mm = 12.0\n"     // 5
      "duration_s = 0.2\n"     // 6
      "[spread]\n"             // 7
      "[[cut]]\n"              // 8
      "x_mm = 8.0\n"           // 9
      "y_mm = 6.0\n";          // 10
  if (!replace.empty()) {
    const std::size_t at = text.find(replace);
    EXPECT_NE(at, std::string::npos) << replace;
    text.replace(at, replace.size(), by);
  } else {
    text += by;
  }
  return text;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = scratch_folder();
    out_ = dir_ / "out";
  }
  // Runs `bleedsim run` on the text; expects exit 2, each of `expected` in the message, no output.
  void expect_refused(const std::string& text, const std::vector<std::string>& expected,
                      const std::string& extra_arguments = "", const std::string& shell_prefix = "") {
    const fs::path file = dir_ / "bad.toml";
    write_text(file, text);
    expect_cli_refused("run '" + file.string() + "' --backend cpu --png-every 1 --out '" + out_.string() +
                           "' " + extra_arguments,
                       expected, shell_prefix);
  }
  void expect_cli_refused(const std::string& arguments, const std::vector<std::string>& expected,
                          const std::string& shell_prefix = "") {
    const CliResult result = run_cli(arguments, shell_prefix);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    for (const std::string& part : expected)
      EXPECT_NE(result.output.find(part), std::string::npos) << "missing '" << part << "' in: " << result.output;
    EXPECT_FALSE(fs::exists(out_)) << "bad input left " << out_;
  }
  fs::path dir_, out_;
};

TEST_F(BadInput, MissingScenarioFile) {
  expect_cli_refused("run '" + (dir_ / "nowhere.toml").string() + "' --out '" + out_.string() + "'",
                     {"nowhere.toml", "cannot read scenario file", "No such file"});
}

TEST_F(BadInput, MalformedToml) {
  expect_refused(scenario_with("[spread]", "[spread"), {"bad.toml:7:"});
}

TEST_F(BadInput, UnknownKey) {
  expect_refused(scenario_with("height_px = 48", "hieght_px = 48"),
                 {"bad.toml:3:", "scene.hieght_px", "unknown", "height_px"});
}

// Issue 38, item 16: a scenario written before keys were renamed failed at one old key a try, in
// alphabetical order, never naming what replaced it. Every unknown key is named in one message, in
// file order, each at its line and column with its key path; a former key says what became of it.
TEST_F(BadInput, EveryUnknownKeyIsNamedAtOnceInFileOrderAndAFormerKeySaysWhatBecameOfIt) {
  std::string text = scenario_with("y_mm = 6.0\n", "y_mm = 6.0\n"   // 10
                                                   "rate_per_s = 300\n"        // 11
                                                   "[particles]\n"             // 12
                                                   "rate_per_s = 500\n"        // 13
                                                   "damping_per_s = 100\n"     // 14
                                                   "max_per_cell = 8\n"        // 15
                                                   "stiffness_per_s2 = 4e5\n"  // 16
                                                   "volume_mm3_per_s = 2\n"    // 17
                                                   "[lightning]\n"             // 18
                                                   "bolts = 3\n");             // 19
  text.replace(text.find("height_px = 48"), 14, "hieght_px = 48");  // 3
  // Each after the first on a line of its own, at its place.
  const std::string file = (dir_ / "bad.toml").string(), line = "\n  " + file;
  const std::vector<std::string> expected = {
      file + ":3:1: scene.hieght_px: unknown key; did you mean 'height_px'? (and 7 more below)",
      line + ":11:1: cut[0].rate_per_s: unknown key: replaced by cut[0].flow_mm3_per_s_per_mm (2026-11-25, issue 12): ",
      line + ":13:1: particles.rate_per_s: unknown key: replaced by particles.flow_mm3_per_s_per_mm (2026-11-25, "
             "issue 12): ",
      line + ":14:1: particles.damping_per_s: unknown key: replaced by particles.damping_ratio (2026-11-25, issue 12): ",
      line + ":15:1: particles.max_per_cell: unknown key: removed (2026-11-25, issue 12): ",
      line + ":16:1: particles.stiffness_per_s2: unknown key: replaced by particles.compression (2026-11-25, issue 12): ",
      line + ":17:1: particles.volume_mm3_per_s: unknown key: replaced by particles.flow_mm3_per_s_per_mm (2026-11-25, "
             "issue 12): ",
      line + ":18:2: lightning: unknown table"};
  expect_refused(text, expected);
  // In file order: each after the one before it.
  const CliResult result = run_cli("validate '" + file + "'");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  std::size_t at = 0;
  for (const std::string& part : expected) {
    const std::size_t found = result.output.find(part, at);
    EXPECT_NE(found, std::string::npos) << "'" << part << "' not after the one before it in: " << result.output;
    if (found != std::string::npos) at = found + part.size();
  }
  EXPECT_EQ(result.output.find("bolts"), std::string::npos) << "an unknown table's keys are its own business";
}

TEST_F(BadInput, WrongType) {
  expect_refused(scenario_with("width_px = 64", "width_px = \"wide\""), {"bad.toml:2:", "scene.width_px", "integer"});
}

TEST_F(BadInput, NegativeSize) {
  expect_refused(scenario_with("width_mm = 16.0", "width_mm = -16.0"), {"bad.toml:4:", "scene.width_mm", "-16"});
}

TEST_F(BadInput, ZeroSize) {
  expect_refused(scenario_with("height_px = 48", "height_px = 0"), {"bad.toml:3:", "scene.height_px", "got 0"});
}

TEST_F(BadInput, SizeTooLargeForMemory) {
  BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED();
  // 40000 x 40000 px needs tens of GiB; the address space is capped at 4 GB so the test means the
  // same on every machine.
  expect_refused(scenario_with("width_px = 64\nheight_px = 48", "width_px = 40000\nheight_px = 40000"),
                 {"bad.toml:2:", "scene.width_px", "memory"}, "", "ulimit -v 4000000;");
}

TEST_F(BadInput, MissingTissuePng) {
  expect_refused(scenario_with("", "[tissue]\ntexture = \"no-such.png\"\n"),
                 {"bad.toml:12:", "tissue.texture", "no-such.png"});
}

TEST_F(BadInput, TissueFileThatIsNotAPng) {
  write_text(dir_ / "junk.png", "this is not a PNG");
  expect_refused(scenario_with("", "[tissue]\ntexture = \"junk.png\"\n"), {"bad.toml:12:", "tissue.texture", "junk.png"});
}

// A tissue mesh: a missing file, and each kind of bad mesh, exits 2 naming the scenario's key or the
// mesh file and its face (docs/mesh.md lists the checks; tests/io/mesh_obj_test.cpp has every kind).
TEST_F(BadInput, ABadTissueMeshNamesItsFileAndTheProblem) {
  const std::string square = "v 0 0 0\nv 16 0 0\nv 16 -12 0\nv 0 -12 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  expect_refused(scenario_with("", "[tissue]\nmesh = \"no-such.obj\"\n"),
                 {"bad.toml:12:8: tissue.mesh: cannot read", "no-such.obj"});
  write_text(dir_ / "no-uv.obj", "v 0 0 0\nv 16 0 0\nv 16 -12 0\nf 1 2 3\n");
  expect_refused(scenario_with("", "[tissue]\nmesh = \"no-uv.obj\"\n"), {"no-uv.obj", "face 1", "texture coordinate"});
  write_text(dir_ / "flat.obj", square + "f 1/1 2/2 2/2\n");
  expect_refused(scenario_with("", "[tissue]\nmesh = \"flat.obj\"\n"), {"flat.obj", "face 1", "no area"});
  write_text(dir_ / "fan.obj", square + "v 8 -6 5\nf 1/1 3/3 2/2\nf 1/1 3/3 4/4\nf 1/1 3/3 5/2\n");
  expect_refused(scenario_with("", "[tissue]\nmesh = \"fan.obj\"\n"), {"fan.obj", "borders 3 faces", "non-manifold"});
}

// Millions of triangles past the reader's budget (4,194,304, core/io/mesh_obj.h) are refused by
// their count, before tinyobjloader holds them: one polygon of 4,194,307 corners would be cut into 4,194,305.
TEST_F(BadInput, AMeshOfMillionsOfTrianglesPastTheBudget) {
  std::string huge = "v 0 0 0\nv 16 0 0\nv 16 -12 0\nvt 0 0\nvt 1 0\nvt 1 1\nf";
  huge.reserve(huge.size() + 4 * 4194307 + 1);
  for (int corner = 0; corner < 4194307; ++corner) huge += " 1/1";
  write_text(dir_ / "huge.obj", huge + "\n");
  expect_refused(scenario_with("", "[tissue]\nmesh = \"huge.obj\"\n"),
                 {"huge.obj", "tissue.mesh", "the mesh has 4194305 triangles, more than the 4194304 a mesh may have"});
}

// Issue 38, item 11: validate passed a mesh whose uvs (0 to 0.01) hold no texel's centre, and run
// then failed (exit 1) with "the mesh covers no texel" and no key; a mesh whose texture a panel mm
// stretches over a kilometre of (its uvs spanning 1e-9, or its coordinates 1e12) made validate
// fail with a narrowing "its limit check should have stopped". Both commands now refuse what a run
// cannot use, at tissue.mesh, naming the mesh file.
TEST_F(BadInput, AMeshARunCannotUseIsRefusedByValidateAsByRun) {
  const auto mesh_with = [](const std::string& size, const std::string& uv) {
    return "v 0 0 0\nv " + size + " 0 0\nv " + size + " -" + size + " 0\nv 0 -" + size + " 0\nvt 0 0\nvt " + uv +
           " 0\nvt " + uv + " " + uv + "\nvt 0 " + uv + "\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  };
  const fs::path file = dir_ / "bad.toml";
  const auto expect_both_refuse = [&](const std::string& mesh, const std::string& scene_tail,
                                      const std::vector<std::string>& expected) {
    SCOPED_TRACE(mesh);
    write_text(file, scenario_with("", "[tissue]\nmesh = \"" + mesh + "\"\nmesh_scale = " + scene_tail));
    const CliResult validate = run_cli("validate '" + file.string() + "'");
    EXPECT_EQ(validate.exit_code, 2) << validate.output;
    for (const std::string& part : expected)
      EXPECT_NE(validate.output.find(part), std::string::npos) << "missing '" << part << "' in: " << validate.output;
    expect_refused(read_bytes(file), expected);
  };
  // The 64 x 48 texels' first centres are at u = 0.5/64 and v = 0.5/48 = 0.0104: a uv square of 0.01
  // holds none, and of 1e-9 neither.
  write_text(dir_ / "small-uv.obj", mesh_with("12", "0.01"));
  expect_both_refuse("small-uv.obj", "1\n",
                     {"bad.toml:12:8: tissue.mesh: ", "small-uv.obj covers no texel of the 64 × 48 texture"});
  write_text(dir_ / "tiny-uv.obj", mesh_with("12", "1e-9"));
  expect_both_refuse("tiny-uv.obj", "1\n[particles]\n",
                     {"bad.toml:12:8: tissue.mesh: ", "tiny-uv.obj covers no texel of the 64 × 48 texture"});
  // A 1e6 mm square (the most a mesh's numbers may be) scaled 1000 times over the 16 x 12 mm panel:
  // a panel mm is at least 6.25e7 mm of its surface (1e9 mm over 16), past the 1000 a mesh may stretch.
  write_text(dir_ / "huge.obj", mesh_with("1e6", "1"));
  expect_both_refuse("huge.obj", "1000\n[particles]\n",
                     {"bad.toml:12:8: tissue.mesh: ",
                      "huge.obj stretches the texture: a panel mm is at least 6.25e+07 mm of its surface, past the 1000"});
  // Coordinates of 1e12 are refused as the mesh file is read.
  write_text(dir_ / "far.obj", mesh_with("1e12", "1"));
  expect_both_refuse("far.obj", "1\n[particles]\n",
                     {"far.obj:2: tissue.mesh: vertex 2's x is '1e12', beyond ±1e6"});
}

TEST_F(BadInput, AMeshsPlacementWithoutAMeshOrThePanelsPlacementWithOne) {
  expect_refused(scenario_with("", "[tissue]\nmesh_scale = 2\n"),
                 {"bad.toml:12:", "tissue.mesh_scale: places a tissue mesh, and this scene names none"});
  expect_refused(scenario_with("", "[tissue]\nmesh_position_mm = [0, 0]\n"),
                 {"bad.toml:12:", "tissue.mesh_position_mm", "expected [x, y, z], three numbers, got an array of 2"});
  write_text(dir_ / "panel.obj", "v 0 0 0\nv 16 0 0\nv 16 -12 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
  const std::string trace = source_dir() + "/scenarios/traces/single-stroke.csv";
  expect_refused(scenario_with("", "[haptics]\ntrace = \"" + trace + "\"\nsurface_z_mm = 100\n[tissue]\nmesh = \"panel.obj\"\n"),
                 {"bad.toml:13:", "haptics.surface_z_mm: places the flat panel under the stylus"});
  expect_refused(scenario_with("", "[tissue]\nmesh = \"panel.obj\"\n[view]\neye_mm = [0, 0, 100]\nlook_at_mm = [0, 0, 50]\n"
                                   "up = [0, 0, 1]\n"),
                 {"bad.toml:15:14: view.look_at_mm: view camera: up [0, 0, 1] is parallel to the view direction [0, 0, -1]"});
  expect_refused(scenario_with("", "[particles]\n[[tip]]\nt_s = 0\nx_mm = 1\ny_mm = 1\n[[tip]]\nt_s = 1\nx_mm = 2\n"
                                   "y_mm = 1\n[suction]\n[tissue]\nmesh = \"panel.obj\"\n"),
                 {"bad.toml:20:1: suction: the instrument's suction acts on the flat panel only"});
}

TEST_F(BadInput, ParticleSubStepPastTheStabilityLimit) {
  // 10 sub-steps at 30 Hz are 3.333 ms, far past the default contact's limit on this 16 × 12 mm
  // panel (tests/io/scenario_effects_test.cpp derives it: 0.1491 ms, 224 sub-steps at least).
  expect_refused(scenario_with("", "[particles]\nsubsteps = 10\n"),
                 {"bad.toml:12:12: particles.substeps: a sub-step of 3.333 ms is past the contact's stability "
                  "limit of 0.1491 ms", "use at least 224 sub-steps per frame"});
}

TEST_F(BadInput, CutParticleRateInASceneWithoutParticles) {
  expect_refused(scenario_with("y_mm = 6.0\n", "y_mm = 6.0\nflow_mm3_per_s_per_mm = 2\n"),
                 {"bad.toml:11:25: cut[0].flow_mm3_per_s_per_mm: has no effect: this scene declares no [particles]"});
}

TEST_F(BadInput, SuctionWithoutAnInstrument) {
  expect_refused(scenario_with("", "[particles]\n[suction]\nradius_mm = 1.0\n"),
                 {"bad.toml:13:13: suction.radius_mm: has no instrument to act through"});
}

TEST_F(BadInput, SuctionThatCannotReachPastTheTip) {
  expect_refused(scenario_with("", "[particles]\n[[tip]]\nt_s = 0\nx_mm = 1\ny_mm = 1\n[[tip]]\nt_s = 1\nx_mm = 2\n"
                                   "y_mm = 1\n[contact]\ntip_radius_mm = 2.0\n[suction]\nradius_mm = 1.5\n"),
                 {"bad.toml:23:13: suction.radius_mm: must be larger than contact.tip_radius_mm"});
}

TEST_F(BadInput, UnwritableOutputPathFromTheCommandLine) {
  write_text(dir_ / "a-file", "");
  out_ = dir_ / "a-file" / "out";
  expect_refused(scenario_with("", ""), {"--out", "cannot create output folder", "a-file"});
}

TEST_F(BadInput, UnwritableOutputPathFromTheScenario) {
  write_text(dir_ / "a-file", "");
  const fs::path file = dir_ / "bad.toml";
  write_text(file, scenario_with("", "[output]\ndir = \"" + (dir_ / "a-file" / "out").string() + "\"\n"));
  const CliResult result = run_cli("run '" + file.string() + "' --backend cpu");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("bad.toml:12:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("output.dir"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "a-file" / "out"));
}

// Issue 13, item 3: a folder name too long for the file system exited 2 and left the parent folder
// it had made on the way.
TEST_F(BadInput, AnOutputPathTooLongLeavesNoFolderItMadeBehind) {
  out_ = dir_ / "newparent" / std::string(300, 'b');
  expect_refused(scenario_with("", ""),
                 {"--out: the folder name '" + std::string(40, 'b') + "...' is 300 characters long; a name may be "
                  "at most 255 (NAME_MAX)"});
  EXPECT_FALSE(fs::exists(dir_ / "newparent"));
}

// Issue 38, item 14: an --out of 4,056 characters passed the checks, then the run failed with "File
// name too long" at view_contact_sheet.png, leaving 17 folders and a finished frames.h5 stranded in
// .bleedsim-partial/. The path is checked against PATH_MAX with the longest path a run (or a study)
// makes in the folder, before anything is made.
TEST_F(BadInput, AnOutputPathWithNoRoomForTheFilesInItIsRefusedBeforeAnythingIsMade) {
  // A folder path of `length` characters: names of 100 under newparent/, then one to make up the rest.
  const auto deep_folder = [&](std::size_t length) {
    fs::path path = dir_ / "newparent";
    while (path.string().size() < length - 101) path /= std::string(100, 'd');
    return path / std::string(length - path.string().size() - 1, 'e');
  };
  const auto refusal = [](std::size_t length) {
    return "--out: the output folder's path is " + std::to_string(length) +
           " characters long; with the longest path written in it";
  };
  out_ = deep_folder(4056);
  ASSERT_EQ(out_.string().size(), 4056u);
  expect_refused(scenario_with("", ""), {refusal(4056), "(PATH_MAX 4096)"}, "--contact-sheet 2");
  // A study's longest path, .bleedsim-partial/plots/.distributions.png.tmp, is 2 characters longer
  // than a run's.
  out_ = deep_folder(4080);
  expect_cli_refused("study '" + (dir_ / "bad.toml").string() + "' --backend cpu --knob resolution=0.5,1 --no-plots --out '" +
                         out_.string() + "'",
                     {refusal(4080), "(PATH_MAX 4096)"});
  EXPECT_FALSE(fs::exists(dir_ / "newparent"));
}

// Issue 13, item 3: a scene name too long to name a folder passed validate, then run exited 2
// naming output.dir (which the file did not write), with no line, and left out/ behind.
TEST_F(BadInput, ASceneNameTooLongForAFolderIsRefusedAtItsKey) {
  const std::string text = "[scene]\nname = \"" + std::string(300, 'a') + "\"\n" + scenario_with("[scene]\n", "");
  const fs::path file = dir_ / "bad.toml";
  write_text(file, text);
  const std::string message = "bad.toml:2:8: scene.name: is 300 characters long; a folder's name may be at most 255";
  const CliResult validate = run_cli("validate '" + file.string() + "'");
  EXPECT_EQ(validate.exit_code, 2) << validate.output;
  EXPECT_NE(validate.output.find(message), std::string::npos) << validate.output;
  const CliResult run = run_shell("cd '" + dir_.string() + "' && '" + cli_path() + "' run bad.toml --backend cpu");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// The folder a scene's name makes, out/<name>, is named by scene.name when it cannot be made.
TEST_F(BadInput, ADefaultOutputFolderThatCannotBeMadeIsPlacedAtTheSceneName) {
  write_text(dir_ / "out", "a file where the folder out/ would go");
  const fs::path file = dir_ / "bad.toml";
  write_text(file, "[scene]\nname = \"blocked\"\n" + scenario_with("[scene]\n", ""));
  const CliResult run = run_shell("cd '" + dir_.string() + "' && '" + cli_path() + "' run bad.toml --backend cpu");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("bad.toml:2:8: scene.name: cannot "), std::string::npos) << run.output;
}

// Issue 38, item 6: a named pipe where bleedsim reads a file blocked it forever, validate too (opening
// a pipe waits for a writer); as a trace it was "no trace file", as a vessel map "Operation not
// supported" (item 15). Each input is looked at with stat() and refused unopened, named by its key and
// as what it is. `timeout` turns a hang into exit 124, a failure, rather than a test that never ends.
TEST_F(BadInput, ANamedPipeWhereverAFileIsNamedIsRefusedUnopened) {
  const fs::path pipe = dir_ / "pipe";
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  const std::string is_a_pipe = "'" + pipe.string() + "': it is a named pipe, not a regular file";
  const struct {
    const char* tables;
    const char* place;
    const char* key_and_what;
  } inputs[] = {{"[tissue]\ntexture = \"pipe\"\n", "bad.toml:12:11: ", "tissue.texture: cannot read texture "},
                {"[particles]\n[vessels]\nmap = \"pipe\"\n", "bad.toml:13:7: ", "vessels.map: cannot read vessel map "},
                {"[tissue]\nmesh = \"pipe\"\n", "bad.toml:12:8: ", "tissue.mesh: cannot read mesh file "},
                {"[haptics]\ntrace = \"pipe\"\n", "bad.toml:12:9: ", "haptics.trace: cannot read trace file "}};
  for (const auto& input : inputs) {
    const fs::path file = dir_ / "bad.toml";
    write_text(file, scenario_with("", input.tables));
    const std::string message = std::string(input.place) + input.key_and_what + is_a_pipe;
    expect_cli_refused("validate '" + file.string() + "'", {message}, "timeout 20");
    expect_cli_refused("run '" + file.string() + "' --backend cpu --out '" + out_.string() + "'", {message},
                       "timeout 20");
  }
  expect_cli_refused("validate '" + pipe.string() + "'",
                     {pipe.string() + ": cannot read scenario file: it is a named pipe, not a regular file"},
                     "timeout 20");
}

// Issue 38, items 6 and 15: a named pipe as a shard blocked `study merge` forever; /dev/null was "Is a
// directory".
TEST_F(BadInput, AShardThatIsNotARegularFileIsRefusedSayingWhatItIs) {
  const fs::path pipe = dir_ / "f.bleedshard";
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  const auto merge = [&](const std::string& shard) {
    return "study merge '" + shard + "' --no-plots --out '" + out_.string() + "'";
  };
  const std::string not_regular = ", not a regular file";
  const std::string cannot_read = ": cannot read shard file: it is ";
  expect_cli_refused(merge(pipe.string()), {pipe.string() + cannot_read + "a named pipe" + not_regular}, "timeout 20");
  expect_cli_refused(merge("/dev/null"), {"/dev/null" + cannot_read + "a character device" + not_regular});
  expect_cli_refused(merge(dir_.string()), {dir_.string() + cannot_read + "a directory" + not_regular});
}

// Issue 38, item 15: a vessel map's errors said "texture" throughout, and `map = ""` was "cannot read
// texture ''". They say "vessel map" and name vessels.map; an empty path says the key is empty.
TEST_F(BadInput, AVesselMapsErrorsNameTheVesselMapAndItsKey) {
  write_text(dir_ / "junk.png", "this is not a PNG");
  const auto map = [&](const std::string& name) {
    return scenario_with("", "[particles]\n[vessels]\nmap = \"" + name + "\"\n");
  };
  const struct {
    std::string name;
    std::string message;
  } cases[] = {
      {"", "bad.toml:13:7: vessels.map: is empty; it names the vessel map to read"},
      {"junk.png", "vessels.map: cannot decode vessel map '" + (dir_ / "junk.png").string() +
                       "' as a PNG: it does not start with a PNG signature and header"},
      {"nowhere.png", "vessels.map: cannot read vessel map '" + (dir_ / "nowhere.png").string() +
                          "': No such file or directory"},
      {"/dev/null", "vessels.map: cannot read vessel map '/dev/null': it is a character device, not a regular file"}};
  for (const auto& c : cases) {
    expect_refused(map(c.name), {c.message}, "", "timeout 20");
    const CliResult validate = run_cli("validate '" + (dir_ / "bad.toml").string() + "'", "timeout 20");
    EXPECT_EQ(validate.output.find("texture"), std::string::npos) << validate.output;
  }
}

// Issue 38, item 15: a trace read through a pipe "is empty" (its size was read by a first pass, and a
// pipe cannot be read twice). It is refused as what it is.
TEST_F(BadInput, ATraceThroughAPipeIsRefusedAsAPipeNotAsEmpty) {
  const std::string trace = source_dir() + "/scenarios/traces/single-stroke.csv";
  const CliResult result = run_shell("cat '" + trace + "' | timeout 20 '" + cli_path() + "' trace info /dev/stdin");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("/dev/stdin: cannot read trace file: it is a named pipe, not a regular file"),
            std::string::npos)
      << result.output;
}

TEST_F(BadInput, UnknownBackendOrNegativePngInterval) {
  const std::string file = (fs::path(source_dir()) / "scenarios/golden/spread-single.toml").string();
  expect_cli_refused("run '" + file + "' --backend gpu --out '" + out_.string() + "'", {"--backend", "gpu"});
  expect_cli_refused("run '" + file + "' --png-every -1 --out '" + out_.string() + "'", {"--png-every"});
}

TEST_F(BadInput, ValidateRefusesTooWithTheSameMessage) {
  const fs::path file = dir_ / "bad.toml";
  write_text(file, scenario_with("height_px = 48", "height_px = 0"));
  const CliResult result = run_cli("validate '" + file.string() + "'");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("bad.toml:3:"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace bleedsim::test
