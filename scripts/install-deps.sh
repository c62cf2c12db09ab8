#!/usr/bin/env bash
# Installs every Debian 12 package tcpmsim needs to build, test, run, plot and benchmark.
# Debian is the only package source. Safe to re-run: it skips apt when all are present.
set -euo pipefail

packages=(
  g++ make cmake git pkg-config            # toolchain; git stamps the commit into records
  ninja-build                              # the build trees' generator (scripts/test.sh)
  libsundials-dev                          # CVODE with dense, band and KLU linear solvers
  libeigen3-dev                            # linear algebra
  libyaml-cpp-dev                          # scenario files
  libhdf5-dev                              # HDF5 C++ API for the records
  libudunits2-dev                          # unit parsing and conversion at the config boundary
  libcli11-dev                             # command line
  catch2                                   # tests (v2)
  libopenmpi-dev openmpi-bin               # sweeps on clusters: mpirun -n K tcpmsim sweep
  libceres-dev                             # fit: Levenberg-Marquardt with bounds (Ceres Solver)
  nlohmann-json3-dev                       # fit and discover reports as JSON
  libboost-dev                             # Boost.Math: the chi-squared tail of the Ljung-Box test
  libzip-dev libxml2-dev                   # export-fmu: the .fmu archive, its description's rules
  clang libclang-rt-14-dev                 # libFuzzer targets (scripts/fuzz.sh)
  python3 python3-h5py python3-numpy python3-matplotlib python3-scipy  # plots, benchmark
  python3-dev pybind11-dev                 # the Python module (pybind11: the standard C++ binding)
  python3-cvxopt                           # the QP of examples/mpc_controller.py
  python3-build python3-setuptools python3-wheel python3-venv python3-pip  # the wheel, a venv
  python3-sphinx python3-myst-parser furo python3-yaml  # the documentation site (scripts/docs.sh)
  python3-nbsphinx pandoc python3-nbclient python3-ipykernel  # its notebooks: run, rendered
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  sudo=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
