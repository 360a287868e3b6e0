#include "core/study/study_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bleedsim {
namespace {

constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

// The weights of a 1-D area resampling: output cell i covers input [i·n/m, (i+1)·n/m) in input
// pixels; each input pixel counts by its overlap, and the weights are divided by the cell's width.
struct Overlap {
  int first;
  std::vector<double> weights;
};

std::vector<Overlap> overlaps(int n, int m) {
  std::vector<Overlap> cells(static_cast<std::size_t>(m));
  const double scale = double(n) / double(m);
  for (int i = 0; i < m; ++i) {
    const double lo = i * scale, hi = (i + 1) * scale;
    Overlap& cell = cells[std::size_t(i)];
    cell.first = int(std::floor(lo));
    for (int j = cell.first; j < n && j < hi; ++j)
      cell.weights.push_back((std::min(hi, double(j + 1)) - std::max(lo, double(j))) / scale);
  }
  return cells;
}

// Resamples `lines` lines of n values to m values each: the rows of an image (along_rows, a line is
// a row y, its values at (y·n + i)) or its columns (a line is a column x of an image `lines` wide,
// its values at (i·lines + x)); each value has `channels` components.
std::vector<double> resample_axis(const std::vector<double>& in, int n, int m, int lines, int channels, bool along_rows) {
  const std::vector<Overlap> cells = overlaps(n, m);
  const auto at = [&](int line, int i, int length) {
    return std::size_t(along_rows ? line * length + i : i * lines + line) * std::size_t(channels);
  };
  std::vector<double> out(std::size_t(m) * std::size_t(lines) * std::size_t(channels), 0.0);
  for (int line = 0; line < lines; ++line)
    for (int i = 0; i < m; ++i) {
      const Overlap& cell = cells[std::size_t(i)];
      for (int c = 0; c < channels; ++c) {
        double sum = 0;
        for (std::size_t k = 0; k < cell.weights.size(); ++k)
          sum += cell.weights[k] * in[at(line, cell.first + int(k), n) + std::size_t(c)];
        out[at(line, i, m) + std::size_t(c)] = sum;
      }
    }
  return out;
}

template <class To, class From>
std::vector<To> converted(const std::vector<From>& v) {
  return std::vector<To>(v.begin(), v.end());
}

template <class T>
double mean_difference(const std::vector<T>& a, const std::vector<T>& b, int power) {
  if (a.empty() || b.empty()) return kNotApplicable;
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::abs(double(a[i]) - double(b[i]));
    sum += power == 1 ? d : d * d;
  }
  return sum / double(a.size());
}

}  // namespace

std::vector<double> area_resample(const std::vector<double>& in, int in_w, int in_h, int out_w, int out_h,
                                  int channels) {
  if (in.size() != std::size_t(in_w) * std::size_t(in_h) * std::size_t(channels))
    throw std::invalid_argument("area_resample: the input is not in_w × in_h × channels values");
  // Across each row (in_w → out_w values), then down each column (in_h → out_h).
  const std::vector<double> rows = resample_axis(in, in_w, out_w, in_h, channels, true);
  return resample_axis(rows, in_h, out_h, out_w, channels, false);
}

void common_grid(int& grid_w, int& grid_h) {
  if (grid_w <= kMaxGridWidth) return;
  grid_h = std::max(1, int(std::lround(double(grid_h) * kMaxGridWidth / grid_w)));
  grid_w = kMaxGridWidth;
}

std::vector<double> pile_heights_mm(const std::vector<float>& film_mm, int w, int h, double cell_height_mm) {
  std::vector<double> heights(std::size_t(w), 0.0);
  for (int x = 0; x < w; ++x) {
    int rows = 0;
    while (rows < h && film_mm[std::size_t(h - 1 - rows) * w + x] > kCoveredFilmMm) ++rows;
    heights[std::size_t(x)] = rows * cell_height_mm;
  }
  return heights;
}

double blood_front_mm(const std::vector<float>& film_mm, int w, int h, double width_mm, double height_mm,
                      double gravity_x, double gravity_y) {
  const double g = std::hypot(gravity_x, gravity_y);
  const double ux = g > 0 ? gravity_x / g : 0.0, uy = g > 0 ? gravity_y / g : 1.0;
  // The most uphill corner: where x·u is least.
  const double origin = std::min(0.0, ux * width_mm) + std::min(0.0, uy * height_mm);
  const double cell_w = width_mm / w, cell_h = height_mm / h;
  double front = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (film_mm[std::size_t(y) * std::size_t(w) + std::size_t(x)] > kCoveredFilmMm)
        front = std::max(front, ux * (x + 0.5) * cell_w + uy * (y + 0.5) * cell_h - origin);
  return front;
}

std::vector<float> film_on_grid(const FrameFields& f, int grid_w, int grid_h) {
  if (f.film_mm.empty()) return {};
  return converted<float>(area_resample(converted<double>(f.film_mm), f.width, f.height, grid_w, grid_h));
}

GridFrame on_grid(const FrameFields& f, int grid_w, int grid_h) {
  GridFrame g;
  g.film_mm = film_on_grid(f, grid_w, grid_h);
  if (!f.stain.empty())
    g.stain = converted<float>(area_resample(converted<double>(f.stain), f.width, f.height, grid_w, grid_h));
  std::vector<double> rgb(std::size_t(f.width) * std::size_t(f.height) * 3);
  for (std::size_t p = 0; p < std::size_t(f.width) * std::size_t(f.height); ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + std::size_t(c)] = f.rgba[p * 4 + std::size_t(c)];
  g.rgb = converted<float>(area_resample(rgb, f.width, f.height, grid_w, grid_h, 3));
  return g;
}

double fastest_speed_mm_s(const std::vector<float>& velocity, const std::vector<std::uint32_t>& age,
                          const ParticleLifetime& lifetime) {
  double fastest = 0;
  for (std::size_t s = 0; s < age.size() && 2 * s + 1 < velocity.size(); ++s)
    if (is_alive(lifetime, age[s])) fastest = std::max(fastest, std::hypot(double(velocity[2 * s]), double(velocity[2 * s + 1])));
  return fastest;
}

double rest_time_s(const std::vector<double>& fastest_mm_s, double frame_s) {
  for (std::size_t k = fastest_mm_s.size(); k-- > 0;)
    if (fastest_mm_s[k] > kRestSpeedMmS) return double(k + 1) * frame_s;
  return 0;
}

FrameMeasures measure_frame(const FrameFields& f, const std::vector<float>& film_grid, int grid_w, int grid_h,
                            double gravity_x, double gravity_y) {
  if (f.film_mm.empty()) return {kNotApplicable, kNotApplicable, kNotApplicable, kNotApplicable, kNotApplicable};
  FrameMeasures m{};
  const double pixel_area_mm2 = (f.width_mm / f.width) * (f.height_mm / f.height);
  m.covered_area_mm2 = 0;
  m.volume_mm3 = 0;
  for (const float t : f.film_mm) {
    m.volume_mm3 += double(t) * pixel_area_mm2;
    if (t > kCoveredFilmMm) m.covered_area_mm2 += pixel_area_mm2;
  }
  m.front_mm = blood_front_mm(film_grid, grid_w, grid_h, f.width_mm, f.height_mm, gravity_x, gravity_y);
  double pile = 0;
  for (const double height : pile_heights_mm(film_grid, grid_w, grid_h, f.height_mm / grid_h)) pile += height;
  m.pile_height_mm = pile / grid_w;
  m.fastest_mm_s = fastest_speed_mm_s(f.velocity, f.age, f.lifetime);
  return m;
}

RunDistance run_distance(const GridFrame& run, const GridFrame& other) {
  RunDistance d;
  d.film_l1_mm = mean_difference(run.film_mm, other.film_mm, 1);
  d.film_l2_mm = std::sqrt(mean_difference(run.film_mm, other.film_mm, 2));
  d.frame_mse = mean_difference(run.rgb, other.rgb, 2);
  d.stain_l1 = mean_difference(run.stain, other.stain, 1);
  return d;
}

double psnr_db(double mse) {
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace bleedsim
