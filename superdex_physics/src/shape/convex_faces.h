#pragma once
// A convex polyhedron as its corners and polygon faces: what the convex-convex narrow phase
// needs (support points over the corners, a reference face to clip against), read from a closed
// convex triangle mesh by merging its coplanar triangles, or made for a box.

#include <vector>

#include "superdex/physics/shape.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ConvexFaces {
  std::vector<Vec3> corners;          // the extreme points (m, shape frame)
  std::vector<Vec3> normals;          // outward unit normal per face
  std::vector<real> offsets;          // per face: normal . x for x on the face (m)
  std::vector<int> loop_start;        // face f's corners are loops[loop_start[f] .. loop_start[f + 1])
  std::vector<int> loops;             // corner indices, counter-clockwise seen from outside
  Vec3 centre = Vec3::Zero();         // the corners' mean (an interior point)
  real radius = 0;                    // the farthest corner's distance from `centre` (m)
  // corner c's neighbours along the faces' edges: neighbours[neighbour_start[c] .. [c + 1])
  std::vector<int> neighbour_start, neighbours;
  // on polyhedra of many corners, the farthest corner along each of the 26 directions to the
  // faces, edges and corners of a cube: where a support search without a start begins
  std::vector<int> seeds;
  // on polyhedra of many faces, the faces grouped by the direction of their normals (the cells of
  // a cube map): face_order lists them cell by cell, cell c's from cell_start[c]; the normals of
  // cell c lie within the cone about the unit cell_axis[c] whose half-angle has cosine
  // cell_cos[c] and sine cell_sin[c]
  std::vector<int> face_order, cell_start;
  std::vector<Vec3> cell_axis;
  std::vector<real> cell_cos, cell_sin;

  int num_faces() const { return static_cast<int>(normals.size()); }
  // The corner farthest along `dir` (shape frame): by hill climbing along the edges from `start`
  // (on a convex polyhedron a corner no neighbour improves on is the farthest), from the seed
  // nearest `dir` when start is -1, or by scanning every corner when there is no edge graph.
  int support(const Vec3& dir, int start = -1) const;
  // The face whose outward normal is most aligned with the unit `dir` (shape frame), and that
  // alignment (the cosine of their angle): every face's, or, with cells, those of the cells whose
  // cone could hold a better one than the best found (face 0 and -2 for a direction not finite).
  int face_towards(const Vec3& dir, real& alignment) const;
};

// The faces of a closed, convex, outward-oriented triangle mesh: triangles that share an edge and
// a plane (normals within `angle_tolerance` rad) are one face; vertices on no face boundary (a
// fan's centre) are not corners.
ConvexFaces convex_faces_of(const TriangleMesh& mesh, real angle_tolerance = real(1e-5));

// Fills f.neighbour_start and f.neighbours from its faces' edges.
void build_corner_graph(ConvexFaces& f);

// Fills f's face cells (face_order, cell_start, cell_axis, cell_cos, cell_sin) from its normals,
// when it has enough faces for them to pay off; clears them otherwise.
void build_face_cells(ConvexFaces& f);

// The 8 corners and 6 faces of a box centred on its frame, into `out` (its storage kept).
void box_convex_faces(const Vec3& half_extents, ConvexFaces& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
