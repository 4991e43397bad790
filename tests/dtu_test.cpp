// The DTU protocol (--protocol dtu, roving/reconstruction/dtu_protocol.h) against DTUeval-python's
// own figures: tests/data/dtu/golden/ holds eval.py's printed line (accuracy, completeness,
// overall) on the scene of tests/data/dtu/make_dataset.py, recorded by record_dtu.sh with Debian
// 12's Open3D 0.16.1, scikit-learn 1.2.1 and SciPy 1.10.1; each file is headed by its command.
// Without the script's shuffle the protocol is deterministic, and the figures agree but for the
// order of summation (NumPy sums pairwise, we in order): relative 1e-10 covers that for 10^4 terms
// of one sign (n eps = 2e-12). With the shuffle, ours is seeded and NumPy's generator is not ours:
// the mean over 20 seeds agrees with the script's mean over its 20 within 3 standard errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "cli_support.h"
#include "sample_rows.h"
#include "roving/formats/images_and_matlab/matlab_file.h"
#include "roving/reconstruction/dtu_protocol.h"
#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/reconstruction/greedy_thinning.h"

namespace roving {
namespace {

using testing::cli::CliRun;
using testing::cli::expect_error;
using testing::cli::run_cli;

const std::string kData = std::string(ROVING_SOURCE_DIR) + "/tests/data/dtu/";
const std::string kTruth = kData + "Points/stl/stl001_total.ply";
const std::string kMask = kData + "ObsMask/ObsMask1_10.mat";
const std::string kPlane = kData + "ObsMask/Plane1.mat";
const char* kFigures[] = {"accuracy", "completeness", "overall"};

// Each golden line's numbers after its first `skip` fields; comment lines apart.
std::vector<std::vector<double>> golden_rows(const std::string& name, int skip = 0) {
  std::ifstream in(kData + "golden/" + name);
  EXPECT_TRUE(in) << name;
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    double value = 0;
    for (int i = 0; fields >> value; ++i)
      if (i >= skip) row.push_back(value);
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json protocol(const std::string& test, const std::string& options) {
  const CliRun run = run_cli("measure " + kTruth + " " + kData + test + " --protocol dtu --dtu-obs-mask " + kMask +
                             " --dtu-plane " + kPlane + " --json - --quiet " + options);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return nlohmann::json::parse(run.out.substr(run.out.find('{')));
}

void expect_in_order(const std::string& test, const std::string& golden) {
  const std::vector<double> expected = golden_rows(golden).at(0);
  const nlohmann::json d = protocol(test, "--protocol-seed none")["dtu_protocol"];
  ASSERT_EQ(d["runs"].size(), 1u);
  EXPECT_TRUE(d["seed"].is_null());
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d[kFigures[i]].get<double>(), expected[i], 1e-10 * expected[i]) << test << " " << kFigures[i];
  }
}

TEST(DtuGolden, MeshInItsOwnOrderIsTheScripts) { expect_in_order("scan1_mesh.ply", "mesh_in_order.txt"); }

TEST(DtuGolden, PointsInTheirOwnOrderAreTheScripts) { expect_in_order("scan1_points.ply", "points_in_order.txt"); }

void expect_within_spread(const std::string& test, const std::string& golden) {
  const std::vector<std::vector<double>> theirs = golden_rows(golden, 1);
  ASSERT_EQ(theirs.size(), 20u);
  const nlohmann::json d = protocol(test, "--protocol-seed 1 --protocol-runs 20")["dtu_protocol"];
  ASSERT_EQ(d["runs"].size(), 20u);
  for (int i = 0; i < 3; ++i) {
    double mean = 0, sd = 0;
    for (const auto& row : theirs) mean += row[i] / theirs.size();
    for (const auto& row : theirs) sd += (row[i] - mean) * (row[i] - mean);
    sd = std::sqrt(sd / (theirs.size() - 1));
    const nlohmann::json& ours = d["spread"][kFigures[i]];
    const double error = std::sqrt(sd * sd / 20 + ours["sd"].get<double>() * ours["sd"].get<double>() / 20);
    EXPECT_NEAR(ours["mean"].get<double>(), mean, 3 * error) << test << " " << kFigures[i];
    EXPECT_GT(ours["sd"].get<double>(), 0) << "runs of different seeds should differ";
    EXPECT_EQ(d[kFigures[i]], d["runs"][0][kFigures[i]]);  // the first run is the one reported
  }
}

TEST(DtuGolden, MeshShuffledWithinTheScriptsSeedSpread) { expect_within_spread("scan1_mesh.ply", "mesh_seeds.txt"); }

TEST(DtuGolden, PointsShuffledWithinTheScriptsSeedSpread) {
  expect_within_spread("scan1_points.ply", "points_seeds.txt");
}

// The text report's header names the DTU evaluation (it is written before the figures exist,
// and once named Tanks and Temples' for every protocol run).
TEST(DtuProtocol, TheTextHeaderNamesTheDtuEvaluation) {
  const CliRun run = run_cli("measure " + kTruth + " " + kData + "scan1_mesh.ply --protocol dtu --dtu-obs-mask " +
                             kMask + " --dtu-plane " + kPlane + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("the DTU benchmark's own evaluation"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("Tanks and Temples"), std::string::npos) << run.out;
}

TEST(DtuProtocol, ASeedGivesTheSameFiguresEveryRun) {
  const nlohmann::json a = protocol("scan1_mesh.ply", "--protocol-seed 7 --protocol-runs 2")["dtu_protocol"];
  const nlohmann::json b = protocol("scan1_mesh.ply", "--protocol-seed 7 --protocol-runs 2")["dtu_protocol"];
  EXPECT_EQ(a["runs"], b["runs"]);
  EXPECT_EQ(a["runs"][0]["seed"], 7);
  EXPECT_EQ(a["runs"][1]["seed"], 8);
}

TEST(DtuProtocol, CountsFollowTheScene) {
  const nlohmann::json d = protocol("scan1_mesh.ply", "--protocol-seed none")["dtu_protocol"];
  // 20,000 sphere points, the table below the plane and the 125 far points above it.
  EXPECT_EQ(d["ground_truth_points"], 23374);
  EXPECT_EQ(d["ground_truth_above"], 20125);
  const nlohmann::json& run = d["runs"][0];
  EXPECT_EQ(run["completeness_counted"], 20000);  // the far cluster is beyond max_dist of all
  EXPECT_LT(run["observed"].get<int>(), run["in_box"].get<int>());  // x >= 8 is not observed
  EXPECT_LT(run["accuracy_counted"].get<int>(), run["observed"].get<int>());  // the far square
  EXPECT_EQ(d["reconstruction_points"].get<int>(), 3159 + d["samples"].get<int>());  // every vertex, then samples
}

TEST(DtuProtocol, TheGridOriginIsTheBoxInSinglePrecision) {
  // eval.py rounds BB to float32 before (p - BB) / Res. On this point (found on a 10^7-point scene)
  // BB in double puts it in voxel 102 along x, BB in single precision in 101: only 101 is observed.
  DtuObservationMask mask;
  mask.dims = {129, 129, 129};
  mask.observed.assign(129 * 129 * 129, 0);
  mask.observed[101 + 129 * (96 + 129 * 33)] = 1;
  mask.box_min = Vec3::Constant(-196.25365277680484);
  mask.box_max = Vec3::Constant(196.25365277680484);
  mask.resolution = 3.0664633246375756;
  const Vec3 p(114.9923770904541, 98.352924060821536, -94.251779079437256);
  DtuOptions options;
  options.first_seed.reset();
  const DtuFigures f = dtu_figures({p}, {p + Vec3(0.5, 0, 0)}, mask, {0, 0, 0, 1}, options);
  EXPECT_EQ(f.runs[0].observed, 1u);
  EXPECT_DOUBLE_EQ(f.runs[0].accuracy, 0.5);
  EXPECT_DOUBLE_EQ(f.runs[0].completeness, 0.5);
}

TEST(DtuProtocol, ThinningIsTheSequentialGreedyOne) {
  // greedy_thinning decides in rounds over the points in spatial order; it must keep exactly what
  // visiting them one by one keeps, in their own order and shuffled. The points are dense enough
  // that most have several neighbours, with duplicates and a pair exactly `density` apart, and far
  // from the origin as DTU's scenes are, so that cell coordinates are rounded (one point of a
  // 10^6-point scene once fell a cell short of the grid's margin).
  std::vector<Vec3> points;
  std::uint64_t state = 12345;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 11;
  };
  const auto uniform = [&] { return double(next()) / double(1ull << 53); };
  const Vec3 offset(-56.514225006103516, 4.0419769287109375, -156.51042557);
  for (int i = 0; i < 4000; ++i) points.push_back(offset + Vec3(2 * uniform(), 2 * uniform(), 2 * uniform()));
  for (int i = 0; i < 50; ++i) points.push_back(points[i * 7]);
  points.push_back(offset + Vec3(3, 3, 3));
  points.push_back(offset + Vec3(3.2, 3, 3));
  const double r = 0.2;
  std::vector<std::uint32_t> own(points.size()), shuffled(points.size());
  std::iota(own.begin(), own.end(), 0u);
  std::vector<std::uint32_t> order = own;
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[next() % i]);
  for (std::size_t k = 0; k < order.size(); ++k) shuffled[order[k]] = static_cast<std::uint32_t>(k);
  for (const auto& rank : {own, shuffled}) {
    std::vector<std::uint32_t> visiting(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) visiting[rank[i]] = static_cast<std::uint32_t>(i);
    std::vector<std::uint8_t> expected(points.size(), 0);
    std::vector<Vec3> kept;
    for (const std::uint32_t i : visiting) {
      const Vec3& p = points[i];
      const bool near = std::any_of(kept.begin(), kept.end(), [&](const Vec3& q) {
        const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        return dx * dx + dy * dy + dz * dz <= r * r;
      });
      if (!near) kept.push_back(p), expected[i] = 1;
    }
    EXPECT_EQ(greedy_thinning(points, rank, r), expected);
    EXPECT_LT(kept.size(), points.size() / 2);  // the case is dense: most points are dropped
  }
}

TEST(DtuProtocol, BesideTheExactFiguresWithSymmetric) {
  const nlohmann::json report = protocol("scan1_mesh.ply", "--protocol-runs 1 --symmetric");
  EXPECT_TRUE(report.contains("reconstruction"));
  EXPECT_TRUE(report.contains("dtu_protocol"));
  EXPECT_EQ(report["dtu_protocol"]["runs"].size(), 1u);
}

// With --symmetric, the exact figures where the protocol measures are the plain area-weighted means
// over the samples in its region (TEST's observed, REF's above the plane), every distance and below
// max_dist, checked here from the samples' own file with the mask and plane read from theirs.
TEST(DtuProtocol, ExactFiguresAreTheMeansOverItsRegion) {
  const std::string csv = ::testing::TempDir() + "dtu_exact_samples.csv";
  const nlohmann::json d =
      protocol("scan1_mesh.ply", "--protocol-runs 1 --symmetric --samples-out " + csv)["dtu_protocol"];
  const nlohmann::json& exact = d["exact_within_region"];
  ASSERT_TRUE(exact.is_object()) << d.dump();
  DtuObservationMask mask;
  const MatlabArray<std::uint8_t> observed = read_matlab_mask(kMask, "ObsMask");
  for (int a = 0; a < 3; ++a) mask.dims[a] = observed.dims.at(a);
  mask.observed = observed.values;
  const MatlabArray<double> box = read_matlab_numbers(kMask, "BB");
  for (int a = 0; a < 3; ++a) mask.box_min[a] = box.values[2 * a], mask.box_max[a] = box.values[2 * a + 1];
  mask.resolution = read_matlab_numbers(kMask, "Res").values.at(0);
  const MatlabArray<double> p = read_matlab_numbers(kPlane, "P");
  const DtuRegion region(mask, {p.values[0], p.values[1], p.values[2], p.values[3]}, d["patch"].get<double>());
  const double cap = d["max_dist"].get<double>();

  const std::vector<SampleRow> test = sample_rows(csv, "B -> A"), reference = sample_rows(csv, "A -> B");
  const auto observed_by = [&](const SampleRow& r) { return region.observed(r.position); };
  const auto above = [&](const SampleRow& r) { return region.above(r.position); };
  const std::size_t test_counted = std::count_if(test.begin(), test.end(), observed_by);
  const std::size_t reference_counted = std::count_if(reference.begin(), reference.end(), above);
  EXPECT_EQ(exact["test_samples"].get<std::size_t>(), test.size());
  EXPECT_EQ(exact["reference_samples"].get<std::size_t>(), reference.size());
  EXPECT_EQ(exact["test_samples_counted"].get<std::size_t>(), test_counted);
  EXPECT_EQ(exact["reference_samples_counted"].get<std::size_t>(), reference_counted);
  // The scene leaves samples out both ways: TEST's beyond x = 8 and its far square, REF's table.
  EXPECT_GT(test_counted, test.size() / 2);
  EXPECT_LT(test_counted, test.size());
  EXPECT_LT(reference_counted, reference.size());

  // The CSV prints 17 significant digits: the sums agree but for their order (relative 1e-12).
  const auto expect_mean = [](const nlohmann::json& figures, const char* figure, std::pair<double, std::size_t> mean) {
    const nlohmann::json& direction = figures[figure];
    EXPECT_NEAR(direction["mean"].get<double>(), mean.first, 1e-12 * mean.first) << figure;
    EXPECT_EQ(direction["hits"].get<std::size_t>(), mean.second) << figure;
  };
  expect_mean(exact["figures"], "accuracy", region_mean(test, observed_by));
  expect_mean(exact["figures"], "completeness", region_mean(reference, above));
  const auto below = [&](auto&& inside) { return [&, inside](const SampleRow& r) { return inside(r) && r.distance < cap; }; };
  expect_mean(exact["figures_below_max_dist"], "accuracy", region_mean(test, below(observed_by)));
  expect_mean(exact["figures_below_max_dist"], "completeness", region_mean(reference, below(above)));
  // Every REF point above the plane has a distance below the cap but the far cluster's: as the script counts.
  EXPECT_EQ(exact["figures_below_max_dist"]["completeness"]["hits"].get<std::size_t>(),
            d["runs"][0]["completeness_counted"].get<std::size_t>());
}

// A region of every sample changes no figure; without --symmetric there are no exact figures.
TEST(DtuProtocol, ARegionOfEverySampleIsNoRegion) {
  const std::vector<double> d = {0.5, -1.5, 2.0, 0.25, 4.0}, weights = {1, 2, 1, 3, 1}, agreement = {1, 0.5, 1, 1, 0};
  const std::vector<std::uint8_t> hit = {1, 1, 1, 1, 0}, every(5, 1), first_three = {1, 1, 1, 0, 0};
  const ReconstructionFigures plain =
      reconstruction_figures({&d, &hit, &weights, &agreement}, {&d, &hit, &weights, &agreement}, {1.0}, true);
  const ReconstructionFigures all = reconstruction_figures({&d, &hit, &weights, &agreement, &every},
                                                           {&d, &hit, &weights, &agreement, &every}, {1.0}, true);
  EXPECT_EQ(plain.accuracy.mean.value, all.accuracy.mean.value);
  EXPECT_EQ(plain.accuracy.mean.upper, all.accuracy.mean.upper);
  EXPECT_EQ(plain.recall, all.recall);
  EXPECT_EQ(plain.normal_consistency, all.normal_consistency);
  // The first three samples: mean (0.5 + 2 * 1.5 + 2) / 4, two of four units of area within 1.
  const ReconstructionFigures part = reconstruction_figures({&d, &hit, &weights, &agreement, &first_three},
                                                            {&d, &hit, &weights, &agreement, &first_three}, {1.0}, true);
  EXPECT_DOUBLE_EQ(part.accuracy.mean.value, 5.5 / 4);
  EXPECT_DOUBLE_EQ(part.precision[0], 0.25);
  EXPECT_EQ(part.accuracy.hits + part.accuracy.no_hits, 3u);
  EXPECT_TRUE(protocol("scan1_mesh.ply", "--protocol-runs 1")["dtu_protocol"]["exact_within_region"].is_null());
}

TEST(DtuProtocol, BadInputGetsOneLine) {
  const std::string pair = kTruth + " " + kData + "scan1_mesh.ply";
  const std::string files = " --dtu-obs-mask " + kMask + " --dtu-plane " + kPlane;
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + kMask, {"--dtu-plane", "Plane<scan>"});
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask missing.mat --dtu-plane " + kPlane,
               {"--dtu-obs-mask", "missing.mat"});
  expect_error("measure " + pair + " --protocol eth3d" + files, {"--protocol"});
  // A folder opens as a file on Linux and fails at the first read: named before it is read.
  const std::string folder = std::filesystem::temp_directory_path().string();
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + kMask + " --dtu-plane " + folder,
               {"--dtu-plane", "directory", folder.c_str()});
  expect_error("measure " + pair + " --dtu-obs-mask " + kMask, {"--dtu-obs-mask", "only with --protocol dtu"});
  expect_error("measure " + pair + " --protocol dtu --pcc" + files, {"--protocol", "--pcc"});
  expect_error("measure " + pair + " --protocol dtu --dtu-density 0" + files, {"--dtu-density", "found 0"});
  expect_error("measure " + pair + " --protocol dtu --dtu-max-dist nan" + files, {"--dtu-max-dist"});
  expect_error("measure " + pair + " --protocol dtu --protocol-seed x1" + files, {"--protocol-seed", "x1"});
  expect_error("measure " + pair + " --protocol dtu --protocol-runs 0" + files, {"--protocol-runs"});
  expect_error("measure " + pair + " --protocol dtu --html out.html" + files, {"--html", "--symmetric"});
  // A mesh in other units than the density's: refused before any point is made.
  expect_error("measure " + pair + " --protocol dtu --dtu-density 1e-7" + files, {"scan1_mesh.ply", "millimetres"});
  // The data set's files: the wrong file, a file that is no .mat, a truncated one.
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + kPlane + " --dtu-plane " + kPlane,
               {"Plane1.mat", "no variable 'ObsMask'"});
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + kMask + " --dtu-plane " + kMask,
               {"ObsMask1_10.mat", "no variable 'P'"});
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + kTruth + " --dtu-plane " + kPlane,
               {"stl001_total.ply", "MATLAB"});
  const std::filesystem::path cut = std::filesystem::temp_directory_path() / "roving-dtu-truncated.mat";
  {
    std::ifstream in(kMask, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + cut.string() + " --dtu-plane " + kPlane,
               {"roving-dtu-truncated.mat"});
  std::filesystem::remove(cut);
  // Files libmatio is not given: MATLAB 4 (a real one, scipy's format='4', and the 520 bytes on
  // which matio's MATLAB 4 reader hung clearing a buffer, found by fuzz_mat), 7.3 (HDF5), and a
  // level 5 file whose dimensions tag declares 5.8 GB, which matio allocated, one whose cell
  // array declares 10^13 elements, for which it allocated too, and one whose 17-byte array flags
  // hid a dimensions tag of 3.2 GB from the walk over the elements (all found by fuzz_mat).
  for (const auto& [file, message] : {std::pair{"plane-v4.mat", "not a MATLAB level 5 .mat file"},
                                      {"matio-v4-timeout.mat", "not a MATLAB level 5 .mat file"},
                                      {"v7.3-header.mat", "version 0x0200 (7.3, HDF5)"},
                                      {"matio-dims-5.8GB.mat", "dimensions declare 2913402892 bytes; 64 remain"},
                                      {"matio-cell-1e13.mat", "a matrix declares more than 533196 elements"},
                                      {"matio-flags-dims-6.4GB.mat", "dimensions declare 3227516929 bytes; 64 remain"}}) {
    const std::string path = kData + "bad/" + file;
    expect_error("measure " + pair + " --protocol dtu --dtu-obs-mask " + path + " --dtu-plane " + kPlane,
                 {file, message});
  }
  // A model the protocol does not take.
  expect_error("measure " + kTruth + " " + roving::testing::data_file("teapot.bpt") + " --protocol dtu" + files,
               {"teapot.bpt", "mesh or a point cloud"});
}

}  // namespace
}  // namespace roving
