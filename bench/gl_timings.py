#!/usr/bin/env python3
"""The GL methods on this machine's GL, timed beside Embree on its CPU cores (issue 31's table).

For each pair (the bunny against itself and against its 10,459-triangle mesh; the scaling pairs
of about 1 M and, with --large, 10 M samples) and each GL backend given, runs `roving measure`
once per method: exact roving with its cameras' triangles built on the CPU and on the GPU, and
with its cameras computed (`--camera-geometry cpu|gpu|compute`), cooperative 24x12 and 72x36
(24x12 also with cameras on the GPU and computed), `--views auto`, viewpoint 24x12; and Embree.
With --huge, also 50 M area samples on the 10 M pair, exact roving drawn and computed alone.
Each answer is checked against Embree's on the same samples before its time is reported: the
share of samples with the same hit flag, the share of common hits within exact roving's depth
tolerance (roving_tolerance in roving/gl_methods/agreement.h; for the view methods the share
of all hits), USiAD against Embree's; and, for `--camera-geometry gpu` and `compute`, the
samples whose hit or d differs at all from the CPU-built cameras' of the same method (computed
cameras take the depth in double where drawn ones interpolate floats: their d differs by design,
within the tolerance the Embree column checks). Times are the report's: query, and for the cameras
their building (CPU threads) and rendering (GL thread: upload, compute, draw, read back). The
--samples-out each run writes for the checks asks each hit's face, chosen within the query (for
computed cameras in the compute pass).

    python3 bench/gl_timings.py --roving build/roving/roving --data build/datasets \
        --backends osmesa,egl --out results/gpu.md [--large] [--huge]
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile

import numpy as np

GL_METHODS = [
    ("roving, cameras on CPU", ["--method", "roving", "--camera-geometry", "cpu"]),
    ("roving, cameras on GPU", ["--method", "roving", "--camera-geometry", "gpu"]),
    ("roving, cameras computed", ["--method", "roving", "--camera-geometry", "compute"]),
    ("cooperative 24x12", ["--method", "cooperative", "--views", "24x12"]),
    ("cooperative 24x12, cameras on GPU", ["--method", "cooperative", "--views", "24x12", "--camera-geometry", "gpu"]),
    ("cooperative 24x12, cameras computed",
     ["--method", "cooperative", "--views", "24x12", "--camera-geometry", "compute"]),
    ("cooperative 72x36", ["--method", "cooperative", "--views", "72x36"]),
    ("cooperative auto", ["--method", "cooperative", "--views", "auto"]),
    ("viewpoint 24x12", ["--method", "viewpoint", "--views", "24x12"]),
]


# With --whole-views (a GPU's run), the cooperative method computed with its views drawn whole:
# no per-view footprint or culling on the CPU, all of each view on the GPU.
WHOLE_VIEWS = ("cooperative 24x12, cameras computed, whole views",
               ["--method", "cooperative", "--views", "24x12", "--camera-geometry", "compute", "--view-culling", "none"])


# The methods of the --huge pair: exact roving's cameras drawn and computed.
CAMERA_METHODS = [m for m in GL_METHODS if m[0] in ("roving, cameras on CPU", "roving, cameras computed")]


def pairs(data, large, huge):
    """(title, REF, TEST, samples, methods) of each pair."""
    yield "bunny / itself", f"{data}/bunny.ply", f"{data}/bunny.ply", "vertices", GL_METHODS
    yield "bunny / 10,459 triangles", f"{data}/bunny.ply", f"{data}/bunny-10459.ply", "vertices", GL_METHODS
    for n in [4, 12] if large else [4]:
        ref, test = f"{data}/scaling/ref-n{n}.ply", f"{data}/scaling/test-n{n}.ply"
        if os.path.exists(ref):
            yield f"scaling n={n}", ref, test, "faces", GL_METHODS
    ref, test = f"{data}/scaling/ref-n12.ply", f"{data}/scaling/test-n12.ply"
    if huge and os.path.exists(ref):
        yield "scaling n=12, 50 M area samples", ref, test, "area:50000000", CAMERA_METHODS


def measure(roving, ref, test, samples, arguments, folder, name):
    report, table = os.path.join(folder, name + ".json"), os.path.join(folder, name + ".csv")
    command = [roving, "measure", ref, test, "--samples", samples, "--max-error", "2%", "--quiet",
               "--hausdorff-bound", "none", "--json", report, "--samples-out", table] + arguments
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(report) as f:
        result = json.load(f)
    columns = read_d_and_hit(table)
    os.remove(table)
    return result, columns[:, 0], columns[:, 1].astype(bool)


def read_d_and_hit(table):
    """Columns d and hit of a --samples-out table (d empty: no hit). numpy's reader takes about a
    minute for the 10 M pair's rows; pandas (with pyarrow's threads where it has them) a second."""
    try:
        import pandas
    except ImportError:
        return np.genfromtxt(table, delimiter=",", skip_header=1, usecols=(6, 7), filling_values=np.nan)
    try:
        frame = pandas.read_csv(table, usecols=[6, 7], engine="pyarrow")
    except Exception:  # no pyarrow, or one that cannot read this table: pandas' own reader
        frame = pandas.read_csv(table, usecols=[6, 7])
    return frame.to_numpy(dtype=float, na_value=np.nan)


def roving_tolerance(gl):  # roving/gl_methods/agreement.cpp
    return 8 * gl["camera_depth_step"] + 10 * gl["camera_half_width"] / 128


def row(name, backend, result, d, hit, exact, cpu_cameras):
    exact_report, exact_d, exact_hit = exact
    gl = result.get("gl", {})
    common = hit & exact_hit
    same_flag = np.mean(hit == exact_hit)
    tolerance = roving_tolerance(gl) if gl.get("sample_cameras") else None
    within = np.mean(np.abs(d[common] - exact_d[common]) <= tolerance) if tolerance and common.any() else None
    usiad, exact_usiad = result["statistics"]["usiad"], exact_report["statistics"]["usiad"]
    if exact_usiad > 0:
        usiad_text = f"{100 * (usiad / exact_usiad - 1):+.3f}%"
    else:  # a model against itself: USiAD 0
        usiad_text = f"{usiad / result['diagonal']:.1e} of the diagonal"
    samples = len(d)
    query = result["seconds"]["query"]
    cameras = ""
    if gl.get("sample_cameras"):
        cameras = f"{gl['camera_build_seconds']:.3f} / {gl['camera_render_seconds']:.3f}"
    views = ""
    if gl.get("views_rendered"):
        views = f"{gl['view_cpu_seconds']:.3f} / {gl['view_draw_seconds']:.3f}"
    differs = ""
    if cpu_cameras is not None:
        differs = str(int(np.sum((hit != cpu_cameras[1]) | (hit & (d != cpu_cameras[0])))))
    return (f"| {name} | {backend} | {query:.3f} | {samples / query / 1e6:.2f} | {cameras} | {views} | "
            f"{100 * same_flag:.3f}% | {'' if within is None else f'{100 * within:.2f}%'} | "
            f"{usiad_text} | {differs} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--roving", default="build/roving/roving")
    parser.add_argument("--data", default="build/datasets")
    parser.add_argument("--backends", default="osmesa,egl")
    parser.add_argument("--large", action="store_true", help="also the 10 M pair")
    parser.add_argument("--huge", action="store_true", help="also 50 M samples on the 10 M pair")
    parser.add_argument("--whole-views", action="store_true",
                        help="also cooperative 24x12 computed with its views drawn whole (--view-culling none)")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()

    lines = []
    renderers = {}
    with tempfile.TemporaryDirectory() as folder:
        for title, ref, test, samples, methods in pairs(args.data, args.large, args.huge):
            if args.whole_views and methods is GL_METHODS:
                methods = GL_METHODS + [WHOLE_VIEWS]
            print(title, file=sys.stderr)
            exact = measure(args.roving, ref, test, samples, ["--method", "embree"], folder, "embree")
            lines += [f"### {title}: {len(exact[1]):,} {samples} samples", "",
                      "| method | GL | query s | M samples/s | cameras: build / render s | views: CPU / draw s | same hit as Embree | "
                      "within the camera tolerance | USiAD vs Embree | hit or d differs from CPU cameras |",
                      "|---|---|---|---|---|---|---|---|---|---|",
                      row("embree", f"{os.cpu_count()} CPU threads", *exact, exact, None)]
            for backend in args.backends.split(","):
                cpu = {}
                for name, arguments in methods:
                    try:
                        result, d, hit = measure(args.roving, ref, test, samples, arguments + ["--backend", backend],
                                                 folder, "gl")
                    except subprocess.CalledProcessError:
                        lines.append(f"| {name} | {backend} | failed | | | | | | | |")
                        continue
                    renderers[backend] = result["gl"]["renderer"]
                    elsewhere = ", cameras on GPU" in name or ", cameras computed" in name
                    cpu_key = name.replace(", cameras on GPU", "").replace(", cameras computed", "")
                    cpu_key = cpu_key.replace(", cameras on CPU", "")
                    if not elsewhere:
                        cpu[cpu_key] = (d, hit)
                    lines.append(row(name, backend, result, d, hit, exact, cpu.get(cpu_key) if elsewhere else None))
            lines.append("")
            write(args.out, renderers, lines)  # after each pair, so that a run cut short keeps what it measured
    print(f"wrote {args.out}", file=sys.stderr)


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def write(path, renderers, lines):
    header = [
        "# The GL methods on this machine's GL, beside Embree on its CPU cores",
        "",
        f"Generated by `bench/gl_timings.py` on {platform.node() or 'this machine'} "
        f"({os.cpu_count()} CPU threads, {cpu_name()}). Renderers:",
        "",
    ] + [f"- `{backend}`: {renderer}" for backend, renderer in renderers.items()] + [
        "",
        "Each answer is checked against Embree's on the same samples before its time is shown: the share "
        "with the same hit flag; for methods with per-sample cameras, the share of common hits within exact "
        "roving's depth tolerance (8 float depth steps plus subpixel snapping times a slope of 10: "
        "roving/gl_methods/agreement.h; view-resolved samples are held to their own, looser tolerance, so "
        "the share is lower for the view methods); USiAD against Embree's; and for cameras built on the GPU "
        "or computed, how many samples' hit or d differs at all from the CPU-built cameras' of the same "
        "method (computed cameras take the depth in double where drawn ones interpolate floats, so theirs "
        "differ by design within the tolerance). "
        "`cameras: build / render` is the time spent building the cameras' batches on the CPU threads "
        "(beside the drawing) and rendering them on the GL thread (upload, compute stage, draw, read back); "
        "`views: CPU / draw` likewise for the views: preparing and reading them on the CPU threads, drawing "
        "and reading them back on the GL thread. "
        "Each run writes every sample's row (`--samples-out`, for the checks), which asks each hit's face: "
        "the query time includes choosing it, by the exact rule near d on the CPU threads after the pass, "
        "or for computed cameras in the compute pass itself (its render time), the CPU choosing only what "
        "the pass leaves (`gl.faces_left_to_cpu`). "
        "Viewpoint sampling alone leaves what its views cannot resolve with certainty as no hits (paper "
        "Section 4.2; distances within 100 float depth steps go to the cameras in the cooperative method, so "
        "a model against itself, d = 0 everywhere, is resolved by no view): its hit share and USiAD show how "
        "much its views resolve, not an error. h is 2% of the diagonal.",
        "",
    ]
    with open(path + ".part", "w") as f:
        f.write("\n".join(header + lines))
    os.replace(path + ".part", path)


if __name__ == "__main__":
    main()
