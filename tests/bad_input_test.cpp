// Bad input: every malformed, truncated, empty or absurd file the loaders see gets a
// roving::Error that names the file and says what was expected and what was found.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>
#include <vector>

#include "roving/core/error.h"
#include "roving/formats/meshes/mesh_io.h"
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

// A binary little-endian PLY: float vertices, and faces as a uchar count and int indices.
std::string binary_ply(const std::vector<Vec3>& vertices,
                       const std::vector<std::vector<std::int32_t>>& faces) {
  std::string bytes = fmt::format(
      "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
      "property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      vertices.size(), faces.size());
  for (const Vec3& v : vertices) {
    const float xyz[3] = {float(v.x()), float(v.y()), float(v.z())};
    bytes.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  for (const auto& face : faces) {
    bytes += static_cast<char>(face.size());
    bytes.append(reinterpret_cast<const char*>(face.data()), 4 * face.size());
  }
  return bytes;
}

TEST_F(BadFiles, BinaryPlyFacesOfEveryKind) {
  // Triangles are read on all cores; any other face sends the whole element through the general
  // reader, which counts, triangulates or reports exactly as before.
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  LoadedMesh mixed = load_mesh(write("mixed.ply", binary_ply(square, {{0, 1, 2}, {0, 1, 2, 3}, {0, 0, 1}})));
  EXPECT_EQ(mixed.mesh.triangle_count(), 3u);
  EXPECT_EQ(mixed.triangulated_polygons, 1u);
  EXPECT_EQ(mixed.dropped_repeated_vertex_faces, 1u);
  expect_error(write("index-high.ply", binary_ply(square, {{0, 1, 2}, {0, 1, 4}})),
               {"face 1", "vertex 4", "[0, 4)"});
  expect_error(write("index-negative.ply", binary_ply(square, {{0, 1, 2}, {0, -1, 2}})),
               {"face 1", "vertex -1"});
  const std::string cut = binary_ply(square, {{0, 1, 2}, {0, 2, 3}});
  expect_error(write("cut.ply", cut.substr(0, cut.size() - 5)), {"truncated"});
}

TEST_F(BadFiles, BinaryPlyReadsTheSameAsAscii) {
  // A grid of 2 x 120 x 120 triangles (more than one block of the parallel reader), binary and ASCII.
  std::vector<Vec3> vertices;
  std::vector<std::vector<std::int32_t>> faces;
  std::string ascii;
  constexpr int n = 121;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      vertices.emplace_back(0.25 * i, 0.5 * j, 0.125 * ((i * j) % 7));
      ascii += fmt::format("{} {} {}\n", vertices.back().x(), vertices.back().y(), vertices.back().z());
    }
  }
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const int v = i * n + j;
      faces.push_back({v, v + 1, v + n + 1});
      faces.push_back({v, v + n + 1, v + n});
    }
  }
  std::string header = fmt::format(
      "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      vertices.size(), faces.size());
  for (const auto& f : faces) ascii += fmt::format("3 {} {} {}\n", f[0], f[1], f[2]);
  const TriangleMesh binary = load_mesh(write("grid.ply", binary_ply(vertices, faces))).mesh;
  const TriangleMesh text = load_mesh(write("grid-ascii.ply", header + ascii)).mesh;
  ASSERT_EQ(binary.triangle_count(), faces.size());
  EXPECT_EQ(binary.triangles(), text.triangles());
  EXPECT_EQ(binary.positions(), text.positions());
}

TEST_F(BadFiles, OffTruncatedOrBadIndex) {
  expect_error(write("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), {"truncated"});
  expect_error(write("counts.off", "OFF\nthree 1 0\n"), {"whole-number", "'three 1'"});
  expect_error(write("magic.off", "PFF\n3 1 0\n"), {"OFF header", "'PFF'"});
  expect_error(write("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"), {"vertex 5"});
}

// The cases the fuzzers and the crafted battery found (issue: untrusted files). Each is refused
// with a message, at once, without allocating what the file only claims.
const char* kPlyVertexHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

TEST_F(BadFiles, PlyPropertyBeforeAnyElement) {
  expect_error(write("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
               {"header line 3", "'element' line before its properties"});
}

TEST_F(BadFiles, PlyPropertyDeclaredTwice) {
  // Found by fuzz_ply: 'x' twice and no 'z' passed the three-axes check.
  expect_error(write("twice.ply",
                     "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                     "property float y\nproperty float x\nend_header\n" +
                         std::string(12, '\0')),
               {"property 'x' twice"});
}

TEST_F(BadFiles, PlyFormatWithoutVersion) {
  expect_error(
      write("noversion.ply", "ply\nformat ascii\nelement vertex 1\nproperty float x\nend_header\n0\n"),
      {"header line 2", "1.0"});
}

TEST_F(BadFiles, PlyAbsurdCountsInTinyFiles) {
  // 2^62 vertices (a product of it with the item size wrapped to 0 in the old check).
  expect_error(write("wrap.ply",
                     "ply\nformat binary_little_endian 1.0\nelement vertex 4611686018427387904\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\n0000"),
               {"truncated or corrupt", "4611686018427387904"});
  // A face list that claims 2^31 corners.
  std::string body = std::string(kPlyVertexHeader) + "element face 1\nproperty list int int vertex_indices\n";
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n";
  binary += std::string(36, '\0');
  const std::int32_t huge = std::numeric_limits<std::int32_t>::max();
  binary.append(reinterpret_cast<const char*>(&huge), 4);
  binary += std::string(12, '\0');
  expect_error(write("list.ply", binary), {"face 0", "2147483647 values"});
}

TEST_F(BadFiles, PlyTruncatedOrStrayTokensAreErrors) {
  const std::string header =
      std::string(kPlyVertexHeader) + "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  ASSERT_EQ(load_mesh(write("ok.ply", header + vertices + "3 0 1 2\n3 0 2 1\n")).mesh.triangle_count(), 2u);
  expect_error(write("cut.ply", header + vertices + "3 0 1 2\n"), {"truncated", "2 face items"});
  // Long enough for the declared counts, yet the last face is missing.
  expect_error(write("cut-long.ply", header + "0.0000 0.0000 0.0000\n1 0 0\n0 1 0\n3 0 1 2\n"),
               {"truncated", "face 1 of 2"});
  expect_error(write("stray.ply", header + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"),
               {":10:", "vertex 0", "end of the line", "'7'"});
  expect_error(write("extra.ply", header + vertices + "3 0 1 2\n3 0 2 1\n3 0 1 2\n"), {"end of the file"});
}

TEST_F(BadFiles, PlyNonFiniteCoordinatesNameTheVertex) {
  expect_error(write("nan.ply", std::string(kPlyVertexHeader) +
                                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
               {"vertex 1", "non-finite"});
}

TEST_F(BadFiles, PlyWithOtherElementsAndBigEndianLoads) {
  // Alpha, a face flag and an edge element are skipped; geometry and colours are what is read.
  const std::string ascii =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar "
      "alpha\n"
      "element face 1\nproperty uchar flags\n"
      "property list uchar uint vertex_indices\nelement edge 1\nproperty int a\nproperty int b\nend_header\n"
      "0 0 0 255 0 0 7\n1 0 0 0 255 0 7\n0 1 0 9 8 7 7\n7 3 0 1 2\n0 1\n";
  const TriangleMesh extras = load_mesh(write("extras.ply", ascii)).mesh;
  EXPECT_NEAR(extras.total_area(), 0.5, 1e-12);
  ASSERT_TRUE(extras.has_colour());
  EXPECT_EQ(extras.vertex_colours()[2], Colour(9, 8, 7));
  std::string big =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put_float = [&](float f) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    for (int shift = 24; shift >= 0; shift -= 8) big += static_cast<char>((bits >> shift) & 0xFF);
  };
  for (float v : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 0.f, 2.f, 0.f}) put_float(v);
  big += '\3';
  for (int index : {0, 1, 2}) big += std::string{0, 0, 0, static_cast<char>(index)};
  EXPECT_NEAR(load_mesh(write("big.ply", big)).mesh.total_area(), 2.0, 1e-12);
}

TEST_F(BadFiles, PlyColoursAreCheckedAndScaled) {
  const std::string header = std::string(kPlyVertexHeader);
  const std::string face = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  // Float colours on [0, 1] become code values on [0, 255].
  const TriangleMesh floats =
      load_mesh(write("float.ply", header +
                                       "property float red\nproperty float green\nproperty float blue\n" +
                                       face + "0 0 0 1 0.5 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"))
          .mesh;
  EXPECT_EQ(floats.vertex_colours()[0], Colour(255, 127.5f, 0));
  expect_error(write("over.ply", header + "property float red\nproperty float green\nproperty float blue\n" +
                                     face + "0 0 0 1.5 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
               {"over.ply", "vertex 0", "colour 'red' is 1.5", "within [0, 1]"});
  expect_error(
      write("nan-colour.ply", header + "property double red\nproperty double green\nproperty double blue\n" +
                                  face + "0 0 0 0 0 0\n1 0 0 0 nan 0\n0 1 0 0 0 0\n3 0 1 2\n"),
      {"vertex 1", "colour 'green' is nan"});
  expect_error(write("uchar.ply", header + "property uchar red\nproperty uchar green\nproperty uchar blue\n" +
                                      face + "0 0 0 0 0 300\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
               {"vertex 0", "colour 'blue' is 300", "uchar within [0, 255]"});
  expect_error(write("partial.ply", header + "property uchar red\nproperty uchar green\n" + face +
                                        "0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n"),
               {"partial.ply", "2 of the colour properties", "all three or none"});
  expect_error(write("int-colour.ply", header + "property int red\nproperty int green\nproperty int blue\n" +
                                           face + "0 0 0 0 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
               {"int-colour.ply", "'red'", "uchar (0-255) or float"});
}

TEST_F(BadFiles, OffAbsurdCountsAndNegativeCorners) {
  expect_error(write("tiny.off", "OFF\n9999999 9\n"), {"truncated or wrong counts", "9999999"});
  expect_error(write("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-2147483648 0 1 2\n"),
               {"face 0", "corner count"});
  expect_error(write("index40.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1099511627776\n"),
               {"vertex 1099511627776"});
  expect_error(write("stray.off", "OFF\n3 1 0\n0 0 0 5\n1 0 0\n0 1 0\n3 0 1 2\n"), {"vertex 0", "found 1"});
}

TEST_F(BadFiles, OffCommentsAreAccepted) {
  const LoadedMesh loaded =
      load_mesh(write("comments.off",
                      "# made by hand\nOFF\n# counts\n3 1 0\n0 0 0\n1 0 0 # a comment\n0 1 0\n"
                      "\n3 0 1 2\n"));
  EXPECT_EQ(loaded.mesh.triangle_count(), 1u);
}

TEST_F(BadFiles, OffBinaryIsBoundedAndStrict) {
  const auto word = [](std::int32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i)
      s[i] = static_cast<char>((static_cast<std::uint32_t>(v) >> (24 - 8 * i)) & 0xFF);
    return s;
  };
  const auto real = [&](float f) {
    std::int32_t bits;
    std::memcpy(&bits, &f, 4);
    return word(bits);
  };
  std::string body = word(3) + word(1) + word(0);
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) body += real(v);
  body += word(3) + word(0) + word(1) + word(2) + word(0);
  EXPECT_EQ(load_mesh(write("binary.off", "OFF BINARY\n" + body)).mesh.triangle_count(), 1u);
  expect_error(write("header-only.off", "OFF BINARY\n"), {"truncated", "vertex count"});
  std::string inflated = body;
  inflated.replace(4, 4, word(2));  // 2 faces declared, 1 present
  expect_error(write("inflated.off", "OFF BINARY\n" + inflated), {"truncated"});
  std::string huge = word(3) + word(1000000000) + word(0);
  expect_error(write("huge.off", "OFF BINARY\n" + huge), {"truncated or wrong counts", "1000000000"});
}

TEST_F(BadFiles, StlTruncatedAsciiAndNonFinite) {
  const std::string facet =
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  EXPECT_EQ(load_mesh(write("ok.stl", "solid t\n" + facet + facet + "endsolid t\n")).mesh.triangle_count(),
            2u);
  expect_error(write("cut.stl", "solid t\n" + facet + "facet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
               {"truncated"});
  expect_error(write("noend.stl", "solid t\n" + facet), {"truncated", "'facet' or 'endsolid'"});
  expect_error(write("word.stl", "solid t\nfacet normal 0 0 1\nouter lop\n"), {":3:", "'loop'", "'lop'"});
  std::string nan_facet = facet;
  nan_facet.replace(nan_facet.find("vertex 1 0 0"), 12, "vertex nan 0 0");
  expect_error(write("nan.stl", "solid t\n" + nan_facet + "endsolid\n"), {"non-finite"});
}

TEST_F(BadFiles, KeywordsAtTheVeryEndOfTheFile) {
  // Found by fuzz_off: a header keyword with no line break after it read past the end.
  expect_error(write("eof.off", "OFF BINARY"), {"truncated", "vertex count"});
  expect_error(write("eof2.off", "\x0c\x0cOFF\x0c\x0c BINARY\x0c"), {"eof2.off"});
  expect_error(write("eof.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header"),
               {"x, y and z"});
}

TEST_F(BadFiles, DirectoryIsNamedAsSuch) {
  const fs::path directory = folder_ / "folder.ply";
  fs::create_directories(directory);
  expect_error(directory.string(), {"is a directory"});
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

// glTF 2.0 through assimp: a triangle (3 float positions, 3 ushort indices) in one buffer,
// placed by a node's translation and by another node's scale.
std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint8_t(bytes[i]) << 16) | (i + 1 < bytes.size() ? std::uint8_t(bytes[i + 1]) << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint8_t(bytes[i + 2]) : 0);
    out += digits[n >> 18], out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

std::string triangle_buffer(float x = 0, std::uint16_t last_index = 2) {
  const float positions[9] = {x, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, last_index, 0};
  return std::string(reinterpret_cast<const char*>(positions), sizeof positions) +
         std::string(reinterpret_cast<const char*>(indices), sizeof indices);
}

// The glTF JSON; `buffer_uri` empty for a GLB's own binary chunk. `mode` 4 is triangles, 0 points.
std::string gltf_json(const std::string& buffer_uri, int mode = 4) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0]}, {"mesh": 0, "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": )" + std::to_string(mode) + R"(}]}],
  "buffers": [{"byteLength": 44)" + (buffer_uri.empty() ? "" : R"(, "uri": ")" + buffer_uri + "\"") + R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

std::string glb(std::string json, const std::string& binary) {
  while (json.size() % 4) json += ' ';
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string chunks = u32(json.size()) + "JSON" + json + u32(binary.size()) + std::string("BIN\0", 4) + binary;
  return "glTF" + u32(2) + u32(12 + chunks.size()) + chunks;
}

TEST_F(BadFiles, GltfAndGlbApplyNodeTransforms) {
  const std::string data_uri = "data:application/octet-stream;base64," + base64(triangle_buffer());
  for (const std::string& path : {write("scene.gltf", gltf_json(data_uri)), write("scene.glb", glb(gltf_json(""), triangle_buffer()))}) {
    const LoadedMesh loaded = load_mesh(path);
    ASSERT_EQ(loaded.mesh.triangle_count(), 2u) << path;  // the mesh, placed by both nodes
    const BoundingBox box = loaded.mesh.bounding_box();
    EXPECT_EQ(box.min, Vec3(0, 0, 0)) << path;
    EXPECT_EQ(box.max, Vec3(11, 2, 0)) << path;  // translated to x in [10, 11]; scaled 2 to [0, 2]^2
    EXPECT_NEAR(loaded.mesh.total_area(), 0.5 + 2.0, 1e-12) << path;
  }
  // A .gltf whose buffer is a file beside it.
  write("scene.bin", triangle_buffer());
  EXPECT_EQ(load_mesh(write("external.gltf", gltf_json("scene.bin"))).mesh.triangle_count(), 2u);
}

// A zip archive of stored (uncompressed) entries, as a 3MF package may be.
std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
  const auto u16 = [](std::uint16_t v) { return std::string(reinterpret_cast<const char*>(&v), 2); };
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const auto crc32 = [](const std::string& data) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char c : data) {
      crc ^= c;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  std::string local, central;
  for (const auto& [name, data] : entries) {
    const std::string common = u16(20) + u16(0) + u16(0) + u16(0) + u16(0) + u32(crc32(data)) + u32(data.size()) +
                               u32(data.size()) + u16(name.size()) + u16(0);
    central += u32(0x02014b50) + u16(20) + common + u16(0) + u16(0) + u16(0) + u32(0) + u32(local.size()) + name;
    local += u32(0x04034b50) + common + name + data;
  }
  return local + central + u32(0x06054b50) + u16(0) + u16(0) + u16(entries.size()) + u16(entries.size()) +
         u32(central.size()) + u32(local.size()) + u16(0);
}

TEST_F(BadFiles, ThreeMfMeshWithItsBuildTransform) {
  const std::string model = R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <resources><object id="1" type="model"><mesh>
  <vertices><vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/></vertices>
  <triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles>
 </mesh></object></resources>
 <build><item objectid="1" transform="1 0 0 0 1 0 0 0 1 5 0 0"/></build>
</model>)";
  const std::string path = write("tetra.3mf", stored_zip({
      {"[Content_Types].xml", R"(<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>)"},
      {"_rels/.rels", R"(<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>)"},
      {"3D/3dmodel.model", model}}));
  const LoadedMesh loaded = load_mesh(path);
  EXPECT_EQ(loaded.mesh.triangle_count(), 4u);
  EXPECT_EQ(loaded.mesh.bounding_box().min, Vec3(5, 0, 0));  // the build item's translation
  EXPECT_EQ(loaded.mesh.bounding_box().max, Vec3(6, 1, 1));
}

// A package whose model entry no longer matches its CRC: Debian's assimp aborts on it (an
// ai_assert in its zip reader). It runs in a child process, so this is an error, not a crash.
TEST_F(BadFiles, ThreeMfThatAbortsAssimpIsAnError) {
  std::string package;
  {
    std::ifstream file(std::string(ROVING_SOURCE_DIR) + "/tests/fuzz/corpus/3mf/tetra.3mf", std::ios::binary);
    package.assign(std::istreambuf_iterator<char>(file), {});
  }
  ASSERT_FALSE(package.empty());
  EXPECT_EQ(load_mesh(write("good.3mf", package)).mesh.triangle_count(), 4u);
  package[package.find("vertex x=\"1\"") + 9] = '2';  // still XML, no longer its CRC
  expect_error(write("corrupt.3mf", package), {"cannot read it as .3mf"});
}

TEST_F(BadFiles, GltfBadFilesNameTheFile) {
  expect_error(write("empty.gltf", ""), {"empty"});
  expect_error(write("broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": ["), {"cannot read it as .gltf"});
  expect_error(write("missing-buffer.gltf", gltf_json("absent.bin")), {"cannot read it as .gltf"});
  expect_error(write("truncated.glb", glb(gltf_json(""), triangle_buffer()).substr(0, 100)), {"cannot read it as .glb"});
  expect_error(write("garbage.3mf", "PK\x03\x04 not really a zip"), {"cannot read it as .3mf"});
  const auto uri = [](const std::string& buffer) { return "data:application/octet-stream;base64," + base64(buffer); };
  expect_error(write("nan.gltf", gltf_json(uri(triangle_buffer(std::nanf(""))))), {"non-finite"});
  expect_error(write("points.gltf", gltf_json(uri(triangle_buffer()), 0)), {"no faces found"});
  expect_error(write("index.gltf", gltf_json(uri(triangle_buffer(0, 7)))), {"cannot read it as .gltf", "index 2 is 7"});
  // What the file declares is checked against what it holds.
  const std::string good = gltf_json(uri(triangle_buffer()));
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  expect_error(write("count.gltf", edited("\"count\": 3, \"type\": \"VEC3\"", "\"count\": 4000000000, \"type\": \"VEC3\"")),
               {"accessors[0]", "do not fit"});
  expect_error(write("view.gltf", edited("\"byteOffset\": 36, \"byteLength\": 6", "\"byteOffset\": 36, \"byteLength\": 60")),
               {"bufferViews[1]", "44-byte buffer"});
  expect_error(write("length.gltf", edited("\"byteLength\": 44", "\"byteLength\": 4400")), {"buffers[0] declares 4400 bytes, 44 exist"});
  expect_error(write("base64.gltf", edited("base64,", "base64,@")), {"base64"});
  expect_error(write("url.gltf", gltf_json("http://example.com/scene.bin")), {"expected a data URI or a file beside"});
  expect_error(write("draco.gltf", edited("{\"asset\"", "{\"extensionsRequired\": [\"KHR_draco_mesh_compression\"], \"asset\"")),
               {"KHR_draco_mesh_compression"});
  expect_error(write("sparse.gltf", edited("\"type\": \"SCALAR\"}", "\"type\": \"SCALAR\", \"sparse\": {}}")), {"sparse"});
  expect_error(write("loop.gltf", edited("{\"mesh\": 0, \"translation\"", "{\"mesh\": 0, \"children\": [0], \"translation\"")),
               {"node 0", "tree"});
  expect_error(write("version.gltf", edited("\"2.0\"", "\"1.0\"")), {"glTF 2.0"});
  const std::string frame = glb(gltf_json(""), triangle_buffer());
  std::string lying = frame;
  lying[8] = static_cast<char>(lying[8] + 4);  // the header's total length
  expect_error(write("lying.glb", lying), {"cannot read it as .glb", "declares"});
  std::string huge_chunk = frame;
  huge_chunk[12] = huge_chunk[13] = huge_chunk[14] = static_cast<char>(0xFF);  // the JSON chunk's length
  expect_error(write("chunk.glb", huge_chunk), {"cannot read it as .glb", "chunk at byte 12"});
  // A chain of 100,000 nodes is walked without recursion; the mesh sits at its end.
  std::string chain = R"({"asset": {"version": "2.0"}, "nodes": [)";
  for (int n = 0; n + 1 < 100000; ++n) chain += fmt::format("{{\"children\": [{}]}}, ", n + 1);
  chain += "{\"mesh\": 0}]";
  chain += good.substr(good.find("],\n  \"meshes\"") + 1);
  EXPECT_EQ(load_mesh(write("chain.gltf", chain)).mesh.triangle_count(), 1u);
}

}  // namespace
}  // namespace roving
