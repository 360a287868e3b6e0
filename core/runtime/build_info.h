#pragma once
// What built this binary, recorded in every output file.
namespace bleedsim {
const char* version();
const char* git_sha();
const char* build_flags();
bool built_with_cuda();
}  // namespace bleedsim
