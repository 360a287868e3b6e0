// Limits that hold (issue 13, items 2 and 5; issue 38, item 13): sizes are counted before anything
// narrows them, and every input's memory — the run's, a texture's, a mesh's, a trace's — is counted
// before it is read or allocated, the refusal naming the file and the key that sets the size; a
// trace is read only as far as the run plays it. Each case here ran out of memory, or on with a
// wrong size, before.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/cli/cli_harness.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

const std::string kScene =
    "[scene]\n"            // 1
    "width_px = 64\n"      // 2
    "height_px = 48\n"     // 3
    "width_mm = 16.0\n"    // 4
    "height_mm = 12.0\n"   // 5
    "duration_s = 0.2\n";  // 6

// Runs `validate` and then `run` on `text`: both must refuse it (exit 2) with each of `expected`,
// and leave no output folder.
void expect_both_refuse(const fs::path& dir, const std::string& text, const std::vector<std::string>& expected,
                        const std::string& shell_prefix = "") {
  write_text(dir / "s.toml", text);
  const fs::path out = dir / "out";
  for (const std::string command : {"validate", "run"}) {
    const CliResult result = run_cli(command + " '" + (dir / "s.toml").string() + "'" +
                                         (command == "run" ? " --backend cpu --out '" + out.string() + "'" : ""),
                                     shell_prefix);
    EXPECT_EQ(result.exit_code, 2) << command << ": " << result.output;
    for (const std::string& part : expected)
      EXPECT_NE(result.output.find(part), std::string::npos) << command << ": no '" << part << "' in " << result.output;
    EXPECT_FALSE(fs::exists(out)) << command;
  }
}

// Item 2: 1e-9 mm particles need ~1e20 grid cells and ~1e13 sub-steps; both overflowed an int,
// and the run went on with a one-cell grid.
TEST(Limits, ANanometreParticleIsRefusedAtItsDiameter) {
  expect_both_refuse(scratch_folder(), kScene + "[particles]\ndiameter_mm = 1e-9\nsplat_radius_mm = 1.0\n",
                     {"s.toml:8:15: particles.diameter_mm: the collision grid would have 1.136e+20 cells"});
}

// A black 8-bit PNG of width x height px with `channels` channels (1: grey, 3: RGB), written by
// Python's zlib: a few hundred KB however many pixels it has, so a test can have a huge image.
void write_blank_png(const fs::path& path, int width, int height, int channels) {
  const std::string size = std::to_string(width) + ", " + std::to_string(height);
  const CliResult made = run_shell(
      "'" + python() + "' -c '\n"
      "import struct, sys, zlib\n"
      "def chunk(kind, data): return struct.pack(\">I\", len(data)) + kind + data + struct.pack(\">I\", zlib.crc32(kind + data))\n"
      "z = zlib.compressobj(9)\n"
      "row = bytes(1 + " + std::to_string(channels) + " * " + std::to_string(width) + ")\n"
      "rows = b\"\".join(z.compress(row) for _ in range(" + std::to_string(height) + ")) + z.flush()\n"
      "sys.stdout.buffer.write(b\"\\x89PNG\\r\\n\\x1a\\n\" + chunk(b\"IHDR\", struct.pack(\">IIBBBBB\", " + size + ", 8, " +
      (channels == 3 ? "2" : "0") + ", 0, 0, 0))"
      " + chunk(b\"IDAT\", rows) + chunk(b\"IEND\", b\"\"))\n' > '" + path.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.output;
}

// Item 5: a 400 KB PNG that decodes to 20000 x 20000 px (1.6 GB of RGBA) for a 64 x 48 panel is
// refused from its header, before a byte of it is decoded.
TEST(Limits, APngBombIsRefusedFromItsHeader) {
  const fs::path dir = scratch_folder();
  write_blank_png(dir / "bomb.png", 20000, 20000, 1);
  if (HasFatalFailure()) return;
  ASSERT_LT(fs::file_size(dir / "bomb.png"), 1u << 20) << "the bomb should be small";
  expect_both_refuse(dir, kScene + "[tissue]\ntexture = \"bomb.png\"\n",
                     {"s.toml:8:11: tissue.texture: texture", "is 20000 x 20000 px; a texture may be at most 16384 px"});
}

// Item 5: validate checks and describes; it draws no tissue and allocates nothing the panel's
// size. An 8000 x 8000 px panel's tissue alone is 256 MB; validate's whole peak must stay far below.
TEST(Limits, ValidateAllocatesNothingThePanelsSize) {
  const fs::path dir = scratch_folder();
  write_text(dir / "big.toml", "[scene]\nwidth_px = 8000\nheight_px = 8000\nwidth_mm = 80\nheight_mm = 80\n"
                               "duration_s = 1\n");
  const CliResult result = run_shell(
      "'" + python() + "' -c 'import resource, subprocess, sys\n"
      "code = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL).returncode\n"
      "print(\"exit\", code, \"peak_kib\", resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)' '" +
      cli_path() + "' validate '" + (dir / "big.toml").string() + "'");
  ASSERT_NE(result.output.find("exit 0 "), std::string::npos) << result.output;
  long peak_kib = 0;
  std::sscanf(result.output.c_str() + result.output.find("peak_kib") + 8, "%ld", &peak_kib);
  EXPECT_LT(peak_kib, 64 * 1024) << "validate took " << peak_kib << " KiB at its peak";
}

// Item 5: a 2^28-slot ring needs ~23 GiB; under a 12 GB limit it was refused naming
// scene.width_px. The key that sets the size is particles.capacity.
TEST(Limits, ARingTooLargeForMemoryIsRefusedAtItsCapacity) {
  BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED();
  expect_both_refuse(scratch_folder(), kScene + "[particles]\ncapacity = 268435456\n",
                     {"s.toml:8:12: particles.capacity: this scene needs", "268435456 particle slots",
                      "of host memory"},
                     "ulimit -v 12000000;");
}

// A trace of `samples` samples 1 ms apart, one per line, as `path`.
void write_long_trace(const fs::path& path, int samples) {
  std::ofstream trace(path);
  trace << "# device: Novint Falcon\n# frame: libnifalcon\n# rate_hz: 1000\nt_s,x_m,y_m,z_m,buttons\n";
  char line[64];
  for (int n = 0; n < samples; ++n) {
    std::snprintf(line, sizeof line, "%d.%03d,0,0,0.1,0\n", n / 1000, n % 1000);
    trace << line;
  }
}

// Issue 38, item 13: a run reads only what it plays of a trace. 2.5 million samples take 160 MB
// kept; under a 150 MB limit a 0.2 s run of them was refused (and a longer limit ran out at 744 MB
// for 5.8 million): now it reads 202 lines, and validate checks all the rest a line at a time.
TEST(Limits, AShortRunOverALongTraceReadsOnlyWhatItPlays) {
  BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED();
  const fs::path dir = scratch_folder();
  write_long_trace(dir / "long.csv", 2'500'000);
  write_text(dir / "s.toml", kScene + "[haptics]\ntrace = \"long.csv\"\n");
  const std::string limit = "ulimit -v 150000;";
  const CliResult validated = run_cli("validate '" + (dir / "s.toml").string() + "'", limit);
  EXPECT_EQ(validated.exit_code, 0) << validated.output;
  EXPECT_NE(validated.output.find("long.csv: 2500000 samples over 2499.999 s; the run reads the first 202\n"),
            std::string::npos)
      << validated.output;
  EXPECT_NE(validated.output.find("64.00 KiB for the 202 samples kept of trace '"), std::string::npos)
      << "validate counts what the run keeps: a store of 1024 samples\n" << validated.output;
  const CliResult ran = run_cli("run '" + (dir / "s.toml").string() + "' --backend cpu -j 1 --output-threads 1 --out '" +
                                (dir / "out").string() + "'", limit);
  EXPECT_EQ(ran.exit_code, 0) << ran.output;
  EXPECT_NE(ran.output.find("long.csv: 202 samples over 0.201 s through the 1 kHz haptic loop (read as far as the "
                            "run goes)"),
            std::string::npos)
      << ran.output;
}

// The samples a run plays are counted as they are kept: a 2500 s run over the same trace needs them
// all, and is refused at its key, naming the file, before its store outgrows the room.
TEST(Limits, ATraceWhosePlayedPartIsTooLargeIsRefusedAtItsKey) {
  BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED();
  const fs::path dir = scratch_folder();
  write_long_trace(dir / "long.csv", 2'500'000);
  std::string scene = kScene;
  scene.replace(scene.find("duration_s = 0.2"), 16, "duration_s = 2500");
  expect_both_refuse(dir, scene + "[haptics]\ntrace = \"long.csv\"\n",
                     {"s.toml:8:9: haptics.trace: cannot read trace file '", "long.csv': keeping its samples up to t = ",
                      "of host memory, but only"},
                     "ulimit -v 150000;");
}

// Issue 38, item 13: a mesh's memory is counted from a pass over its lines before it is read. A
// 480,000-triangle mesh is counted at about 260 MiB to read (it takes some 190); under a 150 MB
// limit it ended in a bare std::bad_alloc, exit 1.
TEST(Limits, AMeshTooLargeForMemoryIsRefusedAtItsKey) {
  BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED();
  const fs::path dir = scratch_folder();
  {
    // A 600 x 400 grid of quads over the panel, each cut into two triangles.
    std::ofstream mesh(dir / "grid.obj");
    const int nx = 600, ny = 400;
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh << "v " << 16.0 * i / nx << " " << 12.0 * j / ny << " 0\n";
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh << "vt " << double(i) / nx << " " << double(j) / ny << "\n";
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = j * (nx + 1) + i + 1, b = a + 1, c = a + nx + 1, d = c + 1;
        mesh << "f " << a << "/" << a << " " << b << "/" << b << " " << d << "/" << d << "\n";
        mesh << "f " << a << "/" << a << " " << d << "/" << d << " " << c << "/" << c << "\n";
      }
  }
  expect_both_refuse(dir, kScene + "[tissue]\nmesh = \"grid.obj\"\n",
                     {"s.toml:8:8: tissue.mesh: this scene needs", "for reading the mesh '",
                      "grid.obj' (480000 triangles)", "of host memory"},
                     "ulimit -v 150000;");
}

// Issue 38, item 13: a 16384 x 16384 px PNG of 1 MB decodes to 1.75 GiB at its peak (the inflated
// rows beside the RGBA image); validate said 50 KiB. Its memory line now counts it, and run, which
// counts the same, decodes it under a limit that the former count of 7.5 GB refused.
TEST(Limits, ValidateAndRunCountATexturesDecoding) {
  const fs::path dir = scratch_folder();
  write_blank_png(dir / "big.png", 16384, 16384, 3);
  if (HasFatalFailure()) return;
  write_text(dir / "s.toml", kScene + "[tissue]\ntexture = \"big.png\"\n");
  const CliResult validated = run_cli("validate '" + (dir / "s.toml").string() + "'");
  ASSERT_EQ(validated.exit_code, 0) << validated.output;
  // The rows, 16384 · (1 + 3 · 16384) bytes, beside the RGBA image, 4 · 16384² bytes, and the file.
  EXPECT_NE(validated.output.find("  memory     50.00 KiB on the backend; 1.75 GiB of host memory at the most to read "
                                  "its files (1.75 GiB for decoding the 16384 x 16384 px texture '"),
            std::string::npos)
      << validated.output;
  if (!address_space_can_be_limited()) return;  // the run under a limit: see BLEEDSIM_SKIP_UNLESS_...
  const CliResult ran =
      run_cli("run '" + (dir / "s.toml").string() + "' --backend cpu -j 1 --output-threads 1 --out '" +
                  (dir / "out").string() + "'",
              "ulimit -v 2500000;");
  EXPECT_EQ(ran.exit_code, 0) << ran.output;
  const CliResult refused =
      run_cli("run '" + (dir / "s.toml").string() + "' --backend cpu --out '" + (dir / "out2").string() + "'",
              "ulimit -v 1500000;");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("s.toml:8:11: tissue.texture: this scene needs 1.75 GiB of host memory (1.75 GiB "
                                "for decoding the 16384 x 16384 px texture '"),
            std::string::npos)
      << refused.output;
}

}  // namespace
}  // namespace bleedsim::test
