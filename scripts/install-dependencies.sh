#!/usr/bin/env bash
# Installs the Debian 12 packages pantocat-fem needs (run as root):
# deal.II 9.4 (with SUNDIALS, Trilinos, PETSc, MPI, Boost, UMFPACK, LAPACK),
# the compiler and CMake, GoogleTest, ccache for fast rebuilds, gnuplot for the
# plots, nlohmann-json (header only) for summary.json. Without the packages
# these recommend (gmsh with its GUI libraries, documentation, ImageMagick:
# about half the download), which pantocat-fem does not use.
# With --browser also Debian's chromium, for the test that reads report.html
# in a real browser (ctest -C browser -L browser); the program does not need it.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends libdeal.ii-dev cmake g++ make libgtest-dev ccache gnuplot-nox nlohmann-json3-dev
if [ "${1:-}" = "--browser" ]; then
  $SUDO apt-get install -y -q --no-install-recommends chromium
fi
