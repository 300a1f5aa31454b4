#!/usr/bin/env bash
# The main job: install what is missing, build, and run the bundled default input, the hybrid
# DEM-FEM pull-out of a wrap-around anchorage (GT230, sand 1, H = 0.4 m, B = 0.25 m: the
# reference paper's Figure 9) at a size that runs in a few minutes on 2 cores.
# Results: output/pullout_hybrid_wraparound_h040_b025/ (summary.json, pullout_curve.png, the
# curve and tension profiles as CSV).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup_debian.sh"
"$root/scripts/build.sh"
cd "$root"
# OpenMP's wait policy is left to the environment: libgomp's default spins between a step's
# parallel regions, twice as fast as PASSIVE on a quiet machine; on one shared with other work,
# export OMP_WAIT_POLICY=PASSIVE first (bench/RESULTS.md, "The OpenMP wait policy").
# --overwrite: a second run of the job replaces the first one's files (only those geohybrid writes).
"$root/build/apps/geohybrid" pullout "$root/examples/pullout_hybrid_wraparound_h040_b025.prm" --overwrite
echo "results: $root/output/pullout_hybrid_wraparound_h040_b025 (summary.json, pullout_curve.png, pullout_curve.csv, sheet_tension.csv, sheet_displacements.csv)"
echo "a demonstration of the workflow: the figure to compare with the experiment is the full-size one beside it in pullout_curve.png (validation/REPORT.md)"
