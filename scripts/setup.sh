#!/usr/bin/env bash
# Installs the build and run-time dependencies from Debian 12's archive (idempotent, as root).
# `setup.sh fuzz` adds clang and its sanitizer runtimes for the fuzz harnesses; `setup.sh package`
# what CPack's Debian generator needs (dpkg-shlibdeps) and debootstrap for test-package.sh;
# `setup.sh browser` headless Chromium for the web page's test;
# `setup.sh slurm` Slurm, munge and GNU parallel for test-slurm.sh.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config ccache
  libcgal-dev libembree-dev libopenmesh-dev libeigen3-dev libtbb-dev libgmp-dev
  libosmesa6-dev libegl-dev libegl-mesa0 libgles-dev libgl-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  libcli11-dev libnanoflann-dev libmatio-dev nlohmann-json3-dev libfmt-dev libssl-dev libassimp-dev libcairo2-dev libpng-dev libjpeg-dev libjs-three
  python3 python3-dev python3-matplotlib python3-numpy python3-pytest pybind11-dev python3-open3d
)
if [ "${1:-}" = browser ]; then packages+=(chromium); fi
if [ "${1:-}" = fuzz ]; then packages+=(clang libclang-rt-14-dev); fi
if [ "${1:-}" = package ]; then packages+=(dpkg-dev file debootstrap); fi
if [ "${1:-}" = slurm ]; then packages+=(slurm-wlm munge parallel); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  source "$(dirname "$0")/step.sh"
  step "apt-get update" $sudo_cmd apt-get update -qq
  step "installing ${#missing[@]} Debian packages: ${missing[*]}" \
    env DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
