/// @file convex_contact_test.cpp
/// Convex-convex contact (GJK/EPA and face clipping) against references that do not share its
/// code: the separating-axis box-box test for random overlapping boxes, analytic gaps for
/// stacked, edge-crossed and vertex-down shapes, and brute-force scans for the hill-climbing
/// support search and the face search through cells of face normals. Also the faces read back from a hull, and hulls of near-duplicate points.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "collision/collision_detection.h"
#include "mesh_builders.h"
#include "superdex/physics/convex_hull.h"
#include "superdex/physics/mesh_shape.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics::test {
namespace {

// A box as a convex mesh shape (its hull), so that the pair goes through the convex path.
MeshShape box_hull(const Vec3& h) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.push_back(Vec3((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(), (i & 4 ? 1 : -1) * h.z()));
  return make_convex_hull_shape(corners, "box");
}

SpatialTransform pose(const Vec3& p, const Quat& q = Quat::Identity()) {
  SpatialTransform X;
  X.R = q.toRotationMatrix();
  X.p = p;
  return X;
}

real deepest(const std::vector<ShapeContact>& c) {
  real d = std::numeric_limits<real>::infinity();
  for (const ShapeContact& x : c) d = std::min(d, x.phi);
  return d;
}

TEST(ConvexFaces, HullOfACubeHasSixSquareFacesAndEightCorners) {
  const MeshShape s = box_hull(Vec3(0.1, 0.2, 0.3));
  ASSERT_TRUE(s.convex);
  ASSERT_TRUE(s.faces);
  const ConvexFaces& f = *s.faces;
  EXPECT_EQ(f.corners.size(), 8u);  // the fan centres are not corners
  ASSERT_EQ(f.num_faces(), 6);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(f.loop_start[k + 1] - f.loop_start[k], 4);
    // axis-aligned outward normals, each face's corners on its plane
    EXPECT_NEAR(f.normals[k].cwiseAbs().maxCoeff(), 1, 1e-12);
    for (int i = f.loop_start[k]; i < f.loop_start[k + 1]; ++i) EXPECT_NEAR(f.normals[k].dot(f.corners[f.loops[i]]), f.offsets[k], 1e-12);
    // counter-clockwise seen from outside
    const Vec3 a = f.corners[f.loops[f.loop_start[k]]], b = f.corners[f.loops[f.loop_start[k] + 1]], c = f.corners[f.loops[f.loop_start[k] + 2]];
    EXPECT_GT((b - a).cross(c - b).dot(f.normals[k]), 0);
  }
  // three edges meet at each corner of a box
  for (size_t c = 0; c < 8; ++c) EXPECT_EQ(f.neighbour_start[c + 1] - f.neighbour_start[c], 3);
}

TEST(ConvexFaces, HillClimbingSupportEqualsBruteForce) {
  const MeshShape s = make_convex_hull_shape(icosphere(3, 0.05).vertices, "icosphere");
  const ConvexFaces& f = *s.faces;
  ASSERT_GT(f.corners.size(), 600u);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  int start = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 d(real(g(rng)), real(g(rng)), real(g(rng)));
    real best = -1e30;
    for (const Vec3& c : f.corners) best = std::max(best, c.dot(d));
    start = f.support(d, start);
    EXPECT_NEAR(f.corners[start].dot(d), best, 1e-12) << "trial " << trial;
  }
}

// The face most aligned with a direction, found through the cube map of face normals, against
// a scan of every face: on an icosphere's hull (faces in every cell), on a hull squashed to a
// disc (faces crowded into few cells, the others empty) and on the directions of face normals
// themselves and next to them (alignment 1 and ties within a cell).
TEST(ConvexFaces, FaceTowardsThroughTheCellsEqualsAScanOfEveryFace) {
  std::vector<Vec3> disc = icosphere(3, 0.05).vertices;
  for (Vec3& v : disc) v.z() *= real(0.05);
  int checked = 0;
  for (const MeshShape& s : {make_convex_hull_shape(icosphere(3, 0.05).vertices, "icosphere"), make_convex_hull_shape(disc, "disc")}) {
    const ConvexFaces& f = *s.faces;
    ASSERT_GT(f.num_faces(), 256);
    ASSERT_FALSE(f.cell_start.empty());
    std::mt19937 rng(41);
    std::normal_distribution<double> g;
    std::vector<Vec3> dirs;
    for (int trial = 0; trial < 400; ++trial) dirs.push_back(Vec3(real(g(rng)), real(g(rng)), real(g(rng))).normalized());
    for (int k = 0; k < f.num_faces(); k += 7) {
      dirs.push_back(f.normals[k]);
      dirs.push_back((f.normals[k] + real(1e-3) * Vec3(real(g(rng)), real(g(rng)), real(g(rng)))).normalized());
    }
    for (const Vec3& d : dirs) {
      real best = -2;
      for (const Vec3& n : f.normals) best = std::max(best, n.dot(d));
      real alignment = 0;
      const int face = f.face_towards(d, alignment);
      EXPECT_EQ(alignment, f.normals[face].dot(d));
      EXPECT_EQ(alignment, best) << s.source << ", direction " << d.transpose();
      ++checked;
    }
    // a direction that is not finite finds no face better than none
    real alignment = 0;
    EXPECT_EQ(f.face_towards(Vec3(std::numeric_limits<real>::quiet_NaN(), 0, 1), alignment), 0);
    EXPECT_EQ(alignment, -2);
  }
  EXPECT_GT(checked, 1000);
}

TEST(ConvexHull, NearDuplicatePointsAreWeldedIntoOneCorner) {
  // a unit cube's corners, each also 1e-7 m (1e-7 of the extent) away from itself: 8 corners,
  // a closed hull without degenerate triangles
  std::vector<Vec3> points = cube_mesh(0.5).vertices;
  const size_t n = points.size();
  for (size_t i = 0; i < n; ++i) points.push_back(points[i] + Vec3(real(1e-7), real(-1e-7), real(5e-8)));
  const TriangleMesh hull = convex_hull(points, "cube with near-duplicates");
  EXPECT_TRUE(is_closed(hull));
  EXPECT_TRUE(degenerate_triangles(hull).empty());
  const MeshShape s = make_convex_hull_shape(points, "cube with near-duplicates");
  EXPECT_EQ(s.faces->corners.size(), 8u);
}

TEST(ConvexContact, StackedBoxesGiveTheFourCornersOfTheOverlapAtTheGap) {
  // a 0.2 m cube over a 1 m x 1 m slab, apart by 1 mm, then pressed 2 mm into it
  const MeshShape top = box_hull(Vec3(0.1, 0.1, 0.1)), slab = box_hull(Vec3(0.5, 0.5, 0.05));
  for (const real gap : {real(0.001), real(-0.002)}) {
    std::vector<ShapeContact> c;
    collide_convex_convex(*top.faces, pose(Vec3(0.02, -0.03, 0.05 + 0.1 + gap)), *slab.faces, pose(Vec3::Zero()), real(0.005), c);
    ASSERT_EQ(c.size(), 4u) << "gap " << gap;
    for (const ShapeContact& x : c) {
      EXPECT_NEAR(x.phi, gap, 1e-9);
      EXPECT_NEAR((x.n_W - Vec3::UnitZ()).norm(), 0, 1e-9);  // from the slab towards the cube
      EXPECT_NEAR(std::abs(x.p_W.x() - 0.02), 0.1, 1e-9);     // the cube's bottom corners
      EXPECT_NEAR(std::abs(x.p_W.y() + 0.03), 0.1, 1e-9);
      EXPECT_NEAR(x.p_W.z(), 0.05 + gap / 2, 1e-9);           // midway between the surfaces
    }
  }
  // beyond the margin: nothing
  std::vector<ShapeContact> none;
  collide_convex_convex(*top.faces, pose(Vec3(0, 0, 0.05 + 0.1 + 0.006)), *slab.faces, pose(Vec3::Zero()), real(0.005), none);
  EXPECT_TRUE(none.empty());
}

TEST(ConvexContact, CrossedEdgesMeetAtOnePointAtTheirDistance) {
  // two cubes (half 0.1 m) turned 45 degrees about x and about y: their edges cross, one over
  // the other; the gap between the edges is the centres' distance less 2 * 0.1 * sqrt(2)
  const MeshShape cube = box_hull(Vec3(0.1, 0.1, 0.1));
  const real h = real(0.1 * std::sqrt(2.0));
  const Quat about_x(Eigen::AngleAxis<real>(real(M_PI / 4), Vec3::UnitX()));
  const Quat about_y(Eigen::AngleAxis<real>(real(M_PI / 4), Vec3::UnitY()));
  for (const real gap : {real(0.003), real(-0.004)}) {
    std::vector<ShapeContact> c;
    collide_convex_convex(*cube.faces, pose(Vec3(0, 0, 2 * h + gap), about_x), *cube.faces, pose(Vec3::Zero(), about_y), real(0.01), c);
    ASSERT_EQ(c.size(), 1u) << "gap " << gap;
    EXPECT_NEAR(c[0].phi, gap, 1e-7);
    EXPECT_NEAR((c[0].n_W - Vec3::UnitZ()).norm(), 0, 1e-6);
    EXPECT_NEAR((c[0].p_W - Vec3(0, 0, h + gap / 2)).norm(), 0, 1e-6);
  }
}

// Penetration of two posed boxes along unit axis L: their projections' overlap (m).
double overlap_along(const Vec3& L, const SpatialTransform& Xa, const Vec3& ha, const SpatialTransform& Xb, const Vec3& hb) {
  double r = 0;
  for (int k = 0; k < 3; ++k) r += ha[k] * std::abs(Xa.R.col(k).dot(L)) + hb[k] * std::abs(Xb.R.col(k).dot(L));
  return r - std::abs(L.dot(Xa.p - Xb.p));
}

// Two boxes of random sizes (half extents in [0.02, 0.2) m) at random orientations, a's centre
// within `spread` (m) of b's at the origin, and the 15 axes of the separating axis theorem.
struct BoxPair {
  Vec3 ha, hb;
  SpatialTransform Xa, Xb;
  std::vector<Vec3> axes;
  double least_overlap() const {
    double least = 1e30;
    for (const Vec3& L : axes) least = std::min(least, overlap_along(L, Xa, ha, Xb, hb));
    return least;
  }
};

BoxPair random_box_pair(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1), size(0.02, 0.2);
  BoxPair p;
  p.ha = Vec3(real(size(rng)), real(size(rng)), real(size(rng)));
  p.hb = Vec3(real(size(rng)), real(size(rng)), real(size(rng)));
  const Quat qa = Quat(real(u(rng)), real(u(rng)), real(u(rng)), real(u(rng))).normalized();
  const Quat qb = Quat(real(u(rng)), real(u(rng)), real(u(rng)), real(u(rng))).normalized();
  p.Xa = pose(Vec3(real(spread * u(rng)), real(spread * u(rng)), real(spread * u(rng))), qa);
  p.Xb = pose(Vec3::Zero(), qb);
  for (int i = 0; i < 3; ++i) {
    p.axes.push_back(p.Xa.R.col(i));
    p.axes.push_back(p.Xb.R.col(i));
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = p.Xa.R.col(i).cross(p.Xb.R.col(j));
      if (c.norm() > 1e-9) p.axes.push_back(c.normalized());
    }
  }
  return p;
}

TEST(ConvexContact, OverlappingBoxesAgreeWithTheSeparatingAxisTheorem) {
  // random overlapping boxes: EPA's deepest penetration is the minimal translation, which by the
  // separating axis theorem is the least overlap over the 3 + 3 face normals and 9 edge
  // directions; and the boxes overlap by exactly that much along the contact normal
  std::mt19937 rng(11);
  int compared = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const BoxPair pair = random_box_pair(rng, 0.15);
    const Vec3 &ha = pair.ha, &hb = pair.hb;
    const SpatialTransform &Xa = pair.Xa, &Xb = pair.Xb;
    const double least = pair.least_overlap();
    if (least < 1e-4) continue;  // apart, or barely touching
    const MeshShape a = box_hull(ha), b = box_hull(hb);
    std::vector<ShapeContact> epa;
    collide_convex_convex(*a.faces, Xa, *b.faces, Xb, 0, epa);
    ASSERT_FALSE(epa.empty()) << "trial " << trial;
    ASSERT_LE(epa.size(), kMaxConvexContacts);
    EXPECT_NEAR(deepest(epa), -least, 1e-6) << "trial " << trial;
    EXPECT_NEAR(overlap_along(epa[0].n_W, Xa, ha, Xb, hb), least, 1e-6) << "trial " << trial;
    // the normal points from b towards a
    EXPECT_GT(epa[0].n_W.dot(Xa.p - Xb.p), 0) << "trial " << trial;
    ++compared;
  }
  EXPECT_GT(compared, 50);
}

TEST(ConvexDistance, GjkDistanceIsCertifiedAndFindsEveryOverlap) {
  // random box pairs: when the separating axis theorem finds them overlapping, GJK must too; when
  // apart, GJK's distance is at least the best axis's separation, and its closest points certify
  // it (the two boxes' supports along the closest points' direction are that far apart)
  std::mt19937 rng(5);
  int apart = 0, overlapping = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const BoxPair pair = random_box_pair(rng, 0.4);
    const Vec3 &ha = pair.ha, &hb = pair.hb;
    const SpatialTransform &Xa = pair.Xa, &Xb = pair.Xb;
    const double separation = -pair.least_overlap();
    const MeshShape a = box_hull(ha), b = box_hull(hb);
    const ConvexDistance d = convex_distance(*a.faces, Xa, *b.faces, Xb);
    if (separation < -1e-6) {
      EXPECT_TRUE(d.overlap || d.distance < 1e-9) << "trial " << trial << ": overlap by " << -separation << " not found";
      ++overlapping;
    } else if (separation > 1e-6) {
      ASSERT_FALSE(d.overlap) << "trial " << trial;
      EXPECT_GE(d.distance, separation - 1e-9) << "trial " << trial;
      const Vec3 n = (d.p_a - d.p_b) / d.distance;
      EXPECT_NEAR(-overlap_along(n, Xa, ha, Xb, hb), d.distance, 1e-9) << "trial " << trial;
      EXPECT_NEAR(-overlap_along(d.normal, Xa, ha, Xb, hb), d.distance, 1e-9) << "trial " << trial;
      ++apart;
    }
  }
  EXPECT_GT(apart, 50);
  EXPECT_GT(overlapping, 50);
}

TEST(ConvexContact, TetrahedronPointDownTouchesAtItsTip) {
  // a regular tetrahedron standing on one vertex over a slab: one contact under the tip
  const real s = real(0.1);
  const std::vector<Vec3> tet{Vec3(0, 0, 0), Vec3(s, 0, s * real(std::sqrt(2.0))), Vec3(-s / 2, s * real(std::sqrt(3.0) / 2), s * real(std::sqrt(2.0))),
                              Vec3(-s / 2, -s * real(std::sqrt(3.0) / 2), s * real(std::sqrt(2.0)))};
  const MeshShape t = make_convex_hull_shape(tet, "tetrahedron"), slab = box_hull(Vec3(0.5, 0.5, 0.05));
  std::vector<ShapeContact> c;
  collide_convex_convex(*t.faces, pose(Vec3(0.1, 0.2, 0.05 - 0.0015)), *slab.faces, pose(Vec3::Zero()), real(0.005), c);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].phi, -0.0015, 1e-9);
  EXPECT_NEAR((c[0].n_W - Vec3::UnitZ()).norm(), 0, 1e-9);
  EXPECT_NEAR((c[0].p_W - Vec3(0.1, 0.2, 0.05 - 0.00075)).norm(), 0, 1e-9);
}

TEST(ConvexDistance, StopsOnceTheGapIsKnownToExceedTheBound) {
  // random apart box pairs: asked to stop beyond half their separation, GJK stops with a lower
  // bound between that and the true distance and a normal that parts the boxes by the bound;
  // asked to stop beyond twice it, it runs to the exact distance
  std::mt19937 rng(17);
  int stopped = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const BoxPair pair = random_box_pair(rng, 0.5);
    const double separation = -pair.least_overlap();
    if (separation < 1e-3) continue;
    const MeshShape a = box_hull(pair.ha), b = box_hull(pair.hb);
    const ConvexDistance exact = convex_distance(*a.faces, pair.Xa, *b.faces, pair.Xb);
    ASSERT_FALSE(exact.overlap || exact.beyond) << "trial " << trial;
    const ConvexDistance early = convex_distance(*a.faces, pair.Xa, *b.faces, pair.Xb, real(separation / 2));
    if (early.beyond) {
      EXPECT_GT(early.distance, separation / 2) << "trial " << trial;
      EXPECT_LE(early.distance, exact.distance + 1e-9) << "trial " << trial;
      EXPECT_GE(-overlap_along(early.normal, pair.Xa, pair.ha, pair.Xb, pair.hb), early.distance - 1e-9) << "trial " << trial;
      ++stopped;
    } else {
      EXPECT_NEAR(early.distance, exact.distance, 1e-12) << "trial " << trial;
    }
    const ConvexDistance full = convex_distance(*a.faces, pair.Xa, *b.faces, pair.Xb, real(2 * exact.distance));
    EXPECT_FALSE(full.beyond) << "trial " << trial;
    EXPECT_NEAR(full.distance, exact.distance, 1e-12) << "trial " << trial;
  }
  EXPECT_GT(stopped, 50);
}

// The least of n . x over the corners of a posed hull (brute force).
double lowest_along(const Vec3& n, const ConvexFaces& f, const SpatialTransform& X) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& c : f.corners) lowest = std::min<double>(lowest, n.dot(X.R * c + X.p));
  return lowest;
}

TEST(ConvexDistance, FinelyMeshedHullsWithinAMillionthOfTheirSize) {
  // hulls of 4-level icospheres (2562 corners, 0.1 m): GJK stops once the distance is within
  // 1e-6 of the size of its lower bound. Certified without a reference: the closest points'
  // distance bounds the true one from above, the returned normal's separation (a brute-force
  // scan of the corners) from below, and the two must meet within that tolerance
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1, 1);
  const MeshShape a = make_convex_hull_shape(icosphere(4, 0.1).vertices, "sphere a");
  const MeshShape b = make_convex_hull_shape(icosphere(4, 0.1).vertices, "sphere b");
  const double size = std::max(a.faces->radius, b.faces->radius);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double gap = std::pow(10.0, -4 + 3 * (u(rng) + 1) / 2);  // 0.1 mm to 10 cm
    const Quat qa(Eigen::AngleAxis<real>(3 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    const Quat qb(Eigen::AngleAxis<real>(3 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    const SpatialTransform Xa = pose(Vec3::Zero(), qa), Xb = pose(-(0.2 + gap) * dir, qb);
    const ConvexDistance d = convex_distance(*a.faces, Xa, *b.faces, Xb);
    ASSERT_FALSE(d.overlap) << "trial " << trial;
    const double upper = (d.p_a - d.p_b).norm();
    const double lower = lowest_along(d.normal, *a.faces, Xa) + lowest_along(-d.normal, *b.faces, Xb);
    EXPECT_NEAR(d.distance, upper, 1e-12) << "trial " << trial;
    EXPECT_LE(lower, upper + 1e-12) << "trial " << trial;
    EXPECT_LE(upper - lower, 2e-6 * size) << "trial " << trial << ", gap " << gap;
  }
}

TEST(Midphase, OrientedBoxesApartExactlyWhenAnAxisSeparatesThemByTheGap) {
  // the separating axis theorem on the 15 axes as the reference: boxes_apart holds when the best
  // axis parts the boxes by more than the gap, and not when none does
  std::mt19937 rng(23);
  int apart = 0, close = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const BoxPair pair = random_box_pair(rng, 0.4);
    const double best = -pair.least_overlap();  // the largest separation over the axes (m)
    const real gap = real(trial % 3 == 0 ? 0.0 : 0.01);
    Bounds a, b;
    a.min = -pair.ha, a.max = pair.ha, b.min = -pair.hb, b.max = pair.hb;
    // boxes off their frames' origins: the same boxes posed from frames moved the other way
    const Vec3 shift(0.03, -0.02, 0.05);
    SpatialTransform Xa = pair.Xa;
    Xa.p -= Xa.R * shift;
    a.min += shift, a.max += shift;
    const bool got = boxes_apart(a, Xa, b, pair.Xb, gap);
    if (best > gap + 1e-4) {
      EXPECT_TRUE(got) << "trial " << trial << ": apart by " << best;
      ++apart;
    } else if (best < gap - 1e-9) {
      EXPECT_FALSE(got) << "trial " << trial << ": within " << best;
      ++close;
    }
  }
  EXPECT_GT(apart, 300);
  EXPECT_GT(close, 300);
}

TEST(ConvexContact, AConvexMeshOnAPlaneTouchesAtItsCornersWithinTheMargin) {
  // a hull of many corners (points on an ellipsoid) posed over a ground plane: its contacts are
  // corners that a scan of all of them finds within the margin, the deepest among them, and
  // they span the patch of those corners
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) {
    const Vec3 d = Vec3(real(g(rng)), real(g(rng)), real(g(rng))).normalized();
    points.push_back(Vec3(real(0.08) * d.x(), real(0.05) * d.y(), real(0.03) * d.z()));
  }
  LinkCollider hull, ground;
  hull.shape = make_convex_hull_shape(points, "ellipsoid");
  ground.shape = PlaneShape{Vec3::UnitZ(), 0};
  const ConvexFaces& f = *std::get<MeshShape>(hull.shape).faces;
  ASSERT_GT(f.corners.size(), 200u);
  std::uniform_real_distribution<double> u(-1, 1);
  int exact = 0, reduced = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Quat q = Quat(real(u(rng)), real(u(rng)), real(u(rng)), real(u(rng))).normalized();
    SpatialTransform X = pose(Vec3::Zero(), q);
    real lowest = std::numeric_limits<real>::infinity();
    for (const Vec3& c : f.corners) lowest = std::min(lowest, (X.R * c).z());
    const real margin = real(0.004);
    X.p = Vec3(0.1, -0.2, -lowest + real(0.006 * u(rng)));
    // the reference: every corner below the margin
    std::vector<Vec3> within;
    real deepest_phi = std::numeric_limits<real>::infinity();
    for (const Vec3& c : f.corners) {
      const Vec3 p = X.R * c + X.p;
      if (p.z() < margin) within.push_back(p);
      deepest_phi = std::min(deepest_phi, p.z());
    }
    std::vector<ShapeContact> got;
    collide_shapes(hull, X, ground, SpatialTransform{}, margin, got);
    if (within.empty()) {
      EXPECT_TRUE(got.empty()) << "trial " << trial;
      continue;
    }
    // at most kMaxConvexContacts, two at least where two corners are within the margin, and
    // spread over the patch: at least 60 % of its widest span between two of them
    ASSERT_LE(got.size(), std::min(within.size(), kMaxConvexContacts)) << "trial " << trial;
    ASSERT_GE(got.size(), std::min<size_t>(within.size(), 2)) << "trial " << trial;
    auto widest = [](const std::vector<Vec3>& points) {
      real w = 0;
      for (const Vec3& p : points)
        for (const Vec3& q : points) w = std::max(w, (p - q).norm());
      return w;
    };
    std::vector<Vec3> got_points;
    for (const ShapeContact& c : got) got_points.push_back(c.p_W);
    EXPECT_GE(widest(got_points), real(0.6) * widest(within)) << "trial " << trial;
    // each contact is one of those corners (midway to the plane), and the deepest is among them
    for (const ShapeContact& c : got) {
      const Vec3 corner = c.p_W + Vec3::UnitZ() * (c.phi / 2);
      real nearest = std::numeric_limits<real>::infinity();
      for (const Vec3& p : within) nearest = std::min(nearest, (p - corner).norm());
      EXPECT_LT(nearest, 1e-9) << "trial " << trial;
    }
    EXPECT_NEAR(deepest(got), deepest_phi, 1e-12) << "trial " << trial;
    (within.size() <= kMaxConvexContacts ? exact : reduced)++;
  }
  EXPECT_GT(exact, 20);
  EXPECT_GT(reduced, 20);
}

TEST(ConvexContact, AFlatFaceOnAPlaneTouchesAtItsRim) {
  // a 128-sided prism (radius 4 cm, 2 cm tall, every corner on its two rims) lying on its end,
  // tipped by 5 mrad about x: the contacts include the lowest rim corner and span the end face
  std::vector<Vec3> points;
  const real radius = real(0.04);
  for (int i = 0; i < 128; ++i) {
    const real a = real(2 * M_PI * i / 128);
    for (real z : {real(0), real(0.02)}) points.push_back(Vec3(radius * std::cos(a), radius * std::sin(a), z));
  }
  LinkCollider prism, ground;
  prism.shape = make_convex_hull_shape(points, "prism");
  ground.shape = PlaneShape{Vec3::UnitZ(), 0};
  const Quat q(Eigen::AngleAxis<real>(real(0.005), Vec3::UnitX()));
  const SpatialTransform X = pose(Vec3(0, 0, radius * real(std::sin(0.005)) + real(0.001)), q);
  std::vector<ShapeContact> got;
  collide_shapes(prism, X, ground, SpatialTransform{}, real(0.01), got);
  ASSERT_EQ(got.size(), kMaxConvexContacts);
  // the end face's corners lie 1 to 1.4 mm above the ground: the deepest contact is the lowest
  EXPECT_NEAR(deepest(got), real(0.001), 1e-5);
  real widest = 0;
  for (const ShapeContact& a : got)
    for (const ShapeContact& b : got) widest = std::max(widest, (a.p_W - b.p_W).norm());
  EXPECT_GT(widest, real(0.95) * 2 * radius);
  for (const ShapeContact& c : got) EXPECT_LT(c.phi, real(0.0015));  // all on the end face
}

}  // namespace
}  // namespace superdex::physics::test
