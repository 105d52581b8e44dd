// Loading the shape files that the links of an articulation description name (prefab.h
// load_link_shape_files): `.superdex_bot` files and their importers.

#include <filesystem>

#include "io/prefab_shapes.h"
#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/prefab.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& what) {
  throw Error(file + ": " + path + ": " + what);
}

}  // namespace

void load_link_shape_files(ArticulationDesc& desc, const std::string& base_dir, const std::string& source, real scale) {
  for (size_t i = 0; i < desc.links.size(); ++i) {
    LinkDesc& link = desc.links[i];
    const std::string path = "links[" + std::to_string(i) + "].shape";
    if (link.shape && scale != 1) link.shape = prefab::scaled_primitive(*link.shape, scale), link.link_from_shape.translation *= scale;
    if (link.center_of_mass && scale != 1) *link.center_of_mass *= scale;
    // the render model (.glb, for the debugger), relative to the file
    if (!link.render_model.empty()) {
      fs::path model_path(link.render_model);
      if (model_path.is_relative()) model_path = fs::path(base_dir) / model_path;
      const std::string field = "links[" + std::to_string(i) + "].renderModel";
      if (!is_existing_file(model_path)) fail(source, field, "render model '" + model_path.string() + "' does not exist");
      if (model_path.extension() != ".glb") fail(source, field, "render models are binary glTF (.glb) files, got '" + model_path.string() + "'");
      link.render_model = model_path.lexically_normal().string();
      if (scale != 1) link.render_model_scale *= scale;
    }
    if (link.shape_file.empty()) continue;
    fs::path shape_path(link.shape_file);
    if (shape_path.is_relative()) shape_path = fs::path(base_dir) / shape_path;
    if (!is_existing_file(shape_path)) fail(source, path, "shape file '" + shape_path.string() + "' does not exist");
    ShapeBake bake;
    bake.scale = link.shape_scale * scale;
    link.link_from_shape.translation *= scale;  // the file's pose (shapeTranslation), kept as the shape's
    try {
      link.shape = load_shape_file(shape_path.string(), bake);
    } catch (const Error& e) {
      fail(source, path, e.what());
    }
    link.shape_scale = Vec3::Ones();
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
