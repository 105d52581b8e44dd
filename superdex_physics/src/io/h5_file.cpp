// Checked HDF5 reads and writes (see h5_file.h). Every return value is checked.

#include "io/h5_file.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <filesystem>
#include <limits>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace h5 {

std::unique_lock<std::recursive_mutex> lock() {
  static std::recursive_mutex mutex;
  std::unique_lock<std::recursive_mutex> guard(mutex);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  return guard;
}

namespace {

std::string class_name(H5T_class_t c) {
  switch (c) {
    case H5T_INTEGER: return "integers";
    case H5T_FLOAT: return "floating-point numbers";
    case H5T_STRING: return "a string";
    case H5T_COMPOUND: return "a compound type";
    case H5T_ENUM: return "an enum";
    case H5T_ARRAY: return "an array type";
    case H5T_VLEN: return "a variable-length type";
    case H5T_REFERENCE: return "references";
    case H5T_OPAQUE: return "opaque data";
    case H5T_BITFIELD: return "a bitfield";
    case H5T_TIME: return "a time type";
    default: return "an unknown type";
  }
}

// Dimensions of a dataspace; false when HDF5 cannot tell.
bool read_dims(hid_t space, std::vector<hsize_t>& dims) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) return false;
  dims.assign(static_cast<size_t>(rank), 0);
  return rank == 0 || H5Sget_simple_extent_dims(space, dims.data(), nullptr) >= 0;
}

// The number of values of a shape, or SIZE_MAX when the product overflows (a corrupt header).
size_t element_count(const std::vector<hsize_t>& dims) {
  size_t n = 1;
  for (hsize_t d : dims) {
    if (d == 0) return 0;
    if (n > std::numeric_limits<size_t>::max() / d) return std::numeric_limits<size_t>::max();
    n *= static_cast<size_t>(d);
  }
  return n;
}

std::string dims_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

constexpr size_t kMaxElements = size_t(1) << 31;
constexpr size_t kMaxValuesPerFileByte = 2048;
constexpr size_t kMaxValueBytes = 16;  // the widest numbers HDF5 describes (long double)

}  // namespace

Reader::Reader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": file not found");
  file_bytes_ = std::filesystem::file_size(path, ec);
  if (ec) file_bytes_ = 0;
  if (H5Fis_hdf5(path.c_str()) <= 0) throw Error(path + ": not an HDF5 file (or unreadable)");
  file_ = Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file_.valid()) throw Error(path + ": cannot open the HDF5 file (corrupt or unreadable)");
}

void Reader::fail(const std::string& where, const std::string& what) const { throw Error(path_ + ": " + where + ": " + what); }

void Reader::check_value_size(const std::string& where, hid_t type, H5T_class_t cls) const {
  const size_t bytes = H5Tget_size(type);
  if (bytes == 0 || bytes > kMaxValueBytes)
    fail(where, "wrong type: " + class_name(cls) + " of " + std::to_string(bytes) + " bytes each (expected at most " +
                    std::to_string(kMaxValueBytes) + ")");
}

size_t Reader::checked_count(const std::string& where, const std::vector<hsize_t>& dims) const {
  const size_t n = element_count(dims);
  if (n > kMaxElements) fail(where, "too large: shape " + dims_text(dims) + " holds more than " + std::to_string(kMaxElements) + " values");
  if (n / kMaxValuesPerFileByte > file_bytes_)
    fail(where, "shape " + dims_text(dims) + " declares more values than the file (" + std::to_string(file_bytes_) +
                    " bytes) can hold (corrupt file?)");
  return n;
}

bool Reader::has(const std::string& path) const {
  // H5Lexists needs every intermediate group to exist: check component by component
  size_t pos = 0;
  while (true) {
    const size_t slash = path.find('/', pos);
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    pos = slash + 1;
  }
}

bool Reader::has_attribute(const std::string& group, const std::string& name) const {
  return H5Aexists_by_name(file_.get(), group.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

void Reader::require_group(const std::string& group) const {
  Id g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(group, "is not a group");
}

Numbers Reader::dataset(const std::string& path, bool integers) const {
  if (!has(path)) fail(path, "missing dataset");
  Id ds(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail(path, "is not a dataset");
  Id type(H5Dget_type(ds.get()), H5Tclose);
  Id space(H5Dget_space(ds.get()), H5Sclose);
  if (!type.valid() || !space.valid()) fail(path, "cannot read the dataset's type or shape");
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) fail(path, "wrong type: expected numbers, got " + class_name(cls));
  if (integers && cls != H5T_INTEGER) fail(path, "wrong type: expected integers, got " + class_name(cls));
  check_value_size(path, type.get(), cls);
  Numbers out;
  out.integer_type = cls == H5T_INTEGER;
  if (!read_dims(space.get(), out.dims)) fail(path, "cannot read the dataset's shape");
  const size_t n = checked_count(path, out.dims);
  out.values.resize(n);
  if (n > 0 && H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) < 0)
    fail(path, "cannot read the data (corrupt file?)");
  return out;
}

Numbers Reader::attribute(const std::string& group, const std::string& name) const {
  const std::string where = group + "/" + name;
  if (!has_attribute(group, name)) fail(where, "missing attribute");
  Id attr(H5Aopen_by_name(file_.get(), group.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail(where, "cannot open the attribute");
  Id type(H5Aget_type(attr.get()), H5Tclose);
  Id space(H5Aget_space(attr.get()), H5Sclose);
  if (!type.valid() || !space.valid()) fail(where, "cannot read the attribute's type or shape");
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) fail(where, "wrong type: expected numbers, got " + class_name(cls));
  check_value_size(where, type.get(), cls);
  Numbers out;
  out.integer_type = cls == H5T_INTEGER;
  if (!read_dims(space.get(), out.dims)) fail(where, "cannot read the attribute's shape");
  const size_t n = checked_count(where, out.dims);
  out.values.resize(n);
  if (n > 0 && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, out.values.data()) < 0) fail(where, "cannot read the attribute (corrupt file?)");
  return out;
}

std::string Reader::string_attribute(const std::string& group, const std::string& name) const {
  const std::string where = group + "/" + name;
  if (!has_attribute(group, name)) fail(where, "missing attribute");
  Id attr(H5Aopen_by_name(file_.get(), group.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail(where, "cannot open the attribute");
  Id type(H5Aget_type(attr.get()), H5Tclose);
  Id space(H5Aget_space(attr.get()), H5Sclose);
  if (!type.valid() || !space.valid()) fail(where, "cannot read the attribute's type or shape");
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_STRING) fail(where, "wrong type: expected a string, got " + class_name(cls));
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count != 1) fail(where, "expected one string, got " + std::to_string(count));
  const htri_t variable = H5Tis_variable_str(type.get());
  if (variable < 0) fail(where, "cannot read the string type");
  if (variable > 0) {
    Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
    if (!mem.valid() || H5Tset_size(mem.get(), H5T_VARIABLE) < 0 || H5Tset_cset(mem.get(), H5Tget_cset(type.get())) < 0)
      fail(where, "cannot set up a string read");
    char* buffer = nullptr;
    if (H5Aread(attr.get(), mem.get(), &buffer) < 0) fail(where, "cannot read the attribute");
    std::string s = buffer ? buffer : "";
    if (buffer) H5free_memory(buffer);
    return s;
  }
  const size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (1u << 20)) fail(where, "unreasonable string size " + std::to_string(size));
  std::vector<char> buffer(size + 1, '\0');
  if (H5Aread(attr.get(), type.get(), buffer.data()) < 0) fail(where, "cannot read the attribute");
  std::string s(buffer.data(), strnlen(buffer.data(), size));
  while (!s.empty() && s.back() == ' ') s.pop_back();  // space-padded strings
  return s;
}

std::vector<std::string> Reader::members(const std::string& group) const {
  require_group(group);
  Id g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  H5G_info_t info;
  if (H5Gget_info(g.get(), &info) < 0) fail(group, "cannot list the group");
  if (info.nlinks > kMaxElements) fail(group, "too many members");
  std::vector<std::string> names;
  for (const H5_index_t index : {H5_INDEX_CRT_ORDER, H5_INDEX_NAME}) {
    names.clear();
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t n = H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
      if (n < 0) break;  // creation order not tracked: list by name
      std::string name(static_cast<size_t>(n) + 1, '\0');
      if (H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT) < 0) break;
      name.resize(static_cast<size_t>(n));
      names.push_back(std::move(name));
    }
    if (names.size() == info.nlinks) return names;
  }
  fail(group, "cannot list the group's members");
}

Writer::Writer(const std::string& path) : path_(path) {
  file_ = Id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!file_.valid()) throw Error(path + ": cannot create the HDF5 file (missing directory or no permission?)");
}

void Writer::fail(const std::string& where, const std::string& what) const { throw Error(path_ + ": " + where + ": " + what); }

void Writer::group(const std::string& name, bool track_order) {
  Id plist(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  if (!plist.valid() || (track_order && H5Pset_link_creation_order(plist.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0))
    fail(name, "cannot set up the group");
  Id g(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(name, "cannot create the group");
}

namespace {
template <class T>
void write_dataset(hid_t file, const std::string& path, const std::vector<hsize_t>& dims, const std::vector<T>& values, hid_t file_type,
                   hid_t mem_type, const std::function<void(const std::string&)>& fail) {
  if (element_count(dims) != values.size()) fail("internal error: " + std::to_string(values.size()) + " values for the given shape");
  Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create the dataspace");
  // non-empty data as one chunk, shuffled and deflated (when the library has zlib)
  Id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!plist.valid()) fail("cannot set up the dataset");
  if (!values.empty() && !dims.empty()) {
    if (H5Pset_chunk(plist.get(), static_cast<int>(dims.size()), dims.data()) < 0) fail("cannot set up the dataset's chunk");
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 && (H5Pset_shuffle(plist.get()) < 0 || H5Pset_deflate(plist.get(), 6) < 0))
      fail("cannot set up the dataset's compression");
  }
  Id ds(H5Dcreate2(file, path.c_str(), file_type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail("cannot create the dataset");
  if (!values.empty() && H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) fail("cannot write the data");
}
}  // namespace

void Writer::dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<double>& values) {
  write_dataset(file_.get(), path, dims, values, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, [&](const std::string& what) { fail(path, what); });
}

void Writer::dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<float>& values) {
  write_dataset(file_.get(), path, dims, values, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, [&](const std::string& what) { fail(path, what); });
}

void Writer::dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<int>& values) {
  write_dataset(file_.get(), path, dims, values, H5T_STD_I32LE, H5T_NATIVE_INT, [&](const std::string& what) { fail(path, what); });
}

void Writer::dataset(const std::string& path, const std::vector<hsize_t>& dims, const std::vector<std::int64_t>& values) {
  write_dataset(file_.get(), path, dims, values, H5T_STD_I64LE, H5T_NATIVE_INT64, [&](const std::string& what) { fail(path, what); });
}

void Writer::flush() {
  if (file_.valid() && H5Fflush(file_.get(), H5F_SCOPE_LOCAL) < 0) fail("/", "cannot write the file (disk full?)");
}

namespace {
template <class T>
void write_attribute(hid_t file, const std::string& object, const std::string& name, const std::vector<T>& values, hid_t file_type,
                     hid_t mem_type, const std::function<void(const std::string&)>& fail) {
  const hsize_t n = values.size();
  Id space(values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!space.valid()) fail("cannot create the dataspace");
  Id attr(H5Acreate_by_name(file, object.c_str(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail("cannot create the attribute");
  if (!values.empty() && H5Awrite(attr.get(), mem_type, values.data()) < 0) fail("cannot write the attribute");
}
}  // namespace

void Writer::attribute(const std::string& group, const std::string& name, const std::vector<double>& values) {
  write_attribute(file_.get(), group, name, values, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                  [&](const std::string& what) { fail(group + "/" + name, what); });
}

void Writer::attribute_f32(const std::string& group, const std::string& name, const std::vector<float>& values) {
  write_attribute(file_.get(), group, name, values, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT,
                  [&](const std::string& what) { fail(group + "/" + name, what); });
}

void Writer::string_attribute(const std::string& group, const std::string& name, const std::string& value) {
  const std::string where = group + "/" + name;
  Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), std::max<size_t>(1, value.size())) < 0 || H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0)
    fail(where, "cannot create the string type");
  Id space(H5Screate(H5S_SCALAR), H5Sclose);
  if (!space.valid()) fail(where, "cannot create the dataspace");
  Id attr(H5Acreate_by_name(file_.get(), group.c_str(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose);
  if (!attr.valid()) fail(where, "cannot create the attribute");
  std::vector<char> buffer(std::max<size_t>(1, value.size()), '\0');
  std::memcpy(buffer.data(), value.data(), value.size());
  if (H5Awrite(attr.get(), type.get(), buffer.data()) < 0) fail(where, "cannot write the attribute");
}

void Writer::close() {
  if (!file_.valid()) return;
  const bool flushed = H5Fflush(file_.get(), H5F_SCOPE_LOCAL) >= 0;
  const bool closed = H5Fclose(file_.release()) >= 0;
  if (!flushed || !closed) throw Error(path_ + ": cannot write the file (disk full?)");
}

}  // namespace h5
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
