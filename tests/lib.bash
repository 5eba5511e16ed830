#!/usr/bin/env bash
# tests/lib.bash -- sourced by the shell tests that count their checks: the
# program under test, a scratch folder, and the check itself.
#
#   test_begin NAME [PROGRAM]  go to the repository's top; prog = PROGRAM,
#                              else $DRAWBEAD, else bin/drawbead, made
#                              absolute (exit 2, naming NAME, when it is
#                              not executable); tmp = a scratch folder
#                              removed at exit; the counts zeroed
#   check DESCRIPTION COMMAND...
#                              run COMMAND, print "ok   DESCRIPTION" or
#                              "FAIL DESCRIPTION", count it
# The caller prints its own last line from checks and failures and ends
# with ((failures == 0)).

test_begin() {
    cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2
    prog=${2:-${DRAWBEAD:-bin/drawbead}}
    if [[ ! -x $prog ]]; then
        echo "$1: no executable '$prog' (build it first)" >&2
        exit 2
    fi
    [[ $prog == /* ]] || prog=$PWD/$prog
    tmp=$(mktemp -d) || exit 2
    # (expanded at exit: tmp is global)
    # shellcheck disable=SC2064
    trap "rm -rf '$tmp'" EXIT
    failures=0
    checks=0
}

check() {
    local what=$1
    shift
    checks=$((checks + 1))
    if "$@"; then
        echo "ok   $what"
    else
        echo "FAIL $what"
        failures=$((failures + 1))
    fi
}
