// Textures: glTF's sampler rules, PNG and JPEG decoding with bounds, OBJ + MTL colour, and the colour
// rule on textured planes whose colours are known in closed form.
#include "roving/core/texture.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "colour_models.h"
#include "coloured.h"
#include "roving/core/colour.h"
#include "roving/core/colour_science.h"
#include "roving/core/colour_statistics.h"
#include "roving/core/error.h"
#include "roving/formats/meshes/mtl_reader.h"
#include "roving/formats/outputs/coloured_mesh_writer.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/formats/images_and_matlab/texture_io.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

namespace fs = std::filesystem;

using testing::checkerboard;
using testing::make_texture;

TEST(TextureSampling, TexelCentresGiveTheTexelUnderEitherFilter) {
  const Texture t = checkerboard(8);
  for (Filter filter : {Filter::Linear, Filter::Nearest}) {
    Sampler sampler;
    sampler.filter = filter;
    for (int j = 0; j < 8; ++j) {
      for (int i = 0; i < 8; ++i) {
        const TexCoord centre((i + 0.5) / 8, (j + 0.5) / 8);
        EXPECT_EQ(sample_texture(t, sampler, centre), t.texel(i, j)) << i << " " << j;
      }
    }
  }
}

TEST(TextureSampling, BilinearBetweenCentresAndTheWrapModes) {
  // A 4 x 2 ramp: R = 10 + 20 i, G = 100 + 50 j.
  const Texture t =
      make_texture(4, 2, [](int i, int j) { return Eigen::Vector3i(10 + 20 * i, 100 + 50 * j, 0); });
  Sampler repeat;
  // Halfway between the centres of texels 1 and 2, a quarter of the way from row 0's to row 1's.
  const Colour mid = sample_texture(t, repeat, TexCoord(2.0 / 4, (0.5 + 0.25) / 2));
  EXPECT_FLOAT_EQ(mid.x(), 40);
  EXPECT_FLOAT_EQ(mid.y(), 112.5);
  // At u = 0 the left edge: repeat blends texel 3 with texel 0; clamp gives texel 0; mirrored
  // repeats texel 0 itself beyond the edge.
  const TexCoord edge(0, 0.25);
  EXPECT_FLOAT_EQ(sample_texture(t, repeat, edge).x(), (70 + 10) / 2.0f);
  Sampler clamp;
  clamp.wrap_s = clamp.wrap_t = Wrap::ClampToEdge;
  EXPECT_FLOAT_EQ(sample_texture(t, clamp, edge).x(), 10);
  EXPECT_FLOAT_EQ(sample_texture(t, clamp, TexCoord(7.5, -3)).x(), 70);
  Sampler mirror;
  mirror.wrap_s = Wrap::MirroredRepeat;
  EXPECT_FLOAT_EQ(sample_texture(t, mirror, edge).x(), 10);
  EXPECT_FLOAT_EQ(sample_texture(t, mirror, TexCoord(1.125, 0.25)).x(), 70);  // mirrored texel 3's centre
  // Repeat has period 1 and mirrored repeat period 2, also far from [0, 1].
  EXPECT_EQ(sample_texture(t, repeat, TexCoord(0.3 + 1e6, 0.7 - 3e6)),
            sample_texture(t, repeat, TexCoord(0.3, 0.7)));
  EXPECT_EQ(sample_texture(t, mirror, TexCoord(-1.7 + 4e8, 0.2)),
            sample_texture(t, mirror, TexCoord(0.3, 0.2)));
  EXPECT_TRUE(sample_texture(t, repeat, TexCoord(1e300, -1e300)).allFinite());
}

class TextureFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("roving-texture-" + std::to_string(::getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(path(name), std::ios::binary) << content;
    return path(name);
  }
  std::string bytes_of(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  // `load` must throw a message containing every fragment.
  template <typename Load>
  void expect_error(Load load, const std::vector<std::string>& fragments) const {
    try {
      load();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      for (const std::string& fragment : fragments)
        EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }

  fs::path folder_;
};

TEST_F(TextureFiles, PngRoundTripsAndJpegIsClose) {
  const Texture t =
      make_texture(37, 23, [](int i, int j) { return Eigen::Vector3i(7 * i, 11 * j, (i * j) % 256); });
  write_texture(t, path("t.png"));
  const Texture png = read_texture(path("t.png"));
  EXPECT_EQ(png.width, 37);
  EXPECT_EQ(png.height, 23);
  EXPECT_EQ(png.rgb, t.rgb);
  write_texture(t, path("t.jpg"), 100);
  const Texture jpeg = read_texture(path("t.jpg"));
  ASSERT_EQ(jpeg.rgb.size(), t.rgb.size());
  // Quality 100 still subsamples chroma 4:2:0, so sharp colour edges move by some steps; the mean does not.
  double total = 0;
  for (std::size_t k = 0; k < t.rgb.size(); ++k) total += std::abs(int(jpeg.rgb[k]) - int(t.rgb[k]));
  EXPECT_LT(total / t.rgb.size(), 8.0);
}

TEST_F(TextureFiles, BadImagesAreOneLineErrors) {
  const Texture t = checkerboard(16);
  write_texture(t, path("good.png"));
  write_texture(t, path("good.jpg"), 90);
  const std::string png = bytes_of("good.png"), jpeg = bytes_of("good.jpg");
  // A 60-byte PNG declaring 2^31 x 2^31 pixels: refused from the header, before any allocation.
  std::string huge = png.substr(0, 33);
  for (int k : {16, 20}) huge[k] = '\x80', huge[k + 1] = huge[k + 2] = huge[k + 3] = '\0';
  huge.resize(60, '\0');
  write("huge.png", huge);
  expect_error([&] { read_texture(path("huge.png")); }, {path("huge.png"), "PNG"});
  write("truncated.png", png.substr(0, png.size() / 2));
  expect_error([&] { read_texture(path("truncated.png")); }, {path("truncated.png"), "not a readable PNG"});
  write("truncated.jpg", jpeg.substr(0, jpeg.size() / 2));
  expect_error([&] { read_texture(path("truncated.jpg")); }, {path("truncated.jpg"), "not a readable JPEG"});
  std::string wide = jpeg;  // SOF0's height and width (after FFC0, length, precision)
  const std::size_t sof = wide.find("\xFF\xC0");
  ASSERT_NE(sof, std::string::npos);
  for (int k : {5, 7}) wide[sof + k] = '\x9C', wide[sof + k + 1] = '\x40';  // 40000 x 40000
  write("wide.jpg", wide);
  expect_error([&] { read_texture(path("wide.jpg")); }, {path("wide.jpg"), "40000 x 40000", "at most"});
  write("text.png", "not an image at all");
  expect_error([&] { read_texture(path("text.png")); }, {path("text.png"), "expected a PNG or JPEG"});
  write("empty.png", "");
  expect_error([&] { read_texture(path("empty.png")); }, {path("empty.png"), "empty"});
  expect_error([&] { write_texture(t, path("q.jpg"), 101); }, {path("q.jpg"), "JPEG quality 101"});
}

// A square of side 10 at height z, normal +z, two triangles, in OBJ with one textured material;
// its UVs span texel centre to texel centre of a `n`-texel-wide texture (so bilinear filtering is
// linear over the whole square).
std::string textured_square_obj(double z, int n, const std::string& mtl) {
  const double lo = 0.5 / n, hi = 1 - 0.5 / n;
  return fmt::format(
      "mtllib {}\nv 0 0 {z}\nv 10 0 {z}\nv 10 10 {z}\nv 0 10 {z}\nvt {lo} {lo}\nvt {hi} {lo}\nvt {hi} {hi}\n"
      "vt {lo} {hi}\nusemtl ramp\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
      mtl, fmt::arg("z", z), fmt::arg("lo", lo), fmt::arg("hi", hi));
}

TEST_F(TextureFiles, RecolouredTextureOnAMovedPlaneDiffersByExactlyTheRecolouring) {
  // A ramp texture (R linear in the column, G in the row): bilinear filtering reproduces the linear
  // field, so REF's colour at x is known. TEST lies 0.5 above with the ramp less 5 in R: every
  // sample's TEST colour is REF's less (5, 0, 0), under each semantics, by Embree and CGAL.
  const int n = 32;
  const auto ramp = [](int shift) {
    return [shift](int i, int j) { return Eigen::Vector3i(40 + 5 * i - shift, 200 - 4 * j, 90); };
  };
  write_texture(make_texture(n, n, ramp(0)), path("ramp.png"));
  write_texture(make_texture(n, n, ramp(5)), path("ramp-5.png"));
  write("ref.mtl", "newmtl ramp\nKd 1 1 1\nmap_Kd ramp.png\n");
  write("test.mtl", "newmtl ramp\nmap_Kd -clamp on ramp-5.png\n");
  const TriangleMesh reference = load_mesh(write("ref.obj", textured_square_obj(0, n, "ref.mtl"))).mesh;
  const TriangleMesh test = load_mesh(write("test.obj", textured_square_obj(0.5, n, "test.mtl"))).mesh;
  ASSERT_TRUE(reference.has_colour());
  ASSERT_NE(reference.texture_mapping(), nullptr);
  // REF's colour at a point is the linear field: R = 40 + 5 (31 x / 10), G = 200 - 4 (31 (10 - y) / 10)
  // (OBJ's v runs up, the image's rows down).
  const auto field = [](const Vec3& p) {
    return Colour(float(40 + 5 * 3.1 * p.x()), float(200 - 4 * 3.1 * (10 - p.y())), 90);
  };
  for (const char* method : {"embree", "cgal"}) {
    for (Semantics semantics : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
      for (const char* kind : {"faces", "vertices", "area:500"}) {
        SCOPED_TRACE(std::string(method) + " " + to_string(semantics) + " " + kind);
        const SampleSet samples = make_samples(reference, parse_sample_spec(kind));
        auto m = make_method(method);
        const DistanceResult result = measure_distances(*m, test, samples, {semantics, 1.0, true});
        const ColourPairs pairs = colour_pairs(reference, samples, test, result, semantics);
        for (std::size_t k = 0; k < samples.size(); ++k) {
          ASSERT_TRUE(result.hit[k]);
          // Float code values near 200 round to 2e-5; the interpolated UV adds 1e-12.
          ASSERT_LT((pairs.reference[k] - field(samples.positions[k])).cwiseAbs().maxCoeff(), 1e-4) << k;
          ASSERT_LT((pairs.test[k] - (pairs.reference[k] - Colour(5, 0, 0))).cwiseAbs().maxCoeff(), 1e-4)
              << k;
        }
        const ColourStatistics s = compute_colour_statistics(pairs, result.hit);
        EXPECT_NEAR(s.rgb[0].psnr, 20 * std::log10(255.0 / 5), 1e-4);
      }
    }
  }
}

TEST_F(TextureFiles, KdTimesTextureAndVertexColours) {
  write_texture(make_texture(2, 2, [](int, int) { return Eigen::Vector3i(200, 100, 50); }), path("flat.png"));
  write("m.mtl",
        "# a comment\nnewmtl plain\nKd 0.5 0.25 1\nKa 1 1 1\nnewmtl textured\nKd 0.5 1 1\nmap_Kd flat.png\n");
  const TriangleMesh mesh =
      load_mesh(write("m.obj",
                      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nusemtl plain\nf 1 2 3\n"
                      "usemtl textured\nf 2/1 4/1 3/1\n"))
          .mesh;
  EXPECT_EQ(colour_on_face(mesh, 0, Vec3(0.2, 0.2, 0)), Colour(127.5, 63.75, 255));
  EXPECT_EQ(colour_on_face(mesh, 1, Vec3(0.8, 0.8, 0)), Colour(100, 100, 50));
  // MeshLab's `v x y z r g b`: colours on [0, 1] become code values.
  const TriangleMesh coloured =
      load_mesh(write("vc.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n")).mesh;
  EXPECT_EQ(coloured.vertex_colours()[1], Colour(0, 255, 0));
  EXPECT_EQ(coloured.texture_mapping(), nullptr);
  // A homogeneous w is not a colour, and a model without usemtl has no materials.
  EXPECT_FALSE(load_mesh(write("w.obj", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n")).mesh.has_colour());
}

TEST_F(TextureFiles, BadObjColourIsAnError) {
  write_texture(checkerboard(4), path("c.png"));
  write("c.mtl", "newmtl c\nmap_Kd c.png\nnewmtl plain\nKd 1 0 0\n");
  const std::string square = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
  const auto obj_error = [&](const std::string& name, const std::string& text,
                             std::initializer_list<std::string> fragments) {
    const std::string file = write(name, text);
    std::vector<std::string> all(fragments);
    all.push_back(file);
    expect_error([&] { load_mesh(file); }, all);
  };
  obj_error("vt-index.obj", "mtllib c.mtl\n" + square + "usemtl c\nf 1/1 2/2 3/1\n",
            {":7:", "texture coordinate '2'", "1..1"});
  obj_error("vt-nan.obj", "vt nan 0\n", {":1:", "2 finite numbers after 'vt'"});
  obj_error("no-mtl.obj", "mtllib c.mtl\n" + square + "usemtl nothing\nf 1 2 3\n",
            {":6:", "'nothing'", "no such material"});
  // A material library that is not there: the geometry, without materials, and a warning naming
  // it (as MeshLab and Open3D read it); faces naming its materials are then plain faces.
  const std::string missing = write("missing.obj", "mtllib absent.mtl\n" + square + "usemtl a\nf 1/1 2/1 3/1\n");
  const LoadedMesh without = load_mesh(missing);
  EXPECT_EQ(without.mesh.triangle_count(), 1u);
  EXPECT_FALSE(without.mesh.has_colour());
  ASSERT_EQ(without.warnings.size(), 1u);
  for (const std::string& fragment : {missing + ":1:", std::string("absent.mtl"), std::string("without its materials")})
    EXPECT_NE(without.warnings[0].find(fragment), std::string::npos) << without.warnings[0];
  obj_error("outside.obj", "mtllib ../c.mtl\n" + square, {"leads out of the folder"});
  obj_error("uv-missing.obj", "mtllib c.mtl\n" + square + "usemtl c\nf 1/1 2 3/1\n",
            {":7:", "without a texture coordinate"});
  obj_error("mixed.obj", "mtllib c.mtl\n" + square + "f 1 2 3\nusemtl plain\nf 1 3 2\n",
            {":6:", "no material"});
  obj_error("partial-colour.obj", "v 0 0 0\nv 1 0 0 1 0 0\nv 0 1 0\nf 1 2 3\n",
            {":2:", "earlier vertices have none"});
  obj_error("late-colour.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            {"1 of 3 vertices have a colour"});
  obj_error("colour-range.obj", "v 0 0 0 1 0 2\nv 1 0 0 1 0 0\nv 0 1 0 1 0 0\nf 1 2 3\n",
            {":1:", "within [0, 1]"});
  const auto mtl_error = [&](const std::string& mtl, std::initializer_list<std::string> fragments) {
    write("bad.mtl", mtl);
    const std::string file = write("uses-bad.obj", "mtllib bad.mtl\n" + square);
    std::vector<std::string> all(fragments);
    all.insert(all.end(), {file + ":1:", path("bad.mtl")});
    expect_error([&] { load_mesh(file); }, all);
  };
  mtl_error("newmtl a\nKd 1.5 0 0\n", {":2:", "within [0, 1]", "'1.5'"});
  mtl_error("newmtl a\nKd spectral file.rfl\n", {":2:", "spectral"});
  mtl_error("Kd 1 1 1\n", {":1:", "before any 'newmtl'"});
  mtl_error("newmtl a\nmap_Kd -s 2 2 1 c.png\n", {":2:", "'-s'", "not supported"});
  mtl_error("newmtl a\nmap_Kd\n", {":2:", "expected a texture file"});
  // A texture that is not there: likewise the geometry without the materials' colour, and a
  // warning naming the library's line and the file.
  write("gone.mtl", "newmtl a\nKd 1 0 0\nmap_Kd gone.png\n");
  const LoadedMesh untextured = load_mesh(write("uses-gone.obj", "mtllib gone.mtl\n" + square + "usemtl a\nf 1/1 2/1 3/1\n"));
  EXPECT_EQ(untextured.mesh.triangle_count(), 1u);
  EXPECT_FALSE(untextured.mesh.has_colour());
  ASSERT_EQ(untextured.warnings.size(), 1u);
  for (const std::string& part :
       {path("gone.mtl") + ":3: map_Kd: no such file", path("gone.png"), std::string("without its materials")}) {
    EXPECT_NE(untextured.warnings[0].find(part), std::string::npos) << untextured.warnings[0];
  }
  // The same named from the model's own folder (relative paths, none of the texture's parts there):
  // still a missing file, not "a link leading out of the folder".
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::path(path("gone.mtl")).parent_path());
  const LoadedMesh here = load_mesh("uses-gone.obj");
  std::filesystem::current_path(before);
  ASSERT_EQ(here.warnings.size(), 1u);
  EXPECT_NE(here.warnings[0].find("gone.mtl:3: map_Kd: no such file 'gone.png'"), std::string::npos) << here.warnings[0];
  // require_materials(true) (--strict-materials): an error naming the library's line and the file.
  require_materials(true);
  expect_error([&] { load_mesh(path("uses-gone.obj")); }, {path("gone.mtl") + ":3:", "map_Kd", "gone.png", "cannot open"});
  expect_error([&] { load_mesh(missing); }, {"absent.mtl", "cannot open"});
  require_materials(false);
  write("fake.png", "GIF89a not a png");
  mtl_error("newmtl a\nmap_Kd fake.png\n", {":2:", "fake.png", "expected a PNG or JPEG"});
}

}  // namespace
}  // namespace roving

namespace roving {
namespace {

// glTF colour: a vertex-coloured, textured bunny written as glTF and as OBJ + MTL (with the
// texture as PNG) and read back gives every sample the same colour, to float's rounding of the
// linear values glTF stores (a thousandth of a step); glTF's linear factors and COLOR_0 are the
// sRGB code values' linear light.
TEST_F(TextureFiles, ColouredMeshesRoundTripThroughGltfAndObj) {
  TriangleMesh bunny =
      with_planar_texture(testing::bunny(), std::make_shared<Texture>(procedural_texture(64, 0, 8)));
  bunny.set_vertex_colours(procedural_colours(bunny));
  write_texture(*bunny.texture_mapping()->materials[0].texture, path("atlas.png"));
  write_coloured_gltf(bunny, path("bunny.gltf"), {"atlas.png"});
  write_coloured_obj(bunny, path("bunny.obj"), path("bunny.mtl"), {"atlas.png"});
  const SampleSet samples = make_samples(bunny, parse_sample_spec("area:3000"));
  const std::vector<Colour> expected = sample_colours(bunny, samples);
  for (const char* file : {"bunny.gltf", "bunny.obj"}) {
    SCOPED_TRACE(file);
    const TriangleMesh loaded = load_mesh(path(file)).mesh;
    ASSERT_TRUE(loaded.has_colour());
    ASSERT_EQ(loaded.triangle_count(), bunny.triangle_count());
    const std::vector<Colour> colours = sample_colours(loaded, samples);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      ASSERT_LT((colours[k] - expected[k]).cwiseAbs().maxCoeff(), 1e-3) << "sample " << k;
    }
  }
  // glTF multiplies baseColorFactor and the texture in linear light: a factor of 0.5 in R is
  // baked into the texels, each R' code(0.5 linear(R')), and the factor becomes white.
  nlohmann::json gltf = nlohmann::json::parse(bytes_of("bunny.gltf"));
  gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 1, 1, 1};
  write("half.bin", bytes_of("bunny.bin"));
  gltf["buffers"][0]["uri"] = "half.bin";
  const TriangleMesh half = load_mesh(write("half.gltf", gltf.dump())).mesh;
  const TextureMapping& mapping = *half.texture_mapping();
  const Material& material = mapping.materials[mapping.face_material[0]];
  EXPECT_EQ(material.factor, Colour::Constant(255));
  const Texture& original = *bunny.texture_mapping()->materials[0].texture;
  for (std::size_t i = 0; i < original.rgb.size(); i += 3) {
    ASSERT_EQ(material.texture->rgb[i], std::lround(srgb_code(0.5 * srgb_linear(original.rgb[i])))) << i;
    ASSERT_EQ(material.texture->rgb[i + 1], original.rgb[i + 1]);
  }
  EXPECT_NEAR(srgb_code(0.5), 187.5, 0.1);
}

TEST_F(TextureFiles, BadGltfColourIsAnError) {
  const auto ramp = std::make_shared<Texture>(
      make_texture(4, 4, [](int i, int j) { return Eigen::Vector3i(10 * i, 10 * j, 5); }));
  TriangleMesh square = testing::textured_square(0, ramp);
  square.set_vertex_colours({Colour(255, 0, 0), Colour(0, 255, 0), Colour(0, 0, 255), Colour(9, 9, 9)});
  write_texture(*ramp, path("ramp.png"));
  write_coloured_gltf(square, path("square.gltf"), {"ramp.png"});
  const nlohmann::json good = nlohmann::json::parse(bytes_of("square.gltf"));
  const TriangleMesh loaded = load_mesh(path("square.gltf")).mesh;
  ASSERT_TRUE(loaded.has_colour());
  // The image inside the buffer (as a GLB holds it): the same texels.
  {
    nlohmann::json embedded = good;
    std::string bin = bytes_of("square.bin");
    while (bin.size() % 4) bin.push_back('\0');
    const std::string png = bytes_of("ramp.png");
    embedded["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", png.size()}});
    embedded["buffers"][0] = {{"uri", "embedded.bin"}, {"byteLength", bin.size() + png.size()}};
    embedded["images"][0] = {{"bufferView", embedded["bufferViews"].size() - 1}, {"mimeType", "image/png"}};
    write("embedded.bin", bin + png);
    const TriangleMesh inside = load_mesh(write("embedded.gltf", embedded.dump())).mesh;
    const TextureMapping& mapping = *inside.texture_mapping();
    EXPECT_EQ(mapping.materials[mapping.face_material[0]].texture->rgb, ramp->rgb);
  }
  // Each edit of the good file, and what its message must name.
  const auto colour_accessor = good["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].get<int>();
  const struct {
    const char* name;
    std::function<void(nlohmann::json&)> edit;
    std::vector<std::string> fragments;
  } cases[] = {
      {"texcoord1",
       [](nlohmann::json& g) {
         g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
       },
       {"baseColorTexture", "texCoord 0"}},
      {"transform",
       [](nlohmann::json& g) {
         g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]
          ["KHR_texture_transform"] = nlohmann::json::object();
       },
       {"KHR_texture_transform"}},
      {"no-uv",
       [](nlohmann::json& g) { g["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0"); },
       {"primitives[0]", "no TEXCOORD_0"}},
      {"factor",
       [](nlohmann::json& g) {
         g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1.5, 0, 0, 1};
       },
       {"materials[0]", "baseColorFactor", "1.5"}},
      {"wrap", [](nlohmann::json& g) { g["samplers"][0]["wrapS"] = 1234; }, {"samplers[0]", "wrapS", "1234"}},
      {"image",
       [](nlohmann::json& g) { g["images"][0]["uri"] = "missing.png"; },
       {"images[0]", "missing.png"}},
      {"no-image", [](nlohmann::json& g) { g["textures"][0].erase("source"); }, {"textures[0]", "no source"}},
      {"colour-type",
       [&](nlohmann::json& g) { g["accessors"][colour_accessor]["componentType"] = 5121; },
       {"COLOR_0", "normalized"}},
      {"colour-count",
       [&](nlohmann::json& g) { g["accessors"][colour_accessor]["count"] = 3; },
       {"COLOR_0", "3 colours for 4"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    nlohmann::json edited = good;
    c.edit(edited);
    const std::string file = write(std::string(c.name) + ".gltf", edited.dump());
    std::vector<std::string> fragments = c.fragments;
    fragments.push_back(file);
    expect_error([&] { load_mesh(file); }, fragments);
  }
  // COLOR_0 on an untextured material with a factor: glTF's product in linear light at each vertex.
  {
    nlohmann::json plain = good;
    plain["materials"][0]["pbrMetallicRoughness"] = {{"baseColorFactor", {0.5, 1, 1, 1}}};
    plain["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    const TriangleMesh tinted = load_mesh(write("tinted.gltf", plain.dump())).mesh;
    const Triangle& t = tinted.triangles()[0];
    const auto at = [&](int corner) { return colour_on_face(tinted, 0, tinted.positions()[t[corner]]); };
    const Colour expected[3] = {Colour(float(srgb_code(0.5)), 0, 0), Colour(0, 255, 0), Colour(0, 0, 255)};
    for (int corner = 0; corner < 3; ++corner) {
      EXPECT_LT((at(corner) - expected[t[corner] % 3]).cwiseAbs().maxCoeff(), 1e-3) << corner;
    }
  }
  // COLOR_0 outside [0, 1] in the buffer itself.
  std::string bin = bytes_of("square.bin");
  const std::size_t view = good["accessors"][colour_accessor]["bufferView"].get<std::size_t>();
  const std::size_t at = good["bufferViews"][view]["byteOffset"].get<std::size_t>();
  const float bad = 2.5f;
  std::memcpy(bin.data() + at, &bad, 4);
  write("square.bin", bin);
  expect_error([&] { load_mesh(path("square.gltf")); }, {"COLOR_0", "2.5", "expected 0 to 1"});
}

}  // namespace
}  // namespace roving
