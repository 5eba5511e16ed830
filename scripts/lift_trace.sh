#!/usr/bin/env bash
# lift_trace.sh -- the lift force traced tool by tool: the vertical force of
# each tool on the sheet, piece by piece (binder faces, radii, crest), and
# the edges' vertical reactions, in the program and in the CalculiX
# continuum at the same instants of the pull (docs/validation.md, "The lift
# force"; scripts/lift_trace.py says how each side's forces are obtained).
#
# Usage: scripts/lift_trace.sh DECK [-o DIR] [options]
#
#   DECK              a deck with tools and a pull (rectangular or profile
#                     bead; what scripts/continuum_check.sh supports)
#   -o, --output DIR  the results folder (default out/lift_trace/<deck name>)
#   --ccx DIR         use the continuum run kept in DIR (continuum.inp,
#                     continuum_model.json and continuum.dat of an earlier
#                     run of this script) instead of running CalculiX
#   --keep DIR        write into DIR the part of the continuum run the
#                     table needs (scripts/lift_trace.py trim-ccx: about
#                     130 kB; the validation keeps it in
#                     docs/validation/continuum/<deck>/lift_trace/), for
#                     --ccx DIR with the same --at
#   --at LIST         the pulls delta/h compared, comma-separated (default
#                     0.5,1; each model's largest restraining force is
#                     always added)
#   --through N, --per-h M, --initial-inc T, --max-inc T, --min-inc T,
#   --contact-slope K
#                     the continuum's mesh, increments and contact slope
#                     (scripts/continuum_check.sh; the stepped bead needs
#                     --contact-slope 1e4)
#   --also VAR=VALUE  also run the program with the deck variable VAR set
#                     to VALUE (repeatable: e.g. normal_stress=none,
#                     n_elements=320; several in one run separated by
#                     spaces) and compare its lift (a line each)
#   --offset D        also run the program with both tools' centreline
#                     chains moved by D h toward the tools (rectangular
#                     bead: arcs of radius less D h about the same centres,
#                     walls and sides out by D h, the lower binder face 2D h
#                     below the upper one at full lock): the tools a sheet
#                     thinned to (1 - 2D) h lies on (repeatable)
#   --bin PATH        the program to run (default bin/drawbead, built first)
#   -h, --help        this help
#
# Writes into DIR: deck.nml (DECK with &control snapshot_every = 0.001, a
# snapshot at every converged increment), program/ (the program's run on
# it: the strain rows of every state in snapshots.dat, about 100 MB for a
# pull of 3h), ccx/ (the continuum: continuum.inp with the per-node
# reactions of both tools printed at every 1/60 of time (1/20 h of a pull
# of 3h), CalculiX's continuum.dat, tens of MB, and the program's
# columns from scripts/continuum_results.py convert in ccx/converted/),
# program_also_K/ and program_offset_K/ (the runs of --also and --offset),
# and lift_trace.txt (the table and a line per run, also printed). CalculiX runs on
# OMP_NUM_THREADS threads (default 1) and takes minutes.
#
# Exit status: 0 done; 1 CalculiX stopped early (the table covers what it
# computed); 2 a usage, deck or model error.
set -u

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

deck=''
dir=''
ccx_dir=''
keep_dir=''
bin_opt=''
at='0.5,1'
model_opts=()
also=()
offsets=()
split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        -h | --help)
            usage
            exit 0
            ;;
        -o | --output)
            need_value 'a folder' "$@"
            dir=$2
            shift 2
            ;;
        --ccx)
            need_value 'a folder' "$@"
            ccx_dir=$2
            shift 2
            ;;
        --keep)
            need_value 'a folder' "$@"
            keep_dir=$2
            shift 2
            ;;
        --at)
            need_value 'a list of delta/h' "$@"
            [[ $2 =~ ^[0-9.]+(,[0-9.]+)*$ ]] || die "--at needs numbers separated by commas, not '$2'"
            at=$2
            shift 2
            ;;
        --also | --offset)
            need_value 'a value (--also VAR=VALUE, --offset a number)' "$@"
            variant_option "$1" "$2"
            shift 2
            ;;
        --through | --per-h | --initial-inc | --max-inc | --min-inc | --contact-slope)
            need_value 'a number' "$@"
            model_option "$1" "$2"
            shift 2
            ;;
        --bin)
            need_value 'a program' "$@"
            bin_opt=$2
            shift 2
            ;;
        -*) die "unknown option '$1' (see --help)" ;;
        *)
            [[ -z $deck ]] || die "one deck only ('$deck', then '$1')"
            deck=$1
            shift
            ;;
    esac
done
[[ -n $deck ]] || die "no deck given (see --help)"
[[ -r $deck ]] || die "cannot read the deck '$deck'"
name=$(basename "$deck" .nml)
[[ -n $dir ]] || dir=$root/out/lift_trace/$name
mkdir -p "$dir" || die "cannot make '$dir'"
dir=$(cd "$dir" && pwd) || die "cannot enter '$dir'"
if [[ -n $ccx_dir ]]; then
    [[ -r $ccx_dir/continuum.dat && -r $ccx_dir/continuum.inp ]] ||
        die "'$ccx_dir' holds no continuum run (continuum.inp, continuum.dat)"
    ccx_dir=$(cd "$ccx_dir" && pwd)
else
    command -v ccx >/dev/null 2>&1 || die "ccx (CalculiX) is not installed: apt-get install calculix-ccx"
    ccx_dir=$dir/ccx
fi
find_program "$bin_opt" 1

# 1. the program, with a snapshot of the sheet at every converged increment
"$bin" --list-variables >"$dir/variables.txt" || die "cannot list the program's variables"
rm -rf "$dir/sweep"
python3 "$root/scripts/sweep_tool.py" decks "$dir/sweep" "$dir/variables.txt" "$deck" \
    snapshot_every=0.001 >/dev/null || die "cannot write the deck with snapshots"
# (the deck's relative paths, profiles and curves, are read from the
# working directory, as for the deck itself)
mv "$dir/sweep/decks/case_0000.nml" "$dir/deck.nml" && rm -rf "$dir/sweep" "$dir/variables.txt"
note "running the program on $deck into $dir/program"
run_deck "$bin" "$dir/deck.nml" "$dir/program"
rc=$?
((rc == exit_ok)) || {
    grep -E '^\*ERROR\*' "$dir/program/run.log" >&2
    die "the program exited with status $rc on '$deck'"
}

# 2. the continuum, with the per-node reactions of both tools
ccx_rc=0
if [[ $ccx_dir == "$dir/ccx" ]]; then
    python3 "$root/scripts/continuum_model.py" "$dir/program/run.log" "$ccx_dir" \
        --output-every 0.016666666666666666 "${model_opts[@]}" || die "no continuum model for '$deck'"
    python3 "$root/scripts/lift_trace.py" patch-inp "$ccx_dir/continuum.inp" || die "cannot ask for the tools' reactions"
    run_ccx "$ccx_dir"
    ccx_rc=$?
    python3 "$root/scripts/continuum_results.py" convert "$ccx_dir" "$ccx_dir/converted" --program "$bin" ||
        die "cannot convert the results in $ccx_dir"
fi

# 3. the table
python3 "$root/scripts/lift_trace.py" trace "$dir/program" "$ccx_dir" --at "$at" >"$dir/lift_trace.txt" ||
    die "cannot trace the lift"

if [[ -n $keep_dir ]]; then
    python3 "$root/scripts/lift_trace.py" trim-ccx "$ccx_dir" "$keep_dir" --at "$at" ||
        die "cannot keep the continuum's results in $keep_dir"
    note "the continuum's results the table needs kept in $keep_dir"
fi

# 4. the variants (of the deck as given: no snapshots): a line each, the
# lift at the instants, program / continuum
{
    echo ''
    echo '## the lift of variants of the program against the same continuum'
    python3 "$root/scripts/lift_trace.py" summary "the deck as it is" "$dir/program" "$ccx_dir" --at "$at"
} >>"$dir/lift_trace.txt" || die "cannot compare the lift"
"$bin" --list-variables >"$dir/variables.txt" || die "cannot list the program's variables"
# compare_variant LABEL RUN_DIR: a line of the lift's comparison (run_variants)
# shellcheck disable=SC2317 # called by run_variants
compare_variant() {
    python3 "$root/scripts/lift_trace.py" summary "$1" "$2" "$ccx_dir" --at "$at" \
        >>"$dir/lift_trace.txt" || die "cannot compare the lift with $1"
}
run_variants compare_variant
rm -f "$dir/variables.txt"
cat "$dir/lift_trace.txt"
((ccx_rc == 0)) || exit 1
exit 0
