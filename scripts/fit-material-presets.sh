#!/bin/sh
# Re-derives the measured silicone presets (sim/src/shell/materials.cpp) from the Soft Robotics
# Materials Database of Marechal et al. 2021 (ODbL): fits every law to each material's raw tensile
# curve with `actuator material fit`, and prints the shipped subset of points (the rows nearest
# 10 %, 20 %, ..., 300 % engineering strain) as C++ rows.
#   scripts/fit-material-presets.sh DATABASE_CHECKOUT [ACTUATOR]
# DATABASE_CHECKOUT is a clone of github.com/LucMarechal/Soft-Robotics-Materials-Database.
set -eu
db=${1:?usage: scripts/fit-material-presets.sh DATABASE_CHECKOUT [ACTUATOR]}
actuator=${2:-build/app/actuator}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in "Ecoflex 00-30" "Ecoflex 00-50" "Dragon Skin 10 MEDIUM" "Dragon Skin 20" "Dragon Skin 30"; do
    echo "== $name"
    # The fit refuses negative stress; Ecoflex 00-50's file has one such row (-0.94 kPa at 4.5 %
    # strain, where its true-stress column is positive: the load cell before the specimen is taut).
    curve="$work/$name.csv"
    python3 - "$db/Tensile-Tests-Data/$name.csv" "$curve" <<'PY'
import sys
lines = open(sys.argv[1], encoding="utf-8-sig").read().splitlines()
head = next(i for i, line in enumerate(lines) if "Engineering Strain" in line)
kept = lines[:head + 1]
for line in lines[head + 1:]:
    fields = line.split(";")
    if len(fields) >= 5 and fields[4] and float(fields[4]) < 0:
        print("dropped a row with negative engineering stress:", line)
        continue
    kept.append(line)
open(sys.argv[2], "w").write("\n".join(kept) + "\n")
PY
    for fit in "neo-hookean" "mooney-rivlin" "yeoh --terms 2" "yeoh --terms 3"; do
        # shellcheck disable=SC2086
        "$actuator" material fit "$curve" --law $fit --out "$work/fit.json" --overwrite | grep -E "^(law|constants|residual|stable|warning)" || true
    done
    python3 - "$curve" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], encoding="utf-8-sig"), delimiter=";"))
head = next(i for i, r in enumerate(rows) if "Engineering Strain" in r)
strain_col = rows[head].index("Engineering Strain")
stress_col = rows[head].index("Engineering Stress (MPa)")
data = [(float(r[strain_col]), float(r[stress_col]) * 1000) for r in rows[head + 1:] if len(r) > stress_col and r[strain_col]]
picked = [min(data, key=lambda p: abs(p[0] - k / 10)) for k in range(1, 31)]
print("    " + ", ".join("{%.5g, %.4g}" % p for p in picked))
PY
done
