// `roving-datasets`: writes the derived test models (normalised and decimated copies of the real
// models) into a folder, with a JSON manifest of what made each file.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "decimate.h"
#include "roving/error.h"
#include "roving/mesh_io.h"
#include "roving/normalise.h"
#include "roving/stopwatch.h"

namespace fs = std::filesystem;

namespace {

std::string default_data_folder() {
  if (const char* env = std::getenv("ROVING_DATA"); env && *env) return env;
  return "../shared/data";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"roving-datasets: normalised and decimated test models from the real ones"};
  std::string data = default_data_folder();
  std::string out = "build/datasets";
  app.add_option("--data", data, "folder of the real models ($ROVING_DATA or ../shared/data)")
      ->capture_default_str();
  app.add_option("--out", out, "folder to write into")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "roving-datasets: error: %s\n", e.what());
    return 2;
  }

  try {
    fs::create_directories(out);
    nlohmann::json manifest = nlohmann::json::array();
    const auto write = [&](const roving::TriangleMesh& mesh, const std::string& name,
                           nlohmann::json made_by) {
      const std::string path = (fs::path(out) / name).string();
      roving::save_mesh(mesh, path, true);
      manifest.push_back({{"file", name},
                          {"made_by", std::move(made_by)},
                          {"vertices", mesh.vertex_count()},
                          {"triangles", mesh.triangle_count()}});
      std::fprintf(stderr, "wrote %s (%zu triangles)\n", path.c_str(), mesh.triangle_count());
    };

    const std::string bunny_path = (fs::path(data) / "stanford-bunny.obj").string();
    const roving::TriangleMesh bunny = roving::normalised(roving::load_mesh(bunny_path).mesh, 128.0);
    write(bunny, "bunny.ply", {{"source", bunny_path}, {"operation", "normalise"}, {"longest_side", 128}});
    write(bunny, "bunny.obj", {{"source", bunny_path}, {"operation", "normalise"}, {"longest_side", 128}});
    // The paper's low and middle resolutions (Table 2).
    for (std::size_t target : {800u, 10459u}) {
      const roving::Stopwatch watch;
      write(roving::decimate_quadric(bunny, target), fmt::format("bunny-{}.ply", target),
            {{"source", "bunny.ply"},
             {"operation", "quadric decimation (OpenMesh DecimaterT + ModQuadricT)"},
             {"target_triangles", target},
             {"seconds", watch.seconds()}});
    }
    std::ofstream(fs::path(out) / "manifest.json") << manifest.dump(2) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roving-datasets: error: %s\n", e.what());
    return 1;
  }
}
