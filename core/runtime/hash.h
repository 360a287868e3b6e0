#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace bleedsim {

// FNV-1a 64 over raw bytes: the per-frame fingerprint that goldens and parity tests compare.
inline std::uint64_t fnv1a64(const void* data, std::size_t bytes,
                             std::uint64_t hash = 0xcbf29ce484222325ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    hash ^= p[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string hex64(std::uint64_t value);

}  // namespace bleedsim
