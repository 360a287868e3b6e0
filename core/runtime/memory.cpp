#include "core/runtime/memory.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace bleedsim {
namespace {

constexpr std::size_t kUnknown = std::numeric_limits<std::size_t>::max();

// A "Key:   123 kB" line of a /proc file, in bytes.
std::size_t proc_kib_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) != 0) continue;
    std::istringstream fields(line.substr(key.size()));
    std::size_t kib = 0;
    if (fields >> kib) return kib * 1024;
  }
  return kUnknown;
}

std::size_t read_number(const char* file) {
  std::ifstream in(file);
  std::size_t value = 0;
  return (in >> value) ? value : kUnknown;  // "max" reads as no number: no limit
}

std::size_t cgroup_room() {
  const std::size_t limit = read_number("/sys/fs/cgroup/memory.max");
  const std::size_t used = read_number("/sys/fs/cgroup/memory.current");
  if (limit == kUnknown || used == kUnknown) return kUnknown;
  return limit > used ? limit - used : 0;
}

std::size_t address_space_room() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnknown;
  const std::size_t used = proc_kib_field("/proc/self/status", "VmSize:");
  if (used == kUnknown) return limit.rlim_cur;
  return limit.rlim_cur > used ? limit.rlim_cur - used : 0;
}

}  // namespace

std::size_t available_host_memory() {
  return std::min({proc_kib_field("/proc/meminfo", "MemAvailable:"), cgroup_room(),
                   address_space_room()});
}

MemoryParts merged(const MemoryParts& parts) {
  MemoryParts out;
  for (const MemoryPart& part : parts) {
    const auto same = std::find_if(out.begin(), out.end(), [&](const MemoryPart& p) { return p.key == part.key; });
    if (same == out.end()) out.push_back(part);
    else same->bytes += part.bytes;
  }
  std::stable_sort(out.begin(), out.end(), [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  return out;
}

Count total_bytes(const MemoryParts& parts) {
  Count total = 0;
  for (const MemoryPart& part : parts) total += part.bytes;
  return total;
}

MemoryParts times(const MemoryParts& parts, std::uint64_t factor) {
  MemoryParts out = parts;
  for (MemoryPart& part : out) part.bytes *= factor;
  return out;
}

void require_memory(const MemoryParts& parts, std::size_t room, const std::string& memory_kind,
                    const SourcePlace& where) {
  const Count need = total_bytes(parts);
  if (need <= Count(room)) return;
  const MemoryParts by_key = merged(parts);
  // The parts that matter: the largest, and any other of at least a hundredth of the need.
  std::string items;
  for (const MemoryPart& part : by_key)
    if (items.empty() || part.bytes.as_double() >= need.as_double() / 100)
      items += (items.empty() ? "" : ", ") + human_bytes(part.bytes.as_double()) + " for " + part.what;
  throw InputError(where, by_key.front().key,
                   "this scene needs " + human_bytes(need.as_double()) + " of " + memory_kind + " memory (" + items +
                       "), but only " + human_bytes(double(room)) + " is available");
}

std::string human_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 4) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.2f %s", bytes, units[unit]);
  return text;
}

}  // namespace bleedsim
