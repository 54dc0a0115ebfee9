#!/usr/bin/env bash
# Installs the Debian packages mddual needs to build, test and benchmark.
# Idempotent: packages already present are skipped, and when everything is
# present the script returns without touching apt at all.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libqhull-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libfcl-dev libccd-dev libbullet-dev
  libompl-dev ompl-demos liburdfdom-dev libassimp-dev
  libyaml-cpp-dev libtinyxml2-dev liborocos-kdl-dev libkdl-parser-dev
  libboost-filesystem-dev libboost-serialization-dev libboost-system-dev
  python3 python3-matplotlib
  python3-dev python3-numpy python3-pytest pybind11-dev python3-pybind11
  python3-pip python3-venv python3-setuptools python3-wheel
  clang libclang-rt-14-dev ninja-build
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
