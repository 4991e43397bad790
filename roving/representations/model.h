// Models of every representation the paper names, as a reference (its samples) or a test (the
// surface the methods draw and intersect).
#pragma once

#include <optional>
#include <string>

#include "roving/core/bezier_patches.h"
#include "roving/core/point_cloud.h"
#include "roving/core/sample_set.h"
#include "roving/core/voxel_grid.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/representations/surfels.h"

namespace roving {

enum class ModelType { Mesh, Points, Voxels, Bezier };
const char* to_string(ModelType type);
// Parses "mesh", "points", "voxels" or "bezier"; throws roving::Error naming `option` otherwise.
ModelType parse_model_type(const std::string& text, const std::string& option);

struct Model {
  ModelType type = ModelType::Mesh;
  // The surface: the mesh itself, the voxels' exposed faces, or the patches' tessellation;
  // empty for a point cloud.
  LoadedMesh mesh;
  std::optional<VoxelGrid> voxels;
  std::optional<BezierSurface> bezier;
  std::size_t patches_flipped = 0;  // to orient them consistently and outward
  int bezier_cells = 0;             // tessellation cells per patch side
  double chordal_error_bound = 0;   // of that tessellation, model units
  PointCloud points;
  bool normals_estimated = false;  // point cloud without normals in its file
  // --pcc (load_for): a point cloud not read yet; MPEG's figures read its file straight into their
  // single precision (mpeg_points of a PackedPointCloud), and `points` stays empty.
  bool points_in_file = false;
  // A protocol's model (load_for): a mesh file read as its vertices alone, its faces left unread, as
  // Open3D's read_point_cloud reads a mesh; `points` holds the vertices, `type` is Points.
  bool mesh_vertices_only = false;
  // A Tanks and Temples model (load_for): points with a non-finite coordinate left out, as the
  // toolbox's crop leaves them out; how many.
  std::size_t non_finite_dropped = 0;
  // A point cloud's surfels, made the first time it is the test model (test_surface).
  mutable std::optional<SurfelSurface> surfels;

  const std::string& path() const { return mesh.path; }
  BoundingBox bounding_box() const;
};

// Loads `path` as `type`, or by extension when none is given: .obj .off .stl meshes; .ply a
// mesh, or a point cloud when its header declares no faces; .binvox voxels; .xyz points; .bpt
// Bezier patches, tessellated so that the chordal error stays below 1e-4 of the control net's
// box diagonal (far below any distance worth measuring; the bound is reported), after the
// patches are oriented consistently and outward.
// Point clouds without normals get PCA normals (k = 12), oriented consistently and outward.
Model load_model(const std::string& path, std::optional<ModelType> type = std::nullopt);

// The type load_model reads `path` as without a type given: by extension, and for .ply by whether
// its header declares faces.
ModelType model_type_of(const std::string& path);

// A point-cloud file's points as the file has them (no normals estimated, none normalised), for
// figures defined on the points themselves (MPEG's). Throws roving::Error naming `path` where it is
// not a point cloud (by `type`, else by extension and header).
PointCloud load_point_cloud(const std::string& path, std::optional<ModelType> type = std::nullopt);

// Models of what is already in memory, `name` standing for a path in messages and reports: a mesh
// (checked as its constructor checks it), or a point cloud (finite points; normals, where given,
// one per point, non-zero, normalised here unless not `unit_normals` (MPEG's figures use them as
// given, as load_point_cloud keeps a file's); where not, estimated as load_model does; colours one
// per point or none). Throw roving::Error naming `name` as load_model does.
Model model_from_mesh(TriangleMesh mesh, const std::string& name);
Model model_from_points(PointCloud points, const std::string& name, bool unit_normals = true);

// Samples on a reference model: a mesh's faces / vertices / area:N; a voxel model's exposed-face
// centres with axis normals (faces) or area:N on its exposed faces; a point cloud's own points
// and normals (faces or vertices); Bezier patches by exact evaluation (faces: cell centres of the
// tessellation grid, vertices: its nodes, area:N uniform by area). Throws roving::Error naming `--samples`
// for a kind the representation does not have.
SampleSet reference_samples(const Model& reference, const SampleSpec& spec);
// The same samples; a mesh reference gives up its geometry to make them (make_samples_releasing).
SampleSet reference_samples_releasing(Model& reference, const SampleSpec& spec);

// The surface a test model offers: a point cloud's surfels (made on the first call, which
// throws roving::Error for what make_surfels refuses), or the model's own triangles.
const TriangleMesh& test_surface(const Model& test);

}  // namespace roving
