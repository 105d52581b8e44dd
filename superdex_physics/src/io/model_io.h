#pragma once
// The readers and writers behind model::load_from_* and model::save_to_* (model.h): the
// .mochi.json text, the .mochi.h5 groups, surface meshes as models, and the names that files
// give the material enums.

#include <optional>
#include <string>
#include <string_view>

#include "superdex/physics/model.h"
#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace model_io {

// JSON text of a .mochi.json file (or the deprecated flat format); errors name `source` and the
// JSON path.
ModelData read_json(std::string_view text, const std::string& source);
std::string write_json(const ModelData& data);

// The groups of a .mochi.h5 file (see FORMATS.md); errors name the file and the HDF5 path.
ModelData read_h5(const std::string& path);
void write_h5(const std::string& path, const ModelData& data);

// A surface mesh as a model: a triangle mesh and nothing else.
ModelData from_triangle_mesh(const TriangleMesh& mesh);

// "NeoHookean", "Projection", ... as files write them; parsing also takes the names files used
// before (StableNeoHookean, ActiveStableNeoHookean, StVK, Linear). nullopt when unknown.
const char* material_type_text(SoftMaterialType type);
std::optional<SoftMaterialType> parse_material_type(std::string_view text);
const char* psd_strategy_text(MaterialPsdStrategy strategy);
std::optional<MaterialPsdStrategy> parse_psd_strategy(std::string_view text);
inline constexpr int kNumMaterialTypes = 6;
inline constexpr int kNumPsdStrategies = 6;

}  // namespace model_io
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
