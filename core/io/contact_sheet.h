#pragma once
// A contact sheet: a few frames spread over a run, shrunk and laid out in a grid in one PNG, so a
// person sees how a scene evolves at a glance.
#include <cstdint>
#include <string>
#include <vector>

namespace bleedsim {

class ContactSheet {
 public:
  // `count` frames (at most frame_count) of a run of frame_count frames of width × height RGBA8.
  ContactSheet(long frame_count, int count, int width, int height);

  // Whether frame k is one of the sheet's: frame 0, the last, and evenly between.
  bool wants(long k) const;
  // Shrinks frame k into its cell (k must be wanted).
  void add(long k, const std::uint8_t* rgba);
  // Writes the sheet (cells not added yet stay dark) as a PNG, through a temporary file.
  void write(const std::string& path) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& rgba() const { return rgba_; }
  // The thumbnails' size: the frame shrunk by a whole factor to at most kThumbWidth px wide.
  int thumb_width() const { return thumb_w_; }
  int thumb_height() const { return thumb_h_; }

  static constexpr int kThumbWidth = 320;
  static constexpr int kGutter = 4;

 private:
  std::vector<long> frames_;  // the frames shown, in order
  int frame_w_, frame_h_, factor_, thumb_w_, thumb_h_, columns_, width_, height_;
  std::vector<std::uint8_t> rgba_;
};

}  // namespace bleedsim
