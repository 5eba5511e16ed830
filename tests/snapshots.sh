#!/usr/bin/env bash
# snapshots.sh -- &control snapshot_every: snapshots.dat holds one block of
# strain rows (the columns of strain_pull.dat) at the first converged
# increment at or past each multiple of snapshot_every h of H and of delta.
#  - the clamped strip in tension, snapshot_every = 2.5: the blocks' loads
#    are those the rule picks from pull.dat, each block has 4 n_elements rows
#    of 19 columns, and the strain is uniform, lambda - 1 = delta/(2L) with
#    2L = 50h, to 1e-8 (the strip is uniform: only the Newton residual,
#    1e-8 of the force scale over a tangent of order the flow stress,
#    separates the elements);
#  - bead A locked (lock only), snapshot_every = 1: six 'lock' blocks at
#    H/h >= 1, ..., 6 (full lock is 6.22h), each the first lock.dat row past
#    its multiple;
#  - without snapshot_every there is no snapshots.dat.
# Usage: tests/snapshots.sh [path/to/drawbead]   (run from anywhere)
set -u
cd "$(dirname "$0")/.." || exit 2
bin=${1:-bin/drawbead}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
fail() {
    echo "FAIL $*"
    failures=$((failures + 1))
}

# expected block loads from a load column: the first load at or past each
# multiple of every, one block per row however many multiples it passed
expected_loads() { # file every
    awk -v e="$2" '!/^#/ && NF > 0 {
        if ($1 >= next_at - 1e-9) { printf "%.10f\n", $1; next_at = (int(($1 + 1e-9) / e) + 1) * e }
    } BEGIN { next_at = e }' "$1"
}
block_loads() { # file phase
    awk -v ph="$2" '/^# block / && $4 == ph { printf "%.10f\n", $5 }' "$1"
}

# 1. strip in tension
awk '{ print } /^&control/ { print "   snapshot_every = 2.5" }' input/strip_tension.nml > "$out/strip.nml"
if ! "$bin" "$out/strip.nml" --output "$out/strip" > "$out/log1" 2>&1; then
    fail "strip_tension with snapshot_every = 2.5: non-zero exit"
else
    snap=$out/strip/snapshots.dat
    # rows per block: those of strain_pull.dat (4 per element)
    rows=$(grep -cv '^#' "$out/strip/strain_pull.dat")
    if [ "$(block_loads "$snap" pull)" != "$(expected_loads "$out/strip/pull.dat" 2.5)" ]; then
        fail "strip: block loads differ from the rule applied to pull.dat"
    fi
    nb=$(grep -c '^# block ' "$snap" 2> /dev/null)
    if [ "${nb:-0}" -lt 4 ]; then
        fail "strip: $nb blocks, expected at least 4 (delta_cr is about 12.6h)"
    fi
    # rows and columns per block, blocks numbered 0, 1, ... and separated
    # by two blank lines (gnuplot's index), and the uniform strain
    if ! awk -v n="$rows" '
        /^# block / { if (b != "" && (rows != n || blanks != 2)) bad = 1
                      if ($3 != nblk++) bad = 1
                      b = $3; L = $5; rows = 0; blanks = 0; next }
        NF == 0 { blanks++; next }
        /^#/ { next }
        { rows++; if (NF != 19) bad = 1; d = $4 - L / 50; if (d < 0) d = -d; if (d > dmax) dmax = d }
        END { if (rows != n) bad = 1; printf "max |lambda - 1 - delta/2L| = %.2e\n", dmax > "/dev/stderr";
              exit bad || dmax > 1e-8 }' "$snap" 2> "$out/strip_err"; then
        fail "strip: wrong rows/columns or non-uniform strain ($(cat "$out/strip_err"))"
    else
        echo "ok   strip: $nb blocks of $rows rows, $(cat "$out/strip_err")"
    fi
fi

# 2. bead A, locking only
sed -e 's/^   fold_curvature = 0.2/   fold_curvature = 1.0, snapshot_every = 1.0/' \
    tests/decks/fold_bead_a.nml > "$out/lock.nml"
if ! "$bin" "$out/lock.nml" --output "$out/lock" > "$out/log2" 2>&1; then
    fail "bead A locking with snapshot_every = 1: non-zero exit"
else
    got=$(block_loads "$out/lock/snapshots.dat" lock)
    want=$(expected_loads "$out/lock/lock.dat" 1.0)
    if [ "$got" != "$want" ] || [ "$(echo "$got" | wc -l)" -ne 6 ]; then
        fail "bead A locking: block loads '$got', expected six: '$want'"
    else
        echo "ok   bead A locking: 6 lock blocks at H/h = $(echo "$got" | tr '\n' ' ')"
    fi
fi

# 3. off by default
if ! "$bin" input/strip_tension.nml --output "$out/plain" > /dev/null 2>&1 ||
    [ -e "$out/plain/snapshots.dat" ]; then
    fail "strip without snapshot_every: failed, or wrote snapshots.dat"
else
    echo "ok   no snapshot_every: no snapshots.dat"
fi
exit $((failures > 0))
