// `roving-datasets`: writes, deterministically, the derived test models (normalised, decimated,
// voxelised, sampled and analytic) into a folder, with a JSON manifest of what made each file,
// its parameters, counts and sha256.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "analytic.h"
#include "coloured.h"
#include "data_folder.h"
#include "decimate.h"
#include "paper_models.h"
#include "plain_mesh_writers.h"
#include "roving/core/error.h"
#include "roving/core/normalise.h"
#include "roving/core/sample_set.h"
#include "roving/formats/points_voxels_patches/binvox.h"
#include "roving/formats/outputs/coloured_mesh_writer.h"
#include "roving/formats/files/file_hash.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/formats/images_and_matlab/texture_io.h"
#include "subdivide.h"
#include "voxelize.h"

namespace fs = std::filesystem;
using namespace roving;
using nlohmann::json;

namespace {

class Writer {
 public:
  explicit Writer(fs::path folder) : folder_(std::move(folder)) { fs::create_directories(folder_); }

  void mesh(const TriangleMesh& m, const std::string& name, json made_by) {
    save_mesh(m, path(name), true);
    add(name, std::move(made_by), {{"vertices", m.vertex_count()}, {"triangles", m.triangle_count()}});
  }
  // A binary STL or OBJ written without OpenMesh (plain_mesh_writers.h), for meshes too big for it.
  void plain(const TriangleMesh& m, const std::string& name, json made_by) {
    if (fs::path(name).extension() == ".stl") {
      write_binary_stl(m, path(name));
    } else {
      write_plain_obj(m, path(name));
    }
    add(name, std::move(made_by), {{"vertices", m.vertex_count()}, {"triangles", m.triangle_count()}});
  }
  void voxels(const VoxelGrid& g, const std::string& name, json made_by) {
    write_binvox(g, path(name));
    add(name, std::move(made_by),
        {{"dimension", g.dimension}, {"voxel_size", g.voxel_size}, {"occupied", g.occupied_count()}});
  }
  void points(const PointCloud& c, const std::string& name, json made_by) {
    if (fs::path(name).extension() == ".xyz") {
      std::ofstream file(path(name));
      file.precision(9);
      for (const Vec3& p : c.positions) file << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    } else {
      write_point_cloud_ply(c, path(name));
    }
    add(name, std::move(made_by), {{"points", c.positions.size()}, {"normals", !c.normals.empty()}});
  }
  void copied(const std::string& name, json made_by) { add(name, std::move(made_by), json::object()); }
  // A textured mesh of one material as OBJ + MTL (NAME.obj, NAME.mtl) and its texture
  // (`texture_name`: PNG, or JPEG at `jpeg_quality`), or as glTF (NAME.gltf and .bin) when
  // `gltf`; the texture written once by whoever names it first.
  void textured(const TriangleMesh& m, const std::string& name, const std::string& texture_name, json made_by,
                int jpeg_quality = 0, bool gltf = false) {
    const Texture& texture = *m.texture_mapping()->materials[0].texture;
    if (!fs::exists(path(texture_name)) || !written_textures_.count(texture_name)) {
      write_texture(texture, path(texture_name), jpeg_quality);
      written_textures_.insert(texture_name);
      add(texture_name, made_by,
          {{"width", texture.width}, {"height", texture.height}, {"jpeg_quality", jpeg_quality}});
    }
    const std::string stem = fs::path(name).stem().string();
    if (gltf) {
      write_coloured_gltf(m, path(stem + ".gltf"), {texture_name});
      add(stem + ".gltf", std::move(made_by),
          {{"vertices", m.vertex_count()}, {"triangles", m.triangle_count()}});
    } else {
      write_coloured_obj(m, path(stem + ".obj"), path(stem + ".mtl"), {texture_name});
      add(stem + ".obj", std::move(made_by),
          {{"vertices", m.vertex_count()}, {"triangles", m.triangle_count()}});
    }
  }
  void finish() {
    std::ofstream(folder_ / "manifest.json")
        << json{{"generator", "roving-datasets"}, {"files", manifest_}}.dump(2) << "\n";
  }

 private:
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  void add(const std::string& name, json made_by, json counts) {
    json entry = {{"file", name},
                  {"made_by", std::move(made_by)},
                  {"counts", std::move(counts)},
                  {"sha256", file_sha256(path(name))}};
    manifest_.push_back(entry);
    std::fprintf(stderr, "wrote %s\n", path(name).c_str());
  }
  fs::path folder_;
  json manifest_ = json::array();
  std::set<std::string> written_textures_;
};

// Points uniform by area on `mesh`, with its face normals (a scanned-cloud stand-in).
PointCloud sampled_points(const TriangleMesh& mesh, std::size_t count) {
  const SampleSet s = make_samples(mesh, {SampleSpec::Kind::Area, count});
  return {s.positions, s.normals, {}};
}

// The colour benchmark's models (docs/benchmark.md "Colour"): the normalised bunny coloured by
// one procedural field over its box, as vertex colours and as a baked per-triangle atlas, and
// copies degraded as a codec or a pipeline would degrade them.
void write_colour_models(const TriangleMesh& bunny, const std::string& folder) {
  Writer write(folder);
  const BoundingBox box = bunny.bounding_box();
  const auto unit = [&](const Vec3& p) { return Vec3((p - box.min).cwiseQuotient(box.size())); };
  const auto whole = [](std::vector<Colour> colours) {
    for (Colour& c : colours) c = c.array().round().matrix();
    return colours;
  };
  const json field = {{"field", "procedural_colour over the bunny's box (datasets_gen/coloured.cpp)"}};
  const auto made = [&](const std::string& operation, json extra = json::object()) {
    json m = {{"source", "bunny.ply"}, {"operation", operation}};
    m.update(field);
    m.update(extra);
    return m;
  };
  TriangleMesh coloured = bunny;
  coloured.set_vertex_colours(whole(procedural_colours(bunny)));
  write.mesh(coloured, "bunny-vc.ply", made("vertex colours of the field"));
  TriangleMesh quantised_colours = coloured;
  quantised_colours.set_vertex_colours(quantised(coloured.vertex_colours(), 4));
  write.mesh(quantised_colours, "bunny-vc-4bit.ply",
             made("vertex colours quantised to 4 bits a channel", {{"bits", 4}}));
  TriangleMesh decimated = decimate_quadric(bunny, 10459);
  decimated.set_vertex_colours(whole(procedural_colours(decimated, box)));
  write.mesh(decimated, "bunny-10459-vc.ply",
             made("quadric decimation to 10459, vertex colours of the field", {{"target_triangles", 10459}}));

  constexpr int kSide = 2048, kBands = 24;
  const auto detail = [&](const Vec3& p) { return detailed_colour(unit(p), kBands); };
  const json atlas = {{"atlas", "per-triangle cells (with_baked_atlas)"}, {"side", kSide}, {"bands", kBands}};
  const TriangleMesh textured = with_baked_atlas(bunny, kSide, detail);
  write.textured(textured, "bunny-atlas.obj", "bunny-atlas.png",
                 made("texture atlas baked from the field", atlas));
  write.textured(textured, "bunny-atlas.gltf", "bunny-atlas.png", made("the same as glTF", atlas), 0, true);
  const Texture& texture = *textured.texture_mapping()->materials[0].texture;
  const auto retextured = [&](const Texture& t) {
    TextureMapping mapping = *textured.texture_mapping();
    mapping.materials[0].texture = std::make_shared<Texture>(t);
    TriangleMesh m = bunny;
    m.set_texture_mapping(std::move(mapping));
    return m;
  };
  for (const int quality : {90, 50, 20}) {
    write.textured(retextured(texture), fmt::format("bunny-atlas-jpeg{}.obj", quality),
                   fmt::format("bunny-atlas-q{}.jpg", quality),
                   made("the atlas as JPEG", {{"jpeg_quality", quality}}), quality);
  }
  for (const int times : {1, 2}) {
    write.textured(retextured(downsampled(texture, times)), fmt::format("bunny-atlas-down{}.obj", 1 << times),
                   fmt::format("bunny-atlas-down{}.png", 1 << times),
                   made("the atlas downsampled by 2 x 2 box filters", {{"factor", 1 << times}}));
  }
  write.textured(retextured(quantised(texture, 4)), "bunny-atlas-4bit.obj", "bunny-atlas-4bit.png",
                 made("the atlas quantised to 4 bits a channel", {{"bits", 4}}));
  const TriangleMesh coarse = with_baked_atlas(decimate_quadric(bunny, 17362), kSide, detail);
  write.textured(coarse, "bunny-17362-atlas.obj", "bunny-17362-atlas.png",
                 made("quadric decimation to 17362 (a quarter), its atlas baked again from the field",
                      {{"target_triangles", 17362}, {"side", kSide}}));
  write.finish();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"roving-datasets: normalised, decimated, voxelised, sampled and analytic test models"};
  std::string data = default_data_folder();
  std::string out = "build/datasets";
  bool quick = false;
  app.add_option("--data", data, "folder of the real models ($ROVING_DATA, else the checkout's data/)")
      ->capture_default_str();
  app.add_option("--out", out, "folder to write into")->capture_default_str();
  app.add_flag("--quick", quick, "the bunny's files only (for tests)");
  bool colour = false;
  app.add_flag(
      "--colour", colour,
      "only the colour benchmark's models, into OUT/colour: the bunny with vertex colours and with a baked "
      "texture atlas, and their degraded copies (decimation, colour quantisation, texture downsampling, "
      "JPEG), as PLY, OBJ + MTL + PNG/JPEG and glTF");
  bool scaling = false;
  app.add_flag("--scaling", scaling,
               "only the scaling benchmark's pairs, into OUT/scaling: the bunny and its perturbed 10,459-triangle "
               "decimation, every triangle split into n^2 (n = 1, 2, 4, 8, 12)");
  bool scaling_large = false;
  app.add_flag("--scaling-large", scaling_large,
               "only the streaming benchmark's references, into OUT/scaling-large: the bunny with every triangle split into "
               "38^2 (100,287,244 triangles) as binary PLY, binary STL and OBJ (1.9, 5.0 and 4.6 GB), and split into "
               "12^2 as STL and OBJ; measured against --scaling's test-n12.ply");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "roving-datasets: error: %s\n", e.what());
    return 2;
  }

  try {
    Writer write(out);
    const auto normalise = [](const std::string& source) {
      return json{{"source", source}, {"operation", "normalise"}, {"longest_side", 128}};
    };
    const auto decimation = [](const std::string& source, std::size_t target) {
      return json{{"source", source},
                  {"operation", "quadric decimation (OpenMesh DecimaterT + ModQuadricT)"},
                  {"target_triangles", target}};
    };

    const std::string bunny_path = (fs::path(data) / "stanford-bunny.obj").string();
    const TriangleMesh bunny = normalised(load_mesh(bunny_path).mesh);
    if (scaling) {
      // 69,451 to 10,000,944 triangles; TEST coarser (the 10,459-triangle decimation) and 0.5% of
      // the diagonal away, split alike: the pair at n = 8 is 4.4 M / 669 k triangles.
      Writer scaled((fs::path(out) / "scaling").string());
      const double diagonal = bunny.bounding_box().diagonal();
      const TriangleMesh coarse = smoothly_perturbed(decimate_quadric(bunny, 10459), 0.005 * diagonal, 0.25 * diagonal);
      for (int n : {1, 2, 4, 8, 12}) {
        scaled.mesh(split_triangles(bunny, n), fmt::format("ref-n{}.ply", n),
                    {{"source", "bunny.ply"}, {"operation", "every triangle split into n^2"}, {"n", n}});
        scaled.mesh(split_triangles(coarse, n), fmt::format("test-n{}.ply", n),
                    {{"source", "bunny.ply"},
                     {"operation", "quadric decimation to 10459, perturbed by 0.5% of the diagonal, every triangle "
                                   "split into n^2"},
                     {"n", n}});
      }
      scaled.finish();
      return 0;
    }
    if (scaling_large) {
      // Binary PLY, binary STL and OBJ: the three formats a REF streams from, at 10^8 and 10^7.
      Writer scaled((fs::path(out) / "scaling-large").string());
      for (int n : {38, 12}) {
        const TriangleMesh split = split_triangles(bunny, n);
        const json made_by = {{"source", "bunny.ply"}, {"operation", "every triangle split into n^2"}, {"n", n}};
        if (n == 38) scaled.mesh(split, "ref-n38.ply", made_by);  // --scaling writes ref-n12.ply
        scaled.plain(split, fmt::format("ref-n{}.stl", n), made_by);
        scaled.plain(split, fmt::format("ref-n{}.obj", n), made_by);
      }
      scaled.finish();
      return 0;
    }
    if (colour) {
      write_colour_models(bunny, (fs::path(out) / "colour").string());
      return 0;
    }
    write.mesh(bunny, "bunny.ply", normalise(bunny_path));
    write.mesh(bunny, "bunny.obj", normalise(bunny_path));
    for (std::size_t target : {800u, 10459u}) {  // the paper's low and middle meshes (Table 2)
      write.mesh(decimate_quadric(bunny, target), fmt::format("bunny-{}.ply", target),
                 decimation("bunny.ply", target));
    }
    // The speed issue's second pair: every vertex of the bunny moved along its normal by up to 1%
    // of the diagonal (as accuracy_pairs.cpp's "perturbed 1%").
    const double diagonal = bunny.bounding_box().diagonal();
    write.mesh(smoothly_perturbed(bunny, 0.01 * diagonal, 0.25 * diagonal), "bunny-perturbed.ply",
               {{"source", "bunny.ply"},
                {"operation", "vertices moved along their normals by a smooth wave (smoothly_perturbed)"},
                {"amplitude", 0.01 * diagonal},
                {"wavelength", 0.25 * diagonal}});
    for (int dimension : {32, 128}) {  // the paper's sparse and dense voxels (Table 2)
      write.voxels(voxelize_conservative(bunny, dimension), fmt::format("bunny-vox{}.binvox", dimension),
                   {{"source", "bunny.ply"},
                    {"operation", "conservative voxelisation (exact triangle-box overlap)"},
                    {"dimension", dimension}});
      write.voxels(voxelize_thin(bunny, dimension), fmt::format("bunny-vox{}-thin.binvox", dimension),
                   {{"source", "bunny.ply"},
                    {"operation", "thin 26-separating voxelisation (Huang et al. 1998)"},
                    {"dimension", dimension}});
    }
    write.points(sampled_points(bunny, 20000), "bunny-points.ply",
                 {{"source", "bunny.ply"},
                  {"operation", "area-uniform samples with face normals"},
                  {"count", 20000},
                  {"seed", 12345}});
    write.points(
        PointCloud{sampled_points(bunny, 20000).positions, {}, {}}, "bunny-points.xyz",
        {{"source", "bunny.ply"}, {"operation", "the same samples without normals"}, {"count", 20000}});

    // Analytic cases: exact sphere of radius 50 against concentric tessellated spheres and a
    // voxelised sphere; a torus against a thicker one; parallel planes 1 apart.
    const Vec3 centre(64, 64, 64);
    write.points(sphere_points(centre, 50, 20000), "sphere-r50-exact.ply",
                 {{"operation", "exact sphere samples (Fibonacci lattice) with exact normals"},
                  {"radius", 50},
                  {"centre", {64, 64, 64}}});
    for (double radius : {50.0, 51.0, 49.0}) {
      write.mesh(icosphere(centre, radius, 5), fmt::format("sphere-r{}-ico5.ply", int(radius)),
                 {{"operation", "icosphere, 5 subdivisions, vertices on the sphere"}, {"radius", radius}});
    }
    write.voxels(
        voxelize_conservative(icosphere(centre, 50, 5), 128), "sphere-r50-vox128.binvox",
        {{"source", "sphere-r50-ico5.ply"}, {"operation", "conservative voxelisation"}, {"dimension", 128}});
    write.mesh(torus(40, 15, 256, 96), "torus-40-15.ply",
               {{"operation", "torus"}, {"major", 40}, {"minor", 15}});
    write.mesh(torus(40, 16, 256, 96), "torus-40-16.ply",
               {{"operation", "torus"}, {"major", 40}, {"minor", 16}});
    write.mesh(square(50, 0, 20), "plane-z0.ply", {{"operation", "square"}, {"half", 50}, {"height", 0}});
    write.mesh(square(60, 1, 7), "plane-z1.ply", {{"operation", "square"}, {"half", 60}, {"height", 1}});
    const std::string teapot = (fs::path(data) / "teapot.bpt").string();
    fs::copy_file(teapot, fs::path(out) / "teapot.bpt", fs::copy_options::overwrite_existing);
    write.copied(
        "teapot.bpt",
        {{"source", teapot}, {"operation", "copy: 32 bicubic Bezier patches, read as a parametric surface"}});

    if (!quick) {
      // The other real models, normalised and decimated to a quarter and a twentieth.
      for (const char* name : {"rocker-arm.obj", "igea.ply", "fandisk.obj"}) {
        const std::string source = (fs::path(data) / name).string();
        const TriangleMesh model = normalised(load_mesh(source).mesh);
        const std::string stem = fs::path(name).stem().string();
        write.mesh(model, stem + ".ply", normalise(source));
        for (std::size_t divisor : {4u, 20u}) {
          // Even: on a closed mesh every collapse removes two triangles.
          const std::size_t target = model.triangle_count() / divisor / 2 * 2;
          write.mesh(decimate_quadric(model, target), fmt::format("{}-{}.ply", stem, target),
                     decimation(stem + ".ply", target));
        }
      }
    }
    if (!quick) {
      for (const PaperCountModel& m : kPaperCountModels) {
        const std::string source = (fs::path(data) / m.source).string();
        write.mesh(decimate_quadric(normalised(load_mesh(source).mesh), m.triangles), m.file,
                   decimation(std::string(m.source) + ", normalised", m.triangles));
      }
    }
    write.finish();
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roving-datasets: error: %s\n", e.what());
    return 1;
  }
}
