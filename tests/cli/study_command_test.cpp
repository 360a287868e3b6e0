// bleedsim study as a user runs it, on a scene small enough for CI: the tables, the HDF5 file and
// the plots written; the same data again when run again (timings aside); bad options refused with
// exit 2 and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tests/cli/cli_harness.h"
#include "tests/cli/study_files.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

// Spread, particles and blur on a 32 × 24 px panel, 0.2 s (6 frames).
fs::path tiny_scene(const fs::path& folder) {
  write_text(folder / "tiny.toml",
             "[scene]\nname = \"tiny\"\nwidth_px = 32\nheight_px = 24\nwidth_mm = 8.0\nheight_mm = 6.0\n"
             "duration_s = 0.2\n[spread]\nradius_mm = 2.0\n[particles]\ncapacity = 1024\nflow_mm3_per_s_per_mm = 3.2\n"
             "[blur]\n[[cut]]\nx_mm = 4.0\ny_mm = 2.0\n");
  return folder / "tiny.toml";
}

std::string study_command(const fs::path& scene, const fs::path& out, const std::string& options) {
  return "study '" + scene.string() + "' --backend cpu --threads 2 " + options + " --out '" + out.string() + "'";
}

TEST(StudyCommand, WritesTheTablesTheDetailsAndThePlots) {
  const fs::path folder = scratch_folder();
  const fs::path out = folder / "study";
  const CliResult result = run_cli(study_command(tiny_scene(folder), out, "--knob resolution=0.5,1 --seeds 3"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("tiny: 4 settings x 3 seeds on 1 backend(s), 12 runs of 6 frames; reference: resolution 1; "
                               "compared on 16 x 12 cells at 6 snapshot frames"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("reference (resolution 1): "), std::string::npos) << result.output;
  const std::vector<std::string> csv = lines_of(read_bytes(out / "study.csv"));
  ASSERT_EQ(csv.size(), 6u) << read_bytes(out / "study.csv");  // header, reference, scene, 0.5, 2, noise floor
  EXPECT_EQ(csv[0].rfind("scene,knob,value,role,backend,status,seeds,film_l1_mm,film_l1_mm_lo,film_l1_mm_hi,", 0), 0u);
  EXPECT_NE(csv[0].find(",covered_area_mm2,covered_area_mm2_lo,covered_area_mm2_hi,covered_area_mm2_dist,"), std::string::npos);
  EXPECT_NE(csv[0].find(",check,time_ms_p50,time_ms_p99,time_ms_p50_lo,time_ms_p50_hi"), std::string::npos);
  EXPECT_EQ(csv[1].rfind("tiny,reference,,reference,cpu,ok,3,0,0,0,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[2].rfind("tiny,scene,,scene,cpu,ok,3,", 0), 0u) << csv[2];
  EXPECT_EQ(csv[3].rfind("tiny,resolution,0.5,ladder,cpu,ok,3,", 0), 0u) << csv[3];
  EXPECT_EQ(csv[4].rfind("tiny,resolution,2,refinement,cpu,ok,3,", 0), 0u) << csv[4];
  EXPECT_EQ(csv[5].rfind("tiny,reference,,noise_floor,,ok,3,", 0), 0u) << csv[5];
  for (const std::string& line : csv) EXPECT_EQ(fields_of(line).size(), fields_of(csv[0]).size()) << line;
  const std::vector<std::string> ladders = lines_of(read_bytes(out / "ladders.csv"));
  ASSERT_GT(ladders.size(), 1u);
  EXPECT_EQ(ladders[0].rfind("knob,metric,unit,level,value,role,status,mean,mean_lo,mean_hi,difference,", 0), 0u);
  EXPECT_EQ(ladders[1].rfind("resolution,film_mm,mm,0,0.5,ladder,ok,", 0), 0u) << ladders[1];
  for (const std::string& line : ladders) EXPECT_EQ(fields_of(line).size(), fields_of(ladders[0]).size()) << line;
  EXPECT_TRUE(fs::exists(out / "study.h5"));
  // The plots, where Debian's matplotlib is (scripts/setup installs it).
  if (run_shell("'" + python() + "' -c 'import matplotlib, h5py'").exit_code != 0)
    GTEST_SKIP() << "plots NOT checked: " << python() << " has no matplotlib or h5py";
  for (const char* plot : {"pareto.png", "resolution.png", "distributions.png"})
    EXPECT_TRUE(fs::exists(out / "plots" / plot)) << plot << "\n" << result.output;
}

TEST(StudyCommand, TwoRunsGiveTheSameDataTimingsAside) {
  // Everything but the time_* columns of study.csv and /timing in study.h5 is the same bytes.
  const fs::path folder = scratch_folder();
  const fs::path scene = tiny_scene(folder);
  for (const char* out : {"a", "b"}) {
    const CliResult result = run_cli(study_command(scene, folder / out, "--knob blur_radius=1,2 --seeds 3 --no-plots --quiet"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  EXPECT_EQ(without_timings(read_bytes(folder / "a" / "study.csv")), without_timings(read_bytes(folder / "b" / "study.csv")));
  EXPECT_NE(read_bytes(folder / "a" / "study.csv"), read_bytes(folder / "b" / "study.csv"));  // the timings differ
  EXPECT_EQ(read_bytes(folder / "a" / "ladders.csv"), read_bytes(folder / "b" / "ladders.csv"));
  const std::map<std::string, std::string> a = study_data(folder / "a" / "study.h5");
  EXPECT_EQ(a, study_data(folder / "b" / "study.h5"));
  for (const char* name : {".@verdict", "frame_time_s", "noise_floor/between_seeds", "settings/000@role",
                           "ladders/blur_radius/values"})
    EXPECT_EQ(a.count(name), 1u) << name;
}

// A study split in two shards and merged, each command run in `folder` (the shards written to `shards`).
std::string shard_command(const std::string& scene, const std::string& shards, int index) {
  return "study '" + scene + "' --backend cpu --threads 2 --knob blur_radius=1,2 --seeds 2 --quiet --shard " +
         std::to_string(index) + "/2 --out '" + shards + "'";
}
CliResult run_in(const fs::path& folder, const std::string& arguments) {
  return run_shell("cd '" + folder.string() + "' && '" + cli_path() + "' " + arguments);
}
std::string merge_command(const std::string& shards, const fs::path& out) {
  return "study merge '" + shards + "/shard-0-of-2.bleedshard' '" + shards + "/shard-1-of-2.bleedshard' --no-plots " +
         "--quiet --out '" + out.string() + "'";
}

// Issue 38, item 7: shards run with another trace, mesh or vessel map merged (exit 0) into a study
// that matched neither: the fingerprint hashed the scenario's text, not the files it names. Shard 1
// is run again with each file changed in turn; the merge refuses it.
TEST(StudyMerge, RefusesShardsRunWithAnotherTraceMeshOrVesselMap) {
  const fs::path folder = scratch_folder();
  const std::string textures = source_dir() + "/scenarios/textures/", traces = source_dir() + "/scenarios/traces/";
  const std::string panel = "v 0 0 0\nv 8 0 0\nv 8 -6 0\nv 0 -6 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  const auto copy = [&](const std::string& from, const char* to) {
    fs::copy_file(from, folder / to, fs::copy_options::overwrite_existing);
  };
  const struct {
    const char* name;
    std::function<void()> write, change;
  } files[] = {
      {"stroke.csv", [&] { copy(traces + "single-stroke.csv", "stroke.csv"); },
       [&] { copy(traces + "quick-strokes.csv", "stroke.csv"); }},
      {"panel.obj", [&] { write_text(folder / "panel.obj", panel + "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"); },
       [&] { write_text(folder / "panel.obj", panel + "f 1/1 2/2 4/4\nf 2/2 3/3 4/4\n"); }},
      {"vessels.png", [&] { copy(textures + "vessels-gradient-64x48.png", "vessels.png"); },
       [&] { copy(textures + "vessel-edges-16x8.png", "vessels.png"); }}};
  for (const auto& file : files) file.write();
  write_text(folder / "named.toml",
             "[scene]\nname = \"named\"\nwidth_px = 32\nheight_px = 24\nwidth_mm = 8.0\nheight_mm = 6.0\n"
             "duration_s = 0.2\n[tissue]\nmesh = \"panel.obj\"\n[haptics]\ntrace = \"stroke.csv\"\n[spread]\n"
             "radius_mm = 2.0\n[particles]\ncapacity = 1024\ndesign_depth_mm = 1\n[vessels]\nmap = \"vessels.png\"\n"
             "[blur]\n[[cut]]\nx_mm = 4.0\ny_mm = 2.0\n");
  for (const int shard : {0, 1}) ASSERT_EQ(run_in(folder, shard_command("named.toml", "shards", shard)).exit_code, 0);
  const CliResult same = run_in(folder, merge_command("shards", folder / "merged"));
  ASSERT_EQ(same.exit_code, 0) << "the shards of one study merge: " << same.output;
  for (const auto& file : files) {
    file.change();
    const CliResult shard = run_in(folder, shard_command("named.toml", "shards", 1));
    ASSERT_EQ(shard.exit_code, 0) << shard.output;
    file.write();
    const fs::path out = folder / (std::string("merged-") + file.name);
    const CliResult merged = run_in(folder, merge_command("shards", out));
    EXPECT_EQ(merged.exit_code, 2) << file.name << ": " << merged.output;
    EXPECT_NE(merged.output.find("shards/shard-1-of-2.bleedshard: a shard of another study than "
                                 "'shards/shard-0-of-2.bleedshard'"),
              std::string::npos)
        << file.name << ": " << merged.output;
    EXPECT_FALSE(fs::exists(out)) << file.name;
  }
}

// Issue 38, item 5: under `ulimit -f 40` a study (and a merge) said "cannot close the file in HDF5
// file 'sf/study.h5.partial'" and then died of SIGSEGV in HDF5's exit handler (exit 139), leaving
// study.h5.partial. Now: exit 1, one line naming the file and the OS error, no study.h5 of either
// name.
TEST(OutputSafety, AFileSizeLimitEndsAStudyWithAMessageNotACrash) {
  const fs::path folder = scratch_folder();
  tiny_scene(folder);
  for (const int shard : {0, 1}) ASSERT_EQ(run_in(folder, shard_command("tiny.toml", "shards", shard)).exit_code, 0);
  const std::string limit = "ulimit -f 40; ";
  const CliResult study = run_shell(limit + "cd '" + folder.string() + "' && '" + cli_path() + "' " +
                                    study_command("tiny.toml", "sf", "--knob blur_radius=1,2 --seeds 2 --no-plots --quiet"));
  const CliResult merge = run_shell(limit + "cd '" + folder.string() + "' && '" + cli_path() + "' " +
                                    merge_command("shards", "mf"));
  for (const auto& [result, out] : {std::pair{study, "sf"}, std::pair{merge, "mf"}}) {
    EXPECT_EQ(result.exit_code, 1) << out << ": " << result.output;
    EXPECT_NE(result.output.find("bleedsim: failed: cannot close the file in HDF5 file '" + std::string(out) +
                                 "/.bleedsim-partial/study.h5.partial': File too large"),
              std::string::npos)
        << out << ": " << result.output;
    EXPECT_FALSE(fs::exists(folder / out / "study.h5")) << out;
    EXPECT_FALSE(fs::exists(folder / out / ".bleedsim-partial" / "study.h5.partial"))
        << out << ": a half-written file left behind";
  }
}

// Issue 38, item 4. Under a file size limit (4 KiB: 8 of sh's blocks) the new study.csv was renamed
// in, ladders.csv failed and the last study's other files stayed: two studies mixed. A study's files
// are written into the partial folder and swapped in together, as a run's.
TEST(OutputSafety, AStudyWhoseWriteFailsLeavesTheLastStudyWhole) {
  const fs::path folder = scratch_folder();
  tiny_scene(folder);
  const std::string study = study_command("tiny.toml", "sf", "--knob blur_radius=1,2 --seeds 2 --no-plots --quiet");
  ASSERT_EQ(run_in(folder, study).exit_code, 0);
  const std::vector<std::string> files = {"jobs.csv", "ladders.csv", "study.csv", "study.h5"};
  std::map<std::string, std::string> last;
  for (const std::string& file : files) last[file] = read_bytes(folder / "sf" / file);
  const CliResult failed = run_shell("ulimit -f 8; cd '" + folder.string() + "' && '" + cli_path() + "' " + study);
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_EQ(failed.output, "bleedsim: failed: cannot write 'sf/.bleedsim-partial/ladders.csv.partial': File too large\n");
  // The new study.csv differs from the last in its timings.
  for (const std::string& file : files)
    EXPECT_TRUE(read_bytes(folder / "sf" / file) == last[file]) << file << " is not the last study's";
  EXPECT_FALSE(fs::exists(folder / "sf" / "ladders.csv.partial")) << "a half-written file beside the last study's";
}

// Issue 38, item 18: a merge found the scenario by the path the shards were given, relative to the
// folder they ran in: shards run in study/ with `--out ../sh` and merged from its parent failed with
// "hs.toml: cannot read scenario file". A shard carries the scenario's text and its absolute path, so
// the merge runs in any folder, even once the scenario file itself is gone; it reads the files the
// scenario names beside that path, and refuses one changed since the shards ran.
TEST(StudyMerge, MergesShardsFromAnotherFolderThanTheyRanIn) {
  const fs::path folder = scratch_folder();
  fs::create_directories(folder / "study");
  fs::copy_file(source_dir() + "/scenarios/traces/single-stroke.csv", folder / "study" / "stroke.csv");
  write_text(folder / "study" / "hs.toml",
             "[scene]\nname = \"hs\"\nwidth_px = 32\nheight_px = 24\nwidth_mm = 8.0\nheight_mm = 6.0\n"
             "duration_s = 0.2\n[haptics]\ntrace = \"stroke.csv\"\n[spread]\nradius_mm = 2.0\n[particles]\n"
             "capacity = 1024\ndesign_depth_mm = 1\n[blur]\n[[cut]]\nx_mm = 4.0\ny_mm = 2.0\n");
  for (const int shard : {0, 1}) {
    const CliResult result = run_in(folder / "study", shard_command("hs.toml", "../sh", shard));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  fs::rename(folder / "study" / "hs.toml", folder / "study" / "hs-edited-since.toml");
  const CliResult merged = run_in(folder, merge_command("sh", "merged"));
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const std::vector<std::string> csv = lines_of(read_bytes(folder / "merged" / "study.csv"));
  // The header, the reference, the scene, blur_radius 1 and its refinement 4, the noise floor.
  ASSERT_EQ(csv.size(), 6u) << read_bytes(folder / "merged" / "study.csv");
  EXPECT_EQ(csv[1].rfind("hs,reference,,reference,cpu,ok,2,", 0), 0u) << csv[1];

  fs::copy_file(source_dir() + "/scenarios/traces/quick-strokes.csv", folder / "study" / "stroke.csv",
                fs::copy_options::overwrite_existing);
  const CliResult changed = run_in(folder, merge_command("sh", "merged-again"));
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("sh/shard-0-of-2.bleedshard: its study is not the one " +
                                (folder / "study" / "hs.toml").string() +
                                "'s text and this build make now (a file it names or bleedsim changed"),
            std::string::npos)
      << changed.output;
  EXPECT_FALSE(fs::exists(folder / "merged-again"));
}

// A study's options and the message that refuses them.
struct Refused {
  const char* options;
  const char* message;
};

// Each case on the tiny scene exits 2 with its message and writes nothing.
void expect_each_refused(const std::vector<Refused>& cases) {
  const fs::path folder = scratch_folder();
  const fs::path scene = tiny_scene(folder);
  for (const Refused& c : cases) {
    const CliResult result = run_cli(study_command(scene, folder / "out", c.options));
    EXPECT_EQ(result.exit_code, 2) << c.options << ": " << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.options << ": " << result.output;
    EXPECT_FALSE(fs::exists(folder / "out")) << c.options;
  }
}

TEST(StudyCommand, BadOptionsExitTwoAndWriteNothing) {
  expect_each_refused(
      {{"--knob substep=1,2", "--knob: no knob 'substep' (known: compression, substeps, particle_size,"},
       {"--knob iterations=1,2", "--knob: no knob 'iterations': the particle model has no solver iterations"},
       {"--knob substeps", "--knob: write it as substeps=v1,v2,... (got 'substeps')"},
       {"--knob substeps=20,x", "--knob substeps: level 2, 'x', is not a decimal number"},
       {"--knob blur_downsample=3", "--knob blur_downsample: values of blur.downsample must be 1, 2 or 4 (got 3)"},
       {"--knob resolution=1 --seeds 1", "--seeds: needs at least 2 (got 1): a confidence interval needs two runs"},
       {"--knob compression=0.0002,0.02", "reference: the finest settings (compression 0.0002) cannot run"}});
}

// Issue 38, item 12: `--knob substeps=70,70` was taken (the repeat dropped without a word), and a
// list's values were read by strtod, which takes "0x10" as 16 and " 10" as 10 and calls 1e400 inf.
// Each level is a decimal number as std::from_chars reads it, written once; an empty one is named.
TEST(StudyCommand, AKnobsLevelsAreEachADecimalNumberGivenOnce) {
  expect_each_refused(
      {{"--knob substeps=70,70", "--knob substeps: 70 is given twice: give each level once"},
       {"--knob compression=0.02,0.04,0.020", "--knob compression: 0.02 is given twice: give each level once"},
       {"--knob substeps=10,,20", "--knob substeps: level 2 of '10,,20' is empty: write numbers between the commas"},
       {"--knob substeps=10,", "--knob substeps: level 2 of '10,' is empty: write numbers between the commas"},
       {"--knob substeps=,10", "--knob substeps: level 1 of ',10' is empty: write numbers between the commas"},
       {"--knob substeps=0x10", "--knob substeps: level 1, '0x10', is not a decimal number"},
       {"--knob 'substeps= 10'", "--knob substeps: level 1, ' 10', is not a decimal number"},
       {"--knob substeps=1e400", "--knob substeps: level 1, '1e400', is out of a double's range"},
       {"--knob substeps=", "--knob: write it as substeps=v1,v2,... (got 'substeps=')"},
       {"--knob substeps=nan", "--knob substeps: values of particles.substeps must be a finite number (got nan)"},
       {"--knob =1,2", "--knob: no knob '' (known: compression, substeps,"}});
}

}  // namespace
}  // namespace bleedsim::test
