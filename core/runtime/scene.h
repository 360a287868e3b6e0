#pragma once
// Scene: everything read-only that a run needs (MuJoCo's "model"). Built from a scenario file by
// load_scenario() or by a host program directly; State holds everything that changes.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/runtime/image.h"
#include "core/runtime/input_error.h"
#include "core/physics/pixel_grid.h"
#include "core/haptics/trace.h"

namespace bleedsim {

// The tissue panel: its size in pixels and in millimetres (pixels need not be square).
struct Domain {
  int width_px = 0;
  int height_px = 0;
  double width_mm = 0.0;
  double height_mm = 0.0;

  PixelGrid grid() const;
  std::int64_t pixel_count() const { return std::int64_t{width_px} * height_px; }
};

// A cut made by the tool: where and when, how large a wound (the spread stain's radius and growth
// rate) and how hard it bleeds particles (rate, for how long). What a cut leaves out comes from the
// scene's [spread] and [particles] defaults.
struct Cut {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double start_s = 0.0;
  double radius_mm = 0.0;
  double growth_per_s = 0.0;
  double rate_per_s = 0.0;  // particles per second while it bleeds
  double bleed_s = 0.0;     // how long it bleeds particles
};

// Parameters of the radial spread; present in a Scene only when the scene calls for it.
struct SpreadParams {
  double radius_mm = 4.0;
  double growth_per_s = 0.5;
};

// Parameters of the particle blood flow (docs/particles.md); present only when the scene calls
// for it. Units: mm, s, and accelerations per unit mass.
struct ParticleParams {
  int capacity = 65536;            // ring-buffer slots
  double diameter_mm = 0.2;
  double cell_mm = 0.0;            // grid cell edge; 0: the diameter
  int max_per_cell = 8;            // neighbours visited per cell, at most
  double rate_per_s = 500.0;       // default particles per second per bleeding cut
  double bleed_s = 2.0;            // default bleeding time of a cut
  double lifetime_s = 30.0;
  double fade_s = 1.0;             // the last part of the lifetime, over which a particle fades
  double gravity_x_mm_s2 = 0.0;    // along the panel; y points down
  double gravity_y_mm_s2 = 1000.0;
  double drag_per_s = 100.0;       // viscous drag: sticky, slow blood
  double stiffness_per_s2 = 4.0e5; // contact spring, per mm of overlap
  double damping_per_s = 100.0;    // contact dashpot, per mm/s of approach speed
  double max_speed_mm_s = 100.0;   // no particle moves faster: none passes through another
  int substeps = 40;               // physics steps per frame
  double jitter_mm = 0.05;         // emission position jitter, ±
  double velocity_x_mm_s = 0.0;    // emission velocity
  double velocity_y_mm_s = 0.0;
  double velocity_jitter_mm_s = 5.0;
  double particle_volume_mm3 = 0.004;  // the blood one particle stands for (the splat's film)
  double splat_radius_mm = 0.0;        // the film's footprint; 0: the diameter
};

// Parameters of the blur of the particles' film (docs/particles.md); present only when the scene
// calls for it (it needs [particles]).
struct BlurParams {
  int downsample = 2;      // 1, 2 or 4
  int radius_px = 4;       // taps either side, in downsampled pixels
  double sigma_px = 2.0;   // the Gaussian's, in downsampled pixels
};

// The haptic loop's rate: tick n is at t = n / kHapticRate_hz, the Falcon's 1 kHz servo loop.
constexpr int kHapticRate_hz = 1000;

// The stylus and the tissue it touches (docs/haptics.md); present only when the scene calls for
// it. Positions in the device frame are libnifalcon's (x right, y up, z towards the user).
struct HapticParams {
  // Where the tissue lies: the plane z = surface_z_mm of the device frame; the tip is in it below.
  double surface_z_mm = 120.0;
  // How device motion maps onto the panel: panel = origin + scale · (x, −y), in mm (the panel's y
  // points down, the device's up). The origin is the panel point under device x = y = 0.
  double origin_x_mm = 0.0;
  double origin_y_mm = 0.0;
  double scale = 1.0;
  // The contact: a spring along the surface normal plus a damper, clamped to the device's maximum.
  double stiffness_N_per_m = 500.0;
  double damping_Ns_per_m = 0.5;
  double device_damping_Ns_per_m = 1.5;  // the Falcon's own, for the passivity bound
  double max_force_N = 8.0;
  // Cutting: a cut every cut_spacing_mm of the tip's path while one of these buttons is held in contact.
  std::uint8_t cut_buttons = 0x1;
  double cut_spacing_mm = 1.0;
};

struct OutputSpec {
  std::string dir;                  // where outputs go; relative paths are to the working directory
  bool hdf5 = true;                 // frames.h5 in dir
  int png_every = 0;                // 0: no PNGs; N: frame 0, every Nth frame, and the last
  int contact_sheet = 0;            // 0: none; N: N frames from first to last in one PNG
  int deflate_level = 4;            // HDF5 gzip level 0–9
  std::vector<std::string> fields;  // fields written to HDF5 besides the frame; empty = all
};

struct Scene {
  std::string name;
  std::string source_path;  // the scenario file ("" when a host built the scene in code)
  std::string source_text;  // its text, recorded in every output for provenance
  Domain domain;
  double duration_s = 1.0;
  double frame_rate_hz = 30.0;
  std::uint64_t seed = 0;
  Image tissue;                        // domain-sized RGBA8
  std::string tissue_source;           // file path, or "procedural"
  std::optional<SpreadParams> spread;  // the effects the scene calls for
  std::optional<ParticleParams> particles;
  std::optional<BlurParams> blur;
  std::optional<HapticParams> haptics;
  std::optional<Trace> trace;          // replayed through the haptic loop, one sample per tick
  std::vector<Cut> cuts;               // cuts the scenario makes, in the order written (the
                                       // order overlapping stains combine in)
  OutputSpec output;
  std::map<std::string, SourcePlace> places;  // where each key was written, for later messages

  int frame_count() const;
  // Frame k shows the state at the end of its frame period: t = (k + 1) / frame_rate.
  double frame_time_s(std::int64_t k) const;
  // Where `key` was written in the scenario file (the file alone when it was not written).
  SourcePlace place_of(const std::string& key) const;
  // A cut at (x, y) starting at t with the scene's spread and particle defaults.
  Cut cut_at(double x_mm, double y_mm, double start_s) const;
  // Haptic ticks (1 kHz, tick n at n ms) at or before the end of frame k: ticks 0 .. n_k − 1 have
  // run when frame k is computed. From integer counts, so no clock drifts from another.
  std::int64_t haptic_ticks_through_frame(std::int64_t k) const;
};

}  // namespace bleedsim
