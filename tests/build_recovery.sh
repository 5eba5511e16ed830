#!/usr/bin/env bash
# build_recovery.sh -- the build recovers by itself from an object whose
# module file is missing (issue 28, item 11: two makes at once left
# build/band.o without build/band.mod, and every later make failed with
# "Cannot open module file 'band.mod'" until make clean).
#
# Usage: tests/build_recovery.sh [binary]   (the binary is not used)
#
# Builds the library in a temporary build directory with quick flags
# (-O0, no LTO: about 15 s on 2 cores), deletes band.mod and the object of
# a module that uses it (solver.o, so that something needs band.mod), runs
# make again and expects it to succeed with both files back. Exit status
# 0 if it does, 1 if not, 2 if the test cannot run.
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2
command -v makedepf90 >/dev/null 2>&1 || { echo "build_recovery: no makedepf90" >&2; exit 2; }
work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
build=$work/build
# a make of its own (not the jobserver of the make running the tests)
quick_make() {
    env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -j2 -s BUILD="$build" \
        FFLAGS='-std=f2008 -fimplicit-none -O0' lib >>"$work/log" 2>&1
}
failures=0
if ! quick_make; then
    echo "build_recovery: the first build failed:"; tail -n 5 "$work/log"
    exit 2
fi
rm -f "$build/band.mod" "$build/solver.o"
if quick_make && [[ -f $build/band.mod && -f $build/solver.o ]]; then
    echo "ok   make rebuilds band.o when band.mod is missing (and then solver.o, which uses it)"
else
    echo "FAIL make after deleting band.mod and solver.o:"; tail -n 5 "$work/log" | sed 's/^/    /'
    failures=1
fi
echo "build_recovery: $failures failed"
((failures == 0))
