#include "core/io/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/io/png_writer.h"

namespace bleedsim {

ContactSheet::ContactSheet(long frame_count, int count, int width, int height)
    : frame_w_(width), frame_h_(height) {
  const long n = std::max(1L, std::min<long>(count, frame_count));
  for (long i = 0; i < n; ++i)
    frames_.push_back(n == 1 ? frame_count - 1 : std::lround(double(i) * double(frame_count - 1) / double(n - 1)));
  factor_ = std::max(1, (width + kThumbWidth - 1) / kThumbWidth);
  thumb_w_ = (width + factor_ - 1) / factor_;
  thumb_h_ = (height + factor_ - 1) / factor_;
  columns_ = int(std::ceil(std::sqrt(double(n))));
  const int rows = int((n + columns_ - 1) / columns_);
  width_ = columns_ * thumb_w_ + (columns_ + 1) * kGutter;
  height_ = rows * thumb_h_ + (rows + 1) * kGutter;
  rgba_.assign(std::size_t(width_) * height_ * 4, 32);
  for (std::size_t p = 3; p < rgba_.size(); p += 4) rgba_[p] = 255;
}

bool ContactSheet::wants(long k) const { return std::find(frames_.begin(), frames_.end(), k) != frames_.end(); }

void ContactSheet::add(long k, const std::uint8_t* rgba) {
  const auto at = std::find(frames_.begin(), frames_.end(), k);
  if (at == frames_.end()) throw std::logic_error("frame " + std::to_string(k) + " is not on the contact sheet");
  const int cell = int(at - frames_.begin());
  const int x0 = kGutter + (cell % columns_) * (thumb_w_ + kGutter);
  const int y0 = kGutter + (cell / columns_) * (thumb_h_ + kGutter);
  // Each thumbnail pixel is the mean of the factor × factor block it stands for (fewer at an edge).
  for (int ty = 0; ty < thumb_h_; ++ty)
    for (int tx = 0; tx < thumb_w_; ++tx) {
      unsigned sum[4] = {0, 0, 0, 0}, count = 0;
      for (int y = ty * factor_; y < std::min(frame_h_, (ty + 1) * factor_); ++y)
        for (int x = tx * factor_; x < std::min(frame_w_, (tx + 1) * factor_); ++x, ++count)
          for (int c = 0; c < 4; ++c) sum[c] += rgba[(std::size_t(y) * frame_w_ + x) * 4 + c];
      std::uint8_t* out = &rgba_[(std::size_t(y0 + ty) * width_ + x0 + tx) * 4];
      for (int c = 0; c < 4; ++c) out[c] = std::uint8_t((sum[c] + count / 2) / count);
    }
}

void ContactSheet::write(const std::string& path) const { write_png_rgba(path, width_, height_, rgba_.data()); }

}  // namespace bleedsim
