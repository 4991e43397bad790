"""The Python module: the CLI's JSON report field by field, per-sample arrays without a copy, the
meshes Python code holds (arrays, mesh-like objects, Open3D), the CLI's errors, batch, and no memory
growth over many calls."""
import csv
import json
import math
import os
import types
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

import roving

CLI = os.environ["ROVING_CLI"]
SOURCE = os.environ["ROVING_SOURCE_DIR"]
DATA = os.environ.get("ROVING_DATA") or os.path.join(SOURCE, "data")
MPEG = os.path.join(SOURCE, "tests", "data", "mpeg")
DTU = os.path.join(SOURCE, "tests", "data", "dtu")
TNT = os.path.join(SOURCE, "tests", "data", "tnt")
BUNNY = os.path.join(DATA, "stanford-bunny.obj")
FANDISK = os.path.join(DATA, "fandisk.obj")
IBSM = os.path.join(SOURCE, "tests", "ibsm")


def cube(half_side):
    """A closed box [-s, s]^3 with outward faces."""
    vertices = np.array([[(half_side if i & 1 else -half_side), (half_side if i & 2 else -half_side),
                          (half_side if i & 4 else -half_side)] for i in range(8)])
    faces = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                      [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return vertices, faces


def cli_json(reference, test, options):
    """`roving measure REF TEST --json -` with the same options, as Python names them."""
    arguments = [CLI, "measure", reference, test, "--json", "-"]
    for key, value in options.items():
        option = "--" + key.replace("_", "-")
        if value is True:
            arguments.append(option)
        else:
            arguments += [option, str(value)]
    run = subprocess.run(arguments, capture_output=True, text=True)
    assert run.returncode in (0, 3), run.stderr  # 3: a --fail-above gate breached
    return json.loads(run.stdout)


def assert_same(cli, py, where="report"):
    """Every field of the CLI's report is in Python's, equal (numbers bit for bit); times and the
    command line differ by nature and are skipped."""
    if isinstance(cli, dict):
        assert isinstance(py, dict), where
        for key, value in cli.items():
            if "seconds" in key or key == "command_line":
                continue
            assert key in py, f"{where}.{key} missing"
            assert_same(value, py[key], f"{where}.{key}")
    elif isinstance(cli, list):
        assert isinstance(py, list) and len(py) == len(cli), where
        for i, (a, b) in enumerate(zip(cli, py)):
            assert_same(a, b, f"{where}[{i}]")
    elif isinstance(cli, float) and math.isnan(cli):
        assert isinstance(py, float) and math.isnan(py), where
    else:
        assert type(cli) is type(py) and cli == py, f"{where}: CLI {cli!r}, Python {py!r}"


@pytest.mark.parametrize("pair,options", [
    ((BUNNY, FANDISK), {}),
    ((BUNNY, FANDISK), {"method": "cgal", "semantics": "nearest", "samples": "area:2000"}),
    ((BUNNY, FANDISK), {"semantics": "closest", "samples": "area:3000", "seed": 7, "histogram_bins": 16}),
    ((BUNNY, FANDISK), {"symmetric": True, "samples": "vertices", "max_error": "2%"}),
    ((BUNNY, FANDISK), {"method": "roving", "samples": "area:2000", "fail_above": "usiad=1e-9"}),
    ((BUNNY, FANDISK), {"method": "v2p-aabb", "samples": "area:1000", "hausdorff_bound": "none"}),
    ((os.path.join(IBSM, "torus-a.obj"), os.path.join(IBSM, "torus-b.obj")),
     {"method": "cooperative", "samples": "area:2000", "ibsm": True, "ibsm_resolution": 128}),
    ((os.path.join(MPEG, "sphere10_a.ply"), os.path.join(MPEG, "sphere10_b.ply")), {"pcc": True, "pcc_resolution": 1023}),
    ((os.path.join(MPEG, "sphere10_a_bare.ply"), os.path.join(MPEG, "sphere10_b.ply")),
     {"pcc": True, "pcc_normals": os.path.join(MPEG, "sphere10_a_normals.ply")}),
    ((os.path.join(MPEG, "blob_float_a.ply"), os.path.join(MPEG, "blob_float_b.ply")), {"samples": "vertices"}),
    ((os.path.join(MPEG, "fandisk10_a.ply"), os.path.join(MPEG, "fandisk10_b.ply")), {"pcc": True}),
    ((os.path.join(DTU, "Points/stl/stl001_total.ply"), os.path.join(DTU, "scan1_mesh.ply")),
     {"protocol": "dtu", "dtu_obs_mask": os.path.join(DTU, "ObsMask/ObsMask1_10.mat"),
      "dtu_plane": os.path.join(DTU, "ObsMask/Plane1.mat"), "protocol_seed": 3, "protocol_runs": 2}),
    ((os.path.join(DTU, "Points/stl/stl001_total.ply"), os.path.join(DTU, "scan1_mesh.ply")),
     {"protocol": "dtu", "dtu_obs_mask": os.path.join(DTU, "ObsMask/ObsMask1_10.mat"),
      "dtu_plane": os.path.join(DTU, "ObsMask/Plane1.mat"), "protocol_runs": 1, "symmetric": True,
      "threshold": "0.5"}),
    ((os.path.join(TNT, "Bench.ply"), os.path.join(TNT, "Bench_points.ply")),
     {"protocol": "tanks-and-temples", "tnt_crop": os.path.join(TNT, "Bench.json"),
      "tnt_alignment": os.path.join(TNT, "Bench_trans.txt"), "tnt_scene": "Barn"}),
    ((os.path.join(TNT, "Bench.ply"), os.path.join(TNT, "Bench_mesh.ply")),
     {"protocol": "tanks-and-temples", "tnt_crop": os.path.join(TNT, "Bench.json"),
      "tnt_alignment": os.path.join(TNT, "Bench_trans.txt"), "tnt_tau": 0.01, "symmetric": True,
      "threshold": "0.02"}),
    ((os.path.join(TNT, "Bench.ply"), os.path.join(TNT, "Bench_moved_points.ply")),
     {"protocol": "tanks-and-temples", "tnt_crop": os.path.join(TNT, "Bench.json"),
      "tnt_alignment": os.path.join(TNT, "Bench_trans.txt"), "tnt_scene": "Barn",
      "tnt_trajectory": os.path.join(TNT, "Bench_moved.log"),
      "tnt_reference_trajectory": os.path.join(TNT, "Bench_COLMAP_SfM.log"),
      "tnt_mapping": os.path.join(TNT, "Bench_mapping_reference.txt"), "protocol_seed": 4, "protocol_runs": 2}),
])
def test_report_equals_the_clis(pair, options):
    result = roving.measure(*pair, **options)
    assert_same(cli_json(*pair, options), result)
    assert bool(result["breached_gates"]) == ("fail_above" in options)


def test_version_is_the_reports_tool():
    tool = roving.measure(BUNNY, BUNNY, samples="area:100")["tool"]
    assert roving.__version__ == tool["version"] and roving.commit == tool["commit"]
    assert roving.__version__.count(".") == 2


def test_per_sample_arrays_without_a_copy(tmp_path):
    samples_csv = tmp_path / "samples.csv"
    result = roving.measure(BUNNY, FANDISK, samples="area:500", samples_out=str(samples_csv))
    columns = result["per_sample"]
    assert columns["positions"].shape == (500, 3) and columns["normals"].shape == (500, 3)
    assert columns["d"].dtype == np.float64 and columns["hit"].dtype == np.bool_
    for name in ("positions", "d", "weight", "element"):
        assert columns[name].flags["OWNDATA"] is False, name  # a view of the library's buffer
    rows = list(csv.DictReader(open(samples_csv)))
    assert len(rows) == 500
    for k, row in enumerate(rows):
        assert bool(int(row["hit"])) == columns["hit"][k]
        if columns["hit"][k]:
            assert float(row["d"]) == columns["d"][k]
        assert float(row["x"]) == columns["positions"][k, 0] and float(row["nz"]) == columns["normals"][k, 2]
        assert int(row["element"]) == columns["element"][k]
        for axis, name in enumerate(("test_x", "test_y", "test_z")):
            assert (float(row[name]) if row[name] else np.nan) == columns["test_point"][k, axis] or \
                not columns["hit"][k]
        if columns["hit"][k]:
            assert int(row["test_face"]) == columns["hit_face"][k]
            assert float(row["bary_1"]) == columns["barycentric"][k, 1]
    d = columns["d"]
    del result, columns
    assert d.sum() == d.sum()  # still valid once the result is gone


def test_correspondences_lie_on_the_named_face():
    lines = [line.split() for line in open(BUNNY) if line.startswith(("v ", "f "))]
    vertices = np.array([[float(x) for x in l[1:4]] for l in lines if l[0] == "v"])
    faces = np.array([[int(x.split("/")[0]) - 1 for x in l[1:4]] for l in lines if l[0] == "f"])
    size = np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0))
    noisy = vertices + np.random.default_rng(7).normal(scale=0.001 * size, size=vertices.shape)
    for semantics in ("first-hit", "closest"):
        result = roving.measure(BUNNY, (noisy, faces), samples="area:2000", semantics=semantics)
        columns = result["per_sample"]
        hit, point = columns["hit"], columns["test_point"]
        # test_point at its barycentric coordinates of hit_face's corners.
        on_face = np.einsum("kc,kcx->kx", columns["barycentric"], noisy[faces[columns["hit_face"]]])
        assert np.abs(point - on_face)[hit].max() < 1e-12 * size
        assert np.isnan(point[~hit]).all() and np.isnan(columns["barycentric"][~hit]).all()
        if semantics == "first-hit":
            # Where the normal line meets TEST: x + d n, to the rule's 1e-6 of the diagonal
            # (normal_line.h), across the line and along it.
            on_line = columns["positions"] + columns["d"][:, None] * columns["normals"]
            assert np.linalg.norm(point - on_line, axis=1)[hit].max() <= 2e-6 * result["diagonal"]
        else:
            # The closest point: |d| from the sample.
            gap = np.linalg.norm(point - columns["positions"], axis=1) - np.abs(columns["d"])
            assert np.abs(gap).max() < 1e-12 * size


def read_obj(path):
    """An OBJ's vertices and triangles (the first index of each corner), as NumPy arrays."""
    lines = [line.split() for line in open(path) if line.startswith(("v ", "f "))]
    vertices = np.array([[float(x) for x in line[1:4]] for line in lines if line[0] == "v"])
    faces = np.array([[int(x.split("/")[0]) - 1 for x in line[1:4]] for line in lines if line[0] == "f"])
    return vertices, faces


def test_colour_and_gl_columns():
    result = roving.measure(os.path.join(IBSM, "torus-a.obj"), os.path.join(IBSM, "torus-b.obj"),
                            method="roving", samples="area:300")
    columns = result["per_sample"]
    assert columns["test_colour"].shape == (300, 3) and columns["reference_colour"].dtype == np.float32
    hit = columns["hit"]
    assert not np.isnan(columns["test_colour"][hit]).any() and np.isnan(columns["test_colour"][~hit]).all()
    assert set(np.unique(columns["resolved_by"])) <= {roving.resolved_by["camera"], roving.resolved_by["no-hit"]}
    assert (columns["delta_e"][hit] >= 0).all()
    # A GL method's face, chosen by the exact rule near its d (hit_colour.h): test_point is the
    # face's point nearest x + d n, within the cameras' bound on d (agreement.h's
    # roving_tolerance), and its barycentric coordinates give it back.
    gl = result["gl"]
    bound = 8 * gl["camera_depth_step"] + 10 * gl["camera_half_width"] / 128
    on_line = columns["positions"] + columns["d"][:, None] * columns["normals"]
    assert np.linalg.norm(columns["test_point"] - on_line, axis=1)[hit].max() <= bound
    vertices, faces = read_obj(os.path.join(IBSM, "torus-b.obj"))
    on_face = np.einsum("kc,kcx->kx", columns["barycentric"], vertices[faces[columns["hit_face"]]])
    assert np.abs(columns["test_point"] - on_face)[hit].max() < 1e-12 * result["diagonal"]
    assert np.isnan(columns["barycentric"][~hit]).all()


class MeshLike:
    """What trimesh and many libraries offer: vertices and faces attributes."""
    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces


def test_meshes_python_holds():
    small, large = cube(0.5), cube(0.55)
    by_pair = roving.measure(small, large, semantics="closest")
    assert by_pair["samples"]["count"] == 12
    np.testing.assert_allclose(by_pair["per_sample"]["d"], 0.05, atol=1e-12)
    by_object = roving.measure(MeshLike(*small), MeshLike(*large), semantics="closest")
    assert by_object["statistics"] == by_pair["statistics"]
    # Other types and layouts are converted (a copy), with the same answer.
    for vertices, faces in [(small[0].astype(np.float32), small[1]), (np.asfortranarray(small[0]), small[1]),
                            (small[0], small[1].astype(np.uint16)), (small[0].astype(">f8"), small[1])]:
        converted = roving.measure((vertices, faces), large, semantics="closest")
        assert converted["statistics"] == by_pair["statistics"]
    # An N x 3 array is a point cloud (PCA normals), measured against a mesh.
    points = np.random.default_rng(1).uniform(-0.5, 0.5, (400, 3))
    points[:, 2] = 0.5
    cloud = roving.measure(points, large, semantics="closest", samples="vertices")
    np.testing.assert_allclose(np.abs(cloud["per_sample"]["d"]), 0.05, atol=1e-12)  # a flat patch: either side


def test_float64_vertices_and_int32_faces_are_read_in_place():
    """The library holds a reference to such arrays while it measures (their memory is the mesh's),
    and to nothing once it returns; other types are converted and not held."""
    small = cube(0.5)
    vertices, faces = cube(0.55)[0], cube(0.55)[1].astype(np.int32)
    lent, converted = (vertices, faces), (np.asfortranarray(vertices), faces.astype(np.int64))
    before = [sys.getrefcount(a) for a in lent + converted]
    during = {}

    def progress(*_):
        if not during:
            during["lent"] = [sys.getrefcount(a) for a in lent + converted]

    in_place = roving.measure(small, lent, semantics="closest", progress=progress)
    assert during["lent"] == [before[0] + 1, before[1] + 1, before[2], before[3]]
    during.clear()
    copied = roving.measure(small, converted, semantics="closest", progress=progress)
    assert during["lent"] == before
    assert [sys.getrefcount(a) for a in lent + converted] == before
    assert in_place["statistics"] == copied["statistics"]
    # An index out of range in a lent array is refused as in a converted one.
    with pytest.raises(roving.Error, match="refers to vertex 8"):
        roving.measure((small[0], np.array([[0, 1, 8]], dtype=np.int32)), small)


def test_open3d_meshes_and_point_clouds():
    o3d = pytest.importorskip("open3d")
    small, large = cube(0.5), cube(0.55)
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(small[0]), o3d.utility.Vector3iVector(small[1]))
    expected = roving.measure(small, large, semantics="closest")
    assert roving.measure(mesh, large, semantics="closest")["statistics"] == expected["statistics"]
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(small[0]))
    cloud.normals = o3d.utility.Vector3dVector(small[0])  # outward along the diagonals
    cloud.colors = o3d.utility.Vector3dVector(np.full((8, 3), 0.5))
    result = roving.measure(cloud, large, semantics="closest", samples="vertices")
    assert result["samples"]["count"] == 8 and result["per_sample"]["hit"].all()


@pytest.mark.parametrize("call,message", [
    (lambda: roving.measure("/nonexistent/ref.obj", BUNNY), "/nonexistent/ref.obj"),
    (lambda: roving.measure(BUNNY, BUNNY, method="magic"), "--method"),
    (lambda: roving.measure(BUNNY, BUNNY, max_error="abc"), "--max-error"),
    (lambda: roving.measure(BUNNY, BUNNY, samples="area:0"), "--samples"),
    (lambda: roving.measure(BUNNY, BUNNY, resolution=0), "--resolution"),
    (lambda: roving.measure(BUNNY, BUNNY, max_eror="1%"), "unknown argument 'max_eror' (did you mean 'max_error'?)"),
    (lambda: roving.measure(np.zeros((3, 2)), BUNNY), "reference points: expected an N x 3 array"),
    (lambda: roving.measure((cube(1)[0], np.array([[0, 1, 8]])), BUNNY), "refers to vertex 8"),
    (lambda: roving.measure((np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]])), BUNNY),
     "finite"),
    (lambda: roving.measure(object(), BUNNY), "reference: expected a path"),
    (lambda: roving.measure((cube(1)[0], np.array([[0, 1, 2.5]])), BUNNY), "refers to vertex 2.5; expected whole-number"),
    (lambda: roving.measure(BUNNY, BUNNY, symmetric="yes"), "symmetric: expected True or False, found 'yes'"),
    (lambda: roving.measure(BUNNY, BUNNY, symmetric=2), "symmetric: expected True or False, found 2"),
    (lambda: roving.measure(BUNNY, BUNNY, max_error=True), "max_error: expected a value (as the command's --max-error"),
    (lambda: roving.measure((1, 2, 3), BUNNY), "a sequence of 3"),
    (lambda: roving.batch("/nonexistent/pairs.csv", out="/nonexistent/out"), "/nonexistent"),
])
def test_bad_input_raises_the_commands_error(call, message):
    with pytest.raises(roving.Error, match=message.replace("-", r"\-").replace("(", r"\(").replace(")", r"\)")
                       .replace("?", r"\?")):
        call()


def test_warnings_are_pythons(capfd):
    # Two boxes apart: the command's two warnings (boxes apart, every sample a no-hit) come as
    # roving.Warning through Python's warnings, at the caller's line, and not on the C-level stderr.
    near, far = cube(1), (cube(1)[0] + 10, cube(1)[1])
    with pytest.warns(roving.Warning) as caught:
        result = roving.measure(near, far, per_sample=False)
    # The same lines as the report's, naming keywords where the command's name its options.
    shown = [str(w.message) for w in caught]
    assert shown == [w.replace("--semantics closest", "semantics='closest'") for w in result["warnings"]]
    assert len(caught) == 2 and "--semantics closest" in result["warnings"][1]
    assert "do not overlap" in result["warnings"][0] and caught[0].filename == __file__
    assert "roving: warning" not in capfd.readouterr().err
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # quiet=True: none, as the command prints none
        assert len(roving.measure(near, far, per_sample=False, quiet=True)["warnings"]) == 2


def test_flags_take_what_python_code_passes():
    # NumPy's bool_ (an element of a mask) and 1 / 0 are True and False, as Python treats them.
    for yes in (True, np.True_, 1):
        assert "directions" in roving.measure(BUNNY, BUNNY, samples="area:100", symmetric=yes, per_sample=False)
    for no in (False, np.False_, 0):
        assert "directions" not in roving.measure(BUNNY, BUNNY, samples="area:100", symmetric=no, per_sample=False)


def test_an_option_error_is_the_clis_message():
    cli = subprocess.run([CLI, "measure", BUNNY, BUNNY, "--resolution", "0"], capture_output=True, text=True)
    with pytest.raises(roving.Error) as error:
        roving.measure(BUNNY, BUNNY, resolution=0)
    assert str(error.value) in cli.stderr


def test_batch_as_the_command(tmp_path):
    manifest = tmp_path / "pairs.csv"
    manifest.write_text(f"reference,test\n{BUNNY},{FANDISK}\n{FANDISK},{BUNNY}\n")
    assert roving.batch(str(manifest), out=str(tmp_path / "py"), samples="area:500") == 0
    subprocess.run([CLI, "batch", str(manifest), "--out", str(tmp_path / "cli"), "--samples", "area:500"],
                   check=True, capture_output=True)
    ours = list(csv.DictReader(open(tmp_path / "py" / "summary.csv")))
    theirs = list(csv.DictReader(open(tmp_path / "cli" / "summary.csv")))
    assert len(ours) == len(theirs) == 2
    for a, b in zip(ours, theirs):
        for key in ("usiad", "rms", "max_abs", "no_hits"):
            assert a[key] == b[key], key



def test_batch_runs_each_pairs_protocol(tmp_path):
    """A manifest naming each pair's data set files: the summary holds what roving.measure gives."""
    manifest = tmp_path / "protocols.csv"
    manifest.write_text(
        "reference,test,protocol,dtu_obs_mask,dtu_plane,tnt_crop,tnt_alignment,tnt_tau\n"
        f"{DTU}/Points/stl/stl001_total.ply,{DTU}/scan1_mesh.ply,dtu,{DTU}/ObsMask/ObsMask1_10.mat,"
        f"{DTU}/ObsMask/Plane1.mat,,,\n"
        f"{TNT}/Bench.ply,{TNT}/Bench_points.ply,tanks-and-temples,,,{TNT}/Bench.json,{TNT}/Bench_trans.txt,0.01\n")
    assert roving.batch(str(manifest), out=str(tmp_path / "out"), quiet=True) == 0
    rows = list(csv.DictReader(open(tmp_path / "out" / "summary.csv")))
    dtu = roving.measure(f"{DTU}/Points/stl/stl001_total.ply", f"{DTU}/scan1_mesh.ply", protocol="dtu",
                         dtu_obs_mask=f"{DTU}/ObsMask/ObsMask1_10.mat", dtu_plane=f"{DTU}/ObsMask/Plane1.mat")
    tnt = roving.measure(f"{TNT}/Bench.ply", f"{TNT}/Bench_points.ply", protocol="tanks-and-temples",
                         tnt_crop=f"{TNT}/Bench.json", tnt_alignment=f"{TNT}/Bench_trans.txt", tnt_tau=0.01)
    assert float(rows[0]["dtu_overall"]) == dtu["dtu_protocol"]["overall"]
    assert float(rows[1]["tnt_f_score"]) == tnt["tanks_and_temples_protocol"]["fscore"]

def test_no_memory_growth_over_a_thousand_calls():
    small, large = cube(0.5), cube(0.55)

    def peak_kib():  # the process's peak resident size (no /proc needed: a chroot may have none)
        import resource
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss

    for _ in range(100):  # allocator pools and caches settle
        roving.measure(small, large, samples="area:200")
    before = peak_kib()
    for _ in range(1000):
        roving.measure(small, large, samples="area:200")
    # 1,000 leaked results of 200 samples would be at least 1000 * 200 * 80 bytes = 16 MB on the peak.
    assert peak_kib() - before < 4 * 1024


def test_progress_callback_hears_each_stage_and_can_stop(tmp_path):
    heard = []
    roving.measure(BUNNY, FANDISK, samples="area:5000", method="roving",
                   progress=lambda stage, what, done, total: heard.append((stage, what, done, total)))
    stages = [stage for stage, what, _, _ in heard if not what]
    assert stages[:3] == ["loading stanford-bunny.obj", "loading fandisk.obj", "sampling"] and "measuring" in stages
    assert any(what == "cameras" and 0 < done <= total == 5000 for _, what, done, total in heard)

    class Stop(Exception):
        pass

    def stop(stage, what, done, total):
        if stage == "measuring":
            raise Stop(stage)

    output = tmp_path / "report.json"
    with pytest.raises(Stop):
        roving.measure(BUNNY, FANDISK, samples="area:5000", json=str(output), progress=stop)
    assert not output.exists() and not list(tmp_path.iterdir())  # nothing written, no temporary left
    with pytest.raises(roving.Error, match="progress: expected a function"):
        roving.measure(BUNNY, FANDISK, progress=3)


def test_certified_bounds_report_progress_and_stop_on_it():
    # The certified Hausdorff interval and the certified shares report their counts as they go, so
    # that a progress function (and Ctrl-C, which listens the same way) can stop them mid-stage.
    heard = []
    roving.measure(BUNNY, FANDISK, symmetric=True, threshold="1%", certify_thresholds=True, per_sample=False,
                   quiet=True, progress=lambda stage, what, done, total: heard.append((stage, what, done, total)))
    counts = {(stage, what) for stage, what, done, total in heard if what and 0 < done <= total}
    assert ("A -> B: certified Hausdorff", "vertices") in counts and ("B -> A: certified Hausdorff", "vertices") in counts
    assert ("A -> B: certified precision and recall", "triangles") in counts, sorted(counts)

    class Stop(Exception):
        pass

    def stop(stage, what, done, total):
        if stage.endswith("certified precision and recall") and what == "triangles":
            raise Stop(stage)

    with pytest.raises(Stop):
        roving.measure(BUNNY, FANDISK, symmetric=True, threshold="1%", certify_thresholds=True, per_sample=False,
                       quiet=True, progress=stop)


def test_ctrl_c_stops_a_long_measurement_and_writes_nothing(tmp_path):
    output = tmp_path / "report.json"
    script = (f"import roving, sys\nprint('started', flush=True)\n"
              f"roving.measure({BUNNY!r}, {BUNNY!r}, method='roving', samples='area:3000000', json={str(output)!r})\n")
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=dict(os.environ))
    assert child.stdout.readline().strip() == "started"
    time.sleep(2)  # loading and sampling done, the cameras under way (the whole run takes much longer)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    _, stderr = child.communicate(timeout=60)
    stopped_after = time.monotonic() - sent
    assert child.returncode != 0 and "KeyboardInterrupt" in stderr, stderr
    assert stopped_after < 5, stopped_after
    assert not list(tmp_path.iterdir())


def test_batch_stops_at_once_and_resumes(tmp_path):
    manifest = tmp_path / "pairs.csv"
    manifest.write_text(f"reference,test\n{BUNNY},{FANDISK}\n{FANDISK},{BUNNY}\n{BUNNY},{BUNNY}\n")
    out = tmp_path / "out"
    heard = []

    class Stop(Exception):
        pass

    def stop_in_the_second_pair(stage, what, done, total):
        heard.append(stage)
        if stage == "measuring" and any(s.startswith("pair 2/3") for s in heard):
            raise Stop(stage)  # in the middle of the second pair

    with pytest.raises(Stop):
        roving.batch(str(manifest), out=str(out), samples="area:500", progress=stop_in_the_second_pair)
    assert heard[0].startswith("pair 1/3: stanford-bunny.obj vs fandisk.obj")
    reports = sorted(p.name for p in out.iterdir())
    assert len(reports) == 1 and reports[0].startswith("000000-") and reports[0].endswith(".json"), reports
    # Run again: the first pair is kept, the others measured.
    assert roving.batch(str(manifest), out=str(out), samples="area:500") == 0
    rows = list(csv.DictReader(open(out / "summary.csv")))
    assert [row["status"] for row in rows] == ["ok"] * 3

    # Ctrl-C in a child process: stops within seconds, KeyboardInterrupt, the pair under way
    # leaving nothing.
    slow = tmp_path / "slow.csv"
    slow.write_text(f"reference,test\n{BUNNY},{BUNNY}\n")
    script = (f"import roving\nprint('started', flush=True)\n"
              f"roving.batch({str(slow)!r}, out={str(tmp_path / 'slow')!r}, method='roving', samples='area:3000000')\n")
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=dict(os.environ))
    assert child.stdout.readline().strip() == "started"
    time.sleep(2)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    _, stderr = child.communicate(timeout=60)
    assert child.returncode != 0 and "KeyboardInterrupt" in stderr, stderr
    assert time.monotonic() - sent < 5
    assert not [p for p in (tmp_path / "slow").iterdir() if p.name != "summary.csv"]


def test_without_per_sample_arrays_a_large_reference_streams():
    # Igea (268,686 faces of binary PLY) read 50,000 faces at a time: the figures of the whole.
    igea = os.path.join(DATA, "igea.ply")
    options = {"samples": "faces", "chunk": 50000}
    whole = roving.measure(igea, FANDISK, **options)
    streamed = roving.measure(igea, FANDISK, per_sample=False, **options)
    assert "per_sample" in whole and "streamed" not in whole["samples"]
    assert "per_sample" not in streamed and streamed["samples"]["streamed"] == {"chunk_faces": 50000, "chunks": 6}
    assert streamed["statistics"] == whole["statistics"]
    assert_same(cli_json(igea, FANDISK, options), streamed)
    with pytest.raises(roving.Error, match="per_sample: expected True or False"):
        roving.measure(igea, FANDISK, per_sample="no")


def test_type_stubs_name_exactly_the_commands_options():
    import ast
    stub = ast.parse(open(os.path.join(SOURCE, "python", "roving.pyi")).read())
    keywords = {f.name: {a.arg for a in f.args.kwonlyargs} for f in stub.body if isinstance(f, ast.FunctionDef)}

    def options(command):
        text = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
        import re
        return {o[2:].replace("-", "_") for o in re.findall(r"^\s+(--[a-z][a-z-]*)", text, re.M)} - {"help"}

    assert keywords["measure"] == options("measure") | {"progress", "per_sample"}
    assert keywords["batch"] == options("batch") | {"progress"}
    assert keywords["merge"] == options("merge")


def test_shards_merge_to_the_one_process_report(tmp_path):
    # The same pair in one call and in three shards merged: every figure equal, but times and how it ran.
    options = {"samples": "area:4000", "seed": 5, "semantics": "closest", "hausdorff_bound": "none"}
    one = roving.measure(BUNNY, FANDISK, **options)
    parts = [str(tmp_path / f"p{i}.part") for i in range(3)]
    for i, part in enumerate(parts):
        shard = roving.measure(BUNNY, FANDISK, shard=f"{i}/3", shard_out=part, **options)
        assert shard["shard"]["index"] == i and shard["shard"]["samples"][0]["total"] == 4000
    merged = roving.merge(*reversed(parts), json=str(tmp_path / "merged.json"))
    incidental = {"seconds", "command_line", "tool", "merged_from", "per_sample", "breached_gates"}
    assert {k: v for k, v in one.items() if k not in incidental} == \
        {k: v for k, v in merged.items() if k not in incidental}
    assert json.load(open(tmp_path / "merged.json"))["statistics"] == one["statistics"]
    with pytest.raises(roving.Error, match="shard 1/3 missing"):
        roving.merge(parts[0], parts[2])
    with pytest.raises(roving.Error, match="models must be files"):
        roving.measure(np.eye(3), FANDISK, shard="0/2", shard_out=str(tmp_path / "x.part"))


def square(x1, z=0.0, cells=20):
    """The rectangle [0, x1] x [0, 1] at height z, facing +z, in cells x cells quads."""
    xs, ys = np.meshgrid(np.linspace(0, x1, cells + 1), np.linspace(0, 1, cells + 1))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.full(xs.size, z)], axis=1)
    at = lambda i, j: j * (cells + 1) + i  # noqa: E731
    faces = [[at(i, j), at(i + 1, j), at(i + 1, j + 1)] for j in range(cells) for i in range(cells)]
    faces += [[at(i, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(cells) for i in range(cells)]
    return vertices, np.array(faces)


def test_reconstruction_figures_in_closed_form():
    # A model against itself: 0 (to rounding), and 1.
    same = roving.measure(square(1), square(1), symmetric=True, threshold=["0.1%"], samples="area:5000")["reconstruction"]
    assert same["chamfer_mean"] < 1e-15 and same["normal_consistency"] == 1
    assert [t["f_score"] for t in same["thresholds"]] == [1]
    # Two parallel squares 0.01 apart: every distance is 0.01 whichever way.
    apart = roving.measure(square(1), square(1, 0.01), symmetric=True, threshold=["0.005", "0.02"],
                           samples="area:5000", max_error="10%")["reconstruction"]
    for name, value in (("chamfer_mean", 0.01), ("chamfer_sum", 0.02), ("chamfer_squared_mean", 1e-4),
                        ("chamfer_squared_sum", 2e-4), ("normal_consistency", 1)):
        assert abs(apart[name] - value) < 1e-12 * max(value, 1), (name, apart[name])
    assert abs(apart["accuracy"]["median"] - 0.01) < 1e-12
    assert [(t["precision"], t["recall"], t["f_score"]) for t in apart["thresholds"]] == [(0, 0, 0), (1, 1, 1)]
    # REF the unit square, TEST its left half (the same plane): TEST is all within 0 of REF
    # (precision 1), and REF within tau of TEST where x < 0.5 + tau (recall 0.5 + tau, by area);
    # REF's mean distance is the integral of x - 0.5 over the right half, 0.125.
    half = roving.measure(square(1), square(0.5), symmetric=True, semantics="closest", threshold=["0.1", "0.25"],
                          samples="area:20000", max_error="50%")["reconstruction"]
    for t, tau in zip(half["thresholds"], (0.1, 0.25)):
        recall = t["recall_interval"]  # every figure a number, its interval beside it (schema 3)
        assert t["precision"] == 1
        assert recall["lower"] <= 0.5 + tau <= recall["upper"] and recall["lower"] <= t["recall"] <= recall["upper"]
        assert recall["upper"] - recall["lower"] < 0.03
    completeness = half["completeness"]
    assert abs(completeness["mean"] - 0.125) < 3 * (completeness["mean_interval"]["upper"] - completeness["mean"])


def test_chamfer_and_f_score_intervals_cover_the_closed_form():
    """The half square again, over 200 seeds of 2,000 samples a direction: the 95% intervals of
    Chamfer (mean and sum of the two means) and of F at tau hold the closed forms (Chamfer mean
    (0 + 0.125) / 2; F = 2 R / (1 + R) with P = 1 and R = 0.5 + tau) in 95% of the runs: between 90%
    and 99% of 200 (three binomial standard deviations, 1.5% each)."""
    tau = 0.25
    recall = 0.5 + tau
    truths = {"chamfer_mean": 0.0625, "chamfer_sum": 0.125}
    covered = {"chamfer_mean": 0, "chamfer_sum": 0, "f_score": 0}
    runs = 200
    for seed in range(1, runs + 1):
        r = roving.measure(square(1), square(0.5), symmetric=True, semantics="closest", threshold=[str(tau)],
                           samples="area:2000", seed=seed, max_error="50%")["reconstruction"]
        for name, truth in truths.items():
            interval = r[name + "_interval"]
            assert interval["lower"] <= r[name] <= interval["upper"]
            covered[name] += interval["lower"] <= truth <= interval["upper"]
        f = r["thresholds"][0]["f_score_interval"]
        covered["f_score"] += f["lower"] <= 2 * recall / (1 + recall) <= f["upper"]
    for name, count in covered.items():
        assert 0.90 * runs <= count <= 0.99 * runs, (name, count)
    # Without area samples there is no interval.
    faces = roving.measure(square(1), square(0.5), symmetric=True, threshold=[str(tau)], max_error="50%")
    assert "chamfer_mean_interval" not in faces["reconstruction"]
    assert "f_score_interval" not in faces["reconstruction"]["thresholds"][0]


def test_certified_precision_and_recall_hold_the_closed_form():
    """The same half square with --certify-thresholds: precision exactly 1; recall 0.5 + tau inside
    bounds whose width is the pieces left astride the line x = 0.5 + tau, on either side of it (at
    most 4,096 pieces of each of the 40 triangles beside it on each side: 2 x 40 x 1/800 / 64 of the
    area, 0.0016). Both sides: tau = 0.25 puts the line on the grid, so the pieces left of it reach
    a distance of exactly tau, which a bound widened by its rounding (docs/semantics.md) cannot
    certify within tau. Areas are summed in double over some 10^4 pieces: 1e-12 for rounding."""
    options = dict(symmetric=True, threshold=["0.1", "0.25", "0.6"], samples="area:2000", max_error="50%",
                   certify_thresholds=True)
    half = roving.measure(square(1), square(0.5), **options)["reconstruction"]
    for t, tau in zip(half["thresholds"], (0.1, 0.25, 0.6)):
        p, r, f = t["precision_certified"], t["recall_certified"], t["f_score_certified"]
        assert p["lower"] == pytest.approx(1, abs=1e-12) and p["upper"] == pytest.approx(1, abs=1e-12)
        truth = min(0.5 + tau, 1)
        assert r["lower"] <= truth + 1e-12 and truth - 1e-12 <= r["upper"], (tau, r)
        assert r["upper"] - r["lower"] <= 2 * 40 / 800 / 64 + 1e-12, (tau, r)
        assert f["lower"] - 1e-12 <= 2 * truth / (1 + truth) <= f["upper"] + 1e-12
    with pytest.raises(roving.Error, match="--certify-thresholds"):
        roving.measure(square(1), square(0.5), symmetric=True, certify_thresholds=True)
    with pytest.raises(roving.Error, match="--certify-thresholds"):
        roving.measure(square(1), square(0.5), symmetric=True, threshold="0.1", certify_thresholds=True,
                       hausdorff_bound="none")


def read_binary_ply(path):
    """x y z [nx ny nz] [red green blue] of make_clouds.py's files, as NumPy arrays."""
    with open(path, "rb") as f:
        header = []
        while not header or header[-1] != "end_header":
            header.append(f.readline().decode().strip())
        names = [line.split()[2] for line in header if line.startswith("property")]
        types = ["<f4" if line.split()[1] == "float" else "u1" for line in header if line.startswith("property")]
        rows = np.frombuffer(f.read(), dtype=list(zip(names, types)))
    return np.stack([rows["x"], rows["y"], rows["z"]], axis=1).astype(np.float64)


def test_pcc_figures_of_numpy_points_equal_the_files():
    """MPEG's figures of point clouds given as NumPy arrays are those of the files they came from."""
    a, b = (os.path.join(MPEG, f"torus11_{x}.ply") for x in "ab")
    from_files = roving.measure(a, b, pcc=True, pcc_resolution=2047)["mpeg_pcc"]
    from_arrays = roving.measure(read_binary_ply(a), read_binary_ply(b), pcc=True, pcc_resolution=2047)["mpeg_pcc"]
    # The arrays carry no normals (so no D2); D1 is the same to the bit.
    for key in ("d1_mse", "d1_psnr", "d1_hausdorff"):
        assert from_arrays["symmetric"][key] == from_files["symmetric"][key], key
    assert from_arrays["d2"] != True and "d2_psnr" not in from_arrays["symmetric"]


def test_pcc_uses_normals_as_given_as_the_files_are():
    """pcc=True takes an Open3D-like cloud's normals as given (not unit, some zero), as the command
    takes a file's and pc_error does: the figures equal the file's."""
    a, b = (os.path.join(MPEG, name) for name in ("sphere10_a_scaled_normals.ply", "sphere10_b.ply"))
    with open(a, "rb") as f:
        while f.readline().strip() != b"end_header":
            pass
        fields = [(n, "<f4") for n in ("x", "y", "z", "nx", "ny", "nz")] + [(n, "u1") for n in ("red", "green", "blue")]
        rows = np.frombuffer(f.read(), dtype=fields)
    cloud = types.SimpleNamespace(points=np.stack([rows["x"], rows["y"], rows["z"]], axis=1).astype(np.float64),
                                  normals=np.stack([rows["nx"], rows["ny"], rows["nz"]], axis=1).astype(np.float64),
                                  colors=np.stack([rows["red"], rows["green"], rows["blue"]], axis=1) / 255.0)
    assert (np.linalg.norm(cloud.normals, axis=1) == 0).any()
    from_file = roving.measure(a, b, pcc=True, pcc_resolution=1023)["mpeg_pcc"]
    from_object = roving.measure(cloud, b, pcc=True, pcc_resolution=1023)["mpeg_pcc"]
    for direction in ("a_to_b", "b_to_a"):
        for key in ("d1_mse", "d2_mse", "d2_hausdorff", "y_mse", "r_mse"):
            assert from_object[direction][key] == from_file[direction][key], (direction, key)


def test_threshold_needs_both_directions():
    with pytest.raises(roving.Error, match="add --symmetric"):
        roving.measure(square(1), square(1), threshold="1%")
    with pytest.raises(roving.Error, match="--threshold"):
        roving.measure(square(1), square(1), symmetric=True, threshold="-1")
