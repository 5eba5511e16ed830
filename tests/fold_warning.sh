#!/usr/bin/env bash
# fold_warning.sh -- a run in which the sheet is bent tighter than
# &control fold_curvature (|rho| h) warns once on stderr, still exits 0, and
# summary.txt records where (fold_phase, fold_load_over_h, s_fold_over_h);
# the shipped Fig. 5a deck (|rho| h <= 0.26) reports no fold; neither run
# prints a note of floating-point flags.
# Usage: tests/fold_warning.sh [path/to/drawbead]   (run from anywhere)
set -u
cd "$(dirname "$0")/.." || exit 2
bin=${1:-bin/drawbead}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
value() { awk -F' = ' -v k="$2" '$1 == k { print $2 }' "$1"; }

"$bin" tests/decks/fold_bead_a.nml --output "$out/fold" > "$out/log" 2> "$out/err"
status=$?
if [ "$status" -ne 0 ]; then
    echo "FAIL fold_bead_a: exit status $status"
    exit 1
fi
if [ "$(grep -c '^\*WARNING\* check_fold: the sheet folds: |rho| h = ' "$out/err")" -ne 1 ]; then
    echo "FAIL fold_bead_a: expected one fold warning on stderr, got:"
    cat "$out/err"
    exit 1
fi
phase=$(value "$out/fold/summary.txt" fold_phase)
load=$(value "$out/fold/summary.txt" fold_load_over_h)
s=$(value "$out/fold/summary.txt" s_fold_over_h)
# the fold is found while locking, before full lock (H = h1 + r1 = 6.22h),
# on one of the radii (|s| < 12h on bead A)
if [ "$phase" != lock ] || ! awk -v l="$load" -v s="$s" 'BEGIN { exit !(l > 0 && l <= 6.22 && s * s < 144) }'; then
    echo "FAIL fold_bead_a: fold_phase = $phase, fold_load_over_h = $load, s_fold_over_h = $s"
    exit 1
fi
echo "ok   fold_bead_a: warned, fold at H/h = $load, s/h = $s"

sed -e 's/fold_curvature = 0.2/fold_curvature = 1.0/' tests/decks/fold_bead_a.nml > "$out/nofold.nml"
if ! "$bin" "$out/nofold.nml" --output "$out/nofold" > "$out/log2" 2> "$out/err2" ||
    grep -q 'folds' "$out/err2" || [ "$(value "$out/nofold/summary.txt" fold_phase)" != none ]; then
    echo "FAIL fold_bead_a with fold_curvature = 1: a fold was reported"
    exit 1
fi
echo "ok   fold_bead_a with fold_curvature = 1: no fold"

# a clean run says nothing about floating-point flags: the release build's
# if-converted loops raise flags for discarded lanes (Makefile,
# -ffpe-summary=none), which gfortran would otherwise note at every STOP
if grep -q 'floating-point exceptions' "$out/err" "$out/err2"; then
    echo "FAIL fold_bead_a: gfortran's note of floating-point flags on stderr:"
    cat "$out/err2"
    exit 1
fi
echo "ok   fold_bead_a: no note of floating-point flags"
