#!/usr/bin/env bash
# sweep.sh -- a design sweep: one run per combination of deck values.
#
# Usage: scripts/sweep.sh [-j N] [--slurm] [-o OUTDIR] [--bin PATH]
#                         BASE.nml VAR=V1,V2,... [VAR=V1,V2,... ...]
#        scripts/sweep.sh --collect OUTDIR
#
# Writes one deck per combination of the values (the cartesian product;
# the first variable varies slowest) into OUTDIR/decks/case_NNNN.nml, made
# from BASE.nml by overriding the named namelist variables (any variable
# the program lists with --list-variables: the group that holds it in the
# base deck is used, or the variable is added to its group; text values
# need no quotes), then runs them, N at a time (one thread each), each
# into OUTDIR/runs/case_NNNN/ (the program's output files, run.log with
# its stdout and stderr, exit_status), with a progress line on stderr
# ("done 37/120, 2 failed, eta 0:41"), and finally writes and prints
# OUTDIR/table.txt: one row per case with the swept values,
# steady_force_over_Eh, peak_force_over_Eh, final_lift_over_Eh,
# delta_cr_over_h, max_thinning (from summary.txt) and the status:
# completed, torn, localized (results: tearing is a result, exit status 0
# of the program), no_convergence, interrupted, bad_input (the deck was
# rejected), out_of_memory, or not_run; every failed case is listed under
# the table with the program's error message. OUTDIR/decks.txt lists the decks (line k+1 is
# case k), OUTDIR/cases.tsv the swept values, OUTDIR/status.tsv the
# status of each case and OUTDIR/variables.txt the program's list of deck
# variables.
#
# Example (a sweep over friction and lock depth of the free-edge bead A):
#   scripts/sweep.sh -o out/sweep_a input/fig9c_beadA_steel_free.nml \
#       friction=0.05,0.1,0.15 lock_depth=3,4,4.7
#
# Options:
#   -j N          runs at a time (default: nproc)
#   -o DIR        the sweep folder (default: out/sweep_<base deck name>)
#   --bin PATH    the program (default: $DRAWBEAD if set, else bin/drawbead
#                 of the repository, built with make -s)
#   --no-build    do not run make
#   --slurm       write the decks and OUTDIR/sweep.slurm, a Slurm job-array
#                 script (one array task per deck, task k runs line k+1 of
#                 OUTDIR/decks.txt), and run nothing: submit it with
#                 "sbatch OUTDIR/sweep.slurm", then build the table with
#                 "scripts/sweep.sh --collect OUTDIR". Edit its #SBATCH
#                 lines (time, partition, account) as your cluster needs.
#   --collect DIR only build DIR/table.txt from the runs present (exit
#                 status 1 if a case failed or has not run yet)
#   -h, --help    this text
#
# The runs are started from the current directory, so that file names in
# the deck (profiles, curve files) mean what they mean for the base deck;
# the Slurm script changes to this directory too.
#
# SIGTERM or SIGINT (Ctrl-C) stops the sweep: the runs going are stopped
# (each at a converged increment, status interrupted), no more are
# started, and the table of what finished is written, its first line
# saying that the sweep was interrupted and by which signal.
#
# Exit status: 0 when every run exited 0 (completed, torn or localized);
# 1 when a run failed (its row is in the table); 2 on a usage, deck or
# build error; 143 (SIGTERM) or 130 (SIGINT) when a signal stopped the
# sweep (the table written).
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2
tool=$root/scripts/sweep_tool.py

jobs_max=$(nproc 2>/dev/null || echo 2)
outdir=''
program=${DRAWBEAD:-}
do_build=1
slurm=0
collect=''
args=()

split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        -j)
            need_value "a number" "$@"
            jobs_max=$2
            shift 2
            ;;
        -j*)
            jobs_max=${1#-j}
            shift
            ;;
        -o | --output)
            need_value "a directory" "$@"
            outdir=$2
            shift 2
            ;;
        --bin)
            need_value "a path" "$@"
            program=$2
            shift 2
            ;;
        --no-build)
            do_build=0
            shift
            ;;
        --slurm)
            slurm=1
            shift
            ;;
        --collect)
            need_value "the sweep folder" "$@"
            collect=$2
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
            args+=("$1")
            shift
            ;;
    esac
done

if [[ -n $collect ]]; then
    ((${#args[@]} == 0)) || die "--collect takes only the sweep folder"
    write_statuses "$collect"
    python3 "$tool" collect "$collect"
    exit $?
fi

((${#args[@]} >= 2)) || die "usage: sweep.sh [-j N] [--slurm] [-o OUTDIR] BASE.nml VAR=V1,V2,... (see --help)"
check_count -j "$jobs_max"
base=${args[0]}
[[ -r $base ]] || die "cannot read the base deck '$base'"
[[ -n $outdir ]] || outdir=$root/out/sweep_$(basename "$base" .nml)
find_program "$program" "$do_build"

# ---------------------------------------------------------------------------
# The decks, with the deck variables the program knows
# ---------------------------------------------------------------------------
mkdir -p "$outdir" || die "cannot create '$outdir'"
outdir=$(cd "$outdir" && pwd) || die "cannot enter '$outdir'"
"$bin" --list-variables >"$outdir/variables.txt" ||
    die "'$bin --list-variables' failed: cannot learn the deck variables"
ndecks=$(python3 "$tool" decks "$outdir" "$outdir/variables.txt" "${args[@]}") || exit 2
mapfile -t decks <"$outdir/decks.txt"
((${#decks[@]} == ndecks && ndecks > 0)) || die "the deck list $outdir/decks.txt is inconsistent"
note "$ndecks decks in $outdir/decks/"

# ---------------------------------------------------------------------------
# Slurm: write the job-array script and stop
# ---------------------------------------------------------------------------
if ((slurm)); then
    mkdir -p "$outdir/slurm" || die "cannot create '$outdir/slurm'"
    script=$outdir/sweep.slurm
    workdir=$PWD
    {
        echo '#!/bin/bash'
        echo "# drawbead sweep of $base: $ndecks decks, one array task each"
        echo "# (written by scripts/sweep.sh; task k runs line k+1 of $outdir/decks.txt)."
        echo "# Submit:   sbatch $script"
        echo "# Collect:  $root/scripts/sweep.sh --collect $outdir"
        echo "#SBATCH --job-name=drawbead-sweep"
        echo "#SBATCH --array=0-$((ndecks - 1))"
        echo "#SBATCH --ntasks=1"
        echo "#SBATCH --cpus-per-task=1"
        echo "#SBATCH --time=00:30:00"
        echo "#SBATCH --output=$outdir/slurm/%A_%a.out"
        cat <<EOF
set -u
source '$root/scripts/lib.sh' || exit 1
bin='$bin'
outdir='$outdir'
cd '$workdir' || exit 1
task=\${SLURM_ARRAY_TASK_ID:?run this script with sbatch, or set SLURM_ARRAY_TASK_ID}
deck=\$(sed -n "\$((task + 1))p" "\$outdir/decks.txt")
if [[ -z \$deck ]]; then
    echo "sweep.slurm: no deck for task \$task in \$outdir/decks.txt" >&2
    exit 1
fi
run_deck "\$bin" "\$deck" "\$outdir/runs/\$(basename "\$deck" .nml)"
EOF
    } >"$script" || die "cannot write '$script'"
    chmod +x "$script"
    note "wrote $script (array 0-$((ndecks - 1)))"
    note "submit with:  sbatch $script"
    note "then collect: $root/scripts/sweep.sh --collect $outdir"
    exit 0
fi

# ---------------------------------------------------------------------------
# Local runs, jobs_max at a time, with a progress line
# ---------------------------------------------------------------------------
# hms SECONDS: h:mm:ss or m:ss
# shellcheck disable=SC2317 # called by progress
hms() {
    local s=$1
    if ((s >= 3600)); then
        printf '%d:%02d:%02d' $((s / 3600)) $((s % 3600 / 60)) $((s % 60))
    else
        printf '%d:%02d' $((s / 60)) $((s % 60))
    fi
}

tty=0
[[ -t 2 ]] && tty=1
# progress INDEX STATUS: count a finished run and print the progress line
# shellcheck disable=SC2317 # called by run_pool
progress() {
    local eta
    finished=$((finished + 1))
    (($2 == 0 || $2 == exit_interrupted)) || failed=$((failed + 1))
    eta=$(hms $(((SECONDS - t0) * (total - finished) / finished)))
    if ((tty)); then
        printf '\rdone %d/%d, %d failed, eta %s   ' "$finished" "$total" "$failed" "$eta" >&2
        ((finished < total)) || echo >&2
    else
        printf 'done %d/%d, %d failed, eta %s\n' "$finished" "$total" "$failed" "$eta" >&2
    fi
}

total=$ndecks
t0=$SECONDS
finished=0
failed=0
pool_decks=("${decks[@]}")
pool_dirs=()
for deck in "${decks[@]}"; do pool_dirs+=("$outdir/runs/$(basename "$deck" .nml)"); done
# a signal stops the runs (the pool waits for them) and the table is written
signal=''
trap 'signal=TERM; pool_stop_runs' TERM
trap 'signal=INT; pool_stop_runs' INT
run_pool "$jobs_max" progress
trap - TERM INT

write_statuses "$outdir"
if [[ -n $signal ]]; then
    note "stopped by SIG$signal: $finished of $total runs ended, the rest not run"
    python3 "$tool" collect "$outdir" --interrupted "SIG$signal"
    note "table in $outdir/table.txt (interrupted)"
    [[ $signal == TERM ]] && exit 143
    exit 130
fi
python3 "$tool" collect "$outdir"
collect_status=$?
((collect_status <= 1)) || exit 2
note "table in $outdir/table.txt"
((failed == 0 && collect_status == 0)) || exit 1
exit 0
