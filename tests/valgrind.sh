#!/usr/bin/env bash
# valgrind.sh -- the program under valgrind's memory checker.
#
# Usage: tests/valgrind.sh [PROGRAM]
#
# PROGRAM (make test's argument) is not the binary checked: valgrind 3.19
# stops with SIGILL on the AVX-512 instructions of the default
# -march=native build, so this script builds bin/drawbead-generic in
# build-generic/ (`make generic-build`: the release flags with ARCH_FLAGS
# empty; up to date after the first time) and runs it, from the repository
# root, under `valgrind --error-exitcode=99 --leak-check=full` on
#   a) tests/decks/strip_tension.nml (a clamped strip, 20 elements, no
#      tools, pulled to localization): exit 0;
#   b) a bead A deck on 24 elements with 5 stations through the thickness,
#      locked 1.5 mm and pulled 0.5h (contact, friction): exit 0;
#   c) the round profile bead (input/round_bead.nml: profile files) on 26
#      elements (1.47 mm, no longer than its 1.5 mm arcs), locked and
#      pulled 0.2h: exit 0;
#   d) tests/decks/bad_wrong_type.nml (the input-error path): exit 1.
# The four run two at a time, one OpenMP thread each (OMP_NUM_THREADS=1:
# batch runs take one thread each, and libgomp's pool thread, never joined,
# would show as a possible leak).  Any valgrind error (invalid read or write,
# use of an uninitialised value, a leak definitely or possibly lost) fails
# the check, which prints valgrind's report.  About 10 s on 2 cores (plus
# the first build).  Skipped
# (exit 0) if valgrind is not installed.  Exit status 0 if all pass, 1 if
# any fails, 2 if the test cannot run.
set -u
export OMP_NUM_THREADS=1

cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2

if ! command -v valgrind >/dev/null 2>&1; then
    echo "valgrind.sh: skip: valgrind is not installed"
    exit 0
fi

# a make of our own: make test's jobserver is not passed to this script
unset MAKEFLAGS MFLAGS MAKELEVEL
if ! make -s -j2 generic-build >/dev/null; then
    echo "valgrind.sh: make generic-build failed" >&2
    exit 2
fi
prog=bin/drawbead-generic

tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT

cat >"$tmp/bead_a.nml" <<'EOF'
&sheet
   n_elements = 24
   left_edge = 'free'
/
&material
   thickness_points = 5
/
&tools
   bead = 'rectangular'
   friction = 0.1
/
&loading
   lock_depth = 1.5
   pull_distance = 0.381
/
EOF
# locked to 2.5 of its 3.55 mm (the tools in contact on both faces; the
# full lock's squeeze takes most of the increments) and pulled 0.2h
sed -e 's/n_elements = 80/n_elements = 26/' -e 's/pull_distance = 3.81/pull_distance = 0.1524/' \
    -e 's/lock_depth = 3.55/lock_depth = 2.5/' input/round_bead.nml >"$tmp/round_bead.nml"

# vg NAME DECK: runs DECK under valgrind; its exit status into NAME.rc
vg() {
    valgrind --error-exitcode=99 --leak-check=full \
        "$prog" -o "$tmp/out_$1" "$2" >"$tmp/$1.out" 2>"$tmp/$1.err"
    echo $? >"$tmp/$1.rc"
}

failures=0
# check NAME EXPECTED_EXIT: the exit status and valgrind's error summary
check() {
    local name=$1 want=$2 rc
    rc=$(<"$tmp/$name.rc")
    if ((rc == want)) && grep -q 'ERROR SUMMARY: 0 errors' "$tmp/$name.err"; then
        echo "ok   $name: exit $rc, no valgrind error"
    else
        echo "FAIL $name: exit $rc (expected $want); valgrind says:"
        grep '^==[0-9]*==' "$tmp/$name.err" | sed 's/^/    /'
        failures=$((failures + 1))
    fi
}

start=$SECONDS
# the profile-tool run is the longest (about 5 s under valgrind): the
# other three run one after another beside it
vg round_bead "$tmp/round_bead.nml" &
{
    vg strip_tension tests/decks/strip_tension.nml
    vg bead_a "$tmp/bead_a.nml"
    vg bad_wrong_type tests/decks/bad_wrong_type.nml
} &
wait
check strip_tension 0
check bead_a 0
check round_bead 0
check bad_wrong_type 1

echo "valgrind.sh: 4 runs, $failures failed, $((SECONDS - start)) s"
((failures == 0))
