#!/usr/bin/env bash
# The main job on a default example: installs what is missing, builds, installs `actuator` on the
# PATH, and runs a short generative optimization: the thesis's B-spline experiment (5.2) for six
# generations of one run, with its report, evolution figure and the best design's before/after
# figures. Results go to out/example/ (replaced on every run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cmake --install "${BUILD_DIR:-build}" > /dev/null
out=out/example
mkdir -p out
actuator evolve assets/experiments/5.2_bspline_middle.json --out "$out" --overwrite \
  --set evolve.runs=1 --set evolve.generations=6 > /dev/null
echo "example: a 6-generation GA of thesis experiment 5.2 in $out/:"
echo "  report.md            our numbers beside the thesis's, with the figures"
echo "  evolution.png        best, mean and worst fitness per generation"
echo "  best_inflation.png   the best design before and after inflation"
echo "  best_stretch.png     the same design under the stretch test"
echo "  evaluations.csv      every evaluation (thumbnails/ pictures each one; evaluations.capnp keeps the meshes)"
grep -A3 "| ours | thesis |" "$out/report.md" || true
