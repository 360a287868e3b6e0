#include "cli/frame_output.h"

#include <cstdio>
#include <string>
#include <utility>

#include "core/io/png_writer.h"

namespace bleedsim::cli {
namespace {

std::string png_name(const char* kind, long frame) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%06ld.png", kind, frame);
  return name;
}

}  // namespace

FrameOutput::FrameOutput(FrameOutputs outputs) : out_(std::move(outputs)) {}

OutputWork FrameOutput::work() {
  return {[this](FrameJob& job) { return plan(job); },
          [this](FrameJob& job, int task) { encode(job, task); },
          [this](const FrameJob& job) { write(job); }};
}

bool FrameOutput::png_due(long frame) const {
  return out_.png_every > 0 && (frame % out_.png_every == 0 || frame == out_.frames - 1);
}

bool FrameOutput::view_due(long frame) const {
  return out_.view && (png_due(frame) || (out_.view_sheet && out_.view_sheet->wants(frame)));
}

// The tasks, in the order the workers take them: each field's chunk (the frame's, the largest,
// first), the frame's PNG, the view.
int FrameOutput::plan(FrameJob& job) const {
  job.chunks.resize(out_.hdf5 ? job.fields.size() : 0);
  return int(job.chunks.size()) + (png_due(job.frame) ? 1 : 0) + (view_due(job.frame) ? 1 : 0);
}

void FrameOutput::encode(FrameJob& job, int task) const {
  const int chunks = int(job.chunks.size());
  if (task < chunks) {
    out_.hdf5->filter(std::size_t(task), job.fields[std::size_t(task)].data(), job.chunks[std::size_t(task)]);
    return;
  }
  const std::uint8_t* rgba = job.fields[0].data();
  const bool png = png_due(job.frame);
  if (png && task == chunks) {
    encode_png_rgba((out_.png_folder / png_name("frame", job.frame)).string(), out_.width, out_.height, rgba,
                    job.png);
    return;
  }
  job.view = out_.view(rgba);
  if (png)
    encode_png_rgba((out_.png_folder / png_name("view", job.frame)).string(), job.view.width, job.view.height,
                    job.view.rgba.data(), job.view_png);
}

void FrameOutput::write(const FrameJob& job) {
  const long k = job.frame;
  if (out_.hdf5) out_.hdf5->append_chunks(job.time_s, job.chunks, job.ticks);
  if (out_.xdmf) {
    std::vector<const void*> fields;
    for (const HostBytes& field : job.fields) fields.push_back(field.data());
    out_.xdmf->add_frame(job.time_s, fields);
  }
  if (png_due(k)) {
    write_png_file((out_.png_folder / png_name("frame", k)).string(), job.png);
    ++pngs_;
    if (out_.view) {
      write_png_file((out_.png_folder / png_name("view", k)).string(), job.view_png);
      ++pngs_;
    }
  }
  if (out_.sheet && out_.sheet->wants(k)) out_.sheet->add(k, job.fields[0].data());
  if (out_.view_sheet && out_.view_sheet->wants(k)) out_.view_sheet->add(k, job.view.rgba.data());
}

}  // namespace bleedsim::cli
