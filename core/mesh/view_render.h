#pragma once
// The endoscope's view of a tissue mesh with its bleeding texture (docs/mesh.md, "The view"): a CPU
// rasteriser for people to look at, not a frame of the simulation. Every triangle, in mesh order,
// is clipped at the near plane, projected through a pinhole at the scope's tip and filled where a
// sample's centre lies inside it (top-left rule: a sample on an edge two triangles share belongs to
// one); a z-buffer keeps the nearest (a tie keeps the lower triangle). The texture coordinate is
// interpolated perspective-correctly and the texture read bilinearly; the headlight at the tip
// lights the surface; samples are averaged into pixels in linear light. Double arithmetic, one
// thread, in a fixed order: the same bytes on every machine.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/mesh/tissue_mesh.h"
#include "core/runtime/image.h"

namespace bleedsim {

// An endoscope in the device frame (x right, y up, z towards the user): a pinhole at its tip
// (eye_mm) looking at look_at_mm, `up` the direction that is up in the image (it need not be
// square to the view). The image centre is the view axis; pixel (i, j) covers [i, i + 1) × [j, j + 1)
// with row 0 at the top, and its centre is (i + ½, j + ½). Square pixels: fov_y_deg is the vertical
// field of view, the horizontal follows from the aspect.
struct ViewCamera {
  Eigen::Vector3d eye_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d look_at_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  // A rigid sinus endoscope's round image spans 80° to 90°; 70° vertically (86° across at 4:3)
  // frames most of it.
  double fov_y_deg = 70.0;
  int width_px = 640;
  int height_px = 480;
  // Nothing nearer the tip than this is drawn. Tissue that close would be against the lens; the
  // depths are doubles, so a small near plane costs no precision in the z-buffer.
  double near_mm = 0.1;
};

// How the view is lit and sampled.
struct ViewLight {
  // The light the tissue scatters back from everywhere else in the cavity, as a fraction of the
  // headlight's: a surface edge-on to the scope reads as dim, not black, and its shape still shows.
  double ambient = 0.25;
  // The headlight's falloff, 1 / (1 + (d / d0)²) at d from the tip (0: none). A bare 1/d² would
  // burn out tissue at a few millimetres and blacken it at the back of the nose; the scope's
  // exposure and the cavity's scattered light soften it. d0 = 40 mm keeps the working distance
  // (10 to 20 mm) within 80 % of full and halves the light 40 mm away, deep in a nasal cavity.
  double falloff_mm = 40.0;
  // sRGB bytes where no tissue is: the dark of the cavity past the headlight's reach, a little red.
  std::array<std::uint8_t, 3> background = {10, 6, 6};
  // n × n samples a pixel, averaged in linear light. 2 takes the staircase off edges for four times
  // the work; 16 resolves an edge's coverage to 1/256, as fine as a byte can show, and is the most.
  int samples_per_axis = 2;
};

// The view: width_px × height_px RGBA8 (alpha 255), colour = texture × (ambient + (1 − ambient) ·
// |n̂ · l̂|) × falloff in linear light, n̂ the smooth normal (corners' area-weighted normals
// interpolated), l̂ towards the tip; |n̂ · l̂| lights both sides of an open sheet. The texture is
// sRGB bytes (its alpha is ignored), u along its columns and v down its rows, clamped at its edges.
// Throws std::invalid_argument naming the problem for a degenerate camera (eye at look_at, up
// along the view, fov outside (0°, 180°), a size outside 1 … 16384, near_mm not positive), a light
// out of range, a texture whose bytes do not match its size, or a mesh with an index out of range
// or a coordinate that is not finite.
Image render_view(const TissueMesh& mesh, const Image& texture, const ViewCamera& camera, const ViewLight& light = {});

// Throws std::invalid_argument, as render_view would, when the camera is degenerate (above).
void check_view_camera(const ViewCamera& camera);

// What the rasteriser found at each sample before shading, for tests and tools: the sample grid is
// width_px · n × height_px · n, row-major, top row first; sample (x, y) has its centre at
// ((x + ½) / n, (y + ½) / n) in pixels.
struct ViewSamples {
  int width = 0;
  int height = 0;
  std::vector<int> triangle;           // the nearest triangle's index; −1 where no triangle is
  std::vector<double> depth_mm;        // its depth along the view axis (infinity where none)
  std::vector<Eigen::Vector3d> point;  // the point of the mesh seen there (mm)
  std::vector<Eigen::Vector2d> uv;     // its texture coordinate
  std::vector<int> coverage;           // how many triangles cover the sample, the hidden ones too
};
ViewSamples rasterise_view(const TissueMesh& mesh, const ViewCamera& camera, int samples_per_axis = 1);

// A triangle's outward normal, ∂P/∂v × ∂P/∂u (P its position, (u, v) its texture coordinate):
// the side the texture reads the right way round from, whatever the corners' winding. Its length
// is twice the triangle's area. A triangle with no area in the texture has no such side; its
// winding's normal stands in.
Eigen::Vector3d outward_normal(const TissueMesh& mesh, int triangle);

}  // namespace bleedsim
