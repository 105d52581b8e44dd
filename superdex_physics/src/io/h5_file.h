#pragma once
// A thin, checked layer over the HDF5 C library: owned ids, a process-wide lock (the library
// build may not be thread-safe), and reads and writes of numeric datasets and attributes
// and string attributes. Every failure becomes superdex::Error "<file>: <path>: <defect>".
// HDF5's automatic error printing is switched off.

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace h5 {

// Holds the HDF5 lock for a scope; also silences HDF5's error stack printing.
std::unique_lock<std::recursive_mutex> lock();

// Owns an HDF5 id and closes it with the matching function.
class Id {
 public:
  Id() = default;
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Id(Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Id& operator=(Id&& o) noexcept {
    std::swap(id_, o.id_);
    std::swap(close_, o.close_);
    return *this;
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() {
    if (id_ >= 0 && close_) close_(id_);
  }
  hid_t get() const { return id_; }
  // Gives up ownership without closing.
  hid_t release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

// Values of a dataset or attribute, converted to double, C order, with their dimensions.
struct Numbers {
  std::vector<hsize_t> dims;  // empty for a scalar
  std::vector<double> values;
  bool integer_type = false;  // stored as integers in the file
};

// Read access to one file. Paths are "group/dataset"; attributes hang off groups.
class Reader {
 public:
  // Throws "<file>: file not found" or "<file>: not an HDF5 file (or unreadable)".
  explicit Reader(const std::string& path);

  const std::string& path() const { return path_; }
  // True when `path` ("mesh" or "mesh/coordinates") names an existing link.
  bool has(const std::string& path) const;
  bool has_attribute(const std::string& group, const std::string& name) const;
  // Throws "<file>: <group>: is not a group" when it is something else.
  void require_group(const std::string& group) const;
  // A numeric dataset; with `integers`, floating-point data is a wrong-type error.
  Numbers dataset(const std::string& path, bool integers) const;
  // A numeric attribute (integer or floating-point).
  Numbers attribute(const std::string& group, const std::string& name) const;
  std::string string_attribute(const std::string& group, const std::string& name) const;
  // The names of the links in `group`, in creation order when the group tracks it, else by name.
  std::vector<std::string> members(const std::string& group) const;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const;

 private:
  // Fails unless a dataset or attribute of shape `dims` can be read: its value count must fit
  // in memory and in what the file could hold (kept below 2^31, and below 2048 values per byte
  // of the file: more than any compression achieves, so only a corrupt or hostile header that
  // declares data the file does not have is refused before it is allocated).
  std::size_t checked_count(const std::string& where, const std::vector<hsize_t>& dims) const;
  // Fails unless each value of a numeric type is at most 16 bytes: a corrupt type can claim
  // gigabytes per value, which HDF5 would allocate to convert one value to double.
  void check_value_size(const std::string& where, hid_t type, H5T_class_t cls) const;

  std::string path_;
  std::uintmax_t file_bytes_ = 0;
  Id file_;
};

// Write access to a new file (an existing one is replaced).
class Writer {
 public:
  explicit Writer(const std::string& path);

  // A group; with `track_order` its links are listed in creation order (Reader::members).
  void group(const std::string& name, bool track_order = false);
  // Datasets of float64, float32, int32 or int64 values; non-empty ones are stored as one chunk,
  // shuffled and deflated.
  void dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<double>& values);
  void dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<float>& values);
  void dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<int>& values);
  void dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<std::int64_t>& values);
  // A scalar attribute when `values` has one entry, else a 1-D array, attached to the group or
  // dataset `group`, of float64 values (attribute_f32: float32).
  void attribute(const std::string& group, const std::string& name, const std::vector<double>& values);
  void attribute_f32(const std::string& group, const std::string& name, const std::vector<float>& values);
  void string_attribute(const std::string& group, const std::string& name, const std::string& value);
  // Writes what is buffered to the file (which stays open); throws when it cannot.
  void flush();
  // Flushes and closes; throws when the data could not be written.
  void close();

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const;
  std::string path_;
  Id file_;
};

}  // namespace h5
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
