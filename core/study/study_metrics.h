#pragma once
// The accuracy study's error metrics (docs/accuracy.md): one frame of a run against the same frame
// of the reference run. Settings that change the panel's resolution are compared on a common grid
// of cells over the same panel, each cell the area mean of the pixels under it, so every setting is
// judged on the same cells.
#include <cstdint>
#include <vector>

namespace bleedsim {

// Film thicker than this covers the tissue (it darkens a pixel visibly: 1 − exp(−40 · 0.01) ≈ 33 %
// of the green).
constexpr double kCoveredFilmMm = 0.01;

// One frame of one run, as the metrics need it: on the run's own pixel grid over the panel.
struct FrameFields {
  int width = 0, height = 0;            // pixels
  double width_mm = 0, height_mm = 0;   // the panel
  std::vector<float> film_mm;           // the film the frame shows (blurred when blurred); empty without particles
  std::vector<float> stain;             // the spread's stain; empty without the spread
  std::vector<std::uint8_t> rgba;       // the frame
};

// A frame on the common grid, with the measures taken at its own resolution: what a run keeps of
// the reference (in float, to keep a long reference in memory), and what each frame is compared as.
struct GridFrame {
  std::vector<float> film_mm, stain, rgb;   // rgb: three values per cell
  std::vector<double> pile_height_mm;       // per column of the grid
  double covered_area_mm2 = 0;              // the panel's area under film thicker than kCoveredFilmMm
  double volume_mm3 = 0;                    // the film's volume: thickness summed over the panel
};

// How far a frame is from the reference's: NaN where the scene lacks the field.
struct FrameErrors {
  double film_l1_mm, film_l2_mm;    // mean and root-mean-square |Δ thickness| over the grid's cells
  double frame_mse;                 // mean squared difference of R, G, B (0–255)
  double stain_l1;                  // mean |Δ stain|
  double covered_area_rel_error;    // |A − A_ref| / A_ref
  double volume_rel_error;          // |V − V_ref| / V_ref
  double pile_height_error_mm;      // mean over columns of |h − h_ref|
};

// Each output cell of out_w × out_h over the same extent is the mean of the input over its area
// (pixels that straddle a cell edge count by the part inside). Separable: rows, then columns.
std::vector<double> area_resample(const std::vector<double>& in, int in_w, int in_h, int out_w, int out_h,
                                  int channels = 1);

// The common grid for panels of these sizes: the coarsest, and no finer than kMaxGridWidth cells
// across (its aspect kept), so that a reference's frames fit in memory.
constexpr int kMaxGridWidth = 320;
void common_grid(int& grid_w, int& grid_h);

// The height of blood standing at the bottom of each column: from the bottom row up, the cells
// whose film is thicker than kCoveredFilmMm without a gap, times the cell height.
std::vector<double> pile_heights_mm(const std::vector<float>& film_mm, int w, int h, double cell_height_mm);

GridFrame on_grid(const FrameFields& frame, int grid_w, int grid_h);
FrameErrors compare(const GridFrame& run, const GridFrame& reference);

// PSNR of 8-bit colour from a mean squared error, dB; infinite for identical frames.
double psnr_db(double mse);

}  // namespace bleedsim
