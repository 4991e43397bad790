// The colour table: sample-based colour figures by every method, and IBSM, on degraded copies.
#include "colour_study.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "coloured.h"
#include "decimate.h"
#include "roving/core/colour.h"
#include "roving/core/colour_statistics.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/images_and_matlab/texture_io.h"
#include "roving/gl_methods/image_based.h"
#include "roving/registry/method_registry.h"

namespace roving {
namespace {

namespace fs = std::filesystem;

struct ColourPair {
  std::string name, how;
  TriangleMesh reference, test;
};

// `texture` after a JPEG round trip at `quality`, through libjpeg-turbo as a user's file would go.
Texture through_jpeg(const Texture& texture, int quality) {
  const fs::path file =
      fs::temp_directory_path() / fmt::format("roving-bench-{}-q{}.jpg", ::getpid(), quality);
  write_texture(texture, file.string(), quality);
  Texture decoded = read_texture(file.string());
  fs::remove(file);
  return decoded;
}

// The pairs: REF coloured by the field, TEST degraded.
std::vector<ColourPair> colour_pairs_of(const TriangleMesh& bunny, const TriangleMesh* rocker_arm,
                                        bool quick) {
  const BoundingBox box = bunny.bounding_box();
  const auto unit = [box](const Vec3& p) { return Vec3((p - box.min).cwiseQuotient(box.size())); };
  const auto whole = [](std::vector<Colour> colours) {
    for (Colour& c : colours) c = c.array().round().matrix();
    return colours;
  };
  std::vector<ColourPair> pairs;
  TriangleMesh coloured = bunny;
  coloured.set_vertex_colours(whole(procedural_colours(bunny)));
  TriangleMesh decimated = decimate_quadric(bunny, 10459);
  decimated.set_vertex_colours(whole(procedural_colours(decimated, box)));
  pairs.push_back({"vertex colours, decimated to 10,459", "quadric decimation, the field at its vertices",
                   coloured, decimated});
  if (!quick) {
    TriangleMesh quantised_colours = coloured;
    quantised_colours.set_vertex_colours(quantised(coloured.vertex_colours(), 4));
    pairs.push_back(
        {"vertex colours, 4 bits", "each channel quantised to 16 levels", coloured, quantised_colours});
  }
  const int side = 2048;  // the bunny's 69,451 cells at 7 texels each
  const auto field = [unit](const Vec3& p) { return detailed_colour(unit(p), 24); };
  const TriangleMesh textured = with_baked_atlas(bunny, side, field);
  const Texture& atlas = *textured.texture_mapping()->materials[0].texture;
  const auto retextured = [&](Texture t) {
    TextureMapping mapping = *textured.texture_mapping();
    mapping.materials[0].texture = std::make_shared<Texture>(std::move(t));
    TriangleMesh m = bunny;
    m.set_texture_mapping(std::move(mapping));
    return m;
  };
  for (const int quality : quick ? std::vector<int>{20} : std::vector<int>{90, 50, 20}) {
    pairs.push_back({fmt::format("atlas, JPEG quality {}", quality), "the atlas through libjpeg-turbo",
                     textured, retextured(through_jpeg(atlas, quality))});
  }
  if (!quick) {
    pairs.push_back(
        {"atlas, downsampled 4x", "2 x 2 box filter, twice", textured, retextured(downsampled(atlas, 2))});
    pairs.push_back(
        {"atlas, 4 bits", "each channel quantised to 16 levels", textured, retextured(quantised(atlas, 4))});
  }
  pairs.push_back({"atlas, decimated to 17,362", "quadric decimation, its atlas baked again from the field",
                   textured, with_baked_atlas(decimate_quadric(bunny, 17362), side, field)});
  if (!quick) {
    // A continuous parametrization (the texture projected along z), which a decimation keeps: the
    // quadric decimater collapses edges onto existing vertices, each keeping its coordinates.
    const auto projected = std::make_shared<Texture>(procedural_texture(1024, 0, 40));
    pairs.push_back({"projected texture, decimated to 17,362 (UVs kept)",
                     "quadric decimation, the same texture", with_planar_texture(bunny, projected, {}, box),
                     with_planar_texture(decimate_quadric(bunny, 17362), projected, {}, box)});
    // Beyond the bunny: the Rocker Arm's own atlas through JPEG.
    const BoundingBox rocker_box = rocker_arm->bounding_box();
    const TriangleMesh rocker_atlas = with_baked_atlas(*rocker_arm, side, [rocker_box](const Vec3& p) {
      return detailed_colour((p - rocker_box.min).cwiseQuotient(rocker_box.size()), 24);
    });
    TextureMapping jpeg = *rocker_atlas.texture_mapping();
    jpeg.materials[0].texture = std::make_shared<Texture>(through_jpeg(*jpeg.materials[0].texture, 50));
    TriangleMesh rocker_jpeg = *rocker_arm;
    rocker_jpeg.set_texture_mapping(std::move(jpeg));
    pairs.push_back({"Rocker Arm atlas, JPEG quality 50",
                     "the Rocker Arm (20,088 triangles) with its own atlas", rocker_atlas, rocker_jpeg});
  }
  return pairs;
}

// Colour figures over `mask` (the samples a method and Embree both hit).
ColourStatistics over(const ColourPairs& pairs, const std::vector<std::uint8_t>& mask) {
  return compute_colour_statistics(pairs, mask);
}

}  // namespace

ColourStudy colour_study(const TriangleMesh& bunny, const TriangleMesh* rocker_arm, bool quick,
                         GlBackend backend, const std::function<void(const std::string&)>& step) {
  ColourStudy study;
  const double h = 0.05 * bunny.bounding_box().diagonal();
  const std::vector<std::string> methods =
      quick ? std::vector<std::string>{"embree", "roving", "cooperative"}
            : std::vector<std::string>{"embree", "cgal", "roving", "cooperative", "viewpoint"};
  ReportTable t{
      "Colour: sample-based figures by every method, and MPEG's image-based IBSM",
      {"pair", "samples", "method", "compared", "PSNR Y'CbCr 6:1:1 (dB)", "PSNR R'G'B' (dB)", "delta E mean",
       "delta E p95", "within 1 step of Embree", "PSNR 6:1:1 - Embree's (dB)", "seconds"},
      {},
      {}};
  ReportTable ib{"Colour: the two correspondences side by side",
                 {"pair", "face samples: PSNR 6:1:1 (dB)", "area samples: PSNR 6:1:1 (dB)",
                  "IBSM: PSNR 6:1:1 (dB)", "face samples: PSNR R'G'B'", "area samples: PSNR R'G'B'",
                  "IBSM: PSNR R'G'B'", "IBSM: depth PSNR (dB)", "IBSM: unmatched pixels (%)", "IBSM (s)"},
                 {},
                 {}};
  // Face samples (the paper's) and vertex samples (where faces meet: seams) in full; area-uniform
  // ones beside IBSM, weighting every point of the surface alike as IBSM's pixels roughly do.
  const std::size_t sample_count = quick ? 8000 : 0;
  const std::size_t area_count = quick ? 8000 : 200000;
  std::vector<SampleSpec> kinds;
  if (quick) {
    kinds.push_back({SampleSpec::Kind::Area, sample_count});
  } else {
    kinds.push_back({});
    kinds.push_back({SampleSpec::Kind::Vertices});
  }
  ImageBasedOptions image_options;
  image_options.backend = backend;
  if (quick) image_options.resolution = 512;
  for (const ColourPair& pair : colour_pairs_of(bunny, rocker_arm, quick)) {
    step("colour: " + pair.name);
    double faces_611 = NAN, faces_rgb = NAN;  // N/A in quick mode: area samples only
    for (const SampleSpec& kind : kinds) {
      const SampleSet samples = make_samples(pair.reference, kind);
      const std::vector<Colour> reference_colours = sample_colours(pair.reference, samples);
      DistanceResult embree;
      ColourPairs exact;
      for (const std::string& name : methods) {
        GlMethodOptions gl;
        gl.backend = backend;
        auto method = make_method(name, gl);
        const Stopwatch watch;
        const DistanceResult r =
            measure_distances(*method, pair.test, samples, {Semantics::FirstHit, h, true});
        const ColourPairs colours =
            colour_pairs(reference_colours, samples, pair.test, r, Semantics::FirstHit);
        const double seconds = watch.seconds();
        const ColourStatistics all = compute_colour_statistics(colours, r.hit);
        std::string within = "(itself)", difference = "";
        if (name == "embree") {
          embree = r, exact = colours;
          if (kind.kind == SampleSpec::Kind::Faces) faces_611 = all.psnr_ycbcr_611, faces_rgb = all.psnr_rgb;
        } else {
          // Checked before shown: on the samples both hit, within one step of Embree on >= 99.9%,
          // PSNRs within 0.1 dB (CGAL: the same to rounding).
          std::vector<std::uint8_t> both(samples.size(), 0);
          std::size_t common = 0, close = 0;
          for (std::size_t k = 0; k < samples.size(); ++k) {
            if (!r.hit[k] || !embree.hit[k]) continue;
            both[k] = 1, ++common;
            close += (colours.test[k] - exact.test[k]).cwiseAbs().maxCoeff() <= 1;
          }
          const ColourStatistics mine = over(colours, both), theirs = over(exact, both);
          const double fraction = double(close) / double(std::max<std::size_t>(common, 1));
          const double d611 = mine.psnr_ycbcr_611 - theirs.psnr_ycbcr_611,
                       drgb = mine.psnr_rgb - theirs.psnr_rgb;
          const double limit = name == "cgal" ? 1e-6 : 0.1;
          // Nothing compared (viewpoint sampling alone where TEST's geometry is REF's): no
          // figure to show or check.
          if (common > 0 && (fraction < 0.999 || !(std::abs(d611) <= limit) || !(std::abs(drgb) <= limit))) {
            study.failures.push_back(fmt::format(
                "colour, {}, {} samples, {}: {:.4f}% within a step of Embree, PSNR {:+.3g} / {:+.3g} dB",
                pair.name, samples.kind, name, 100 * fraction, d611, drgb));
          }
          within = common > 0 ? fmt::format("{:.3f}%", 100 * fraction) : "(none compared)";
          difference = common > 0 ? fmt::format("{:+.4f}", d611) : "";
        }
        study.figures[fmt::format("colour/{}/{}/{}/psnr_611", pair.name, samples.kind, name)] =
            all.psnr_ycbcr_611;
        t.rows.push_back({pair.name, samples.kind, name, fmt::format("{}", all.compared),
                          figure(all.psnr_ycbcr_611, 2), figure(all.psnr_rgb, 2), figure(all.delta_e_mean, 3),
                          figure(all.delta_e_p95, 3), within, difference, figure(seconds, 3)});
        if (name == "cooperative" && pair.name == "atlas, JPEG quality 20" &&
            kind.kind != SampleSpec::Kind::Vertices) {
          ColourStudy::PictureJob job;
          job.file = quick ? "colour-jpeg20-quick.png" : "colour-jpeg20.png";
          job.caption =
              "the bunny's atlas against its JPEG at quality 20: delta E at each face, by the cooperative "
              "method";
          const HeatmapLayout faces = sample_count ? HeatmapLayout{HeatmapElement::Points, 1}
                                                   : HeatmapLayout{HeatmapElement::Faces, 1};
          const std::vector<float> delta_e = sample_delta_e(colours, r.hit);
          const HeatmapScale scale{HeatmapQuantity::DeltaE, percentile_99(delta_e, 1)};
          job.picture.title = "bunny (atlas) against its JPEG at quality 20";
          job.picture.subtitle = fmt::format(
              "colour difference by cooperative (24x12), {} samples; CIEDE2000 mean {:.3g}, p95 {:.3g}",
              samples.size(), all.delta_e_mean, all.delta_e_p95);
          job.picture.legend.quantity = HeatmapQuantity::DeltaE;
          job.picture.legend.range = scale.range;
          job.picture.legend.no_value_label = "no hit: no colour";
          job.surface = coloured_surface(
              &pair.reference, faces, samples,
              heatmap_colours(heatmap_values(&pair.reference, faces, samples, delta_e), scale));
          study.pictures.push_back(std::move(job));
        }
      }
    }
    // Embree's figures on area-uniform samples: each point of the surface weighted alike.
    const SampleSet area = make_samples(pair.reference, {SampleSpec::Kind::Area, area_count});
    auto embree = make_method("embree");
    const DistanceResult on_area =
        measure_distances(*embree, pair.test, area, {Semantics::FirstHit, h, true});
    const ColourStatistics area_all = compute_colour_statistics(
        colour_pairs(sample_colours(pair.reference, area), area, pair.test, on_area, Semantics::FirstHit),
        on_area.hit);
    const ImageBasedResult image = image_based_comparison(pair.reference, pair.test, image_options);
    study.figures[fmt::format("colour/{}/ibsm/psnr_611", pair.name)] = image.psnr_ycbcr_611;
    ib.rows.push_back({pair.name, figure(faces_611, 2), figure(area_all.psnr_ycbcr_611, 2),
                       figure(image.psnr_ycbcr_611, 2), figure(faces_rgb, 2), figure(area_all.psnr_rgb, 2),
                       figure(image.psnr_rgb, 2), figure(image.depth_psnr, 2),
                       figure(image.unmatched_percent, 3), figure(image.seconds, 2)});
  }
  t.settings = fmt::format(
      "REF the normalised bunny (or Rocker Arm) coloured by one procedural field, as vertex colours, as a "
      "baked per-triangle texture atlas ({} texels a side) or as a texture projected along z; TEST degraded "
      "as "
      "the pair says. {}, h = 5%, first hit. "
      "Colour "
      "figures are over each method's compared hits (TEST's colour where d was measured: on the hit's face "
      "for "
      "Embree and CGAL, drawn in the frame buffer for the GL methods). Each non-Embree row was checked "
      "against "
      "Embree on the samples both hit before it is shown: within one 8-bit step in every channel on >= 99.9% "
      "of "
      "them, PSNRs within 0.1 dB (CGAL: 1e-6). Viewpoint sampling alone accepts only distances a view can "
      "certify to 1%, so where TEST's geometry is REF's (d = 0: the colour-only pairs) it compares almost no "
      "samples, and its figures there say nothing; the cooperative method hands those samples to its "
      "cameras. "
      "Seconds: build, query and colour, one run, this machine.",
      2048,
      sample_count
          ? fmt::format("{} area-uniform samples", sample_count)
          : "Face samples (69,451; on the Rocker Arm 20,088) and vertex samples (34,834; 10,044), where "
            "faces meet: every vertex of the atlas is a seam, and there the GL methods take the "
            "colour of the face the exact rule takes"),
  ib.settings = fmt::format(
      "The same pairs: Embree's sample-based figures, on face samples (one per triangle, at its centroid) "
      "and on {} area-uniform samples (every point of the surface alike), against IBSM (`roving measure "
      "--ibsm`: {} orthographic views on "
      "a Fibonacci sphere, {} pixels a side, back faces culled, 8-bit colours over the pixels both models "
      "cover).",
      area_count, image_options.views, image_options.resolution);
  study.tables = {t, ib};
  study.notes =
      "## How the models were made\n\n"
      "`roving-datasets --colour` writes the same models as files (PLY, OBJ + MTL + PNG/JPEG, glTF); this "
      "table makes "
      "them in memory by the same code (`datasets_gen/coloured.cpp`). The field: R and G slow sinusoids "
      "across the "
      "bunny's box, B a ramp in z (`procedural_colour`); on the atlas G is also banded with 24 periods along "
      "the box's "
      "diagonal (`detailed_colour`), detail that downsampling and JPEG lose. The atlas gives every triangle "
      "its own "
      "square cell (MeshLab's trivial per-triangle parametrization), its corners one texel in from the "
      "cell's "
      "edges, every texel of the cell the field at the point its centre maps to on the triangle's plane, so "
      "bilinear "
      "sampling inside the triangle reads only its cell. Degradations: JPEG through libjpeg-turbo at the "
      "quality "
      "given (4:2:0); 2 x 2 box-filter downsampling (a 4x downsampled atlas bleeds across cells, as "
      "downsampling an "
      "atlas without gutters does); quantisation to 16 levels a channel; quadric decimation (OpenMesh) with "
      "the field "
      "sampled again at the new vertices, or the atlas baked again for the decimated mesh, or, for a texture "
      "projected along z (a continuous parametrization, 1,024 texels a side with 40 bands in G), its "
      "coordinates "
      "kept: the decimater collapses edges onto existing vertices.\n\n"
      "## What the two correspondences measure\n\n"
      "Our figures pair each sample of REF with the point where its normal line meets TEST: a colour error "
      "is "
      "measured where the surfaces correspond. IBSM pairs the pixels of two renderings: what each model "
      "shows along "
      "the same line of sight. Where TEST's geometry is REF's (the texture-only pairs) both pair the same "
      "points "
      "and differ by how they weight them: IBSM by projected area over 16 views, back faces culled, in 8-bit "
      "pixels "
      "; ours by sample. Where the geometry moves (the "
      "decimated pairs), a pixel near a silhouette or a step sees a different part of the surface on each "
      "model and "
      "IBSM counts that as colour error as well, while its depth PSNR and unmatched pixels show the "
      "geometric change; "
      "ours keeps the colour error apart from the distance, which the tables of results/README.md report.\n";
  return study;
}

}  // namespace roving
