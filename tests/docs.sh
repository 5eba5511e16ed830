#!/usr/bin/env bash
# docs.sh -- the documents against the program.
#
# Usage: bash tests/docs.sh PROGRAM   (from the top of the repository;
#        make test runs it with bin/drawbead, make test-check with
#        bin/drawbead-check)
#
# Checks
#   a) the README's first example: every number of its block equals the
#      program's output to the digits shown (scripts/doc_tables.py --check
#      readme_example: one run of input/fig5a_beadA_steel.nml);
#   b) every relative link and image of README.md and docs/*.md points at
#      an existing file (and heading), every table block is known and
#      closed, README.md is at most 10 KB (scripts/doc_tables.py
#      --check-links);
#   c) every namelist variable the program echoes is a row of
#      docs/input-reference.md, and every summary.txt key and output file
#      of a run is in docs/output-reference.md (a run with nothing to do);
#   d) every tests/unit/*.pf, tests/verification/*.pf, tests/*.sh and
#      tests/regression/*.sh (written regression/<name>) is a row of the
#      tables of docs/validation.md, section "The verification ladder",
#      and every row there names one of them.
# Exit status 0 when all pass, 1 otherwise.
set -u -o pipefail

program=${1:-${DRAWBEAD:-}}
if [[ -z $program || ! -x $program ]]; then
    echo "docs.sh: usage: bash tests/docs.sh PROGRAM" >&2
    exit 1
fi
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# a) and b)
python3 scripts/doc_tables.py --bin "$program" --check readme_example || fail "README example"
python3 scripts/doc_tables.py --check-links || fail "links and blocks of the documents"

# c) a run with no tools, no locking and no pulling: the echo of the
# resolved input names every variable; summary.txt holds every key
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '&sheet n_elements = 2 /\n&loading pull_distance = 0 /\n' >"$work/empty.nml"
if ! "$program" "$work/empty.nml" --output "$work/out" >"$work/log" 2>&1; then
    fail "the program did not run an empty deck (see below)"
    cat "$work/log"
fi
variables=$(awk '/^&[A-Z]+/ { in_group = 1; next } /^ *\// { in_group = 0 }
    in_group && match($0, /^ *[A-Z0-9_]+=/) { v = substr($0, RSTART, RLENGTH - 1)
    gsub(/ /, "", v); print tolower(v) }' "$work/log")
[[ -n $variables ]] || fail "no variables found in the echo of the resolved input"
for v in $variables; do
    grep -q "^| \`$v\` |" docs/input-reference.md || fail "docs/input-reference.md has no row for $v"
done
keys=$(awk -F' = ' '!/^#/ && NF == 2 { print $1 }' "$work/out/summary.txt")
[[ -n $keys ]] || fail "no keys in summary.txt"
for k in $keys; do
    grep -q "^| \`$k\` |" docs/output-reference.md || fail "docs/output-reference.md has no row for $k"
done
for f in "$work/out"/*; do
    name=$(basename "$f")
    grep -q "\`$name\`" docs/output-reference.md || fail "docs/output-reference.md does not name $name"
done

# d) the verification ladder: a row per suite and script, none for a file
# that is gone
ladder=$(awk '/^## The verification ladder/ { on = 1; next } on && /^## / { exit } on' docs/validation.md)
rows=$(sed -n "s/^| \`\([^\`]*\)\` |.*/\1/p" <<<"$ladder")
[[ -n $rows ]] || fail "docs/validation.md: no rows in the section 'The verification ladder'"
for f in tests/unit/*.pf tests/verification/*.pf tests/*.sh tests/regression/*.sh; do
    name=${f#tests/}
    case $name in unit/* | verification/*) name=${name#*/} ;; esac
    grep -qxF "$name" <<<"$rows" || fail "docs/validation.md (the verification ladder) has no row for $f"
done
for name in $rows; do
    [[ -f tests/$name || -f tests/unit/$name || -f tests/verification/$name ]] ||
        fail "docs/validation.md (the verification ladder) has a row for $name, not a file of tests/"
done

if ((failures > 0)); then
    echo "docs.sh: $failures failure(s)"
    exit 1
fi
echo "docs.sh: all checks passed"
