#!/usr/bin/env bash
# continuum_check.sh -- the continuum cross-check of a deck: the same case as
# a CalculiX plane-strain continuum model, its results in the program's own
# files, and program and continuum drawn together (docs/continuum-check.md).
#
# Usage: scripts/continuum_check.sh DECK [-o DIR] [options]
#
#   DECK              a drawbead deck (rectangular or profile tools, or none;
#                     clamped or free left edge; swift, voce or table
#                     hardening; von Mises: r_value = 1 (model 'combined':
#                     r0 = r90 = 1); model 'j2', or 'combined' with linear
#                     back stresses, kinematic_gamma = 0)
#   -o, --output DIR  the results folder (default out/continuum/<deck name>)
#   --through N       CPE8R elements through the thickness, even (default 4)
#   --per-h M         CPE8R elements per thickness h along the sheet (default 4)
#   --initial-inc T   first time increment (default 0.01; locking takes time
#                     0..1, pulling 1..2)
#   --max-inc T       largest time increment (default 0.02)
#   --min-inc T       smallest time increment (default 1e-7)
#   --output-every T  a row of results every T of time (default --max-inc)
#   --contact-slope K the contact's pressure-overclosure slope, MPa/mm
#                     (default 1e5; the friction's stick slope is K/10): 1e4
#                     gets the stepped bead (tight closed tools) through
#   --bin PATH        the program to run (default bin/drawbead, built first)
#   --no-plot         no pictures
#   -h, --help        this help
#
# Writes into DIR: program/ (the program's run on DECK: its files and
# run.log), ccx/ (continuum.inp, CalculiX's continuum.dat, .sta and ccx.log;
# large), lock.dat, pull.dat, strain_lock.dat, strain_pull.dat (the
# continuum's results in the program's columns), continuum_summary.txt,
# program_summary.txt (the same numbers read off the program's files),
# comparison.txt (both, and their ratio; also printed; the continuum's
# numbers from the first output time at which it is not a sheet lying in
# the tools are left out, and a line says when and why) and, with gnuplot,
# lock.png, pull.png and strain.png (program and continuum together).
# CalculiX runs on OMP_NUM_THREADS threads (default 1).
#
# Exit status: 0 the continuum run completed; 1 it stopped early (the
# files hold what it computed); 2 a usage, deck, model or build error.
set -u

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

deck=''
dir=''
bin_opt=''
plot=1
model_opts=()
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
        --through | --per-h | --initial-inc | --max-inc | --min-inc | --output-every | --contact-slope)
            need_value 'a number' "$@"
            model_option "$1" "$2"
            shift 2
            ;;
        --bin)
            need_value 'a program' "$@"
            bin_opt=$2
            shift 2
            ;;
        --no-plot)
            plot=0
            shift
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
command -v ccx >/dev/null 2>&1 || die "ccx (CalculiX) is not installed: apt-get install calculix-ccx"
name=$(basename "$deck" .nml)
[[ -n $dir ]] || dir=$root/out/continuum/$name
mkdir -p "$dir/ccx" || die "cannot make '$dir'"
dir=$(cd "$dir" && pwd) || die "cannot enter '$dir'"
find_program "$bin_opt" 1

# 1. the program on the deck: its resolved input is the case (defaults and
# checks are the program's own), its results the comparison
note "running the program on $deck into $dir/program"
run_deck "$bin" "$deck" "$dir/program"
rc=$?
if ((rc == exit_bad_input)); then
    grep -E '^\*ERROR\*' "$dir/program/run.log" >&2
    die "the program rejected '$deck'"
fi
((rc == exit_ok || rc == exit_no_convergence)) || note "the program exited with status $rc"

# 2. the continuum model, and CalculiX
python3 "$root/scripts/continuum_model.py" "$dir/program/run.log" "$dir/ccx" "${model_opts[@]}" ||
    die "no continuum model for '$deck'"
# a ccx that stops early leaves its results up to there: compared all the same
run_ccx "$dir/ccx" || :

# 3. its results in the program's files, and the compared numbers
python3 "$root/scripts/continuum_results.py" convert "$dir/ccx" "$dir" --program "$bin" ||
    die "cannot convert the results in $dir/ccx"
python3 "$root/scripts/continuum_results.py" metrics "$dir/program" "$dir/ccx/continuum_model.json" \
    --title "program: $name" >"$dir/program_summary.txt" || die "cannot read the program's results"
python3 "$root/scripts/continuum_results.py" compare "$dir/program_summary.txt" \
    "$dir/continuum_summary.txt" >"$dir/comparison.txt" || die "cannot compare"
cat "$dir/comparison.txt"

# 4. program and continuum together
if ((plot)) && command -v gnuplot >/dev/null 2>&1; then
    gnuplot -c "$root/scripts/plot_lock.gp" --title="$name: punch force" \
        "$dir/program/lock.dat::program" "$dir/lock.dat::continuum" "$dir/lock.png" >/dev/null 2>&1 ||
        note "no lock.png"
    gnuplot -c "$root/scripts/plot_pull.gp" --title="$name: restraining force" \
        "$dir/program/pull.dat::program" "$dir/pull.dat::continuum" "$dir/pull.png" >/dev/null 2>&1 ||
        note "no pull.png"
    gnuplot -e "set terminal pngcairo size 900,800 noenhanced; set output '$dir/strain.png';
        set multiplot layout 2,1 title '$name: mid-surface strain lambda - 1';
        set xlabel 's/h'; set ylabel 'lambda - 1'; set key top left; set grid;
        set title 'after locking';
        plot '$dir/program/strain_lock.dat' using 1:4 with lines lw 2 lc rgb '#0072B2' title 'program',
             '$dir/strain_lock.dat' using 1:4 with lines lw 2 dt 2 lc rgb '#D55E00' title 'continuum';
        set title 'after pulling';
        plot '$dir/program/strain_pull.dat' using 1:4 with lines lw 2 lc rgb '#0072B2' title 'program',
             '$dir/strain_pull.dat' using 1:4 with lines lw 2 dt 2 lc rgb '#D55E00' title 'continuum';
        unset multiplot" \
        >/dev/null 2>&1 || note "no strain.png"
fi

status=$(summary_value "$dir/continuum_summary.txt" status)
state=$(summary_value "$dir/continuum_summary.txt" continuum_state)
[[ $state == 'sheet in the tools' ]] ||
    note "the continuum is $state: its numbers from then on are left out of comparison.txt"
note "continuum: $status; results in $dir"
[[ $status == completed ]] || exit 1
exit 0
