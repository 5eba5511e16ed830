#!/usr/bin/env bash
# penetration_warning.sh -- a run whose largest penetration exceeds 0.05h
# warns on stderr (and still finishes with exit status 0).
# Usage: tests/penetration_warning.sh [path/to/drawbead]   (run from anywhere)
set -u
cd "$(dirname "$0")/.." || exit 2
bin=${1:-bin/drawbead}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" tests/decks/soft_penalty.nml --output "$out/run" > "$out/log" 2> "$out/err"
status=$?
if [ "$status" -ne 0 ]; then
    echo "FAIL soft_penalty: exit status $status"
    exit 1
fi
if ! grep -q '^\*WARNING\* run_phase: penetration .*> 0.05h' "$out/err"; then
    echo "FAIL soft_penalty: no penetration warning on stderr"
    exit 1
fi
pen=$(awk -F' = ' '$1 == "max_penetration_over_h" { print $2 }' "$out/run/summary.txt")
echo "ok   soft_penalty: warned, max_penetration_over_h = $pen"
