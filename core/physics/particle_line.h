#pragma once
// A film with depth's contact line (docs/particles.md#a-film-with-depth), which
// the pinning holds, measured on a grid of nodes about line_grid_mm apart: a scale fixed in mm, so
// that the line is the same whatever the particles. (A measure at the kernel's scale is, inside a
// film, the parcels' disorder over R, which grows as the particles shrink.)
//
// Each parcel lays its volume on the four nodes around it with bilinear weights (cloud in cell), so
// that the film's depth on the nodes, and all that follows from it, moves continuously with the
// parcels: no jump when one crosses a line of the grid, which would wake a film at rest. A node's
// colour is its depth over the wetted depth, at most 1: inside a film deeper than that it is 1
// exactly, whatever the parcels' disorder, and the line lies only where the film ends. Each square
// of the grid holds |∇c|·area of line (its colour's gradient from its corners), which it gives to
// its corners by their weights, and each node to its parcels by theirs: the parcels' shares add up
// to the squares' line, which across a straight edge is the edge's length.
//
// The nodes' weights are gathered, not scattered: each node sums the parcels of the bin's cells
// within a grid step of it, in the sorted order, with no atomics: the same on every backend and
// thread. A node on a wall has the film's mirror image's weights too (twice its parcels'), so that
// its colour is the film's depth there, as the push's images make it; past the walls is a ring of
// dry nodes. A film that wets a wall has a contact line along it: the wall is a surface too, and
// its pinning holds the film there as the mucosa's does. (Without it the film's bottom row, on the
// floor's line, was squeezed along the floor by the pool above it, and a pool crept along it for
// seconds.)
#include <cmath>
#include <cstdint>

#include "core/physics/hd.h"
#include "core/physics/particle_bin.h"
#include "core/physics/particle_state.h"

namespace bleedsim {

BLEEDSIM_HD inline std::uint32_t line_node_count(const ParticleModel& m) {
  return std::uint32_t(m.line_nodes_x) * std::uint32_t(m.line_nodes_y);
}

// A parcel's bilinear weight on a node along one axis: 1 at the node, 0 a grid step away.
BLEEDSIM_HD inline float tent(float at_mm, int node, float step_mm) {
  return max_float(0.0f, 1.0f - fabsf(at_mm - float(node) * step_mm) / step_mm);
}

// A node on a wall stands for its mirror image too: twice the weight (a corner's, four times).
BLEEDSIM_HD inline float mirrored(int node, int nodes) { return node == 0 || node == nodes - 1 ? 2.0f : 1.0f; }

BLEEDSIM_HD inline float node_weight(const ParticleModel& m, float x, float y, int a, int b) {
  return tent(x, a, m.line_step_x) * mirrored(a, m.line_nodes_x) * tent(y, b, m.line_step_y) *
         mirrored(b, m.line_nodes_y);
}

// The weights of the parcels on node n (n < line_node_count), summed over the bin's cells within a
// grid step of it: row by row, each row's run of the sorted order.
BLEEDSIM_HD inline void line_node_weight(const ParticleArrays& p, const ParticleModel& m, std::uint32_t n) {
  const int a = int(n % std::uint32_t(m.line_nodes_x)), b = int(n / std::uint32_t(m.line_nodes_x));
  const float x = float(a) * m.line_step_x, y = float(b) * m.line_step_y;
  const int x0 = cell_coordinate(x - m.line_step_x, m.cell_mm, m.cells_x);
  const int x1 = cell_coordinate(x + m.line_step_x, m.cell_mm, m.cells_x);
  const int y0 = cell_coordinate(y - m.line_step_y, m.cell_mm, m.cells_y);
  const int y1 = cell_coordinate(y + m.line_step_y, m.cell_mm, m.cells_y);
  float weight = 0.0f;
  for (int row = y0; row <= y1; ++row) {
    const SortedRun run = row_run(p, m, row, x0, x1);
    for (std::uint32_t j = run.begin; j < run.end; ++j) {
      const FloatPair q = pair_at(p.sorted_position, j);
      weight += node_weight(m, q.x, q.y, a, b);
    }
  }
  p.line_weight[n] = weight;
}

// The weight on node (a, b); past the walls, where the ring of nodes around the panel is dry, 0.
BLEEDSIM_HD inline float weight_on(const ParticleArrays& p, const ParticleModel& m, int a, int b) {
  if (a < 0 || b < 0 || a >= m.line_nodes_x || b >= m.line_nodes_y) return 0.0f;
  return p.line_weight[std::uint32_t(b) * std::uint32_t(m.line_nodes_x) + std::uint32_t(a)];
}

// The line of the grid's square (a, b), its corners nodes (a, b) to (a + 1, b + 1), per unit of its
// corners' weight (mm): its share of the line for each unit of weight a parcel lays on a corner.
BLEEDSIM_HD inline float square_line_per_weight(const ParticleArrays& p, const ParticleModel& m, int a, int b) {
  const float w00 = weight_on(p, m, a, b), w10 = weight_on(p, m, a + 1, b);
  const float w01 = weight_on(p, m, a, b + 1), w11 = weight_on(p, m, a + 1, b + 1);
  const float weight = (w00 + w10) + (w01 + w11);
  if (weight == 0.0f) return 0.0f;
  const float c00 = min_float(w00 / m.wetted_weight, 1.0f), c10 = min_float(w10 / m.wetted_weight, 1.0f);
  const float c01 = min_float(w01 / m.wetted_weight, 1.0f), c11 = min_float(w11 / m.wetted_weight, 1.0f);
  // |∇c| times the square's area: the colour's rise across it along x times its height, and along y.
  const float across_x = 0.5f * ((c10 - c00) + (c11 - c01)) * m.line_step_y;
  const float across_y = 0.5f * ((c01 - c00) + (c11 - c10)) * m.line_step_x;
  return sqrtf(across_x * across_x + across_y * across_y) / weight;
}

// The share of the contact line (mm) of a parcel at (x, y): on each of the four nodes around it, its
// weight there times the line per unit weight of the four squares that node is a corner of.
BLEEDSIM_HD inline float line_share(const ParticleArrays& p, const ParticleModel& m, float x, float y) {
  const int a = cell_coordinate(x, m.line_step_x, m.line_nodes_x - 1);
  const int b = cell_coordinate(y, m.line_step_y, m.line_nodes_y - 1);
  float around[3][3];  // squares (a − 1 … a + 1, b − 1 … b + 1)
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) around[j][i] = square_line_per_weight(p, m, a - 1 + i, b - 1 + j);
  float share = 0.0f;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const float per_weight = (around[j][i] + around[j][i + 1]) + (around[j + 1][i] + around[j + 1][i + 1]);
      share += node_weight(m, x, y, a + i, b + j) * per_weight;
    }
  return share;
}

}  // namespace bleedsim
