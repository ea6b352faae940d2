#!/usr/bin/env bash
# Installs panelrad's build and test dependencies from Debian packages. Idempotent: packages
# already present are left alone, and nothing is fetched when all are there. Needs root (or sudo).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libcgal-dev libgmp-dev libmpfr-dev     # exact predicates and constructions (geometry/)
  libeigen3-dev                          # vectors and dense linear algebra
  libboost-dev                           # header-only: used by CGAL; Boost.Math Legendre zeros (quadrature/)
  libopenmesh-dev                        # the tests' second OFF/OBJ reader (geometry/oracles)
  libgtest-dev libgmock-dev              # GoogleTest
  clang libclang-rt-14-dev libomp-dev    # fuzz/: libFuzzer and clang's sanitizer runtimes, clang's OpenMP
  nlohmann-json3-dev                     # JSON sidecar of OFF scenes (panelrad solve)
  libpng-dev                             # PNG picture of a solved scene
  libcli11-dev                           # command-line option parsing (cli/)
  gnuplot-nox                            # bench/plot_pareto.gp (error-time plot of bench/sweep)
  libopenmpi-dev openmpi-bin             # the MPI build (-DPANELRAD_MPI=ON) and its tests
  pybind11-dev python3-dev               # the Python module (-DPANELRAD_PYTHON=ON)
  python3-numpy python3-scipy python3-pytest  # its arrays, LinearOperator interface and tests
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
