// The `roving` Python module: the library's measurement from file paths or NumPy arrays. It calls
// the same code as `roving measure` (no second implementation): the statistics come back as a
// dict, the per-sample distances and hit flags as NumPy arrays that own the library's buffers
// (no copy), and the library's errors as roving.Error with the same messages.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "roving/core/error.h"
#include "roving/core/statistics.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/model.h"

namespace py = pybind11;
using namespace roving;

namespace {

// A NumPy array that takes over `values` (moved to the heap, freed with the array).
template <class T>
py::array_t<T> adopt(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({owned->size()}, {sizeof(T)}, owned->data(), free_when_done);
}

py::dict statistics_dict(const Statistics& s) {
  py::dict d;
  d["siad"] = s.siad, d["usiad"] = s.usiad, d["std_signed"] = s.std_signed, d["std_unsigned"] = s.std_unsigned;
  d["rms"] = s.rms, d["min_signed"] = s.min_signed, d["max_signed"] = s.max_signed, d["max_abs"] = s.max_abs;
  d["p50"] = s.p50, d["p90"] = s.p90, d["p95"] = s.p95, d["p99"] = s.p99;
  d["siad_area"] = s.siad_area, d["usiad_area"] = s.usiad_area, d["rms_area"] = s.rms_area;
  d["siad_hits"] = s.siad_hits, d["usiad_hits"] = s.usiad_hits;
  return d;
}

struct Options {
  std::string method, semantics, views, backend;
  int resolution;
  std::string max_error;
  std::size_t histogram_bins = 64;
};

// Measures `samples` of a reference of diagonal `diagonal` against `test`, the GIL released.
py::dict measure_samples(const TriangleMesh& test, SampleSet samples, double diagonal, const Options& o) {
  GlMethodOptions gl;
  parse_views(o.views, gl);
  gl.backend = parse_gl_backend(o.backend);
  gl.resolution = o.resolution;
  const auto method = make_method(o.method, gl);
  DistanceOptions options;
  options.semantics = o.semantics.empty() ? method->supported_semantics().front() : parse_semantics(o.semantics);
  options.max_error = parse_max_error(o.max_error).resolve(diagonal);
  DistanceResult result;
  Statistics statistics;
  {
    py::gil_scoped_release release;
    result = measure_distances(*method, test, samples, options);
    statistics = compute_statistics(result.signed_distance, result.hit, samples.weights, options.max_error,
                                    o.histogram_bins);
  }
  py::dict out;
  out["method"] = method->name();
  out["semantics"] = to_string(options.semantics);
  out["max_error"] = options.max_error;
  out["diagonal"] = diagonal;
  out["samples"] = samples.size();
  out["hits"] = statistics.hit_count;
  out["no_hits"] = statistics.no_hit_count;
  out["statistics"] = statistics_dict(statistics);
  out["seconds"] = py::dict(py::arg("build") = result.build_seconds, py::arg("query") = result.query_seconds);
  if (result.gl) {
    out["observations"] = result.gl->observations();
    out["views_rendered"] = result.gl->views_rendered;
    out["sample_cameras"] = result.gl->sample_cameras;
  }
  // d of a no-hit is meaningless: 0 in the buffer, told apart by `hit`.
  out["distance"] = adopt(std::move(result.signed_distance));
  out["hit"] = adopt(std::move(result.hit)).attr("view")("bool");  // 0/1 bytes read as bool: no copy
  out["positions"] = py::array_t<double>({samples.size(), std::size_t{3}},
                                         reinterpret_cast<const double*>(samples.positions.data()));
  return out;
}

// An N x 3 array of `what` (float64 or int64 after NumPy's conversion), checked.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> rows_of_three(const py::handle& array, const char* what) {
  auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(1) != 3) {
    throw Error(std::string(what) + ": expected an N x 3 array, found " +
                (a ? std::to_string(a.ndim()) + " dimensions" : std::string("something that is not an array")));
  }
  return a;
}

TriangleMesh mesh_from_arrays(const py::handle& vertices, const py::handle& faces, const char* name) {
  const auto v = rows_of_three<double>(vertices, (std::string(name) + " vertices").c_str());
  const auto f = rows_of_three<long long>(faces, (std::string(name) + " faces").c_str());
  std::vector<Vec3> positions(v.shape(0));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) positions[i] = Vec3(v.at(i, 0), v.at(i, 1), v.at(i, 2));
  std::vector<Triangle> triangles(f.shape(0));
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    for (int c = 0; c < 3; ++c) {
      const long long index = f.at(i, c);
      if (index < 0 || index >= v.shape(0)) {
        throw Error(std::string(name) + " faces: face " + std::to_string(i) + " refers to vertex " +
                    std::to_string(index) + "; expected an index in [0, " + std::to_string(v.shape(0)) + ")");
      }
      triangles[i][c] = static_cast<int>(index);
    }
  }
  return TriangleMesh(std::move(positions), std::move(triangles), std::string(name) + " arrays");
}

}  // namespace

PYBIND11_MODULE(roving, m) {
  m.doc() = "Shape dissimilarity between 3D models: Z-buffer surface roving, Embree and CGAL references, baselines";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.attr("methods") = method_names();

  m.def(
      "measure",
      [](const std::string& reference, const std::string& test, const std::string& method,
         const std::string& semantics, const std::string& samples, const std::string& max_error,
         const std::string& views, int resolution, const std::string& backend) {
        const Model ref = load_model(reference), tst = load_model(test);
        SampleSet sample_set = reference_samples(ref, parse_sample_spec(samples));
        return measure_samples(test_surface(tst), std::move(sample_set), ref.bounding_box().diagonal(),
                               {method, semantics, views, backend, resolution, max_error});
      },
      py::arg("reference"), py::arg("test"), py::arg("method") = "embree", py::arg("semantics") = "",
      py::arg("samples") = "faces", py::arg("max_error") = "5%", py::arg("views") = "24x12",
      py::arg("resolution") = 1024, py::arg("backend") = "",
      R"doc(Measures the reference model's samples against the test model, as `roving measure REF TEST` does.

Arguments:
  reference   path of the reference model (REF): .obj .ply .off .stl .gltf .glb .3mf, voxels
              (.binvox), Bezier patches (.bpt) or a point cloud (.xyz, .ply without faces)
  test        path of the test model (TEST), the same formats; a point cloud is drawn as surfels
  method      one of roving.methods: 'embree' and 'cgal' (exact references), 'roving',
              'viewpoint', 'cooperative' (the paper's GL methods), 'v2v-naive', 'v2v-kdtree',
              'v2p-naive', 'v2p-aabb' (baselines, closest semantics only)
  semantics   'first-hit' (the paper's), 'nearest' or 'closest' (Metro style); '' takes the
              method's default (first-hit, closest for the baselines)
  samples     'faces' (triangle centroids), 'vertices' or 'area:N' (N points uniform by area)
  max_error   h, the acceptance threshold along the normal: a length in model units ('0.5') or a
              percentage of REF's bounding-box diagonal ('5%'); a no-hit counts as d = +h
  views       the GL methods' view directions 'HxV' (e.g. '24x12'), or 'auto' / 'auto:HxV'
  resolution  the GL views' size in pixels (viewpoint and cooperative)
  backend     'osmesa' (Mesa's llvmpipe, always there) or 'egl' (a GPU where a driver exists); by
              default $ROVING_GL_BACKEND, else 'osmesa'

Returns a dict: 'statistics' (siad, usiad, rms, max_abs, the percentiles, the area-weighted forms, ...:
the JSON report's statistics), 'distance' (signed d per sample; 0 where 'hit' is False), 'hit' (bool per
sample), 'positions' (the samples, K x 3), 'method', 'semantics', 'max_error' (h in model units),
'diagonal', 'samples', 'hits', 'no_hits', 'seconds' (build, query), and for the GL methods
'observations', 'views_rendered' and 'sample_cameras'.
Raises roving.Error (a ValueError) with a one-line message naming the file or argument.)doc");

  m.def(
      "measure_arrays",
      [](const py::handle& reference_vertices, const py::handle& reference_faces,
         const py::handle& test_vertices, const py::handle& test_faces, const py::object& sample_points,
         const py::object& sample_normals, const std::string& method, const std::string& semantics,
         const std::string& samples, const std::string& max_error, const std::string& views, int resolution,
         const std::string& backend) {
        const TriangleMesh reference = mesh_from_arrays(reference_vertices, reference_faces, "reference");
        const TriangleMesh test = mesh_from_arrays(test_vertices, test_faces, "test");
        SampleSet sample_set;
        if (sample_points.is_none() != sample_normals.is_none()) {
          throw Error("sample_points and sample_normals: expected both or neither");
        }
        if (sample_points.is_none()) {
          sample_set = make_samples(reference, parse_sample_spec(samples));
        } else {
          const auto p = rows_of_three<double>(sample_points, "sample_points");
          const auto n = rows_of_three<double>(sample_normals, "sample_normals");
          if (p.shape(0) != n.shape(0) || p.shape(0) == 0) {
            throw Error("sample_points and sample_normals: expected the same number (> 0) of rows, found " +
                        std::to_string(p.shape(0)) + " and " + std::to_string(n.shape(0)));
          }
          sample_set.kind = "given";
          for (py::ssize_t i = 0; i < p.shape(0); ++i) {
            const Vec3 normal(n.at(i, 0), n.at(i, 1), n.at(i, 2));
            if (!(normal.norm() > 0) || !std::isfinite(normal.norm())) {
              throw Error("sample_normals: row " + std::to_string(i) + " is not a finite non-zero vector");
            }
            sample_set.positions.emplace_back(p.at(i, 0), p.at(i, 1), p.at(i, 2));
            sample_set.normals.push_back(normal.normalized());
            sample_set.weights.push_back(1.0);
          }
        }
        return measure_samples(test, std::move(sample_set), reference.bounding_box().diagonal(),
                               {method, semantics, views, backend, resolution, max_error});
      },
      py::arg("reference_vertices"), py::arg("reference_faces"), py::arg("test_vertices"),
      py::arg("test_faces"), py::arg("sample_points") = py::none(), py::arg("sample_normals") = py::none(),
      py::arg("method") = "embree", py::arg("semantics") = "", py::arg("samples") = "faces",
      py::arg("max_error") = "5%", py::arg("views") = "24x12", py::arg("resolution") = 1024,
      py::arg("backend") = "",
      R"doc(Measures a reference mesh against a test mesh given as NumPy arrays.

Arguments:
  reference_vertices, test_vertices  float arrays N x 3 (finite coordinates)
  reference_faces, test_faces        integer arrays M x 3 of vertex indices (0-based, in range)
  sample_points, sample_normals      optional float arrays K x 3: the samples to measure from and
                                     their normals (non-zero; normalised here); both or neither.
                                     Without them the samples are made on the reference by 'samples'
  method, semantics, samples, max_error, views, resolution, backend
                                     as in roving.measure; max_error's percentage is of the
                                     reference's bounding-box diagonal

Returns the same dict as roving.measure. Raises roving.Error naming the array and what was wrong.)doc");
}
