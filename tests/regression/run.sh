#!/usr/bin/env bash
# run.sh -- regression tests, the CalculiX test suite's way: run each deck
# of tests/regression/decks.txt and compare its summary.txt with the
# reference tests/regression/<deck name>.ref.
#
# Usage: tests/regression/run.sh [--update] [--rtol R] [-j N] [PROGRAM]
#        (PROGRAM: default $DRAWBEAD, else bin/drawbead; make test passes it)
#
# A reference holds the run's exit status (exit_status = N) and every
# 'key = value' line of its summary.txt but cpu_seconds. Compared:
#   - numbers with a relative tolerance R (default 1e-6): a value passes if
#     |new - ref| <= R max(|new|, |ref|). The results must agree to
#     round-off, whatever the compiler makes of the loops: the -O0 checked
#     build and the vectorized -O2 -march=native release build differ by
#     at most 1.4e-10 relative on every value of every deck here (the
#     energy balance errors, small differences of large sums; forces and
#     strains within 1e-12), and the Newton tolerance leaves the converged
#     state uncertain far below 1e-6. A change of the formulation, a
#     constant or a step rule moves these values by much more than that.
#   - text ('none', status, phase names) and the exit status exactly;
#   - a key missing from the run, or a key the reference lacks (a new
#     summary value: run --update), is a difference.
# Not compared: increments, newton_iterations, cutbacks and assemblies (they are
# recorded in the references, so that a change shows in the diff of
# --update, but the step control may take another path for round-off
# reasons on another compiler without a visible change of the results),
# and the keys decks.txt lists for a deck (with the reason).
#
# Prints one line per deck ("ok" with the largest relative difference, or
# "FAIL" followed by the list of differences) and a total. The decks run
# N at a time (default 2), one thread each, in a temporary folder; all of
# them take about 3 s with the release build.
#
# Options:
#   --update    run the decks and rewrite every reference from the results
#               (after a change that is meant to move results: review the
#               change with git diff tests/regression/ before committing)
#   --rtol R    the relative tolerance (default 1e-6)
#   -j N        runs at a time (default 2)
#   -h, --help  this text
#
# Exit status: 0 when every deck matches (or with --update, every deck
# ran); 1 when a deck differs, failed to run or has no reference; 2 on a
# usage error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/../../scripts/lib.sh" || exit 2

here=$root/tests/regression
update=0
rtol=1e-6
jobs_max=2
program=${DRAWBEAD:-}
split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        --update)
            update=1
            shift
            ;;
        --rtol)
            need_value "a number" "$@"
            rtol=$2
            shift 2
            ;;
        -j)
            need_value "a number" "$@"
            jobs_max=$2
            shift 2
            ;;
        -h | --help)
            usage
            exit 0
            ;;
        -*)
            die "unknown option '$1' (see --help)"
            ;;
        *)
            program=$1
            shift
            ;;
    esac
done
check_count -j "$jobs_max"
[[ $rtol =~ ^[0-9.]+([eE][-+]?[0-9]+)?$ ]] || die "--rtol needs a number, not '$rtol'"
cd "$root" || exit 2
find_program "$program" 0

# ---------------------------------------------------------------------------
# The decks: decks.txt lines "path [key,key,...]"
# ---------------------------------------------------------------------------
names=()
pool_decks=()
declare -A skip=()
declare -A seen=()
while read -r deck keys _; do
    [[ -z $deck || $deck == \#* ]] && continue
    [[ -r $deck ]] || die "cannot read the deck '$deck' (decks.txt)"
    name=$(basename "$deck" .nml)
    [[ -z ${seen[$name]:-} ]] || die "two decks named '$name' in decks.txt (one reference each)"
    seen[$name]=1
    names+=("$name")
    pool_decks+=("$deck")
    skip[$name]=",${keys:-},"
done <"$here/decks.txt"
((${#names[@]} > 0)) || die "no decks in $here/decks.txt"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/drawbead-regression.XXXXXX") || die "cannot create a temporary folder"
trap 'rm -rf "$tmp"' EXIT
pool_dirs=()
for name in "${names[@]}"; do pool_dirs+=("$tmp/$name"); done

t0=$(date +%s.%N)
ran() { :; }
run_pool "$jobs_max" ran
seconds=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')

# reference_of DIR: a run's reference text (exit status, then its summary
# values but cpu_seconds)
reference_of() {
    echo "exit_status = $(cat "$1/exit_status")"
    [[ -r $1/summary.txt ]] || return 0
    awk '/^#/ || !index($0, "=") { next }
         { k = $0; sub(/ *=.*/, "", k) } k != "cpu_seconds"' "$1/summary.txt"
}

# ---------------------------------------------------------------------------
# --update: rewrite the references
# ---------------------------------------------------------------------------
if ((update)); then
    status=0
    for i in "${!names[@]}"; do
        name=${names[i]}
        ref=$here/$name.ref
        rc=$(cat "$tmp/$name/exit_status")
        if [[ ! -r $tmp/$name/summary.txt ]]; then
            echo "FAIL $name: no summary.txt (exit $rc); its log:"
            sed 's/^/    /' "$tmp/$name/run.log"
            status=1
            continue
        fi
        {
            echo "# ${pool_decks[i]}: reference of tests/regression/run.sh (written by --update)"
            reference_of "$tmp/$name"
        } >"$ref.new"
        if [[ -r $ref ]] && cmp -s <(grep -v '^#' "$ref") <(grep -v '^#' "$ref.new"); then
            echo "same $name"
        else
            echo "new  $name"
        fi
        mv "$ref.new" "$ref"
    done
    echo "regression: references of ${#names[@]} decks written in tests/regression/ ($seconds s)"
    exit "$status"
fi

# ---------------------------------------------------------------------------
# Compare
# ---------------------------------------------------------------------------
# compare REF NEW RTOL SKIP: the differences of NEW (a reference text) from
# REF, one per line, then a last line "worst W" (the largest relative
# difference of the numbers that passed)
compare() {
    awk -v rtol="$3" -v skip="$4" '
        function numeric(s) { return s ~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eEdD][-+]?[0-9]+)?$/ }
        function abs(x) { return x < 0 ? -x : x }
        function parse(line, which,   k, v) {
            if (line ~ /^#/ || !index(line, "=")) return
            k = line; sub(/=.*/, "", k); gsub(/^[ \t]+|[ \t]+$/, "", k)
            v = substr(line, index(line, "=") + 1); gsub(/^[ \t]+|[ \t]+$/, "", v)
            if (k == "cpu_seconds" || k == "increments" || k == "newton_iterations" || k == "cutbacks" || k == "assemblies") return
            if (index(skip, "," k ",")) return
            if (which == 1) { ref[k] = v; order[++n] = k } else got[k] = v
        }
        FNR == NR { parse($0, 1); next }
        { parse($0, 2) }
        END {
            worst = 0
            for (i = 1; i <= n; i++) {
                k = order[i]
                if (!(k in got)) { print k ": missing from the run (reference " ref[k] ")"; continue }
                a = ref[k]; b = got[k]
                if (numeric(a) && numeric(b)) {
                    x = a + 0; y = b + 0
                    scale = abs(x) > abs(y) ? abs(x) : abs(y)
                    d = abs(x - y)
                    if (d > rtol * scale) printf "%s: %s, reference %s (relative %.2e)\n", k, b, a, d / scale
                    else if (scale > 0 && d / scale > worst) worst = d / scale
                } else if (a != b) print k ": " b ", reference " a
            }
            for (k in got) if (!(k in ref)) print k ": " got[k] ", not in the reference (run --update)"
            printf "worst %.1e\n", worst
        }' "$1" "$2"
}

failed=0
for name in "${names[@]}"; do
    ref=$here/$name.ref
    if [[ ! -r $ref ]]; then
        echo "FAIL $name: no reference $ref (run tests/regression/run.sh --update)"
        failed=$((failed + 1))
        continue
    fi
    mapfile -t diffs < <(compare "$ref" <(reference_of "$tmp/$name") "$rtol" "${skip[$name]}")
    worst=${diffs[-1]#worst }
    unset 'diffs[-1]'
    if ((${#diffs[@]} == 0)); then
        echo "ok   $name (largest relative difference $worst)"
    else
        echo "FAIL $name: ${#diffs[@]} differences from $ref"
        printf '       %s\n' "${diffs[@]}"
        failed=$((failed + 1))
    fi
done

# a reference whose deck left decks.txt is stale
shopt -s nullglob
for ref in "$here"/*.ref; do
    name=$(basename "$ref" .ref)
    if [[ -z ${seen[$name]:-} ]]; then
        echo "FAIL $name: $ref has no deck in decks.txt (remove it)"
        failed=$((failed + 1))
    fi
done

echo "regression: ${#names[@]} decks, $failed failed, rtol $rtol ($seconds s)"
((failed == 0))
