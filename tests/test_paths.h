#pragma once
// Where tests find the repository, the CLI and a scratch folder: the environment's, else the
// build's (scripts/gpu-check runs binaries built here with the tree in another folder on the GPU
// machine). A test reads the tree through source_dir() alone: the build's path is compiled in under
// a name of its own, for this file, and tests/source_elsewhere_check.py runs the tests with it hidden.
#include <cstdlib>
#include <string>

namespace bleedsim::test {

inline std::string from_env_or(const char* name, const char* fallback) {
  const char* value = std::getenv(name);
  return value && *value ? value : fallback;
}

inline std::string source_dir() { return from_env_or("BLEEDSIM_SOURCE_DIR", BLEEDSIM_SOURCE_DIR_AS_BUILT); }
// Debian's Python, which has h5py (the first python3 on PATH may not).
inline std::string python() { return from_env_or("BLEEDSIM_PYTHON", "/usr/bin/python3"); }
#ifdef BLEEDSIM_BINARY_DIR
inline std::string binary_dir() { return from_env_or("BLEEDSIM_BINARY_DIR", BLEEDSIM_BINARY_DIR); }
#endif
#ifdef BLEEDSIM_CLI
inline std::string cli_path() { return from_env_or("BLEEDSIM_CLI", BLEEDSIM_CLI); }
#endif

}  // namespace bleedsim::test
