#include "core/io/hdf5_objects.h"

#include <utility>

namespace bleedsim {
namespace {

using Datatype = Hdf5Handle<H5Tclose>;

Datatype utf8_text(const Hdf5Checker& check) {
  Datatype type{check(H5Tcopy(H5T_C_S1), "copy the string type")};
  check(H5Tset_size(type.get(), H5T_VARIABLE), "size a string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set a string character set");
  return type;
}

}  // namespace

Hdf5Objects::Hdf5Objects(std::string file) : check{std::move(file)} {
  prepare_hdf5_for_writing();
  dataset_create_ = untracked(H5P_DATASET_CREATE);
  group_create_ = untracked(H5P_GROUP_CREATE);
}

Hdf5Objects::PropertyList Hdf5Objects::untracked(hid_t plist_class) const {
  PropertyList plist{check(H5Pcreate(plist_class), "create a property list")};
  check(H5Pset_obj_track_times(plist.get(), 0), "turn off object time tracking");
  return plist;
}

Hdf5Objects::Group Hdf5Objects::group(hid_t parent, const std::string& name) const {
  return Group{check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, group_create_.get(), H5P_DEFAULT),
                     "create group " + name)};
}

void Hdf5Objects::text(hid_t object, const std::string& name, const std::string& value) const {
  const Datatype type = utf8_text(check);
  const Hdf5Handle<H5Sclose> space{check(H5Screate(H5S_SCALAR), "create a dataspace")};
  const Hdf5Handle<H5Aclose> attribute{
      check(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute " + name)};
  const char* chars = value.c_str();
  check(H5Awrite(attribute.get(), type.get(), &chars), "write attribute " + name);
}

void Hdf5Objects::number(hid_t object, const std::string& name, double value) const {
  const Hdf5Handle<H5Sclose> space{check(H5Screate(H5S_SCALAR), "create a dataspace")};
  const Hdf5Handle<H5Aclose> attribute{
      check(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute " + name)};
  check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

Hdf5Handle<H5Dclose> Hdf5Objects::dataset(hid_t group, const std::string& name, hid_t type,
                                          const std::vector<hsize_t>& dims) const {
  const Hdf5Handle<H5Sclose> space{check(H5Screate_simple(int(dims.size()), dims.data(), nullptr), "create a dataspace")};
  return Hdf5Handle<H5Dclose>{check(
      H5Dcreate2(group, name.c_str(), type, space.get(), H5P_DEFAULT, dataset_create_.get(), H5P_DEFAULT),
      "create dataset " + name)};
}

void Hdf5Objects::numbers(hid_t group, const std::string& name, const std::vector<double>& values, std::size_t columns,
                          const std::string& unit) const {
  const std::vector<hsize_t> dims = columns ? std::vector<hsize_t>{values.size() / columns, columns}
                                            : std::vector<hsize_t>{values.size()};
  const Hdf5Handle<H5Dclose> set = dataset(group, name, H5T_IEEE_F64LE, dims);
  if (!values.empty())
    check(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write dataset " + name);
  if (!unit.empty()) text(set.get(), "unit", unit);
}

void Hdf5Objects::integers(hid_t group, const std::string& name, const std::vector<std::int64_t>& values) const {
  const Hdf5Handle<H5Dclose> set = dataset(group, name, H5T_STD_I64LE, {values.size()});
  if (!values.empty())
    check(H5Dwrite(set.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write dataset " + name);
}

void Hdf5Objects::texts(hid_t group, const std::string& name, const std::vector<std::string>& values) const {
  const Datatype type = utf8_text(check);
  const Hdf5Handle<H5Dclose> set = dataset(group, name, type.get(), {values.size()});
  std::vector<const char*> chars;
  for (const std::string& value : values) chars.push_back(value.c_str());
  if (!values.empty())
    check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, chars.data()), "write dataset " + name);
}

}  // namespace bleedsim
