#include "grainflow/io/hdf5_file.hpp"

#include <hdf5.h>

#include <cstdio>
#include <filesystem>
#include <numeric>

#include "grainflow/core/error.hpp"

namespace grainflow::io {
namespace {

static_assert(sizeof(hid_t) == sizeof(std::int64_t), "H5Handle stores hid_t as int64");

// HDF5 prints its own error stack to stderr by default; grainflow reports errors itself.
void silence_hdf5() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw RunError("HDF5 file '" + file + "': cannot " + what);
}

hid_t check(hid_t id, const std::string& file, const std::string& what) {
  if (id < 0) fail(file, what);
  return id;
}

void check_status(herr_t status, const std::string& file, const std::string& what) {
  if (status < 0) fail(file, what);
}

int close_file(std::int64_t id) { return H5Fclose(id); }
int close_dataset(std::int64_t id) { return H5Dclose(id); }
int close_space(std::int64_t id) { return H5Sclose(id); }
int close_plist(std::int64_t id) { return H5Pclose(id); }
int close_group(std::int64_t id) { return H5Gclose(id); }
int close_attribute(std::int64_t id) { return H5Aclose(id); }
int close_type(std::int64_t id) { return H5Tclose(id); }
int close_object(std::int64_t id) { return H5Oclose(id); }

}  // namespace

void H5Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

// ---------------------------------------------------------------------------------------------

void GrowingDataset::append_from(const H5Reader& source, std::size_t rows) {
  if (rows == 0) return;
  const H5Array old = source.read(name_);
  if (old.shape.empty() || old.shape[0] < rows)
    throw RunError(source.path() + ": dataset '" + name_ + "' holds " +
                   std::to_string(old.shape.empty() ? 0 : old.shape[0]) + " samples, the checkpoint counts " +
                   std::to_string(rows));
  const std::size_t row = old.values.size() / old.shape[0];
  for (std::size_t k = 0; k < rows; ++k) append(old.values.data() + k * row);
}

void GrowingDataset::append(const double* row) {
  std::vector<hsize_t> extent(shape_.begin(), shape_.end());
  extent[0] = samples_ + 1;
  check_status(H5Dset_extent(dataset_.get(), extent.data()), file_, "extend dataset '" + name_ + "'");
  H5Handle space(check(H5Dget_space(dataset_.get()), file_, "get the space of '" + name_ + "'"), close_space);
  std::vector<hsize_t> start(shape_.size(), 0), count(extent);
  start[0] = samples_;
  count[0] = 1;
  check_status(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), file_,
               "select a sample of '" + name_ + "'");
  H5Handle memory(
      check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), file_, "describe a sample"),
      close_space);
  check_status(H5Dwrite(dataset_.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(), H5P_DEFAULT, row), file_,
               "write a sample of '" + name_ + "'");
  ++samples_;
  shape_[0] = samples_;
}

// ---------------------------------------------------------------------------------------------

H5Writer::H5Writer(std::string path) : path_(std::move(path)), temporary_(path_ + ".tmp") {
  silence_hdf5();
  file_ =
      H5Handle(check(H5Fcreate(temporary_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), temporary_, "create it"),
               close_file);
}

H5Writer::~H5Writer() {
  if (!committed_) {  // an exception unwound past us: leave nothing under either name
    file_.reset();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void H5Writer::group(const std::string& name) {
  H5Handle g(check(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), path_,
                   "create group '" + name + "'"),
             close_group);
}

GrowingDataset H5Writer::growing(const std::string& name, const std::vector<unsigned long long>& shape,
                                 unsigned long long chunk_samples) {
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{std::max<hsize_t>(1, chunk_samples)};
  for (auto s : shape) {
    dims.push_back(s);
    max_dims.push_back(s);
    chunk.push_back(std::max<hsize_t>(1, s));
  }
  H5Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims.data()), path_,
                       "describe dataset '" + name + "'"),
                 close_space);
  H5Handle properties(check(H5Pcreate(H5P_DATASET_CREATE), path_, "create dataset properties"), close_plist);
  check_status(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()), path_,
               "chunk dataset '" + name + "'");
  GrowingDataset d;
  d.file_ = path_;
  d.name_ = name;
  d.dataset_ = H5Handle(check(H5Dcreate2(file_.get(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT,
                                         properties.get(), H5P_DEFAULT),
                              path_, "create dataset '" + name + "'"),
                        close_dataset);
  d.shape_.assign(dims.begin(), dims.end());
  return d;
}

void H5Writer::write(const std::string& name, const std::vector<double>& values,
                     const std::vector<unsigned long long>& shape) {
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  const auto count = std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
  if (count != values.size()) fail(path_, "write '" + name + "': shape does not match the values");
  H5Handle space(
      check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), path_, "describe '" + name + "'"),
      close_space);
  H5Handle d(check(H5Dcreate2(file_.get(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                              H5P_DEFAULT),
                   path_, "create dataset '" + name + "'"),
             close_dataset);
  check_status(H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path_,
               "write dataset '" + name + "'");
}

void H5Writer::write_flat(const std::string& name, std::int64_t type, const void* data, std::size_t count) {
  hsize_t dims[1] = {count};
  H5Handle space(check(H5Screate_simple(1, dims, nullptr), path_, "describe '" + name + "'"), close_space);
  H5Handle d(check(H5Dcreate2(file_.get(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   path_, "create dataset '" + name + "'"),
             close_dataset);
  if (count > 0)
    check_status(H5Dwrite(d.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), path_, "write dataset '" + name + "'");
}

void H5Writer::write_bytes(const std::string& name, const std::vector<std::uint8_t>& bytes) {
  write_flat(name, H5T_NATIVE_UINT8, bytes.data(), bytes.size());
}

void H5Writer::write(const std::string& name, const std::vector<std::int64_t>& values) {
  write_flat(name, H5T_NATIVE_INT64, values.data(), values.size());
}

namespace {
void scalar_attribute(hid_t file, const std::string& path, const std::string& where, const std::string& key, hid_t type,
                      const void* value) {
  H5Handle object(check(H5Oopen(file, where.c_str(), H5P_DEFAULT), path, "open '" + where + "'"), close_object);
  H5Handle space(check(H5Screate(H5S_SCALAR), path, "describe attribute '" + key + "'"), close_space);
  H5Handle a(check(H5Acreate2(object.get(), key.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT), path,
                   "create attribute '" + key + "' on '" + where + "'"),
             close_attribute);
  check_status(H5Awrite(a.get(), type, value), path, "write attribute '" + key + "'");
}
}  // namespace

void H5Writer::attribute(const std::string& where, const std::string& key, double value) {
  scalar_attribute(file_.get(), path_, where, key, H5T_NATIVE_DOUBLE, &value);
}

void H5Writer::attribute(const std::string& where, const std::string& key, std::int64_t value) {
  scalar_attribute(file_.get(), path_, where, key, H5T_NATIVE_INT64, &value);
}

void H5Writer::attribute(const std::string& where, const std::string& key, const std::string& value) {
  H5Handle type(check(H5Tcopy(H5T_C_S1), path_, "make a string type"), close_type);
  check_status(H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())), path_, "size a string type");
  check_status(H5Tset_cset(type.get(), H5T_CSET_UTF8), path_, "set UTF-8");
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  scalar_attribute(file_.get(), path_, where, key, type.get(), padded.data());
}

void H5Writer::copy_to(const std::string& path) {
  check_status(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), path_, "flush");
  const std::string temporary = path + ".tmp";
  std::error_code error;
  std::filesystem::copy_file(temporary_, temporary, std::filesystem::copy_options::overwrite_existing, error);
  if (!error) std::filesystem::rename(temporary, path, error);
  if (error) fail(path, "copy the stream from '" + temporary_ + "': " + error.message());
}

void H5Writer::commit() {
  check_status(H5Fflush(file_.get(), H5F_SCOPE_GLOBAL), path_, "flush it");
  file_.reset();
  std::error_code error;
  std::filesystem::rename(temporary_, path_, error);
  if (error) fail(path_, "rename it from '" + temporary_ + "': " + error.message());
  committed_ = true;
}

// ---------------------------------------------------------------------------------------------

H5Reader::H5Reader(std::string path) : path_(std::move(path)) {
  silence_hdf5();
  file_ = H5Handle(check(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), path_, "open it"), close_file);
}

bool H5Reader::has(const std::string& name) const { return H5Lexists(file_.get(), name.c_str(), H5P_DEFAULT) > 0; }

bool H5Reader::has_attribute(const std::string& where, const std::string& key) const {
  return H5Aexists_by_name(file_.get(), where.c_str(), key.c_str(), H5P_DEFAULT) > 0;
}

std::vector<std::uint8_t> H5Reader::read_bytes(const std::string& name) const {
  H5Handle d(check(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), path_, "open dataset '" + name + "'"),
             close_dataset);
  H5Handle space(check(H5Dget_space(d.get()), path_, "get the space of '" + name + "'"), close_space);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) fail(path_, "read the size of '" + name + "'");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count));
  if (!bytes.empty())
    check_status(H5Dread(d.get(), H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), path_,
                 "read dataset '" + name + "'");
  return bytes;
}

H5Array H5Reader::read(const std::string& name) const {
  H5Handle d(check(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), path_, "open dataset '" + name + "'"),
             close_dataset);
  H5Handle space(check(H5Dget_space(d.get()), path_, "get the space of '" + name + "'"), close_space);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(path_, "read the rank of '" + name + "'");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  H5Array a;
  a.shape.assign(dims.begin(), dims.end());
  a.values.resize(std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>()));
  if (!a.values.empty())
    check_status(H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data()), path_,
                 "read dataset '" + name + "'");
  return a;
}

double H5Reader::number(const std::string& where, const std::string& key) const {
  H5Handle a(check(H5Aopen_by_name(file_.get(), where.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT), path_,
                   "open attribute '" + key + "' of '" + where + "'"),
             close_attribute);
  double value = 0.0;
  check_status(H5Aread(a.get(), H5T_NATIVE_DOUBLE, &value), path_, "read attribute '" + key + "'");
  return value;
}

std::string H5Reader::text(const std::string& where, const std::string& key) const {
  H5Handle a(check(H5Aopen_by_name(file_.get(), where.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT), path_,
                   "open attribute '" + key + "' of '" + where + "'"),
             close_attribute);
  H5Handle type(check(H5Aget_type(a.get()), path_, "get the type of '" + key + "'"), close_type);
  std::string value(H5Tget_size(type.get()), '\0');
  check_status(H5Aread(a.get(), type.get(), value.data()), path_, "read attribute '" + key + "'");
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

void resume_streams(const std::string& path, std::initializer_list<GrowingDataset*> datasets, std::size_t rows) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(
        path, "", "missing: the checkpoint's copy of a stream written as the run goes (keep it beside checkpoint.h5)");
  try {
    const H5Reader source(path);
    for (GrowingDataset* d : datasets) d->append_from(source, rows);
  } catch (const RunError& e) {
    throw InputError(path, "", std::string("cannot continue the stream from it: ") + e.what());
  }
}

}  // namespace grainflow::io
