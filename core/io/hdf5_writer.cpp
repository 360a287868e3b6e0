#include "core/io/hdf5_writer.h"

#include <hdf5.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/haptics/haptic_channel.h"
#include "core/io/hdf5_filters.h"
#include "core/io/hdf5_handles.h"
#include "core/runtime/count.h"
#include "core/runtime/memory.h"

namespace bleedsim {
namespace {

using File = Hdf5Handle<H5Fclose>;
using Group = Hdf5Handle<H5Gclose>;
using Dataset = Hdf5Handle<H5Dclose>;
using Dataspace = Hdf5Handle<H5Sclose>;
using Datatype = Hdf5Handle<H5Tclose>;
using Attribute = Hdf5Handle<H5Aclose>;
using PropertyList = Hdf5Handle<H5Pclose>;
using Checker = Hdf5Checker;

// --- Types -------------------------------------------------------------------------------------

// The file types are spelled out (little-endian), so the file does not depend on the host.
hid_t stored_type_of(ElementType type) {
  switch (type) {
    case ElementType::u8: return H5T_STD_U8LE;
    case ElementType::u32: return H5T_STD_U32LE;
    case ElementType::u64: return H5T_STD_U64LE;
    case ElementType::f32: return H5T_IEEE_F32LE;
  }
  throw std::logic_error("HDF5 writer: unknown element type");
}
hid_t memory_type_of(ElementType type) {
  switch (type) {
    case ElementType::u8: return H5T_NATIVE_UINT8;
    case ElementType::u32: return H5T_NATIVE_UINT32;
    case ElementType::u64: return H5T_NATIVE_UINT64;
    case ElementType::f32: return H5T_NATIVE_FLOAT;
  }
  throw std::logic_error("HDF5 writer: unknown element type");
}

Datatype string_type(const Checker& check, size_t size, H5T_cset_t cset) {
  Datatype type{check(H5Tcopy(H5T_C_S1), "copy the string type")};
  check(H5Tset_size(type.get(), size), "size a string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "set string padding");
  check(H5Tset_cset(type.get(), cset), "set a string character set");
  return type;
}

// --- Attributes --------------------------------------------------------------------------------

// Writes a scalar attribute, creating it the first time and overwriting it after (frames_written
// is rewritten on every append).
void write_scalar_attribute(const Checker& check, hid_t object, const std::string& where,
                            const std::string& name, hid_t stored_type, hid_t memory_type,
                            const void* value) {
  const std::string what = "attribute " + name + " of " + where;
  const htri_t exists = H5Aexists(object, name.c_str());
  check(herr_t(exists), "look up " + what);
  Attribute attribute;
  if (exists > 0) {
    attribute = Attribute{check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "open " + what)};
  } else {
    Dataspace scalar{check(H5Screate(H5S_SCALAR), "create a scalar dataspace")};
    attribute = Attribute{
        check(H5Acreate2(object, name.c_str(), stored_type, scalar.get(), H5P_DEFAULT, H5P_DEFAULT),
              "create " + what)};
  }
  check(H5Awrite(attribute.get(), memory_type, value), "write " + what);
}

// Text for people and for h5py: a variable-length UTF-8 string, read back as str.
void write_text_attribute(const Checker& check, hid_t object, const std::string& where,
                          const std::string& name, const std::string& value) {
  Datatype type = string_type(check, H5T_VARIABLE, H5T_CSET_UTF8);
  const char* text = value.c_str();
  write_scalar_attribute(check, object, where, name, type.get(), type.get(), &text);
}

// The HDF5 Image specification wants fixed-length, null-terminated ASCII strings; HDFView looks
// for exactly those before it offers to show a dataset as an image.
void write_image_spec_attribute(const Checker& check, hid_t object, const std::string& where,
                                const std::string& name, const std::string& value) {
  Datatype type = string_type(check, value.size() + 1, H5T_CSET_ASCII);
  write_scalar_attribute(check, object, where, name, type.get(), type.get(), value.c_str());
}

void write_image_attributes(const Checker& check, hid_t dataset, const std::string& where,
                            const FieldLayout& field) {
  if (!field.image) return;  // a per-element array (particles, counters) is no picture
  const bool truecolor =
      field.type == ElementType::u8 && (field.channels == 3 || field.channels == 4);
  const bool grayscale = field.channels == 1;
  if (!truecolor && !grayscale) return;  // no image class fits: HDFView shows it as a table
  write_image_spec_attribute(check, dataset, where, "CLASS", "IMAGE");
  write_image_spec_attribute(check, dataset, where, "IMAGE_VERSION", "1.2");
  if (truecolor) {
    write_image_spec_attribute(check, dataset, where, "IMAGE_SUBCLASS", "IMAGE_TRUECOLOR");
    write_image_spec_attribute(check, dataset, where, "INTERLACE_MODE", "INTERLACE_PIXEL");
  } else {
    write_image_spec_attribute(check, dataset, where, "IMAGE_SUBCLASS", "IMAGE_GRAYSCALE");
    const std::uint8_t white_is_zero = 0;
    write_scalar_attribute(check, dataset, where, "IMAGE_WHITE_IS_ZERO", H5T_STD_U8LE,
                           H5T_NATIVE_UINT8, &white_is_zero);
  }
}

// --- Objects -----------------------------------------------------------------------------------

// Object headers record creation/modification times unless told not to; with them the same run
// would give different bytes every second. Groups and datasets both take the setting.
PropertyList creation_plist(const Checker& check, hid_t plist_class) {
  PropertyList plist{check(H5Pcreate(plist_class), "create a property list")};
  check(H5Pset_obj_track_times(plist.get(), 0), "turn off object time tracking");
  return plist;
}

std::vector<std::string> split_path(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = name.find('/', begin);
    parts.push_back(name.substr(begin, end - begin));
    if (end == std::string::npos) return parts;
    begin = end + 1;
  }
}

// Opens (or creates, without time tracking) every group on the way to `parts`' last element.
Group open_parent_group(const Checker& check, hid_t file, const std::vector<std::string>& parts) {
  Group group{check(H5Gopen2(file, "/", H5P_DEFAULT), "open the root group")};
  std::string where;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    where += "/" + parts[i];
    const char* name = parts[i].c_str();
    const htri_t exists = H5Lexists(group.get(), name, H5P_DEFAULT);
    check(herr_t(exists), "look up group " + where);
    if (exists > 0) {
      group = Group{check(H5Gopen2(group.get(), name, H5P_DEFAULT), "open group " + where)};
    } else {
      PropertyList gcpl = creation_plist(check, H5P_GROUP_CREATE);
      group = Group{check(H5Gcreate2(group.get(), name, H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                          "create group " + where)};
    }
  }
  return group;
}

// A dataset that grows by one frame per append along its first dimension (time).
struct GrowingDataset {
  std::string where;                    // "/spread/stain", for messages
  hid_t memory_type = H5I_INVALID_HID;  // what append() hands over
  std::vector<hsize_t> frame_shape;     // (1, H, W[, C]) for an image, (1, N[, C]) for a
                                        // per-element array, (1) for /time
  Dataset dataset;
};

// Creates it empty, chunked by `chunk_frames` frames.
GrowingDataset create_growing_dataset(const Checker& check, hid_t parent, const std::string& name,
                                      const std::string& where, hid_t stored_type,
                                      hid_t memory_type, std::vector<hsize_t> frame_shape,
                                      hsize_t chunk_frames, int deflate_level) {
  std::vector<hsize_t> dims = frame_shape, max_dims = frame_shape, chunk = frame_shape;
  dims[0] = 0;
  max_dims[0] = H5S_UNLIMITED;
  chunk[0] = chunk_frames;
  Dataspace space{check(H5Screate_simple(int(dims.size()), dims.data(), max_dims.data()),
                        "create the dataspace of " + where)};
  PropertyList dcpl = creation_plist(check, H5P_DATASET_CREATE);
  check(H5Pset_chunk(dcpl.get(), int(chunk.size()), chunk.data()), "set the chunks of " + where);
  if (deflate_level > 0) {
    // Shuffle groups the bytes of each float by significance, which deflate compresses far better.
    check(H5Pset_shuffle(dcpl.get()), "set the shuffle filter of " + where);
    check(H5Pset_deflate(dcpl.get(), unsigned(deflate_level)),
          "set the deflate filter of " + where);
  }
  Dataset dataset{check(H5Dcreate2(parent, name.c_str(), stored_type, space.get(), H5P_DEFAULT,
                                   dcpl.get(), H5P_DEFAULT),
                        "create dataset " + where)};
  return {where, memory_type, std::move(frame_shape), std::move(dataset)};
}

// Grows the dataset to first + rows entries and writes `data` (that many entries) as the last ones.
void write_rows(const Checker& check, const GrowingDataset& target, hsize_t first, hsize_t rows,
                const void* data) {
  const std::string& where = target.where;
  std::vector<hsize_t> dims = target.frame_shape;
  dims[0] = first + rows;
  check(H5Dset_extent(target.dataset.get(), dims.data()), "extend dataset " + where);
  if (rows == 0) return;

  Dataspace file_space{check(H5Dget_space(target.dataset.get()), "get the dataspace of " + where)};
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = first;
  std::vector<hsize_t> count = target.frame_shape;
  count[0] = rows;
  const std::string entries = "entries " + std::to_string(first) + ".." + std::to_string(first + rows - 1);
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                            nullptr),
        "select " + entries + " of " + where);
  Dataspace memory_space{check(H5Screate_simple(int(count.size()), count.data(), nullptr),
                               "create the memory dataspace of " + where)};
  check(H5Dwrite(target.dataset.get(), target.memory_type, memory_space.get(), file_space.get(),
                 H5P_DEFAULT, data),
        "write " + entries + " of " + where);
}

// Grows the dataset to frame + 1 frames and stores `chunk` (its filters already run) as frame `frame`.
// No conversion runs on a chunk written this way: the host's bytes must be the file's (little-endian).
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "chunks are written as the host holds them");
void write_chunk(const Checker& check, const GrowingDataset& target, hsize_t frame,
                 const std::vector<std::uint8_t>& chunk) {
  std::vector<hsize_t> dims = target.frame_shape;
  dims[0] = frame + 1;
  check(H5Dset_extent(target.dataset.get(), dims.data()), "extend dataset " + target.where);
  std::vector<hsize_t> offset(dims.size(), 0);
  offset[0] = frame;
  check(H5Dwrite_chunk(target.dataset.get(), H5P_DEFAULT, 0, offset.data(), chunk.size(), chunk.data()),
        "write entry " + std::to_string(frame) + " of " + target.where);
}

// --- Room for the next frame -------------------------------------------------------------------

// HDF5 updates its superblock and indexes in place as a frame goes in: a write that fails half way
// (a full disk, a file size limit) can leave a file that no longer opens, and HDF5 1.10 then
// crashes closing it. So the room for a whole frame is checked before any of it is written, and a
// run out of room stops with every earlier frame intact. The room is what the file system leaves
// to this user and what the file size limit (ulimit -f) leaves the file. Returns 0, or the errno
// of the write that would fail (ENOSPC, EFBIG) with `left` set to the room there is.
int room_for(const std::string& file, std::uint64_t need, std::uint64_t& left) {
  left = std::numeric_limits<std::uint64_t>::max();
  struct statvfs fs {};
  const std::string folder = std::filesystem::path(file).parent_path().string();
  if (statvfs(folder.empty() ? "." : folder.c_str(), &fs) == 0) left = std::uint64_t(fs.f_bavail) * fs.f_frsize;
  if (left < need) return ENOSPC;
  rlimit limit{};
  struct stat st {};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && stat(file.c_str(), &st) == 0) {
    const std::uint64_t size = std::uint64_t(st.st_size);
    left = limit.rlim_cur > size ? limit.rlim_cur - size : 0;
    if (left < need) return EFBIG;
  }
  return 0;
}

// --- Checks on the caller's input ----------------------------------------------------------------

// HDF5 stores a chunk's size in 32 bits; a frame is one chunk, so one frame must fit.
constexpr std::uint64_t kMaxChunkBytes = 0xffffffffu;
// What a frame's chunk indexes, extended extents and attributes can add, generously: a new index
// node for every dataset, and the file's own.
constexpr std::uint64_t kMetadataPerDataset = 16 * 1024;
constexpr std::uint64_t kMetadataMargin = 64 * 1024;

Count frame_bytes(const FieldLayout& field) {
  return Count(element_size(field.type)) * field.channels * field.width * field.height;
}

void validate(const std::vector<FieldLayout>& fields,
              const std::vector<std::pair<std::string, std::string>>& attributes,
              int deflate_level) {
  if (deflate_level < 0 || deflate_level > 9)
    throw std::invalid_argument("HDF5 deflate level must be 0-9, got " +
                                std::to_string(deflate_level));
  std::set<std::string> names = {"time"};
  for (const FieldLayout& field : fields) {
    const std::string quoted = "HDF5 field '" + field.name + "'";
    for (const std::string& part : split_path(field.name))
      if (part.empty() || part == "." || part == "..")
        throw std::invalid_argument(quoted + ": a name is a relative path like 'spread/stain'");
    if (!names.insert(field.name).second)
      throw std::invalid_argument(quoted + " is named twice (or clashes with /time)");
    if (field.width <= 0 || field.height <= 0 || field.channels <= 0)
      throw std::invalid_argument(quoted + ": width, height and channels must be positive");
    if (!field.image && field.height != 1)
      throw std::invalid_argument(quoted + ": a field that is not an image has height 1 (got " +
                                  std::to_string(field.height) + "); its width counts elements");
    if (frame_bytes(field) > Count(kMaxChunkBytes))
      throw std::runtime_error(quoted +
                               ": one frame is larger than 4 GiB, HDF5's largest chunk "
                               "(each frame is one chunk)");
  }
  std::set<std::string> attribute_names = {"complete", "frames_written"};
  for (const auto& attribute : attributes)
    if (!attribute_names.insert(attribute.first).second)
      throw std::invalid_argument("HDF5 root attribute '" + attribute.first +
                                  "' is given twice or is one the writer sets itself");
}

}  // namespace

// --- The writer --------------------------------------------------------------------------------

struct Hdf5FrameWriter::Impl {
  std::string final_path;
  Checker check;  // names the .partial file
  int deflate_level = 0;
  std::vector<FieldLayout> layouts;  // the fields', in order
  // Declared before the datasets so that it is destroyed after them: HDF5 only really closes a
  // file once nothing in it is open.
  File file;
  GrowingDataset time;
  std::vector<GrowingDataset> fields;
  std::vector<GrowingDataset> haptics;  // one per haptic column, when the run has the channel
  Count frame_bytes = 0;  // one frame of every field
  std::int64_t frames = 0;
  std::int64_t ticks = 0;
  bool finished = false;

  void write_root_attribute(const std::string& name, hid_t stored_type, hid_t memory_type,
                            const void* value) {
    write_scalar_attribute(check, file.get(), "/", name, stored_type, memory_type, value);
  }
  void write_frames_written() {
    write_root_attribute("frames_written", H5T_STD_I64LE, H5T_NATIVE_INT64, &frames);
  }
  void write_complete(bool complete) {
    const std::int8_t value = complete ? 1 : 0;
    write_root_attribute("complete", H5T_STD_I8LE, H5T_NATIVE_INT8, &value);
  }
};

Hdf5FrameWriter::Hdf5FrameWriter(const std::string& path, const std::vector<FieldLayout>& fields,
                                 const std::vector<std::pair<std::string, std::string>>& attributes,
                                 int deflate_level, bool haptic_channel)
    : impl_(std::make_unique<Impl>()) {
  validate(fields, attributes, deflate_level);
  prepare_hdf5_for_writing();

  Impl& impl = *impl_;
  impl.final_path = path;
  impl.check.file = path + ".partial";
  impl.deflate_level = deflate_level;
  impl.layouts = fields;
  const Checker& check = impl.check;

  // The root group is created from the file creation list, which is also an object creation list.
  PropertyList fcpl = creation_plist(check, H5P_FILE_CREATE);
  const hid_t file = H5Fcreate(check.file.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT);
  if (file < 0) throw_hdf5_error("cannot create HDF5 file '" + check.file + "'");
  impl.file = File{file};

  for (const auto& [name, value] : attributes) write_text_attribute(check, file, "/", name, value);
  impl.write_complete(false);
  impl.write_frames_written();

  // One value per frame: chunks of many frames, unfiltered (8 bytes a frame is not worth it).
  impl.time = create_growing_dataset(check, file, "time", "/time", H5T_IEEE_F64LE,
                                     H5T_NATIVE_DOUBLE, {1}, 1024, 0);
  const hid_t time = impl.time.dataset.get();
  write_text_attribute(check, time, "/time", "unit", "s");
  write_text_attribute(check, time, "/time", "description",
                       "simulated time of each frame (end of its frame period)");

  for (const FieldLayout& spec : fields) {
    const std::vector<std::string> parts = split_path(spec.name);
    const std::string where = "/" + spec.name;
    // An image is (T, H, W[, C]); a per-element array (T, N[, C]), as H5MD stores a
    // per-particle time series.
    std::vector<hsize_t> frame_shape = {1};
    if (spec.image) frame_shape.push_back(hsize_t(spec.height));
    frame_shape.push_back(hsize_t(spec.width));
    if (spec.channels != 1) frame_shape.push_back(hsize_t(spec.channels));

    Group parent = open_parent_group(check, file, parts);
    impl.fields.push_back(
        create_growing_dataset(check, parent.get(), parts.back(), where, stored_type_of(spec.type),
                               memory_type_of(spec.type), frame_shape, 1, deflate_level));
    impl.frame_bytes += frame_bytes(spec);
    const hid_t dataset = impl.fields.back().dataset.get();
    write_text_attribute(check, dataset, where, "unit", spec.unit);
    write_text_attribute(check, dataset, where, "description", spec.description);
    write_image_attributes(check, dataset, where, spec);
  }
  if (haptic_channel) {
    // One row per 1 kHz tick, (N) or (N, C): chunks of a second of ticks.
    Group group = open_parent_group(check, file, {"haptics", ""});
    write_text_attribute(check, group.get(), "/haptics", "description",
                         "the 1 kHz haptic loop, one row per tick (docs/haptics.md)");
    for (const HapticColumn& column : haptic_columns()) {
      const std::string where = std::string("/haptics/") + column.name;
      std::vector<hsize_t> row_shape = {1};
      if (column.components != 1) row_shape.push_back(hsize_t(column.components));
      const bool f64 = column.type == HapticColumn::Type::f64;
      impl.haptics.push_back(create_growing_dataset(check, group.get(), column.name, where,
                                                    f64 ? H5T_IEEE_F64LE : H5T_STD_U8LE,
                                                    f64 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_UINT8, row_shape,
                                                    hsize_t(kHapticRate_hz), deflate_level));
      write_text_attribute(check, impl.haptics.back().dataset.get(), where, "unit", column.unit);
      write_text_attribute(check, impl.haptics.back().dataset.get(), where, "description", column.description);
    }
  }
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
}

// Unfinished: the handles close (the file stays valid, with every flushed frame) and the name
// stays .partial, so nobody mistakes it for a finished run.
Hdf5FrameWriter::~Hdf5FrameWriter() = default;

void Hdf5FrameWriter::append(double time_s, const std::vector<const void*>& field_data,
                             const std::vector<HapticTick>& ticks) {
  Impl& impl = *impl_;
  if (field_data.size() != impl.fields.size())
    throw std::invalid_argument("Hdf5FrameWriter::append: " + std::to_string(field_data.size()) +
                                " pointers for " + std::to_string(impl.fields.size()) + " fields");
  std::vector<std::vector<std::uint8_t>> chunks(field_data.size());
  for (std::size_t i = 0; i < field_data.size(); ++i) filter(i, field_data[i], chunks[i]);
  append_chunks(time_s, chunks, ticks);
}

void Hdf5FrameWriter::filter(std::size_t field, const void* frame, std::vector<std::uint8_t>& chunk) const {
  const Impl& impl = *impl_;
  if (field >= impl.layouts.size())
    throw std::invalid_argument("Hdf5FrameWriter::filter: field " + std::to_string(field) + " of " +
                                std::to_string(impl.layouts.size()));
  if (!frame) throw std::invalid_argument("Hdf5FrameWriter::filter: no data for /" + impl.layouts[field].name);
  const FieldLayout& layout = impl.layouts[field];
  const auto* bytes = static_cast<const std::uint8_t*>(frame);
  if (impl.deflate_level == 0) {
    chunk.assign(bytes, bytes + layout.bytes());
    return;
  }
  shuffle_then_deflate(bytes, layout.bytes(), element_size(layout.type), impl.deflate_level, chunk);
}

void Hdf5FrameWriter::append_chunks(double time_s, const std::vector<std::vector<std::uint8_t>>& chunks,
                                    const std::vector<HapticTick>& ticks) {
  Impl& impl = *impl_;
  if (impl.finished) throw std::logic_error("Hdf5FrameWriter::append after finish");
  if (chunks.size() != impl.fields.size())
    throw std::invalid_argument("Hdf5FrameWriter::append_chunks: " + std::to_string(chunks.size()) +
                                " chunks for " + std::to_string(impl.fields.size()) + " fields");
  for (std::size_t i = 0; i < chunks.size(); ++i)
    if (chunks[i].empty())
      throw std::invalid_argument("Hdf5FrameWriter::append_chunks: no data for " + impl.fields[i].where);
  if (!ticks.empty() && impl.haptics.empty())
    throw std::invalid_argument("Hdf5FrameWriter::append: haptic ticks for a file made without the haptic channel");

  // The most one frame can add: its data (deflate can grow a chunk a little), and the indexes.
  const std::size_t datasets = 1 + impl.fields.size() + impl.haptics.size();
  Count need = Count(sizeof time_s) + impl.frame_bytes + Count(impl.frame_bytes.value() / 64) + kMetadataMargin +
               Count(datasets) * kMetadataPerDataset;
  for (const HapticColumn& column : haptic_columns()) need += Count(ticks.size()) * column.components * 8;
  std::uint64_t left = 0;
  if (const int full = room_for(impl.check.file, need.value(), left))
    throw std::runtime_error("cannot write frame " + std::to_string(impl.frames) + " to HDF5 file '" +
                             impl.check.file + "': " + std::strerror(full) + " (" + human_bytes(double(left)) +
                             (full == EFBIG ? " below the file size limit" : " free") + ", a frame takes up to " +
                             human_bytes(need.as_double()) + ")");

  const hsize_t frame = hsize_t(impl.frames);
  write_rows(impl.check, impl.time, frame, 1, &time_s);
  for (std::size_t i = 0; i < chunks.size(); ++i) write_chunk(impl.check, impl.fields[i], frame, chunks[i]);
  // The haptic columns are chunked by a second of ticks, so a frame adds part of a chunk, which HDF5
  // keeps in its chunk cache and filters again at each flush: at most 24 KB a column (1000 ticks of
  // 3 doubles), little beside a frame's fields, so they keep HDF5's own path.
  for (std::size_t c = 0; c < impl.haptics.size(); ++c) {
    const std::vector<std::uint8_t> bytes = haptic_column_bytes(haptic_columns()[c], ticks);
    write_rows(impl.check, impl.haptics[c], hsize_t(impl.ticks), hsize_t(ticks.size()), bytes.data());
  }
  impl.ticks += std::int64_t(ticks.size());
  // The count is only raised once the frame is in every dataset, then all of it goes to disk:
  // a run killed from here on keeps this frame.
  ++impl.frames;
  impl.write_frames_written();
  impl.check(H5Fflush(impl.file.get(), H5F_SCOPE_GLOBAL), "flush");
}

void Hdf5FrameWriter::finish(bool complete) {
  Impl& impl = *impl_;
  if (impl.finished) throw std::logic_error("Hdf5FrameWriter::finish called twice");
  impl.finished = true;  // whatever happens below, the writer takes no more frames

  impl.write_complete(complete);
  impl.write_frames_written();
  // Close explicitly, checking each: only a file that closed cleanly takes its final name.
  impl.check(impl.time.dataset.close(), "close dataset /time");
  for (GrowingDataset& field : impl.fields)
    impl.check(field.dataset.close(), "close dataset " + field.where);
  for (GrowingDataset& column : impl.haptics)
    impl.check(column.dataset.close(), "close dataset " + column.where);
  impl.check(impl.file.close(), "close the file");

  std::error_code error;
  std::filesystem::rename(impl.check.file, impl.final_path, error);
  if (error)
    throw std::runtime_error("cannot rename HDF5 file '" + impl.check.file + "' to '" +
                             impl.final_path + "': " + error.message());
}

int Hdf5FrameWriter::frames_written() const { return int(impl_->frames); }

}  // namespace bleedsim
