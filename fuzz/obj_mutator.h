#pragma once
// Mutations of a Wavefront OBJ text that keep it mostly OBJ, so that the mesh fuzzer's inputs pass
// the reader's first checks and reach the later ones (the indices, the ear clipping, the surface):
// lines inserted, deleted, duplicated and swapped; a number or a corner replaced by a value at the
// edge of what the reader takes; a face given more or fewer corners, or its corners reordered; a
// polygon added that is non-convex, crosses itself or has no area.
#include <random>
#include <string>

namespace bleedsim::fuzz {

// `text` after one such mutation, chosen by `rng`.
std::string mutate_obj(const std::string& text, std::minstd_rand& rng);

}  // namespace bleedsim::fuzz
