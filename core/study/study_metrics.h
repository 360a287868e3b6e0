#pragma once
// What the accuracy study measures of one run (docs/accuracy.md, "The metrics"): every frame, the
// blood front, the covered area, the volume in view, the pile's height and the fastest particle (of
// which the time the blood comes to rest); at the snapshot frames,
// the film, the stain and the colour on a common grid of cells over the panel (each cell the area
// mean of the pixels under it), so that settings of different resolutions are compared on the
// same cells.
#include <cstdint>
#include <vector>

#include "core/physics/particles.h"

namespace bleedsim {

// Film thicker than this covers the tissue (it darkens a pixel visibly: 1 − exp(−40 · 0.01) ≈ 33 %
// of the green).
constexpr double kCoveredFilmMm = 0.01;

// Blood moving slower than this is at rest (issue 36's bound: ParticleRest's tests hold the default
// scene to it from 2 s after the last emission).
constexpr double kRestSpeedMmS = 0.1;

// One frame of one run, as the metrics need it: on the run's own pixel grid over the panel.
struct FrameFields {
  int width = 0, height = 0;            // pixels
  double width_mm = 0, height_mm = 0;   // the panel
  std::vector<float> film_mm;           // the film the frame shows (blurred when blurred); empty without particles
  std::vector<float> stain;             // the spread's stain; empty without the spread
  std::vector<std::uint8_t> rgba;       // the frame
  std::vector<float> velocity;          // mm/s, two per slot of the particles' ring; empty without particles
  std::vector<std::uint32_t> age;       // steps, one per slot
  ParticleLifetime lifetime{0, 0};      // the model's: which ages are alive
};

// The common grid for panels of these sizes: the coarsest, and no finer than kMaxGridWidth cells
// across (its aspect kept), so that a run's snapshots stay within a few MB.
constexpr int kMaxGridWidth = 160;
void common_grid(int& grid_w, int& grid_h);

// Each output cell of out_w × out_h over the same extent is the mean of the input over its area
// (pixels that straddle a cell edge count by the part inside). Separable: rows, then columns.
std::vector<double> area_resample(const std::vector<double>& in, int in_w, int in_h, int out_w, int out_h,
                                  int channels = 1);

// A frame's fields on the common grid: the film and the stain (empty where the scene lacks them)
// and the colour (R, G, B per cell, 0–255).
struct GridFrame {
  std::vector<float> film_mm, stain, rgb;
};
GridFrame on_grid(const FrameFields& frame, int grid_w, int grid_h);
std::vector<float> film_on_grid(const FrameFields& frame, int grid_w, int grid_h);

// The height of blood standing at the bottom of each column: from the bottom row up, the cells
// whose film is thicker than kCoveredFilmMm without a gap, times the cell height.
std::vector<double> pile_heights_mm(const std::vector<float>& film_mm, int w, int h, double cell_height_mm);

// How far the blood has run along gravity: the farthest covered cell's centre, measured along the
// gravity's direction in the panel from the panel's most uphill corner (straight down: the lowest
// covered cell's y, mm from the top); 0 while nothing is covered.
double blood_front_mm(const std::vector<float>& film_mm, int w, int h, double width_mm, double height_mm,
                      double gravity_x, double gravity_y);

// The fastest live particle's speed, mm/s (0 with none alive).
double fastest_speed_mm_s(const std::vector<float>& velocity, const std::vector<std::uint32_t>& age,
                          const ParticleLifetime& lifetime);

// When the blood came to rest for good: the end of the last frame in which a live particle moved
// faster than kRestSpeedMmS (frame k ends at (k + 1)·frame_s), 0 if none ever did. A run still
// moving at its last frame rests no earlier than its end, which is what this gives.
double rest_time_s(const std::vector<double>& fastest_mm_s, double frame_s);

// Every frame's measures of a run with a film (the particles'); NaN without one.
struct FrameMeasures {
  double front_mm;          // blood_front_mm on the grid
  double covered_area_mm2;  // the panel's area under film thicker than kCoveredFilmMm, at its own pixels
  double volume_mm3;        // the film's volume in view: thickness summed over the panel's pixels
  double pile_height_mm;    // the mean over the grid's columns of pile_heights_mm
  double fastest_mm_s;      // fastest_speed_mm_s of the particles
};
FrameMeasures measure_frame(const FrameFields& frame, const std::vector<float>& film_grid, int grid_w, int grid_h,
                            double gravity_x, double gravity_y);

// One run's distance from another's at the same frames: mean and root-mean-square |Δ thickness|
// over the cells, the colour's mean squared difference (8-bit levels) and the stain's mean |Δ|;
// NaN where the scene lacks the field.
struct RunDistance {
  double film_l1_mm, film_l2_mm, frame_mse, stain_l1;
};
RunDistance run_distance(const GridFrame& run, const GridFrame& other);

// PSNR of 8-bit colour from a mean squared error, dB; infinite for identical frames.
double psnr_db(double mse);

}  // namespace bleedsim
