// tests/check_hdf5_layout.py, the layout checker users run on a frames.h5, against what the HDF5
// frame writer writes: the same layout passes, a file without provenance or with an image where an
// array is named fails.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/io/hdf5_samples.h"
#include "tests/test_paths.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;
using namespace test;

// --- The layout checker script -----------------------------------------------------------------

// Runs tests/check_hdf5_layout.py as a user would; its exit status.
int run_layout_checker(const fs::path& file, const std::string& more_arguments = "") {
  const std::string command = "'" + test::python() + "' '" + test::source_dir() +
                              "/tests/check_hdf5_layout.py' '" + file.string() +
                              "' --frames 3 --width 7 --height 5 --fields spread/stain" +
                              more_arguments;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The writer and the checker describe one layout: a full file passes, one without a provenance
// attribute fails.
TEST(Hdf5LayoutChecker, AcceptsWhatTheWriterWritesAndRejectsMissingProvenance) {
  const std::string has_h5py = "'" + test::python() + "' -c 'import h5py' >/dev/null 2>&1";
  if (std::system(has_h5py.c_str()) != 0)
    GTEST_SKIP() << test::python() << " has no h5py (BLEEDSIM_PYTHON may name one that has)";
  const fs::path folder = test_folder();
  Attributes provenance = {{"bleedsim_version", "0.1.0"}, {"git_sha", "0123456789abcdef"},
                           {"backend", "reference_cpu"},  {"device", "test host"},
                           {"build_flags", "-O2"},        {"scenario_text", "[spread]\n"}};
  write_sample(folder / "good.h5", 4, provenance);
  EXPECT_EQ(run_layout_checker(folder / "good.h5"), 0);

  provenance.erase(provenance.begin() + 1);  // git_sha
  write_sample(folder / "no_git_sha.h5", 4, provenance);
  EXPECT_EQ(run_layout_checker(folder / "no_git_sha.h5"), 1);
}

// Per-element arrays pass as (T, N[, C]) without image attributes; an image named as one fails.
TEST(Hdf5LayoutChecker, AcceptsNonImageArraysAndRejectsAnImageNamedAsOne) {
  const std::string has_h5py = "'" + test::python() + "' -c 'import h5py' >/dev/null 2>&1";
  if (std::system(has_h5py.c_str()) != 0)
    GTEST_SKIP() << test::python() << " has no h5py (BLEEDSIM_PYTHON may name one that has)";
  const fs::path folder = test_folder();
  const Attributes provenance = {{"bleedsim_version", "0.1.0"}, {"git_sha", "0123456789abcdef"},
                                 {"backend", "reference_cpu"},  {"device", "test host"},
                                 {"build_flags", "-O2"},        {"scenario_text", "[spread]\n"}};
  write_array_sample(folder / "arrays.h5", 4, provenance);
  EXPECT_EQ(run_layout_checker(folder / "arrays.h5"), 0);  // arrays not asked for: ignored
  EXPECT_EQ(run_layout_checker(folder / "arrays.h5",
                               " --arrays particles/position,particles/accounting,particles/id"),
            0);
  // /spread/stain is (T, H, W) and an HDF5 image: CLASS gives it away.
  EXPECT_EQ(run_layout_checker(folder / "arrays.h5", " --arrays particles/position,spread/stain"),
            1);
  EXPECT_EQ(run_layout_checker(folder / "arrays.h5", " --arrays particles/missing"), 1);
}

}  // namespace
}  // namespace bleedsim
