// The Tanks and Temples protocol (--protocol tanks-and-temples, roving/reconstruction/
// tanks_and_temples_protocol.h) against the toolbox's own figures: tests/data/tnt/golden/ holds
// what EvaluateHisto returned (precision, recall, F, the curves' edges and both cumulative
// curves, each value repr'd) and the point counts after Open3D's crop and down-sampling, on the
// scene of tests/data/tnt/make_dataset.py, recorded by record_tnt.sh with Debian 12's Open3D
// 0.16.1 and NumPy 1.24.2; each file is headed by its command. registration.txt holds what run.py's
// registration (RANSAC on the cameras, three rounds of ICP) returned, seed by seed. Every step is deterministic and
// follows the same arithmetic in the same order, so the figures are compared for equality: a
// count off by one point moves precision by 5e-5, far above any rounding.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "cli_support.h"
#include "roving/core/error.h"
#include "roving/formats/outputs/distance_cloud_writer.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/formats/files/file_hash.h"
#include "roving/protocols/tanks_and_temples_evaluation.h"
#include "roving/reconstruction/correspondence_ransac.h"
#include "roving/reconstruction/crop_volume.h"
#include "roving/core/geometry.h"
#include "roving/reconstruction/point_registration.h"
#include "roving/reconstruction/spatial_order.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"
#include "roving/reconstruction/voxel_down_sample.h"
#include "sample_rows.h"

namespace roving {
namespace {

using testing::cli::CliRun;
using testing::cli::expect_error;
using testing::cli::run_cli;

const std::string kData = std::string(ROVING_SOURCE_DIR) + "/tests/data/tnt/";
const std::string kTruth = kData + "Bench.ply";
const std::string kScene = " --tnt-crop " + kData + "Bench.json --tnt-alignment " + kData + "Bench_trans.txt";

// The golden file's rows of numbers, comment lines apart.
std::vector<std::vector<double>> golden_rows(const std::string& name) {
  std::ifstream in(kData + "golden/" + name);
  EXPECT_TRUE(in) << name;
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    for (double value = 0; fields >> value;) row.push_back(value);
    rows.push_back(row);
  }
  return rows;
}

nlohmann::json protocol(const std::string& test, const std::string& options) {
  const CliRun run = run_cli("measure " + kTruth + " " + kData + test + " --protocol tanks-and-temples" + kScene +
                             " --json - --quiet " + options);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return nlohmann::json::parse(run.out.substr(run.out.find('{')));
}

void expect_the_toolboxs(const std::string& test, const std::string& golden) {
  const std::vector<std::vector<double>> rows = golden_rows(golden);
  ASSERT_EQ(rows.size(), 5u);
  const nlohmann::json t = protocol(test, "--tnt-tau 0.01")["tanks_and_temples_protocol"];
  EXPECT_EQ(t["precision"].get<double>(), rows[0].at(0));
  EXPECT_EQ(t["recall"].get<double>(), rows[0].at(1));
  EXPECT_EQ(t["fscore"].get<double>(), rows[0].at(2));
  EXPECT_EQ(t["reconstruction_cropped"].get<double>(), rows[1].at(0));
  EXPECT_EQ(t["reconstruction_thinned"].get<double>(), rows[1].at(1));
  EXPECT_EQ(t["ground_truth_cropped"].get<double>(), rows[1].at(2));
  EXPECT_EQ(t["ground_truth_thinned"].get<double>(), rows[1].at(3));
  EXPECT_EQ(t["edges"].get<std::vector<double>>(), rows[2]);
  EXPECT_EQ(t["cumulative_precision"].get<std::vector<double>>(), rows[3]);
  EXPECT_EQ(t["cumulative_recall"].get<std::vector<double>>(), rows[4]);
  // The scene leaves something out at every step: the crop, the down-sampling, tau both ways.
  EXPECT_LT(rows[1][0], t["reconstruction_points"].get<double>());
  EXPECT_LT(rows[1][1], rows[1][0]);
  EXPECT_LT(rows[1][3], rows[1][2]);
  EXPECT_LT(rows[0][0], 1.0);
  EXPECT_LT(rows[0][1], 0.9);
}

TEST(TanksAndTemplesGolden, PointsAreTheToolboxs) { expect_the_toolboxs("Bench_points.ply", "points.txt"); }

// A mesh is read as its vertices (Open3D's read_point_cloud): the same figures as the cloud of them.
TEST(TanksAndTemplesGolden, MeshVerticesAreTheToolboxs) { expect_the_toolboxs("Bench_mesh.ply", "mesh.txt"); }

// A binary PLY mesh is read as its vertices alone (the toolbox's read_point_cloud reads no face):
// the report says so, and its vertices are checked as the whole mesh's reader checks them.
TEST(TanksAndTemplesProtocol, AMeshIsReadAsItsVertices) {
  const CliRun run = run_cli("measure " + kTruth + " " + kData + "Bench_mesh.ply --protocol tanks-and-temples" +
                             kScene + " --tnt-tau 0.01");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("Bench_mesh.ply: mesh, read as its 24820 vertices"), std::string::npos) << run.out;
  // A vertex of NaN: one line naming the file and the vertex.
  std::ifstream in(kData + "Bench_mesh.ply", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t body = bytes.find("end_header\n") + 11;
  const float nan = std::nanf("");
  std::memcpy(&bytes[body + 7 * 12 + 4], &nan, sizeof nan);  // vertex 7's y
  const std::string bad = (std::filesystem::temp_directory_path() / "roving-tnt-nan-vertex.ply").string();
  std::ofstream(bad, std::ios::binary) << bytes;
  expect_error("measure " + kTruth + " " + bad + " --protocol tanks-and-temples" + kScene + " --tnt-tau 0.01",
               {"roving-tnt-nan-vertex.ply", "vertex 7", "non-finite"});
  std::filesystem::remove(bad);
}

// run.py's registration (--tnt-trajectory) against run.py's own, seed by seed: its RANSAC draws are
// Open3D's on one thread from utility.random.seed, so the cameras' alignment is the toolbox's; each
// ICP round's count of pairs (fitness) is equal, and its RMSE and alignment agree to 1e-12: the
// pairs are summed in the order of the thinned points (Morton's here, Open3D's hash map's there)
// and the alignments multiplied by Eigen here and by NumPy there, which moves the last bits only.
// The figures after it are then the toolbox's, equal.
const std::string kRegistration = " --tnt-trajectory " + kData + "Bench_moved.log --tnt-reference-trajectory " +
                                  kData + "Bench_COLMAP_SfM.log --tnt-mapping " + kData +
                                  "Bench_mapping_reference.txt";

void expect_matrix_near(const nlohmann::json& matrix, const std::vector<double>& row_by_row, std::size_t from,
                        double tolerance) {
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_NEAR(matrix[k / 4][k % 4].get<double>(), row_by_row.at(from + k), tolerance) << k;
  }
}

TEST(TanksAndTemplesGolden, RegistrationIsRunPys) {
  const std::vector<std::vector<double>> rows = golden_rows("registration.txt");
  ASSERT_EQ(rows.size(), 5u * 6u);
  const nlohmann::json t =
      protocol("Bench_moved_points.ply", "--tnt-tau 0.01 --protocol-seed 1 --protocol-runs 5" + kRegistration)
          ["tanks_and_temples_protocol"];
  const nlohmann::json& runs = t["registration"]["runs"];
  ASSERT_EQ(runs.size(), 5u);
  EXPECT_EQ(t["registration"]["cameras"], 60);
  for (std::size_t k = 0; k < 5; ++k) {
    const nlohmann::json& run = runs[k];
    const std::vector<double>* golden = &rows[6 * k];
    EXPECT_EQ(run["seed"].get<double>(), golden[0].at(0));
    expect_matrix_near(run["cameras"]["transformation"], golden[1], 0, 0);  // bit for bit
    EXPECT_EQ(run["cameras"]["fitness"], 0.95);  // the three outlying cameras left out
    for (std::size_t r = 0; r < 3; ++r) {
      const nlohmann::json& round = run["rounds"][r];
      EXPECT_EQ(round["fitness"].get<double>(), golden[2 + r].at(0)) << k << " " << r;
      EXPECT_NEAR(round["inlier_rmse"].get<double>(), golden[2 + r].at(1), 1e-12 * golden[2 + r].at(1));
      expect_matrix_near(round["transformation"], golden[2 + r], 2, 1e-12);
    }
    expect_matrix_near(run["transformation"], golden[4], 2, 1e-12);
    EXPECT_EQ(run["precision"].get<double>(), golden[5].at(0)) << k;
    EXPECT_EQ(run["recall"].get<double>(), golden[5].at(1)) << k;
    EXPECT_EQ(run["fscore"].get<double>(), golden[5].at(2)) << k;
  }
  // Every run's figures differ: the first is the one reported (its own scoring and the report's
  // agree); the spread is over the five.
  EXPECT_EQ(t["precision"], runs[0]["precision"]);
  EXPECT_EQ(t["fscore"], runs[0]["fscore"]);
  EXPECT_EQ(t["alignment"], runs[0]["transformation"]);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(runs[k]["reported"], k == 0) << k;
  EXPECT_LT(t["registration"]["spread"]["fscore"]["min"].get<double>(),
            t["registration"]["spread"]["fscore"]["max"].get<double>());
}

// The run reported is the one whose figures the most runs give, the earliest of them; where every
// run differs, the first.
TEST(TanksAndTemplesProtocol, TheReportedRunIsTheModalOne) {
  const auto runs_of = [](std::vector<double> fscores) {
    std::vector<TanksAndTemplesRegistrationRun> runs(fscores.size());
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].precision = runs[k].recall = runs[k].fscore = fscores[k];
    return runs;
  };
  EXPECT_EQ(modal_run(runs_of({0.5})), 0u);
  EXPECT_EQ(modal_run(runs_of({0.74336041, 0.74336030, 0.74336030, 0.74336030, 0.74336030})), 1u);
  EXPECT_EQ(modal_run(runs_of({0.1, 0.2, 0.3})), 0u);
  EXPECT_EQ(modal_run(runs_of({0.1, 0.2, 0.2, 0.1})), 0u);  // a tie: the earliest
  EXPECT_EQ(modal_run(runs_of({0.3, 0.2, 0.1, 0.1, 0.2})), 1u);
  // Equal F from other precision and recall is another result.
  std::vector<TanksAndTemplesRegistrationRun> runs = runs_of({0.5, 0.5, 0.5});
  runs[0].precision = runs[1].precision = 0.4;
  runs[0].recall = runs[1].recall = 0.6;
  EXPECT_EQ(modal_run(runs), 0u);
  runs[1].recall = 0.61;
  EXPECT_EQ(modal_run(runs), 0u);  // now each differs
  runs[2].precision = 0.4;
  runs[2].recall = 0.61;
  EXPECT_EQ(modal_run(runs), 1u);
  runs[1].reported = true;
  EXPECT_EQ(&reported_run(runs), &runs[1]);
}

// A similarity of the unit sphere's Fibonacci points.
Eigen::Matrix4d known_similarity() {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = 1.03 * Eigen::AngleAxisd(0.04, Vec3(1, 2, 2).normalized()).toRotationMatrix();
  m.block<3, 1>(0, 3) = Vec3(0.02, -0.01, 0.03);
  return m;
}

std::vector<Vec3> sphere_points(std::size_t n) {
  std::vector<Vec3> points;
  for (std::size_t k = 0; k < n; ++k) {
    const double z = 1 - 2 * (k + 0.5) / n, r = std::sqrt(1 - z * z), a = 2.399963229728653 * k;
    points.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
  return points;
}

// ICP from the identity brings an ellipsoid moved by a small similarity back onto itself: the
// product of its updates is the inverse of that similarity, to far below the points' spacing.
TEST(PointRegistration, IcpUndoesASmallSimilarity) {
  std::vector<Vec3> target = sphere_points(4000);
  for (Vec3& p : target) p = Vec3(1.0 * p[0], 0.7 * p[1], 0.5 * p[2]);  // no symmetry to slide along
  std::vector<Vec3> source = target;
  transform_points(known_similarity(), source);
  const PointTree tree(target);
  const PointRegistration r = icp_point_to_point(source, tree, 0.5, {0, 0, 200});
  EXPECT_TRUE(r.transformation.isApprox(known_similarity().inverse(), 1e-6)) << r.transformation;
  EXPECT_EQ(r.fitness, 1.0);
  EXPECT_LT(r.inlier_rmse, 1e-6);
  EXPECT_THROW(icp_point_to_point(source, tree, 0), Error);
  const std::vector<Vec3> none;
  EXPECT_THROW(icp_point_to_point(source, PointTree(none), 1), Error);
}

// ICP carries each point's nearest target point from step to step and searches again only where
// the point moved far enough to change it: every step's pairs, fitness and RMSE must be those of
// a search from scratch, bit for bit. A noisy ellipsoid, its copy moved, a distance that leaves
// some points without a pair.
TEST(PointRegistration, IcpPairsAreThoseOfASearchFromScratch) {
  std::vector<Vec3> target = sphere_points(3000);
  for (Vec3& p : target) p = Vec3(1.0 * p[0], 0.7 * p[1], 0.5 * p[2]);
  std::vector<Vec3> source = sphere_points(5000);
  for (std::size_t k = 0; k < source.size(); ++k) {
    const Vec3& p = source[k];
    source[k] = Vec3(1.0 * p[0], 0.7 * p[1], 0.5 * p[2]) * (1 + 0.01 * std::sin(37.0 * double(k)));
  }
  transform_points(known_similarity(), source);
  const PointTree tree(target);
  const double max_distance = 0.03;
  std::vector<Vec3> moved = source;  // ICP's steps, each searched from scratch
  PointRegistration scratch = evaluate_registration(moved, tree, max_distance, Eigen::Matrix4d::Identity());
  for (int steps = 1; steps <= 12; ++steps) {
    const Eigen::Matrix4d update = similarity_of_pairs(moved, target, scratch.pairs);
    transform_points(update, moved);
    scratch = evaluate_registration(moved, tree, max_distance, update * scratch.transformation);
    const PointRegistration carried = icp_point_to_point(source, tree, max_distance, {-1, -1, steps});
    ASSERT_EQ(carried.iterations, steps);
    EXPECT_EQ(carried.pairs, scratch.pairs) << steps << " steps";
    EXPECT_EQ(carried.fitness, scratch.fitness) << steps << " steps";
    EXPECT_EQ(carried.inlier_rmse, scratch.inlier_rmse) << steps << " steps";
    EXPECT_EQ(carried.transformation, scratch.transformation) << steps << " steps";
  }
  EXPECT_GT(scratch.fitness, 0.9);
  EXPECT_LT(scratch.fitness, 1.0);
}

// order_in_space keeps every point (duplicates too) and lists them by their Morton buckets, each
// bucket's points in their first order: 5,000 points of a sphere in its spiral's order, which
// jumps about the surface, and each point again at the end.
TEST(SpatialOrder, KeepsEveryPointInBucketsOfSpace) {
  std::vector<Vec3> points = sphere_points(5000);
  points.insert(points.end(), points.begin(), points.end());
  std::vector<Vec3> ordered = points;
  order_in_space(ordered);
  BoundingBox box;
  for (const Vec3& p : points) box.extend(p);
  // 10,000 points: 2^4 buckets of about 1,024.
  const auto bucket = [&](const Vec3& p) { return morton_code(p, box) >> (30 - 4); };
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::vector<Vec3> a = points, b = ordered;
  std::sort(a.begin(), a.end(), less);
  std::sort(b.begin(), b.end(), less);
  EXPECT_EQ(a, b);
  std::size_t moved = 0;
  for (std::size_t k = 1; k < ordered.size(); ++k) {
    ASSERT_LE(bucket(ordered[k - 1]), bucket(ordered[k])) << k;
    moved += ordered[k] != points[k];
  }
  EXPECT_GT(moved, ordered.size() / 2);  // the spiral's order is not space's
  // Within a bucket, the first order.
  for (std::uint64_t code = 0; code < 16; ++code) {
    std::vector<Vec3> first, after;
    for (const Vec3& p : points)
      if (bucket(p) == code) first.push_back(p);
    for (const Vec3& p : ordered)
      if (bucket(p) == code) after.push_back(p);
    EXPECT_EQ(first, after) << code;
  }
  std::vector<Vec3> one{Vec3(1, 2, 3)}, none;
  order_in_space(one);
  order_in_space(none);
  EXPECT_EQ(one, std::vector<Vec3>{Vec3(1, 2, 3)});
  EXPECT_TRUE(none.empty());
}

// RANSAC on pairs of which a quarter are wrong: a draw of inliers alone gives the similarity
// exactly (to rounding), which leaves every right pair's source on its target.
TEST(PointRegistration, RansacLeavesOutWrongPairs) {
  const std::vector<Vec3> target = sphere_points(80);
  std::vector<Vec3> source = target;
  transform_points(known_similarity().inverse(), source);
  for (std::size_t k = 0; k < source.size(); k += 4) source[k] += Vec3(0.5, 0.5, 0.5);
  PointPairs pairs;
  for (std::uint32_t k = 0; k < target.size(); ++k) pairs.emplace_back(k, k);
  const PointRegistration r = ransac_on_pairs(source, target, pairs, 0.05, 6, {}, 7);
  EXPECT_TRUE(r.transformation.isApprox(known_similarity(), 1e-9)) << r.transformation;
  EXPECT_EQ(r.fitness, 0.75);
  EXPECT_EQ(ransac_on_pairs(source, target, pairs, 0.05, 6, {}, 7).transformation, r.transformation);  // seeded
  EXPECT_THROW(ransac_on_pairs(source, target, PointPairs(pairs.begin(), pairs.begin() + 5), 0.05, 6, {}, 7), Error);
  EXPECT_THROW(ransac_on_pairs(source, target, {{0, 0}, {1, 1}, {2, 200}}, 0.05, 3, {}, 7), Error);
  EXPECT_THROW(ransac_on_pairs(source, target, pairs, -1, 6, {}, 7), Error);
}

TEST(TanksAndTemplesProtocol, TheSceneNamesItsTau) {
  const nlohmann::json by_scene = protocol("Bench_points.ply", "--tnt-scene Barn")["tanks_and_temples_protocol"];
  const nlohmann::json given = protocol("Bench_points.ply", "--tnt-tau 0.01")["tanks_and_temples_protocol"];
  EXPECT_EQ(by_scene["tau"].get<double>(), 0.01);
  EXPECT_EQ(by_scene["voxel_size"].get<double>(), 0.005);
  EXPECT_EQ(by_scene["scene"], "Barn");
  EXPECT_TRUE(given["scene"].is_null());
  EXPECT_EQ(by_scene["fscore"], given["fscore"]);
  EXPECT_EQ(protocol("Bench_points.ply", "--tnt-scene Ignatius")["tanks_and_temples_protocol"]["tau"].get<double>(),
            0.003);
}

// Open3D's CropInPolygon: the axis range closed; a crossing counts below the point when strictly
// below it, so a point on a left edge is outside and one on a right edge inside.
TEST(TanksAndTemplesProtocol, TheCropIsOpen3Ds) {
  const std::vector<Vec3> square = {{0, 0, 9}, {2, 0, 9}, {2, 2, 9}, {0, 2, 9}};
  const CropVolume z(2, -1, 1, square, "square");
  EXPECT_TRUE(z.contains({1, 1, 0}));
  EXPECT_TRUE(z.contains({1, 1, 1}));     // on axis_max
  EXPECT_TRUE(z.contains({1, 1, -1}));    // on axis_min
  EXPECT_FALSE(z.contains({1, 1, 1.0000001}));
  EXPECT_FALSE(z.contains({0, 1, 0}));    // on the left edge: its crossing is not below
  EXPECT_TRUE(z.contains({2, 1, 0}));     // on the right edge
  EXPECT_FALSE(z.contains({1, 0, 0}));    // on the bottom edge: v not above the lower vertex
  EXPECT_TRUE(z.contains({1, 2, 0}));     // on the top edge
  EXPECT_FALSE(z.contains({3, 1, 0}));
  // x orthogonal: the polygon across (y, z); y orthogonal: across (x, z).
  const CropVolume x(0, -1, 1, {{9, 0, 0}, {9, 2, 0}, {9, 2, 2}, {9, 0, 2}}, "x");
  EXPECT_TRUE(x.contains({0.5, 1, 1}));
  EXPECT_FALSE(x.contains({0.5, 1, 3}));
  const CropVolume y(1, -1, 1, {{0, 9, 0}, {2, 9, 0}, {2, 9, 2}, {0, 9, 2}}, "y");
  EXPECT_TRUE(y.contains({1, 0.5, 1}));
  EXPECT_FALSE(y.contains({1, 2, 1}));
  // A non-convex polygon: the notch of a U is outside.
  const CropVolume u(2, -1, 1, {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}},
                     "u");
  EXPECT_TRUE(u.contains({0.5, 2, 0}));
  EXPECT_FALSE(u.contains({1.5, 2, 0}));
  EXPECT_TRUE(u.contains({2.5, 2, 0}));
}

// Open3D's VoxelDownSample: cubes from half a side below the least corner; each the mean of its points.
TEST(TanksAndTemplesProtocol, DownSamplingIsOpen3Ds) {
  const std::vector<Vec3> points = {{0, 0, 0}, {0.4, 0, 0}, {0.6, 0, 0}, {1.4, 0, 0}, {1.6, 0.2, 0.1}};
  // The grid starts at -0.5: cubes [-0.5, 0.5), [0.5, 1.5), [1.5, 2.5) along x.
  const std::vector<Vec3> means = voxel_down_sample(points, 1.0);
  ASSERT_EQ(means.size(), 3u);
  EXPECT_EQ(means[0], Vec3((0 + 0.4) / 2.0, 0, 0));
  EXPECT_EQ(means[1], Vec3((0.6 + 1.4) / 2.0, 0, 0));
  EXPECT_EQ(means[2], Vec3(1.6, 0.2, 0.1));
  EXPECT_TRUE(voxel_down_sample({}, 1.0).empty());
  EXPECT_THROW(voxel_down_sample(points, 0), Error);
  EXPECT_THROW(voxel_down_sample({{0, 0, 0}, {1e10, 0, 0}}, 1e-3), Error);  // an index past an int
}

// np.arange's length and values, and np.histogram's closed last bin.
TEST(TanksAndTemplesProtocol, TheCurvesAreNumPys) {
  const std::vector<double> edges = histogram_edges(0.003 * 5, 0.003 / 100);  // 499.99999999999994 steps
  ASSERT_EQ(edges.size(), 500u);
  EXPECT_EQ(edges[1], 0.003 / 100);
  EXPECT_EQ(edges[499], 499 * (0.003 / 100));
  const std::vector<double> shares = cumulative_shares({0.5, 1.0, 2.0, 2.0, 3.5}, {0, 1, 2});
  ASSERT_EQ(shares.size(), 2u);
  EXPECT_EQ(shares[0], 1 / 5.0);  // below 1: 0.5 (1.0 falls in the next bin)
  EXPECT_EQ(shares[1], 4 / 5.0);  // the last bin closed: 2.0 twice counted
}

// With --symmetric, the exact figures within the crop are the area-weighted shares of the samples
// inside it within tau (REF's points, TEST's face centres weighted by area), from the samples' own
// file; TEST's samples lie where the alignment moved them.
TEST(TanksAndTemplesProtocol, ExactFiguresAreTheSharesWithinTheCrop) {
  const std::string csv = ::testing::TempDir() + "tnt_exact_samples.csv";
  const nlohmann::json report =
      protocol("Bench_mesh.ply", "--tnt-tau 0.01 --symmetric --samples-out " + csv);
  const nlohmann::json& t = report["tanks_and_temples_protocol"];
  const nlohmann::json& exact = t["exact_within_crop"];
  ASSERT_TRUE(exact.is_object()) << t.dump();
  const CropVolume crop = read_crop_volume(kData + "Bench.json");
  const std::vector<SampleRow> test = sample_rows(csv, "B -> A"), reference = sample_rows(csv, "A -> B");
  const auto share_within = [&](const std::vector<SampleRow>& rows, std::size_t& counted) {
    double within = 0, area = 0;
    counted = 0;
    for (const SampleRow& r : rows) {
      if (!crop.contains(r.position)) continue;
      ++counted;
      area += r.weight;
      if (r.hit && r.distance < 0.01) within += r.weight;
    }
    return within / area;
  };
  std::size_t test_counted = 0, reference_counted = 0;
  const double precision = share_within(test, test_counted), recall = share_within(reference, reference_counted);
  EXPECT_EQ(exact["test_samples_counted"].get<std::size_t>(), test_counted);
  EXPECT_EQ(exact["reference_samples_counted"].get<std::size_t>(), reference_counted);
  EXPECT_LT(test_counted, test.size());
  EXPECT_LT(reference_counted, reference.size());
  const nlohmann::json& figures = exact["figures"];
  const nlohmann::json& at_tau = figures["thresholds"][0];
  EXPECT_EQ(at_tau["tau"].get<double>(), 0.01);
  // The sums agree but for their order: relative 1e-12.
  EXPECT_NEAR(at_tau["precision"].get<double>(), precision, 1e-12);
  EXPECT_NEAR(at_tau["recall"].get<double>(), recall, 1e-12);
  // The exact figures and the protocol's are two estimates of one quantity: close on this dense scene.
  EXPECT_NEAR(at_tau["precision"].get<double>(), t["precision"].get<double>(), 0.02);
  EXPECT_NEAR(at_tau["recall"].get<double>(), t["recall"].get<double>(), 0.03);
  EXPECT_TRUE(protocol("Bench_mesh.ply", "--tnt-tau 0.01")["tanks_and_temples_protocol"]["exact_within_crop"].is_null());
}

TEST(TanksAndTemplesProtocol, TheCurvesArePictured) {
  const std::string png = ::testing::TempDir() + "tnt_curves.png";
  std::filesystem::remove(png);
  protocol("Bench_points.ply", "--tnt-tau 0.01 --tnt-curves " + png);
  std::ifstream in(png, std::ios::binary);
  std::string signature(8, '\0');
  in.read(signature.data(), 8);
  EXPECT_EQ(signature, "\x89PNG\r\n\x1a\n");
  std::filesystem::remove(png);
}

// A viewing file of ours (distance_cloud_writer.h): its records (x y z float64, r g b bytes).
std::vector<std::string> ply_records(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::size_t body = bytes.find("end_header\n") + 11;
  std::vector<std::string> records;
  for (std::size_t at = body; at + 27 <= bytes.size(); at += 27) records.push_back(bytes.substr(at, 27));
  EXPECT_EQ((bytes.size() - body) % 27, 0u) << path;
  return records;
}

// Records sorted as the golden file sorts them (by x, y, z, then colour): doubles compared as numbers.
void sort_records(std::vector<std::string>& records) {
  const auto key = [](const std::string& r) {
    double xyz[3];
    std::memcpy(xyz, r.data(), sizeof xyz);
    return std::make_tuple(xyz[0], xyz[1], xyz[2], std::uint8_t(r[24]), std::uint8_t(r[25]), std::uint8_t(r[26]));
  };
  std::sort(records.begin(), records.end(), [&](const std::string& a, const std::string& b) { return key(a) < key(b); });
}

// The toolbox's viewing files (EvaluateHisto's write_color_distances): the same points with the same
// colours, compared by the digest of the sorted records and, to show a difference, each colour's count.
TEST(TanksAndTemplesGolden, ViewingFilesAreTheToolboxs) {
  const std::string prefix = ::testing::TempDir() + "tnt_view";
  const nlohmann::json t =
      protocol("Bench_points.ply", "--tnt-tau 0.01 --tnt-plys " + prefix)["tanks_and_temples_protocol"];
  EXPECT_EQ(t["plys"], nlohmann::json({prefix + ".precision.ply", prefix + ".recall.ply"}));
  std::ifstream golden(kData + "golden/points_plys.txt");
  ASSERT_TRUE(golden);
  std::vector<std::string> lines;
  for (std::string line; std::getline(golden, line);)
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string name = k == 0 ? "precision" : "recall";
    std::vector<std::string> records = ply_records(prefix + "." + name + ".ply");
    sort_records(records);
    std::map<std::array<int, 3>, int> counts;
    std::string all;
    for (const std::string& r : records) {
      ++counts[{std::uint8_t(r[24]), std::uint8_t(r[25]), std::uint8_t(r[26])}];
      all += r;
    }
    std::string histogram;
    for (const auto& [c, n] : counts) histogram += fmt::format("{}{},{},{}:{}", histogram.empty() ? "" : " ", c[0], c[1], c[2], n);
    const std::string sorted_path = prefix + "." + name + ".sorted";
    std::ofstream(sorted_path, std::ios::binary) << all;
    EXPECT_EQ(fmt::format("{} {} {}", name, records.size(), file_sha256(sorted_path)), lines[2 * k]);
    EXPECT_EQ(histogram, lines[2 * k + 1]) << name;
    EXPECT_GT(counts.size(), 50u) << name << ": the distances span the colour map";
    std::filesystem::remove(sorted_path);
    std::filesystem::remove(prefix + "." + name + ".ply");
  }
}

// hot_r's ends and its steps: matplotlib's table, Open3D's rounding to bytes.
TEST(TanksAndTemplesProtocol, DistanceColoursAreHotR) {
  EXPECT_EQ(hot_r_colour(0.0), (std::array<std::uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(hot_r_colour(1.0), (std::array<std::uint8_t, 3>{11, 0, 0}));  // 0.0416 * 255 = 10.6, rounded
  for (double t = 0; t < 1; t += 1.0 / 512) {  // darker, never lighter, as t grows
    const std::array<std::uint8_t, 3> a = hot_r_colour(t), b = hot_r_colour(t + 1.0 / 512);
    for (int c = 0; c < 3; ++c) EXPECT_LE(b[c], a[c]) << t;
  }
}

// NaN and infinite points in the ground truth (or the reconstruction): the toolbox crops every cloud
// before it uses it, and Open3D's crop leaves them out, so the figures are those without them,
// with a warning naming the file and how many. DTU's script crashes on them: refused, naming the
// file and the first.
TEST(TanksAndTemplesProtocol, NonFinitePointsAreCroppedAwayAsTheToolboxCropsThem) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "roving-tnt-nan";
  std::filesystem::create_directories(dir);
  PointCloud truth = read_point_cloud(kTruth, false);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  for (std::size_t at : {std::size_t{0}, truth.positions.size() / 3, truth.positions.size() / 2}) {
    truth.positions.insert(truth.positions.begin() + std::ptrdiff_t(at), Vec3(nan, 0, 0));
  }
  truth.positions.push_back(Vec3(1, inf, 2));
  truth.normals.clear();
  truth.colours.clear();
  const std::string broken = (dir / "Bench_nan.ply").string();
  write_point_cloud_ply(truth, broken);
  const std::string options = " --protocol tanks-and-temples" + kScene + " --tnt-tau 0.01 --json - ";
  const CliRun with = run_cli("measure " + broken + " " + kData + "Bench_points.ply" + options);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_NE(with.err.find("Bench_nan.ply: 4 points with a NaN or infinite coordinate left out"), std::string::npos)
      << with.err;
  const nlohmann::json t = nlohmann::json::parse(with.out)["tanks_and_temples_protocol"];
  const std::vector<std::vector<double>> rows = golden_rows("points.txt");
  EXPECT_EQ(t["fscore"].get<double>(), rows[0].at(2));
  EXPECT_EQ(t["ground_truth_cropped"].get<double>(), rows[1].at(2));
  EXPECT_EQ(t["ground_truth_thinned"].get<double>(), rows[1].at(3));
  EXPECT_EQ(t["cumulative_recall"].get<std::vector<double>>(), rows[4]);
  const std::string dtu = std::string(ROVING_SOURCE_DIR) + "/tests/data/dtu/ObsMask/";
  expect_error("measure " + broken + " " + kData + "Bench_points.ply --protocol dtu --dtu-obs-mask " + dtu +
                   "ObsMask1_10.mat --dtu-plane " + dtu + "Plane1.mat",
               {"Bench_nan.ply", "vertex 0", "non-finite"});
  std::filesystem::remove_all(dir);
}

TEST(TanksAndTemplesProtocol, BadInputGetsOneLine) {
  const std::string pair = kTruth + " " + kData + "Bench_points.ply";
  const std::string run = "measure " + pair + " --protocol tanks-and-temples ";
  expect_error(run + "--tnt-tau 0.01", {"--tnt-crop", "<scene>.json"});
  const std::string folder = std::filesystem::temp_directory_path().string();
  expect_error(run + "--tnt-tau 0.01 --tnt-crop " + folder, {"--tnt-crop", "directory", folder.c_str()});
  expect_error(run + kScene, {"--tnt-scene", "--tnt-tau"});
  expect_error(run + kScene + " --tnt-tau 0.01 --tnt-scene Barn", {"--tnt-scene", "--tnt-tau"});
  expect_error(run + kScene + " --tnt-scene Bench", {"--tnt-scene", "'Bench'", "Barn"});
  expect_error(run + kScene + " --tnt-tau 0", {"--tnt-tau", "found 0"});
  expect_error(run + kScene + " --tnt-tau -1", {"--tnt-tau"});
  expect_error(run + kScene + " --tnt-tau nan", {"--tnt-tau"});
  expect_error(run + kScene + " --tnt-tau 1e-300", {"Bench_points.ply", "too small"});
  expect_error(run + "--tnt-crop missing.json --tnt-tau 0.01", {"--tnt-crop", "missing.json"});
  expect_error("measure " + pair + " --tnt-tau 0.01", {"--tnt-tau", "only with --protocol tanks-and-temples"});
  expect_error("measure " + pair + " --tnt-plys view", {"--tnt-plys", "only with --protocol tanks-and-temples"});
  expect_error(run + kScene + " --tnt-tau 0.01 --tnt-plys /nonexistent-folder/view",
               {"/nonexistent-folder/view.precision.ply", "cannot open"});
  expect_error("measure " + pair + " --protocol dtu --tnt-crop " + kData + "Bench.json", {"--tnt-crop"});
  expect_error(run + kScene + " --tnt-tau 0.01 --html out.html", {"--html", "--symmetric"});
  // The scene's files: a crop volume and an alignment that are not what the toolbox reads.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "roving-tnt-bad";
  std::filesystem::create_directories(dir);
  const auto file = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  const std::string polygon = R"("bounding_polygon": [[0, 0, 0], [1, 0, 0], [1, 1, 0]])";
  const std::string head = R"({"class_name": "SelectionPolygonVolume", "version_major": 1, "version_minor": 0, )";
  for (const auto& [name, text, fragment] : {
           std::tuple{"not-json.json", std::string("ply\nformat ascii"), "SelectionPolygonVolume"},
           {"truncated.json", head + R"("orthogonal_axis": "Z", "axis_min": 0)", "SelectionPolygonVolume"},
           {"class.json", R"({"class_name": "ViewTrajectory"})", "class_name"},
           {"version.json", R"({"class_name": "SelectionPolygonVolume", "version_major": 2})", "version_major"},
           {"axis.json", head + R"("orthogonal_axis": "W", "axis_min": 0, "axis_max": 1, )" + polygon + "}",
            "orthogonal_axis"},
           {"range.json", head + R"("orthogonal_axis": "Z", "axis_min": 2, "axis_max": 1, )" + polygon + "}",
            "axis_min <= axis_max"},
           {"no-min.json", head + R"("orthogonal_axis": "Z", "axis_max": 1, )" + polygon + "}", "'axis_min'"},
           {"open.json",
            head + R"("orthogonal_axis": "Z", "axis_min": 0, "axis_max": 1, "bounding_polygon": [[0, 0, 0], [1, 0, 0]]})",
            "closed polygon of 3 or more"},
           {"vertex.json",
            head + R"("orthogonal_axis": "Z", "axis_min": 0, "axis_max": 1, "bounding_polygon": [[0, 0], [1, 0, 0], [1, 1, 0]]})",
            "vertex 0"}}) {
    expect_error(run + "--tnt-tau 0.01 --tnt-crop " + file(name, text), {name, fragment});
  }
  const std::string crop = " --tnt-tau 0.01 --tnt-crop " + kData + "Bench.json --tnt-alignment ";
  for (const auto& [name, text, fragment] : {
           std::tuple{"three-rows.txt", std::string("1 0 0 0\n0 1 0 0\n0 0 1 0\n"), "3 rows"},
           {"five-columns.txt", std::string("1 0 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"), "5 numbers"},
           {"word.txt", std::string("1 0 0 0\n0 one 0 0\n0 0 1 0\n0 0 0 1\n"), "'one'"},
           {"nan.txt", std::string("1 0 0 0\n0 nan 0 0\n0 0 1 0\n0 0 0 1\n"), "'nan'"},
           {"projective.txt", std::string("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n"), "affine"},
           {"singular.txt", std::string("1 0 0 0\n0 0 0 0\n0 0 1 0\n0 0 0 1\n"), "invertible"}}) {
    expect_error(run + crop + file(name, text), {name, fragment});
  }
  // run.py's registration: its files, and what it needs beside them.
  const std::string moved = "measure " + kTruth + " " + kData + "Bench_moved_points.ply --protocol tanks-and-temples ";
  const std::string log = kData + "Bench_moved.log", reference = kData + "Bench_COLMAP_SfM.log";
  expect_error(moved + kScene + " --tnt-tau 0.01 --tnt-trajectory " + log, {"--tnt-reference-trajectory"});
  expect_error(moved + "--tnt-crop " + kData + "Bench.json --tnt-tau 0.01 --tnt-trajectory " + log +
                   " --tnt-reference-trajectory " + reference,
               {"--tnt-alignment", "_trans.txt"});
  expect_error(moved + kScene + " --tnt-tau 0.01 --tnt-mapping " + kData + "Bench_mapping_reference.txt",
               {"--tnt-mapping", "only with --tnt-trajectory"});
  expect_error(moved + kScene + " --tnt-tau 0.01 --tnt-trajectory " + log + " --tnt-reference-trajectory " + reference,
               {"Bench_moved.log", "1700 cameras", "--tnt-mapping"});
  expect_error(moved + kScene + " --tnt-tau 0.01 --protocol-seed none" + kRegistration, {"--protocol-seed", "'none'"});
  expect_error("measure " + pair + " --tnt-trajectory " + log, {"--tnt-trajectory", "only with --protocol"});
  const std::string pose = "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
  std::string three_cameras;
  for (int k = 0; k < 3; ++k) three_cameras += fmt::format("{0} {0} 3\n", k) + pose;
  for (const auto& [name, text, fragment] : {
           std::tuple{"short.log", std::string("0 0 1\n1 0 0 0\n0 1 0 0\n"), "ends after 2 of its pose's 4 rows"},
           {"word.log", std::string("0 0 1\n1 0 0 0\n0 one 0 0\n0 0 1 0\n0 0 0 1\n"), "line 3"},
           {"inf.log", std::string("0 0 1\n1 0 0 0\n0 inf 0 0\n0 0 1 0\n0 0 0 1\n"), "4 finite numbers"},
           {"five.log", std::string("0 0 1\n1 0 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"), "line 2"},
           {"empty.log", std::string("\n"), "no camera"},
           {"three.log", three_cameras, "3 cameras matched to the reference's 60"}}) {
    expect_error(moved + kScene + " --tnt-tau 0.01 --tnt-reference-trajectory " + reference + " --tnt-trajectory " +
                     file(name, text),
                 {name, fragment});
  }
  const std::string video = moved + kScene + " --tnt-tau 0.01 --tnt-trajectory " + log +
                            " --tnt-reference-trajectory " + reference + " --tnt-mapping ";
  for (const auto& [name, text, fragment] : {
           std::tuple{"counts.txt", std::string("sixty\n1700\n"), "line 1"},
           {"short.txt", std::string("3\n1700\n0 8\n1 36\n"), "reference frame 3 of 3"},
           {"beyond.txt", std::string("1\n1700\n0 1701\n"), "frame 1701"},
           {"zero.txt", std::string("1\n1700\n0 0\n"), "frame 0"},
           {"none.txt", std::string("0\n1700\n"), "no reference frame"},
           {"past-video.txt", std::string("1\n2000\n0 1800\n"), "from 1 to 1700"},
           {"few.txt", std::string("1\n1700\n0 8\n"), "1 cameras matched to the reference's 60"}}) {
    expect_error(video + file(name, text), {name, fragment});
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace roving
