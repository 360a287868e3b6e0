#pragma once
// Trails (docs/optics.md, "Trails"): where blood has run, the tissue stays wetted and faintly
// stained. Each frame a pixel keeps the larger of its residue, dried by one frame, and its share of
// the film over it now: r ← max(r · decay, residue · h), decay = exp(−1 / (frame rate · drying_s))
// computed once on the host. Once nothing runs over it, a pixel's residue so fades as
// exp(−t / drying_s). The blend draws it as that much blood. Where the suction's tip passed this
// frame (its reach around the segments of its path), it took the wetting too: the residue is 0.
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
  const float* sweep = nullptr;  // the suction's path this frame: segments (x0, y0, x1, y1), mm
  int sweep_segments = 0;
  float reach_sq = 0.0f;         // the suction's radius², mm²
  // The path's bounds grown by more than the reach (sweep_trail): no pixel outside them is within
  // reach, so most pixels test no segment (a stylus' frame is some 34 of them).
  float sweep_box[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // min x, min y, max x, max y, mm

  BLEEDSIM_HD int width() const { return grid.width; }
  BLEEDSIM_HD int height() const { return grid.height; }
  BLEEDSIM_HD void operator()(int i, int j) const {
    const std::size_t p = std::size_t(j) * grid.width + i;
    const bool sucked = sweep_segments > 0 && swept(pixel_centre_x_mm(grid, i), pixel_centre_y_mm(grid, j));
    residue_mm[p] = sucked ? 0.0f : max_float(residue_mm[p] * decay, residue * film_mm[p]);
  }

  // Whether (x, y) lies within the reach of a segment: its distance² to the segment's nearest point.
  BLEEDSIM_HD bool swept(float x, float y) const {
    if (x < sweep_box[0] || y < sweep_box[1] || x > sweep_box[2] || y > sweep_box[3]) return false;
    for (int k = 0; k < sweep_segments; ++k) {
      const float* s = sweep + 4 * k;
      const float ux = s[2] - s[0], uy = s[3] - s[1], u2 = ux * ux + uy * uy;
      const float along = u2 > 0.0f ? min_float(max_float(((x - s[0]) * ux + (y - s[1]) * uy) / u2, 0.0f), 1.0f) : 0.0f;
      const float dx = x - (s[0] + along * ux), dy = y - (s[1] + along * uy);
      if (dx * dx + dy * dy <= reach_sq) return true;
    }
    return false;
  }
};

}  // namespace bleedsim
