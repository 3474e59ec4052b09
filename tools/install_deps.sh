#!/usr/bin/env bash
# Installs the Debian 12 packages grainflow needs to build, test and plot; with `fuzz`, also clang
# with libFuzzer and its OpenMP runtime (for `make fuzz`, not needed by `make test`). python3-vtk9: the
# integration test that reads the snapshots with VTK's own readers (tests/integration/test_vtu_reader.py);
# pybind11, pytest, nbconvert and ipykernel: the Python module and its tests (the example notebook).
# Idempotent: installs only what is missing; runs apt-get update first on a fresh machine.
# Usage: tools/install_deps.sh [fuzz]
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libtomlplusplus-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfftw3-dev libhdf5-dev hdf5-tools
  libopenmpi-dev openmpi-bin
  python3-matplotlib python3-numpy python3-h5py python3-pil python3-vtk9
  python3-dev pybind11-dev python3-pytest jupyter-nbconvert python3-nbformat python3-ipykernel
)
if [ "${1:-}" = fuzz ]; then packages+=(clang libclang-rt-14-dev libomp-dev); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install_deps: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
