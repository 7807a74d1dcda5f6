#!/usr/bin/env bash
# Installs what shard needs to build, test and plot, from Debian 12 packages.
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
packages=(build-essential cmake ninja-build ccache pkg-config
          libeigen3-dev libyaml-cpp-dev libgmsh-dev gmsh libgtest-dev libgmock-dev libbenchmark-dev
          python3 python3-numpy python3-matplotlib python3-meshio)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq "${missing[@]}"
fi
