// Convex polyhedra as polygon faces: coplanar triangles merged by union-find over shared edges,
// each face's boundary walked from its edges whose twin lies on another face.

#include "shape/convex_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The 26 unit directions from a cube's centre to its faces, edges and corners.
constexpr int kNumSeeds = 26;
const std::array<Vec3, kNumSeeds>& seed_directions() {
  static const std::array<Vec3, kNumSeeds> table = [] {
    std::array<Vec3, kNumSeeds> t;
    for (int k = 0; k < kNumSeeds; ++k) {
      const int i = k < 13 ? k : k + 1;  // components -1, 0, 1; the centre (13) skipped
      t[k] = Vec3(real(i % 3 - 1), real(i / 3 % 3 - 1), real(i / 9 - 1)).normalized();
    }
    return t;
  }();
  return table;
}

// Face cells: a cube map of kCellSide x kCellSide cells on each of its 6 faces.
constexpr int kCellSide = 6, kNumCells = 6 * kCellSide * kCellSide;

// The cell of a direction: the cube face of its largest component, and the other two components
// over it, each in kCellSide bins.
int cell_of(const Vec3& n) {
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) > std::abs(n[axis])) axis = i;
  const int side = 2 * axis + (n[axis] < 0 ? 1 : 0);
  const real m = std::abs(n[axis]);
  int bins[2];
  for (int j = 0, i = 0; i < 3; ++i) {
    if (i == axis) continue;
    const real u = m > 0 ? n[i] / m : real(0);  // in [-1, 1]
    bins[j++] = std::clamp(static_cast<int>((u + 1) / 2 * kCellSide), 0, kCellSide - 1);
  }
  return (side * kCellSide + bins[0]) * kCellSide + bins[1];
}

}  // namespace

int ConvexFaces::support(const Vec3& dir, int start) const {
  const int n = static_cast<int>(corners.size());
  if (neighbour_start.size() != corners.size() + 1) {
    int best = 0;
    real best_dot = corners[0].dot(dir);
    for (int i = 1; i < n; ++i) {
      const real d = corners[i].dot(dir);
      if (d > best_dot) best_dot = d, best = i;
    }
    return best;
  }
  int at = start >= 0 && start < n ? start : 0;
  if (start < 0 && !seeds.empty()) {
    // the seed whose direction is nearest dir
    real best_dot = -std::numeric_limits<real>::infinity();
    for (int k = 0; k < kNumSeeds; ++k) {
      const real d = seed_directions()[k].dot(dir);
      if (d > best_dot) best_dot = d, at = seeds[k];
    }
  }
  real at_dot = corners[at].dot(dir);
  // steepest strictly uphill moves only: it ends, and at a corner no neighbour improves on
  for (;;) {
    int best = at;
    real best_dot = at_dot;
    for (int k = neighbour_start[at]; k < neighbour_start[at + 1]; ++k) {
      const int c = neighbours[k];
      const real d = corners[c].dot(dir);
      if (d > best_dot) best = c, best_dot = d;
    }
    if (best == at) break;
    at = best;
    at_dot = best_dot;
  }
  return at;
}

int ConvexFaces::face_towards(const Vec3& dir, real& alignment) const {
  int best = 0;
  alignment = -2;
  auto consider = [&](int face) {
    const real a = normals[face].dot(dir);
    if (a > alignment) alignment = a, best = face;
  };
  auto scan = [&](const int* faces, int count) {
    for (int k = 0; k < count; ++k) consider(faces[k]);
  };
  if (cell_start.empty() || !dir.allFinite()) {
    for (int k = 0; k < num_faces(); ++k) consider(k);
    return best;
  }
  // a cell's normals are at least (angle to its axis) - (its half-angle) from dir, their
  // alignment at most the cosine of that: after dir's own cell, only the cells whose bound is
  // not below the best found are scanned (with the bound's round-off: unit vectors to a few
  // epsilons)
  const int own = cell_of(dir);
  scan(face_order.data() + cell_start[own], cell_start[own + 1] - cell_start[own]);
  const real slack = 16 * std::numeric_limits<real>::epsilon();
  for (int c = 0; c < kNumCells; ++c) {
    if (c == own || cell_start[c] == cell_start[c + 1]) continue;
    const real ca = cell_axis[c].dot(dir);
    if (ca < cell_cos[c]) {
      // dir outside the cone: cos(angle - half-angle)
      const real sa = std::sqrt(std::max(real(0), 1 - ca * ca));
      if (ca * cell_cos[c] + sa * cell_sin[c] + slack < alignment) continue;
    }
    scan(face_order.data() + cell_start[c], cell_start[c + 1] - cell_start[c]);
  }
  return best;
}

void build_face_cells(ConvexFaces& f) {
  f.face_order.clear();
  f.cell_start.clear();
  f.cell_axis.clear();
  f.cell_cos.clear();
  f.cell_sin.clear();
  // a scan of a few dozen normals is cheaper than the cells' bounds
  constexpr int kMinFaces = 64;
  const int nf = f.num_faces();
  if (nf < kMinFaces) return;
  const int num_cells = kNumCells;
  std::vector<int> cell(nf), count(num_cells + 1, 0);
  for (int k = 0; k < nf; ++k) ++count[(cell[k] = cell_of(f.normals[k])) + 1];
  for (int c = 0; c < num_cells; ++c) count[c + 1] += count[c];
  f.cell_start = count;
  f.face_order.resize(nf);
  for (int k = 0; k < nf; ++k) f.face_order[count[cell[k]]++] = k;
  // each cell's cone: about its normals' mean direction, out to the farthest of them
  f.cell_axis.assign(num_cells, Vec3::UnitZ());
  f.cell_cos.assign(num_cells, real(1));
  f.cell_sin.assign(num_cells, real(0));
  for (int c = 0; c < num_cells; ++c) {
    const int s = f.cell_start[c], e = f.cell_start[c + 1];
    if (s == e) continue;
    Vec3 axis = Vec3::Zero();
    for (int k = s; k < e; ++k) axis += f.normals[f.face_order[k]];
    axis = axis.norm() > 0 ? Vec3(axis.normalized()) : f.normals[f.face_order[s]];
    real cos_half = 1;
    for (int k = s; k < e; ++k) cos_half = std::min(cos_half, axis.dot(f.normals[f.face_order[k]]));
    cos_half = std::clamp(cos_half, real(-1), real(1));
    f.cell_axis[c] = axis;
    f.cell_cos[c] = cos_half;
    f.cell_sin[c] = std::sqrt(std::max(real(0), 1 - cos_half * cos_half));
  }
}

void build_corner_graph(ConvexFaces& f) {
  f.seeds.clear();
  // hill climbing from one corner crosses about the square root of the corners: seeds pay off
  // on large hulls only
  if (f.corners.size() > 32)
    for (int k = 0; k < kNumSeeds; ++k) {
      const Vec3& d = seed_directions()[k];
      int best = 0;
      for (int c = 1; c < static_cast<int>(f.corners.size()); ++c)
        if (f.corners[c].dot(d) > f.corners[best].dot(d)) best = c;
      f.seeds.push_back(best);
    }
  std::vector<std::vector<int>> adj(f.corners.size());
  for (int face = 0; face < f.num_faces(); ++face) {
    const int s = f.loop_start[face], e = f.loop_start[face + 1];
    for (int k = s; k < e; ++k) {
      const int a = f.loops[k], b = f.loops[k + 1 < e ? k + 1 : s];
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
  }
  f.neighbour_start.assign(1, 0);
  f.neighbours.clear();
  for (std::vector<int>& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    f.neighbours.insert(f.neighbours.end(), a.begin(), a.end());
    f.neighbour_start.push_back(static_cast<int>(f.neighbours.size()));
  }
}

namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

std::uint64_t edge_key(int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); }

}  // namespace

ConvexFaces convex_faces_of(const TriangleMesh& mesh, real angle_tolerance) {
  const int nt = static_cast<int>(mesh.triangles.size());
  std::vector<Vec3> normal(nt);
  std::vector<real> area(nt);
  std::unordered_map<std::uint64_t, int> edge_triangle;  // directed edge -> its triangle
  edge_triangle.reserve(3 * static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 c = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
    area[t] = c.norm() / 2;
    normal[t] = area[t] > 0 ? Vec3(c.normalized()) : Vec3::Zero();
    for (int k = 0; k < 3; ++k) edge_triangle[edge_key(tri[k], tri[(k + 1) % 3])] = t;
  }
  // neighbours across an edge on one plane (or a degenerate triangle) are one face
  const real min_cos = std::cos(angle_tolerance);
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const auto it = edge_triangle.find(edge_key(tri[(k + 1) % 3], tri[k]));
      if (it == edge_triangle.end()) continue;
      const int u = it->second;
      if (area[t] == 0 || area[u] == 0 || normal[t].dot(normal[u]) >= min_cos) parent[find_root(parent, t)] = find_root(parent, u);
    }
  }
  std::vector<int> face_of_root(nt, -1);
  std::vector<std::vector<int>> members;
  for (int t = 0; t < nt; ++t) {
    const int r = find_root(parent, t);
    if (face_of_root[r] < 0) face_of_root[r] = static_cast<int>(members.size()), members.emplace_back();
    members[face_of_root[r]].push_back(t);
  }
  ConvexFaces out;
  std::unordered_map<int, int> corner_of;  // mesh vertex -> corner
  for (const std::vector<int>& face : members) {
    // boundary: directed edges whose twin is on another face
    std::unordered_map<int, int> next;
    Vec3 n = Vec3::Zero();
    for (int t : face) {
      n += area[t] * normal[t];
      const auto& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const int a = tri[k], b = tri[(k + 1) % 3];
        const auto twin = edge_triangle.find(edge_key(b, a));
        if (twin == edge_triangle.end() || find_root(parent, twin->second) != find_root(parent, t)) next[a] = b;
      }
    }
    if (next.size() < 3 || !(n.norm() > 0)) continue;  // a sliver of zero area
    n.normalize();
    out.loop_start.push_back(static_cast<int>(out.loops.size()));
    // the boundary walked from its smallest vertex (deterministic), at most once around
    int start = next.begin()->first;
    for (const auto& [a, b] : next) start = std::min(start, a);
    real offset = 0;
    int count = 0;
    for (int v = start; count < static_cast<int>(next.size());) {
      auto [it, inserted] = corner_of.try_emplace(v, static_cast<int>(out.corners.size()));
      if (inserted) out.corners.push_back(mesh.vertices[v]);
      out.loops.push_back(it->second);
      offset += n.dot(mesh.vertices[v]);
      ++count;
      const auto nx = next.find(v);
      if (nx == next.end() || nx->second == start) break;
      v = nx->second;
    }
    out.normals.push_back(n);
    out.offsets.push_back(offset / count);
  }
  out.loop_start.push_back(static_cast<int>(out.loops.size()));
  for (const Vec3& c : out.corners) out.centre += c;
  if (!out.corners.empty()) out.centre /= static_cast<real>(out.corners.size());
  for (const Vec3& c : out.corners) out.radius = std::max(out.radius, (c - out.centre).norm());
  build_corner_graph(out);
  build_face_cells(out);
  return out;
}

void box_convex_faces(const Vec3& h, ConvexFaces& out) {
  out.corners.resize(8);
  for (int i = 0; i < 8; ++i) out.corners[i] = Vec3((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(), (i & 4 ? 1 : -1) * h.z());
  // corner i has bit 0 for +x, bit 1 for +y, bit 2 for +z; each face counter-clockwise from outside
  static constexpr int kLoops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  out.normals = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
  out.offsets = {h.x(), h.x(), h.y(), h.y(), h.z(), h.z()};
  out.loops.clear();
  out.loop_start.clear();
  for (const auto& loop : kLoops) {
    out.loop_start.push_back(static_cast<int>(out.loops.size()));
    out.loops.insert(out.loops.end(), loop, loop + 4);
  }
  out.loop_start.push_back(static_cast<int>(out.loops.size()));
  out.centre = Vec3::Zero();
  out.radius = h.norm();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
