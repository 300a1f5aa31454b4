#!/usr/bin/env bash
# The test suite: install what is missing, build, run every test with ctest; then rebuild the
# DEM library and its tests with AddressSanitizer + UndefinedBehaviorSanitizer and run them.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup_debian.sh"
"$root/scripts/build.sh"
(cd "$root/build" && ctest --output-on-failure -j 2)
echo "== DEM tests under AddressSanitizer + UndefinedBehaviorSanitizer =="
# -g1: line tables only, enough for file:line in the sanitizers' stack traces, and a quarter less
# compile time than full debug information.
GEOHYBRID_BUILD_DIR="$root/build-sanitize" "$root/scripts/build.sh" \
  -DGEOHYBRID_SANITIZE=ON -DGEOHYBRID_WITH_DEALII=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
# Four long physics checks are left to the Release stage above: they run the same code as the
# shorter tests here, only for more steps (under ASan+UBSan: biaxial peak friction 126 s, tank
# filling 121 s, the cluster packing's critical step 64 s, nearly half of this stage's CPU; the
# later lifts' growth friction fills the small tank twice).
(cd "$root/build-sanitize" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure -j 2 -L test_dem \
    -E '^(Biaxial\.PeakFrictionGrowsWithContactFrictionAndServoHolds|TankFilling\.LayersAtTargetPorosityInEquilibriumUnderGravity|TankFilling\.LaterLiftsStartNearTheFrictionOfTheLiftBelow|TimeStep\.CriticalStepStableForAClusterPacking)$')
