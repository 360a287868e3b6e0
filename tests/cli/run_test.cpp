// bleedsim run / hash / validate end to end, as a user runs them.
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "core/runtime/backend.h"
#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

std::string scenario(const std::string& name) { return (fs::path(source_dir()) / "scenarios" / name).string(); }

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

long long int_attribute(const fs::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  long long value = -1;
  H5Aread(a, H5T_NATIVE_LLONG, &value);
  H5Aclose(a);
  H5Fclose(f);
  return value;
}

// A dataset's stored values as bytes; empty when the file has no such dataset.
std::vector<char> dataset_bytes(const fs::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  std::vector<char> bytes;
  if (H5Lexists(f, name, H5P_DEFAULT) > 0) {
    const hid_t d = H5Dopen(f, name, H5P_DEFAULT), type = H5Dget_type(d), space = H5Dget_space(d);
    bytes.resize(std::size_t(H5Sget_simple_extent_npoints(space)) * H5Tget_size(type));
    H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
    H5Sclose(space);
    H5Tclose(type);
    H5Dclose(d);
  }
  H5Fclose(f);
  return bytes;
}

TEST(Run, WritesHdf5AndPngsAndSaysWhere) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path out = scratch_folder() / "out";
  const CliResult result =
      run_cli("run '" + scenario("golden/spread-single.toml") + "' --backend cpu --png-every 10 --out '" + out.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("45 frames in"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find((out / "frames.h5").string()), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("6 PNGs in"), std::string::npos) << result.output;
  EXPECT_EQ(files_in(out), std::vector<std::string>({".bleedsim-manifest", "frames.h5", "frames.xmf", "png"}));
  EXPECT_EQ(files_in(out / "png"),
            std::vector<std::string>({"frame_000000.png", "frame_000010.png", "frame_000020.png",
                                      "frame_000030.png", "frame_000040.png", "frame_000044.png"}));
  // The file as h5py sees it (an independent reader): layout, chunks, filters, provenance.
  const CliResult check = run_shell("'" + python() + "' '" + source_dir() + "/tests/check_hdf5_layout.py' '" +
                                    (out / "frames.h5").string() +
                                    "' --frames 45 --width 160 --height 120 --fields spread/stain");
  EXPECT_EQ(check.exit_code, 0) << check.output;
}

// Width and height from a PNG's IHDR chunk (bytes 16–23, big-endian).
std::pair<int, int> png_size(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  const auto word = [&](int at) { return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3]; };
  return {word(16), word(20)};
}

TEST(Run, WritesAContactSheetOfTheFramesAskedFor) {
  const fs::path out = scratch_folder() / "out";
  const CliResult result = run_cli("run '" + scenario("golden/spread-single.toml") +
                                   "' --backend cpu --no-hdf5 --contact-sheet 3 --out '" + out.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("contact_sheet.png"), std::string::npos) << result.output;
  EXPECT_EQ(files_in(out), std::vector<std::string>({".bleedsim-manifest", "contact_sheet.png"}))
      << "--no-hdf5 writes neither frames.h5 nor its description, frames.xmf";
  // Three 160 × 120 frames (small enough to stay whole) in a 2 × 2 grid with 4 px gutters.
  EXPECT_EQ(png_size(out / "contact_sheet.png"), std::make_pair(2 * 160 + 3 * 4, 2 * 120 + 3 * 4));
}

// The turbinate scene (a tissue mesh and a [view]) for a third of a second, ten frames, written into
// `dir`; returns its path.
fs::path short_turbinate(const fs::path& dir) {
  std::string text = read_bytes(scenario("turbinate.toml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"duration_s = 6.0", "duration_s = 0.34"},
                                 {"\"meshes/turbinate.obj\"", "\"" + scenario("meshes/turbinate.obj") + "\""}}) {
    EXPECT_NE(text.find(from), std::string::npos) << from;
    if (text.find(from) != std::string::npos) text.replace(text.find(from), from.size(), to);
  }
  write_text(dir / "short.toml", text);
  return dir / "short.toml";
}

TEST(Run, ASceneWithAViewDrawsTheMeshBesideEachPngAndInASheet) {
  // The turbinate scene for a third of a second: PNGs of frames 0, 5 and 9, each with its view, and
  // both contact sheets; validate names the mesh and how the texture stretches over it.
  const fs::path dir = scratch_folder(), out = dir / "turbinate";
  const CliResult result = run_cli("run '" + short_turbinate(dir).string() + "' --backend cpu --png-every 5 " +
                                   "--contact-sheet 2 --out '" + out.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* file : {"png/frame_000000.png", "png/view_000000.png", "png/view_000005.png", "png/view_000009.png",
                           "contact_sheet.png", "view_contact_sheet.png"})
    EXPECT_TRUE(fs::exists(out / file)) << file << " in " << result.output;
  EXPECT_NE(result.output.find("6 PNGs"), std::string::npos) << result.output;
  const CliResult validate = run_cli("validate '" + scenario("turbinate.toml") + "'");
  EXPECT_NE(validate.output.find("3072 triangles, 749.9 mm²; a panel mm is 0.585 to 1.67 mm of its surface"),
            std::string::npos) << validate.output;
  EXPECT_NE(validate.output.find("stages     surface, spread, particles"), std::string::npos) << validate.output;
}

TEST(Run, TheSameSceneTwiceGivesByteIdenticalFiles) {
  const fs::path dir = scratch_folder();
  for (const char* name : {"a", "b"}) {
    const CliResult result = run_cli("run '" + scenario("golden/spread-overlap.toml") +
                                     "' --backend cpu --png-every 15 -q --out '" + (dir / name).string() + "'");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output, "") << "--quiet printed something";
  }
  EXPECT_EQ(read_bytes(dir / "a/frames.h5"), read_bytes(dir / "b/frames.h5"));
  EXPECT_EQ(read_bytes(dir / "a/frames.xmf"), read_bytes(dir / "b/frames.xmf"));
  for (const std::string& png : files_in(dir / "a/png"))
    EXPECT_EQ(read_bytes(dir / "a/png" / png), read_bytes(dir / "b/png" / png)) << png;
}

TEST(Run, AnyNumberOfOutputThreadsWritesTheSameBytes) {
  // Frames encoded on one worker, one after another, and on six, several frames at once and out of
  // order: the same frames.h5, frames.xmf, PNGs (frames and views) and contact sheets, byte for byte.
  const fs::path dir = scratch_folder(), toml = short_turbinate(dir);
  for (const char* threads : {"1", "6"}) {
    const CliResult result = run_cli("run '" + toml.string() + "' --backend cpu --png-every 3 --contact-sheet 4 -q " +
                                     "--output-threads " + threads + " --out '" + (dir / threads).string() + "'");
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  for (const char* file : {"frames.h5", "frames.xmf", "contact_sheet.png", "view_contact_sheet.png"})
    EXPECT_EQ(read_bytes(dir / "1" / file), read_bytes(dir / "6" / file)) << file;
  EXPECT_EQ(files_in(dir / "1/png").size(), 8u);  // frames 0, 3, 6 and 9, each with its view
  EXPECT_EQ(files_in(dir / "1/png"), files_in(dir / "6/png"));
  for (const std::string& png : files_in(dir / "1/png"))
    EXPECT_EQ(read_bytes(dir / "1/png" / png), read_bytes(dir / "6/png" / png)) << png;
}

TEST(Run, ThreadCountsGiveTheSameHashes) {
  // A short golden scene with particles and the spread: --threads reaches both.
  const CliResult one = run_cli("hash '" + scenario("golden/particles-spread-wrap.toml") + "' --backend cpu --threads 1");
  const CliResult seven = run_cli("hash '" + scenario("golden/particles-spread-wrap.toml") + "' --backend cpu --threads 7");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  ASSERT_EQ(seven.exit_code, 0) << seven.output;
  const auto hashes = [](const std::string& output) { return output.substr(output.find('\n') + 1); };
  EXPECT_NE(hashes(one.output).find("run "), std::string::npos);
  EXPECT_EQ(hashes(one.output), hashes(seven.output));
}

TEST(Run, ASceneWithoutTheSpreadWritesNoSpreadField) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path out = scratch_folder() / "out";
  const CliResult result = run_cli("run '" + scenario("tissue-only.toml") + "' --backend cpu -q --out '" + out.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const CliResult check = run_shell("'" + python() + "' '" + source_dir() + "/tests/check_hdf5_layout.py' '" +
                                    (out / "frames.h5").string() + "' --fields ''");
  EXPECT_EQ(check.exit_code, 0) << check.output;
  const hid_t file = H5Fopen((out / "frames.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_LE(H5Lexists(file, "/spread", H5P_DEFAULT), 0);
  H5Fclose(file);
}

TEST(Run, AnInterruptedRunKeepsEveryFrameItFinished) {
  const fs::path dir = scratch_folder();
  write_text(dir / "long.toml",
             "[scene]\nwidth_px = 1024\nheight_px = 768\nwidth_mm = 32\nheight_mm = 24\nduration_s = 20\n"
             "[spread]\n[[cut]]\nx_mm = 16\ny_mm = 12\n");
  const fs::path out = dir / "out";
  const CliResult result = run_shell(
      "'" + cli_path() + "' run '" + (dir / "long.toml").string() + "' --backend cpu -q --out '" + out.string() +
      "' & pid=$!; for i in $(seq 200); do [ -f '" + (out / ".bleedsim-partial" / "frames.h5.partial").string() +
      "' ] && break; sleep 0.05; done; sleep 0.5; kill -INT $pid; wait $pid; echo \"exit=$?\"");
  EXPECT_NE(result.output.find("exit=130"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("interrupted after"), std::string::npos) << result.output;
  ASSERT_TRUE(fs::exists(out / "frames.h5")) << result.output;
  EXPECT_EQ(files_in(out), std::vector<std::string>({".bleedsim-manifest", "frames.h5", "frames.xmf"}))
      << "an interrupted run is whole, and swapped in";
  EXPECT_EQ(int_attribute(out / "frames.h5", "complete"), 0);
  const long long written = int_attribute(out / "frames.h5", "frames_written");
  EXPECT_GE(written, 1);
  EXPECT_LT(written, 600);
  // frames.xmf describes the frames the file holds, one time each.
  const std::string description = read_bytes(out / "frames.xmf");
  long long times = 0;
  for (std::size_t at = description.find("<Time "); at != std::string::npos; at = description.find("<Time ", at + 1))
    ++times;
  EXPECT_EQ(times, written);
}

// A text attribute of the file's root (variable-length UTF-8, as the writer makes them).
std::string text_attribute(const fs::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  char* value = nullptr;
  H5Aread(a, type, &value);
  const std::string text = value ? value : "<unread>";
  H5free_memory(value);
  H5Tclose(type);
  H5Aclose(a);
  H5Fclose(f);
  return text;
}

// --set on a run: its frames are those of the file with the values written in, and the file's
// provenance lists them (its scenario_text is the file's, without them).
TEST(Run, SetValuesRunAsIfWrittenInTheFileAndTheRunRecordsThem) {
  const fs::path dir = scratch_folder();
  const std::string file = read_bytes(scenario("golden/spread-single.toml"));
  std::string edited = file;
  edited.replace(edited.find("duration_s = 1.5"), 16, "duration_s = 0.2");
  edited.replace(edited.find("radius_mm = 4.0"), 15, "radius_mm = 2.5");
  write_text(dir / "edited.toml", edited);
  const CliResult set = run_cli("run '" + scenario("golden/spread-single.toml") +
                                "' --backend cpu -q --png-every 0 --set scene.duration_s=0.2 --set spread.radius_mm=2.5 --out '" +
                                (dir / "set").string() + "'");
  ASSERT_EQ(set.exit_code, 0) << set.output;
  const CliResult written = run_cli("run '" + (dir / "edited.toml").string() + "' --backend cpu -q --png-every 0 --out '" +
                                    (dir / "written").string() + "'");
  ASSERT_EQ(written.exit_code, 0) << written.output;
  EXPECT_EQ(int_attribute(dir / "set" / "frames.h5", "frames_written"), 6);
  EXPECT_EQ(dataset_bytes(dir / "set" / "frames.h5", "frame"), dataset_bytes(dir / "written" / "frames.h5", "frame"));
  EXPECT_EQ(text_attribute(dir / "set" / "frames.h5", "scenario_overrides"), "scene.duration_s=0.2\nspread.radius_mm=2.5\n");
  EXPECT_EQ(text_attribute(dir / "set" / "frames.h5", "scenario_text"), file);
  EXPECT_EQ(text_attribute(dir / "written" / "frames.h5", "scenario_overrides"), "");
}

// A bad --set is refused as a file's bad value is, at its place among the --set (overrides:N:COLUMN)
// with its key, before anything is written.
TEST(Run, ABadSetIsRefusedAtItsPlaceAndNothingIsWritten) {
  const fs::path out = scratch_folder() / "out";
  const CliResult result = run_cli("run '" + scenario("golden/spread-single.toml") +
                                   "' --backend cpu --set scene.duration_s=0.2 --set spread.radius_mm=-1 --out '" +
                                   out.string() + "'");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("bleedsim: error: overrides:2:18: spread.radius_mm: must be greater than 0"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Validate, DescribesTheSceneWithItsSetValuesAndRefusesABadOne) {
  const CliResult result = run_cli("validate '" + scenario("default.toml") + "' --set scene.duration_s=1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("  --set      scene.duration_s=1\n"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("  time       1 s at 30 Hz: 30 frames\n"), std::string::npos) << result.output;
  const CliResult bad = run_cli("validate '" + scenario("default.toml") + "' --set particles.diamter_mm=0.1");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_EQ(bad.output, "bleedsim: error: overrides:1:11: particles.diamter_mm: unknown key; did you mean 'diameter_mm'?\n");
}

TEST(Validate, DescribesTheRunWithoutWritingAnything) {
  const CliResult result = run_cli("validate '" + scenario("default.toml") + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("valid"), std::string::npos);
  // The default scene runs every stage: the spread, the particles, their film, its blur, the trails.
  EXPECT_NE(result.output.find("stages     spread, particles, splat, blur, trail, blend\n"), std::string::npos)
      << result.output;
  const CliResult tissue = run_cli("validate '" + scenario("tissue-only.toml") + "'");
  EXPECT_NE(tissue.output.find("stages     blend\n"), std::string::npos) << tissue.output;
}

// The particle model as validate describes it, from the default parameters (docs/particles.md):
// film t = 0.004 / (√3/2 · 0.2²) = 0.1155 mm; the yield's grip 50 / t = 433.0 mm/s²; the critical
// drop R = 2 · 30 / (t · (1000 − 433.0)) = 0.9164 mm, V = t · π · R² = 0.3047 mm³. And the ring: one
// cut bleeding 2 mm³/s for 2 s has 4 / 0.004 = 1000 particles alive within a 30 s lifetime, more
// than 64 slots (a warning, and still valid), fewer than 1024 (no warning).
TEST(Validate, DescribesTheParticlesAndWarnsWhenTheRingWillOverwriteLiveBlood) {
  const fs::path dir = scratch_folder();
  const auto scene_with_capacity = [&](int capacity) {
    const fs::path file = dir / ("ring-" + std::to_string(capacity) + ".toml");
    write_text(file, "[scene]\nname = \"ring\"\nwidth_px = 64\nheight_px = 48\nwidth_mm = 16.0\nheight_mm = 12.0\n"
                     "duration_s = 1.0\n[particles]\ncapacity = " +
                         std::to_string(capacity) + "\n[[cut]]\nx_mm = 8.0\ny_mm = 2.0\n");
    return run_cli("validate '" + file.string() + "'");
  };
  const CliResult small = scene_with_capacity(64);
  ASSERT_EQ(small.exit_code, 0) << small.output;
  EXPECT_NE(small.output.find("film       0.115 mm thick; the mucosa holds drops up to 0.305 mm³ (radius 0.916 mm)"),
            std::string::npos)
      << small.output;
  EXPECT_NE(small.output.find("warning: the cuts can have up to 1000 particles alive at once"), std::string::npos)
      << small.output;
  EXPECT_NE(small.output.find("more than the ring's 64 slots: it will overwrite live blood"), std::string::npos)
      << small.output;
  const CliResult large = scene_with_capacity(1024);
  ASSERT_EQ(large.exit_code, 0) << large.output;
  EXPECT_EQ(large.output.find("warning"), std::string::npos) << large.output;
}

// The film is one particle thick: a hexagonal layer of 0.2 mm particles over a W × H mm panel is
// W·H / (√3/2 · 0.04) of them. The cut above puts 1000 on the panel at once: a 4 × 4 mm panel holds
// 461.9 (a warning naming the flow, still valid), a 6 × 6 mm one 1039.2 (none).
TEST(Validate, WarnsWhenThePanelGetsMoreBloodThanOneLayerOfFilmHolds) {
  const fs::path dir = scratch_folder();
  const auto scene_of_side = [&](int side_mm) {
    const fs::path file = dir / ("layer-" + std::to_string(side_mm) + ".toml");
    write_text(file, "[scene]\nname = \"layer\"\nwidth_px = 40\nheight_px = 40\nwidth_mm = " + std::to_string(side_mm) +
                         ".0\nheight_mm = " + std::to_string(side_mm) +
                         ".0\nduration_s = 1.0\n[particles]\n[[cut]]\nx_mm = 2.0\ny_mm = 1.0\n");
    return run_cli("validate '" + file.string() + "'");
  };
  const CliResult small = scene_of_side(4);
  ASSERT_EQ(small.exit_code, 0) << small.output;
  EXPECT_NE(small.output.find("warning: particles.flow_mm3_per_s_per_mm: the cuts can have 1000 particles on the "
                              "panel at once, more than the one layer of film it holds (462 of 0.2 mm"),
            std::string::npos)
      << small.output;
  const CliResult large = scene_of_side(6);
  ASSERT_EQ(large.exit_code, 0) << large.output;
  EXPECT_EQ(large.output.find("warning"), std::string::npos) << large.output;
}

// The bleeding effects and the instrument as validate describes them, from the files: suction-pass's
// scripted tip (2 points, 2.5 to 4 s), its reach 1.2 mm and 8 mm³/s, its body 0.6 + 0.2 / 2 mm; the
// stylus' suction on the second button (0x2) in falcon-suction; vessels-pulse's map and threshold.
TEST(Validate, DescribesTheBleedingAndTheInstrument) {
  const CliResult scripted = run_cli("validate '" + scenario("suction-pass.toml") + "'");
  ASSERT_EQ(scripted.exit_code, 0) << scripted.output;
  EXPECT_NE(scripted.output.find("suction    a scripted tip, 2 points from 2.5 s to 4 s: reach 1.2 mm, up to 8 mm³/s"),
            std::string::npos) << scripted.output;
  EXPECT_NE(scripted.output.find("contact    a scripted tip, 2 points from 2.5 s to 4 s: particle centres kept 0.7 mm"),
            std::string::npos) << scripted.output;
  const CliResult stylus = run_cli("validate '" + scenario("falcon-suction.toml") + "'");
  ASSERT_EQ(stylus.exit_code, 0) << stylus.output;
  EXPECT_NE(stylus.output.find("suction    the stylus: reach 1 mm, up to 6 mm³/s"), std::string::npos) << stylus.output;
  EXPECT_NE(stylus.output.find("in contact with a button of 0x2 held\n"), std::string::npos) << stylus.output;
  const CliResult vessels = run_cli("validate '" + scenario("vessels-pulse.toml") + "'");
  ASSERT_EQ(vessels.exit_code, 0) << vessels.output;
  // Its cuts' mean densities, the first marked arterial in the file, the last between vessels (the
  // map is 0 along its wound).
  const std::string means = "vessels    each wound's flow times the map's mean along it; map procedural; the cuts' means ";
  const std::size_t at = vessels.output.find(means);
  ASSERT_NE(at, std::string::npos) << vessels.output;
  const std::string line = vessels.output.substr(at, vessels.output.find('\n', at) - at);
  EXPECT_EQ(line.find(means + "0."), 0u) << line;
  EXPECT_NE(line.find(" (arterial) "), std::string::npos) << line;
  EXPECT_EQ(line.substr(line.size() - 2), " 0") << line;
  EXPECT_NE(vessels.output.find("pulse      72 beats a minute, w(t) = 1 + 0.6 sin(2πft) + 0.3 sin(4πft); arterial: cuts "
                                "marked so, and wounds of mean vessel density ≥ 0.6\n"),
            std::string::npos) << vessels.output;
}

TEST(Backend, AutoSaysWhichBackendItTookAndWhy) {
  const CliResult result = run_cli("run '" + scenario("golden/spread-single.toml") + "' --no-hdf5 --out '" +
                                   (scratch_folder() / "out").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::string why_not;
  const bool cuda = cuda_device_available(&why_not);
  EXPECT_NE(result.output.find(cuda ? "on cuda" : "on cpu"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find(cuda ? "auto: CUDA device found" : "auto: " + why_not), std::string::npos)
      << result.output;
}

// A run on CUDA writes the values the CPU run writes: every field of every frame, and the same PNGs
// (the frames' hashes agree, gpu-check's parity; this is the files a user reads).
TEST(Backend, ACudaRunWritesTheFieldsAndPngsOfTheCpuRun) {
  std::string why_not;
  if (!cuda_device_available(&why_not)) GTEST_SKIP() << "no CUDA device: " << why_not;
  const fs::path dir = scratch_folder();
  for (const char* backend : {"cpu", "cuda"}) {
    const CliResult result = run_cli("run '" + scenario("golden/optics-trails.toml") + "' --backend " + backend +
                                     " --png-every 7 -q --out '" + (dir / backend).string() + "'");
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  int fields = 0;
  for (const char* field : {"frame", "spread/stain", "splat/thickness", "blur/thickness", "trail/residue"}) {
    const std::vector<char> cpu = dataset_bytes(dir / "cpu/frames.h5", field);
    fields += !cpu.empty();
    EXPECT_TRUE(cpu == dataset_bytes(dir / "cuda/frames.h5", field)) << field;
  }
  EXPECT_EQ(fields, 5);
  EXPECT_EQ(files_in(dir / "cpu/png").size(), 14u);  // frames 0, 7, …, 84 and the last, 89
  EXPECT_EQ(files_in(dir / "cpu/png"), files_in(dir / "cuda/png"));
  for (const std::string& png : files_in(dir / "cpu/png"))
    EXPECT_EQ(read_bytes(dir / "cpu/png" / png), read_bytes(dir / "cuda/png" / png)) << png;
}

TEST(Backend, AskingForCudaWithoutADeviceSaysWhy) {
  std::string why_not;
  if (cuda_device_available(&why_not)) GTEST_SKIP() << "this machine has a CUDA device";
  const CliResult result = run_cli("run '" + scenario("golden/spread-single.toml") + "' --backend cuda --out '" +
                                   (scratch_folder() / "out").string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("cuda backend is not available"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace bleedsim::test
