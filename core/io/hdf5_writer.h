#pragma once
// Frames and fields to HDF5 as the run goes (docs/output-format.md).
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/runtime/state.h"

namespace bleedsim {

class Hdf5FrameWriter {
 public:
  // Writes one dataset per field, named by its path ("frame" → /frame, "spread/stain" →
  // /spread/stain): (T, H, W[, C]) for an image, (T, N[, C]) for a field with image == false
  // (height 1, N = width elements). Creates `path`.partial; the file takes its final name in
  // finish(). Root attributes are written as strings (provenance: version, git sha, backend,
  // device, flags, scenario text). With `haptic_channel`, /haptics/<column> (core/haptics/haptic_channel.h)
  // grows by the ticks each append() brings.
  Hdf5FrameWriter(const std::string& path, const std::vector<FieldLayout>& fields,
                  const std::vector<std::pair<std::string, std::string>>& attributes,
                  int deflate_level, bool haptic_channel = false);
  // Unfinished (an exception unwound the run): closes the file and leaves it as .partial.
  ~Hdf5FrameWriter();
  Hdf5FrameWriter(const Hdf5FrameWriter&) = delete;
  Hdf5FrameWriter& operator=(const Hdf5FrameWriter&) = delete;

  // Appends one frame: one host pointer per field, in the order given to the constructor, and the
  // haptic ticks replayed for it. Flushes, so a run killed later keeps every frame appended before.
  void append(double time_s, const std::vector<const void*>& field_data,
              const std::vector<HapticTick>& ticks = {});
  // Records `complete` and the frame count, closes, and renames to the final path.
  void finish(bool complete);
  int frames_written() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bleedsim
