#pragma once
#include <cstddef>
#include <string>

#include "core/runtime/input_error.h"
#include "core/runtime/scene.h"

namespace bleedsim {

// Host memory this process can still take: the least of the memory the kernel reports available,
// the cgroup's limit, and the address-space limit (ulimit -v), each less what is already in use.
std::size_t available_host_memory();

// Refuses a scene too large for this machine before anything is allocated: throws InputError for
// scene.width_px (at `where`, when the scene came from a file) naming the size, what it needs and
// what `room` there is in `memory_kind`.
void require_room(const Scene& scene, std::size_t need, std::size_t room, const std::string& memory_kind,
                  const SourcePlace& where = {});

// "1.50 GiB", "312 MiB", "4.0 KiB", "17 B".
std::string human_bytes(double bytes);

}  // namespace bleedsim
