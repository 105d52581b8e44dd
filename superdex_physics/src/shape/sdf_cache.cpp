// The on-disk cache of computed distance grids: `.mochi.h5` files holding an `sdf/` group,
// named by a 128-bit hash of the mesh and the grid options. Reads that fail or do not match
// the expected layout are treated as misses; writes go through a temporary file and a rename
// so that concurrent processes never see half-written entries.

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

#include "core/fnv_hash.h"
#include "shape/sdf_internal.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mochi_h5.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// FNV-1a and a second, differently based and mixed stream: a 128-bit key, plenty against
// accidental collisions.
struct Hasher {
  Fnv1a64 a;
  std::uint64_t b = 0x6c62272e07bb0142ull;
  void bytes(const void* data, size_t n) {
    a.bytes(data, n);
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      b = (b ^ (p[i] ^ 0x5a)) * 0x100000001b3ull;
      b ^= b >> 31;
    }
  }
  template <class T>
  void value(const T& x) {
    bytes(&x, sizeof x);
  }
};

// The cached grid matches the layout these options give (else it belongs to something else).
bool matches_layout(const SdfGrid& cached, const SdfGrid& layout) {
  if (cached.size != layout.size) return false;
  const real h = (layout.grid_max - layout.grid_min).maxCoeff();
  const real tol = real(1e-5) * h;
  return (cached.grid_min - layout.grid_min).cwiseAbs().maxCoeff() <= tol && (cached.grid_max - layout.grid_max).cwiseAbs().maxCoeff() <= tol;
}

}  // namespace

std::filesystem::path sdf_cache_directory() {
  if (const char* dir = std::getenv("SUPERDEX_CACHE_DIR"); dir && *dir) return dir;
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "superdex" / "sdf";
  return {};
}

std::string sdf_cache_key(const TriangleMesh& mesh, const SdfOptions& options) {
  Hasher h;
  const char tag[] = "superdex-sdf-v1";
  h.bytes(tag, sizeof tag);
  h.value(static_cast<std::uint64_t>(mesh.vertices.size()));
  h.value(static_cast<std::uint64_t>(mesh.triangles.size()));
  for (const Vec3& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) h.value(static_cast<double>(p[k]));
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) h.value(static_cast<std::int32_t>(t[k]));
  h.value(static_cast<std::int32_t>(options.resolution));
  h.value(static_cast<std::int32_t>(options.padding_cells));
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(h.a.value), static_cast<unsigned long long>(h.b));
  return std::string(text) + ".mochi.h5";
}

std::shared_ptr<const SdfGrid> cached_sdf(const TriangleMesh& mesh, const SdfOptions& options, const std::string& where) {
  const std::filesystem::path dir = sdf_cache_directory();
  if (dir.empty()) return std::make_shared<const SdfGrid>(compute_sdf(mesh, options, where));
  const SdfGrid layout = sdf_layout(mesh, options, where);
  const std::filesystem::path file = dir / sdf_cache_key(mesh, options);
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    try {
      MochiH5 entry = read_mochi_h5(file.string());
      if (entry.sdf && matches_layout(entry.sdf->grid, layout)) return std::make_shared<const SdfGrid>(std::move(entry.sdf->grid));
    } catch (const Error&) {
      // corrupt or foreign entry: recompute and overwrite below
    }
  }
  auto grid = std::make_shared<const SdfGrid>(compute_sdf(mesh, options, where));
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path tmp =
      dir / (file.filename().string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++));
  try {
    std::filesystem::create_directories(dir);
    MochiH5 entry;
    entry.sdf = MochiSdf{*grid, std::nullopt, std::nullopt, std::nullopt};
    write_mochi_h5(tmp.string(), entry);
    std::filesystem::rename(tmp, file);
  } catch (const std::exception&) {
    // an unwritable cache only costs the next load a recomputation
    std::filesystem::remove(tmp, ec);
  }
  return grid;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
