// Nothing lost, nothing half-written (issue 13, items 1, 3, 4 and 6; docs/reliability.md): one run
// at a time per output folder, a finished run's files swapped in together, a failed write ending the
// run in one line with its frames kept and the folder's last whole run untouched. Every file is
// read back by h5py, an independent reader.
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_harness.h"
#include "tests/cli/study_files.h"

namespace bleedsim::test {
namespace {

namespace fs = std::filesystem;

std::string scenario(const std::string& name) { return (fs::path(source_dir()) / "scenarios" / name).string(); }

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// What h5py reads of a frames file: whether it opens, and its completion, frame count and scene.
struct H5Read {
  bool opens = false;
  int complete = -1;
  long frames_written = -1;
  long frames_stored = -1;
  std::string scene;
  std::string error;
};

H5Read read_with_h5py(const fs::path& file) {
  const CliResult result = run_shell(
      "'" + python() + "' -c 'import h5py, sys\n"
      "with h5py.File(sys.argv[1], \"r\") as f:\n"
      "    print(int(f.attrs[\"complete\"]), int(f.attrs[\"frames_written\"]), f[\"frame\"].shape[0], "
      "f.attrs[\"scene_name\"])' " + quoted(file));
  H5Read read;
  std::istringstream fields(result.output);
  read.opens = result.exit_code == 0 && bool(fields >> read.complete >> read.frames_written >> read.frames_stored >> read.scene);
  if (!read.opens) read.error = result.output;
  return read;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A scene of `frames` frames of 256 x 192 px with the spread: long enough to be caught running.
fs::path write_scene(const fs::path& dir, const std::string& name, int frames) {
  const fs::path file = dir / (name + ".toml");
  write_text(file, "[scene]\nname = \"" + name + "\"\nwidth_px = 256\nheight_px = 192\nwidth_mm = 16\nheight_mm = 12\n"
                   "duration_s = " + std::to_string(frames / 30.0) + "\n[spread]\n[[cut]]\nx_mm = 8\ny_mm = 6\n");
  return file;
}

std::string run_into(const fs::path& scene, const fs::path& out, const std::string& extra = "") {
  return "'" + cli_path() + "' run " + quoted(scene) + " --backend cpu -q --out " + quoted(out) + " " + extra;
}

// Item 1. Two runs into one folder: the second truncated the first's open HDF5 file (bytes 137 to
// 16 MB zeroed) and the first still said complete=1. The second must be refused before it opens
// anything, naming the folder and the first run's pid, and the first must end whole.
TEST(OutputSafety, ASecondRunIntoABusyFolderIsRefusedAndTheFirstEndsWhole) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path dir = scratch_folder(), out = dir / "X";
  const fs::path first = write_scene(dir, "first", 150);
  const CliResult result = run_shell(
      run_into(first, out) + " & pid=$!; for i in $(seq 500); do [ -e " + quoted(out / ".bleedsim.lock") +
      " ] && break; sleep 0.01; done; " + run_into(scenario("tissue-only.toml"), out) +
      "; echo \"second=$? first_pid=$pid\"; wait $pid; echo \"first=$?\"");
  EXPECT_NE(result.output.find("first=0"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("second=2"), std::string::npos) << result.output;
  const std::string pid = result.output.substr(result.output.find("first_pid=") + 10);
  EXPECT_NE(result.output.find("bleedsim: error: --out: output folder '" + out.string() +
                               "' is in use by another bleedsim run (pid " + pid.substr(0, pid.find('\n')) + ")"),
            std::string::npos)
      << result.output;
  const H5Read read = read_with_h5py(out / "frames.h5");
  ASSERT_TRUE(read.opens) << read.error;
  EXPECT_EQ(read.complete, 1);
  EXPECT_EQ(read.frames_written, 150);
  EXPECT_EQ(read.frames_stored, 150);
  EXPECT_EQ(read.scene, "first");
  EXPECT_EQ(entries(out), std::vector<std::string>({".bleedsim-manifest", "frames.h5", "frames.xmf"}))
      << "no lock, partial or swap folder left";
}

// Item 6. A run that writes no PNGs left the previous run's PNGs and contact sheet beside its own
// frames.h5; a failed run deleted the old PNGs but kept the old frames.h5.
TEST(OutputSafety, TheFolderShowsOneWholeRunNeverAMix) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path dir = scratch_folder(), out = dir / "out";
  const fs::path with_pngs = write_scene(dir, "with-pngs", 12), without = write_scene(dir, "without", 9);
  ASSERT_EQ(run_shell(run_into(with_pngs, out, "--png-every 4 --contact-sheet 3")).exit_code, 0);
  EXPECT_EQ(entries(out), std::vector<std::string>({".bleedsim-manifest", "contact_sheet.png", "frames.h5", "frames.xmf", "png"}));

  const CliResult second = run_shell(run_into(without, out));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(entries(out), std::vector<std::string>({".bleedsim-manifest", "frames.h5", "frames.xmf"}))
      << "the first run's PNGs outlived it";
  EXPECT_EQ(read_with_h5py(out / "frames.h5").scene, "without");

  // A run that fails (its file may not grow past 300 KB) leaves the last whole run as it was.
  const std::string before = read_bytes(out / "frames.h5");
  const CliResult failed = run_shell("ulimit -f 300; " + run_into(with_pngs, out, "--png-every 1 --contact-sheet 3"));
  EXPECT_EQ(failed.exit_code, 1) << failed.output;
  EXPECT_EQ(read_bytes(out / "frames.h5"), before);
  EXPECT_EQ(entries(out), std::vector<std::string>({".bleedsim-manifest", ".bleedsim-partial", "frames.h5", "frames.xmf"}));
}

// Item 4. Under `ulimit -f` the run died of SIGXFSZ without a word (exit 153). A write failure ends
// the run with exit 1 and one line naming the file and the OS error; the finished frames stay, in a
// file that opens; the last whole run is untouched.
TEST(OutputSafety, AFileSizeLimitEndsTheRunInOneLineKeepingItsFrames) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path dir = scratch_folder(), out = dir / "out";
  const fs::path scene = write_scene(dir, "limited", 60);
  ASSERT_EQ(run_shell(run_into(scene, out)).exit_code, 0);
  const std::string before = read_bytes(out / "frames.h5");
  // 2000 KiB holds some of the 60 frames, not all.
  const CliResult result = run_shell("ulimit -f 2000; " + run_into(scene, out));
  EXPECT_EQ(result.exit_code, 1) << result.output;
  const fs::path partial = out / ".bleedsim-partial" / "frames.h5.partial";
  EXPECT_EQ(result.output.rfind("bleedsim: failed: cannot write frame ", 0), 0u) << result.output;
  EXPECT_NE(result.output.find("to HDF5 file '" + partial.string() + "': File too large"), std::string::npos)
      << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_EQ(read_bytes(out / "frames.h5"), before);
  const H5Read read = read_with_h5py(partial);
  ASSERT_TRUE(read.opens) << read.error;
  EXPECT_EQ(read.complete, 0);
  EXPECT_GE(read.frames_written, 1);
  EXPECT_LT(read.frames_written, 60);
  EXPECT_NE(result.output.find(std::to_string(read.frames_written) + " finished frames kept in"), std::string::npos)
      << result.output;
}

// `script` (written to `dir`) run by sh in a user and mount namespace of its own, where it may mount
// (no privileges needed).
CliResult in_a_mount_namespace(const fs::path& dir, const std::string& script) {
  write_text(dir / "in-namespace.sh", "set -u\n" + script);
  return run_shell("unshare --user --map-root-user --mount sh " + quoted(dir / "in-namespace.sh"));
}

// A small file system of its own (tmpfs) to fill: `script` runs in it, as its working folder.
CliResult on_a_small_disk(const fs::path& dir, const std::string& size, const std::string& script) {
  return in_a_mount_namespace(dir, "T=$(mktemp -d)\nmount -t tmpfs -o size=" + size + " none \"$T\" || exit 90\ncd \"$T\"\n" +
                                       script);
}

// Whether the kernel allows user namespaces, in which a test may mount.
bool mount_namespaces_available() {
  return run_shell("unshare --user --map-root-user --mount sh -c 'mount -t tmpfs none \"$(mktemp -d)\"'").exit_code == 0;
}

// Item 4. A disk full before the first frame exited 2, as if the input were bad, and left
// frames.h5.partial; full mid-run, the message came on two lines with "bytes actually written =
// 18446744073709551615". Now: exit 1, one line with the OS error, the last whole run untouched.
TEST(OutputSafety, AFullDiskEndsTheRunInOneLineLeavingTheLastRunWhole) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  if (!mount_namespaces_available()) GTEST_SKIP() << "no user namespaces here: cannot make a small file system to fill";
  const fs::path dir = scratch_folder();
  const fs::path scene = write_scene(dir, "filling", 60), small = write_scene(dir, "small", 3);
  const std::string cli = "'" + cli_path() + "' ";
  const std::string run_small = cli + "run " + quoted(small) + " --backend cpu -q --out out";
  // Run 1 fits; run 2 fills the disk part way (mid-run); then the disk is filled outright and run 3
  // finds no room before its first frame.
  const CliResult result = on_a_small_disk(
      dir, "3m",
      run_small + "; echo run1=$?; cp out/frames.h5 saved.h5\n" +
          cli + "run " + quoted(scene) + " --backend cpu -q --out out; echo run2=$?\n"
          "cmp out/frames.h5 saved.h5 && echo kept2\n"
          "'" + python() + "' -c 'import h5py, sys; f = h5py.File(sys.argv[1], \"r\"); "
          "print(\"#\", int(f.attrs[\"complete\"]), int(f.attrs[\"frames_written\"]))' "
          "out/.bleedsim-partial/frames.h5.partial\n"
          "rm -rf out/.bleedsim-partial; cat /dev/zero > filler 2>/dev/null\n" +
          run_small + "; echo run3=$?; cmp out/frames.h5 saved.h5 && echo kept3\n");
  const std::string& o = result.output;
  EXPECT_NE(o.find("run1=0"), std::string::npos) << o;
  EXPECT_NE(o.find("run2=1"), std::string::npos) << o;
  EXPECT_NE(o.find("run3=1"), std::string::npos) << o;
  EXPECT_NE(o.find("kept2"), std::string::npos) << o;
  EXPECT_NE(o.find("kept3"), std::string::npos) << o;
  EXPECT_NE(o.find("'out/.bleedsim-partial/frames.h5.partial': No space left on device"), std::string::npos) << o;
  EXPECT_EQ(o.find("bleedsim: error:"), std::string::npos) << "a full disk is not bad input: " << o;
  EXPECT_EQ(o.find("18446744073709551615"), std::string::npos) << o;
  // Each failure is one line: "bleedsim: failed: ...".
  std::istringstream lines(o);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("bleedsim", 0) != 0 && line.rfind("run", 0) != 0 && line.rfind("kept", 0) != 0 &&
        line.rfind("# ", 0) != 0)
      ADD_FAILURE() << "a line that is no message of its own: '" << line << "' in " << o;
  // Run 2's finished frames open, and are some of its 60.
  const std::size_t at = o.find("# 0 ");
  ASSERT_NE(at, std::string::npos) << "the partial file of the run cut short did not open: " << o;
  const long kept = std::stol(o.substr(at + 4));
  EXPECT_GE(kept, 1) << o;
  EXPECT_LT(kept, 60) << o;
}

// A run killed outright (SIGKILL) stops wherever it is: the folder's last whole run is untouched,
// and the killed run's frames, each flushed as it was written, open in its partial file.
TEST(OutputSafety, AKilledRunLeavesTheLastRunWholeAndItsOwnFramesReadable) {
  BLEEDSIM_SKIP_UNLESS_H5PY();
  const fs::path dir = scratch_folder(), out = dir / "out";
  ASSERT_EQ(run_shell(run_into(write_scene(dir, "done", 3), out)).exit_code, 0);
  const std::string before = read_bytes(out / "frames.h5");
  const fs::path partial = out / ".bleedsim-partial" / "frames.h5.partial";
  const CliResult result = run_shell(
      run_into(write_scene(dir, "killed", 3000), out) + " & pid=$!; for i in $(seq 1000); do "
      "[ -s " + quoted(partial) + " ] && break; sleep 0.01; done; sleep 1; kill -KILL $pid; wait $pid; echo \"exit=$?\"");
  EXPECT_NE(result.output.find("exit=137"), std::string::npos) << result.output;
  EXPECT_EQ(read_bytes(out / "frames.h5"), before);
  const H5Read read = read_with_h5py(partial);
  ASSERT_TRUE(read.opens) << read.error;
  EXPECT_EQ(read.scene, "killed");
  EXPECT_EQ(read.complete, 0);
  EXPECT_GE(read.frames_written, 1);
}

// Issue 38, item 15: the next run cleared a killed run's finished frames without a word. It still
// clears them (the folder is the next run's), and says what it clears and where.
TEST(OutputSafety, TheNextRunSaysWhatAKilledRunLeftThatItClears) {
  const fs::path dir = scratch_folder(), out = dir / "out";
  const fs::path scene = write_scene(dir, "done", 3);
  ASSERT_EQ(run_shell(run_into(scene, out)).exit_code, 0);
  fs::create_directories(out / ".bleedsim-partial");
  write_text(out / ".bleedsim-partial" / "frames.h5.partial", "the frames a killed run wrote");
  const CliResult next = run_shell(run_into(scene, out));
  EXPECT_EQ(next.exit_code, 0) << next.output;
  EXPECT_NE(next.output.find("bleedsim: note: clearing '" + (out / ".bleedsim-partial").string() +
                             "': 1 file a killed or failed command left there (frames.h5.partial)"),
            std::string::npos)
      << next.output;
  EXPECT_FALSE(fs::exists(out / ".bleedsim-partial" / "frames.h5.partial"));
  const CliResult quiet = run_shell(run_into(scene, out));
  EXPECT_EQ(quiet.output.find("clearing"), std::string::npos) << "nothing was left to clear: " << quiet.output;
}

// The base scene of issue 38: 32 x 24 px, 0.2 s (6 frames) unless told, the spread and particles;
// quick enough to run a few hundred times.
fs::path write_small_scene(const fs::path& dir, const std::string& name, const std::string& duration_s = "0.2") {
  const fs::path file = dir / (name + ".toml");
  write_text(file, "[scene]\nname = \"" + name + "\"\nwidth_px = 32\nheight_px = 24\nwidth_mm = 16\nheight_mm = 12\n"
                   "duration_s = " + duration_s + "\n[spread]\n[particles]\ncapacity = 1024\ndesign_depth_mm = 1\n"
                   "[[cut]]\nx_mm = 8\ny_mm = 6\n[output]\npng_every = 2\ncontact_sheet = 4\n");
  return file;
}

// What a user sees in a folder: every file in it, by its path inside, with its bytes; bleedsim's own
// entries (.bleedsim-*, the lock, the manifest) aside.
std::map<std::string, std::string> visible_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    if (it->path().filename().string().rfind(".bleedsim", 0) == 0) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file()) files[fs::relative(it->path(), dir).string()] = read_bytes(it->path());
  }
  return files;
}

std::string names_of(const std::map<std::string, std::string>& files) {
  std::string names;
  for (const auto& [name, bytes] : files) names += name + " ";
  return names;
}

void copy_folder(const fs::path& from, const fs::path& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

// A folder's files by their paths inside, each as a kill test compares it.
using FolderView = std::function<std::map<std::string, std::string>(const fs::path&)>;

// Issue 38, items 1 and 4: `write`, a command that writes `out` (holding a copy of `older` each
// time), killed (BLEEDSIM_TEST_KILL_AT=N, docs/reliability.md) before each step of its swap in turn;
// and after each such kill, `recover`, a command that recovers the folder and then fails (exit 1)
// before it writes, killed before each step of the recovery in turn and then run again. Once
// recovered, the folder, as `view` reads it, always holds what `older` holds or what `newer` holds
// (what `write` writes): one whole, never a mix, never less; and no swap is left pending, which
// would stop every later command in the folder.
void expect_every_kill_to_leave_one_whole(const fs::path& out, const fs::path& older, const fs::path& newer,
                                          const std::string& write, const std::string& recover,
                                          const FolderView& view) {
  const std::map<std::string, std::string> old_files = view(older), new_files = view(newer);
  ASSERT_NE(old_files, new_files);
  const fs::path killed_state = out.string() + "-killed";
  const auto kill_at = [](int step) { return "export BLEEDSIM_TEST_KILL_AT=" + std::to_string(step) + "; "; };
  const auto expect_one_whole = [&](const std::string& when) {
    const std::map<std::string, std::string> now = view(out);
    EXPECT_TRUE(now == old_files || now == new_files) << when << ": the folder holds " << names_of(now);
    EXPECT_FALSE(fs::exists(out / ".bleedsim-swap")) << when << ": the swap was neither completed nor rolled back";
  };
  int commit_steps = 0;
  for (int step = 1; step < 100; ++step) {
    copy_folder(older, out);
    const CliResult killed = run_shell(kill_at(step) + write);
    if (killed.exit_code == 0) {
      EXPECT_TRUE(view(out) == new_files) << "not killed: the folder holds " << names_of(view(out));
      break;
    }
    ASSERT_EQ(killed.exit_code, 128 + SIGKILL) << "step " << step << ": " << killed.output;
    commit_steps = step;
    copy_folder(out, killed_state);
    for (int recovery_step = 1; recovery_step < 100; ++recovery_step) {
      copy_folder(killed_state, out);
      const std::string when = "killed at step " + std::to_string(step) + " of the swap, then at step " +
                               std::to_string(recovery_step) + " of the recovery";
      const CliResult recovery = run_shell(kill_at(recovery_step) + recover);
      if (recovery.exit_code != 128 + SIGKILL) {
        EXPECT_EQ(recovery.exit_code, 1) << when << ": " << recovery.output;
        expect_one_whole("killed at step " + std::to_string(step) + " of the swap, then recovered");
        break;
      }
      const CliResult recovered = run_shell(recover);
      EXPECT_EQ(recovered.exit_code, 1) << when << ": " << recovered.output;
      expect_one_whole(when);
    }
  }
  EXPECT_GE(commit_steps, 8) << "the swap's steps were not reached: is BLEEDSIM_TEST_KILL_AT read?";
}

// Issue 38, item 1. A kill just before the swap folder was removed left it empty; the next run's
// recovery took the folder's files, the swapped-in run's, for the last run's and deleted them. The
// swap is journaled: a run killed at any step, then one killed at any step of the recovery, leave
// the older run whole or the newer run whole, and the user's file.
TEST(OutputSafety, AKillAtAnyStepOfTheSwapLeavesOneWholeRun) {
  const fs::path dir = scratch_folder(), out = dir / "out";
  // The newer run is a frame longer, so that its frames.xmf too differs from the older one's.
  const fs::path older = write_small_scene(dir, "older"), newer = write_small_scene(dir, "newer", "0.24");
  const std::string newer_options = "--png-every 3 --contact-sheet 0";
  // The two runs as they look whole, each with a file of the user's beside it.
  ASSERT_EQ(run_shell(run_into(older, dir / "old")).exit_code, 0);
  ASSERT_EQ(run_shell(run_into(newer, dir / "new", newer_options)).exit_code, 0);
  ASSERT_NE(read_bytes(dir / "old" / "frames.xmf"), read_bytes(dir / "new" / "frames.xmf"));
  for (const char* run : {"old", "new"}) write_text(dir / run / "notes.txt", "the user's own");
  // A run that recovers the folder and then fails before its first frame is written.
  const std::string recover = "ulimit -f 1; " + run_into(older, out);

  // The reproducer: the state a kill before the last step of the old swap left.
  copy_folder(dir / "new", out);
  fs::create_directory(out / ".bleedsim-swap");
  const CliResult after_empty_swap = run_shell(recover);
  EXPECT_EQ(after_empty_swap.exit_code, 1) << after_empty_swap.output;
  EXPECT_TRUE(visible_files(out) == visible_files(dir / "new"))
      << "after an empty swap folder, the folder holds " << names_of(visible_files(out)) << ": " << after_empty_swap.output;

  expect_every_kill_to_leave_one_whole(out, dir / "old", dir / "new", run_into(newer, out, newer_options), recover,
                                       visible_files);
}

// A study of one frame of an 8 x 6 px panel, two seeds: a ladder of one level is 6 jobs, done in
// hundredths of a second, so that the study can run a few hundred times.
fs::path write_study_scene(const fs::path& dir) {
  const fs::path file = dir / "study.toml";
  write_text(file, "[scene]\nname = \"study\"\nwidth_px = 8\nheight_px = 6\nwidth_mm = 8\nheight_mm = 6\n"
                   "duration_s = 0.04\n[spread]\nradius_mm = 2\n[[cut]]\nx_mm = 4\ny_mm = 2\n");
  return file;
}

std::string study_into(const fs::path& scene, const fs::path& out, const std::string& options) {
  return "'" + cli_path() + "' study " + quoted(scene) + " --backend cpu --threads 1 --seeds 2 -q " + options +
         " --out " + quoted(out);
}

// What a study folder holds but its timings, which differ from run to run: every file the user
// sees, by its path; the tables without their time columns, study.h5's data without /timing, and a
// plot by its name alone (it draws the timings).
std::map<std::string, std::string> study_without_timings(const fs::path& dir) {
  std::map<std::string, std::string> files = visible_files(dir);
  for (auto& [name, contents] : files) {
    if (name == "study.csv" || name == "jobs.csv") contents = without_timings(contents);
    if (name == "study.h5") {
      contents.clear();
      for (const auto& [key, value] : study_data(dir / name)) contents += key + " = " + value + "\n";
    }
    if (name.rfind("plots/", 0) == 0) contents.clear();
  }
  return files;
}

// Issue 38, item 4: the same for a study's files, which are swapped in as a run's (78f8421). The
// older study has its plots (where Debian's matplotlib draws them), the newer climbs another
// ladder without them, so that each has files the other lacks.
TEST(OutputSafety, AKillAtAnyStepOfTheSwapLeavesOneWholeStudy) {
  const fs::path dir = scratch_folder(), out = dir / "out";
  const fs::path scene = write_study_scene(dir);
  const std::string older = "--knob resolution=1", newer = "--knob resolution=0.5,1 --no-plots";
  ASSERT_EQ(run_shell(study_into(scene, dir / "old", older)).exit_code, 0);
  ASSERT_EQ(run_shell(study_into(scene, dir / "new", newer)).exit_code, 0);
  for (const char* study : {"old", "new"}) write_text(dir / study / "notes.txt", "the user's own");
  // A study that recovers the folder and then fails at its first file, study.csv.
  const std::string recover = "ulimit -f 1; " + study_into(scene, out, older + " --no-plots");
  expect_every_kill_to_leave_one_whole(out, dir / "old", dir / "new", study_into(scene, out, newer), recover,
                                       study_without_timings);
}

// Issue 38, item 2. `--out` into a folder of the user's moved every name a run may write (png/,
// frames.h5, contact_sheet.png) aside and deleted it, whoever wrote it. Only what the folder's last
// run wrote, as its manifest lists, is replaced; a file of the user's that a run would write over is
// refused, before anything is written.
TEST(OutputSafety, ARunReplacesOnlyWhatTheLastRunWroteNeverAUsersFile) {
  const fs::path dir = scratch_folder(), project = dir / "proj", mine = dir / "mine";
  const fs::path scene = write_small_scene(dir, "base");
  fs::create_directories(project / "png");
  write_text(project / "png" / "fig1.png", "fig");
  for (int run = 1; run <= 2; ++run) {
    const CliResult result = run_shell("cd " + quoted(project) + " && '" + cli_path() + "' run " + quoted(scene) +
                                       " --backend cpu -q --out . --png-every 0");
    EXPECT_EQ(result.exit_code, 0) << "run " << run << ": " << result.output;
    EXPECT_EQ(read_bytes(project / "png" / "fig1.png"), "fig") << "run " << run << " deleted the user's png/";
    EXPECT_TRUE(fs::exists(project / "frames.h5")) << "run " << run;
  }

  fs::create_directories(mine);
  write_text(mine / "frames.h5", "my own data");
  write_text(mine / "contact_sheet.png", "my own sheet");
  const CliResult refused = run_shell(run_into(scene, mine));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("bleedsim: error: --out: '" + (mine / "frames.h5").string() +
                                "' was not written by a bleedsim run in this folder"),
            std::string::npos)
      << refused.output;
  EXPECT_TRUE(read_bytes(mine / "frames.h5") == "my own data") << "the user's frames.h5 was replaced";
  EXPECT_TRUE(read_bytes(mine / "contact_sheet.png") == "my own sheet") << "the user's contact_sheet.png was replaced";
  EXPECT_EQ(entries(mine), std::vector<std::string>({"contact_sheet.png", "frames.h5"})) << "nothing written";
}

// Issue 38, item 3. A swap that failed half way (a folder it must move cannot be moved) left the
// last run's frames.h5 moved aside beside its png/: a mix, with no rollback, and every rerun failed
// the same way. A failed swap is rolled back: the folder shows the last run as it was, the new run's
// files stay in the partial folder, and the message names the file and the OS error. (The failure:
// png/ is a mount point, which rename(2) refuses with EBUSY, for root too.)
TEST(OutputSafety, ASwapThatFailsHalfWayIsRolledBack) {
  if (!mount_namespaces_available()) GTEST_SKIP() << "no user namespaces here: cannot make a folder that cannot be moved";
  const fs::path dir = scratch_folder();
  const fs::path scene = write_small_scene(dir, "base");
  const std::string run = "'" + cli_path() + "' run " + quoted(scene) + " --backend cpu -q --out own";
  const CliResult result = in_a_mount_namespace(
      dir, "cd " + quoted(dir) + "\n" + run + "; echo first=$?\ncp -a own saved\n"
           "mount --bind own/png own/png || exit 90\n" +
           run + " --png-every 3; echo second=$?\n"
           "diff -r --exclude='.bleedsim*' own saved && echo unchanged\n"
           "umount own/png\n" + run + " --png-every 3; echo third=$?\nls own/png\n");
  const std::string& o = result.output;
  EXPECT_NE(o.find("first=0"), std::string::npos) << o;
  EXPECT_NE(o.find("second=1"), std::string::npos) << o;
  EXPECT_NE(o.find("bleedsim: failed: cannot move 'own/png': Device or resource busy (to 'own/.bleedsim-swap/.old/png'); "
                   "the swap was rolled back: the folder's last whole run is as it was, the new files are in "
                   "own/.bleedsim-partial\n"),
            std::string::npos)
      << o;
  EXPECT_NE(o.find("unchanged"), std::string::npos) << "the folder is not the last run as it was: " << o;
  EXPECT_NE(o.find("third=0"), std::string::npos) << o;
  EXPECT_NE(o.find("frame_000003.png"), std::string::npos) << "the third run's PNGs are not in png/: " << o;
}

}  // namespace
}  // namespace bleedsim::test
