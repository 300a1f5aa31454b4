#!/usr/bin/env bash
# The validation campaign as `geohybrid sweep` files (bench/run_validation --sweep-files): every
# member of the committed sweeps of the 0.05 m/s campaign (validation/campaign_0.05/sweeps/) has
# the parameters_hash of that case's and seed's committed run (validation/campaign_0.05/runs/),
# so the sweep files are the campaign, entry for entry; the generator, run again into a temporary
# directory, gives the same hashes; and another interface angle gives none of them.
# Usage: tests/test_validation_sweeps.sh REPOSITORY GEOHYBRID   (ctest: validation_sweeps)
set -euo pipefail
repo="$(cd "$1" && pwd)" geohybrid="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
archive="$repo/validation/campaign_0.05"
failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }

# "case seed hash" of every member of the sweep files in $1, the cases read from each file's header.
member_hashes() {
  local f cases c k i
  for f in wraparounds_table3 wraparounds_table6 runouts; do
    "$geohybrid" sweep "$1/$f.prm" --print-parameters-hash > "$tmp/$f.hashes" || { fail "$1/$f.prm refused"; continue; }
    cases="$(sed -n 's/^# The cases, in this order, each crossed with the seeds: //p' "$1/$f.prm" | tr ',' ' ')"
    i=0
    for c in $cases; do for k in 1 2 3; do
      i=$((i + 1)); echo "$c $k $(sed -n "${i}p" "$tmp/$f.hashes" | awk '{ print $2 }')"
    done; done
    [[ "$(wc -l < "$tmp/$f.hashes")" -eq "$i" ]] || fail "$f: $(wc -l < "$tmp/$f.hashes") members for $i cases x seeds"
  done
}
committed() { sed -n 's/^ *"parameters_hash": "\([0-9a-f]*\)".*/\1/p' "$archive/runs/$1/seed$2/summary.json"; }

n=0
while read -r c k h; do
  n=$((n + 1))
  [[ "$h" == "$(committed "$c" "$k")" ]] || fail "committed sweeps: $c seed $k: hash '$h', the committed run's '$(committed "$c" "$k")'"
done < <(member_hashes "$archive/sweeps")
(( n == 36 )) || fail "committed sweeps: $n members, the campaign has 12 cases x 3 seeds"

VALIDATION_RUNS="$archive/runs" VALIDATION_RATE=0.05 "$repo/bench/run_validation" --sweep-files "$tmp/again" > /dev/null
[[ "$(member_hashes "$tmp/again")" == "$(member_hashes "$archive/sweeps")" ]] || fail "the generator run again gives other members"
VALIDATION_RUNS="$archive/runs" VALIDATION_RATE=0.05 VALIDATION_DELTA=41 "$repo/bench/run_validation" --sweep-files "$tmp/other" > /dev/null
while read -r c k h; do
  [[ "$h" != "$(committed "$c" "$k")" ]] || fail "at 41 deg, $c seed $k has the 40.11 deg run's hash"
done < <(member_hashes "$tmp/other")

if (( failures > 0 )); then exit 1; fi
echo "validation sweeps: the $n members are the committed runs, entry for entry"
