#!/usr/bin/env bash
# threads.sh -- the results do not depend on the number of OpenMP threads.
#
# The assembly computes its elements in parallel into per-element arrays
# and adds them up serially in element order (src/solver.f90, assemble),
# and the commit treats each element alone, so a run with one thread and
# a run with two must give the same results bit for bit: every output
# file equal, summary.txt equal but for cpu_seconds.  Two decks, both
# shortened to a pull of 0.5h (about 1 s in all):
#   a) input/fig5a_beadA_steel.nml (paper section, clamped, friction);
#   b) input/cc_fig9c_beadA_steel_free.nml (contact section, free edge).
# OMP_NUM_THREADS=2 asks for two threads whatever the number of cores;
# OMP_WAIT_POLICY=passive (waiting threads sleep at once) keeps the
# two-thread runs short on a busy machine, and changes no result.
# A binary built without OpenMP (make OPENMP_FLAGS=) passes trivially.
# Usage: tests/threads.sh [path/to/drawbead]   (run from anywhere)
# Exit status 0 if both decks agree, 1 otherwise, 2 if the test cannot run.
set -u
cd "$(dirname "$0")/.." || exit 2
bin=${1:-${DRAWBEAD:-bin/drawbead}}
[[ -x $bin ]] || { echo "threads.sh: no executable '$bin'" >&2; exit 2; }
work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
failures=0

# check NAME DECK: run DECK (pull shortened to 0.5h) with 1 and 2 threads
# and compare every output
check() {
    local name=$1 deck=$2 h n f differ=0
    h=$(awk -F'=' '$1 ~ /^ *thickness *$/ { gsub(/[ ,]/, "", $2); print $2 }' "$deck")
    [[ -n $h ]] || { echo "FAIL $name: no thickness in $deck"; failures=$((failures + 1)); return; }
    sed "s/^ *pull_distance *=.*/   pull_distance = $(awk -v h="$h" 'BEGIN { print 0.5 * h }')/" \
        "$deck" >"$work/$name.nml"
    for n in 1 2; do
        if ! OMP_NUM_THREADS=$n OMP_WAIT_POLICY=passive "$bin" "$work/$name.nml" --output "$work/$name.$n" \
            >"$work/$name.$n.log" 2>&1; then
            echo "FAIL $name: the run with $n thread(s) exited non-zero:"
            sed 's/^/    /' "$work/$name.$n.log"
            failures=$((failures + 1))
            return
        fi
        grep -v '^cpu_seconds = ' "$work/$name.$n/summary.txt" >"$work/$name.$n.summary"
    done
    if ! grep -q '^final_delta_over_h = 5' "$work/$name.1.summary"; then
        echo "FAIL $name: the shortened run did not reach 0.5h:"
        grep -E '^(status|final_delta_over_h) = ' "$work/$name.1.summary" | sed 's/^/    /'
        failures=$((failures + 1))
        return
    fi
    if ! cmp -s "$work/$name.1.summary" "$work/$name.2.summary"; then
        echo "FAIL $name: summary.txt differs between 1 and 2 threads:"
        diff "$work/$name.1.summary" "$work/$name.2.summary" | head -20 | sed 's/^/    /'
        differ=1
    fi
    for f in "$work/$name.1"/*.dat; do
        if ! cmp -s "$f" "$work/$name.2/${f##*/}"; then
            echo "FAIL $name: ${f##*/} differs between 1 and 2 threads"
            differ=1
        fi
    done
    if ((differ)); then
        failures=$((failures + 1))
    else
        echo "ok   $name: 1 and 2 threads give the same summary and $(find "$work/$name.1" -name '*.dat' | wc -l) .dat files bit for bit"
    fi
}

check fig5a input/fig5a_beadA_steel.nml
check cc_fig9c input/cc_fig9c_beadA_steel_free.nml
((failures == 0)) || exit 1
exit 0
