#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs every Debian 12 package roifem builds, tests and plots with.
# Idempotent: when everything is present it only checks and returns (no apt-get update).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libsundials-dev          # ARKODE, IDA, SUNLinSol_KLU (6.4)
  libpetsc-real-dev libmumps-dev libopenmpi-dev openmpi-bin   # roifem-mpi (libsundials-dev pulls them in too)
  libeigen3-dev            # sparse matrices, CHOLMOD/KLU wrappers
  libspectra-dev           # Lanczos eigenvalues (highest frequency, stability limits)
  libsuitesparse-dev       # CHOLMOD, KLU
  libopenblas-dev          # fast BLAS for CHOLMOD's supernodal factorization
  libgsl-dev               # odeiv2
  libhdf5-dev              # results files
  libgmsh-dev              # mesh generation and reading
  calculix-ccx             # geometrically nonlinear reference (roifem model-error)
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev   # CGAL Mesh_3: brains from images (roifem mesh --image)
  libnifti2-dev            # NIfTI-1/2 images
  mricron-data             # the Colin27 brain template and the AAL atlas (BSD-3)
  libtomlplusplus-dev      # scenario files
  libcli11-dev             # command line
  libgtest-dev libgmock-dev
  libbenchmark-dev
  clang libclang-rt-14-dev # libFuzzer harnesses (scripts/fuzz.sh)
  clang-format clang-tidy  # scripts/lint.sh (14 on Debian 12)
  python3-h5py python3-matplotlib python3-numpy   # plots (Debian's /usr/bin/python3)
  pybind11-dev python3-dev python3-pytest         # the Python module roifem (python/) and its tests
  libboost-dev             # Beast and Asio: roifem serve's HTTP and WebSocket
  libjs-three              # three.js, which roifem serve's page draws with (served locally)
  chromium                 # the browser test (tests/browser): headless, software WebGL
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The browser test's driver: puppeteer-core from npm, pinned by tests/browser/package-lock.json,
# with the machine's Node.js (Debian's nodejs and npm where it has none).
browser_tests="$(dirname "$0")/../tests/browser"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "setup: installing nodejs npm"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi
if [ ! -f "$browser_tests/node_modules/.package-lock.json" ] ||
   [ "$browser_tests/package-lock.json" -nt "$browser_tests/node_modules/.package-lock.json" ]; then
  echo "setup: installing the browser test's puppeteer-core (npm ci)"
  (cd "$browser_tests" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
echo "setup: all packages present"
