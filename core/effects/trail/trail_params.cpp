#include "core/effects/trail/trail_params.h"

namespace bleedsim {

const ParamTable<TrailParams>& trail_table() {
  using P = TrailParams;
  static const ParamTable<P> table{
      "trail",
      "declares trails: where blood has run the tissue stays wetted and faintly stained, drying slowly "
      "(needs [particles])",
      {{"residue", ParamType::number, BLEEDSIM_MEMBER(P, residue), "", {0, 1},
        "the share of the film passing over a pixel that it leaves behind, drawn as that much blood"},
       {"drying_s", ParamType::number, BLEEDSIM_MEMBER(P, drying_s), "s", {0, 86400, true},
        "the residue fades as exp(−t / drying_s) once nothing runs over it"}},
      {}};
  return table;
}

}  // namespace bleedsim
