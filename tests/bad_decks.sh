#!/usr/bin/env bash
# bad_decks.sh -- every tests/decks/bad_*.nml must be rejected.
#
# Usage: tests/bad_decks.sh [binary]     (default binary: bin/drawbead)
#
# The binary path is taken relative to the repository root, which is the
# parent of this script's directory; the script runs from there. For each
# deck the program must exit with status 1 (input error) and its stderr must
# name what the deck's first line, "! expect: <name>", gives: a variable
# (stderr must contain "variable <name>") or a group written '&group'
# (stderr must contain "group &group"). Matching "variable <name>" rather
# than the bare name keeps a deck's file name (bad_left_edge.nml) from
# passing for the message. A comment line "! message: <text>" in the deck
# asks for that text in stderr too. A deck may take 60 s at most (a hang, such as
# an endless curve file read forever, is a failure, not a stalled test).
# One line is printed per deck; the exit status is
# 0 when all decks pass, 1 when any fails, 2 when the script cannot run.
set -u

cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2

bin=${1:-bin/drawbead}
if [[ ! -x $bin ]]; then
    echo "bad_decks: no executable '$bin' (build it first)" >&2
    exit 2
fi

stderr_file=$(mktemp)
trap 'rm -f "$stderr_file"' EXIT

shopt -s nullglob
decks=(tests/decks/bad_*.nml)
if ((${#decks[@]} == 0)); then
    echo "bad_decks: no tests/decks/bad_*.nml found" >&2
    exit 2
fi

failures=0
for deck in "${decks[@]}"; do
    first_line=$(head -n 1 "$deck")
    expect=${first_line#*expect:}
    expect=${expect#"${expect%%[![:space:]]*}"}
    expect=${expect%"${expect##*[![:space:]]}"}
    if [[ $first_line != *expect:* || -z $expect ]]; then
        echo "FAIL $deck: first line must be '! expect: <variable>'"
        failures=$((failures + 1))
        continue
    fi

    message=$(sed -n 's/^! message: *//p' "$deck" | head -n 1)

    if [[ $expect == '&'* ]]; then
        pattern="group $expect"
    else
        pattern="variable $expect"
    fi

    timeout -k 2 60 "$bin" "$deck" >/dev/null 2>"$stderr_file"
    status=$?

    if ((status == 124 || status == 137)); then
        echo "FAIL $deck: no end within 60 s (a hang)"
        failures=$((failures + 1))
    elif ((status != 1)); then
        echo "FAIL $deck: exit status $status, expected 1"
        failures=$((failures + 1))
    elif ! grep -qF -- "$pattern" "$stderr_file"; then
        echo "FAIL $deck: stderr does not contain '$pattern':"
        sed 's/^/    /' "$stderr_file"
        failures=$((failures + 1))
    elif [[ -n $message ]] && ! grep -F -- "$pattern" "$stderr_file" | grep -qF -- "$message"; then
        echo "FAIL $deck: no stderr line holds both '$pattern' and '$message':"
        sed 's/^/    /' "$stderr_file"
        failures=$((failures + 1))
    else
        echo "ok   $deck ($expect)"
    fi
done

echo "bad_decks: ${#decks[@]} decks, $failures failed"
((failures == 0))
