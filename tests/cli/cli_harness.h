#pragma once
// Runs the bleedsim CLI as a user would, in a scratch folder of its own per test.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/test_paths.h"

namespace bleedsim::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `shell_prefix` runs before the CLI in the same shell (e.g. "ulimit -v 4000000;").
inline CliResult run_shell(const std::string& command) {
  CliResult result;
  FILE* pipe = popen(("(" + command + ") 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> chunk;
  while (std::size_t n = std::fread(chunk.data(), 1, chunk.size(), pipe)) result.output.append(chunk.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

inline CliResult run_cli(const std::string& arguments, const std::string& shell_prefix = "") {
  return run_shell(shell_prefix + " '" + cli_path() + "' " + arguments);
}

// Whether `ulimit -v` can cap this build's CLI: an AddressSanitizer build reserves terabytes of
// address space at start and cannot run under any such limit.
inline bool address_space_can_be_limited() {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return false;
#endif
#endif
  return true;
}
#define BLEEDSIM_SKIP_UNLESS_ADDRESS_SPACE_CAN_BE_LIMITED()                                                   \
  if (!::bleedsim::test::address_space_can_be_limited())                                                     \
  GTEST_SKIP() << "ulimit -v cannot cap an AddressSanitizer build (it reserves terabytes of address space); " \
                  "the Release build runs this test"

// Whether the tests' Python has h5py, the independent reader some tests read a run's HDF5 file back
// with. The GPU machine's Python has none: there those tests skip, saying so; CI installs h5py
// (scripts/setup) and runs them.
inline bool python_has_h5py() { return run_shell("'" + python() + "' -c 'import h5py'").exit_code == 0; }
#define BLEEDSIM_SKIP_UNLESS_H5PY()                                                                     \
  if (!::bleedsim::test::python_has_h5py())                                                            \
  GTEST_SKIP() << ::bleedsim::test::python() << " has no h5py, the independent reader this test reads " \
               << "the HDF5 file back with: NOT checked here (CI runs it)"

// A fresh, empty folder for the running test.
inline std::filesystem::path scratch_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(binary_dir()) / "test-scratch" / info->test_suite_name() / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace bleedsim::test
