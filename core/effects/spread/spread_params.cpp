#include "core/effects/spread/spread_params.h"

namespace bleedsim {

const ParamTable<SpreadParams>& spread_table() {
  using P = SpreadParams;
  static const ParamTable<P> table{
      "spread",
      "declares the radial spread of blood from the cuts; its keys are the defaults of cuts that give none",
      {{"radius_mm", ParamType::number, BLEEDSIM_MEMBER(P, radius_mm), "mm", {0, 1e4, true},
        "radius of a cut's stain"},
       {"growth_per_s", ParamType::number, BLEEDSIM_MEMBER(P, growth_per_s), "1/s", {0, 1000, true},
        "how fast a stain grows: full 1 / growth_per_s seconds after its cut"}},
      {}};
  return table;
}

}  // namespace bleedsim
