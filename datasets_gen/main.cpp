// `roving-datasets`: writes, deterministically, the derived test models (normalised, decimated,
// voxelised, sampled and analytic) into a folder, with a JSON manifest of what made each file,
// its parameters, counts and sha256.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "data_folder.h"
#include "analytic.h"
#include "decimate.h"
#include "paper_models.h"
#include "roving/core/error.h"
#include "roving/core/normalise.h"
#include "roving/core/sample_set.h"
#include "roving/formats/binvox.h"
#include "roving/formats/file_hash.h"
#include "roving/formats/mesh_io.h"
#include "roving/formats/point_cloud_io.h"
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
};

// Points uniform by area on `mesh`, with its face normals (a scanned-cloud stand-in).
PointCloud sampled_points(const TriangleMesh& mesh, std::size_t count) {
  const SampleSet s = make_samples(mesh, {SampleSpec::Kind::Area, count});
  return {s.positions, s.normals, {}};
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
  bool scaling = false;
  app.add_flag("--scaling", scaling,
               "only the scaling benchmark's pairs, into OUT/scaling: the bunny and its perturbed 10,459-triangle "
               "decimation, every triangle split into n^2 (n = 1, 2, 4, 8, 12)");
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
