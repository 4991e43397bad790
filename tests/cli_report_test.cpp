// What `roving measure` reports beyond the statistics: both directions (Metro's summary),
// provenance, gates for a user's CI, warnings, the samples table's columns, suggestions for
// typos, and silence in pipes. Two concentric cubes (half-sides 0.5 and 0.55) give every figure
// in closed form: each face sample is 0.05 from the other cube's face.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_support.h"
#include "roving/formats/outputs/heatmap.h"

namespace {

using namespace roving::testing::cli;

struct Cubes {
  Folder folder;
  std::string small = folder.file("small.obj", cube_obj(0.5));
  std::string large = folder.file("large.obj", cube_obj(0.55));
  std::string pair = small + " " + large;
};

// The field of a CSV row under the header's column `name` (no quoting: the samples table has none).
std::string csv_field(const std::string& header, const std::string& row, const std::string& name) {
  const auto fields = [](const std::string& line) {
    std::vector<std::string> out(1);
    for (const char c : line) {
      if (c == ',')
        out.emplace_back();
      else
        out.back().push_back(c);
    }
    return out;
  };
  const std::vector<std::string> names = fields(header), values = fields(row);
  const auto at = std::find(names.begin(), names.end(), name);
  if (at == names.end() || names.size() != values.size()) return "(no column " + name + ")";
  return values[at - names.begin()];
}

// Embree's closest point is computed in float: 0.05 to about 1e-7.
constexpr double kFloatTolerance = 1e-6;

// The web page's tables of the pair's figures: both directions together (Metro's summary), and each
// family of figures the report holds (here the reconstruction figures: every face sample of either
// cube lies 0.05 from the other, so both shares within tau = 0.06 are whole).
TEST(CliReport, PageShowsThePairsFiguresByFamily) {
  const Cubes cubes;
  const std::string page = (cubes.folder.path / "pair.html").string();
  const CliRun run = run_cli("measure " + cubes.pair + " --symmetric --threshold 0.06 --html " + page + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* row :
       {"<section class=\"pair\">\n<h2>Both directions</h2>", "<tr><th>Hausdorff (max |d| of both)</th><td class=\"number\">0.05 (",
        "<section class=\"pair\">\n<h2>Reconstruction figures</h2>",
        "<tr><th>precision at tau = 0.06 (", "<tr><th>F-score at tau = 0.06 (3.149%)</th><td class=\"number\">100%</td></tr>"}) {
    EXPECT_NE(html.find(row), std::string::npos) << row;
  }
  // One direction: no pair's tables.
  const CliRun one = run_cli("measure " + cubes.pair + " --html " + page + " --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  std::ifstream again(page);
  const std::string single((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  EXPECT_EQ(single.find("<section class=\"pair\">"), std::string::npos);
}

// Cubes of half-sides 0.5 and 0.55: every point of the small one is 0.05 from the large one; the
// large one's corners are 0.05 sqrt(3) from the small one. The certified interval holds both.
TEST(CliReport, CertifiedHausdorffIntervalHoldsTheClosedForm) {
  const Cubes cubes;
  const CliRun run = run_cli("measure " + cubes.pair + " --symmetric --hausdorff-bound 1e-6 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  const double truths[2] = {0.05, 0.05 * std::sqrt(3.0)};
  for (int k = 0; k < 2; ++k) {
    const auto& h = json["directions"][k]["hausdorff_certified"];
    EXPECT_LE(h["lower"].get<double>(), truths[k] + 1e-12);
    EXPECT_GE(h["upper"].get<double>(), truths[k] - 1e-12);
    EXPECT_LE(h["upper"].get<double>() - h["lower"].get<double>(), 1e-6 * (1 + 1e-9));
  }
  EXPECT_GE(json["two_sided"]["hausdorff_certified"]["upper"].get<double>(), truths[1] - 1e-12);
  // The sampled Hausdorff distance (face centroids) sees only 0.05: the corners lie between samples.
  EXPECT_NEAR(json["two_sided"]["hausdorff"].get<double>(), 0.05, kFloatTolerance);
  // Not asked for under first-hit without --symmetric; refused when absurd.
  EXPECT_FALSE(nlohmann::json::parse(run_cli("measure " + cubes.pair + " --json -").out).contains("hausdorff_certified"));
  EXPECT_EQ(run_cli("measure " + cubes.pair + " --symmetric --hausdorff-bound -1").exit_code, 2);
  EXPECT_FALSE(nlohmann::json::parse(run_cli("measure " + cubes.pair + " --symmetric --hausdorff-bound none --json -").out)
                   ["two_sided"]
                       .contains("hausdorff_certified"));
}

// Gates on figures with intervals: by default the figure decides and a note says when its interval
// straddles the limit (or lies wholly above it); --gate-on upper decides on the interval's top.
TEST(CliReport, GatesOnTheUpperEndOfAnIntervalAndSayWhenTheDecisionRestsInsideIt) {
  const Cubes cubes;
  // Sampled Hausdorff 0.05 (face centroids); certified ~0.0866 (the large cube's corners).
  const std::string symmetric = "measure " + cubes.pair + " --symmetric --fail-above hausdorff=0.07";
  const CliRun estimate = run_cli(symmetric);
  EXPECT_EQ(estimate.exit_code, 0) << estimate.err;
  EXPECT_NE(estimate.err.find("lies wholly above it"), std::string::npos) << estimate.err;
  const CliRun upper = run_cli(symmetric + " --gate-on upper");
  EXPECT_EQ(upper.exit_code, 3) << upper.err;
  EXPECT_NE(upper.err.find("its interval reaching"), std::string::npos) << upper.err;
  // REF a unit square, TEST the plane z = 0.1 x: USiAD's surface mean is 0.05, and 500 random
  // samples' interval is about +-0.0025 wide around its estimate.
  const std::string square = cubes.folder.file("square.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const std::string tilted =
      cubes.folder.file("tilted.obj", "v -1 -1 -0.1\nv 2 -1 0.2\nv -1 2 -0.1\nv 2 2 0.2\nf 1 2 3\nf 2 4 3\n");
  const std::string sampled = "measure " + square + " " + tilted + " --samples area:500 --max-error 0.5 --fail-above usiad=0.05";
  const CliRun inside = run_cli(sampled);
  EXPECT_NE(inside.err.find("gate usiad: the limit 0.05 lies inside the interval"), std::string::npos) << inside.err;
  EXPECT_EQ(run_cli(sampled + " --gate-on upper").exit_code, 3);
  EXPECT_EQ(run_cli(sampled + " --gate-on both").exit_code, 2);
}

// area:auto draws samples until USiAD's interval is as narrow as asked: square against the plane
// z = 0.1 x, where |d| has standard deviation 0.1 / sqrt(12) and USiAD's surface mean is 0.05, so a
// half-width of 0.5% of it needs N >= (1.96 * 0.0289 / 0.00025)^2 = 51,300: a second round.
TEST(CliReport, AreaAutoSamplesUntilThePrecisionAsked) {
  const Cubes cubes;
  const std::string square = cubes.folder.file("square.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const std::string tilted =
      cubes.folder.file("tilted.obj", "v -1 -1 -0.1\nv 2 -1 0.2\nv -1 2 -0.1\nv 2 2 0.2\nf 1 2 3\nf 2 4 3\n");
  const CliRun run =
      run_cli("measure " + square + " " + tilted + " --samples area:auto --precision 0.5% --max-error 0.5 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  const auto& aim = json["samples"]["auto"];
  EXPECT_TRUE(aim["met"].get<bool>());
  EXPECT_EQ(aim["rounds"], 2);
  EXPECT_LE(aim["usiad_half_width_reached"].get<double>(), aim["usiad_half_width_asked"].get<double>());
  EXPECT_GE(json["samples"]["count"].get<std::size_t>(), 51300u * 9 / 10);
  EXPECT_LE(json["samples"]["count"].get<std::size_t>(), 80000u);
  const auto& usiad = json["sampling_error"]["usiad"];
  EXPECT_LE(usiad["lower"].get<double>(), 0.05 * (1 + 0.01));  // the truth, within twice the half-width
  EXPECT_GE(usiad["upper"].get<double>(), 0.05 * (1 - 0.01));
  expect_error("measure " + square + " " + tilted + " --samples area:auto --precision 0", {"--precision", "USiAD"});
}

TEST(CliReport, SymmetricGivesBothDirectionsAndMetrosSummary) {
  const Cubes cubes;
  const CliRun run = run_cli("measure " + cubes.pair + " --symmetric --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["semantics"], "closest");  // the default where the method has it
  EXPECT_EQ(json["diagonal_of"], "both models");
  EXPECT_NEAR(json["diagonal"].get<double>(), 1.1 * std::sqrt(3.0), 1e-12);
  ASSERT_EQ(json["directions"].size(), 2u);
  // The large cube lies outside the small one's faces (+0.05), the small one inside the large's.
  EXPECT_NEAR(json["directions"][0]["statistics"]["siad"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(json["directions"][1]["statistics"]["siad"].get<double>(), -0.05, kFloatTolerance);
  EXPECT_EQ(json["directions"][0]["label"], "A -> B");
  EXPECT_EQ(json["directions"][0]["samples"]["count"], 12);
  EXPECT_NEAR(json["two_sided"]["hausdorff"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(json["two_sided"]["mean_both"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(json["two_sided"]["rms_both"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(json["two_sided_relative_to_diagonal"]["max_abs"].get<double>(), 0.05 / (1.1 * std::sqrt(3.0)),
              kFloatTolerance);

  const CliRun text = run_cli("measure " + cubes.pair + " --symmetric");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* field : {"A -> B", "B -> A", "Hausdorff distance", "of both models", "mean |d|, both"}) {
    EXPECT_NE(text.out.find(field), std::string::npos) << field;
  }
  // Under first-hit the two-sided maximum is not a Hausdorff distance, and says so.
  const CliRun first_hit = run_cli("measure " + cubes.pair + " --symmetric --semantics first-hit --json -");
  ASSERT_EQ(first_hit.exit_code, 0) << first_hit.err;
  EXPECT_TRUE(nlohmann::json::parse(first_hit.out)["two_sided"]["hausdorff"].is_null());
}

TEST(CliReport, ExtremesLeaveNoHitsOut) {
  const Cubes cubes;
  // h = 0.03 is closer than the other cube: every first-hit sample is a no-hit.
  const CliRun run = run_cli("measure " + cubes.pair + " --max-error 0.03 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["no_hits"], 12);
  EXPECT_EQ(json["statistics"]["max_abs"], 0.0);  // not h: no-hits are counted, not folded in
  EXPECT_NEAR(json["statistics"]["usiad"].get<double>(), 0.03, 1e-12);  // the means keep the paper's rule
  const CliRun hits = run_cli("measure " + cubes.pair + " --max-error 0.2 --json -");
  const auto stats = nlohmann::json::parse(hits.out)["statistics"];
  EXPECT_NEAR(stats["min_signed"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(stats["max_signed"].get<double>(), 0.05, kFloatTolerance);
  EXPECT_NEAR(stats["max_abs"].get<double>(), 0.05, kFloatTolerance);
}

TEST(CliReport, ProvenanceNamesToolInputsAndSeed) {
  const Cubes cubes;
  const CliRun version = run_cli("--version");
  ASSERT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("roving ", 0), 0u) << version.out;
  EXPECT_NE(version.out.find("(commit "), std::string::npos) << version.out;

  const CliRun run = run_cli("measure " + cubes.pair + " --samples area:50 --json -");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["schema_version"], 3);
  EXPECT_EQ(json["tool"]["name"], "roving");
  EXPECT_FALSE(json["tool"]["commit"].get<std::string>().empty());
  EXPECT_NE(json["command_line"].get<std::string>().find("--samples area:50"), std::string::npos);
  ASSERT_EQ(json["inputs"].size(), 2u);
  EXPECT_EQ(json["inputs"][0]["path"], cubes.small);
  EXPECT_EQ(json["inputs"][0]["bytes"], fs::file_size(cubes.small));
  const std::string hash = json["inputs"][0]["sha256"];
  EXPECT_EQ(hash.size(), 64u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_NE(json["inputs"][1]["sha256"], hash);  // different files
  EXPECT_EQ(json["seed"], 12345);                // the fixed default, reported

  // Another seed, other samples; the same seed, the same ones.
  const auto rows = [&](const std::string& seed) {
    const std::string csv = cubes.folder.file("samples-" + seed + ".csv");
    const CliRun r = run_cli("measure " + cubes.pair + " --samples area:50 --seed " + seed + " --samples-out " + csv);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream file(csv);
    return std::string(std::istreambuf_iterator<char>(file), {});
  };
  EXPECT_NE(rows("7"), rows("8"));
  EXPECT_EQ(rows("7"), rows("7"));
  expect_error("measure " + cubes.pair + " --seed 7", {"--seed", "area:N", "faces"});
  expect_error("measure " + cubes.pair + " --samples area:10 --seed x", {"--seed"});
}

TEST(CliReport, GatesPassFailAndRefuseMalformedLimits) {
  const Cubes cubes;
  const std::string run_pair = "measure " + cubes.pair + " --semantics closest";
  // USiAD is 0.05; the small cube's diagonal is sqrt(3): 2% of it is 0.0346, 3% is 0.052.
  for (const char* pass : {"usiad=0.1", "usiad=3%", "max_abs=0.06", "no_hits=0", "siad=0.1"}) {
    const CliRun run = run_cli(run_pair + " --fail-above " + pass);
    EXPECT_EQ(run.exit_code, 0) << pass << ": " << run.err;
    EXPECT_EQ(run.err, "") << pass;
  }
  const CliRun fail = run_cli(run_pair + " --fail-above usiad=2% --fail-above rms=0.03 --fail-above p99=1");
  EXPECT_EQ(fail.exit_code, 3) << fail.err;
  EXPECT_EQ(std::count(fail.err.begin(), fail.err.end(), '\n'), 2) << fail.err;
  for (const char* fragment : {"usiad = 0.05", "0.034641", "--fail-above usiad=2%", "rms = 0.05", "limit 0.03"}) {
    EXPECT_NE(fail.err.find(fragment), std::string::npos) << fragment << " in " << fail.err;
  }
  EXPECT_FALSE(fail.out.empty());  // the report is still written
  // Both directions are checked, and the two-sided summary has its own names.
  const CliRun symmetric = run_cli("measure " + cubes.pair + " --symmetric --fail-above siad=0.03 "
                                   "--fail-above hausdorff=0.1");
  EXPECT_EQ(symmetric.exit_code, 3);
  EXPECT_NE(symmetric.err.find("siad (A -> B) = 0.05"), std::string::npos) << symmetric.err;
  EXPECT_NE(symmetric.err.find("siad (B -> A) = -0.05"), std::string::npos) << symmetric.err;
  EXPECT_EQ(symmetric.err.find("hausdorff"), std::string::npos) << symmetric.err;

  expect_error(run_pair + " --fail-above usiad", {"--fail-above", "METRIC=LIMIT", "'usiad'"});
  expect_error(run_pair + " --fail-above usiad=abc", {"--fail-above", "'usiad=abc'"});
  expect_error(run_pair + " --fail-above usiad=-1", {"--fail-above", "'usiad=-1'"});
  expect_error(run_pair + " --fail-above usiad=150%", {"--fail-above", "'usiad=150%'"});
  expect_error(run_pair + " --fail-above bogus=1", {"--fail-above", "'bogus=1'", "usiad"});
  expect_error(run_pair + " --fail-above hausdorff=1", {"--fail-above", "needs --symmetric"});
  expect_error("measure " + cubes.pair + " --symmetric --semantics first-hit --fail-above hausdorff=1",
               {"--fail-above", "closest"});
}

TEST(CliReport, WarningsForMisalignedAndInsideOutModels) {
  const Cubes cubes;
  // A clean run in a pipe says nothing on stderr: no warnings, no progress.
  const CliRun clean = run_cli("measure " + cubes.pair + " --json -");
  EXPECT_EQ(clean.err, "");
  EXPECT_TRUE(nlohmann::json::parse(clean.out)["warnings"].empty());

  const std::string far = cubes.folder.file("far.obj", cube_obj(0.5, 10));
  const CliRun disjoint = run_cli("measure " + cubes.small + " " + far + " --json -");
  ASSERT_EQ(disjoint.exit_code, 0) << disjoint.err;
  EXPECT_NE(disjoint.err.find("roving: warning: the bounding boxes"), std::string::npos) << disjoint.err;
  EXPECT_NE(disjoint.err.find("do not overlap"), std::string::npos) << disjoint.err;
  EXPECT_NE(disjoint.err.find("100% of the samples (12 of 12) found no surface"), std::string::npos)
      << disjoint.err;
  EXPECT_EQ(nlohmann::json::parse(disjoint.out)["warnings"].size(), 2u);

  // An OBJ whose material library is missing: measured, with a warning naming the library.
  const std::string unlit = cubes.folder.file("unlit.obj", "mtllib beetle.mtl\nusemtl shell\n" + cube_obj(0.5, 0));
  const CliRun without = run_cli("measure " + cubes.small + " " + unlit + " --json -");
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_NE(without.err.find("roving: warning: " + unlit + ":1: mtllib 'beetle.mtl': no such file"), std::string::npos)
      << without.err;
  EXPECT_EQ(nlohmann::json::parse(without.out)["warnings"].size(), 1u);
  // --strict-materials refuses it, naming the library.
  const CliRun strict = run_cli("measure " + cubes.small + " " + unlit + " --strict-materials");
  EXPECT_EQ(strict.exit_code, 1) << strict.err;
  EXPECT_NE(strict.err.find("beetle.mtl"), std::string::npos) << strict.err;
  EXPECT_NE(strict.err.find("cannot open"), std::string::npos) << strict.err;

  const std::string shifted = cubes.folder.file("shifted.obj", cube_obj(0.5, 0.2));
  const CliRun offset = run_cli("measure " + cubes.small + " " + shifted + " --max-error 0.1");
  EXPECT_NE(offset.err.find("small.obj reaches 0.2 beyond that of"), std::string::npos) << offset.err;
  // A part measured against the whole (a partial scan) is no mistake: no warning.
  const std::string part = cubes.folder.file("part.obj", "v 0 0 0.5\nv 0.5 0 0.5\nv 0 0.5 0.5\nf 1 2 3\n");
  EXPECT_EQ(run_cli("measure " + part + " " + cubes.small).err, "");

  const std::string flipped = cubes.folder.file("flipped.obj", cube_obj(0.5, 0, true));
  const CliRun inside_out = run_cli("measure " + flipped + " " + cubes.large + " --json -");
  ASSERT_EQ(inside_out.exit_code, 0) << inside_out.err;
  EXPECT_NE(inside_out.err.find("inside out"), std::string::npos) << inside_out.err;
  EXPECT_NE(inside_out.err.find("flipped.obj"), std::string::npos) << inside_out.err;
}

TEST(CliReport, SamplesTableNamesElementWeightAndResolution) {
  const Cubes cubes;
  const std::string csv = cubes.folder.file("faces.csv");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --samples-out " + csv).exit_code, 0);
  std::ifstream file(csv);
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line,
            "x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by,test_face,test_x,test_y,test_z,bary_0,bary_1,bary_2");
  std::getline(file, line);
  // Face 0 of the unit cube: a right triangle of legs 1, area 0.5; Embree resolves no "how".
  EXPECT_NE(line.find(",1,0,0.5,,"), std::string::npos) << line;
  // Its centroid at z = -0.5, 0.05 out along its normal -z: the larger cube's face 0 at z = -0.55.
  const std::string header = "x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by,test_face,test_x,test_y,test_z,"
                             "bary_0,bary_1,bary_2";
  EXPECT_EQ(csv_field(header, line, "test_face"), "0");
  EXPECT_NEAR(std::stod(csv_field(header, line, "test_x")), -1.0 / 6, 1e-15);
  EXPECT_NEAR(std::stod(csv_field(header, line, "test_y")), -1.0 / 6, 1e-15);
  EXPECT_NEAR(std::stod(csv_field(header, line, "test_z")), -0.55, 1e-15);
  double weights = 0;
  for (const char* w : {"bary_0", "bary_1", "bary_2"}) {
    EXPECT_GE(std::stod(csv_field(header, line, w)), 0) << line;
    weights += std::stod(csv_field(header, line, w));
  }
  EXPECT_NEAR(weights, 1, 1e-15);

  const std::string gl = cubes.folder.file("gl.csv");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --method roving --max-error 0.03 --samples-out " + gl).exit_code, 0);
  std::ifstream gl_file(gl);
  std::getline(gl_file, line);
  std::getline(gl_file, line);
  EXPECT_NE(line.find(",,0,0,0.5,no-hit"), std::string::npos) << line;  // nothing within 0.03

  const std::string both = cubes.folder.file("both.csv");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --symmetric --samples-out " + both).exit_code, 0);
  std::ifstream both_file(both);
  std::string text((std::istreambuf_iterator<char>(both_file)), {});
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 25);  // header + 12 + 12
  EXPECT_NE(text.find(",direction\n"), std::string::npos);
  EXPECT_NE(text.find(",B -> A\n"), std::string::npos);
}

TEST(CliReport, HeatMapColoursTheReferencesOwnSurface) {
  const Cubes cubes;
  const auto read = [](const std::string& path) {
    std::ifstream file(path);
    return std::string(std::istreambuf_iterator<char>(file), {});
  };
  // Face samples: the reference's 12 triangles, each with its colour and d (0.05: red side).
  const std::string faces = cubes.folder.file("faces.ply");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --heatmap " + faces + " --heatmap-range 0.25").exit_code, 0);
  const std::string text = read(faces);
  for (const char* line : {"element vertex 8\n", "element face 12\n", "property float quality\n",
                           "d = -0.25 blue", "(per face)"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << " in " << text.substr(0, 600);
  }
  // d / range = 0.2: ColorBrewer's RdBu's first stop after white, (253, 219, 199), and d itself.
  EXPECT_NE(text.find("3 0 2 1 253 219 199 0.05"), std::string::npos) << text;
  // No hit within h = 0.03: grey and NaN quality, never 0.
  const std::string misses = cubes.folder.file("misses.ply");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --max-error 0.03 --heatmap " + misses).exit_code, 0);
  EXPECT_NE(read(misses).find("128 128 128 nan"), std::string::npos);
  // Vertex samples colour the vertices; area samples stay points.
  const std::string vertices = cubes.folder.file("vertices.ply");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --samples vertices --heatmap " + vertices).exit_code, 0);
  EXPECT_NE(read(vertices).find("(per vertex)"), std::string::npos);
  const std::string points = cubes.folder.file("points.ply");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --samples area:30 --heatmap " + points).exit_code, 0);
  EXPECT_NE(read(points).find("element vertex 30\n"), std::string::npos);
  EXPECT_EQ(read(points).find("element face"), std::string::npos);
  for (const char* bad : {"0", "-1", "abc", "150%"}) {
    expect_error("measure " + cubes.pair + " --heatmap " + faces + " --heatmap-range " + bad,
                 {"--heatmap-range", bad});
  }
}

// The PNG's size from its IHDR chunk (big-endian width and height after the 8-byte signature
// and the chunk's length and type), or {0, 0} when the file is not a PNG.
std::pair<int, int> png_size(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::string head(24, '\0');
  file.read(head.data(), 24);
  if (head.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || head.compare(12, 4, "IHDR") != 0) return {0, 0};
  const auto word = [&](int at) {
    int value = 0;
    for (int k = 0; k < 4; ++k) value = value << 8 | static_cast<unsigned char>(head[at + k]);
    return value;
  };
  return {word(16), word(20)};
}

TEST(CliReport, HeatMapPictureIsAPngOfThreeViewsAndALegend) {
  const Cubes cubes;
  // Three 400-px views with 16-px margins and the 250-px legend; the title, labels and views.
  const std::string faces = cubes.folder.file("faces.png");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --heatmap-png " + faces).exit_code, 0);
  EXPECT_EQ(png_size(faces), std::pair(16 + 3 * 416 + 250, 64 + 24 + 400 + 16));
  // A point-cloud reference is drawn as points; a GL method measures before the picture's own
  // context and after it.
  const std::string xyz = cubes.folder.file("points.xyz", "0 0 0.5 0 0 1\n0.1 0 0.5 0 0 1\n0 0.1 0.5 0 0 1\n");
  const std::string points = cubes.folder.file("points.png");
  ASSERT_EQ(run_cli("measure " + xyz + " " + cubes.large + " --method roving --heatmap-png " + points).exit_code, 0);
  EXPECT_EQ(png_size(points).first, 16 + 3 * 416 + 250);
  // Under --symmetric, one picture per direction, each named so.
  const std::string both = cubes.folder.file("both.png");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --symmetric --heatmap-png " + both).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(both));
  for (const char* name : {"both.A-to-B.png", "both.B-to-A.png"}) {
    EXPECT_EQ(png_size(cubes.folder.file(name)).first, 16 + 3 * 416 + 250) << name;
  }
  expect_error("measure " + cubes.pair + " --heatmap-png " + cubes.folder.path.string(), {"--heatmap-png", "directory"});
  // A picture that cannot be written fails the run, and the other outputs are not written either.
  const std::string json = cubes.folder.file("never.json");
  const std::string unwritable = cubes.folder.file("no-such-folder/h.png");
  expect_error("measure " + cubes.pair + " --json " + json + " --heatmap-png " + unwritable, {unwritable.c_str()});
  EXPECT_FALSE(std::filesystem::exists(json));
}

// A bad option value or combination is a usage error, exit 2 like a parse error, before any file
// is read; an error in an input file is exit 1.
TEST(CliReport, BadOptionValuesExitTwoAndBadFilesOne) {
  const Cubes cubes;
  for (const std::string& options :
       std::vector<std::string>{"--seed 3", "--views 0x3", "--max-error bogus", "--samples area:0", "--method nope", "--semantics far",
        "--heatmap-range -1", "--json " + cubes.folder.path.string()}) {
    const CliRun run = run_cli("measure " + cubes.pair + " " + options);
    EXPECT_EQ(run.exit_code, 2) << options << ": " << run.err;
    EXPECT_NE(run.err.find("see roving measure --help"), std::string::npos) << run.err;
  }
  EXPECT_EQ(run_cli("batch " + cubes.folder.path.string() + " " + cubes.folder.path.string() + " --shard 5/2").exit_code,
            2);
  EXPECT_EQ(run_cli("measure " + cubes.small + " " + cubes.folder.file("missing.obj")).exit_code, 1);
}

TEST(CliReport, TyposGetSuggestionsAndHelpListsEveryFormat) {
  const Cubes cubes;
  expect_error("mesure " + cubes.pair, {"unknown command 'mesure'", "did you mean 'measure'"});
  expect_error("measure " + cubes.pair + " --max-eror 3", {"unknown option '--max-eror'", "'--max-error'"});
  expect_error("measure " + cubes.pair + " --symetric", {"'--symmetric'"});
  const CliRun help = run_cli("measure --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* listed : {".obj", ".ply", ".off", ".stl", ".gltf", ".glb", ".3mf", ".bpt", ".xyz", ".binvox", "bezier", "--fail-above",
                             "--symmetric", "--seed", "--quiet"}) {
    EXPECT_NE(help.out.find(listed), std::string::npos) << listed;
  }
}

// The quality column (signed d) of a heat map's faces.
std::vector<double> heatmap_face_quality(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  std::size_t vertices = 0, faces = 0;
  while (std::getline(file, line) && line != "end_header") {
    std::sscanf(line.c_str(), "element vertex %zu", &vertices);
    std::sscanf(line.c_str(), "element face %zu", &faces);
  }
  for (std::size_t i = 0; i < vertices; ++i) std::getline(file, line);
  std::vector<double> quality;
  for (std::size_t i = 0; i < faces && std::getline(file, line); ++i) {
    quality.push_back(std::stod(line.substr(line.find_last_of(' ') + 1)));
  }
  return quality;
}

TEST(CliReport, SymmetricHeatMapsOnePerDirectionAndRefusesWhatHasOneDirection) {
  const Cubes cubes;
  const std::string h = cubes.folder.file("h.ply");
  ASSERT_EQ(run_cli("measure " + cubes.pair + " --symmetric --heatmap " + h).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(h));
  // A -> B on the small cube: the large one lies outside (+0.05); B -> A on the large: inside.
  const auto a_to_b = heatmap_face_quality(cubes.folder.file("h.A-to-B.ply"));
  const auto b_to_a = heatmap_face_quality(cubes.folder.file("h.B-to-A.ply"));
  ASSERT_EQ(a_to_b.size(), 12u);
  ASSERT_EQ(b_to_a.size(), 12u);
  for (double d : a_to_b) EXPECT_NEAR(d, 0.05, kFloatTolerance);
  for (double d : b_to_a) EXPECT_NEAR(d, -0.05, kFloatTolerance);
  const std::string xyz = cubes.folder.file("points.xyz", "0 0 0.5 0 0 1\n0.1 0 0.5 0 0 1\n0 0.1 0.5 0 0 1\n");
  // A point cloud as A is also B's test model: drawn as surfels, which 3 points cannot make.
  expect_error("measure " + xyz + " " + cubes.large + " --symmetric", {"points.xyz", "more than 8 points", "found 3"});
}

// Every field path of a JSON value: objects by dotted names, arrays of objects as NAME[].
void collect_paths(const nlohmann::json& json, const std::string& prefix, std::set<std::string>& out) {
  if (json.is_object()) {
    for (const auto& [key, value] : json.items()) collect_paths(value, prefix.empty() ? key : prefix + "." + key, out);
  } else if (json.is_array() && !json.empty() && json.front().is_object()) {
    for (const auto& value : json) collect_paths(value, prefix + "[]", out);
  } else {
    out.insert(prefix);
  }
}

// The backticked names in the first column of docs/report-json.md's tables.
std::set<std::string> documented_paths() {
  std::ifstream file(std::string(ROVING_SOURCE_DIR) + "/docs/report-json.md");
  std::set<std::string> paths;
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string cell = line.substr(1, line.find('|', 1) - 1);
    for (std::size_t open = cell.find('`'); open != std::string::npos; open = cell.find('`', open + 1)) {
      const std::size_t close = cell.find('`', open + 1);
      paths.insert(cell.substr(open + 1, close - open - 1));
      open = close;
    }
  }
  return paths;
}

bool documented(const std::string& path, const std::set<std::string>& documented) {
  if (documented.count(path)) return true;
  for (const std::string& pattern : documented) {  // NAME.* stands for every field under NAME
    if (pattern.size() > 2 && pattern.compare(pattern.size() - 2, 2, ".*") == 0 &&
        path.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0) {
      return true;
    }
  }
  return false;
}

TEST(CliReport, ColourFiguresGatesAndSamplesTable) {
  // Two cubes 0.05 apart whose vertex colours differ only in red, by 10: every compared hit
  // (faces lie parallel, so each line meets the same-numbered face) differs by exactly 10 in R'.
  const Folder folder;
  const std::string ref = folder.file("ref.ply", coloured_cube_ply(0.5, 200));
  const std::string test = folder.file("test.ply", coloured_cube_ply(0.55, 210));
  const std::string csv = folder.file("samples.csv");
  const CliRun run =
      run_cli("measure " + ref + " " + test + " --samples vertices --json - --samples-out " + csv);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto colour = nlohmann::json::parse(run.out)["colour"];
  EXPECT_EQ(colour["compared"], 8);
  EXPECT_NEAR(colour["rgb"]["r"]["mean_abs"].get<double>(), 10, 1e-4);
  EXPECT_NEAR(colour["rgb"]["r"]["psnr"].get<double>(), 20 * std::log10(25.5), 1e-4);
  EXPECT_TRUE(colour["rgb"]["b"]["psnr"].is_null()) << "an exact channel's PSNR is infinite: null";
  std::ifstream table(csv);
  std::string header, row;
  std::getline(table, header);
  std::getline(table, row);
  EXPECT_NE(header.find(",resolved_by,ref_r,ref_g,ref_b,test_r,test_g,test_b,delta_e"), std::string::npos)
      << header;
  EXPECT_NE(row.find(",200,0,200,210,0,200,"), std::string::npos) << row;

  // Gates on colour: a breach exits 3; a colour gate on models without colour is an error.
  const CliRun breached = run_cli("measure " + ref + " " + test + " --fail-above delta_e_mean=0.5");
  EXPECT_EQ(breached.exit_code, 3) << breached.err;
  EXPECT_NE(breached.err.find("gate breached: delta_e_mean"), std::string::npos) << breached.err;
  EXPECT_EQ(run_cli("measure " + ref + " " + test + " --fail-above colour_rms_y=2%").exit_code, 0);
  const std::string plain = folder.file("plain.obj", cube_obj(0.55));
  expect_error("measure " + ref + " " + plain + " --fail-above delta_e_max=1",
               {"delta_e_max", "nothing measured"});
  const CliRun one = run_cli("measure " + ref + " " + plain + " --json -");
  EXPECT_EQ(one.exit_code, 0);
  EXPECT_NE(one.err.find("has colour but"), std::string::npos) << one.err;
  EXPECT_FALSE(nlohmann::json::parse(one.out).contains("colour")) << "no colour: absent, not zero";

  // No hit within h: no colour figure at all (null, not zero), and a colour gate fails closed.
  const CliRun far =
      run_cli("measure " + ref + " " + test + " --max-error 0.01 --json - --fail-above delta_e_max=50");
  EXPECT_EQ(far.exit_code, 3) << far.err;
  EXPECT_NE(far.err.find("gate breached: delta_e_max has no value"), std::string::npos) << far.err;
  const auto far_colour = nlohmann::json::parse(far.out)["colour"];
  EXPECT_EQ(far_colour["compared"], 0);
  EXPECT_TRUE(far_colour["delta_e_mean"].is_null() && far_colour["rgb"]["r"]["rms"].is_null()) << far_colour;

  // A coloured point cloud as REF: each point's own colour (code values 0-255) against the cube's.
  const std::string points = folder.file(
      "points.xyz", "# x y z nx ny nz r g b\n0 0 0.5 0 0 1 190 5 200\n0.1 0 0.5 0 0 1 190 5 200.5\n");
  const CliRun cloud = run_cli("measure " + points + " " + test + " --max-error 0.2 --json -");
  ASSERT_EQ(cloud.exit_code, 0) << cloud.err;
  const auto cloud_json = nlohmann::json::parse(cloud.out);
  EXPECT_EQ(cloud_json["reference"]["colour"]["point_colours"], true);
  EXPECT_EQ(cloud_json["colour"]["compared"], 2);
  EXPECT_NEAR(cloud_json["colour"]["rgb"]["r"]["mean_abs"].get<double>(), 20, 1e-4);
  // G varies over the top face (vertices 4-7: 160, 200, 240, 24): (0, 0) is midway between 5 and 6,
  // (0.1, 0) lies in face (5, 7, 6) at u = 0.65 / 1.1, v = 1/2, where G = 416 - 216 u - 176 v.
  const double g_far = 416 - 216 * 0.65 / 1.1 - 88;
  EXPECT_NEAR(cloud_json["colour"]["rgb"]["g"]["mean_abs"].get<double>(), ((220 - 5) + (g_far - 5)) / 2,
              1e-4);
  EXPECT_NEAR(cloud_json["colour"]["rgb"]["b"]["mean_abs"].get<double>(), 0.25, 1e-4);
}

// --heatmap-of delta-e: the heat map of each sample's colour difference on the sequential map,
// its legend in delta E, from the same values as the samples table's delta_e; refused where a
// model has no colour and with a range in % of the diagonal.
TEST(CliReport, ColourHeatMapShowsEachSamplesDeltaE) {
  const Folder folder;
  const std::string ref = folder.file("ref.ply", coloured_cube_ply(0.5, 200));
  const std::string test = folder.file("test.ply", coloured_cube_ply(0.55, 210));
  const std::string ply = folder.file("de.ply"), png = folder.file("de.png"), csv = folder.file("s.csv");
  for (const char* method : {"embree", "roving", "v2v-kdtree"}) {
    SCOPED_TRACE(method);
    const CliRun run = run_cli("measure " + ref + " " + test + " --method " + method +
                               " --samples vertices --heatmap-of delta-e --heatmap-range 20 --heatmap " +
                               ply + " --heatmap-png " + png + " --samples-out " + csv);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::ifstream file(ply);
    const std::string text(std::istreambuf_iterator<char>(file), {});
    EXPECT_NE(text.find("colour difference, CIEDE2000 delta E"), std::string::npos) << text.substr(0, 400);
    EXPECT_NE(text.find("(per vertex)"), std::string::npos);
    // Vertex 0's delta E, as the samples table gives it, is its quality; its colour is YlOrRd's
    // at delta E / 20.
    std::ifstream table(csv);
    std::string header, row;
    std::getline(table, header);
    std::getline(table, row);
    const double delta_e = std::stod(csv_field(header, row, "delta_e"));
    EXPECT_GT(delta_e, 1);
    const auto c = roving::sequential_colour(delta_e / 20);
    std::istringstream lines(text.substr(text.find("end_header\n") + 11));
    double x, y, z, quality;
    int r, g, b;
    lines >> x >> y >> z >> r >> g >> b >> quality;
    EXPECT_NEAR(quality, delta_e, 1e-4 * delta_e);
    EXPECT_TRUE(r == c[0] && g == c[1] && b == c[2]) << r << ' ' << g << ' ' << b;
    EXPECT_EQ(png_size(png).first, 16 + 3 * 416 + 250);
  }
  const std::string plain = folder.file("plain.obj", cube_obj(0.55));
  expect_error("measure " + ref + " " + plain + " --heatmap-of delta-e --heatmap " + ply,
               {"--heatmap-of delta-e", "colour on both models", plain.c_str()});
  expect_error("measure " + ref + " " + test + " --heatmap-of delta-e --heatmap-range 5%",
               {"--heatmap-range", "5%"});
  expect_error("measure " + ref + " " + test + " --heatmap-of colour", {"--heatmap-of", "colour"});
}

TEST(CliReport, JsonLayoutIsTheDocumentedOne) {
  const Cubes cubes;
  const std::set<std::string> docs = documented_paths();
  ASSERT_GT(docs.size(), 50u) << "docs/report-json.md not found or not parsed";
  const std::string teapot = roving::testing::data_file("teapot.bpt");
  const std::string points = cubes.folder.file(
      "points.xyz",
      "# x y z nx ny nz r g b\n0 0 0.5 0 0 1 1 2 3\n0.1 0 0.5 0 0 1 4 5 6\n0 0.1 0.5 0 0 1 7 8 9\n");
  std::string grid_points = "//X,Y,Z,R,G,B,Nx,Ny,Nz\n";  // a 5 x 5 grid on the plane z = 0.55, in colour
  for (int i = 0; i < 25; ++i) {
    grid_points +=
        fmt::format("{} {} 0.55 {} 0 200 0 0 1\n", 0.25 * (i % 5) - 0.5, 0.25 * (i / 5) - 0.5, 10 * i);
  }
  const std::string grid = cubes.folder.file("grid.xyz", grid_points);
  const std::string coloured = cubes.folder.file("red.ply", coloured_cube_ply(0.5, 200)) + " " +
                               cubes.folder.file("redder.ply", coloured_cube_ply(0.55, 210));
  const std::string dtu = std::string(ROVING_SOURCE_DIR) + "/tests/data/dtu/";
  const std::string dtu_protocol = dtu + "Points/stl/stl001_total.ply " + dtu + "scan1_mesh.ply --protocol dtu " +
                                   "--dtu-obs-mask " + dtu + "ObsMask/ObsMask1_10.mat --dtu-plane " + dtu +
                                   "ObsMask/Plane1.mat --protocol-runs 2";
  const std::string tnt = std::string(ROVING_SOURCE_DIR) + "/tests/data/tnt/";
  const std::string tnt_protocol = tnt + "Bench.ply " + tnt + "Bench_mesh.ply --protocol tanks-and-temples --tnt-crop " +
                                   tnt + "Bench.json --tnt-alignment " + tnt + "Bench_trans.txt --tnt-scene Barn";
  const std::string igea = roving::testing::data_file("igea.ply");  // binary PLY, read a block at a time
  std::set<std::string> written;
  const auto check_layout = [&](const std::string& arguments, const CliRun& run) {
    ASSERT_EQ(run.exit_code, 0) << arguments << ": " << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["schema_version"], 3);
    std::set<std::string> paths;
    collect_paths(json, "", paths);
    for (const std::string& path : paths) {
      // A direction of a two-sided report has the one-sided layout.
      const std::string one_sided = path.rfind("directions[].", 0) == 0 && path != "directions[].label"
                                        ? path.substr(std::string("directions[].").size())
                                        : path;
      EXPECT_TRUE(documented(one_sided, docs)) << arguments << ": '" << path << "' is not in docs/report-json.md";
      written.insert(one_sided);
    }
  };
  // A shard's report, and the merge of two.
  std::string parts;
  for (const char* shard : {"0/2", "1/2"}) {
    const std::string part = cubes.folder.file(std::string("shard") + shard[0] + ".part");
    const std::string arguments = "measure " + cubes.pair + " --shard " + shard + " --shard-out " + part + " --json -";
    check_layout(arguments, run_cli(arguments));
    parts += " " + part;
  }
  check_layout("merge" + parts, run_cli("merge" + parts + " --json -"));
  for (const std::string& arguments :
       {coloured + " --symmetric", coloured + " --ibsm --ibsm-resolution 64", cubes.pair,
        cubes.pair + " --symmetric", cubes.pair + " --semantics closest", cubes.pair + " --samples area:auto",
        cubes.pair + " --symmetric --threshold 1%", cubes.pair + " --symmetric --threshold 1% --samples area:200",
        cubes.pair + " --symmetric --threshold 1% --threshold 10% --certify-thresholds",
        cubes.pair + " --method cooperative --views 4x2 --resolution 64",
        teapot + " " + teapot + " --samples area:100", points + " " + cubes.small,
        cubes.small + " " + grid, grid + " " + grid + " --samples vertices", points + " " + grid + " --pcc",
        points + " " + grid + " --pcc --pcc-neighbors-proc 3 --pcc-mse-space 8", coloured + " --pcc --samples area:500",
        coloured + " --pcc --samples area:500 --pcc-normal-calc-modification false", dtu_protocol, dtu_protocol + " --symmetric", tnt_protocol,
        tnt_protocol + " --symmetric", igea + " " + igea + " --chunk 100000"}) {
    check_layout(arguments, run_cli("measure " + arguments + " --json -"));
  }
  // And the document names nothing the tool no longer writes (voxels need a .binvox: not run here).
  for (const std::string& path : docs) {
    if (path.find(".*") != std::string::npos || path.find("voxels") != std::string::npos || path == "directions") {
      continue;
    }
    EXPECT_TRUE(written.count(path)) << "docs/report-json.md lists '" << path << "', which no run wrote";
  }
}

}  // namespace
