#!/usr/bin/env bash
# exit_state_check.sh -- the state of the sheet leaving the bead
# (exit_state.dat, docs/theory.md §9.1) against the CalculiX continuum's,
# at the same material point: the continuum's material of the same
# reference x as the program's exit station. Compares the thickness and the
# equivalent plastic strain at the bottom face, the middle and the top face
# (and through the thickness), with their ratios (docs/validation.md, "The
# sheet leaving the bead"; scripts/exit_state.py says how each side's
# numbers are read).
#
# Usage: scripts/exit_state_check.sh DECK [-o DIR] [options]
#
#   DECK              a deck with tools and a pull long enough that the
#                     material at the exit station has passed the whole
#                     bead (what scripts/continuum_check.sh supports)
#   -o, --output DIR  the results folder (default out/exit_state/<deck name>)
#   --ccx DIR         use the continuum run kept in DIR (continuum.inp,
#                     continuum_model.json and continuum.dat of an earlier
#                     run of this script) instead of running CalculiX
#   --continuum FILE  compare with the continuum's exit state kept in FILE
#                     (written by --keep) instead of a continuum run: no
#                     CalculiX, seconds
#   --keep FILE       write the continuum's exit state (a few kB: its
#                     integration points within --band h of the station,
#                     the thickness there) into FILE; the validation keeps
#                     it in docs/validation/continuum/<deck>/exit_state.txt
#   --band B          the continuum's band kept about the program's
#                     station, in h (default 4)
#   --also VAR=VALUE  also run the program with the deck variable VAR set
#                     to VALUE (repeatable: e.g. normal_stress=none,
#                     n_elements=424; several in one run separated by
#                     spaces, "penalty=0.37 contact_smoothing=0.001") and
#                     compare it with the same continuum, at its own
#                     station (a line each)
#   --offset D        also run the program with both tools' centreline
#                     chains moved by D h toward the tools
#                     (scripts/lift_trace.sh --offset; repeatable)
#   --check           exit status 1 when the thickness is off the
#                     continuum's by more than 2% or an equivalent plastic
#                     strain (faces, middle) by more than 10%
#   --through N, --per-h M, --initial-inc T, --max-inc T, --min-inc T,
#   --output-every T, --contact-slope K
#                     the continuum's mesh, increments and contact
#                     (scripts/continuum_check.sh)
#   --pull-step       the continuum's pull as a step of its own
#                     (scripts/continuum_model.py --pull-step): the long
#                     exit-state sheets stop at the start of the pull
#                     without it (docs/continuum-check.md, "Long sheets")
#   --pull-steps N    the pull as N steps with a restart record at each
#                     step's end (continuum_model.py --pull-steps): a run
#                     stopped in the pull can go on from the last step it
#                     finished (scripts/ccx_resume.py DIR/ccx;
#                     docs/continuum-check.md, "Long sheets"), then this
#                     script with --ccx DIR/ccx
#   --bin PATH        the program to run (default bin/drawbead, built first)
#   -h, --help        this help
#
# Writes into DIR: program/ (the program's run on DECK), ccx/ (the
# continuum: continuum.inp with the band's integration-point coordinates
# printed, CalculiX's continuum.dat, tens of MB, and ccx.log),
# continuum_exit_state.txt (the continuum's exit state, as --keep writes
# it), program_also_K/ and program_offset_K/ (the runs of --also and
# --offset) and exit_state_comparison.txt (the table and a line per run,
# also printed). CalculiX
# runs on OMP_NUM_THREADS threads (default 1) and takes tens of minutes
# for a pull through the whole bead.
#
# Exit status: 0 done; 1 CalculiX stopped early (the table compares its
# last output time), or --check and a ratio outside the targets; 2 a
# usage, deck or model error.
set -u

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

deck=''
dir=''
ccx_dir=''
cont_file=''
keep_file=''
bin_opt=''
band=4
check=()
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
        --continuum)
            need_value 'a file' "$@"
            cont_file=$2
            shift 2
            ;;
        --keep)
            need_value 'a file' "$@"
            keep_file=$2
            shift 2
            ;;
        --band)
            need_value 'a number' "$@"
            [[ $2 =~ ^[0-9]*\.?[0-9]+$ ]] || die "--band needs a positive number, not '$2'"
            band=$2
            shift 2
            ;;
        --also | --offset)
            need_value 'a value (--also VAR=VALUE, --offset a number)' "$@"
            variant_option "$1" "$2"
            shift 2
            ;;
        --check)
            check=(--check)
            shift
            ;;
        --pull-step)
            model_opts+=(--pull-step)
            shift
            ;;
        --through | --per-h | --initial-inc | --max-inc | --min-inc | --output-every | --contact-slope | --pull-steps)
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
[[ -z $ccx_dir || -z $cont_file ]] || die "--ccx and --continuum: one of them"
name=$(basename "$deck" .nml)
[[ -n $dir ]] || dir=$root/out/exit_state/$name
mkdir -p "$dir" || die "cannot make '$dir'"
dir=$(cd "$dir" && pwd) || die "cannot enter '$dir'"
if [[ -n $cont_file ]]; then
    [[ -r $cont_file ]] || die "cannot read the continuum's exit state '$cont_file'"
elif [[ -n $ccx_dir ]]; then
    [[ -r $ccx_dir/continuum.dat && -r $ccx_dir/continuum_model.json ]] ||
        die "'$ccx_dir' holds no continuum run (continuum_model.json, continuum.dat)"
    ccx_dir=$(cd "$ccx_dir" && pwd)
else
    command -v ccx >/dev/null 2>&1 || die "ccx (CalculiX) is not installed: apt-get install calculix-ccx"
    ccx_dir=$dir/ccx
fi
find_program "$bin_opt" 1

# 1. the program: its exit station
note "running the program on $deck into $dir/program"
run_deck "$bin" "$deck" "$dir/program"
rc=$?
if ((rc == exit_bad_input)); then
    grep -E '^\*ERROR\*' "$dir/program/run.log" >&2
    die "the program rejected '$deck'"
fi
((rc == exit_ok)) || die "the program exited with status $rc on '$deck'"
[[ -r $dir/program/exit_state.dat ]] || die "the program wrote no exit_state.dat (a deck with tools and a pull?)"
station=$(python3 "$root/scripts/exit_state.py" station "$dir/program") || die "no exit station"
grep -q '^# passed the whole bead: yes' "$dir/program/exit_state.dat" ||
    note "the material at the exit station has not passed the whole bead (pull further, or a longer sheet)"

# 2. the continuum, with the coordinates of the integration points about the station
ccx_rc=0
if [[ -z $cont_file ]]; then
    if [[ $ccx_dir == "$dir/ccx" ]]; then
        python3 "$root/scripts/continuum_model.py" "$dir/program/run.log" "$ccx_dir" "${model_opts[@]}" ||
            die "no continuum model for '$deck'"
        python3 "$root/scripts/exit_state.py" patch-inp "$ccx_dir/continuum.inp" \
            "$ccx_dir/continuum_model.json" "$station" --band "$band" ||
            die "cannot ask for the integration points' coordinates"
        run_ccx "$ccx_dir"
        ccx_rc=$?
    fi
    cont_file=$dir/continuum_exit_state.txt
    python3 "$root/scripts/exit_state.py" extract "$ccx_dir" "$cont_file" "$station" --band "$band" ||
        die "cannot read the continuum's exit state in $ccx_dir"
    if [[ -n $keep_file ]]; then
        if ! mkdir -p "$(dirname "$keep_file")" || ! cp "$cont_file" "$keep_file"; then
            die "cannot keep the continuum's exit state in $keep_file"
        fi
        note "the continuum's exit state kept in $keep_file"
    fi
fi

# 3. the table
python3 "$root/scripts/exit_state.py" compare "$dir/program" "$cont_file" "${check[@]}" \
    >"$dir/exit_state_comparison.txt"
cmp_rc=$?
((cmp_rc <= 1)) || die "cannot compare the exit states"

# 4. the variants (of the deck as given): a line each, at their own stations
if ((${#also[@]} + ${#offsets[@]} > 0)); then
    {
        echo ''
        echo '# variants of the program against the same continuum'
        python3 "$root/scripts/exit_state.py" summary "the deck as it is" "$dir/program" "$cont_file"
    } >>"$dir/exit_state_comparison.txt" || die "cannot compare the deck as it is"
    "$bin" --list-variables >"$dir/variables.txt" || die "cannot list the program's variables"
fi
# compare_variant LABEL RUN_DIR: a line of the comparison (run_variants)
# shellcheck disable=SC2317 # called by run_variants
compare_variant() {
    python3 "$root/scripts/exit_state.py" summary "$1" "$2" "$cont_file" \
        >>"$dir/exit_state_comparison.txt" || die "cannot compare the exit state with $1"
}
run_variants compare_variant
rm -f "$dir/variables.txt"
cat "$dir/exit_state_comparison.txt"
((ccx_rc == 0 && cmp_rc == 0)) || exit 1
exit 0
