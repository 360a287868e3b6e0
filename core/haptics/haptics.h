#pragma once
// The 1 kHz haptic loop (docs/haptics.md). Each tick takes one sample of the Falcon, finds whether
// the stylus touches the tissue — the flat panel's plane, or the scene's tissue mesh through
// MeshContact — computes the force the device sends back, and, while the cutting button is held in
// contact, lays cuts along the stylus' path on the tissue, at their place in its texture.
//
// Host code only and free of frame stages: a live simulator runs a HapticLoop on its own 1 kHz
// thread with samples from libnifalcon and hands the cuts to its Simulation; a scenario's trace
// is replayed through the same loop between frames (Simulation::step).
#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/haptics/mesh_contact.h"

#include "core/scene/scene.h"

namespace bleedsim {

// One sample of the device, in libnifalcon's frame (metres; x right, y up, z towards the user).
struct DeviceSample {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  std::uint8_t buttons = 0;  // bitmask of the four grip buttons
};

// What one tick found and did: one row of the haptic channel (HDF5 /haptics, docs/output-format.md).
struct HapticTick {
  std::int64_t tick = 0;
  double t_s = 0;
  Eigen::Vector3d tool_m = Eigen::Vector3d::Zero();    // the sample's position, device frame
  // Where it lies over the tissue, in the texture's mm: on the flat panel, under the tip; on a mesh,
  // the contact's proxy, or out of contact the surface's point nearest to the tip.
  Eigen::Vector2d panel_mm = Eigen::Vector2d::Zero();
  std::uint8_t buttons = 0;
  bool contact = false;       // the tip is in the tissue (on the flat panel: below its plane, over it)
  double penetration_m = 0;   // how far in (0 out of contact)
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();  // sent to the device
  bool cutting = false;       // in contact with a cutting button held
};

// The outcome of a tick: its record, and the cut it made, if any.
struct HapticStep {
  HapticTick record;
  std::optional<Cut> cut;
};

class HapticLoop {
 public:
  // Keeps what it needs of the scene (the panel or the mesh, the contact parameters, the cuts' wound).
  // Throws std::invalid_argument when the scene has no [haptics] or its parameters are not passive.
  explicit HapticLoop(const Scene& scene);

  // Tick number ticks_done(): contact, force and cut for this sample.
  HapticStep tick(const DeviceSample& sample);
  std::int64_t ticks_done() const { return ticks_done_; }

 private:
  // The record's contact, penetration, force and panel_mm for this sample; they return where on the
  // tissue the tip is, in its surface's own mm, along which a stroke's cuts are spaced.
  Eigen::Vector3d touch_plane(const DeviceSample& sample, HapticTick& record) const;
  Eigen::Vector3d touch_mesh(const DeviceSample& sample, HapticTick& record);
  Eigen::Vector2d on_panel(const Eigen::Vector3d& tool_m) const;
  bool over_panel(const Eigen::Vector2d& panel_mm) const;
  Eigen::Vector2d in_texture_mm(const SurfacePoint& at) const;

  HapticParams params_;
  Domain domain_;
  Cut cut_template_;  // the scene's wound: what a cut leaves out of position and time
  std::int64_t ticks_done_ = 0;
  Eigen::Vector3d previous_m_ = Eigen::Vector3d::Zero();
  std::shared_ptr<const MeshSurface> mesh_;  // the tissue mesh, if the scene has one
  std::optional<MeshContact> mesh_contact_;  // the stylus' contact with it
  // The stroke's latest cut, in the texture and on the tissue; none between strokes.
  std::optional<Eigen::Vector2d> last_cut_mm_;
  Eigen::Vector3d last_cut_on_tissue_mm_ = Eigen::Vector3d::Zero();
};

}  // namespace bleedsim
