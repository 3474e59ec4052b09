// A thin RAII layer over the HDF5 C library for what grainflow stores: double datasets that grow
// along their first axis as samples arrive (trajectories), small fixed arrays, and scalar or string
// attributes. Files are written under a temporary name and renamed when closed (see commit()), so a
// run that dies leaves no half-written file under the real name. Every failure throws RunError
// naming the file and the object.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace grainflow::io {

class H5Reader;

// An owned HDF5 identifier, closed with the matching H5*close function.
class H5Handle {
 public:
  using Closer = int (*)(std::int64_t);
  H5Handle() = default;
  H5Handle(std::int64_t id, Closer closer) : id_(id), closer_(closer) {}
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  H5Handle(H5Handle&& other) noexcept { swap(other); }
  H5Handle& operator=(H5Handle&& other) noexcept {
    swap(other);
    return *this;
  }
  ~H5Handle() { reset(); }
  std::int64_t get() const { return id_; }
  void reset();

 private:
  void swap(H5Handle& other) noexcept {
    std::swap(id_, other.id_);
    std::swap(closer_, other.closer_);
  }
  std::int64_t id_ = -1;
  Closer closer_ = nullptr;
};

// A dataset of doubles shaped [samples, rest...] whose first extent grows by append().
class GrowingDataset {
 public:
  GrowingDataset() = default;
  // `row` holds one sample: the product of `shape` (the dimensions after the first).
  void append(const double* row);
  std::size_t samples() const { return samples_; }
  // A restart: appends the first `rows` samples of the same-named dataset in `source` (the copy
  // made with the checkpoint); throws RunError if it holds fewer.
  void append_from(const H5Reader& source, std::size_t rows);

 private:
  friend class H5Writer;
  std::string file_, name_;
  H5Handle dataset_;
  std::vector<unsigned long long> shape_;  // full shape, first extent = samples_
  std::size_t samples_ = 0;
};

class H5Writer {
 public:
  // Creates `path` + ".tmp"; commit() renames it to `path`.
  explicit H5Writer(std::string path);
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  void group(const std::string& name);  // e.g. "/zones"
  // A growing dataset; `shape` are the dimensions after the sample axis, `chunk_samples` how many
  // samples one HDF5 chunk holds.
  GrowingDataset growing(const std::string& name, const std::vector<unsigned long long>& shape,
                         unsigned long long chunk_samples = 64);
  void write(const std::string& name, const std::vector<double>& values, const std::vector<unsigned long long>& shape);
  void write(const std::string& name, const std::vector<std::int64_t>& values);
  void write_bytes(const std::string& name, const std::vector<std::uint8_t>& bytes);  // opaque state (checkpoints)
  // Attributes on the object `where` ("/" for the file).
  void attribute(const std::string& where, const std::string& key, double value);
  void attribute(const std::string& where, const std::string& key, std::int64_t value);
  void attribute(const std::string& where, const std::string& key, const std::string& value);
  // Flushes, closes and renames the temporary file to its real name.
  void commit();
  // Flushes and copies the file as it is now to `path` (via a temporary and a rename): the stream
  // as of a checkpoint, for a restart to continue from.
  void copy_to(const std::string& path);

 private:
  void write_flat(const std::string& name, std::int64_t type, const void* data,
                  std::size_t count);  // 1-D, HDF5 type id
  std::string path_, temporary_;
  H5Handle file_;
  bool committed_ = false;
};

// A restart: appends the first `rows` samples of each dataset from `path`, the stream's copy made
// with the checkpoint; throws InputError naming the file when it is missing, unreadable or short.
void resume_streams(const std::string& path, std::initializer_list<GrowingDataset*> datasets, std::size_t rows);

// Reading back (grainflow analyze, tests).
struct H5Array {
  std::vector<unsigned long long> shape;
  std::vector<double> values;  // row-major
};

class H5Reader {
 public:
  explicit H5Reader(std::string path);
  bool has(const std::string& name) const;
  bool has_attribute(const std::string& where, const std::string& key) const;
  H5Array read(const std::string& name) const;  // any numeric dataset, as doubles
  std::vector<std::uint8_t> read_bytes(const std::string& name) const;
  double number(const std::string& where, const std::string& key) const;
  std::string text(const std::string& where, const std::string& key) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  H5Handle file_;
};

}  // namespace grainflow::io
