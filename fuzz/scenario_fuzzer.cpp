// The scenario reader (core/io/scenario.h) on any bytes: it must refuse them with an InputError or
// accept them, never crash, overflow, read out of bounds or run out of memory. The text is read as
// a file in scenarios/, so the seeds' relative paths reach the real traces and textures (read as
// `bleedsim validate` reads them: a texture's header only, no tissue drawn).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    bleedsim::parse_scenario(text, BLEEDSIM_SOURCE_DIR "/scenarios/fuzzed.toml", bleedsim::ReadTissue::header_only);
  } catch (const bleedsim::InputError&) {
  }
  return 0;
}
