#pragma once
// Frames and fields to HDF5 as the run goes (docs/output-format.md).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/haptics/haptics.h"
#include "core/scene/state.h"

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
  // The same as filter() for each field, then append_chunks().
  void append(double time_s, const std::vector<const void*>& field_data,
              const std::vector<HapticTick>& ticks = {});
  // One frame of field `field` (its frame's bytes, in host order) as its dataset stores it: through
  // shuffle and deflate at the file's level, or as it is at level 0, into `chunk`. Touches no HDF5
  // state, so several threads may filter frames at once, while another appends.
  void filter(std::size_t field, const void* frame, std::vector<std::uint8_t>& chunk) const;
  // Appends one frame given as its fields' chunks (filter()'s, one per field, in order), written as
  // they are (H5Dwrite_chunk), then the ticks; flushes, as append() does.
  void append_chunks(double time_s, const std::vector<std::vector<std::uint8_t>>& chunks,
                     const std::vector<HapticTick>& ticks = {});
  // Records `complete` and the frame count, closes, and renames to the final path.
  void finish(bool complete);
  int frames_written() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bleedsim
