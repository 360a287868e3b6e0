#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "core/runtime/count.h"
#include "core/runtime/input_error.h"

namespace bleedsim {

// Host memory this process can still take: the least of the memory the kernel reports available,
// the cgroup's limit, and the address-space limit (ulimit -v), each less what is already in use.
std::size_t available_host_memory();

// Part of what a run will allocate, under the scenario key that sets its size ("scene.width_px"
// for a panel-sized field, "particles.capacity" for the ring buffer), with what it is for.
struct MemoryPart {
  std::string key;
  std::string what;  // "the 640 x 480 px panel", "268435456 particle slots"
  Count bytes;
};
using MemoryParts = std::vector<MemoryPart>;

// The parts added up, those under one key merged (the first one's `what` kept), largest first.
MemoryParts merged(const MemoryParts& parts);
Count total_bytes(const MemoryParts& parts);
// Each part `factor` times over (a CPU run keeps a host copy of every field beside it).
MemoryParts times(const MemoryParts& parts, std::uint64_t factor);

// Refuses a need larger than the room before anything is allocated: throws InputError at `where`
// for the key of the largest part, naming what it needs, what each part takes and what `room`
// there is in `memory_kind` ("host", "device").
void require_memory(const MemoryParts& parts, std::size_t room, const std::string& memory_kind,
                    const SourcePlace& where = {});

// "1.50 GiB", "312 MiB", "4.0 KiB", "17 B".
std::string human_bytes(double bytes);

}  // namespace bleedsim
