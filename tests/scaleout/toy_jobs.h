#pragma once
// Toy jobs for the distribution layer's tests: each job's record is a fixed function of its index,
// 0 bytes to 3 MiB long, so a result can be checked byte for byte against the job that made it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/physics/counter_hash.h"

namespace bleedsim::test {

inline std::size_t toy_record_size(std::size_t job) {
  // Empty, tiny, odd, page-sized, and past any small buffer or message size.
  static const std::size_t sizes[] = {0, 1, 7, 4096, 3 * 1048576 + 5, 0, 65537, 300000, 12, 1048576};
  return sizes[job % (sizeof sizes / sizeof sizes[0])];
}

inline std::vector<std::uint8_t> toy_record(std::size_t job) {
  std::vector<std::uint8_t> record(toy_record_size(job));
  for (std::size_t i = 0; i < record.size(); ++i)
    record[i] = std::uint8_t(counter_hash(job, i / 4, 0, 7) >> (8 * (i % 4)));
  return record;
}

// Costs that follow the sizes, as a study's would follow its frames.
inline std::vector<double> toy_costs(std::size_t jobs) {
  std::vector<double> costs;
  for (std::size_t j = 0; j < jobs; ++j) costs.push_back(1000.0 + double(toy_record_size(j)));
  return costs;
}

}  // namespace bleedsim::test
