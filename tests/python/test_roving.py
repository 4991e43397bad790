"""The Python module: agreement with the CLI on the same pair, NumPy arrays in and out, bad
input raising roving.Error with the library's messages."""
import json
import os
import subprocess

import numpy as np
import pytest

import roving

DATA = os.environ.get("ROVING_DATA") or os.path.join(os.environ["ROVING_SOURCE_DIR"], "data")
BUNNY = os.path.join(DATA, "stanford-bunny.obj")
FANDISK = os.path.join(DATA, "fandisk.obj")


def cube(half_side):
    """A closed box [-s, s]^3 with outward faces."""
    vertices = np.array([[(half_side if i & 1 else -half_side), (half_side if i & 2 else -half_side),
                          (half_side if i & 4 else -half_side)] for i in range(8)])
    faces = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                      [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return vertices, faces


@pytest.mark.parametrize("method,semantics", [("embree", "first-hit"), ("cgal", "nearest"),
                                              ("embree", "closest"), ("v2p-aabb", "closest")])
def test_agrees_with_the_cli(method, semantics):
    result = roving.measure(BUNNY, FANDISK, method=method, semantics=semantics, samples="area:2000")
    cli = json.loads(subprocess.run(
        [os.environ["ROVING_CLI"], "measure", BUNNY, FANDISK, "--method", method, "--semantics", semantics,
         "--samples", "area:2000", "--json", "-"], check=True, capture_output=True, text=True).stdout)
    for key in ("siad", "usiad", "rms", "max_abs", "p99", "usiad_area"):
        assert result["statistics"][key] == cli["statistics"][key], key
    assert result["no_hits"] == cli["no_hits"]
    assert result["samples"] == cli["samples"]["count"] == 2000


def test_arrays_in_and_out():
    small, large = cube(0.5), cube(0.55)
    result = roving.measure_arrays(*small, *large, semantics="closest")
    assert result["samples"] == 12
    assert isinstance(result["distance"], np.ndarray) and result["distance"].dtype == np.float64
    assert result["hit"].dtype == np.bool_ and result["hit"].all()
    np.testing.assert_allclose(result["distance"], 0.05, atol=1e-6)  # the large cube is 0.05 outside
    assert result["positions"].shape == (12, 3)
    # The distance array owns the library's buffer: no copy, writable, survives the result dict.
    distance = result["distance"]
    del result
    assert distance.flags["OWNDATA"] is False and distance.sum() > 0

    points = np.array([[0.0, 0.0, 0.5], [0.1, 0.2, 0.5]])
    normals = np.array([[0.0, 0.0, 2.0], [0.0, 0.0, 1.0]])  # normalised by the library
    given = roving.measure_arrays(*small, *large, sample_points=points, sample_normals=normals)
    np.testing.assert_allclose(given["distance"], [0.05, 0.05], atol=1e-6)
    assert given["semantics"] == "first-hit"


def test_gl_method_reports_observations():
    result = roving.measure_arrays(*cube(0.5), *cube(0.55), method="roving")
    assert result["sample_cameras"] == 12 and result["views_rendered"] == 0
    np.testing.assert_allclose(result["distance"], 0.05, atol=1e-5)


@pytest.mark.parametrize("call,message", [
    (lambda: roving.measure("/nonexistent/ref.obj", BUNNY), "/nonexistent/ref.obj"),
    (lambda: roving.measure(BUNNY, BUNNY, method="magic"), "--method"),
    (lambda: roving.measure(BUNNY, BUNNY, max_error="abc"), "--max-error"),
    (lambda: roving.measure(BUNNY, BUNNY, samples="area:0"), "--samples"),
    (lambda: roving.measure_arrays(np.zeros((3, 2)), np.zeros((1, 3)), *cube(1)), "reference vertices"),
    (lambda: roving.measure_arrays(*cube(1)[:1], np.array([[0, 1, 8]]), *cube(1)), "refers to vertex 8"),
    (lambda: roving.measure_arrays(*cube(1), *cube(1), sample_points=np.zeros((2, 3))), "both or neither"),
    (lambda: roving.measure_arrays(*cube(1), *cube(1), sample_points=np.zeros((1, 3)),
                                   sample_normals=np.zeros((1, 3))), "non-zero"),
    (lambda: roving.measure_arrays(np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]]),
                                   *cube(1)), "finite"),
])
def test_bad_input_raises_the_librarys_error(call, message):
    with pytest.raises(roving.Error, match=message.replace("-", r"\-")):
        call()
