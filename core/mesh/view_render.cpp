#include "core/mesh/view_render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/physics/optics.h"
#include "core/physics/optics_tables.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

constexpr int kMaxSide = 16384;
constexpr int kMaxSamplesPerAxis = 16;
// The samples rasterised at once: the z-buffer of a band of rows, not of the whole view, so that a
// large view at many samples a pixel stays within tens of megabytes.
constexpr long long kBandSamples = 1 << 19;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// As a scenario writes it: [0, 0, 1].
std::string text(const Eigen::Vector3d& v) {
  return "[" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) + "]";
}

// The camera's frame: a point p is at ((p − eye)·right, (p − eye)·up, (p − eye)·forward) in it, the
// last its depth; a point at depth z > 0 is on the screen at (cx + f x / z, cy − f y / z) pixels.
struct CameraFrame {
  Eigen::Vector3d eye, right, up, forward;
  double focal_px = 0.0, cx = 0.0, cy = 0.0, near = 0.0;
  int width = 0, height = 0;

  Eigen::Vector3d to_camera(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - eye;
    return {d.dot(right), d.dot(up), d.dot(forward)};
  }
  Eigen::Vector2d to_screen(const Eigen::Vector3d& c) const {
    return {cx + focal_px * c.x() / c.z(), cy - focal_px * c.y() / c.z()};
  }
};

// (camera) => its frame, or std::invalid_argument naming what makes it degenerate
CameraFrame camera_frame(const ViewCamera& c) {
  const auto refuse = [](const std::string& why) { throw std::invalid_argument("view camera: " + why); };
  if (!c.eye_mm.allFinite() || !c.look_at_mm.allFinite() || !c.up.allFinite())
    refuse("eye_mm " + text(c.eye_mm) + ", look_at_mm " + text(c.look_at_mm) + " and up " + text(c.up) +
           " must be finite");
  const Eigen::Vector3d view = c.look_at_mm - c.eye_mm;
  if (!(view.norm() > 0.0))
    refuse("eye_mm and look_at_mm are the same point " + text(c.eye_mm) + ": the camera looks nowhere");
  if (!(c.up.norm() > 0.0)) refuse("up is the zero vector: the image has no up");
  CameraFrame f;
  f.forward = view.normalized();
  const Eigen::Vector3d side = f.forward.cross(c.up.normalized());
  // Past a sine of 10⁻⁹ the image's roll would be rounding, not the camera's.
  if (!(side.norm() > 1e-9))
    refuse("up " + text(c.up) + " is parallel to the view direction " + text(f.forward) +
           ": the image's roll is undefined");
  if (!(c.fov_y_deg > 0.0 && c.fov_y_deg < 180.0))
    refuse("fov_y_deg is " + format_number(c.fov_y_deg) + "; a pinhole's field of view is in (0, 180) degrees");
  if (c.width_px < 1 || c.width_px > kMaxSide || c.height_px < 1 || c.height_px > kMaxSide)
    refuse("the image is " + std::to_string(c.width_px) + " x " + std::to_string(c.height_px) +
           " pixels; width_px and height_px must be 1 to " + std::to_string(kMaxSide));
  if (!(c.near_mm > 0.0 && std::isfinite(c.near_mm)))
    refuse("near_mm is " + format_number(c.near_mm) + "; the near plane must be a positive distance in front of the eye");
  f.eye = c.eye_mm;
  f.right = side.normalized();
  f.up = f.right.cross(f.forward);
  f.width = c.width_px;
  f.height = c.height_px;
  f.cx = 0.5 * c.width_px;
  f.cy = 0.5 * c.height_px;
  f.focal_px = f.cy / std::tan(c.fov_y_deg * M_PI / 360.0);
  f.near = c.near_mm;
  return f;
}

}  // namespace

void check_view_camera(const ViewCamera& camera) { camera_frame(camera); }

namespace {

void check_mesh(const TissueMesh& mesh) {
  const auto refuse = [](const std::string& why) { throw std::invalid_argument("view of a mesh: " + why); };
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!mesh.positions[i].allFinite()) refuse("position " + std::to_string(i) + " is not finite");
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i)
    if (!mesh.uvs[i].allFinite()) refuse("texture coordinate " + std::to_string(i) + " is not finite");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int corner = mesh.triangles[t].corner[k], uv = mesh.triangles[t].uv[k];
      if (corner < 0 || std::size_t(corner) >= mesh.positions.size() || uv < 0 || std::size_t(uv) >= mesh.uvs.size())
        refuse("triangle " + std::to_string(t) + " names a position or texture coordinate the mesh does not have");
    }
}

// The nearest fragment at one sample: its triangle, depth and the weights of its triangle's corners.
struct Fragment {
  double depth = kInfinity;
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

// A corner of a triangle's piece on the screen: where it is, 1/depth, and the weights of the
// triangle's own corners at it over depth (attributes over depth interpolate linearly on the screen).
struct ScreenCorner {
  Eigen::Vector2d p;
  double inv_z;
  Eigen::Vector3d weights_over_z;
};

// (mesh, camera frame, samples a pixel) => the nearest fragment at each sample of a band of rows.
// Each corner is taken into the camera's frame and onto the screen once, so that the corners two
// triangles share are the same bits in both.
class Rasteriser {
 public:
  Rasteriser(const TissueMesh& mesh, const CameraFrame& frame, int n)
      : mesh_(mesh), frame_(frame), n_(n), width_(frame.width * n), height_(frame.height * n) {
    camera_.reserve(mesh.positions.size());
    screen_.reserve(mesh.positions.size());
    for (const Eigen::Vector3d& p : mesh.positions) {
      camera_.push_back(frame.to_camera(p));
      screen_.push_back(camera_.back().z() >= frame.near ? frame.to_screen(camera_.back()) : Eigen::Vector2d::Zero());
    }
  }
  int width() const { return width_; }
  int height() const { return height_; }

  // Sample rows [first, first + rows): fragments (rows × width, reset here) and, when not null, the
  // count of triangles covering each sample.
  void band(int first, int rows, Fragment* fragments, int* coverage) const {
    std::fill(fragments, fragments + std::size_t(rows) * width_, Fragment{});
    if (coverage) std::fill(coverage, coverage + std::size_t(rows) * width_, 0);
    const double top = double(first) / n_, bottom = double(first + rows) / n_;  // the band, in pixels
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const auto& c = mesh_.triangles[t].corner;
      const Eigen::Vector3d z(camera_[c[0]].z(), camera_[c[1]].z(), camera_[c[2]].z());
      if (z.maxCoeff() < frame_.near) continue;  // wholly behind the near plane
      if (z.minCoeff() >= frame_.near) {
        // Wholly in front: skip it unless it reaches the band's rows.
        const double y0 = screen_[c[0]].y(), y1 = screen_[c[1]].y(), y2 = screen_[c[2]].y();
        if (std::max({y0, y1, y2}) < top - 1.0 || std::min({y0, y1, y2}) > bottom + 1.0) continue;
        ScreenCorner piece[3];
        for (int k = 0; k < 3; ++k)
          piece[k] = {screen_[c[k]], 1.0 / z[k], Eigen::Vector3d::Unit(k) / z[k]};
        fill(piece, int(t), first, rows, fragments, coverage);
        continue;
      }
      clip_and_fill(int(t), first, rows, fragments, coverage);
    }
  }

 private:
  // A corner of the polygon left of a triangle by the near plane, in the camera's frame.
  struct ClipCorner {
    Eigen::Vector3d at;
    Eigen::Vector3d weights;
    int position;  // the mesh's position when it is one of the triangle's corners, else −1
  };

  // (a triangle crossing the near plane) => the polygon in front of it (Sutherland–Hodgman against
  // depth ≥ near: three or four corners), fanned into pieces and filled. A crossing point is found
  // from the edge's corner in front, whichever way the triangle runs along the edge, so two
  // triangles sharing the edge cut it at the same point.
  void clip_and_fill(int t, int first, int rows, Fragment* fragments, int* coverage) const {
    const auto& c = mesh_.triangles[t].corner;
    ClipCorner polygon[4];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const ClipCorner a{camera_[c[k]], Eigen::Vector3d::Unit(k), c[k]};
      const ClipCorner b{camera_[c[(k + 1) % 3]], Eigen::Vector3d::Unit((k + 1) % 3), c[(k + 1) % 3]};
      const bool a_in = a.at.z() >= frame_.near, b_in = b.at.z() >= frame_.near;
      if (a_in) polygon[count++] = a;
      if (a_in != b_in) {
        const ClipCorner& in = a_in ? a : b;
        const ClipCorner& out = a_in ? b : a;
        const double s = (frame_.near - in.at.z()) / (out.at.z() - in.at.z());
        Eigen::Vector3d at = in.at + s * (out.at - in.at);
        at.z() = frame_.near;
        polygon[count++] = {at, in.weights + s * (out.weights - in.weights), -1};
      }
    }
    ScreenCorner screen[4];
    for (int k = 0; k < count; ++k) {
      const ClipCorner& p = polygon[k];
      screen[k] = {p.position >= 0 ? screen_[p.position] : frame_.to_screen(p.at), 1.0 / p.at.z(),
                   p.weights / p.at.z()};
    }
    for (int k = 1; k + 1 < count; ++k) {
      ScreenCorner piece[3] = {screen[0], screen[k], screen[k + 1]};
      fill(piece, t, first, rows, fragments, coverage);
    }
  }

  // (a piece of triangle t on the screen) => the samples of the band whose centres it covers, each
  // taking the piece's fragment where it is nearer than what the sample has. An edge's function is
  // computed from its endpoints in one canonical order whichever triangle it belongs to, so two
  // triangles sharing it get values of exactly opposite sign, and a sample exactly on it goes to the
  // triangle for which it is a top or left edge (a clockwise triangle on the y-down screen: an
  // edge running up, or running right along a row with the triangle below).
  void fill(ScreenCorner* v, int t, int first, int rows, Fragment* fragments, int* coverage) const {
    const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    const double area = cross(v[1].p - v[0].p, v[2].p - v[0].p);
    if (area == 0.0) return;  // edge-on
    if (area < 0.0) std::swap(v[1], v[2]);
    struct Edge {
      Eigen::Vector2d from, delta;
      double sign;
      bool takes_zero;
    } edge[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d &a = v[k].p, &b = v[(k + 1) % 3].p;
      const bool ordered = a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
      const Eigen::Vector2d from = ordered ? a : b, delta = ordered ? b - a : a - b;
      const double sign = ordered ? 1.0 : -1.0;
      const double dx = sign * delta.x(), dy = sign * delta.y();
      edge[k] = {from, delta, sign, dy < 0.0 || (dy == 0.0 && dx > 0.0)};
    }
    // The samples whose centres may be inside (one more each side; the edges decide).
    const double min_x = std::min({v[0].p.x(), v[1].p.x(), v[2].p.x()});
    const double max_x = std::max({v[0].p.x(), v[1].p.x(), v[2].p.x()});
    const double min_y = std::min({v[0].p.y(), v[1].p.y(), v[2].p.y()});
    const double max_y = std::max({v[0].p.y(), v[1].p.y(), v[2].p.y()});
    const double x0 = std::max(std::floor(min_x * n_ - 0.5), 0.0);
    const double x1 = std::min(std::ceil(max_x * n_ - 0.5), double(width_ - 1));
    const double y0 = std::max(std::floor(min_y * n_ - 0.5), double(first));
    const double y1 = std::min(std::ceil(max_y * n_ - 0.5), double(first + rows - 1));
    if (x0 > x1 || y0 > y1) return;
    for (int y = int(y0); y <= int(y1); ++y) {
      const double py = (y + 0.5) / n_;
      for (int x = int(x0); x <= int(x1); ++x) {
        const Eigen::Vector2d p((x + 0.5) / n_, py);
        double e[3];
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) {
          e[k] = edge[k].sign * cross(edge[k].delta, p - edge[k].from);
          inside = e[k] > 0.0 || (e[k] == 0.0 && edge[k].takes_zero);
        }
        if (!inside) continue;
        const std::size_t at = std::size_t(y - first) * width_ + x;
        if (coverage) ++coverage[at];
        // Edge k runs from corner k to k + 1: its function is the weight of corner k + 2.
        const double sum = e[0] + e[1] + e[2];
        const double b0 = e[1] / sum, b1 = e[2] / sum, b2 = e[0] / sum;
        const double inv_z = b0 * v[0].inv_z + b1 * v[1].inv_z + b2 * v[2].inv_z;
        const double depth = 1.0 / inv_z;
        Fragment& f = fragments[at];
        if (!(depth < f.depth)) continue;  // a tie keeps the lower triangle, drawn first
        f.depth = depth;
        f.triangle = t;
        f.weights = (b0 * v[0].weights_over_z + b1 * v[1].weights_over_z + b2 * v[2].weights_over_z) * depth;
      }
    }
  }

  const TissueMesh& mesh_;
  const CameraFrame& frame_;
  const int n_, width_, height_;
  std::vector<Eigen::Vector3d> camera_;  // each position in the camera's frame
  std::vector<Eigen::Vector2d> screen_;  // ... and on the screen, where it is in front of the near plane
};

// The sample rows a band takes: whole pixel rows, about kBandSamples samples.
int band_pixel_rows(const CameraFrame& frame, int n) {
  const long long per_row = (long long)frame.width * n * n;
  return int(std::clamp<long long>(kBandSamples / per_row, 1, frame.height));
}

Eigen::Vector3d point_of(const TissueMesh& mesh, const Fragment& f) {
  const auto& c = mesh.triangles[f.triangle].corner;
  return f.weights[0] * mesh.positions[c[0]] + f.weights[1] * mesh.positions[c[1]] + f.weights[2] * mesh.positions[c[2]];
}

Eigen::Vector2d uv_of(const TissueMesh& mesh, const Fragment& f) {
  const auto& c = mesh.triangles[f.triangle].uv;
  return f.weights[0] * mesh.uvs[c[0]] + f.weights[1] * mesh.uvs[c[1]] + f.weights[2] * mesh.uvs[c[2]];
}

// (texture, uv) => its colour in linear light: bilinear between the four texels whose centres,
// ((i + ½)/W, (j + ½)/H), surround uv, the texture clamped at its edges.
Eigen::Vector3d sample_texture(const Image& texture, const double* to_linear, const Eigen::Vector2d& uv) {
  // Clamped before the floor, so that a coordinate far off the texture is still a small integer.
  const double x = std::clamp(uv.x() * texture.width - 0.5, -1.0, double(texture.width));
  const double y = std::clamp(uv.y() * texture.height - 0.5, -1.0, double(texture.height));
  const double fx = std::floor(x), fy = std::floor(y);
  const double sx = x - fx, sy = y - fy;
  const int i0 = std::clamp(int(fx), 0, texture.width - 1), i1 = std::clamp(int(fx) + 1, 0, texture.width - 1);
  const int j0 = std::clamp(int(fy), 0, texture.height - 1), j1 = std::clamp(int(fy) + 1, 0, texture.height - 1);
  const auto texel = [&](int i, int j) {
    const std::uint8_t* t = texture.rgba.data() + (std::size_t(j) * texture.width + i) * 4;
    return Eigen::Vector3d(to_linear[t[0]], to_linear[t[1]], to_linear[t[2]]);
  };
  return (1 - sy) * ((1 - sx) * texel(i0, j0) + sx * texel(i1, j0)) + sy * ((1 - sx) * texel(i0, j1) + sx * texel(i1, j1));
}

}  // namespace

Eigen::Vector3d outward_normal(const TissueMesh& mesh, int triangle) {
  const auto& c = mesh.triangles[triangle].corner;
  const auto& t = mesh.triangles[triangle].uv;
  const Eigen::Vector3d winding =
      (mesh.positions[c[1]] - mesh.positions[c[0]]).cross(mesh.positions[c[2]] - mesh.positions[c[0]]);
  const Eigen::Vector2d du1 = mesh.uvs[t[1]] - mesh.uvs[t[0]], du2 = mesh.uvs[t[2]] - mesh.uvs[t[0]];
  // With e1, e2 the edges from corner 0 and D the uv edges' determinant, ∂P/∂u × ∂P/∂v = (e1 × e2) / D.
  const double determinant = du1.x() * du2.y() - du2.x() * du1.y();
  return determinant > 0.0 ? Eigen::Vector3d(-winding) : winding;
}

ViewSamples rasterise_view(const TissueMesh& mesh, const ViewCamera& camera, int samples_per_axis) {
  const CameraFrame frame = camera_frame(camera);
  if (samples_per_axis < 1 || samples_per_axis > kMaxSamplesPerAxis)
    throw std::invalid_argument("view: samples_per_axis is " + std::to_string(samples_per_axis) + "; it must be 1 to " +
                                std::to_string(kMaxSamplesPerAxis));
  check_mesh(mesh);
  const Rasteriser raster(mesh, frame, samples_per_axis);
  ViewSamples out;
  out.width = raster.width();
  out.height = raster.height();
  const std::size_t count = std::size_t(out.width) * out.height;
  std::vector<Fragment> fragments(count);
  out.coverage.assign(count, 0);
  raster.band(0, out.height, fragments.data(), out.coverage.data());
  out.triangle.reserve(count);
  for (const Fragment& f : fragments) {
    out.triangle.push_back(f.triangle);
    out.depth_mm.push_back(f.depth);
    out.point.push_back(f.triangle < 0 ? Eigen::Vector3d::Zero() : point_of(mesh, f));
    out.uv.push_back(f.triangle < 0 ? Eigen::Vector2d::Zero() : uv_of(mesh, f));
  }
  return out;
}

Image render_view(const TissueMesh& mesh, const Image& texture, const ViewCamera& camera, const ViewLight& light) {
  const CameraFrame frame = camera_frame(camera);
  const auto refuse = [](const std::string& why) { throw std::invalid_argument("view: " + why); };
  if (!(light.ambient >= 0.0 && light.ambient <= 1.0))
    refuse("ambient is " + std::to_string(light.ambient) + "; it is a fraction of the headlight, 0 to 1");
  if (!(light.falloff_mm >= 0.0 && std::isfinite(light.falloff_mm)))
    refuse("falloff_mm is " + std::to_string(light.falloff_mm) + "; it must be a distance, or 0 for no falloff");
  if (light.samples_per_axis < 1 || light.samples_per_axis > kMaxSamplesPerAxis)
    refuse("samples_per_axis is " + std::to_string(light.samples_per_axis) + "; it must be 1 to " +
           std::to_string(kMaxSamplesPerAxis));
  if (texture.width < 1 || texture.height < 1 ||
      texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
    refuse("the texture is " + std::to_string(texture.width) + " x " + std::to_string(texture.height) + " with " +
           std::to_string(texture.rgba.size()) + " bytes; it needs a positive size and 4 bytes a texel");
  check_mesh(mesh);

  // The blend's sRGB tables (core/physics/optics.h): bytes to linear light, and back to the nearest byte.
  const std::vector<float> tables = optics_tables();
  const SrgbTables srgb = srgb_tables(tables.data());
  double to_linear[kSrgbBytes];
  for (int b = 0; b < kSrgbBytes; ++b) to_linear[b] = linear_from_srgb(srgb, std::uint8_t(b));
  const Eigen::Vector3d background(to_linear[light.background[0]], to_linear[light.background[1]],
                                   to_linear[light.background[2]]);

  // Each position's normal: the outward normals of its triangles, weighted by their areas.
  std::vector<Eigen::Vector3d> normals(mesh.positions.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d n = outward_normal(mesh, int(t));
    for (int c : mesh.triangles[t].corner) normals[c] += n;
  }

  // (a fragment) => its colour in linear light, lit by the headlight at the tip
  const auto shade = [&](const Fragment& f) -> Eigen::Vector3d {
    const auto& c = mesh.triangles[f.triangle].corner;
    Eigen::Vector3d n = f.weights[0] * normals[c[0]] + f.weights[1] * normals[c[1]] + f.weights[2] * normals[c[2]];
    // Where the corners' normals cancel (a sheet folded back on itself), the triangle's own.
    if (!(n.norm() > 0.0)) n = outward_normal(mesh, f.triangle);
    const Eigen::Vector3d to_eye = frame.eye - point_of(mesh, f);
    const double d = to_eye.norm();
    const double facing = std::fabs(n.normalized().dot(to_eye)) / d;
    const double falloff = light.falloff_mm > 0.0 ? 1.0 / (1.0 + (d / light.falloff_mm) * (d / light.falloff_mm)) : 1.0;
    return sample_texture(texture, to_linear, uv_of(mesh, f)) * ((light.ambient + (1.0 - light.ambient) * facing) * falloff);
  };

  // Band by band: rasterise its samples, then shade them and average each pixel's in linear light.
  const int n = light.samples_per_axis;
  const Rasteriser raster(mesh, frame, n);
  const int band_rows = band_pixel_rows(frame, n);
  std::vector<Fragment> fragments(std::size_t(band_rows) * n * raster.width());
  Image image;
  image.width = frame.width;
  image.height = frame.height;
  image.rgba.resize(std::size_t(frame.width) * frame.height * 4);
  for (int row0 = 0; row0 < frame.height; row0 += band_rows) {
    const int rows = std::min(band_rows, frame.height - row0);
    raster.band(row0 * n, rows * n, fragments.data(), nullptr);
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < frame.width; ++i) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx) {
            const Fragment& f = fragments[std::size_t(j * n + sy) * raster.width() + i * n + sx];
            sum += f.triangle < 0 ? background : shade(f);
          }
        const Eigen::Vector3d pixel = sum / double(n * n);
        std::uint8_t* out = image.rgba.data() + (std::size_t(row0 + j) * frame.width + i) * 4;
        for (int k = 0; k < 3; ++k) out[k] = srgb_from_linear(srgb, float(pixel[k]));
        out[3] = 255;
      }
  }
  return image;
}

}  // namespace bleedsim
