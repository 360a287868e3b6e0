#pragma once
// The suction at the instrument's tip (docs/bleeding.md, "Suction"): it takes the blood within its
// reach, nearest first, up to its flow. A hook in the particle step (suction_hook.h).
#include <cstdint>

#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for suction; needs [particles] and an instrument.
struct SuctionParams {
  double radius_mm = 1.5;             // particle centres within this of the tip are within reach
  double max_flow_mm3_per_s = 30.0;   // the most blood it takes a second
  std::uint8_t buttons = 0x2;         // with the stylus: the grip buttons that turn it on, in contact
};

const ParamTable<SuctionParams>& suction_table();
const Effect<SuctionParams>& suction_effect();

}  // namespace bleedsim
