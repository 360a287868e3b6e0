#pragma once
// Scene: everything read-only that a run needs (MuJoCo's "model"). Built from a scenario file by
// load_scenario() or by a host program directly; State holds everything that changes.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/input_error.h"
#include "core/pixel_grid.h"

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

// A cut made by the tool: where and when, and how large a wound (the spread stain's radius and
// growth rate; a cut the scenario or host leaves them out of takes the [spread] defaults).
struct Cut {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double start_s = 0.0;
  double radius_mm = 0.0;
  double growth_per_s = 0.0;
};

// Parameters of the radial spread; present in a Scene only when the scene calls for it.
struct SpreadParams {
  double radius_mm = 4.0;
  double growth_per_s = 0.5;
};

struct OutputSpec {
  std::string dir;                  // where outputs go; relative paths are to the working directory
  bool hdf5 = true;                 // frames.h5 in dir
  int png_every = 0;                // 0: no PNGs; N: frame 0, every Nth frame, and the last
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
  std::vector<Cut> cuts;               // cuts the scenario makes, in the order written (the
                                       // order overlapping stains combine in)
  OutputSpec output;
  std::map<std::string, SourcePlace> places;  // where each key was written, for later messages

  int frame_count() const;
  // Frame k shows the state at the end of its frame period: t = (k + 1) / frame_rate.
  double frame_time_s(std::int64_t k) const;
  // Where `key` was written in the scenario file (the file alone when it was not written).
  SourcePlace place_of(const std::string& key) const;
  // A cut at (x, y) starting at t with the scene's spread defaults for its size.
  Cut cut_at(double x_mm, double y_mm, double start_s) const;
};

}  // namespace bleedsim
