// Mesh shapes from Python: create_tri_mesh_shape (numpy arrays) and load_shape_from_file
// (.mochi.h5, .obj, .stl, .ply with an optional baked scale and transform).

#include <nanobind/stl/string.h>

#include "bind_common.h"
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
          ShapeBake bake;
          bake.scale = read_scale(bake_scale, where + ": bake_scale");
          const Transform X = read_transform(bake_transform, where + ": bake_transform");
          bake.rotation = X.rotation;
          bake.translation = X.translation;
          // tetrahedra make a tet-mesh shape (for soft actors); other files a rigid shape
          if (std::optional<TetMesh> tets = read_tet_mesh_file(path, bake))
            return create_tet_mesh_shape(std::move(*tets), path);
          return create_shape(load_shape_file(path, bake));
        }, "file_path"_a, "bake_scale"_a.none() = nb::none(), "bake_transform"_a.none() = nb::none(),
        "A shape from a .mochi.h5, .obj, .stl or .ply file. bake_scale (a number or 3 numbers) and then\n"
        "bake_transform (TransformRT) are applied to the vertices before the distance grid is computed.");
}

}  // namespace superdex::python
