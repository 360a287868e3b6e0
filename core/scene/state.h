#pragma once
// State: everything that changes as a run goes (MuJoCo's "data"). Stages read the Scene and the
// old State and write the new State; the fields live on the backend.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "core/physics/blur.h"
#include "core/physics/trail.h"
#include "core/runtime/buffer.h"
#include "core/scene/scene.h"
#include "core/scene/tool.h"

namespace bleedsim {

enum class ElementType { u8, u32, u64, f32 };
std::size_t element_size(ElementType type);

// What a quantity is: its name, element type and shape. Writers and readers need only this.
// Most are images (height × width pixels); some are per-element arrays (one row of `width`
// elements: a particle per ring-buffer slot, or a handful of counters).
struct FieldLayout {
  std::string name;  // "frame", "spread/stain": also its path in the HDF5 output
  ElementType type = ElementType::f32;
  int channels = 1;
  int width = 0;
  int height = 0;  // 1 when not an image
  std::string unit;
  std::string description;
  bool image = true;  // last, so aggregate initialisers written before it stay valid
  bool on_request = false;  // written to files only when the scene lists it (per-particle arrays)

  std::size_t bytes() const {
    return std::size_t(width) * std::size_t(height) * std::size_t(channels) * element_size(type);
  }
};

// A quantity a stage produces (the frame, an effect's field, particle state), held on the backend.
struct Field : FieldLayout {
  Buffer data;
};

struct State {
  std::int64_t frames_done = 0;  // frames computed so far; the next is frame number frames_done
  std::vector<Cut> cuts;         // the scene's cuts, then those fed at run time, in that order
  // The stylus's samples for the frame being computed (the haptic loop's, or the host's), after
  // the last one of the frames before it: its tip between them is the instrument's.
  std::vector<ToolSample> stylus;
  std::deque<Field> fields;      // deque: a Field's address never moves once added
  // The trail's pass for the frame being computed, which the blend runs in its own pass over the
  // same pixels (TrailThenBlend): set by the trail stage, taken by the blend stage.
  std::optional<TrailPixel> trail_pass;
  // The blur's first pass, which the splat runs in its conversion's pass (SplatArgs::downsample):
  // set by the blur stage when it is built; the blur stage then runs the passes after it.
  std::optional<BlurArgs> film_downsample;

  Field* find(const std::string& name);
  const Field* find(const std::string& name) const;
  // A field a stage reads: throws std::logic_error when none was added (the pipeline builds every
  // writer before its readers, so a missing one is a bug, not a scene's mistake).
  const Field& require(const std::string& name) const;
};

}  // namespace bleedsim
