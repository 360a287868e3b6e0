#include "core/effects/spread/spread_tiles.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "core/effects/surface/surface_stage.h"
#include "core/mesh/surface_bake.h"

namespace bleedsim {
namespace {

// The pixels [first, end) of n along one axis whose centres, (i + ½)·mm_per_px, lie within
// [from_mm, to_mm], and at least one more on each side; clamped to the panel before the conversion to int.
std::pair<int, int> pixels_within(double from_mm, double to_mm, double mm_per_px, int n) {
  const double first = std::floor(from_mm / mm_per_px - 0.5) - 1.0;
  const double end = std::ceil(to_mm / mm_per_px - 0.5) + 2.0;
  return {int(std::clamp(first, 0.0, double(n))), int(std::clamp(end, 0.0, double(n)))};
}

int tiles_along(int pixels) { return (pixels + kSpreadTilePx - 1) / kSpreadTilePx; }

template <class T>
void append(std::vector<unsigned char>& bytes, const std::vector<T>& values) {
  const auto* from = reinterpret_cast<const unsigned char*>(values.data());
  bytes.insert(bytes.end(), from, from + values.size() * sizeof(T));
}

}  // namespace

double spread_reach_per_mm(const Scene& scene) {
  if (!scene.mesh) return 1.0;
  return 1.001 / panel_stretch(scene.mesh->mesh(), texture_panel(scene.domain)).least;
}

int spread_tile_count(const PixelGrid& grid) { return tiles_along(grid.width) * tiles_along(grid.height); }

PixelBox stain_box(const SpreadCut& cut, const PixelGrid& grid, double reach_per_mm) {
  const double reach = cut.radius_mm * reach_per_mm;
  const auto [i0, i1] = pixels_within(cut.x_mm - reach, cut.x_mm + reach, grid.mm_per_px_x, grid.width);
  const auto [j0, j1] = pixels_within(cut.y_mm - reach, cut.y_mm + reach, grid.mm_per_px_y, grid.height);
  return {i0, i1, j0, j1};
}

PixelBox united(const PixelBox& a, const PixelBox& b) {
  return {std::min(a.i0, b.i0), std::max(a.i1, b.i1), std::min(a.j0, b.j0), std::max(a.j1, b.j1)};
}

void SpreadUpload::lay_out(const std::vector<SpreadCut>& cuts, int live, const PixelGrid& grid, double reach_per_mm) {
  grid_ = grid;
  live_ = live;
  across_ = tiles_along(grid.width);
  count_tiles(cuts, reach_per_mm);
  list_cuts();
  // The cuts first, at the block's start, which the backends align for them; the ints after them
  // start on a multiple of 16 bytes.
  bytes_.clear();
  append(bytes_, cuts);
  first_at_ = bytes_.size();
  append(bytes_, first_);
  cut_at_ = bytes_.size();
  append(bytes_, cut_);
}

// Which tiles each live cut may reach (those its stain box touches), and how many cuts each tile
// lists, as offsets: first_[t + 1] − first_[t].
void SpreadUpload::count_tiles(const std::vector<SpreadCut>& cuts, double reach_per_mm) {
  first_.assign(std::size_t(spread_tile_count(grid_)) + 1, 0);
  reached_.clear();
  std::int64_t listed = 0;
  for (std::size_t c = std::size_t(live_); c < cuts.size(); ++c) {
    const PixelBox box = stain_box(cuts[c], grid_, reach_per_mm);
    TileBox tiles{0, 0, 0, 0};  // none, for a cut wholly off the panel
    if (box.i1 > box.i0 && box.j1 > box.j0)
      tiles = {box.i0 / kSpreadTilePx, (box.i1 - 1) / kSpreadTilePx + 1, box.j0 / kSpreadTilePx,
               (box.j1 - 1) / kSpreadTilePx + 1};
    reached_.push_back(tiles);
    for (int y = tiles.y0; y < tiles.y1; ++y)
      for (int x = tiles.x0; x < tiles.x1; ++x) ++first_[std::size_t(y) * across_ + x + 1];
    listed += std::int64_t(tiles.x1 - tiles.x0) * (tiles.y1 - tiles.y0);
  }
  // The device indexes the lists with int.
  if (listed > INT_MAX) throw std::length_error("the spread's tile lists would hold more than 2^31 - 1 cuts");
  std::partial_sum(first_.begin(), first_.end(), first_.begin());
}

// Each live cut's index into the list of every tile it may reach, cut by cut in the frame's order,
// so that every list ascends and a pixel multiplies its cuts in the order of the product over all.
void SpreadUpload::list_cuts() {
  next_.assign(first_.begin(), first_.end() - 1);
  cut_.resize(std::size_t(first_.back()));
  for (std::size_t k = 0; k < reached_.size(); ++k) {
    const TileBox& tiles = reached_[k];
    for (int y = tiles.y0; y < tiles.y1; ++y)
      for (int x = tiles.x0; x < tiles.x1; ++x) cut_[std::size_t(next_[std::size_t(y) * across_ + x]++)] = int(k);
  }
}

SpreadPixel SpreadUpload::pixel_work(const void* at, float* stain, const SurfaceMap& surface,
                                     const float* settled) const {
  const auto* block = static_cast<const unsigned char*>(at);
  const SpreadTiles tiles{reinterpret_cast<const int*>(block + first_at_),
                          reinterpret_cast<const int*>(block + cut_at_), across_};
  return {reinterpret_cast<const SpreadCut*>(block) + live_, tiles, grid_, stain, surface, settled};
}

}  // namespace bleedsim
