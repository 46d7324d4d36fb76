#!/usr/bin/env bash
# Installs the Debian 12 packages the workbench builds and tests with, only those that are missing.
# Run as root (or with sudo). Everything comes from Debian: no downloads at build time.
set -euo pipefail

packages=(
  g++ cmake make pkg-config git
  libeigen3-dev              # linear algebra (sim)
  libmetis-dev               # fill-reducing order of the shell models' sparse factorisation (sim)
  libosmesa6-dev             # offscreen OpenGL, OSMesa backend (render)
  libegl-dev libegl-mesa0 libopengl-dev  # offscreen OpenGL, EGL surfaceless backend (render)
  libpng-dev zlib1g-dev      # PNG files (render), archive checksums (app)
  libimgui-dev               # Dear ImGui overlays (render)
  fonts-dejavu-core          # the overlay font (render)
  capnproto libcapnp-dev     # archives and RPC (app)
  libcli11-dev               # command-line options (app)
  libfmt-dev                 # number formatting (app)
  nlohmann-json3-dev         # JSON: experiment files, outputs, checkpoints (app)
  libgtest-dev libgmock-dev  # tests
  libpagmo-dev               # optimizers: CMA-ES, DE, PSO, NSGA-II, ... (sim_optimize; brings Boost and TBB)
  libbenchmark-dev           # benchmarks
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests
  python3-pandas python3-distributed  # the module's tables as DataFrames; Dask as an evaluator (tests)
  python3-deap python3-matplotlib     # examples/ (run by the tests)
  python3-meshio python3-vtk9  # field files (VTU) read by two real clients (tests)
  python3-pil                # Jupyter pictures (_repr_png_) decoded by another library (tests)
  python3-venv python3-setuptools python3-wheel  # pip install python/ into a venv (tests)
  python3-optuna             # actuator.optuna and examples/optuna_study.py (tests)
  python3-nbclient python3-nbformat python3-ipykernel  # examples/*.ipynb executed by the tests
  libcgal-dev                # exported solids checked by an independent library (tests only; header-only, brings GMP and MPFR)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
