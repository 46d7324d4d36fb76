#!/usr/bin/env bash
# The main job on the default example: installs what is missing, builds, and evaluates the thesis's
# best sine actuator (A = 4.1, phase 0.5..pi-0.5) inflated and stretched, with its figures.
# Results go to out/example/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
out=out/example
mkdir -p "$out"
actuator=${BUILD_DIR:-build}/app/actuator
"$actuator" simulate --shape sine --amplitude 4.1 --phase 0.5,pi-0.5 \
  --save-initial "$out/initial.obj" --save-mesh "$out/inflated.obj" > "$out/inflate.json"
"$actuator" simulate --shape sine --amplitude 4.1 --phase 0.5,pi-0.5 --load stretch \
  --save-mesh "$out/stretched.obj" > "$out/stretch.json"
"$actuator" render --shape sine --amplitude 4.1 --phase 0.5,pi-0.5 --out "$out" > "$out/render.json"
echo "example: wrote $out/{inflate,stretch,render}.json, $out/{initial,inflated,stretched}.obj and $out/{inflation,stretch}.png"
cat "$out/inflate.json" "$out/stretch.json"
