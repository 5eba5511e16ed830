#!/usr/bin/env bash
# fuzz.sh -- the program on mutated decks, profiles and curve files.
#
# Usage: tests/fuzz.sh [PROGRAM] [--seed N] [--cases N] [--first K] [-j N]
#                      [--timeout S] [--keep DIR] [--no-replay]
#   PROGRAM      the binary (default: $DRAWBEAD, else bin/drawbead)
#   --seed N     seed of the mutations (default 1); the cases are the same
#                for the same seed
#   --cases N    number of mutated cases (default 600; make test runs the
#                default, e.g. --cases 5000 for a longer search)
#   --first K    number of the first case (default 0): `--first 1234
#                --cases 1` runs case 1234 of a longer run alone
#   -j N         cases run at a time (default 2)
#   --timeout S  seconds of CPU a case may use (default 120): more is a
#                hang; one that uses none (blocked) is stopped after 10 S
#                seconds of wall time
#   --keep DIR   where the failing cases go (default out/fuzz_failures;
#                emptied first)
#   --no-replay  skip part a)
#
# Runs from the repository root (the parent of this script's directory).
#   a) replay: every tests/decks/fuzz_*.nml, a crash the fuzzer once found
#      made into a small deck, must give the outcome its first line names:
#      "! expect: <variable>" or "! expect: &<group>": exit status 1 and a
#      stderr line naming the deck ("deck 'tests/decks/fuzz_...nml'") and
#      "variable <variable>" or "group &<group>";
#      "! expect: no crash": any acceptable outcome (below).
#   b) fuzz: scripts/fuzz_inputs.py writes the mutated cases (each its own
#      directory: deck.nml, the files it names, what.txt listing the base
#      files and mutations); each runs as `drawbead -o out deck.nml` in its
#      directory under a CPU-time limit (`ulimit -t`; a wall-time limit
#      ten times longer under `timeout`) and a 2 GB address-space limit.  An
#      acceptable outcome is
#        - exit 0 with out/summary.txt valid: one `status = ` line saying
#          completed, localized or torn, every `key = value` a finite number,
#          `none` or a known word (a status or a phase);
#        - exit 1, 2, 3, 4 or 5 with an `*ERROR*` line on stderr (and, with
#          2, 4 or 5, a summary, if any, valid as above, its status
#          no_convergence, interrupted or out_of_memory);
#      and never: a signal (exit > 128), a hang (timeout's 124, or killed
#      at the CPU limit: SIGKILL 137, SIGXCPU 152), another
#      exit status, or a Fortran runtime error or backtrace on stderr
#      ("Fortran runtime error", "Error termination", "Backtrace",
#      "Program received signal", "SIGSEGV", "Floating-point exception").
#      Each failing case is copied to the --keep directory with cmd.sh
#      (replays it), stdout.txt, stderr.txt and verdict.txt; the distinct
#      failures are listed, each with a count and its first case.
# 600 cases take about 8 s on 2 cores (the checked build: about 65 s); the
# replay, the time limit once if any deck hangs.  The limit is on CPU
# time, which the load of a shared machine does not stretch, and far above
# any case's run: a mutation may make a fine mesh that runs to the end
# (case 338 of seed 1, a refined zone of 0.0085 mm, 820 elements: 3 s of
# CPU with the release build, 30 s with the checked one, which took 56 s
# to more than 120 s of wall time on a busy machine), where before Newton
# recognised the round-off floor of such meshes (docs/theory.md §8.2) it
# stopped in its first increment.  Exit status 0 if all pass, 1 if any
# fails, 2 if the test cannot run.
set -u
# the cases run several at a time: one thread each (docs/performance.md)
export OMP_NUM_THREADS=1

cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2
top=$PWD

# ---------------------------------------------------------------------------
# Running one deck and judging its outcome
# ---------------------------------------------------------------------------
runtime_error_re='Fortran runtime error|Error termination|Backtrace|Program received signal|SIGSEGV|Floating-point exception'
summary_words='completed|localized|torn|no_convergence|interrupted|write_failed|out_of_memory|running|lock|pull|none|load_maximum|section|off|zone|first|yes|no'

# summary_problem FILE: prints why FILE is not a valid summary (nothing if it is)
summary_problem() {
    [[ -f $1 ]] || { echo "no summary.txt"; return; }
    awk -v words="^($summary_words)\$" '
        /^#/ || /^[[:space:]]*$/ { next }
        {
            eq = index($0, " = ")
            if (eq == 0) { print "line " NR " is not key = value: " $0; bad = 1; exit }
            key = substr($0, 1, eq - 1); value = substr($0, eq + 3)
            if (key !~ /^[a-z_][A-Za-z0-9_]*$/) { print "line " NR ": bad key " key; bad = 1; exit }
            if (key == "status") { nstatus++; status = value }
            if (value ~ words) next
            if (value !~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eEdD][-+]?[0-9]+)?$/) {
                print "line " NR ": " key " = " value " is not a finite number, none or a known word"
                bad = 1; exit
            }
        }
        END {
            if (bad) exit
            if (nstatus != 1) print nstatus + 0 " status lines"
            else print "status " status
        }' "$1" | grep -v '^status '
}

# summary_status FILE: the value of the status line
summary_status() {
    sed -n 's/^status = //p' "$1" | head -n 1
}

# verdict RC STDERR SUMMARY: "ok" or "FAIL <kind>: <detail>" for one run
verdict() {
    local rc=$1 err=$2 summary=$3 problem line
    line=$(grep -aEm1 "$runtime_error_re" "$err")
    # the line before "Error termination" (gfortran's "In file ..., around
    # line N: ...") says more
    [[ -n $line ]] && line=$(grep -aEm1 "^(In file|At line) |$runtime_error_re" "$err")
    if ((rc == 124 || rc == 137 || rc == 152)); then
        echo "FAIL hang: no end within the time limit (exit $rc)"
    elif ((rc > 128)); then
        echo "FAIL signal: killed by signal $((rc - 128)) (exit $rc)"
    elif [[ -n $line ]]; then
        echo "FAIL runtime error: exit $rc, stderr: $line"
    elif ((rc == 0)); then
        problem=$(summary_problem "$summary")
        if [[ -n $problem ]]; then
            echo "FAIL bad summary: exit 0, $problem"
        elif [[ ! $(summary_status "$summary") =~ ^(completed|localized|torn)$ ]]; then
            echo "FAIL bad summary: exit 0 with status $(summary_status "$summary")"
        else
            echo ok
        fi
    elif ((rc >= 1 && rc <= 5)); then
        if ! grep -aqF '*ERROR*' "$err"; then
            echo "FAIL no message: exit $rc without an *ERROR* line on stderr"
        elif ((rc == 2 || rc == 4 || rc == 5)) && [[ -f $summary ]]; then
            problem=$(summary_problem "$summary")
            local want=no_convergence
            ((rc == 4)) && want=interrupted
            ((rc == 5)) && want=out_of_memory
            if [[ -n $problem ]]; then
                echo "FAIL bad summary: exit $rc, $problem"
            elif [[ $(summary_status "$summary") != "$want" ]]; then
                echo "FAIL bad summary: exit $rc with status $(summary_status "$summary")"
            else
                echo ok
            fi
        else
            echo ok
        fi
    else
        echo "FAIL exit status: $rc (not 0 to 4)"
    fi
}

# run_bounded PROG LIMIT CWD DECK OUT DIR: PROG -o OUT DECK, run from CWD
# under the CPU-time limit (LIMIT s; ten times that of wall time) and the
# memory limit, into DIR: stdout.txt, stderr.txt,
# exit_status.txt and verdict.txt ("ok" or "FAIL <kind>: <detail>").  The
# braces keep bash's own "Segmentation fault" line off the terminal (the
# program's stderr tells the story).
run_bounded() {
    local prog=$1 limit=$2 cwd=$3 deck=$4 out=$5 dir=$6
    {
        (
            cd "$cwd" || exit 2
            ulimit -v 2000000 -c 0 -t "$limit"
            exec timeout -k 2 "$((10 * limit))" "$prog" -o "$out" "$deck" >"$dir/stdout.txt" 2>"$dir/stderr.txt"
        )
        echo $? >"$dir/exit_status.txt"
    } 2>/dev/null
    verdict "$(<"$dir/exit_status.txt")" "$dir/stderr.txt" "$out/summary.txt" >"$dir/verdict.txt"
}

# one case, as the script calls itself through xargs
if [[ ${1:-} == --run-case ]]; then
    run_bounded "$2" "$3" "$4" deck.nml "$4/out" "$4"
    exit 0
fi

# ---------------------------------------------------------------------------
# Options
# ---------------------------------------------------------------------------
prog=${DRAWBEAD:-bin/drawbead}
seed=1 cases=600 first=0 jobs=2 limit=120 keep=out/fuzz_failures replay=1
usage() {
    echo "usage: tests/fuzz.sh [PROGRAM] [--seed N] [--cases N] [--first K] [-j N] [--timeout S] [--keep DIR] [--no-replay]" >&2
    exit 2
}
while (($# > 0)); do
    case $1 in
    --seed | --cases | --first | -j | --timeout | --keep)
        (($# >= 2)) || usage
        case $1 in
        --seed) seed=$2 ;;
        --cases) cases=$2 ;;
        --first) first=$2 ;;
        -j) jobs=$2 ;;
        --timeout) limit=$2 ;;
        --keep) keep=$2 ;;
        esac
        shift 2
        ;;
    --no-replay)
        replay=0
        shift
        ;;
    -h | --help) usage ;;
    -*) usage ;;
    *)
        prog=$1
        shift
        ;;
    esac
done
for n in "$seed" "$cases" "$first" "$jobs" "$limit"; do
    [[ $n =~ ^[0-9]+$ ]] || usage
done
if [[ ! -x $prog ]]; then
    echo "fuzz.sh: no executable '$prog' (build it first)" >&2
    exit 2
fi
[[ $prog == /* ]] || prog=$top/$prog
[[ $keep == /* ]] || keep=$top/$keep

tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
failures=0

# ---------------------------------------------------------------------------
# a) replay of the crashes found before
# ---------------------------------------------------------------------------
if ((replay)); then
    echo "== a) replay: tests/decks/fuzz_*.nml"
    shopt -s nullglob
    declare -A expects
    for deck in tests/decks/fuzz_*.nml; do
        first_line=$(head -n 1 "$deck")
        expect=${first_line#*expect:}
        expect=${expect#"${expect%%[![:space:]]*}"}
        expect=${expect%"${expect##*[![:space:]]}"}
        if [[ $first_line != *expect:* || -z $expect ]]; then
            echo "FAIL $deck: first line must be '! expect: <variable>', '! expect: &<group>' or '! expect: no crash'"
            failures=$((failures + 1))
            continue
        fi
        expects[$deck]=$expect
        # all at once, from the top (the decks name files from there): a
        # hang costs the time limit once, not once per deck
        dir=$tmp/replay/${deck##*/}
        mkdir -p "$dir"
        run_bounded "$prog" "$limit" "$top" "$deck" "$dir/out" "$dir" &
    done
    wait
    for deck in tests/decks/fuzz_*.nml; do
        [[ -n ${expects[$deck]:-} ]] || continue
        expect=${expects[$deck]}
        dir=$tmp/replay/${deck##*/}
        rc=$(<"$dir/exit_status.txt")
        result=$(<"$dir/verdict.txt")
        pattern="variable $expect"
        [[ $expect == '&'* ]] && pattern="group $expect"
        if [[ $result != ok ]]; then
            echo "FAIL $deck: ${result#FAIL }"
            failures=$((failures + 1))
        elif [[ $expect != 'no crash' ]] && ((rc != 1)); then
            echo "FAIL $deck: exit status $rc, expected 1"
            failures=$((failures + 1))
        elif [[ $expect != 'no crash' ]] &&
            ! grep -aF -- "deck '$deck'" "$dir/stderr.txt" | grep -qF -- "$pattern"; then
            echo "FAIL $deck: no stderr line names the deck and '$pattern':"
            sed 's/^/    /' "$dir/stderr.txt" | head -n 5
            failures=$((failures + 1))
        else
            echo "ok   $deck ($expect, exit $rc)"
        fi
    done
fi

# ---------------------------------------------------------------------------
# b) mutated cases
# ---------------------------------------------------------------------------
echo "== b) fuzz: $cases cases from case $first, seed $seed, $jobs at a time, ${limit} s of CPU each"
start=$SECONDS
if ! python3 scripts/fuzz_inputs.py generate --seed "$seed" --cases "$cases" --first "$first" \
    --out "$tmp/cases"; then
    echo "fuzz.sh: scripts/fuzz_inputs.py failed" >&2
    exit 2
fi
mkdir -p "$tmp/cases"
find "$tmp/cases" -mindepth 1 -maxdepth 1 -type d -name 'case_*' -print0 | sort -z |
    xargs -0 -r -n 1 -P "$jobs" bash "$top/tests/fuzz.sh" --run-case "$prog" "$limit"

# only the cases an earlier run kept go (--keep may name a directory in use)
rm -rf "${keep:?}"/case_*
nfail=0
declare -A count example
for dir in "$tmp"/cases/case_*; do
    [[ -d $dir ]] || continue
    result=$(<"$dir/verdict.txt")
    [[ $result == ok ]] && continue
    nfail=$((nfail + 1))
    case=${dir##*/}
    mkdir -p "$keep" && cp -r "$dir" "$keep/"
    rm -rf "$keep/$case/out"
    cat >"$keep/$case/cmd.sh" <<EOF
#!/usr/bin/env bash
# replays $case (seed $seed; regenerate it with:
#   python3 scripts/fuzz_inputs.py generate --seed $seed --first $((10#${case#case_})) --cases 1 --out DIR)
cd "\$(dirname "\${BASH_SOURCE[0]}")" || exit 2
ulimit -v 2000000 -c 0 -t $limit
timeout -k 2 $((10 * limit)) "\${DRAWBEAD:-$prog}" -o out deck.nml
EOF
    chmod +x "$keep/$case/cmd.sh"
    # the failure's kind, its first stderr line (numbers and addresses
    # masked) and the first source line of a backtrace tell one bug from
    # another
    key="${result%%:*}: $(grep -aEm1 "$runtime_error_re|\*ERROR\*|^At line|^In file" "$dir/stderr.txt" |
        sed -E 's/0x[0-9a-f]+/0x./g; s/[0-9]+ bytes/N bytes/g' | cut -c1-150)"
    key+=$(grep -aoEm1 'at src/[^ ]+' "$dir/stderr.txt" | sed 's/^/ /')
    count[$key]=$((${count[$key]:-0} + 1))
    [[ -n ${example[$key]:-} ]] || example[$key]=$case
done
echo "fuzz: $cases cases, $nfail failed, $((SECONDS - start)) s"
if ((nfail > 0)); then
    echo "distinct failures (count, first case; each kept in $keep/<case>: cmd.sh replays it):"
    for key in "${!count[@]}"; do
        printf '  %4d  %s  %s\n' "${count[$key]}" "${example[$key]}" "$key"
        sed 's/^/        /' "$keep/${example[$key]}/what.txt"
    done
    failures=$((failures + nfail))
fi

echo "fuzz.sh: $failures failed"
((failures == 0))
