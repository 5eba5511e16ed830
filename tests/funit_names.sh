#!/usr/bin/env bash
# funit_names.sh -- the lite test runner (tests/pfunit_lite.py and the funit
# module of tests/funit_lite.f90) refuses what the real pFUnit 4.14 would
# refuse or silently mis-read:
#   a) a local, a dummy argument or a procedure named like something the real
#      funit exports (fHamcrest's is, near, ...) is a compile error;
#   b) @test(disable), a test subroutine with a prefix (pure) or with a
#      statement after it on its line, and @disable away from its @test are
#      errors of the converter (pFUnit would run or lose those tests);
#   c) with PFUNIT_DIR set (make test PFUNIT_DIR=...), the lite funit
#      exports every name the real one exports (a newer pFUnit may add some).
# Usage: tests/funit_names.sh   (run from anywhere; FC defaults to gfortran)
set -u
cd "$(dirname "$0")/.." || exit 2
fc=${FC:-gfortran}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
ok() { echo "ok   $1"; }
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

if ! "$fc" -ffree-line-length-none -J "$tmp" -c -o "$tmp/funit.o" tests/funit_lite.f90; then
    echo "FAIL tests/funit_lite.f90 does not compile"
    exit 1
fi

# suite NAME BODY: write $tmp/NAME.pf, a test module holding BODY.
suite() {
    printf 'module %s\n   use funit\n   implicit none\ncontains\n%s\nend module %s\n' \
        "$1" "$2" "$1" > "$tmp/$1.pf"
}
# compiles NAME: convert and compile $tmp/NAME.pf; the messages in $tmp/NAME.err
compiles() {
    python3 tests/pfunit_lite.py convert "$tmp/$1.pf" "$tmp/$1.f90" > "$tmp/$1.err" 2>&1 &&
        "$fc" -ffree-line-length-none -I "$tmp" -J "$tmp" -c -o "$tmp/$1.o" \
            "$tmp/$1.f90" >> "$tmp/$1.err" 2>&1
}

# a) clashes with the names of the real funit
suite test_clean "   @test
   subroutine test_a()
      integer :: k
      k = 1
      @assertEqual(1, k)
   end subroutine test_a"
if compiles test_clean; then ok "a clean suite compiles"; else fail "a clean suite does not compile:"; cat "$tmp/test_clean.err"; fi

suite test_local_is "   @test
   subroutine test_a()
      integer :: is
      is = 1
      @assertEqual(1, is)
   end subroutine test_a"
if ! compiles test_local_is && grep -q "‘is’\|'is'" "$tmp/test_local_is.err"; then
    ok "a local 'is' (fHamcrest) is a compile error"
else
    fail "a local 'is' is accepted"; cat "$tmp/test_local_is.err"
fi

suite test_dummy_near "   pure real(kind(1.0d0)) function half(near) result(h) ! near: fHamcrest
      real(kind(1.0d0)), intent(in) :: near
      h = 0.5d0*near
   end function half"
if ! compiles test_dummy_near && grep -q "‘near’\|'near'" "$tmp/test_dummy_near.err"; then
    ok "a dummy argument 'near' (fHamcrest) is a compile error"
else
    fail "a dummy argument 'near' is accepted"; cat "$tmp/test_dummy_near.err"
fi

suite test_helper_run "   subroutine run()
   end subroutine run"
if ! compiles test_helper_run && grep -q "‘run’\|'run'" "$tmp/test_helper_run.err"; then
    ok "a procedure 'run' (pFUnit) is a compile error"
else
    fail "a procedure 'run' is accepted"; cat "$tmp/test_helper_run.err"
fi

# b) directives pFUnit would read otherwise
refused() { # refused LABEL NAME BODY PATTERN
    suite "$2" "$3"
    if ! compiles "$2" && grep -q "$4" "$tmp/$2.err"; then
        ok "$1 is refused"
    else
        fail "$1 is accepted"; cat "$tmp/$2.err"
    fi
}
refused "@test(disable)" test_opt "   @test(disable)
   subroutine test_a()
   end subroutine test_a" "write @disable on the line after @test"
refused "a pure test subroutine" test_pure "   @test
   pure subroutine test_a()
   end subroutine test_a" "subroutine test_a: write"
refused "a statement after the test subroutine" test_semi "   @test
   subroutine test_a(); integer :: k
      k = 1
   end subroutine test_a" "subroutine test_a: write"
refused "@disable after the subroutine" test_late "   @test
   subroutine test_a()
   @disable
   end subroutine test_a" "@disable must stand between"

suite test_disabled "   @test
   @disable
   subroutine test_a()
   end subroutine test_a"
if compiles test_disabled && python3 tests/pfunit_lite.py driver "$tmp/run.f90" "$tmp/test_disabled.pf" &&
    grep -q "funit_skip_test('test_disabled', 'test_a')" "$tmp/run.f90"; then
    ok "@test then @disable: the test is counted as disabled"
else
    fail "@test then @disable"; cat "$tmp/test_disabled.err"
fi

# c) the lite funit against the real one: the names each exports, from
# gfortran's dump of a program that uses it
# (the probe has a folder of its own: gfortran looks for modules in the
# source's folder first, and $tmp holds the lite funit.mod)
names() { # names INCLUDE_DIR: the public names of module funit there
    mkdir -p "$tmp/probe"
    printf 'program probe\nuse funit\nend program probe\n' > "$tmp/probe/probe.f90"
    "$fc" -fsyntax-only -fdump-fortran-original -I "$1" "$tmp/probe/probe.f90" |
        sed -n "s/^ *symtree: '\([A-Za-z][A-Za-z0-9_]*\)'.*/\1/p" |
        tr '[:upper:]' '[:lower:]' | grep -vx probe | sort -u
}
if [ -n "${PFUNIT_DIR:-}" ] && [ -f "$PFUNIT_DIR/include/funit.mod" ]; then
    names "$PFUNIT_DIR/include" > "$tmp/real.txt"
    names "$tmp" > "$tmp/lite.txt"
    # module names are not entities a test could declare
    missing=$(comm -23 "$tmp/real.txt" "$tmp/lite.txt" | grep -vx 'funit\|fhamcrest\|iso_fortran_env')
    if [ "$(wc -l < "$tmp/real.txt")" -gt 50 ] && [ -z "$missing" ]; then
        ok "the lite funit exports all $(wc -l < "$tmp/real.txt") names of $PFUNIT_DIR's funit"
    else
        fail "names of the real funit missing from tests/funit_lite.f90: ${missing//$'\n'/ }"
    fi
else
    echo "skip the comparison with the real funit (PFUNIT_DIR is not set)"
fi

echo "funit_names.sh: $fails failed"
[ "$fails" -eq 0 ]
