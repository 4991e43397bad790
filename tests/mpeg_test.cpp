// MPEG's point-cloud figures (roving/mpeg/) against the tools' own output: the golden files in
// tests/data/mpeg/golden/ are pc_error's stdout on the pairs of tests/data/mpeg/make_clouds.py
// (tests/data/mpeg/record_pc_error.sh, mpeg-pcc-dmetric release-v0.14.2) and mmetric's on the mesh
// pairs of make_meshes.py (record_mmetric.sh, mmetric 1.1.7 `mm compare --mode pcc`), each headed by
// its command. Both print 9 significant digits (float's max_digits10), so a figure agrees when it
// rounds to what they printed: relative 1e-8. A PSNR printed as inf is null in our JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "cli_support.h"
#include "roving/core/error.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/mpeg/lattice_neighbours.h"
#include "roving/mpeg/mpeg_points.h"
#include "roving/mpeg/point_cloud_psnr.h"

namespace roving {
namespace {

using testing::cli::CliRun;
using testing::cli::expect_error;
using testing::cli::run_cli;

const std::string kData = std::string(ROVING_SOURCE_DIR) + "/tests/data/mpeg/";

struct Golden {
  std::string command;                        // pc_error's, as recorded
  std::string file_a, file_b;
  std::string options;                        // the command's options, as `roving measure --pcc` takes them
  std::string colour_space;                   // --mseSpace: "0", "1" (default) or "8"
  double peak = 0;
  std::map<std::string, std::string> values;  // "a_to_b/d1_mse" -> "1.48473455"
};

// A pc_error (or mmetric) command line's options as roving's: each option that changes a figure has
// its equivalent (docs/mpeg.md's table); those that change none are left out; any other fails.
std::string translated(const std::string& command) {
  static const std::map<std::string, std::string> ours = {
      {"resolution", "--pcc-resolution"},        {"inputNorm", "--pcc-normals"},
      {"dropdups", "--pcc-dropdups"},            {"dropDuplicates", "--pcc-dropdups"},
      {"neighborsProc", "--pcc-neighbors-proc"},
      {"averageNormals", "--pcc-average-normals"}, {"mseSpace", "--pcc-mse-space"},
      {"normalCalcModificationEnable", "--pcc-normal-calc-modification"}};
  // Files, and options whose figures roving always gives (colour, Hausdorff) or that change none.
  static const std::set<std::string> none = {"fileA", "fileB", "inputModelA", "inputModelB", "color",
                                             "hausdorff", "nbThreads", "mode"};
  std::string options;
  const std::regex option(R"(--(\w+)(=(\S+))?)");
  for (auto it = std::sregex_iterator(command.begin(), command.end(), option); it != std::sregex_iterator(); ++it) {
    const std::string key = (*it)[1], value = (*it)[3];
    if (none.count(key)) continue;
    const auto found = ours.find(key);
    if (found == ours.end()) {
      ADD_FAILURE() << "--" << key << " of " << command << " has no equivalent";
      continue;
    }
    options += " " + found->second + " " + (key == "inputNorm" ? kData + value : value);
  }
  return options;
}

Golden read_golden(const std::string& name) {
  std::ifstream in(kData + "golden/" + name + ".txt");
  EXPECT_TRUE(in) << name;
  Golden g;
  std::getline(in, g.command);
  std::smatch m;
  const auto option = [&](const char* key) {
    const std::regex pattern(std::string("--") + key + "=(\\S+)");
    return std::regex_search(g.command, m, pattern) ? m[1].str() : std::string();
  };
  g.file_a = option("fileA") + option("inputModelA");  // pc_error's or mmetric's
  g.file_b = option("fileB") + option("inputModelB");
  g.options = translated(g.command);
  g.colour_space = option("mseSpace").empty() ? "1" : option("mseSpace");
  const char* sections[] = {"a_to_b", "b_to_a", "symmetric"};
  // c[k]'s names in each colour space (h.c[k] are always R, G, B).
  const char* const spaces[][3] = {{"r", "g", "b"}, {"y", "cb", "cr"}, {"ycocg_y", "co", "cg"}};
  const auto& space = spaces[g.colour_space == "0" ? 0 : g.colour_space == "8" ? 2 : 1];
  const char* rgb[] = {"r", "g", "b"};
  const std::regex geometry(R"(^\s*(mse|h\.)[12F]?(,PSNR)?\s*[12F]?\s*\((p2point|p2plane)\): (\S+))");
  const std::regex colour(R"(^\s*(h\.)?c\[(\d)\],(PSNR)?\s*[12F]\s*: (\S+))");
  const std::regex peak(R"(^Peak distance for PSNR: (\S+))");
  std::string section;
  for (std::string line; std::getline(in, line);) {
    if (line.size() > 2 && line[1] == '.' && line[0] >= '1' && line[0] <= '3') section = sections[line[0] - '1'];
    if (std::regex_search(line, m, peak)) g.peak = std::stod(m[1]);
    if (std::regex_search(line, m, geometry)) {
      const bool hausdorff = m[1] == "h.", psnr = m[2].matched;
      const std::string figure = std::string(m[3] == "p2point" ? "d1" : "d2") + (hausdorff ? "_hausdorff" : "") +
                                 (psnr ? "_psnr" : hausdorff ? "" : "_mse");
      g.values[section + "/" + figure] = m[4];
    } else if (std::regex_search(line, m, colour)) {
      const int channel = std::stoi(m[2]);
      const bool hausdorff = m[1].matched;
      const std::string name = hausdorff ? rgb[channel] : space[channel];
      const bool psnr = m[3].matched;
      g.values[section + "/" + name + (hausdorff ? "_hausdorff" : "") + (psnr ? "_psnr" : hausdorff ? "" : "_mse")] =
          m[4];
    }
  }
  return g;
}

nlohmann::json measure_pcc(const Golden& g) {
  const CliRun run = run_cli("measure " + kData + g.file_a + " " + kData + g.file_b + " --pcc --json -" + g.options);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return nlohmann::json::parse(run.out)["mpeg_pcc"];
}

void expect_equal_to_pc_error(const std::string& name, std::size_t at_least) {
  SCOPED_TRACE(name);
  const Golden g = read_golden(name);
  ASSERT_GE(g.values.size(), at_least) << g.command;
  const nlohmann::json ours = measure_pcc(g);
  EXPECT_NEAR(ours["peak"].get<double>(), g.peak, 1e-8 * g.peak);
  for (const auto& [key, printed] : g.values) {
    const auto slash = key.find('/');
    const nlohmann::json& value = ours[key.substr(0, slash)][key.substr(slash + 1)];
    if (printed == "inf") {
      EXPECT_TRUE(value.is_null()) << key << ": " << value;
      continue;
    }
    ASSERT_TRUE(value.is_number()) << key << " missing from " << ours.dump();
    // pc_error starts its maxima from the smallest double, so where every distance is 0 it prints
    // that (2.22507386e-308) for 0 (docs/mpeg.md).
    const double theirs = printed == "2.22507386e-308" ? 0.0 : std::stod(printed);
    EXPECT_NEAR(value.get<double>(), theirs, 1e-8 * std::abs(theirs)) << key << " (pc_error printed " << printed << ")";
  }
}

// 10-bit voxels with duplicates in both clouds (averaged colours), D2 from A's normals carried onto
// B, Y'CbCr and RGB colour, the peak given and pc_error's default.
TEST(PcErrorGolden, VoxelisedTenBitsWithDuplicates) {
  expect_equal_to_pc_error("sphere10_r1023", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("sphere10_peak", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("sphere10_rgb", 3 * 8 + 3 * 12);
}

// pc_error's options that change a figure, each from its recorded command line as translated()
// translates it: which points at one position are kept (--dropdups), which colour of the points
// tied nearest (--neighborsProc: on sphere10 most points have several), D2 from the first found
// alone (--averageNormals 0), YCoCg-R (--mseSpace 8), and some together.
TEST(PcErrorGolden, EveryOptionThatChangesAFigure) {
  for (const char* name : {"sphere10_dropdups0", "sphere10_dropdups1", "sphere10_neighbors0", "sphere10_neighbors2",
                           "sphere10_neighbors3", "sphere10_neighbors4", "sphere10_average_normals0", "sphere10_ycocg",
                           "sphere10_dropdups0_neighbors2", "sphere10_mixed", "blob_float_neighbors3"}) {
    expect_equal_to_pc_error(name, 3 * 8 + 3 * 12);
  }
  expect_equal_to_pc_error("torus11_average_normals0", 3 * 8);
  // The options are in the report, as pc_error names them; the defaults' reports have none.
  const nlohmann::json mixed = measure_pcc(read_golden("sphere10_mixed"));
  EXPECT_EQ(mixed["pc_error_options"],
            nlohmann::json({{"dropdups", 1}, {"neighborsProc", 4}, {"averageNormals", 0}, {"mseSpace", 8}}));
  EXPECT_EQ(mixed["points"][0], 6649);
  EXPECT_EQ(measure_pcc(read_golden("sphere10_dropdups0"))["points"][0], 8000);
  EXPECT_FALSE(measure_pcc(read_golden("sphere10_r1023")).contains("pc_error_options"));
}

// NaN normals in A (60 of 8,000): pc_error computes on, adding for a nearest point with a NaN normal
// the sum of the coordinates' differences, unsquared (under --averageNormals 0 the squared distance);
// so do MPEG's figures here, with a warning naming how many and the first.
TEST(PcErrorGolden, NanNormalsAsPcErrorComputesOnThem) {
  expect_equal_to_pc_error("sphere10_nan_normals", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("sphere10_nan_normals_average0", 3 * 8 + 3 * 12);
  const CliRun run =
      run_cli("measure " + kData + "sphere10_a_nan_normals.ply " + kData + "sphere10_b.ply --pcc --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("of " + kData + "sphere10_a_nan_normals.ply's normals are NaN, the first its point"),
            std::string::npos)
      << run.err;
}

// The defaults through pc_error's loop as written (pc_error_loop.h) and through the faster search
// give the same figures, bit for bit: the voxelised pairs' lattice, the float pair's k-d tree.
TEST(PcErrorFigures, ItsLoopAsWrittenAgreesWithTheFasterSearch) {
  for (const char* pair : {"sphere10", "torus11", "blob_float"}) {
    SCOPED_TRACE(pair);
    MpegPoints a = mpeg_points(read_point_cloud(kData + pair + "_a.ply", false), "a", MpegReading{true});
    const MpegPoints b = mpeg_points(read_point_cloud(kData + pair + "_b.ply", false), "b", MpegReading{false});
    MpegRules rules;
    const MpegFigures fast = mpeg_point_cloud_figures(a, b, rules, "a");
    a.nan_normals = 1;  // pretends: the loop as written then answers
    const MpegFigures loop = mpeg_point_cloud_figures(a, b, rules, "a");
    for (const auto& [f, l] : {std::pair(fast.a_to_b, loop.a_to_b), std::pair(fast.b_to_a, loop.b_to_a)}) {
      EXPECT_EQ(f.d1_mse, l.d1_mse);
      EXPECT_EQ(f.d2_mse, l.d2_mse);
      EXPECT_EQ(f.d1_hausdorff, l.d1_hausdorff);
      EXPECT_EQ(f.d2_hausdorff, l.d2_hausdorff);
      EXPECT_EQ(f.ycbcr_mse, l.ycbcr_mse);
      EXPECT_EQ(f.rgb_mse, l.rgb_mse);
      EXPECT_EQ(f.rgb_hausdorff, l.rgb_hausdorff);
    }
  }
}

// A's normals not unit, and some of length 0, as some tools write them: pc_error uses them as the
// file has them (D2 scales by each normal's squared length; a zero normal gives 0), so --pcc does,
// where a plain measure makes them unit (and refuses one of length 0).
TEST(PcErrorGolden, NormalsAsTheFileHasThem) {
  expect_equal_to_pc_error("sphere10_scaled_normals", 3 * 8 + 3 * 12);
}

// B as A: B has no normals, so neither has D2 (pc_error takes D2's normals from A alone).
TEST(PcErrorGolden, WithoutNormalsThereIsNoD2) {
  expect_equal_to_pc_error("sphere10_swapped", 3 * 4 + 3 * 12);
  const nlohmann::json ours = measure_pcc(read_golden("sphere10_swapped"));
  EXPECT_TRUE(ours["d2"].is_string());
  EXPECT_FALSE(ours["symmetric"].contains("d2_mse"));
}

// pc_error's --inputNorm: A without normals, its normals in a file of their own (A's points in
// another order, other normals), paired with A's points as pc_error pairs them.
TEST(PcErrorGolden, NormalsFromAFileOfTheirOwn) {
  expect_equal_to_pc_error("sphere10_normals_file", 3 * 8 + 3 * 12);
  const nlohmann::json ours = measure_pcc(read_golden("sphere10_normals_file"));
  EXPECT_EQ(ours["normals_from"], kData + "sphere10_a_normals.ply");
  EXPECT_EQ(measure_pcc(read_golden("sphere10_r1023"))["normals_from"], "A's file");
}

// A point-cloud A against a mesh B (mmetric's rules) takes a normals file too: A's own normals
// given again change nothing, other normals change D2 alone.
TEST(PcErrorFigures, NormalsFileForACloudAgainstAMesh) {
  const std::string a = kData + "sphere10_a.ply", b = kData + "fandisk10_b.ply";
  const auto figures = [&](const std::string& normals) {
    const CliRun run = run_cli("measure " + a + " " + b + " --pcc --pcc-resolution 1023 --json -" +
                               (normals.empty() ? "" : " --pcc-normals " + normals));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["mpeg_pcc"];
  };
  const nlohmann::json own = figures(""), again = figures(a), tilted = figures(kData + "sphere10_a_normals.ply");
  EXPECT_EQ(own["normals_from"], "A's file");
  EXPECT_EQ(again["normals_from"], a);
  EXPECT_EQ(again["symmetric"], own["symmetric"]);
  EXPECT_EQ(tilted["symmetric"]["d1_mse"], own["symmetric"]["d1_mse"]);
  EXPECT_NE(tilted["b_to_a"]["d2_mse"], own["b_to_a"]["d2_mse"]);
}

TEST(PcErrorGolden, ElevenBitsWithoutColour) {
  expect_equal_to_pc_error("torus11_r2047", 3 * 8);
  expect_equal_to_pc_error("torus11_peak", 3 * 8);
}

TEST(PcErrorGolden, FloatCoordinates) {
  expect_equal_to_pc_error("blob_float_peak", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("blob_float_rgb", 3 * 8 + 3 * 12);
}

// A cloud against itself: every MSE and Hausdorff 0, every PSNR infinite (null), as pc_error's.
TEST(PcErrorGolden, ACloudAgainstItselfIsExact) {
  expect_equal_to_pc_error("sphere10_identical", 3 * 8 + 3 * 12);
  const std::string a = kData + "sphere10_a.ply";
  const CliRun run = run_cli("measure " + a + " " + a + " --pcc --pcc-resolution 1023 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json s = nlohmann::json::parse(run.out)["mpeg_pcc"]["symmetric"];
  for (const char* key : {"d1_mse", "d2_mse", "d1_hausdorff", "d2_hausdorff", "y_mse", "r_mse", "r_hausdorff"})
    EXPECT_EQ(s[key].get<double>(), 0.0) << key;
  for (const char* key : {"d1_psnr", "d2_psnr", "d1_hausdorff_psnr", "y_psnr", "r_psnr"})
    EXPECT_TRUE(s[key].is_null()) << key;
}

// Two point clouds without --pcc: the surface figures (surfels) and pc_error's beside them.
// Meshes as a mesh codec outputs them (decimated, quantised, with degenerate triangles), sampled as
// mmetric samples them: its sample counts, default peak (A's box diagonal), D2 with B's own
// normals, merged normals averaged, and a mesh against a point cloud.
TEST(MmetricGolden, MeshesSampledAsMmetricSamplesThem) {
  expect_equal_to_pc_error("mmetric_fandisk10", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_r1023", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_rocker8", 3 * 8);
  expect_equal_to_pc_error("mmetric_fandisk10_points", 3 * 8 + 3 * 12);
  // --normalCalcModificationEnable=false: A -> B's D2 along A's normals carried onto B, as pc_error's.
  expect_equal_to_pc_error("mmetric_fandisk10_carried", 3 * 8 + 3 * 12);
  // Its --neighborsProc (the tied nearest points' colour: the nearest and the farthest in RGB).
  expect_equal_to_pc_error("mmetric_fandisk10_neighbors0", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_neighbors3", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_neighbors4", 3 * 8 + 3 * 12);
  // ... weighing a merged point by how many it merged (--neighborsProc=2), and its --dropDuplicates:
  // every sample at one position kept (0), or the first (1), alone and with --neighborsProc.
  expect_equal_to_pc_error("mmetric_fandisk10_neighbors2", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_dropdups0", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_dropdups1", 3 * 8 + 3 * 12);
  expect_equal_to_pc_error("mmetric_fandisk10_dropdups0_neighbors4", 3 * 8 + 3 * 12);
  const nlohmann::json ours = measure_pcc(read_golden("mmetric_fandisk10"));
  std::ifstream golden(kData + "golden/mmetric_fandisk10.txt");
  const std::string text((std::istreambuf_iterator<char>(golden)), std::istreambuf_iterator<char>());
  // "Generated N points" per mesh, then the merged sizes.
  EXPECT_NE(text.find("Generated " + std::to_string(ours["points_read"][0].get<int>()) + " points"), std::string::npos);
  EXPECT_NE(text.find("Generated " + std::to_string(ours["points_read"][1].get<int>()) + " points"), std::string::npos);
  EXPECT_NE(text.find("scaling ratio: " + std::to_string(ours["points"][0].get<int>()) + ", " +
                      std::to_string(ours["points"][1].get<int>())),
            std::string::npos);
  EXPECT_EQ(ours["computed_as"].get<std::string>().rfind("mmetric", 0), 0u);
}

// Beside mmetric's sampled figures, D1 and D2 of the surfaces themselves. Two parallel squares t apart,
// side 100 in 10 x 10 cells: every point of each has its closest point straight across, so the
// surfaces' D1 MSE is t^2 exactly (area samples give it with a zero-width interval), and the
// certified Hausdorff interval holds t^2. The sampled figure is no smaller (a point's nearest
// sample is never nearer than the surface it lies on).
TEST(MmetricGolden, SurfacesOwnD1AndD2BesideTheSampledOnes) {
  const testing::cli::fs::path folder = testing::cli::fs::temp_directory_path() / "roving-mpeg-planes";
  testing::cli::fs::create_directories(folder);
  // A rectangle [0, width] x [0, 100] at height z in 10 x 10 cells.
  const auto square = [&](const std::string& name, double z, double width = 100) {
    std::ofstream obj(folder / name);
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i) obj << "v " << width / 10 * i << " " << 10 * j << " " << z << "\n";
    for (int j = 0; j < 10; ++j) {
      for (int i = 0; i < 10; ++i) {
        const int a = j * 11 + i + 1;
        obj << "f " << a << " " << a + 1 << " " << a + 12 << "\nf " << a << " " << a + 12 << " " << a + 11 << "\n";
      }
    }
    return (folder / name).string();
  };
  const double t = 3;
  const std::string a = square("a.obj", 0), b = square("b.obj", t);
  const CliRun run = run_cli("measure " + a + " " + b + " --pcc --samples area:20000 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json mpeg = nlohmann::json::parse(run.out)["mpeg_pcc"];
  const nlohmann::json exact = mpeg["exact_surface"]["symmetric"];
  EXPECT_NEAR(exact["d1_mse"].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(exact["d1_mse_interval"][0].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(exact["d1_mse_interval"][1].get<double>(), t * t, 1e-9);
  EXPECT_LE(exact["d1_hausdorff_certified"][0].get<double>(), t * t + 1e-9);
  EXPECT_GE(exact["d1_hausdorff_certified"][1].get<double>(), t * t - 1e-9);
  EXPECT_GE(mpeg["symmetric"]["d1_mse"].get<double>(), t * t - 1e-9);
  EXPECT_EQ(exact["no_hits"], 0);
  // Straight across, the distance is all along the normal: D2 = D1.
  EXPECT_NEAR(exact["d2_mse"].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(exact["d2_mse_interval"][1].get<double>(), t * t, 1e-9);

  // B half as wide: A's points beyond x = 50 have their closest point on B's edge, at squared
  // distance t^2 + (x - 50)^2, but only t of it lies along B's normal. So A -> B's D2 is t^2 at
  // every sample (a zero-width interval) while its D1 is t^2 + the mean of (x - 50)^2 over half
  // of A, 50^2 / 3 / 2 = 416.67 (its 95% interval must hold that); B -> A is t^2 both ways.
  const std::string half = square("half.obj", t, 50);
  const CliRun edge = run_cli("measure " + a + " " + half + " --pcc --samples area:20000 --json -");
  ASSERT_EQ(edge.exit_code, 0) << edge.err;
  const nlohmann::json surfaces = nlohmann::json::parse(edge.out)["mpeg_pcc"]["exact_surface"];
  const nlohmann::json ab = surfaces["a_to_b"], ba = surfaces["b_to_a"];
  EXPECT_NEAR(ab["d2_mse"].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(ab["d2_mse_interval"][0].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(ab["d2_mse_interval"][1].get<double>(), t * t, 1e-9);
  const double d1 = t * t + 2500.0 / 6;
  EXPECT_LE(ab["d1_mse_interval"][0].get<double>(), d1);
  EXPECT_GE(ab["d1_mse_interval"][1].get<double>(), d1);
  EXPECT_NEAR(ba["d1_mse"].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(ba["d2_mse"].get<double>(), t * t, 1e-9);
  EXPECT_NEAR(surfaces["symmetric"]["d2_mse"].get<double>(), t * t, 1e-9);
  EXPECT_EQ(surfaces["symmetric"]["d1_mse"], ab["d1_mse"]);
  // A floor on it: its zero-width interval decides the same either way.
  const double d2_psnr = surfaces["symmetric"]["d2_psnr"].get<double>();
  const std::string gate = "measure " + a + " " + half + " --pcc --samples area:20000 --gate-on upper --fail-below ";
  EXPECT_EQ(run_cli(gate + fmt::format("mpeg_surface_d2_psnr={}", d2_psnr - 0.01)).exit_code, 0);
  EXPECT_EQ(run_cli(gate + fmt::format("mpeg_surface_d2_psnr={}", d2_psnr + 0.01)).exit_code, 3);
  testing::cli::fs::remove_all(folder);
}

TEST(PcErrorFigures, GivenBesideTheSurfaceFiguresForTwoPointClouds) {
  const Golden g = read_golden("blob_float_peak");
  const CliRun run = run_cli("measure " + kData + g.file_a + " " + kData + g.file_b + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_TRUE(json.contains("statistics"));
  EXPECT_NEAR(json["mpeg_pcc"]["symmetric"]["d1_psnr"].get<double>(), std::stod(g.values.at("symmetric/d1_psnr")),
              1e-6);
  const CliRun text = run_cli("measure " + kData + g.file_a + " " + kData + g.file_b);
  EXPECT_NE(text.out.find("MPEG point-cloud figures"), std::string::npos) << text.out;
}

// batch --pcc: each pair's figures in its report and the summary's MPEG columns, duplicates and all.
TEST(PcErrorFigures, BatchSummaryHasThem) {
  const testing::cli::fs::path folder = testing::cli::fs::temp_directory_path() / "roving-mpeg-batch";
  testing::cli::fs::remove_all(folder);
  testing::cli::fs::create_directories(folder);
  {
    std::ofstream manifest(folder / "pairs.csv");
    manifest << "reference,test,pcc_normals\n";
    for (const char* pair : {"sphere10", "torus11"}) {
      manifest << kData << pair << "_a.ply," << kData << pair << "_b.ply,\n";
    }
    // A's normals in a file of their own, named relative to the manifest.
    testing::cli::fs::copy_file(kData + "sphere10_a_normals.ply", folder / "normals.ply");
    manifest << kData << "sphere10_a_bare.ply," << kData << "sphere10_b.ply,normals.ply\n";
  }
  const CliRun run = run_cli("batch " + (folder / "pairs.csv").string() + " --pcc --pcc-resolution 1023 --quiet --out " +
                             (folder / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream summary(folder / "out" / "summary.csv");
  std::string header, line;
  std::getline(summary, header);
  std::vector<std::string> columns;
  std::stringstream split(header);
  for (std::string c; std::getline(split, c, ',');) columns.push_back(c);
  const std::size_t d1 = std::find(columns.begin(), columns.end(), "mpeg_d1_psnr") - columns.begin();
  const std::size_t d2 = std::find(columns.begin(), columns.end(), "mpeg_d2_psnr") - columns.begin();
  ASSERT_LT(d1, columns.size());
  ASSERT_LT(d2, columns.size());
  for (const char* pair : {"sphere10", "torus11"}) {
    ASSERT_TRUE(std::getline(summary, line));
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
    const CliRun one = run_cli("measure " + kData + pair + "_a.ply " + kData + pair +
                               "_b.ply --pcc --pcc-resolution 1023 --json -");
    const double expected = nlohmann::json::parse(one.out)["mpeg_pcc"]["symmetric"]["d1_psnr"].get<double>();
    EXPECT_DOUBLE_EQ(std::stod(cells.at(d1)), expected) << pair;
  }
  ASSERT_TRUE(std::getline(summary, line));
  std::vector<std::string> cells;
  std::stringstream row(line);
  for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
  const Golden g = read_golden("sphere10_normals_file");
  EXPECT_NEAR(std::stod(cells.at(d2)), std::stod(g.values.at("symmetric/d2_psnr")), 1e-6) << line;
  testing::cli::fs::remove_all(folder);
}

// --fail-below gates MPEG's PSNRs: exit 3 below the floor with a line naming it, 0 above; a floor on
// a figure not measured fails before the work.
TEST(PcErrorFigures, PsnrFloorsGate) {
  const std::string pair = kData + "sphere10_a.ply " + kData + "sphere10_b.ply --pcc --pcc-resolution 1023";
  // D1 63.2522 dB, D2 68.0986 dB, Y 34.3333 dB (the golden values above).
  EXPECT_EQ(run_cli("measure " + pair + " --fail-below mpeg_d1_psnr=63 --fail-below mpeg_d2_psnr=68").exit_code, 0);
  const CliRun low = run_cli("measure " + pair + " --fail-below mpeg_d1_psnr=63.3 --fail-below mpeg_y_psnr=30");
  EXPECT_EQ(low.exit_code, 3);
  EXPECT_NE(low.err.find("gate breached: mpeg_d1_psnr = 63.2522 dB is below the floor 63.3 dB"), std::string::npos)
      << low.err;
  EXPECT_EQ(low.err.find("mpeg_y_psnr"), std::string::npos) << low.err;
  expect_error("measure " + pair + " --fail-below mpeg_surface_d1_psnr=60", {"--fail-below", "mpeg_surface_d1_psnr"});
  const CliRun unknown = run_cli("measure " + pair + " --fail-below usiad=1");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("expected a metric among mpeg_d1_psnr"), std::string::npos) << unknown.err;
}

// pc_error's merging of equal points: lexicographic order of the float coordinates, -0 equal to
// +0 as float's == has it, the first normal in file order (a NaN one behind it is never read),
// colours summed and divided as integers.
TEST(MpegPoints, EqualPointsMergeAsPcErrorMergesThem) {
  PointCloud cloud;
  cloud.positions = {{1, 0, 0}, {-0.0, 2, 0}, {0, 2, 0}, {0, -1, 5}, {1, 0, 0}, {1, 0, 1e-9}};
  const double nan = std::nan("");
  cloud.normals = {{1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
  cloud.colours = {{10, 20, 30}, {0, 0, 0}, {255, 255, 254}, {7, 8, 9}, {11, 21, 32}, {1, 2, 3}};
  const MpegPoints points = mpeg_points(cloud, "six.ply", MpegReading{true});
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points.points_read, 6u);
  using P = std::array<float, 3>;
  EXPECT_EQ(points.positions, (std::vector<P>{{0, -1, 5}, {0, 2, 0}, {1, 0, 0}, {1, 0, 1e-9f}}));
  EXPECT_EQ(points.normals, (std::vector<P>{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}}));
  using C = std::array<std::uint8_t, 3>;
  EXPECT_EQ(points.colours, (std::vector<C>{{7, 8, 9}, {127, 127, 127}, {10, 20, 31}, {1, 2, 3}}));
  // mmetric's merging averages the normals instead, so there the NaN one is read and named.
  try {
    mpeg_points(cloud, "six.ply", MpegReading{true, true});
    ADD_FAILURE() << "a NaN normal that is averaged was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("six.ply: normal 2"), std::string::npos) << e.what();
  }
  // Of several, the first in the file is named, not the first in the points' sorted order (point
  // 5, at z = 1e-9, sorts after point 2; point 3, at z = 5, before it).
  cloud.normals[5] = {nan, 0, 0};
  cloud.normals[3] = {nan, 0, 0};
  try {
    mpeg_points(cloud, "six.ply", MpegReading{true, true});
    ADD_FAILURE() << "NaN normals that are averaged were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("six.ply: normal 2"), std::string::npos) << e.what();
  }
}

// pc_error's --dropdups 0 and 1, the counts --neighborsProc 2 weighs by, and NaN normals kept where
// asked (pc_error computes on with them; counted, the first in file order named).
TEST(MpegPoints, DuplicatesKeptOrTheFirstAsPcErrorsDropdupsSays) {
  PointCloud cloud;
  cloud.positions = {{1, 0, 0}, {-0.0, 2, 0}, {0, 2, 0}, {0, -1, 5}, {1, 0, 0}, {1, 0, 1e-9}};
  const double nan = std::nan("");
  cloud.normals = {{1, 0, 0}, {0, 1, 0}, {nan, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
  cloud.colours = {{10, 20, 30}, {0, 0, 0}, {255, 255, 254}, {7, 8, 9}, {11, 21, 32}, {1, 2, 3}};
  using C = std::array<std::uint8_t, 3>;
  MpegReading all{true};
  all.dropdups = 0;
  EXPECT_THROW(mpeg_points(cloud, "six.ply", all), Error);  // point 2's NaN normal is used now
  all.nan_normals = true;
  const MpegPoints kept = mpeg_points(cloud, "six.ply", all);
  ASSERT_EQ(kept.size(), 6u);  // sorted, equal points in file order
  EXPECT_EQ(kept.colours, (std::vector<C>{{7, 8, 9}, {0, 0, 0}, {255, 255, 254}, {10, 20, 30}, {11, 21, 32}, {1, 2, 3}}));
  EXPECT_EQ(kept.nan_normals, 1u);
  EXPECT_EQ(kept.first_nan_normal, 2u);
  EXPECT_TRUE(std::isnan(kept.normals[2][0]));
  MpegReading first{true};
  first.dropdups = 1;
  const MpegPoints firsts = mpeg_points(cloud, "six.ply", first);  // point 2 is dropped, its normal unused
  EXPECT_EQ(firsts.colours, (std::vector<C>{{7, 8, 9}, {0, 0, 0}, {10, 20, 30}, {1, 2, 3}}));
  using P = std::array<float, 3>;
  EXPECT_EQ(firsts.normals, (std::vector<P>{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}}));
  EXPECT_EQ(firsts.nan_normals, 0u);
  MpegReading counted{true};
  counted.merged_counts = true;
  EXPECT_EQ(mpeg_points(cloud, "six.ply", counted).merged, (std::vector<std::uint32_t>{1, 2, 2, 1}));
  // An infinite normal is refused even where NaN ones are kept.
  cloud.normals[0] = {std::numeric_limits<double>::infinity(), 0, 0};
  all.dropdups = 2;
  EXPECT_THROW(mpeg_points(cloud, "six.ply", all), Error);
}

// The lattice search against every point: the shell is all points at the least squared distance
// (exact: integers), listed up to kListed, or nothing where none is within sqrt(kMaxSquared).
TEST(LatticeNeighbours, ShellIsEveryPointAtTheLeastDistance) {
  using P = std::array<float, 3>;
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(-21, 20);  // bricks either side of 0
  std::set<P> unique;
  while (unique.size() < 3000)
    unique.insert(P{float(coordinate(random)), float(coordinate(random)), float(coordinate(random))});
  for (int k = -4; k <= 4; ++k) unique.insert(P{float(k), 200, 0});  // a row far off: long shells of 2
  // Points at the ends of the range, so that the bricks' x spans all it can (the slabs' tables).
  unique.insert(P{-1048576, 5, 5});
  unique.insert(P{1048576, -5, 5});
  const std::vector<P> points(unique.begin(), unique.end());
  const auto lattice = LatticeNeighbours::build(points);
  ASSERT_TRUE(lattice);
  LatticeNeighbours::Probe probe;
  LatticeNeighbours::Shell shell;
  std::uniform_int_distribution<int> query(-34, 34);
  for (int n = 0; n < 4000; ++n) {
    const P q = n % 10 == 0 ? points[std::size_t(n) % points.size()]
                            : P{float(query(random)), float(query(random) + (n % 7 == 0 ? 196 : 0)),
                                float(query(random))};
    for (const bool skip_zero : {false, true}) {
      double least = INFINITY;
      std::set<std::uint32_t> nearest;
      for (std::uint32_t i = 0; i < points.size(); ++i) {
        double squared = 0;
        for (int c = 0; c < 3; ++c) squared += double(points[i][c] - q[c]) * double(points[i][c] - q[c]);
        if (skip_zero && squared == 0) continue;
        if (squared < least) least = squared, nearest.clear();
        if (squared == least) nearest.insert(i);
      }
      const bool found = lattice->nearest(q, skip_zero, probe, shell);
      ASSERT_EQ(found, least <= LatticeNeighbours::kMaxSquared) << q[0] << " " << q[1] << " " << q[2];
      if (!found) continue;
      ASSERT_EQ(shell.squared, least);
      ASSERT_EQ(shell.count, nearest.size());
      const std::set<std::uint32_t> listed(
          shell.index.begin(), shell.index.begin() + std::min(shell.count, LatticeNeighbours::kListed));
      ASSERT_EQ(listed.size(), std::min(shell.count, LatticeNeighbours::kListed));
      for (const std::uint32_t i : listed) EXPECT_TRUE(nearest.count(i)) << i;
    }
  }
}

TEST(LatticeNeighbours, OnlyVoxelisedCloudsOfDistinctPoints) {
  using P = std::array<float, 3>;
  EXPECT_TRUE(LatticeNeighbours::build({P{0, 0, 0}, P{-1048576, 1048576, 3}}));
  EXPECT_FALSE(LatticeNeighbours::build({P{0, 0, 0}, P{0.5f, 0, 0}}));           // not integral
  EXPECT_FALSE(LatticeNeighbours::build({P{0, 0, 0}, P{2097152, 0, 0}}));        // beyond 2^20
  EXPECT_FALSE(LatticeNeighbours::build({P{1, 2, 3}, P{0, 0, 0}, P{1, 2, 3}}));  // two equal
  EXPECT_FALSE(LatticeNeighbours::build({}));
}

// A voxelised pair goes through the lattice, the same pair moved by half a voxel (every
// difference, so every distance and tie, unchanged in single precision) through the k-d tree:
// the figures agree, up to the order in which a D2 adds its tied points (a few ulps). The pair
// has ties of every size: a shell of 30 points around a point (pc_error's search sees all 30) and
// one of 31 (it sees 30 of them, its tree's choice: there the lattice leaves it the query).
TEST(PcErrorFigures, VoxelisedCloudsGiveTheFiguresOfTheGeneralSearch) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> coordinate(0, 40), channel(0, 255);
  std::normal_distribution<double> gauss;
  PointCloud a, b;
  const auto add = [&](PointCloud& cloud, Vec3 p) {
    cloud.positions.push_back(p);
    cloud.colours.push_back(Colour(float(channel(random)), float(channel(random)), float(channel(random))));
    if (&cloud == &a) cloud.normals.push_back(Vec3(gauss(random), gauss(random), gauss(random)).normalized());
  };
  for (int k = 0; k < 4000; ++k) {
    const Vec3 p(coordinate(random), coordinate(random), coordinate(random) / 8);
    add(a, p);
    add(b, p + Vec3(coordinate(random) % 3 - 1, coordinate(random) % 3 - 1, coordinate(random) % 5 - 2));
  }
  // Shells: squared length 9 has 30 lattice points, 17 has 48 (31 of them taken).
  for (const auto& [centre, squared, taken] :
       {std::tuple{Vec3(100, 0, 0), 9, 30}, std::tuple{Vec3(0, 100, 0), 17, 31}}) {
    add(a, centre);
    int count = 0;
    for (int x = -5; x <= 5; ++x)
      for (int y = -5; y <= 5; ++y)
        for (int z = -5; z <= 5; ++z)
          if (x * x + y * y + z * z == squared && count++ < taken) add(b, centre + Vec3(x, y, z));
  }
  add(b, Vec3(-50, -50, -50));  // beyond the lattice's reach of every point of A
  PointCloud a_moved = a, b_moved = b;
  for (Vec3& p : a_moved.positions) p += Vec3(0.5, 0.5, 0.5);
  for (Vec3& p : b_moved.positions) p += Vec3(0.5, 0.5, 0.5);
  for (const bool mmetric : {false, true}) {
    for (const std::optional<double> resolution : {std::optional<double>(), std::optional<double>(1023)}) {
      MpegRules rules;
      rules.mmetric = mmetric;
      rules.resolution = resolution;
      const MpegFigures on =
          mpeg_point_cloud_figures(mpeg_points(a, "a", MpegReading{true}), mpeg_points(b, "b", MpegReading{false}), rules, "a");
      const MpegFigures off = mpeg_point_cloud_figures(mpeg_points(a_moved, "a", MpegReading{true}),
                                                       mpeg_points(b_moved, "b", MpegReading{false}), rules, "a");
      EXPECT_EQ(on.peak, off.peak);
      for (const auto& [x, y] : {std::pair{on.a_to_b, off.a_to_b}, std::pair{on.b_to_a, off.b_to_a}}) {
        EXPECT_EQ(x.d1_mse, y.d1_mse);
        EXPECT_EQ(x.d1_hausdorff, y.d1_hausdorff);
        EXPECT_NEAR(x.d2_mse, y.d2_mse, 1e-13 * y.d2_mse);
        EXPECT_NEAR(x.d2_hausdorff, y.d2_hausdorff, 1e-13 * y.d2_hausdorff);
        EXPECT_EQ(x.ycbcr_mse, y.ycbcr_mse);
        EXPECT_EQ(x.rgb_mse, y.rgb_mse);
        EXPECT_EQ(x.rgb_hausdorff, y.rgb_hausdorff);
      }
    }
  }
}

// A cloud as another file would hold it: ASCII PLY, binary PLY in double, XYZ with named columns.
void write_as(const PointCloud& cloud, const std::string& path, const std::string& form) {
  const bool normals = !cloud.normals.empty(), colours = !cloud.colours.empty();
  std::ofstream out(path, std::ios::binary);
  if (form == "xyz") {
    out << "# x y z" << (normals ? " nx ny nz" : "") << (colours ? " r g b" : "") << "\n";
  } else {
    out << "ply\nformat " << (form == "ascii" ? "ascii" : "binary_little_endian") << " 1.0\nelement vertex "
        << cloud.positions.size() << "\n";
    const std::string type = form == "ascii" ? "float" : "double";
    for (const char* name : {"x", "y", "z"}) out << "property " << type << " " << name << "\n";
    if (normals) for (const char* name : {"nx", "ny", "nz"}) out << "property " << type << " " << name << "\n";
    if (colours) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    out << "end_header\n";
  }
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    std::vector<double> values(cloud.positions[i].data(), cloud.positions[i].data() + 3);
    if (normals) values.insert(values.end(), cloud.normals[i].data(), cloud.normals[i].data() + 3);
    if (form == "double") {
      out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(double)));
      for (int c = 0; colours && c < 3; ++c) out.put(char(std::uint8_t(cloud.colours[i][c])));
      continue;
    }
    for (const double v : values) out << fmt::format("{} ", v);  // shortest text that reads back the same
    if (colours) out << cloud.colours[i][0] << ' ' << cloud.colours[i][1] << ' ' << cloud.colours[i][2];
    out << "\n";
  }
}

// A binary PLY of floats is read where it lies (read_mpeg_points); every other file through the
// general reader. Holding the same values, they give the same figures to the last bit, on the
// lattice (sphere10) and off it (blob_float); a NaN is named either way.
TEST(PcErrorFigures, EveryFileFormGivesTheFiguresOfTheBinaryOne) {
  const testing::cli::fs::path folder = testing::cli::fs::temp_directory_path() / "roving-mpeg-forms";
  testing::cli::fs::create_directories(folder);
  const auto figures = [](const std::string& a, const std::string& b) {
    const CliRun run = run_cli("measure " + a + " " + b + " --pcc --json -");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    nlohmann::json json = nlohmann::json::parse(run.out)["mpeg_pcc"];
    json.erase("seconds");
    return json;
  };
  for (const std::string pair : {"sphere10", "blob_float"}) {
    const std::string a = kData + pair + "_a.ply", b = kData + pair + "_b.ply";
    const nlohmann::json binary = figures(a, b);
    EXPECT_TRUE(binary["d2"] == true && binary["colour"] == true) << binary.dump();
    for (const std::string form : {"ascii", "double", "xyz"}) {
      SCOPED_TRACE(pair + " as " + form);
      const std::string ext = form == "xyz" ? ".xyz" : ".ply";
      const std::string a_copy = (folder / (pair + "_a_" + form + ext)).string();
      const std::string b_copy = (folder / (pair + "_b_" + form + ext)).string();
      write_as(read_point_cloud(a, false), a_copy, form);
      write_as(read_point_cloud(b, false), b_copy, form);
      nlohmann::json copy = figures(a_copy, b_copy);
      EXPECT_EQ(copy, binary) << copy.dump();
    }
  }
  PointCloud nan_cloud = read_point_cloud(kData + "sphere10_b.ply", false);
  nan_cloud.positions[2].y() = std::nan("");
  for (const std::string form : {"double", "ascii"}) {
    const std::string path = (folder / ("nan_" + form + ".ply")).string();
    write_as(nan_cloud, path, form);
    const std::string name = "nan_" + form + ".ply";
    expect_error("measure " + path + " " + kData + "sphere10_a.ply --pcc", {name.c_str(), " 2 ", "finite"});
  }
  testing::cli::fs::remove_all(folder);
}

// pc_error 0.14.2 reads colour only as uchar (pcc_processing.cpp's checkField(inFile, "red",
// {"uint8", "uchar"})): a cloud whose colours are floats has none for it, and none here, with a
// warning naming the file; the geometry's figures are those of the same clouds without colour.
TEST(PcErrorFigures, FloatColoursGiveNoColourFiguresAsPcErrorGivesNone) {
  testing::cli::Folder folder;
  const auto cloud = [&](const std::string& name, double shift, bool float_colours) {
    std::string text = fmt::format(
        "ply\nformat ascii 1.0\nelement vertex 27\nproperty float x\nproperty float y\nproperty float z\n"
        "property {0} red\nproperty {0} green\nproperty {0} blue\nend_header\n",
        float_colours ? "float" : "uchar");
    for (int i = 0; i < 27; ++i) {
      text += fmt::format("{} {} {} {}\n", i % 3 + shift, i / 3 % 3, i / 9, float_colours ? "0.5 0.25 1" : "128 64 255");
    }
    return folder.file(name, text);
  };
  const std::string a = cloud("a.ply", 0, true), b = cloud("b.ply", 0.25, true), plain = cloud("plain.ply", 0.25, false);
  const CliRun run = run_cli("measure " + a + " " + b + " --pcc --pcc-resolution 2 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_FALSE(report["mpeg_pcc"]["colour"].get<bool>());
  EXPECT_FALSE(report["mpeg_pcc"]["symmetric"].contains("y_psnr"));
  for (const std::string& file : {a, b}) {
    EXPECT_NE(run.err.find("colour: " + file + " stores its colours as floats; pc_error reads colour only as uchar"),
              std::string::npos) << run.err;
  }
  // One float-coloured, one uchar-coloured: only the uchar one has colour, and no colour figures.
  const CliRun mixed = run_cli("measure " + a + " " + plain + " --pcc --pcc-resolution 2 --json -");
  ASSERT_EQ(mixed.exit_code, 0) << mixed.err;
  EXPECT_FALSE(nlohmann::json::parse(mixed.out)["mpeg_pcc"]["colour"].get<bool>());
  EXPECT_EQ(nlohmann::json::parse(mixed.out)["mpeg_pcc"]["symmetric"]["d1_psnr"], report["mpeg_pcc"]["symmetric"]["d1_psnr"]);
}

TEST(PcErrorFigures, BadInputIsOneLine) {
  const std::string a = kData + "sphere10_a.ply", b = kData + "sphere10_b.ply";
  // 1e-300 and 1e-46 are positive doubles that single precision (pc_error's) rounds to 0.
  for (const char* peak : {"-1", "nan", "1e40", "1e-300", "1e-46", "1e-39"}) {
    SCOPED_TRACE(peak);
    const CliRun run = run_cli("measure " + a + " " + b + " --pcc --pcc-resolution " + peak);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("--pcc-resolution"), std::string::npos) << run.err;
  }
  // 0 is pc_error's "no resolution given" (-r 0): the default peak, every figure as without it.
  const CliRun zero = run_cli("measure " + a + " " + b + " --pcc --pcc-resolution 0 --json -");
  const CliRun none = run_cli("measure " + a + " " + b + " --pcc --json -");
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  EXPECT_EQ(nlohmann::json::parse(zero.out)["mpeg_pcc"]["symmetric"], nlohmann::json::parse(none.out)["mpeg_pcc"]["symmetric"]);
  EXPECT_EQ(nlohmann::json::parse(zero.out)["mpeg_pcc"]["peak_from"], nlohmann::json::parse(none.out)["mpeg_pcc"]["peak_from"]);
  const CliRun ibsm = run_cli("measure " + a + " " + b + " --pcc --ibsm");
  EXPECT_EQ(ibsm.exit_code, 2);
  EXPECT_NE(ibsm.err.find("--ibsm: not with --pcc"), std::string::npos) << ibsm.err;
  const CliRun first_hit = run_cli("measure " + a + " " + b + " --pcc --semantics first-hit");
  EXPECT_EQ(first_hit.exit_code, 2);
  EXPECT_NE(first_hit.err.find("closest-point"), std::string::npos) << first_hit.err;
  // Bezier patches are neither a point cloud nor a mesh.
  expect_error("measure " + roving::testing::data_file("teapot.bpt") + " " + b + " --pcc",
               {"teapot.bpt", "point clouds and meshes"});

  const testing::cli::fs::path folder = testing::cli::fs::temp_directory_path() / "roving-mpeg-test";
  testing::cli::fs::create_directories(folder);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(folder / name) << text;
    return (folder / name).string();
  };
  // A NaN coordinate, named with its file.
  const std::string nan_cloud = write("nan.xyz", "0 0 0\n1 0 0\nnan 1 0\n0 0 1\n");
  expect_error("measure " + nan_cloud + " " + b + " --pcc", {"nan.xyz", "point 2", "non-finite"});
  // One point: no spacing to take as the peak unless one is given.
  const std::string one = write("one.xyz", "1 2 3\n");
  const std::string plain = kData + "torus11_b.ply";
  expect_error("measure " + one + " " + plain + " --pcc", {"one.xyz", "--pcc-resolution"});
  EXPECT_EQ(run_cli("measure " + one + " " + plain + " --pcc --pcc-resolution 1023").exit_code, 0);
  // --pcc-normals: a file without normals, of other points, of as many other points; a mesh's.
  const std::string normals = " --pcc --pcc-normals ";
  expect_error("measure " + a + " " + b + normals + b, {"sphere10_b.ply", "no normals", "expected A's points"});
  expect_error("measure " + a + " " + b + normals + kData + "torus11_a.ply",
               {"torus11_a.ply", "7", "points at distinct positions", "expected A's 6649"});
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n";
  const std::string two = write("two.ply", ply + "0 0 0 0 0 1\n1 0 0 0 0 1\n");
  const std::string other = write("other.ply", ply + "0 0 0 0 0 1\n2 0 0 0 0 1\n");
  const std::string fewer = write("fewer.ply", ply + "0 0 0 0 0 1\n0 0 0 0 0 1\n");
  expect_error("measure " + two + " " + plain + normals + other, {"other.ply", "(2, 0, 0) that A has not"});
  expect_error("measure " + two + " " + plain + normals + fewer, {"fewer.ply", "1 points", "(2 read)", "A's 2"});
  expect_error("measure " + kData + "fandisk10_a.ply " + kData + "fandisk10_b.ply" + normals + two,
               {"--pcc-normals", "fandisk10_a.ply is a mesh"});
  expect_error("measure " + kData + "fandisk10_a.ply " + kData + "fandisk10_b.ply --pcc-normals " + two,
               {"--pcc-normals", "two point clouds"});
  // A folder for the normals file: named as a folder, before anything is read.
  expect_error("measure " + a + " " + b + normals + folder.string(), {"--pcc-normals", "directory", "roving-mpeg-test"});
  // pc_error's options where they do not apply, and out of range.
  const std::string meshes = "measure " + kData + "fandisk10_a.ply " + kData + "fandisk10_b.ply --pcc";
  expect_error(meshes + " --pcc-average-normals 0", {"--pcc-average-normals", "two point clouds", "mmetric"});
  expect_error(meshes + " --pcc-mse-space 8", {"--pcc-mse-space", "two point clouds", "mmetric"});
  expect_error("measure " + kData + "fandisk10_a.ply " + kData + "fandisk10_b.ply --pcc-dropdups 1",
               {"--pcc-dropdups", "MPEG's figures", "--pcc"});
  expect_error("measure " + a + " " + b + " --pcc --pcc-normal-calc-modification false",
               {"--pcc-normal-calc-modification", "mmetric's option", "points and points"});
  expect_error("measure " + a + " " + b + " --pcc --pcc-neighbors-proc 5", {"--pcc-neighbors-proc", "5"});
  expect_error("measure " + a + " " + b + " --pcc --pcc-mse-space 2", {"--pcc-mse-space", "2"});
  expect_error("measure " + a + " " + b + " --pcc --pcc-dropdups -1", {"--pcc-dropdups", "-1"});
  testing::cli::fs::remove_all(folder);
}

}  // namespace
}  // namespace roving
