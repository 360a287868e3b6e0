#pragma once
// What a run writes of each frame (docs/output-format.md), as the output queue's work: the tasks a
// frame's encoding splits into (each field's HDF5 chunk, the frame's PNG, the view and its PNG) and,
// frame after frame, the writing of what they made: the HDF5 frame, the PNG files, the contact
// sheets' cells.
#include <filesystem>
#include <functional>
#include <vector>

#include "cli/output_queue.h"
#include "core/io/contact_sheet.h"
#include "core/io/hdf5_writer.h"
#include "core/io/xdmf_writer.h"
#include "core/runtime/image.h"

namespace bleedsim::cli {

// Where a run's frames go; a null pointer, or png_every 0, writes none of that kind.
struct FrameOutputs {
  Hdf5FrameWriter* hdf5 = nullptr;  // every field, the frame first
  XdmfWriter* xdmf = nullptr;       // told of each frame the HDF5 file takes
  std::filesystem::path png_folder;
  int png_every = 0;  // PNGs of frame 0, every png_every-th frame and the last of `frames`
  long frames = 0;
  int width = 0, height = 0;  // the frame's, in pixels
  // Draws the view of a frame's RGBA, for a scene with a [view]: beside each PNG, and in its sheet.
  std::function<Image(const std::uint8_t* rgba)> view;
  ContactSheet* sheet = nullptr;
  ContactSheet* view_sheet = nullptr;
};

class FrameOutput {
 public:
  explicit FrameOutput(FrameOutputs outputs);
  // The output queue's work; it refers to this object, which must outlive the queue.
  OutputWork work();
  // PNG files written; read once the queue has drained.
  long pngs() const { return pngs_; }

 private:
  int plan(FrameJob& job) const;
  void encode(FrameJob& job, int task) const;
  void write(const FrameJob& job);
  bool png_due(long frame) const;
  bool view_due(long frame) const;

  FrameOutputs out_;
  long pngs_ = 0;  // on the writer thread
};

}  // namespace bleedsim::cli
