// Bad input: every malformed, truncated, empty or absurd file the loaders see gets a
// roving::Error that names the file and says what was expected and what was found.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "roving/core/error.h"
#include "roving/formats/mesh_io.h"
#include "test_support.h"

namespace roving {
namespace {

namespace fs = std::filesystem;

class BadFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("roving-bad-input-" + std::to_string(::getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::string write(const std::string& name, const std::string& content) {
    const std::string path = (folder_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    return path;
  }

  // Loading `path` must throw a message naming the file and containing every `fragments`.
  void expect_error(const std::string& path, std::initializer_list<const char*> fragments) {
    try {
      const LoadedMesh loaded = load_mesh(path);
      ADD_FAILURE() << path << " loaded (" << loaded.mesh.triangle_count() << " triangles)";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      for (const char* fragment : fragments) EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }

  fs::path folder_;
};

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST_F(BadFiles, MissingFile) {
  expect_error((folder_ / "absent.obj").string(), {"cannot open"});
}

TEST_F(BadFiles, UnknownOrMissingExtension) {
  expect_error(write("model.xyz", kTriangleObj), {"unknown mesh format", ".xyz"});
  expect_error(write("model", kTriangleObj), {"unknown mesh format", "no extension"});
}

TEST_F(BadFiles, EmptyFiles) {
  for (const char* name : {"empty.obj", "empty.ply", "empty.off", "empty.stl"}) {
    expect_error(write(name, ""), {"empty"});
  }
}

TEST_F(BadFiles, ObjMalformedVertexNamesTheLine) {
  expect_error(write("bad-vertex.obj", "v 0 0 0\nv 1 abc 0\n"), {":2:", "'abc'"});
  expect_error(write("short-vertex.obj", "v 0 0\n"), {":1:", "3 numbers"});
}

TEST_F(BadFiles, ObjBadIndices) {
  expect_error(write("index-high.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), {":4:", "vertex 7", "1..3"});
  expect_error(write("index-zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), {"vertex 0"});
  expect_error(write("index-negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), {"vertex -4"});
  expect_error(write("index-text.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n"), {"'x'"});
  expect_error(write("two-corners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), {"at least 3 corners"});
}

TEST_F(BadFiles, NonFiniteCoordinates) {
  expect_error(write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), {"vertex 1", "non-finite"});
  expect_error(write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"), {"vertex 2", "non-finite"});
  expect_error(write("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), {"vertex 1", "finite"});
}

TEST_F(BadFiles, NoFacesOrOnlyDegenerateFaces) {
  expect_error(write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), {"no faces", "3 vertices"});
  expect_error(write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), {"zero area"});
}

TEST_F(BadFiles, RepeatedVertexFacesAreDroppedAndCounted) {
  const LoadedMesh loaded = load_mesh(write("repeat.obj", std::string(kTriangleObj) + "f 1 1 2\n"));
  EXPECT_EQ(loaded.mesh.triangle_count(), 1u);
  EXPECT_EQ(loaded.dropped_repeated_vertex_faces, 1u);
}

TEST_F(BadFiles, PlyMalformedHeader) {
  expect_error(write("header.ply", "ply\nformat ascii 1.0\nelement vertex three\nend_header\n"),
               {"line 3", "COUNT", "'element vertex three'"});
  expect_error(write("nomagic.ply", "this is not a ply file\n"), {"magic", "'this is not a ply file'"});
  expect_error(write("format.ply", "ply\nformat utf8 1.0\nend_header\n"), {"format ascii"});
  expect_error(
      write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\nend_header\n0\n"),
      {"property type"});
  expect_error(write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"), {"end_header"});
  expect_error(write("huge.ply",
                     "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\n"
                     "end_header\n0\n"),
               {"truncated"});
}

TEST_F(BadFiles, PlyBadIndex) {
  expect_error(write("index.ply",
                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                     "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"),
               {"vertex 9", "[0, 3)"});
}

TEST_F(BadFiles, TruncatedBinaryFiles) {
  // A valid binary PLY and STL of one tetrahedron, cut short in the middle of their data.
  const TriangleMesh tetrahedron({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                 {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  for (const char* name : {"tetra.ply", "tetra.stl"}) {
    const std::string path = (folder_ / name).string();
    save_mesh(tetrahedron, path, true);
    ASSERT_EQ(load_mesh(path).mesh.triangle_count(), 4u) << name;
    fs::resize_file(path, fs::file_size(path) - 20);
    expect_error(path, {"truncated"});
  }
}

TEST_F(BadFiles, OffTruncatedOrBadIndex) {
  expect_error(write("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), {"truncated"});
  expect_error(write("counts.off", "OFF\nthree 1 0\n"), {"whole-number", "'three 1'"});
  expect_error(write("magic.off", "PFF\n3 1 0\n"), {"OFF header", "'PFF'"});
  expect_error(write("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"), {"vertex 5"});
}

TEST_F(BadFiles, SaveAndLoadRoundTripKeepsTheGeometry) {
  const TriangleMesh cube = testing::box(1.0);
  for (const char* name : {"cube.obj", "cube.ply", "cube.off", "cube.stl"}) {
    const std::string path = (folder_ / name).string();
    save_mesh(cube, path, true);
    const TriangleMesh loaded = load_mesh(path).mesh;
    EXPECT_EQ(loaded.triangle_count(), 12u) << name;
    EXPECT_NEAR(loaded.total_area(), 24.0, 1e-9) << name;
  }
}

}  // namespace
}  // namespace roving
