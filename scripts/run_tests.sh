#!/usr/bin/env bash
# The test suite: install what is missing, build, run every test with ctest; then rebuild the
# libraries and the DEM, fem and coupling tests with AddressSanitizer +
# UndefinedBehaviorSanitizer and run them.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup_debian.sh"
"$root/scripts/build.sh"
(cd "$root/build" && ctest --output-on-failure -j 2)
echo "== DEM, fem and coupling tests under AddressSanitizer + UndefinedBehaviorSanitizer =="
# One build of the libraries and of those tests' programs, not of the applications (test_app, the
# geohybrid program), which this stage does not run. deal.II, PETSc and Open MPI are not
# instrumented; tests/sanitizer_suppressions.txt names what of theirs is suppressed, and why.
# -g1: line tables only, enough for file:line in the sanitizers' stack traces, and a quarter less
# compile time than full debug information. Release, with these flags: deal.II's set-up of a
# target knows only the Debug and Release flavours.
GEOHYBRID_BUILD_DIR="$root/build-sanitize" GEOHYBRID_BUILD_TARGET=geohybrid_sanitizer_tests "$root/scripts/build.sh" \
  -DGEOHYBRID_SANITIZE=ON -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -g1 -DNDEBUG"
# Left to the Release stage above, as they run the same code as shorter tests here, only for more
# steps: four long DEM physics checks (under ASan+UBSan: biaxial peak friction 126 s, tank
# filling 121 s, the cluster packing's critical step 64 s; the later lifts' growth friction fills
# the small tank twice); the two wrap-around fills (nodes 2.5 mm apart: 227 s; nodes 10 mm apart
# laid in two stages: 85 s, a third of this stage's time on one core, 2026-12-07); the fem pull-out at half the rate (the same pull,
# twice); the three hybrid pull-outs of a small tank (a fill of its particle box
# and a pull each, the DEM's loops 15-20 times slower here: its set-up runs in
# ParticleBoxLifts.SmallTankTheFormerDefaultRefusedSetsUp, the coupled steps in the stepper's,
# the crossing's and the interface's tests); the MPI tests (label mpi: two ranks of Open MPI).
# And, for CI's time (the suite took 1,165 s on 2 cores with them, 2026-12-05), the longer of two
# tests that run one procedure: the lift cache's bit-for-bit fill (32 s here; its refusal test
# takes a lift too), the column's energy balance (22 s; the other columns run the same steps, and
# the multi-rate column its four times more steps), the biaxial moved across thread counts (16 s;
# its consolidation test runs the servo), REDF's size fractions and trapezoid (26 s; its target
# porosity test), the small tank's fill on one and two threads (21 s; its plateau test fills it),
# the fill measured a band above a floor with soil below it (its twin measured a band below a
# lid runs the same fill).
(cd "$root/build-sanitize" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS="suppressions=$root/tests/sanitizer_suppressions.txt" \
  ctest --output-on-failure -j 2 -L '^test_(dem_.*|fem|coupling)$' -LE '^mpi$' \
    -E '^(Biaxial\.PeakFrictionGrowsWithContactFrictionAndServoHolds|TankFilling\.LayersAtTargetPorosityInEquilibriumUnderGravity|TankFilling\.LaterLiftsStartNearTheFrictionOfTheLiftBelow|TankFilling\.SoilGoingOnBelowTheFillIsMeasuredABandAboveTheFloor|TimeStep\.CriticalStepStableForAClusterPacking|WrapAroundFill\..*|PulloutProblem\.HalvingThePullRateLeavesTheCurveUnchanged|HybridPullOut\..*|LiftCache\.ATakenLiftMakesTheSameTankBitForBit|GeostaticColumn\.EnergyBalanceClosesWithGravityAndDamping|MultiRate\.GeostaticColumnKeepsItsStressesAndEnergyBalance|Biaxial\.MovedToOtherThreadCountsMidRunIsBitForBitTheStraightRun|Redf\.SizeFractionsReproducedAtTargetPorosity|Redf\.TrapezoidReachesTargetPorosityAndStress|PullOutTank\.FillWithSheetSameOnOneAndTwoThreads)$')
