#!/usr/bin/env bash
# The main job: install what is missing, build, and run the bundled default input.
# Results: output/dem_deposition/ (summary.json, time_series.csv, particles.xdmf for ParaView).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup_debian.sh"
"$root/scripts/build.sh"
cd "$root"
"$root/build/apps/geohybrid" dem "$root/examples/dem_deposition.prm"
echo "results: $root/output/dem_deposition (summary.json, time_series.csv, time_series.png, particles.xdmf for ParaView)"
