#!/usr/bin/env bash
# Installs the Debian 12 packages geohybrid needs, if any is missing. Nothing is downloaded
# from anywhere else. Needs root (or sudo) only when something must be installed.
set -euo pipefail
packages=(build-essential cmake libdeal.ii-dev libeigen3-dev petsc-dev libhdf5-dev libgtest-dev
          openmpi-bin gnuplot-nox nlohmann-json3-dev
          chromium ${GEOHYBRID_EXTRA_PACKAGES:-}) # chromium: the report test loads its page headless
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
$sudo_cmd apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
