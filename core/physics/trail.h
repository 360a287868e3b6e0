#pragma once
// Trails (docs/optics.md, "Trails"): where blood has run, the tissue stays wetted and faintly
// stained. Each frame a pixel keeps the larger of its residue, dried by one frame, and its share of
// the film over it now: r ← max(r · decay, residue · h), decay = exp(−1 / (frame rate · drying_s))
// computed once on the host. Once nothing runs over it, a pixel's residue so fades as
// exp(−t / drying_s). The blend draws it as that much blood.
#include <cmath>
#include <cstddef>

#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

struct TrailPixel {
  const float* film_mm;  // the particles' film this frame
  float* residue_mm;     // updated in place: each pixel reads and writes only itself
  float residue;         // the share of the film left behind
  float decay;           // one frame's drying
  PixelGrid grid;

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    residue_mm[p] = fmaxf(residue_mm[p] * decay, residue * film_mm[p]);
  }
};

}  // namespace bleedsim
