#pragma once
/// @file mesh_test_helpers.h
/// Builders for the mesh suites: a cube and an icosphere as TriangleMesh, a temporary
/// directory removed after the test, and writers of OBJ / STL / PLY text and bytes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "superdex/physics/shape.h"

namespace superdex::physics::test {

/// An axis-aligned cube centred at `center` with the given half side (m), 8 vertices,
/// 12 triangles counter-clockwise seen from outside.
inline TriangleMesh cube_mesh(double half = 0.5, const Vec3& center = Vec3::Zero()) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(center + Vec3(real(i & 1 ? half : -half), real(i & 2 ? half : -half), real(i & 4 ? half : -half)));
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

/// An icosahedron subdivided `levels` times and projected on the sphere of `radius` (m):
/// 20 * 4^levels triangles, counter-clockwise seen from outside.
inline TriangleMesh icosphere(int levels, double radius = 1) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& tri : f) {
      const int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], ab, ca});
      g.push_back({tri[1], bc, ab});
      g.push_back({tri[2], ca, bc});
      g.push_back({ab, bc, ca});
    }
    f = std::move(g);
  }
  TriangleMesh m;
  for (const auto& p : v) m.vertices.push_back((radius * p).cast<real>());
  m.triangles = f;
  return m;
}

/// Exact signed distance (m) to an axis-aligned box of half extents h centred at the origin.
inline double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& h) {
  const Eigen::Vector3d q = p.cwiseAbs() - h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// A fresh directory under the system temp dir, removed with its contents at scope exit.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("superdex_" + std::string(info ? info->name() : "test") + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Writes `content` to `path` (binary-safe) and returns the path.
inline std::string write_file(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
  return path;
}

/// The mesh as OBJ text (1-based indices).
inline std::string obj_text(const TriangleMesh& m) {
  std::ostringstream os;
  os.precision(17);
  for (const Vec3& p : m.vertices) os << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : m.triangles) os << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return os.str();
}

/// The mesh as ASCII STL text.
inline std::string stl_ascii_text(const TriangleMesh& m) {
  std::ostringstream os;
  os.precision(9);
  os << "solid test\n";
  for (const auto& t : m.triangles) {
    os << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) os << "      vertex " << m.vertices[t[k]].x() << " " << m.vertices[t[k]].y() << " " << m.vertices[t[k]].z() << "\n";
    os << "    endloop\n  endfacet\n";
  }
  os << "endsolid test\n";
  return os.str();
}

/// The mesh as binary STL bytes (little-endian).
inline std::string stl_binary_bytes(const TriangleMesh& m) {
  std::string out(80, ' ');
  auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  const std::uint32_t count = static_cast<std::uint32_t>(m.triangles.size());
  put(&count, 4);
  for (const auto& t : m.triangles) {
    const float zero[3] = {0, 0, 0};
    put(zero, 12);
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const float x = static_cast<float>(m.vertices[t[k]][a]);
        put(&x, 4);
      }
    const std::uint16_t attr = 0;
    put(&attr, 2);
  }
  return out;
}

/// The mesh as PLY: "ascii" text, or "binary_little_endian" with float x y z and a
/// uchar/int face list.
inline std::string ply_bytes(const TriangleMesh& m, bool binary) {
  std::ostringstream os;
  os << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment test mesh\n";
  os << "element vertex " << m.vertices.size() << "\nproperty float x\nproperty float y\nproperty float z\n";
  os << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string out = os.str();
  if (!binary) {
    std::ostringstream body;
    body.precision(9);
    for (const Vec3& p : m.vertices) body << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const auto& t : m.triangles) body << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    return out + body.str();
  }
  for (const Vec3& p : m.vertices)
    for (int a = 0; a < 3; ++a) {
      const float x = static_cast<float>(p[a]);
      out.append(reinterpret_cast<const char*>(&x), 4);
    }
  for (const auto& t : m.triangles) {
    out.push_back(3);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = t[k];
      out.append(reinterpret_cast<const char*>(&i), 4);
    }
  }
  return out;
}

}  // namespace superdex::physics::test
