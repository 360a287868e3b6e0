#include "core/io/xdmf_writer.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/io/whole_file.h"
#include "core/physics/particles.h"

namespace bleedsim {
namespace {

constexpr const char* kPosition = "particles/position";
constexpr const char* kAge = "particles/age";
constexpr const char* kAccounting = "particles/accounting";

// Enough digits that the reader's parse gives back the same double (times) or float (the panel's
// mm per pixel, which the simulation holds as floats).
std::string exact(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}
std::string exact(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  return text;
}

std::string joined(const std::vector<std::uint64_t>& values) {
  std::string text;
  for (const std::uint64_t value : values) text += (text.empty() ? "" : " ") + std::to_string(value);
  return text;
}

std::string number_type(ElementType type) {
  switch (type) {
    case ElementType::u8: return R"(NumberType="UChar" Precision="1")";
    case ElementType::u32: return R"(NumberType="UInt" Precision="4")";
    case ElementType::u64: return R"(NumberType="UInt" Precision="8")";
    case ElementType::f32: return R"(NumberType="Float" Precision="4")";
  }
  throw std::logic_error("XDMF writer: unknown element type");
}

// Scalar, or Vector for 2 or 3 components (the reader gives a 2-component vector a third, 0),
// or Matrix (the reader keeps every component: RGBA stays 4 bytes a pixel).
const char* attribute_type(int channels) {
  if (channels == 1) return "Scalar";
  return channels <= 3 ? "Vector" : "Matrix";
}

// A field's dataset: (T, H, W[, C]) for an image, (T, N[, C]) otherwise.
std::vector<std::uint64_t> dataset_shape(const FieldLayout& field, std::uint64_t frames) {
  std::vector<std::uint64_t> shape = {frames};
  if (field.image) shape.push_back(std::uint64_t(field.height));
  shape.push_back(std::uint64_t(field.width));
  if (field.channels != 1) shape.push_back(std::uint64_t(field.channels));
  return shape;
}

// Frame `frame` of the field's dataset, its entries from `first` on along the axis after time
// (`count` of them; every entry of the axes after), as an XDMF hyperslab of the HDF5 dataset.
std::string hyperslab(const std::string& h5_name, const FieldLayout& field, std::uint64_t frames,
                      std::uint64_t frame, std::uint64_t first, std::uint64_t count, const std::string& indent) {
  const std::vector<std::uint64_t> shape = dataset_shape(field, frames);
  std::vector<std::uint64_t> start(shape.size(), 0), stride(shape.size(), 1), counts = shape;
  start[0] = frame;
  start[1] = first;
  counts[0] = 1;
  counts[1] = count;
  // The shape the reader sees: for an image (1, H, W[, C]), since it reads (H, W) as H tuples of W
  // components; for a run of particles (count[, C]), the part the function adds to its array.
  const std::vector<std::uint64_t> seen(counts.begin() + (field.image ? 0 : 1), counts.end());
  std::vector<std::uint64_t> selection = start;
  selection.insert(selection.end(), stride.begin(), stride.end());
  selection.insert(selection.end(), counts.begin(), counts.end());
  return indent + R"(<DataItem ItemType="HyperSlab" Type="HyperSlab" Dimensions=")" + joined(seen) + "\">\n" +
         indent + R"( <DataItem Dimensions="3 )" + std::to_string(shape.size()) + R"(" Format="XML">)" +
         joined(selection) + "</DataItem>\n" + indent + R"( <DataItem Dimensions=")" + joined(shape) + "\" " +
         number_type(field.type) + R"( Format="HDF">)" + h5_name + ":/" + field.name + "</DataItem>\n" + indent +
         "</DataItem>\n";
}

// The run's slots of frame `frame`, one hyperslab, or two when the run wraps, read one after the
// other (the function ";" joins arrays end to end). An empty run too is a function: the reader
// fails on an empty hyperslab read alone.
std::string ring_slots(const std::string& h5_name, const FieldLayout& field, std::uint64_t frames,
                       std::uint64_t frame, const RingRun& run, const std::string& indent) {
  const std::uint64_t capacity = std::uint64_t(field.width);
  const std::uint64_t before_wrap = std::min(run.count, capacity - run.first);
  std::string dimensions = std::to_string(run.count);
  if (field.channels != 1) dimensions += " " + std::to_string(field.channels);
  const bool wraps = before_wrap < run.count;
  std::string text = indent + R"(<DataItem ItemType="Function" Function=")" + (wraps ? "$0;$1" : "$0") +
                     R"(" Dimensions=")" + dimensions + "\">\n";
  text += hyperslab(h5_name, field, frames, frame, run.first, before_wrap, indent + " ");
  if (wraps) text += hyperslab(h5_name, field, frames, frame, 0, run.count - before_wrap, indent + " ");
  return text + indent + "</DataItem>\n";
}

// Elements of a frame's grid, indented as its children.
std::string attribute(const FieldLayout& field, const std::string& data) {
  return R"(    <Attribute Name=")" + field.name + R"(" AttributeType=")" + attribute_type(field.channels) +
         R"(" Center="Node">)" + "\n" + data + "    </Attribute>\n";
}

std::string time_element(double time_s) { return R"(    <Time Value=")" + exact(time_s) + "\"/>\n"; }

}  // namespace

RingRun ring_run(std::uint64_t emitted, const std::uint32_t* ages, std::uint64_t capacity,
                 std::uint32_t lifetime_steps) {
  std::uint64_t count = 0;
  for (std::uint64_t slot = 0; slot < capacity; ++slot)
    if ((ages[slot] & ~kAspirated) < lifetime_steps) ++count;
  return {(emitted - count) % capacity, count};
}

XdmfWriter::XdmfWriter(std::string h5_name, const std::vector<FieldLayout>& fields, const PixelGrid& panel,
                       std::uint32_t lifetime_steps)
    : h5_name_(std::move(h5_name)), fields_(fields), panel_(panel), lifetime_steps_(lifetime_steps) {
  bool position = false, age = false, accounting = false;
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    if (fields_[i].name == kPosition) position = true, position_ = i;
    if (fields_[i].name == kAge) age = true, age_ = i;
    if (fields_[i].name == kAccounting) accounting = true, accounting_ = i;
  }
  particles_ = position && age && accounting;
}

void XdmfWriter::add_frame(double time_s, const std::vector<const void*>& field_data) {
  if (field_data.size() != fields_.size())
    throw std::invalid_argument("XdmfWriter::add_frame: " + std::to_string(field_data.size()) + " fields for " +
                                std::to_string(fields_.size()));
  RingRun run;
  if (particles_) {
    const std::uint64_t emitted = static_cast<const std::uint64_t*>(field_data[accounting_])[0];
    run = ring_run(emitted, static_cast<const std::uint32_t*>(field_data[age_]),
                   std::uint64_t(fields_[position_].width), lifetime_steps_);
  }
  frames_.push_back({time_s, run});
}

std::string XdmfWriter::text() const {
  const std::uint64_t frames = frames_.size();
  // Nodes at the pixels' centres, in mm; XDMF lists axes z, y, x. y grows down the panel, as in
  // the frame and the particles' positions.
  const std::string panel_shape =
      R"(    <Topology TopologyType="3DCoRectMesh" Dimensions="1 )" + std::to_string(panel_.height) + " " +
      std::to_string(panel_.width) + "\"/>\n" + "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n" +
      R"(     <DataItem Dimensions="3" Format="XML">0 )" + exact(pixel_centre_y_mm(panel_, 0)) + " " +
      exact(pixel_centre_x_mm(panel_, 0)) + "</DataItem>\n" + R"(     <DataItem Dimensions="3" Format="XML">1 )" +
      exact(panel_.mm_per_px_y) + " " + exact(panel_.mm_per_px_x) + "</DataItem>\n" + "    </Geometry>\n";
  std::string text = "<?xml version=\"1.0\" ?>\n"
                     "<!-- " + h5_name_ + " for ParaView's XDMF Reader: docs/output-format.md#paraview -->\n"
                     "<Xdmf Version=\"2.0\">\n <Domain>\n"
                     "  <Grid Name=\"panel\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::uint64_t k = 0; k < frames; ++k) {
    text += "   <Grid Name=\"panel\" GridType=\"Uniform\">\n" + time_element(frames_[k].time_s) + panel_shape;
    for (const FieldLayout& field : fields_)
      if (field.image)
        text += attribute(field, hyperslab(h5_name_, field, frames, k, 0, std::uint64_t(field.height), "     "));
    text += "   </Grid>\n";
  }
  text += "  </Grid>\n";
  if (particles_) {
    const FieldLayout& position = fields_[position_];
    text += "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::uint64_t k = 0; k < frames; ++k) {
      const RingRun& run = frames_[k].particles;
      text += "   <Grid Name=\"particles\" GridType=\"Uniform\">\n" + time_element(frames_[k].time_s) +
              R"(    <Topology TopologyType="Polyvertex" NodesPerElement="1" NumberOfElements=")" +
              std::to_string(run.count) + "\"/>\n" + "    <Geometry GeometryType=\"XY\">\n" +
              ring_slots(h5_name_, position, frames, k, run, "     ") + "    </Geometry>\n";
      for (const FieldLayout& field : fields_)
        if (!field.image && field.width == position.width && field.name != kPosition && field.name != kAccounting)
          text += attribute(field, ring_slots(h5_name_, field, frames, k, run, "     "));
      text += "   </Grid>\n";
    }
    text += "  </Grid>\n";
  }
  return text + " </Domain>\n</Xdmf>\n";
}

void XdmfWriter::write(const std::string& path) const {
  const std::string description = text();
  write_whole_file(path, description.data(), description.size(), "XDMF description");
}

}  // namespace bleedsim
