#pragma once
// The tissue's surface as its texture sees it (docs/mesh.md, "Blood on a curved surface"). On a
// tissue mesh the panel is the texture: panel millimetres are texture coordinates scaled by the
// scene's width_mm × height_mm, and a texel's stretch tells how far on the surface a step across the
// panel goes. Blood moves and measures in surface millimetres; the panel only says where it is.
//
// Each texel holds its triangle's map from panel to surface millimetres, J = [∂P/∂x ∂P/∂y], written
// in an orthonormal frame of the tangent plane whose first axis lies along the panel's x:
//   J = [[a, b], [0, c]],   a = |∂P/∂x|,  b = ∂P/∂y · e₁,  c = |∂P/∂y − b e₁|   (a, c > 0),
// so a panel offset (dx, dy) is the surface offset (a·dx + b·dy, c·dy), exactly for a flat
// triangle and to first order across a curved mesh, and any shear of the uv map is kept. Velocities,
// accelerations and gravity (the surface's own, its tangential part) are vectors in that frame, in
// surface mm/s and mm/s²; positions stay in panel mm. The flat panel is a = c = 1, b = 0, and then
// every conversion below is exact: a flat mesh reproduces the flat panel's bytes.
//
// A texel no triangle covers is off the surface (outside the uv chart, or in a hole of it): the
// particles treat it as a wall. The bake gives it its nearest covered texel's frame and gravity, so
// that reading either is always safe.
#include <cstddef>

#include "core/physics/hd.h"
#include "core/physics/pixel_grid.h"

namespace bleedsim {

// One texel's frame: surface mm per panel mm.
struct SurfaceFrame {
  float a, b, c;
};

// The surface maps as the physics reads them; without a mesh, frame is null and the panel is flat.
struct SurfaceMap {
  const float* frame = nullptr;    // width × height × 4: a, b, c, and 1 on the surface (0 off it)
  const float* gravity = nullptr;  // width × height × 2: the tangential gravity in the frame, mm/s²
  PixelGrid grid;
};

constexpr int kSurfaceFrameChannels = 4;
constexpr int kSurfaceGravityChannels = 2;

BLEEDSIM_HD inline bool curved(const SurfaceMap& s) { return s.frame != nullptr; }

BLEEDSIM_HD inline SurfaceFrame frame_of(const SurfaceMap& s, std::size_t texel) {
  const float* f = s.frame + kSurfaceFrameChannels * texel;
  return {f[0], f[1], f[2]};
}

BLEEDSIM_HD inline SurfaceFrame frame_at(const SurfaceMap& s, float x_mm, float y_mm) {
  return frame_of(s, pixel_containing(s.grid, x_mm, y_mm));
}

BLEEDSIM_HD inline bool on_surface(const SurfaceMap& s, float x_mm, float y_mm) {
  return s.frame[kSurfaceFrameChannels * pixel_containing(s.grid, x_mm, y_mm) + 3] != 0.0f;
}

// The frame a pair of particles shares: the mean of theirs, the same sum from either side, so the
// pair's offsets are exact opposites and its forces equal and opposite.
BLEEDSIM_HD inline SurfaceFrame pair_frame(const SurfaceFrame& p, const SurfaceFrame& q) {
  return {0.5f * (p.a + q.a), 0.5f * (p.b + q.b), 0.5f * (p.c + q.c)};
}

// A panel offset as a surface offset (mm), J · (dx, dy).
BLEEDSIM_HD inline void to_surface(const SurfaceFrame& f, float dx, float dy, float* sx, float* sy) {
  *sx = f.a * dx + f.b * dy;
  *sy = f.c * dy;
}

// A surface vector (an offset, or a velocity) as the panel's, J⁻¹ · (sx, sy).
BLEEDSIM_HD inline void to_panel(const SurfaceFrame& f, float sx, float sy, float* dx, float* dy) {
  *dy = sy / f.c;
  *dx = (sx - f.b * *dy) / f.a;
}

// How far across the panel, along x and along y, a surface disc of radius r reaches: the extents
// of the ellipse |J d| ≤ r, r·|row of J⁻¹|: r·√(1/a² + b²/(a²c²)) and r/c.
BLEEDSIM_HD inline void panel_reach(const SurfaceFrame& f, float r, float* rx, float* ry) {
  const float bc = f.b / f.c;
  *rx = r * (sqrtf(1.0f + bc * bc) / f.a);
  *ry = r / f.c;
}

// The share of a texel's panel area that is surface area: det J.
BLEEDSIM_HD inline float area_stretch(const SurfaceFrame& f) { return f.a * f.c; }

}  // namespace bleedsim
