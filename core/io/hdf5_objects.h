#pragma once
// Groups, text attributes and datasets of a fixed size, written once into an open HDF5 file: what the
// study's file (core/study/study_output.cpp) and the haptic quality group of a run's file
// (core/io/hdf5_haptic_quality.cpp) are made of. Every handle is closed on every path out (a group
// left open keeps its file open, and HDF5 crashes at exit on a file whose close failed); errors are
// exceptions naming the file and the OS error; objects carry no creation times, so the same data
// give the same bytes.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/hdf5_handles.h"

namespace bleedsim {

class Hdf5Objects {
 public:
  using Group = Hdf5Handle<H5Gclose>;

  // `file` names the file in messages. Prepares HDF5 for writing (core/io/hdf5_handles.h).
  explicit Hdf5Objects(std::string file);

  Group group(hid_t parent, const std::string& name) const;
  // A variable-length UTF-8 text attribute (h5py reads it as str).
  void text(hid_t object, const std::string& name, const std::string& value) const;
  // A 64-bit float attribute.
  void number(hid_t object, const std::string& name, double value) const;
  // A dataset of doubles, rows × columns (columns 0: one dimension), with a unit when one is given.
  void numbers(hid_t group, const std::string& name, const std::vector<double>& values, std::size_t columns = 0,
               const std::string& unit = "") const;
  // A one-dimensional dataset of 64-bit integers.
  void integers(hid_t group, const std::string& name, const std::vector<std::int64_t>& values) const;
  // A one-dimensional dataset of variable-length UTF-8 strings.
  void texts(hid_t group, const std::string& name, const std::vector<std::string>& values) const;

  const Hdf5Checker check;

 private:
  using PropertyList = Hdf5Handle<H5Pclose>;
  PropertyList untracked(hid_t plist_class) const;
  // An empty dataset of `type` and shape `dims` (one or two dimensions), to be written once.
  Hdf5Handle<H5Dclose> dataset(hid_t group, const std::string& name, hid_t type, const std::vector<hsize_t>& dims) const;

  PropertyList dataset_create_, group_create_;
};

}  // namespace bleedsim
