// The spread's tiles (core/physics/spread.h, core/effects/spread/spread_tiles.h): a pixel multiplies in only
// the cuts its tile lists. Leaving a cut out is exact only where its stain at the pixel is exactly 0
// (light · (1 − 0) is light to the bit), and the lists must keep the cuts' order; then the stain is,
// byte for byte, the product over every cut (spread_stain). Checked, with every pixel a cut stains
// found in its tile's list, for cuts on and across tile borders and corners, partly and wholly off
// the panel, far smaller and larger than a tile, piled on one another, below full strength, on a
// panel whose sides are not multiples of a tile; on the flat panel and on the turbinate, whose
// texture stretches a stain's reach 0.6 to 1.7 times. And that the lists do leave cuts out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "core/effects/spread/spread_tiles.h"
#include "core/physics/spread.h"
#include "tests/effects/turbinate_scene.h"
#include "tests/runtime/scenes_in_code.h"

namespace bleedsim {
namespace {

float width_mm(const PixelGrid& g) { return float(g.width) * g.mm_per_px_x; }
float height_mm(const PixelGrid& g) { return float(g.height) * g.mm_per_px_y; }

// Cuts that test the tiles' edges, in panel mm: a tile is tx × ty mm.
std::vector<SpreadCut> awkward_cuts(const PixelGrid& g) {
  const float px = g.mm_per_px_x, py = g.mm_per_px_y;
  const float tx = kSpreadTilePx * px, ty = kSpreadTilePx * py, w = width_mm(g), h = height_mm(g);
  std::vector<SpreadCut> cuts = {
      {tx, ty, 0.3f * tx, 0.9f},                      // on a tile corner
      {2.0f * tx, 1.5f * ty, 0.5f * tx, 0.6f},        // on a border between columns of tiles
      {2.5f * tx, 2.0f * ty, 0.5f * ty, 0.6f},        // on a border between rows
      {16.5f * px, 10.5f * py, 16.0f * px, 0.8f},     // its edge on the centre of the next tile's first pixel
      {10.5f * px, 16.5f * py, 16.0f * py, 0.8f},     // ... below
      {-0.5f * tx, 0.5f * h, tx, 1.0f},               // half off the left side
      {w + 0.3f * tx, h - 0.2f * ty, 0.8f * tx, 0.7f},  // mostly off the bottom right corner
      {0.5f * w, -0.2f * ty, 0.6f * tx, 0.5f},        // off the top
      {-3.0f * tx, -3.0f * ty, tx, 1.0f},             // wholly off the panel
      {40.5f * px, 40.5f * py, 0.01f * px, 1.0f},     // far smaller than a pixel, on a pixel's centre
      {41.0f * px, 41.0f * py, 0.01f * px, 1.0f},     // ... between centres: it stains none
      {0.5f * w, 0.5f * h, 2.5f * tx, 0.4f},          // wider than two tiles
  };
  for (int k = 0; k < 5; ++k)  // piled on one spot across a corner
    cuts.push_back(
        {3.0f * tx + 0.1f * k * px, 2.0f * ty - 0.1f * k * py, (0.2f + 0.3f * k) * tx, 0.15f * float(k + 1)});
  // And more anywhere over the panel and a tile beyond, from a fixed seed.
  std::mt19937 draw(17);
  std::uniform_real_distribution<float> x(-tx, w + tx), y(-ty, h + ty), radius(0.01f, 1.5f), amplitude(0.05f, 1.0f);
  for (int k = 0; k < 80; ++k) cuts.push_back({x(draw), y(draw), radius(draw) * tx, amplitude(draw)});
  return cuts;
}

// The live cuts [live, end) through the tiles, against spread_stain over all of them, pixel by pixel
// and byte for byte; and every pixel a live cut stains lies in a tile that lists it, in order.
void expect_tiles_exact(const std::vector<SpreadCut>& cuts, int live, const PixelGrid& grid, const SurfaceMap& surface,
                        double reach_per_mm) {
  SpreadUpload upload;
  upload.lay_out(cuts, live, grid, reach_per_mm);
  std::vector<float> stain(std::size_t(grid.width) * grid.height);
  // On the CPU the block needs no copy: the work reads it where it was laid out.
  const SpreadPixel work = upload.pixel_work(upload.bytes().data(), stain.data(), surface);
  const SpreadTiles& tiles = work.tiles;
  for (int t = 0; t < spread_tile_count(grid); ++t)
    ASSERT_TRUE(std::is_sorted(tiles.cut + tiles.first[t], tiles.cut + tiles.first[t + 1])) << "tile " << t;

  const int live_count = int(cuts.size()) - live;
  long stained = 0;  // (pixel, cut) pairs where the cut's stain is not 0
  long skipped = 0;  // (pixel, cut) pairs the pixel's tile leaves out
  for (int j = 0; j < grid.height; ++j)
    for (int i = 0; i < grid.width; ++i) {
      work(i, j);
      const float got = stain[std::size_t(j) * grid.width + i];
      const float all = spread_stain(cuts.data() + live, live_count, grid, i, j, surface);
      ASSERT_EQ(std::memcmp(&got, &all, sizeof got), 0)
          << "pixel (" << i << ", " << j << "): " << got << " through its tile, " << all << " from every cut";
      const float x = pixel_centre_x_mm(grid, i), y = pixel_centre_y_mm(grid, j);
      const SurfaceFrame frame = curved(surface) ? frame_of(surface, std::size_t(j) * grid.width + i) : SurfaceFrame{};
      const int t = tile_of(tiles, i, j);
      skipped += live_count - (tiles.first[t + 1] - tiles.first[t]);
      for (int c = 0; c < live_count; ++c) {
        if (cut_stain(cuts[std::size_t(live + c)], x, y, curved(surface) ? &frame : nullptr) == 0.0f) continue;
        ++stained;
        ASSERT_TRUE(std::binary_search(tiles.cut + tiles.first[t], tiles.cut + tiles.first[t + 1], c))
            << "cut " << c << " stains pixel (" << i << ", " << j << ") but tile " << t << " does not list it";
      }
    }
  // Not bounds: that the cuts stain the panel, and that the tiles leave some of them out.
  EXPECT_GT(stained, 0);
  EXPECT_GT(skipped, 0);
}

// 150 × 100 px: 4⅔ × 3⅛ tiles. Non-square pixels (0.2 × 0.25 mm).
const PixelGrid kPanel{150, 100, 0.2f, 0.25f};

TEST(SpreadTiles, StainThroughTheTilesIsTheStainOfEveryCutOnThePanel) {
  expect_tiles_exact(awkward_cuts(kPanel), 0, kPanel, {}, 1.0);
}

TEST(SpreadTiles, IndexTheLiveCutsBehindTheSettlingOnes) {
  // The stage lays the settling cuts out first; the table counts from the first live one.
  expect_tiles_exact(awkward_cuts(kPanel), 7, kPanel, {}, 1.0);
}

TEST(SpreadTiles, StainThroughTheTilesIsTheStainOfEveryCutOnTheTurbinate) {
  Scene scene = test::scene_in_code(true);
  const SurfaceMaps maps = test::lay_on_turbinate(scene, Domain{150, 70, 40.0, 16.0});
  const PixelGrid grid = scene.domain.grid();
  const SurfaceMap surface{maps.frame.data(), maps.gravity.data(), grid};
  expect_tiles_exact(awkward_cuts(grid), 0, grid, surface, spread_reach_per_mm(scene));
}

// The tiles listing cut c.
int tiles_listing(const SpreadTiles& tiles, int tile_count, int c) {
  int n = 0;
  for (int t = 0; t < tile_count; ++t)
    n += int(std::count(tiles.cut + tiles.first[t], tiles.cut + tiles.first[t + 1], c));
  return n;
}

TEST(SpreadTiles, ListACutOnlyInTheTilesItReaches) {
  // 256 × 192 px at 0.1 mm: 8 × 6 tiles of 3.2 mm.
  const PixelGrid grid{256, 192, 0.1f, 0.1f};
  const std::vector<SpreadCut> cuts = {
      {1.0f, 1.0f, 1.0f, 1.0f},     // top left: pixels 0–19 × 0–19, tile (0, 0)
      {24.6f, 18.2f, 1.0f, 1.0f},   // bottom right: pixels 236–255 × 172–191, tile (7, 5)
      {-9.0f, 30.0f, 2.0f, 1.0f},   // off the panel
      {12.8f, 9.6f, 4.0f, 0.5f},    // wider than a tile: pixels 88–167 × 56–135, tiles 2–5 × 1–4
  };
  SpreadUpload upload;
  upload.lay_out(cuts, 0, grid, 1.0);
  std::vector<float> stain(std::size_t(grid.width) * grid.height);
  const SpreadTiles tiles = upload.pixel_work(upload.bytes().data(), stain.data()).tiles;
  const int count = spread_tile_count(grid);
  ASSERT_EQ(count, 48);
  // A pixel in the top left tile walks one cut, not four; one in the bottom right, another one.
  EXPECT_EQ(std::vector<int>(tiles.cut + tiles.first[0], tiles.cut + tiles.first[1]), std::vector<int>{0});
  EXPECT_EQ(std::vector<int>(tiles.cut + tiles.first[count - 1], tiles.cut + tiles.first[count]), std::vector<int>{1});
  EXPECT_EQ(tiles_listing(tiles, count, 0), 1);
  EXPECT_EQ(tiles_listing(tiles, count, 1), 1);
  EXPECT_EQ(tiles_listing(tiles, count, 2), 0);
  EXPECT_EQ(tiles_listing(tiles, count, 3), 16);
  EXPECT_EQ(tiles.first[count], 18);  // nothing else listed
}

}  // namespace
}  // namespace bleedsim
