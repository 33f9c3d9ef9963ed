#!/usr/bin/env bash
# Installs what lme-mpm needs from Debian (bookworm) packages; does nothing when all of
# it is already there. Needs root (or sudo) only when something is missing.
set -euo pipefail
packages=(libdeal.ii-dev libgtest-dev googletest libboost-program-options-dev libeigen3-dev
          nlohmann-json3-dev
          libbenchmark-dev cmake g++ make python3 python3-matplotlib openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends "${missing[@]}"
