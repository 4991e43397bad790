#!/usr/bin/python3
"""The documentation pages against the tools: every option of `roving measure` and `roving batch`
is described on docs/measuring.md or docs/batch.md; every --option the README and the docs pages
name exists in some tool's --help (or is another program's, listed below); every relative link
resolves. Run by CTest: docs_test.py SOURCE_DIR ROVING ROVING_BENCH ROVING_DATASETS."""
import pathlib
import re
import subprocess
import sys

source, roving, bench, datasets = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
# Options of other programs the pages show (cmake, g++, pkg-config, Google Benchmark, git, sbatch).
OTHER_PROGRAMS = {"--build", "--install", "--prefix", "--cflags", "--libs", "--dependency", "--array",
                  "--benchmark_repetitions", "--benchmark_report_aggregates_only", "--benchmark_out",
                  "--benchmark_out_format", "--benchmark_filter", "--output-on-failure", "--test-dir",
                  "--headless", "--check", "--help", "--version", "--always", "--dirty",
                  "--cpus-per-task", "--export", "--job-name", "--mem", "--output", "--parsable",
                  # MPEG's pc_error (docs/mpeg.md; the regex stops at its options' capitals)
                  "--file", "--color", "--hausdorff", "--nb", "--mse", "--dropdups", "--neighbors", "--average",
                  "--input", "--single", "--lidar",
                  "--mode", "--normal", "--drop"}  # mmetric's compare --mode, --normalCalcModificationEnable, --dropDuplicates


def options_of(*command):
    text = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    return set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9_-]*)", text))


measure = options_of(roving, "measure", "--help")
batch = options_of(roving, "batch", "--help")
known = (measure | batch | options_of(roving, "--help") | options_of(bench, "--help") | options_of(datasets, "--help")
         | options_of(sys.executable, str(source / "bench" / "gl_timings.py"), "--help")
         | options_of(sys.executable, str(source / "bench" / "cloudcompare_c2m.py"), "--help")
         | options_of(sys.executable, str(source / "bench" / "tnt_speed.py"), "--help"))
pages = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
failures = []
for option, command, page in ([(o, "measure", "measuring.md") for o in sorted(measure)] +
                              [(o, "batch", "batch.md") for o in sorted(batch - measure)]):
    if option not in OTHER_PROGRAMS and f"`{option}" not in (source / "docs" / page).read_text():
        failures.append(f"docs/{page}: `{option}` (an option of roving {command}) is not described")
for page in pages:
    text = page.read_text()
    for option in sorted(set(re.findall(r"(?<![\w-])(--[a-z][a-z0-9_-]*)", text)) - known - OTHER_PROGRAMS):
        failures.append(f"{page.relative_to(source)}: names {option}, which no tool's --help has")
    for link in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
        if not (page.parent / link).exists():
            failures.append(f"{page.relative_to(source)}: the link '{link}' leads nowhere")
for failure in failures:
    print(failure)
print(f"{len(pages)} pages, {len(measure | batch)} options: {len(failures)} problems")
sys.exit(1 if failures else 0)
