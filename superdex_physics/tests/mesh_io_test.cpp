/// @file mesh_io_test.cpp
/// Mesh files (OBJ, STL ASCII and binary, PLY ASCII and binary) read into the same cube, and
/// every malformed input rejected with a message naming the file, the line and the defect.
/// Also the mesh checks: closedness and convexity.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh_test_helpers.h"
#include "superdex/physics/error.h"
#include "superdex/physics/mesh_io.h"
#include "superdex/physics/mesh_validation.h"

namespace superdex::physics::test {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Same vertex set (any order) and the same triangles up to that renumbering.
void expect_same_mesh(const TriangleMesh& got, const TriangleMesh& want) {
  ASSERT_EQ(got.vertices.size(), want.vertices.size());
  ASSERT_EQ(got.triangles.size(), want.triangles.size());
  std::vector<int> map(got.vertices.size(), -1);
  for (size_t i = 0; i < got.vertices.size(); ++i)
    for (size_t j = 0; j < want.vertices.size(); ++j)
      if ((got.vertices[i] - want.vertices[j]).norm() < 1e-6) map[i] = static_cast<int>(j);
  for (size_t t = 0; t < got.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(map[got.triangles[t][k]], want.triangles[t][k]) << "triangle " << t;
}

TEST(MeshIo, ObjCube) {
  TempDir dir;
  const TriangleMesh cube = cube_mesh();
  expect_same_mesh(read_mesh_file(write_file(dir.file("cube.obj"), obj_text(cube))), cube);
}

TEST(MeshIo, ObjQuadsNegativeIndicesAndIgnoredRecords) {
  TempDir dir;
  // a unit square as one quad with v/vt/vn references, plus one triangle by negative indices
  const std::string text =
      "# comment\nmtllib x.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ns off\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\nv 0 0 1\nf -5//1 -4//1 -1//1\n";
  const TriangleMesh m = read_obj_file(write_file(dir.file("quad.obj"), text));
  ASSERT_EQ(m.vertices.size(), 5u);
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (std::array<int, 3>{0, 1, 4}));
}

TEST(MeshIo, StlAsciiAndBinaryAreWelded) {
  TempDir dir;
  const TriangleMesh cube = cube_mesh();
  const TriangleMesh ascii = read_mesh_file(write_file(dir.file("cube.stl"), stl_ascii_text(cube)));
  const TriangleMesh binary = read_mesh_file(write_file(dir.file("cube_bin.STL"), stl_binary_bytes(cube)));
  expect_same_mesh(ascii, cube);
  expect_same_mesh(binary, cube);
  EXPECT_TRUE(is_closed(ascii));
  EXPECT_TRUE(is_closed(binary));
}

TEST(MeshIo, BinaryStlWhoseHeaderSaysSolid) {
  TempDir dir;
  std::string bytes = stl_binary_bytes(cube_mesh());
  bytes.replace(0, 5, "solid");
  expect_same_mesh(read_stl_file(write_file(dir.file("tricky.stl"), bytes)), cube_mesh());
}

TEST(MeshIo, PlyAsciiAndBinary) {
  TempDir dir;
  const TriangleMesh cube = cube_mesh();
  expect_same_mesh(read_mesh_file(write_file(dir.file("cube.ply"), ply_bytes(cube, false))), cube);
  expect_same_mesh(read_mesh_file(write_file(dir.file("cube_bin.ply"), ply_bytes(cube, true))), cube);
}

TEST(MeshIo, PlyExtraPropertiesElementsAndDoubles) {
  TempDir dir;
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nelement face 2\nproperty uint flags\nproperty list uchar uint vertex_index\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 0\n7 3 0 1 2\n0 4 0 1 2 3\n0 1\n";
  const TriangleMesh m = read_ply_file(write_file(dir.file("extra.ply"), text));
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 3u);  // a triangle and a fan-triangulated quad
}

// An element without properties occupies nothing; a huge declared count of it (issue 9) once
// looped once per record, for ever in practice. Binary and ASCII alike, it is skipped.
TEST(MeshIo, PlyElementWithoutPropertiesAndAHugeCountIsSkipped) {
  TempDir dir;
  const TriangleMesh cube = cube_mesh();
  for (const bool binary : {false, true}) {
    std::string bytes = ply_bytes(cube, binary);
    bytes.insert(bytes.find("end_header"), "element nothing 4611686018427387904\n");
    expect_same_mesh(read_ply_file(write_file(dir.file(binary ? "empty_b.ply" : "empty_a.ply"), bytes)), cube);
  }
}

TEST(MeshIo, MissingFileAndUnknownExtension) {
  TempDir dir;
  EXPECT_THAT([&] { read_mesh_file(dir.file("nope.obj")); }, ThrowsMessage<Error>(AllOf(HasSubstr("nope.obj"), HasSubstr("file not found"))));
  write_file(dir.file("mesh.xyz"), "v 0 0 0\n");
  EXPECT_THAT([&] { read_mesh_file(dir.file("mesh.xyz")); },
              ThrowsMessage<Error>(AllOf(HasSubstr("mesh.xyz"), HasSubstr("unknown mesh file extension '.xyz'"))));
}

TEST(MeshIo, ObjErrorsNameTheLine) {
  TempDir dir;
  auto error_of = [&](const std::string& text) {
    try {
      read_obj_file(write_file(dir.file("bad.obj"), text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 abc 0\nf 1 2 3\n"), AllOf(HasSubstr("bad.obj:3:"), HasSubstr("malformed number 'abc'")));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), AllOf(HasSubstr("bad.obj:4:"), HasSubstr("face index 9 out of range")));
  EXPECT_THAT(error_of("v 0 0 0\nf -1 -2 -3\n"), AllOf(HasSubstr("bad.obj:2:"), HasSubstr("out of range")));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), HasSubstr("face index 0 is invalid"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), AllOf(HasSubstr("bad.obj:2:"), HasSubstr("non-finite coordinate")));
  EXPECT_THAT(error_of("# nothing\n"), AllOf(HasSubstr("bad.obj"), HasSubstr("empty mesh")));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\n"), HasSubstr("empty mesh: no triangles"));
  // nothing but degenerate triangles: no surface at all
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n"),
              HasSubstr("2 degenerate (zero-area) triangles; the first is triangle 0 (vertices 0, 1, 2)"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n"), AllOf(HasSubstr("bad.obj:3:"), HasSubstr("at least 3 vertices")));
}

TEST(MeshIo, StlErrors) {
  TempDir dir;
  EXPECT_THAT([&] { read_stl_file(write_file(dir.file("short.stl"), "garbage")); },
              ThrowsMessage<Error>(AllOf(HasSubstr("short.stl"), HasSubstr("not an STL file"))));
  EXPECT_THAT([&] { read_stl_file(write_file(dir.file("size.stl"), std::string(200, 'x'))); },
              ThrowsMessage<Error>(HasSubstr("not a valid STL file")));
  const std::string bad_number = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 zz\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
  EXPECT_THAT([&] { read_stl_file(write_file(dir.file("num.stl"), bad_number)); },
              ThrowsMessage<Error>(AllOf(HasSubstr("num.stl:5:"), HasSubstr("malformed number 'zz'"))));
  EXPECT_THAT([&] { read_stl_file(write_file(dir.file("empty.stl"), "solid x\nendsolid x\n")); },
              ThrowsMessage<Error>(HasSubstr("empty mesh")));
  // moving corner 7 onto corner 3 welds them: the triangles using both collapse and are dropped
  TriangleMesh flat = cube_mesh();
  flat.vertices[7] = flat.vertices[3];
  const TriangleMesh welded = read_stl_file(write_file(dir.file("flat.stl"), stl_binary_bytes(flat)));
  EXPECT_TRUE(degenerate_triangles(welded).empty());
  EXPECT_LT(welded.triangles.size(), flat.triangles.size());
  std::string nan_bytes = stl_binary_bytes(cube_mesh());
  const float nan = std::nanf("");
  std::memcpy(&nan_bytes[84 + 50 * 2 + 12], &nan, 4);
  EXPECT_THAT([&] { read_stl_file(write_file(dir.file("nan.stl"), nan_bytes)); },
              ThrowsMessage<Error>(HasSubstr("triangle 2 has a non-finite coordinate")));
}

TEST(MeshIo, PlyErrors) {
  TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto error_of = [&](const std::string& text) {
    try {
      read_ply_file(write_file(dir.file("bad.ply"), text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"), AllOf(HasSubstr("bad.ply:13:"), HasSubstr("vertex index 5 out of range")));
  EXPECT_THAT(error_of(header + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), AllOf(HasSubstr("bad.ply:11:"), HasSubstr("malformed number 'x'")));
  EXPECT_THAT(error_of(header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), AllOf(HasSubstr("bad.ply:11:"), HasSubstr("non-finite coordinate")));
  EXPECT_THAT(error_of(header + "0 0 0\n1 0 0\n"), HasSubstr("the file ends early"));
  EXPECT_THAT(error_of("ply\nformat binary_middle_endian 1.0\nend_header\n"), AllOf(HasSubstr("bad.ply:2:"), HasSubstr("unknown PLY format")));
  EXPECT_THAT(error_of("PLY?\n"), HasSubstr("not a PLY file"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n"),
              HasSubstr("empty mesh"));
  std::string truncated = ply_bytes(cube_mesh(), true);
  truncated.resize(truncated.size() - 7);
  EXPECT_THAT(error_of(truncated), AllOf(HasSubstr("ends early"), HasSubstr("element 'face' record 11")));
}

TEST(MeshValidation, ClosedAndConvex) {
  const TriangleMesh cube = cube_mesh(), sphere = icosphere(2);
  EXPECT_TRUE(is_closed(cube));
  EXPECT_TRUE(is_closed(sphere));
  EXPECT_TRUE(is_convex(cube));
  EXPECT_TRUE(is_convex(sphere));
  EXPECT_NEAR(signed_volume(cube), 1.0, 1e-12);

  TriangleMesh open = cube;
  open.triangles.pop_back();
  EXPECT_FALSE(is_closed(open));
  EXPECT_EQ(edge_report(open).boundary_edges, 3);
  EXPECT_EQ(edge_report(open).describe(), "3 boundary edges");
  EXPECT_FALSE(is_convex(open));

  TriangleMesh flipped = cube;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_FALSE(is_closed(flipped));
  EXPECT_EQ(edge_report(flipped).misoriented_edges, 3);

  // an inside-out cube is closed, convex, with negative volume
  TriangleMesh inside_out = cube;
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_TRUE(is_closed(inside_out));
  EXPECT_TRUE(is_convex(inside_out));
  EXPECT_NEAR(signed_volume(inside_out), -1.0, 1e-12);

  // a dent makes the sphere non-convex
  TriangleMesh dented = sphere;
  dented.vertices[0] *= real(0.7);
  EXPECT_TRUE(is_closed(dented));
  EXPECT_FALSE(is_convex(dented));
}

TEST(MeshValidation, CheckNamesTheDefect) {
  TriangleMesh m = cube_mesh();
  m.triangles[4][2] = 8;
  EXPECT_THAT([&] { check_triangle_mesh(m, "here"); }, ThrowsMessage<Error>(HasSubstr("here: triangle 4 has vertex index 8 out of range [0, 8)")));
  m = cube_mesh();
  m.vertices[3].y() = std::numeric_limits<real>::quiet_NaN();
  EXPECT_THAT([&] { check_triangle_mesh(m, "here"); }, ThrowsMessage<Error>(HasSubstr("here: vertex 3 has a non-finite coordinate")));
  EXPECT_THAT([&] { check_triangle_mesh(TriangleMesh{}, "here"); }, ThrowsMessage<Error>(HasSubstr("here: empty mesh: no vertices")));
}

}  // namespace
}  // namespace superdex::physics::test
