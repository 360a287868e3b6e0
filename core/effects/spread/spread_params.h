#pragma once
// The radial spread's parameters (report §2.2.1; docs/scenario-format.md, [spread]).
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for the spread. The cuts that give no size of
// their own take these.
struct SpreadParams {
  double radius_mm = 4.0;
  double growth_per_s = 0.5;
};

const ParamTable<SpreadParams>& spread_table();
// Its row: the spread stage (spread_stage.cpp).
const Effect<SpreadParams>& spread_effect();

}  // namespace bleedsim
