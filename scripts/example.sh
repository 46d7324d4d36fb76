#!/usr/bin/env bash
# The main job on the default example: installs what is missing, builds, and evaluates the thesis's
# best sine actuator (A = 4.1, phase 0.5..pi-0.5) inflated and stretched. Results go to out/example/.
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
echo "example: wrote $out/{inflate,stretch}.json and $out/{initial,inflated,stretched}.obj"
cat "$out/inflate.json" "$out/stretch.json"
