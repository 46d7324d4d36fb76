#!/usr/bin/env bash
# The main job on a default example: installs what is missing, builds, installs `actuator` on the
# PATH, and makes the journey a researcher makes from a search to a part on the bench:
#   1. a short multi-objective search (NSGA-II, contraction against peak stretch) for a braided
#      B-spline muscle of Ecoflex 00-30 inside an envelope of 2.5 tube radii;
#   2. the chosen design's characteristic curves (force against contraction at two pressures);
#   3. its cast-ready export: the mould to print, what to mix and pour, the winding plan, in order.
# Results go to out/example/ (replaced on every run); out/example/report.md says what is where.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cmake --install "${BUILD_DIR:-build}" > /dev/null
out=out/example
rm -rf "$out"
mkdir -p "$out"

echo "example: 1/3 searching (NSGA-II over braided B-spline muscles in a 2.5-radius envelope) ..."
actuator evolve assets/experiments/optimizers/O5.2F_nsga2_shell.json --out "$out/search" > "$out/search.json"

# The design that contracts most on the front (the search's other objective, the peak stretch, is
# in its record).
id=$(actuator inspect "$out/search/evaluations.capnp" --top 1 --json |
  python3 -c 'import json, sys; print(json.load(sys.stdin)["evaluations"][0]["id"])')

echo "example: 2/3 characteristic curves of design $id ..."
actuator characterize --from "$out/search/evaluations.capnp" --index "$id" --pressures-kpa 0.2,0.4 --points 5 \
  --out "$out/curves" > "$out/curves.json"

echo "example: 3/3 cast-ready export of design $id ..."
# A one-piece core is refused when the wall cannot stretch over it on the way out; then the core is
# printed to dissolve instead.
if ! actuator export --from "$out/search/evaluations.capnp" --index "$id" --out "$out/part" > "$out/part.json" 2> "$out/export_refusal.txt"; then
  echo "example: $(cat "$out/export_refusal.txt")"
  echo "example: exporting with a lost core instead"
  actuator export --from "$out/search/evaluations.capnp" --index "$id" --core lost --out "$out/part" > "$out/part.json"
fi
rm -f "$out/export_refusal.txt"

python3 - "$out" "$id" <<'PY'
import json, pathlib, sys

out, design = pathlib.Path(sys.argv[1]), int(sys.argv[2])
search = json.loads((out / "search.json").read_text())
record = json.loads((out / "curves.json").read_text())
manifest = json.loads((out / "part" / "manifest.json").read_text())
top = record["isobaric"][-1]
shape = record["shape"]
lines = [
    "# From a search to a part on the bench",
    "",
    f"1. **Search** ({search['experiment']}): {search['details'][0]}; {search['seconds']:.0f} s.",
    "   The front: [search/pareto_front.png](search/pareto_front.png), its designs:"
    " [search/pareto_designs.png](search/pareto_designs.png), the report: [search/report.md](search/report.md).",
    f"2. **Chosen design**: evaluation {design}, the front's largest contraction: B-spline control points"
    f" {', '.join(f'{c:g}' for c in shape['control_points'][0])} (x 5 mm radius), a braid at"
    f" +/-{record['model']['fibre_angle_deg']:.1f} deg to the meridian, {record['silicone_mass_g']:.1f} g of silicone.",
    f"3. **Characteristic curves** at {', '.join(str(p['pressure_kpa']) for p in record['isobaric'])} kPa:"
    f" at {top['pressure_kpa']} kPa it shortens freely by {top['free_stroke_percent']:.2f} % and pulls"
    f" {top['force_at_no_contraction_n']:.3f} N held at its rest length; one stroke does {top['work_per_stroke_mj']:.3f} mJ."
    " [curves/force_contraction.png](curves/force_contraction.png), [curves/force_pressure.png](curves/force_pressure.png).",
    f"4. **Cast-ready export** in [part/](part/): a {manifest['core']['kind']} core, the mould's parts in"
    " [part/mold_assembly.png](part/mold_assembly.png); the steps follow (from [part/casting.md](part/casting.md)).",
    "",
]
sheet = (out / "part" / "casting.md").read_text().splitlines()
lines += ["#" + line if line.startswith("#") else line for line in sheet]  # one level down
(out / "report.md").write_text("\n".join(lines) + "\n")
PY

echo "example: done in $out/:"
echo "  report.md                 the journey: search, chosen design, curves, and what to print, mix, pour and wind, in order"
echo "  search/                   the NSGA-II run (pareto_front.png, pareto_designs.png, report.md, evaluations.capnp)"
echo "  curves/                   characteristic curves of the chosen design (force_contraction.png, characteristic.csv)"
echo "  part/                     STL files of the mould, mold_assembly.png, casting.md, manifest.json"
