#!/usr/bin/env bash
# bench.sh -- wall-clock benchmark of drawbead on the paper decks.
#
# Usage: scripts/bench.sh [options] [deck.nml ...]
#
# Builds the release program (make -s, the Makefile's release flags), then
# runs each deck N times, one run at a time, each into its own scratch
# output directory (bin/drawbead DECK --output DIR, stdout to /dev/null),
# and prints one table row per deck: the median, smallest and largest wall
# time, the median CPU time the program reports (cpu_seconds), and
# increments, newton_iterations, cutbacks and status from the run's
# summary.txt (CPU time is less disturbed than wall time by other jobs on
# the machine). Without deck arguments it runs input/fig*.nml of the
# repository. Deck paths are taken relative to the current directory (as
# are file names inside the decks).
#
# Options:
#   -n N              runs per deck (default 3; env BENCH_RUNS)
#   --build-dir DIR   build in DIR and use DIR/drawbead, leaving build/ and
#                     bin/ alone (env BENCH_BUILD_DIR; default: the normal
#                     build/ and bin/drawbead)
#   --fflags FLAGS    compile with FLAGS instead of the release flags (env
#                     BENCH_FFLAGS); an FFLAGS set in the environment is
#                     otherwise ignored, so that the default really is the
#                     release flags
#   --no-build        do not run make; use the existing binary
#   --keep DIR        write the run outputs under DIR and keep them
#                     (default: a temporary directory, removed at the end)
#   --markdown        print the table as a GitHub markdown table
#   -h, --help        this text
#
# The table goes to stdout, after lines starting with '#' (an HTML comment
# with --markdown) that give the number of runs, the binary, the compiler
# and flags, and the host with its load average. Build output, progress and
# the stderr of failed runs go to stderr.
#
# Exit status: 0 when every run exited 0; 1 when any run exited otherwise
# (1 bad input, 2 no convergence; the table is still printed); 2 on a usage
# or build error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

runs=${BENCH_RUNS:-3}
build_dir=${BENCH_BUILD_DIR:-}
fflags=${BENCH_FFLAGS:-}
do_build=1
keep_dir=''
markdown=0
decks=()

split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        -n)
            need_value "a number" "$@"
            runs=$2
            shift 2
            ;;
        -n*)
            runs=${1#-n}
            shift
            ;;
        --build-dir)
            need_value "a directory" "$@"
            build_dir=$2
            shift 2
            ;;
        --fflags)
            need_value "a value" "$@"
            fflags=$2
            shift 2
            ;;
        --no-build)
            do_build=0
            shift
            ;;
        --keep)
            need_value "a directory" "$@"
            keep_dir=$2
            shift 2
            ;;
        --markdown)
            markdown=1
            shift
            ;;
        -h | --help)
            usage
            exit 0
            ;;
        --)
            shift
            decks+=("$@")
            break
            ;;
        -*)
            die "unknown option '$1' (see --help)"
            ;;
        *)
            decks+=("$1")
            shift
            ;;
    esac
done

check_count -n "$runs"

if ((${#decks[@]} == 0)); then
    shopt -s nullglob
    decks=("$root"/input/fig*.nml)
    shopt -u nullglob
    ((${#decks[@]} > 0)) || die "no decks given and none found as $root/input/fig*.nml"
fi
for deck in "${decks[@]}"; do
    [[ -f $deck && -r $deck ]] || die "cannot read deck '$deck'"
done

# ---------------------------------------------------------------------------
# Build
# ---------------------------------------------------------------------------
make_args=()
if [[ -n $build_dir ]]; then
    [[ $build_dir == /* ]] || build_dir=$PWD/$build_dir
    bin=$build_dir/drawbead
    make_args+=("BUILD=$build_dir" "BIN=$bin")
    stamp=$build_dir/flags.txt
else
    bin=$root/bin/drawbead
    stamp=$root/build/flags.txt
fi
if [[ -n $fflags ]]; then
    make_args+=("FFLAGS=$fflags")
fi

if ((do_build)); then
    # FFLAGS from the environment would override the Makefile's release flags
    unset FFLAGS
    build_program "${make_args[@]}" all
fi
[[ -x $bin ]] || die "no executable '$bin' (build it first, or drop --no-build)"

# ---------------------------------------------------------------------------
# Scratch space
# ---------------------------------------------------------------------------
if [[ -n $keep_dir ]]; then
    mkdir -p "$keep_dir" || die "cannot create '$keep_dir'"
    scratch=$(cd "$keep_dir" && pwd) || die "cannot enter '$keep_dir'"
else
    scratch=$(mktemp -d "${TMPDIR:-/tmp}/drawbead-bench.XXXXXX") ||
        die "cannot create a temporary directory"
    trap 'rm -rf "$scratch"' EXIT
fi

# ---------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------

# now -- wall-clock time in seconds with a fraction
now() {
    if [[ -n ${EPOCHREALTIME:-} ]]; then
        printf '%s\n' "${EPOCHREALTIME/,/.}"
    else
        date +%s.%N
    fi
}

# value FILE KEY -- the summary value, or '-'
value() {
    local v
    v=$(summary_value "$1" "$2")
    printf '%s\n' "${v:--}"
}

# stats T1 T2 ... -- "median min max" of the numbers, 3 decimals
stats() {
    printf '%s\n' "$@" | sort -g | awk '
        { t[NR] = $1 }
        END {
            if (NR % 2) med = t[(NR + 1) / 2]; else med = (t[NR / 2] + t[NR / 2 + 1]) / 2
            printf "%.3f %.3f %.3f\n", med, t[1], t[NR]
        }'
}

# ---------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------
failures=0
rows=()
for deck in "${decks[@]}"; do
    name=$(basename "$deck")
    name=${name%.nml}
    times=()
    cpus=()
    deck_status=0
    first_summary=''
    for ((i = 1; i <= runs; i++)); do
        dir=$scratch/$name/run$i
        rm -rf "$dir"
        mkdir -p "$dir" || die "cannot create '$dir'"
        printf '%s: %s run %d/%d ... ' "$me" "$name" "$i" "$runs" >&2
        t0=$(now)
        "$bin" "$deck" --output "$dir" >/dev/null 2>"$dir.stderr"
        rc=$?
        t1=$(now)
        t=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.6f", b - a }')
        times+=("$t")
        printf '%.3f s, exit %d\n' "$t" "$rc" >&2
        if ((rc != 0)); then
            deck_status=$rc
            failures=$((failures + 1))
            note "$deck exited with status $rc; its stderr:"
            sed 's/^/    /' "$dir.stderr" >&2
        fi
        cpu=$(value "$dir/summary.txt" cpu_seconds)
        if [[ $cpu != - ]]; then cpus+=("$cpu"); fi
        # the runs of a deck must agree: compare the counters with run 1
        this=$(for key in status increments newton_iterations cutbacks; do
            value "$dir/summary.txt" "$key"
        done | tr '\n' ' ')
        if ((i == 1)); then
            first_summary=$this
        elif [[ $this != "$first_summary" ]]; then
            note "warning: $name run $i summary ($this) differs from run 1 ($first_summary)"
        fi
    done
    summary=$scratch/$name/run1/summary.txt
    read -r med tmin tmax < <(stats "${times[@]}")
    cpu_med=-
    if ((${#cpus[@]} > 0)); then
        read -r cpu_med _ < <(stats "${cpus[@]}")
    fi
    status=$(value "$summary" status)
    ((deck_status == 0)) || status="$status(exit $deck_status)"
    fields=("$name" "$med" "$tmin" "$tmax" "$cpu_med")
    for key in increments newton_iterations cutbacks; do
        fields+=("$(value "$summary" "$key")")
    done
    fields+=("$status")
    # one tab-separated row per deck (deck names may hold blanks)
    rows+=("$(IFS=$'\t'; printf '%s' "${fields[*]}")")
done

# ---------------------------------------------------------------------------
# Table
# ---------------------------------------------------------------------------
flags='?'
[[ -f $stamp ]] && flags=$(<"$stamp")
info=("drawbead benchmark: $runs run(s) per deck, wall seconds"
    "binary: $bin"
    "compiler and flags: $flags"
    "host: $(uname -n), $(getconf _NPROCESSORS_ONLN 2>/dev/null || echo '?') cores, load average $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo '?'), $(date '+%Y-%m-%d %H:%M')")
if ((markdown)); then
    # an HTML comment: kept with the table, not rendered
    echo '<!--'
    printf '%s\n' "${info[@]}"
    echo '-->'
    echo
    echo '| deck | median (s) | min (s) | max (s) | CPU (s) | increments | newton_iterations | cutbacks | status |'
    echo '| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |'
    for row in "${rows[@]}"; do
        IFS=$'\t' read -r -a fields <<<"$row"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "${fields[@]}"
    done
else
    printf '# %s\n' "${info[@]}"
    width=4
    for row in "${rows[@]}"; do
        name=${row%%$'\t'*}
        if ((${#name} > width)); then width=${#name}; fi
    done
    format="%-${width}s %10s %8s %8s %8s %11s %18s %9s  %s\n"
    # shellcheck disable=SC2059 # the format holds only the computed width
    printf "$format" '#deck' median_s min_s max_s cpu_s increments newton_iterations cutbacks status
    for row in "${rows[@]}"; do
        IFS=$'\t' read -r -a fields <<<"$row"
        # shellcheck disable=SC2059
        printf "$format" "${fields[@]}"
    done
fi

if ((failures > 0)); then
    note "$failures run(s) exited with a non-zero status"
    exit 1
fi
exit 0
