#pragma once
// The host's half of the spread's tiles (core/physics/spread.h): which pixels a cut's stain may
// reach, and which cuts each tile lists, laid out behind the cuts so that a frame uploads both in
// one copy (Backend::upload is a synchronous copy on CUDA). Bounds are in double and generous: a
// pixel more on every side than the reach, far beyond what float rounding can move a pixel's
// centre or a cut's offset, so a pixel outside them gets exactly 0 from the cut.
#include <cstddef>
#include <vector>

#include "core/physics/spread.h"
#include "core/scene/scene.h"

namespace bleedsim {

// Panel mm a cut's stain may reach per mm of its radius: 1 on the flat panel; on a tissue mesh
// 1/σ, σ the texture's least stretch (a stain of radius r reaches r/σ across the panel), with a
// thousandth to spare (the texels' frames are their triangles', to float rounding).
double spread_reach_per_mm(const Scene& scene);

// The panel's tiles: ⌈width / kSpreadTilePx⌉ × ⌈height / kSpreadTilePx⌉.
int spread_tile_count(const PixelGrid& grid);

// Pixels [i0, i1) × [j0, j1); empty where i1 ≤ i0 or j1 ≤ j0.
struct PixelBox {
  int i0, i1, j0, j1;
};

// Every pixel `cut` may stain, clamped to the panel: those whose centres lie within its radius ×
// reach_per_mm along x and along y, and at least one more on each side.
PixelBox stain_box(const SpreadCut& cut, const PixelGrid& grid, double reach_per_mm);

// The box from the least of both starts to the greatest of both ends.
PixelBox united(const PixelBox& a, const PixelBox& b);

// One frame's cuts as the spread uploads them, in one block: the cuts, then the tile table
// (SpreadTiles) of those from `live` on, the ones SpreadPixel multiplies in (those before it are
// for SpreadSettle). Keeps its scratch between frames.
class SpreadUpload {
 public:
  // Lays out `cuts` and the tile table of cuts [live, end) over `grid`; reach_per_mm is
  // spread_reach_per_mm's.
  void lay_out(const std::vector<SpreadCut>& cuts, int live, const PixelGrid& grid, double reach_per_mm);
  // The block to copy (its cuts at the start, 16-byte aligned, as SpreadCut asks).
  const std::vector<unsigned char>& bytes() const { return bytes_; }
  // The pixel work over the block once copied to `at` (device memory; on the CPU, any host copy).
  SpreadPixel pixel_work(const void* at, float* stain, const SurfaceMap& surface = {},
                         const float* settled = nullptr) const;

 private:
  // The tiles a box of pixels touches: [x0, x1) × [y0, y1) in tiles.
  struct TileBox {
    int x0, x1, y0, y1;
  };
  void count_tiles(const std::vector<SpreadCut>& cuts, double reach_per_mm);
  void list_cuts();

  PixelGrid grid_;
  int live_ = 0;
  int across_ = 0;
  std::size_t first_at_ = 0, cut_at_ = 0;  // where first_ and cut_ lie in the block
  std::vector<TileBox> reached_;  // per live cut
  std::vector<int> first_;        // the table: tiles + 1 offsets ...
  std::vector<int> cut_;          // ... into the live cuts' indices
  std::vector<int> next_;         // per tile, where its next index goes while listing
  std::vector<unsigned char> bytes_;
};

}  // namespace bleedsim
