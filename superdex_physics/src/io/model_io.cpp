// Loading and saving models (model.h): dispatch by file name or MeshFileType, files from memory,
// and the file names of the material enums.

#include "io/model_io.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "io/file_extension.h"
#include "io/mesh_io_detail.h"
#include "shape/model_mesh.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_io.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

bool GridSdfData::operator==(const GridSdfData& o) const {
  auto same_rotation = [](const std::optional<Quaternion>& a, const std::optional<Quaternion>& b) {
    return a.has_value() == b.has_value() && (!a || a->coeffs() == b->coeffs());
  };
  return dims == o.dims && values == o.values && bounds == o.bounds && negative_value_bounds == o.negative_value_bounds &&
         scale == o.scale && same_rotation(rotation, o.rotation) && translation == o.translation;
}

namespace model_io {

namespace {

struct EnumName {
  const char* text;
  int value;
};
// current names first (they are what files get written with), then the names files used before
constexpr EnumName kMaterialTypes[] = {
    {"NeoHookean", 0}, {"StVenantKirchhoff", 1}, {"LinearElastic", 2}, {"ActiveNeoHookean", 3}, {"ActiveShapeTargetingArap", 4},
    {"Arap", 5},       {"StableNeoHookean", 0},  {"ActiveStableNeoHookean", 3}, {"StVK", 1},    {"Linear", 2},
};
constexpr EnumName kPsdStrategies[] = {
    {"MaterialDefault", 0}, {"None", 1}, {"Projection", 2}, {"Fast", 3}, {"AbsEigenProjection", 4}, {"PerTermProjection", 5},
};

template <size_t N>
std::optional<int> parse_name(const EnumName (&names)[N], std::string_view text) {
  for (const EnumName& n : names)
    if (text == n.text) return n.value;
  return std::nullopt;
}

template <size_t N>
const char* name_of(const EnumName (&names)[N], int value) {
  for (const EnumName& n : names)
    if (n.value == value) return n.text;
  return "?";
}

}  // namespace

const char* material_type_text(SoftMaterialType type) { return name_of(kMaterialTypes, static_cast<int>(type)); }
std::optional<SoftMaterialType> parse_material_type(std::string_view text) {
  const auto v = parse_name(kMaterialTypes, text);
  return v ? std::optional<SoftMaterialType>(static_cast<SoftMaterialType>(*v)) : std::nullopt;
}
const char* psd_strategy_text(MaterialPsdStrategy strategy) { return name_of(kPsdStrategies, static_cast<int>(strategy)); }
std::optional<MaterialPsdStrategy> parse_psd_strategy(std::string_view text) {
  const auto v = parse_name(kPsdStrategies, text);
  return v ? std::optional<MaterialPsdStrategy>(static_cast<MaterialPsdStrategy>(*v)) : std::nullopt;
}

ModelData from_triangle_mesh(const TriangleMesh& mesh) {
  ModelData data;
  data.mesh = mesh_data(mesh.vertices, mesh.triangles);
  return data;
}

}  // namespace model_io

namespace {

// The 8-byte HDF5 signature, at offset 0 (or at 512, 1024, ... after a user block).
bool looks_like_hdf5(std::string_view data) {
  static constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
  for (size_t offset = 0; offset + kSignature.size() <= data.size(); offset = offset == 0 ? 512 : 2 * offset)
    if (data.substr(offset, kSignature.size()) == kSignature) return true;
  return false;
}

// HDF5 reads files: bytes in memory go through a private temporary file (removed afterwards).
ModelData read_h5_bytes(std::string_view data) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("superdex_model_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".mochi.h5");
  struct Remove {
    std::filesystem::path p;
    ~Remove() {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
  } remove{path};
  {
    std::ofstream out(path, std::ios::binary);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!out) throw Error("model bytes: cannot write a temporary file to read the HDF5 data (" + path.string() + ")");
  }
  try {
    return model_io::read_h5(path.string());
  } catch (const Error& e) {
    // name the data, not the temporary file
    std::string what = e.what();
    if (what.rfind(path.string(), 0) == 0) what = "model bytes (HDF5)" + what.substr(path.string().size());
    throw Error(what);
  }
}

}  // namespace

namespace model {

ModelData load_from_file_unchecked(const std::string& path) {
  // ".h5" as written (upper-case names are not HDF5 models)
  if (path.ends_with(".h5")) return model_io::read_h5(path);
  const std::string ext = lower_extension(path);
  if (ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".off") return model_io::from_triangle_mesh(read_mesh_file(path));
  return model_io::read_json(mesh_io::read_bytes(path), path);
}

ModelData load_from_file(const std::string& path) {
  ModelData data = load_from_file_unchecked(path);
  auto_correct(data);
  validate(data);
  return data;
}

ModelData load_from_bytes_unchecked(std::string_view data, MeshFileType type) {
  if (data.empty()) throw Error("model bytes: no data (0 bytes)");
  const std::string bytes(data);
  switch (type) {
    case MeshFileType::Legacy:
      if (looks_like_hdf5(data)) return read_h5_bytes(data);
      return model_io::read_json(data, "model bytes (JSON)");
    case MeshFileType::PLY: return model_io::from_triangle_mesh(read_ply_bytes(bytes, "model bytes (PLY)"));
    case MeshFileType::OFF: return model_io::from_triangle_mesh(read_off_bytes(bytes, "model bytes (OFF)"));
    case MeshFileType::STL: return model_io::from_triangle_mesh(read_stl_bytes(bytes, "model bytes (STL)"));
    case MeshFileType::OBJ: return model_io::from_triangle_mesh(read_obj_bytes(bytes, "model bytes (OBJ)"));
  }
  throw Error("model bytes: unknown MeshFileType " + std::to_string(static_cast<int>(type)));
}

ModelData load_from_bytes(std::string_view data, MeshFileType type) {
  ModelData model = load_from_bytes_unchecked(data, type);
  auto_correct(model);
  validate(model);
  return model;
}

void save_to_file(const ModelData& data, const std::string& path, FileFormat format) {
  if (format != FileFormat::JSON && format != FileFormat::H5)
    throw Error(path + ": unknown FileFormat " + std::to_string(static_cast<int>(format)));
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) throw Error(path + ": cannot create the directory " + parent.string() + ": " + ec.message());
  }
  if (format == FileFormat::H5) {
    model_io::write_h5(path, data);
    return;
  }
  const std::string text = model_io::write_json(data);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw Error(path + ": cannot write the file");
}

std::string save_to_json_string(const ModelData& data) { return model_io::write_json(data); }

}  // namespace model
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
