#include "core/haptics/haptics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/effects/cuts.h"

namespace bleedsim {

HapticLoop::HapticLoop(const Scene& scene)
    : domain_(scene.domain), cut_template_(cut_at(scene, 0, 0, 0)), mesh_(scene.mesh) {
  if (!scene.haptics) throw std::invalid_argument("a haptic loop needs a scene with [haptics]");
  params_ = *scene.haptics;
  if (const ParamProblem problem = check_params(haptic_table(), params_, scene))
    throw std::invalid_argument(problem.text());
  if (mesh_) mesh_contact_.emplace(*mesh_, params_);
}

Eigen::Vector2d HapticLoop::on_panel(const Eigen::Vector3d& tool_m) const {
  // The panel's y points down, the device's up.
  const Eigen::Vector2d device_mm(1000.0 * tool_m.x(), -1000.0 * tool_m.y());
  return Eigen::Vector2d(params_.origin_x_mm, params_.origin_y_mm) + params_.scale * device_mm;
}

bool HapticLoop::over_panel(const Eigen::Vector2d& p) const {
  return p.x() >= 0 && p.x() <= domain_.width_mm && p.y() >= 0 && p.y() <= domain_.height_mm;
}

// The texture spans the panel: uv (0, 0) is its top-left corner, (1, 1) its bottom-right.
Eigen::Vector2d HapticLoop::in_texture_mm(const SurfacePoint& at) const {
  const Eigen::Vector2d uv = mesh_->uv(at);
  return Eigen::Vector2d(uv.x() * domain_.width_mm, uv.y() * domain_.height_mm);
}

Eigen::Vector3d HapticLoop::touch_plane(const DeviceSample& sample, HapticTick& r) const {
  // Contact: the tip below the surface plane, over the tissue (there is none beyond the panel).
  r.panel_mm = on_panel(sample.position_m);
  const double depth_m = params_.surface_z_mm / 1000.0 - sample.position_m.z();
  r.contact = depth_m > 0 && over_panel(r.panel_mm);
  r.penetration_m = r.contact ? depth_m : 0.0;

  // The force along the surface normal (+z, out of the tissue): a spring on the penetration and a
  // damper on the tip's speed along the normal (a backward difference over one tick). The tissue
  // pushes, never pulls, and no more than the device can.
  if (r.contact) {
    const double normal_speed_m_s = (sample.position_m.z() - previous_m_.z()) / kHapticPeriod_s;
    const double push_N = params_.stiffness_N_per_m * r.penetration_m - params_.damping_Ns_per_m * normal_speed_m_s;
    r.force_N.z() = std::clamp(push_N, 0.0, params_.max_force_N);
  }
  return Eigen::Vector3d(r.panel_mm.x(), r.panel_mm.y(), 0.0);
}

Eigen::Vector3d HapticLoop::touch_mesh(const DeviceSample& sample, HapticTick& r) {
  const Eigen::Vector3d tip_mm = 1000.0 * sample.position_m;
  const MeshTouch touch = mesh_contact_->touch(tip_mm);
  r.contact = touch.contact;
  r.penetration_m = touch.penetration_mm / 1000.0;
  r.force_N = touch.force_N;
  const SurfacePoint at = touch.contact ? touch.proxy : mesh_->closest(tip_mm);
  r.panel_mm = in_texture_mm(at);
  return at.point;
}

HapticStep HapticLoop::tick(const DeviceSample& sample) {
  HapticStep step;
  HapticTick& r = step.record;
  r.tick = ticks_done_;
  r.t_s = double(ticks_done_) / kHapticRate_hz;
  r.tool_m = sample.position_m;
  r.buttons = sample.buttons;
  if (ticks_done_ == 0) previous_m_ = sample.position_m;  // no speed before the first sample
  const Eigen::Vector3d on_tissue_mm = mesh_ ? touch_mesh(sample, r) : touch_plane(sample, r);
  previous_m_ = sample.position_m;

  // Cutting: the first contact with the button held cuts at once; then a cut every cut_spacing_mm
  // of the path on the tissue (on a mesh, between the proxy's points: the wound follows the surface).
  // Lifting or letting go ends the stroke.
  r.cutting = r.contact && (sample.buttons & params_.cut_buttons) != 0;
  if (!r.cutting) {
    last_cut_mm_.reset();
  } else if (!last_cut_mm_ || (on_tissue_mm - last_cut_on_tissue_mm_).norm() >= params_.cut_spacing_mm) {
    // Each cut stands for cut_spacing_mm of the stroke's wound, centred on it, in the direction the
    // stroke came from its last cut in the texture (along x for a stroke's first): the stroke bleeds
    // by its length, however finely it is cut, and from the vessels along its path.
    Cut cut = cut_template_;
    if (last_cut_mm_) {
      const Eigen::Vector2d travel = r.panel_mm - *last_cut_mm_;
      cut.wound_angle_deg = std::atan2(travel.y(), travel.x()) * 180.0 / 3.14159265358979323846;
    }
    last_cut_mm_ = r.panel_mm;
    last_cut_on_tissue_mm_ = on_tissue_mm;
    cut.x_mm = r.panel_mm.x();
    cut.y_mm = r.panel_mm.y();
    cut.start_s = r.t_s;
    cut.wound_mm = params_.cut_spacing_mm;
    step.cut = cut;
  }
  ++ticks_done_;
  return step;
}

}  // namespace bleedsim
