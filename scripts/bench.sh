#!/usr/bin/env bash
# bench.sh -- wall-clock benchmark of drawbead: the paper's and the contact
# decks with 1 and 2 threads, and the cost per iteration against the mesh.
#
# Usage: scripts/bench.sh [options] [deck.nml ...]
#
# Builds the release program (make -s, the Makefile's release flags), then
# runs each deck N times for each thread count (OMP_NUM_THREADS), one run
# at a time, each into its own scratch output directory (bin/drawbead DECK
# --output DIR), and prints one table row per deck and thread count:
#   median, min, max   wall time of the N runs, s
#   cpu                median CPU time the program reports (cpu_seconds:
#                      summed over its threads, spinning included)
#   increments, iterations (newton_iterations), assemblies, cutbacks
#                      from the run's summary.txt (the runs of a deck must
#                      agree; a warning otherwise)
#   us/asm             median wall time per assembly, microseconds
#   ns/pt              median wall time per material point, nanoseconds: an
#                      assembly visits thickness_points x 4 Gauss stations
#                      x n_elements of them (read from the run's echo of its
#                      deck); both figures are "all in" (set-up, solves and
#                      output included)
#   status             from summary.txt
# and a row "total" per thread count, the sum of the medians. Then the
# scaling table: the scaling deck with n_elements set to each count of
# --elements, N runs each per thread count, with the median wall time per
# Newton iteration (ms/it) and per element and iteration (us/el/it), and
# ns/pt as above. Without deck arguments it runs input/fig*.nml and
# input/cc_*.nml of the repository. Deck paths are taken relative to the
# current directory (as are file names inside the decks).
#
# Options:
#   -n N              runs per deck, thread count and mesh (default 3; env
#                     BENCH_RUNS)
#   --threads LIST    thread counts, comma-separated (default 1,2; env
#                     BENCH_THREADS)
#   --scaling DECK    the deck of the scaling table (default
#                     input/fig7c_beadB_steel_mu0.nml, locking only: a
#                     short run on 640 elements; env BENCH_SCALING_DECK)
#   --elements LIST   its element counts, comma-separated (default
#                     80,160,320,640; env BENCH_ELEMENTS)
#   --no-scaling      no scaling table
#   --build-dir DIR   build in DIR and use DIR/drawbead, leaving build/ and
#                     bin/ alone (env BENCH_BUILD_DIR; default: the normal
#                     build/ and bin/drawbead)
#   --fflags FLAGS    compile with FLAGS instead of the release flags (env
#                     BENCH_FFLAGS); an FFLAGS set in the environment is
#                     otherwise ignored, so that the default really is the
#                     release flags (add -fopenmp for threads)
#   --no-build        do not run make; use the existing binary
#   --bin PATH        run the program PATH (implies --no-build)
#   --keep DIR        write the run outputs under DIR and keep them
#                     (default: a temporary directory, removed at the end)
#   --markdown        print the tables as GitHub markdown tables
#   -h, --help        this text
#
# The tables go to stdout, after lines starting with '#' (an HTML comment
# with --markdown) that give the number of runs, the binary, the compiler
# and flags, and the host with its load average before and after the runs
# (look at it: other work on the machine slows the runs, two threads
# most; the load after includes the runs' own). Build output, progress
# and the stderr of failed runs go to stderr.
#
# Exit status: 0 when every run exited 0; 1 when any run exited otherwise
# (1 bad input, 2 no convergence; the tables are still printed); 2 on a
# usage or build error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

runs=${BENCH_RUNS:-3}
threads_list=${BENCH_THREADS:-1,2}
scaling_deck=${BENCH_SCALING_DECK:-}
elements_list=${BENCH_ELEMENTS:-80,160,320,640}
do_scaling=1
build_dir=${BENCH_BUILD_DIR:-}
fflags=${BENCH_FFLAGS:-}
do_build=1
bin_given=''
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
        --threads)
            need_value "a list of thread counts" "$@"
            threads_list=$2
            shift 2
            ;;
        --scaling)
            need_value "a deck" "$@"
            scaling_deck=$2
            shift 2
            ;;
        --elements)
            need_value "a list of element counts" "$@"
            elements_list=$2
            shift 2
            ;;
        --no-scaling)
            do_scaling=0
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
        --bin)
            need_value "a program" "$@"
            bin_given=$2
            do_build=0
            shift 2
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
IFS=',' read -r -a thread_counts <<<"$threads_list"
((${#thread_counts[@]} > 0)) || die "--threads needs a list of thread counts, not '$threads_list'"
for n in "${thread_counts[@]}"; do check_count --threads "$n"; done
IFS=',' read -r -a element_counts <<<"$elements_list"
((${#element_counts[@]} > 0)) || die "--elements needs a list of element counts, not '$elements_list'"
for n in "${element_counts[@]}"; do check_count --elements "$n"; done

if ((${#decks[@]} == 0)); then
    shopt -s nullglob
    decks=("$root"/input/fig*.nml "$root"/input/cc_*.nml)
    shopt -u nullglob
    ((${#decks[@]} > 0)) || die "no decks given and none found as $root/input/{fig,cc_}*.nml"
fi
for deck in "${decks[@]}"; do
    [[ -f $deck && -r $deck ]] || die "cannot read deck '$deck'"
done
if ((do_scaling)); then
    [[ -n $scaling_deck ]] || scaling_deck=$root/input/fig7c_beadB_steel_mu0.nml
    [[ -f $scaling_deck && -r $scaling_deck ]] || die "cannot read the scaling deck '$scaling_deck'"
    grep -qi '^ *&sheet' "$scaling_deck" || die "the scaling deck '$scaling_deck' has no &sheet group"
fi

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
if [[ -n $bin_given ]]; then
    bin=$bin_given
    [[ $bin == /* || ! -e $bin ]] || bin=$PWD/$bin
    # the flags of a given program are not known
    stamp=''
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

# echoed FILE NAME -- the integer the run echoed for its deck variable NAME
# (the program writes the resolved groups with write(nml=)), or '-'
echoed() {
    local v
    v=$(awk -v k="$2" 'toupper($0) ~ "^ *" k "=" { sub(/^[^=]*= */, ""); sub(/[ ,].*$/, ""); print; exit }' "$1" 2>/dev/null)
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

# ratio A B SCALE DECIMALS -- A / B * SCALE, or '-' if B is not a positive number
ratio() {
    awk -v a="$1" -v b="$2" -v s="$3" -v d="$4" 'BEGIN {
        if (a ~ /^[0-9.eE+-]+$/ && b ~ /^[0-9.eE+-]+$/ && b + 0 > 0) printf "%.*f\n", d, a / b * s
        else print "-" }'
}

# bench_deck DECK NAME THREADS -- run DECK N times with THREADS threads
# into $scratch/NAME/tTHREADS/runI; sets the globals med tmin tmax cpu_med,
# summary (run 1's summary.txt), echo_file (run 1's stdout) and
# deck_status (the last non-zero exit status, or 0)
bench_deck() {
    local deck=$1 name=$2 nthreads=$3 i dir t0 t1 t rc cpu this first=''
    local times=() cpus=()
    deck_status=0
    for ((i = 1; i <= runs; i++)); do
        dir=$scratch/$name/t$nthreads/run$i
        rm -rf "$dir"
        mkdir -p "$dir" || die "cannot create '$dir'"
        printf '%s: %s, %d thread(s), run %d/%d ... ' "$me" "$name" "$nthreads" "$i" "$runs" >&2
        t0=$(now)
        OMP_NUM_THREADS=$nthreads "$bin" "$deck" --output "$dir" >"$dir.stdout" 2>"$dir.stderr"
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
        this=$(for key in status increments newton_iterations assemblies cutbacks; do
            value "$dir/summary.txt" "$key"
        done | tr '\n' ' ')
        if ((i == 1)); then
            first=$this
        elif [[ $this != "$first" ]]; then
            note "warning: $name run $i summary ($this) differs from run 1 ($first)"
        fi
    done
    summary=$scratch/$name/t$nthreads/run1/summary.txt
    echo_file=$scratch/$name/t$nthreads/run1.stdout
    read -r med tmin tmax < <(stats "${times[@]}")
    cpu_med=-
    if ((${#cpus[@]} > 0)); then
        read -r cpu_med _ < <(stats "${cpus[@]}")
    fi
}

# points_per_assembly -- material points of one assembly of the run whose
# stdout is $echo_file and summary $summary: thickness_points x 4 x the
# model's elements (summary key elements: with a refined zone more than the
# deck's n_elements), or '-'
points_per_assembly() {
    local nel npt
    nel=$(value "$summary" elements)
    [[ $nel =~ ^[0-9]+$ ]] || nel=$(echoed "$echo_file" N_ELEMENTS)
    npt=$(echoed "$echo_file" THICKNESS_POINTS)
    if [[ $nel =~ ^[0-9]+$ && $npt =~ ^[0-9]+$ ]]; then
        echo $((npt * 4 * nel))
    else
        echo -
    fi
}

# ---------------------------------------------------------------------------
# Runs: every deck with every thread count
# ---------------------------------------------------------------------------
failures=0
rows=()
declare -A totals=()
# the load before the runs (at the end it includes the runs' own)
load_start=$(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo '?')
for deck in "${decks[@]}"; do
    name=$(basename "$deck")
    name=${name%.nml}
    for nthreads in "${thread_counts[@]}"; do
        bench_deck "$deck" "$name" "$nthreads"
        status=$(value "$summary" status)
        ((deck_status == 0)) || status="$status(exit $deck_status)"
        asm=$(value "$summary" assemblies)
        points=$(points_per_assembly)
        fields=("$name" "$nthreads" "$med" "$tmin" "$tmax" "$cpu_med")
        for key in increments newton_iterations assemblies cutbacks; do
            fields+=("$(value "$summary" "$key")")
        done
        fields+=("$(ratio "$med" "$asm" 1e6 0)")
        fields+=("$(ratio "$med" "$(awk -v a="$asm" -v p="$points" 'BEGIN { if (p ~ /^[0-9]+$/ && a ~ /^[0-9]+$/) print a * p; else print "-" }')" 1e9 1)")
        fields+=("$status")
        # one tab-separated row per deck and thread count (names may hold blanks)
        rows+=("$(IFS=$'\t'; printf '%s' "${fields[*]}")")
        totals[$nthreads]=$(awk -v a="${totals[$nthreads]:-0}" -v b="$med" 'BEGIN { printf "%.3f", a + b }')
    done
done
for nthreads in "${thread_counts[@]}"; do
    rows+=("$(printf 'total\t%s\t%s\t-\t-\t-\t-\t-\t-\t-\t-\t-\tsum of the medians' "$nthreads" "${totals[$nthreads]}")")
done

# ---------------------------------------------------------------------------
# Scaling: the scaling deck on each mesh
# ---------------------------------------------------------------------------
scale_rows=()
if ((do_scaling)); then
    base=$(basename "$scaling_deck")
    base=${base%.nml}
    for nel in "${element_counts[@]}"; do
        mesh_deck=$scratch/${base}_$nel.nml
        # n_elements replaced, or added at the top of &sheet
        if grep -qiE '^ *n_elements *=' "$scaling_deck"; then
            sed -E "s/^( *)n_elements *=.*/\1n_elements = $nel/I" "$scaling_deck" >"$mesh_deck"
        else
            sed -E "s/^( *&sheet)( *)$/\1\n   n_elements = $nel/I" "$scaling_deck" >"$mesh_deck"
        fi
        for nthreads in "${thread_counts[@]}"; do
            bench_deck "$mesh_deck" "${base}_$nel" "$nthreads"
            status=$(value "$summary" status)
            ((deck_status == 0)) || status="$status(exit $deck_status)"
            its=$(value "$summary" newton_iterations)
            asm=$(value "$summary" assemblies)
            points=$(points_per_assembly)
            fields=("$(echoed "$echo_file" N_ELEMENTS)" "$nthreads" "$med")
            for key in increments newton_iterations assemblies; do
                fields+=("$(value "$summary" "$key")")
            done
            fields+=("$(ratio "$med" "$its" 1e3 3)")
            fields+=("$(ratio "$med" "$(awk -v a="$its" -v n="$nel" 'BEGIN { if (a ~ /^[0-9]+$/) print a * n; else print "-" }')" 1e6 2)")
            fields+=("$(ratio "$med" "$(awk -v a="$asm" -v p="$points" 'BEGIN { if (p ~ /^[0-9]+$/ && a ~ /^[0-9]+$/) print a * p; else print "-" }')" 1e9 1)")
            fields+=("$status")
            scale_rows+=("$(IFS=$'\t'; printf '%s' "${fields[*]}")")
        done
    done
fi

# ---------------------------------------------------------------------------
# Tables
# ---------------------------------------------------------------------------
flags='?'
[[ -n $stamp && -f $stamp ]] && flags=$(<"$stamp")
info=("drawbead benchmark: $runs run(s) per deck and thread count, wall seconds"
    "binary: $bin"
    "compiler and flags: $flags"
    "host: $(uname -n), $(getconf _NPROCESSORS_ONLN 2>/dev/null || echo '?') cores, load average $load_start before the runs, $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo '?') after them (their own included), $(date '+%Y-%m-%d %H:%M')")
head_main=$'deck\tthreads\tmedian_s\tmin_s\tmax_s\tcpu_s\tincrements\titerations\tassemblies\tcutbacks\tus/asm\tns/pt\tstatus'
head_scale=$'elements\tthreads\tmedian_s\tincrements\titerations\tassemblies\tms/it\tus/el/it\tns/pt\tstatus'

# md_table HEADER ROWS... -- a markdown table of tab-separated rows under
# the tab-separated HEADER (the first and last columns left-aligned text,
# the numbers between right-aligned)
md_table() {
    local hdr row sep='|' k
    IFS=$'\t' read -r -a hdr <<<"$1"
    shift
    printf '| %s ' "${hdr[@]}"
    printf '|\n'
    for ((k = 0; k < ${#hdr[@]}; k++)); do
        if ((k == 0 || k == ${#hdr[@]} - 1)); then sep+=' --- |'; else sep+=' ---: |'; fi
    done
    printf '%s\n' "$sep"
    for row in "$@"; do
        IFS=$'\t' read -r -a fields <<<"$row"
        printf '| %s ' "${fields[@]}"
        printf '|\n'
    done
}

# text_table HEADER ROWS... -- the same as aligned columns, '#' before the header
text_table() {
    local hdr row width=6 format k
    IFS=$'\t' read -r -a hdr <<<"$1"
    shift
    for row in "$@"; do
        if ((${#row} > 0)); then
            k=${row%%$'\t'*}
            if ((${#k} > width)); then width=${#k}; fi
        fi
    done
    format="%-${width}s"
    for ((k = 1; k < ${#hdr[@]} - 1; k++)); do format+=' %10s'; done
    format+='  %s\n'
    # shellcheck disable=SC2059 # the format holds only the computed widths
    printf "$format" "#${hdr[0]}" "${hdr[@]:1}"
    for row in "$@"; do
        IFS=$'\t' read -r -a fields <<<"$row"
        # shellcheck disable=SC2059
        printf "$format" "${fields[@]}"
    done
}

if ((markdown)); then
    # an HTML comment: kept with the table, not rendered
    echo '<!--'
    printf '%s\n' "${info[@]}"
    echo '-->'
    echo
    md_table "$head_main" "${rows[@]}"
    if ((do_scaling)); then
        echo
        echo "Scaling: $(basename "$scaling_deck") with n_elements changed; cost per Newton iteration against the elements."
        echo
        md_table "$head_scale" "${scale_rows[@]}"
    fi
else
    printf '# %s\n' "${info[@]}"
    text_table "$head_main" "${rows[@]}"
    if ((do_scaling)); then
        echo
        echo "# scaling: $(basename "$scaling_deck") with n_elements changed"
        text_table "$head_scale" "${scale_rows[@]}"
    fi
fi

if ((failures > 0)); then
    note "$failures run(s) exited with a non-zero status"
    exit 1
fi
exit 0
