#pragma once
// Scene: everything read-only that a run needs (MuJoCo's "model"): the panel, time, the tissue,
// the instrument, the cuts, and the effects the scene calls for with their parameters. Built by a
// host program in code, or from a scenario file by core/io/scenario.h, which keeps the file's text,
// where each key was written and the output settings beside the Scene, not in it. State holds
// everything that changes. The scene knows no effect by name: Scene::effects holds each one's
// parameters by their type (core/effects/effect_list.h lists them).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh_surface.h"
#include "core/physics/pixel_grid.h"
#include "core/runtime/count.h"
#include "core/runtime/image.h"
#include "core/runtime/memory.h"
#include "core/runtime/params.h"
#include "core/runtime/type_map.h"
#include "core/scene/cut.h"
#include "core/scene/stylus.h"
#include "core/scene/tool.h"
#include "core/scene/trace.h"

namespace bleedsim {

// The tissue panel: its size in pixels and in millimetres (pixels need not be square).
struct Domain {
  int width_px = 0;
  int height_px = 0;
  double width_mm = 0.0;
  double height_mm = 0.0;

  PixelGrid grid() const;
  Count pixels() const { return Count(width_px) * Count(height_px); }
  // `bytes_per_pixel` over the whole panel: memory its size, scene.width_px × height_px, sets.
  MemoryPart memory(Count bytes_per_pixel) const;
};

// The longest name of a file or folder most file systems hold (NAME_MAX): a scene's name, which
// names its output folder, and each part of an output path.
constexpr std::size_t kMaxFileName = 255;

// The most frames a run may have: frame_count() is an int, and counters derived from it stay exact.
constexpr std::int64_t kMaxFrames = 10'000'000;

struct Scene {
  std::string name;
  Domain domain;
  double duration_s = 1.0;
  double frame_rate_hz = 30.0;
  std::uint64_t seed = 0;
  Image tissue;               // domain-sized RGBA8
  std::string tissue_source;  // file path, or "procedural"
  // The tissue's surface, placed in the device frame (mm): the texture is its uv map and the panel
  // its texture (docs/mesh.md). None: the flat panel.
  std::shared_ptr<const MeshSurface> mesh;
  std::string mesh_source;  // the mesh's file, when there is one
  // The mucosa's vessels: a density map over the panel, width_px × height_px, row by row, each
  // 0 … 1; read in a scene with [vessels].
  std::vector<float> vessel_density;
  std::vector<TipPoint> tips;           // a scripted instrument's path, in a scene without [haptics]
  std::optional<HapticParams> haptics;  // the stylus
  std::optional<Trace> trace;           // replayed through the haptic loop, one sample per tick
  std::vector<Cut> cuts;                // cuts the scene makes, in the order written (the order
                                        // overlapping stains combine in)
  TypeMap effects;                      // the effects the scene calls for: each one's parameters

  int frame_count() const;
  // Frame k shows the state at the end of its frame period: t = (k + 1) / frame_rate.
  double frame_time_s(std::int64_t k) const;
  // Haptic ticks (1 kHz, tick n at n ms) at or before the end of frame k: ticks 0 .. n_k − 1 have
  // run when frame k is computed. From integer counts, so no clock drifts from another.
  std::int64_t haptic_ticks_through_frame(std::int64_t k) const;
};

// The [scene] table: the panel, time and seed.
const ParamTable<Scene>& scene_table();

}  // namespace bleedsim
