#pragma once
/// @file mesh_test_helpers.h
/// Helpers of the mesh suites: the cube and icosphere builders (mesh_builders.h), a temporary
/// directory removed after the test, and writers of OBJ / STL / PLY text and bytes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "mesh_builders.h"
#include "superdex/physics/error.h"
#include "superdex/physics/shape.h"

namespace superdex::physics::test {

/// The message of the superdex::Error that f throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
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
