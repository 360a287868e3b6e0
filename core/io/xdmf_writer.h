#pragma once
// frames.h5 described in XDMF 2 (frames.xmf), so that ParaView's XDMF Reader opens a run without a
// plugin (docs/output-format.md#paraview): the image fields as a 2D image over time, the particles
// as points, the frames' times as times, each value read from the HDF5 file's own datasets.
#include <cstdint>
#include <string>
#include <vector>

#include "core/physics/pixel_grid.h"
#include "core/scene/state.h"

namespace bleedsim {

// The slots of the ring buffer that hold the ids [oldest alive, emitted): `count` slots from
// `first`, wrapping past the last slot to slot 0.
struct RingRun {
  std::uint64_t first = 0;
  std::uint64_t count = 0;
};

// The run in a frame's arrays: every slot whose age, aspirated or not, is below the lifetime holds
// one of those ids (an expired particle's age stays at the lifetime, a slot never used has
// kNeverUsed), and the newest is in slot (emitted - 1) mod capacity.
RingRun ring_run(std::uint64_t emitted, const std::uint32_t* ages, std::uint64_t capacity,
                 std::uint32_t lifetime_steps);

class XdmfWriter {
 public:
  // `h5_name`: the HDF5 file, by its path from the folder the description is written into.
  // `fields`: the HDF5 file's, in its writer's order. Every image field is an attribute of the
  // panel, a grid of `panel`'s pixels whose nodes are the pixels' centres, in mm. With
  // particles/position, particles/age and particles/accounting among the fields, the particles
  // are points, each other per-particle field an attribute of theirs, in frames whose ring runs
  // ring_run() finds with `lifetime_steps`.
  XdmfWriter(std::string h5_name, const std::vector<FieldLayout>& fields, const PixelGrid& panel,
             std::uint32_t lifetime_steps);

  // A frame the HDF5 file has just taken: its time and its fields' host data, in `fields`' order.
  void add_frame(double time_s, const std::vector<const void*>& field_data);
  // The description of the frames added so far.
  std::string text() const;
  // text() into `path`, whole or not at all (write_whole_file).
  void write(const std::string& path) const;

 private:
  struct Frame {
    double time_s;
    RingRun particles;
  };
  std::string h5_name_;
  std::vector<FieldLayout> fields_;
  PixelGrid panel_;
  std::uint32_t lifetime_steps_;
  // Indexes into fields_, when the particles are described.
  bool particles_ = false;
  std::size_t position_ = 0, age_ = 0, accounting_ = 0;
  std::vector<Frame> frames_;
};

}  // namespace bleedsim
