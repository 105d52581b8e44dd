// Mesh and model shapes from Python: create_tri/tet_mesh_shape (numpy arrays), create_mesh_shape,
// create_model_shape, load_shape_from_file/bytes (with an optional baked scale and transform),
// and the meshes of a shape (get_shape_mesh, ..._surface_mesh, ..._visual_mesh).

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_model_view.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/mesh_shape.h"

namespace superdex::python {

namespace {

// "(4, 3)" for messages.
std::string shape_text(const nb::ndarray<>& a) {
  std::string s = "(";
  for (size_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// "float32", "int64", ... for messages.
std::string dtype_text(const nb::dlpack::dtype& d) {
  const char* kind = d.code == static_cast<uint8_t>(nb::dlpack::dtype_code::Int)     ? "int"
                     : d.code == static_cast<uint8_t>(nb::dlpack::dtype_code::UInt)  ? "uint"
                     : d.code == static_cast<uint8_t>(nb::dlpack::dtype_code::Float) ? "float"
                     : d.code == static_cast<uint8_t>(nb::dlpack::dtype_code::Bool)  ? "bool"
                                                                                      : "other";
  return kind + std::to_string(d.bits);
}

// Flat values of an array-like of numbers (any shape, C order) with `per_row` values per row;
// integers are required when `integers`.
nb::object flat_rows(nb::handle obj, const std::string& arg, int per_row, bool integers) {
  nb::object np = nb::module_::import_("numpy");
  nb::object a;
  try {
    a = np.attr("asarray")(obj);
  } catch (nb::python_error&) {
    throw Error(arg + ": expected an array of numbers");
  }
  nb::ndarray<> view;
  if (!nb::try_cast(a, view, false)) throw Error(arg + ": expected an array of numbers, got dtype " + std::string(nb::str(a.attr("dtype")).c_str()));
  const auto code = static_cast<nb::dlpack::dtype_code>(view.dtype().code);
  const bool is_int = code == nb::dlpack::dtype_code::Int || code == nb::dlpack::dtype_code::UInt;
  if (integers && !is_int && view.size() > 0) throw Error(arg + ": expected integers, got dtype " + dtype_text(view.dtype()));
  if (!integers && !is_int && code != nb::dlpack::dtype_code::Float) throw Error(arg + ": expected numbers, got dtype " + dtype_text(view.dtype()));
  const bool rows = view.ndim() == 2 && view.shape(1) == static_cast<size_t>(per_row);
  if (!rows && view.ndim() != 1)
    throw Error(arg + ": expected " + std::to_string(per_row) + " values per row, flat or of shape (n, " + std::to_string(per_row) +
                "), got shape " + shape_text(view));
  if (view.size() % per_row != 0)
    throw Error(arg + ": expected a multiple of " + std::to_string(per_row) + " values, got " + std::to_string(view.size()));
  return np.attr("ascontiguousarray")(a, "dtype"_a = np.attr(integers ? "int64" : "float64")).attr("ravel")();
}

// Vertices (3 reals each, m) and elements (`k` vertex indices each) from Python arguments.
template <int K>
void read_mesh(nb::handle coordinates, nb::handle connectivity, const std::string& where, std::vector<Vec3>& nodes,
               std::vector<std::array<int, K>>& elements) {
  const auto cv = nb::cast<nb::ndarray<const double, nb::ndim<1>, nb::c_contig>>(flat_rows(coordinates, where + ": coordinates", 3, false));
  const auto tv = nb::cast<nb::ndarray<const std::int64_t, nb::ndim<1>, nb::c_contig>>(flat_rows(connectivity, where + ": connectivity", K, true));
  const size_t n = cv.shape(0) / 3;
  nodes.reserve(n);
  for (size_t i = 0; i < n; ++i) nodes.emplace_back(real(cv(3 * i)), real(cv(3 * i + 1)), real(cv(3 * i + 2)));
  for (size_t e = 0; e < tv.shape(0) / K; ++e) {
    std::array<int, K> element;
    for (int k = 0; k < K; ++k) {
      const std::int64_t index = tv(K * e + k);
      if (index < 0 || index >= static_cast<std::int64_t>(n))
        throw Error(where + ": connectivity[" + std::to_string(K * e + k) + "] = " + std::to_string(index) + " is out of range [0, " +
                    std::to_string(n) + ")");
      element[k] = static_cast<int>(index);
    }
    elements.push_back(element);
  }
}

// A bake scale: None (1), a number (uniform) or 3 numbers.
Vec3 read_scale(nb::handle obj, const std::string& arg) {
  if (obj.is_none()) return Vec3::Ones();
  const VecX v = read_vector(obj, arg);
  if (v.size() != 1 && v.size() != 3) throw Error(arg + ": expected a number or 3 numbers, got " + std::to_string(v.size()) + " values");
  const Vec3 s = v.size() == 1 ? Vec3::Constant(v[0]) : Vec3(v[0], v[1], v[2]);
  if (!s.allFinite() || (s.array() <= 0).any())
    throw Error(arg + ": must be positive and finite, got (" + std::to_string(s.x()) + ", " + std::to_string(s.y()) + ", " +
                std::to_string(s.z()) + ")");
  return s;
}

// A bake from optional Python arguments: a scale (a number or 3), then a TransformRT.
ShapeBake read_bake(nb::handle bake_scale, nb::handle bake_transform, const std::string& where) {
  ShapeBake bake;
  bake.scale = read_scale(bake_scale, where + ": bake_scale");
  const Transform X = read_transform(bake_transform, where + ": bake_transform");
  bake.rotation = X.rotation;
  bake.translation = X.translation;
  return bake;
}

// The argument `arg` (a T or its view), or T built from the keywords; not both. Errors name `where`.
template <class T>
T data_of(nb::handle arg, nb::kwargs kwargs, const char* arg_name, const std::string& type_name, const std::string& where) {
  if (arg.is_none()) return nb::cast<T>(nb::type<T>()(**kwargs));
  if (kwargs.size() > 0) throw Error(where + ": give either " + arg_name + " or its fields as keywords, not both");
  try {
    return *optional_of<T>(arg);
  } catch (const nb::cast_error&) {
    throw Error(where + ": " + arg_name + ": expected a " + type_name + " or " + type_name + "View");
  }
}

}  // namespace

void export_meshes(nb::module_& m) {
  m.def("create_tri_mesh_shape", [](nb::handle coordinates, nb::handle connectivity) {
          TriangleMesh mesh;
          read_mesh<3>(coordinates, connectivity, "create_tri_mesh_shape", mesh.vertices, mesh.triangles);
          return create_shape(make_mesh_shape(std::move(mesh), "create_tri_mesh_shape"));
        }, "coordinates"_a, "connectivity"_a,
        "A triangle mesh shape: coordinates (3 per node, m, shape frame; flat or (n, 3)), connectivity (3 node indices per\n"
        "triangle, counter-clockwise seen from outside). Closed meshes get a signed-distance grid; open ones only offer\n"
        "surface points and cannot carry mass from a density.");
  m.def("create_tet_mesh_shape", [](nb::handle coordinates, nb::handle connectivity) {
          TetMesh mesh;
          read_mesh<4>(coordinates, connectivity, "create_tet_mesh_shape", mesh.nodes, mesh.tets);
          return create_tet_mesh_shape(std::move(mesh), "create_tet_mesh_shape");
        }, "coordinates"_a, "connectivity"_a,
        "A tetrahedral mesh shape (soft actors; rigid actors take its boundary): coordinates (3 per node, m; flat or (n, 3)),\n"
        "connectivity (4 node indices per tetrahedron, positive volume).");
  m.def("load_shape_from_file", [](nb::handle file_path, nb::handle bake_scale, nb::handle bake_transform) {
          const std::string where = "load_shape_from_file";
          std::string path;
          try {
            path = nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(file_path));
          } catch (const std::exception&) {
            throw Error(where + ": file_path: expected a str or os.PathLike");
          }
          return load_shape_from_file(path, read_bake(bake_scale, bake_transform, where));
        }, "file_path"_a, "bake_scale"_a.none() = nb::none(), "bake_transform"_a.none() = nb::none(),
        "A shape from a .mochi.json, .mochi.h5, .obj, .off, .stl or .ply file. bake_scale (a number or 3 numbers) and\n"
        "then bake_transform (TransformRT) are applied to the model before anything is computed from it.");
  m.def("load_shape_from_bytes", [](nb::handle file_data, nb::handle format, nb::handle bake_scale, nb::handle bake_transform) {
          const std::string where = "load_shape_from_bytes";
          std::string bytes;
          try {
            nb::bytes b(nb::module_::import_("builtins").attr("bytes")(file_data));
            bytes.assign(b.c_str(), b.size());
          } catch (const std::exception&) {
            throw Error(where + ": file_data: expected bytes, a bytearray or an array of bytes");
          }
          MeshFileType type = MeshFileType::Legacy;
          if (!format.is_none()) {
            if (PyBool_Check(format.ptr()) == 0 && nb::try_cast(format, type, false)) {
              // a MeshFileType
            } else if (PyLong_Check(format.ptr()) && nb::cast<int>(format) >= 0 && nb::cast<int>(format) <= static_cast<int>(MeshFileType::OBJ))
              type = static_cast<MeshFileType>(nb::cast<int>(format));
            else
              throw Error(where + ": format: expected a MeshFileType (LEGACY, PLY, OFF, STL or OBJ)");
          }
          return load_shape_from_bytes(bytes, type, read_bake(bake_scale, bake_transform, where));
        }, "file_data"_a, "format"_a.none() = nb::none(), "bake_scale"_a.none() = nb::none(), "bake_transform"_a.none() = nb::none(),
        "A shape from the bytes of a file. format: MeshFileType (LEGACY, the default, tells HDF5 from JSON by its\n"
        "signature); bake_scale and bake_transform as load_shape_from_file.");
  m.def("create_mesh_shape", [](nb::handle mesh, nb::kwargs kwargs) {
          ModelData model;
          model.mesh = data_of<MeshData>(mesh, kwargs, "mesh", "MeshData", "create_mesh_shape");
          return create_model_shape(std::move(model), "create_mesh_shape");
        }, "mesh"_a.none() = nb::none(), "kwargs"_a,
        "A shape from a MeshData (or MeshDataView, or its fields as keywords): tetrahedra (4 nodes per element), triangles\n"
        "(3) or a polyline (2). The data is copied.");
  m.def("create_model_shape", [](nb::handle model, nb::kwargs kwargs) {
          return create_model_shape(data_of<ModelData>(model, kwargs, "model", "ModelData", "create_model_shape"), "create_model_shape");
        }, "model"_a.none() = nb::none(), "kwargs"_a,
        "The shape a ModelData (or ModelDataView, or its fields as keywords) describes: a mesh, a box, a plane or a\n"
        "sphere. The data is copied.");
  m.def("get_shape_mesh", [](const ShapeHandle& shape) { return shared_view(shape_meshes(shape, "get_shape_mesh").mesh); }, "shape"_a,
        "The shape's main mesh (tetrahedra, triangles or a polyline); empty for primitives. The view keeps the data alive.");
  m.def("get_shape_surface_mesh", [](const ShapeHandle& shape) { return shared_view(shape_meshes(shape, "get_shape_surface_mesh").surface); },
        "shape"_a, "The compact triangle surface: only the nodes it uses, in increasing order of their mesh index; empty for primitives.");
  m.def("get_shape_visual_mesh", [](const ShapeHandle& shape) { return shared_view(shape_meshes(shape, "get_shape_visual_mesh").visual); },
        "shape"_a, "The shape's visual mesh; empty when the model has none.");
}

}  // namespace superdex::python
