#!/usr/bin/env bash
# bead_curves.sh -- equivalent-bead load curves from a sweep over lock_depth.
#
# Usage: scripts/bead_curves.sh [-o DIR] [--no-origin] [--lcid N] SWEEPDIR
#
# SWEEPDIR is a folder made by scripts/sweep.sh with lock_depth among the
# swept variables (run it first, e.g.
#   scripts/sweep.sh -o out/sweep_a input/fig9c_beadA_steel_free.nml \
#       lock_depth=1,2,3,4,4.7
# ). For each combination of the other swept variables (if any) it writes
# two-column tables, with '#' header lines giving the units and the
# source:
#   DIR/restraining[_VAR-VALUE...].txt  restraining force per unit bead
#       length (N/mm) against the penetration = lock_depth (mm): the steady
#       restraining force (steady_force_over_Eh) where the run found one,
#       else the peak force (peak_force_over_Eh); the header says which
#   DIR/lift[_VAR-VALUE...].txt          lift (binder-opening, normal)
#       force per unit bead length (N/mm) against the penetration (mm):
#       pull.dat column 8, averaged over the same window as the steady
#       force, or taken at the peak force
#   DIR/closing[_VAR-VALUE...].txt       closing (punch) force per unit
#       bead length (N/mm) against the rise H (mm) while the bead is pressed
#       in, from lock.dat of the deepest run (the force bending the sheet
#       into the bead as the binder closes)
# and DIR/drawbead_curves.k, the restraining and lift curves as LS-DYNA
# *DEFINE_CURVE_TITLE cards (LCID N, N+1, N+2, ...: restraining then lift
# force for each combination), for *CONTACT_DRAWBEAD's LCIDRF and LCIDNF.
# The forces are in N/mm (E h of each run times the normalized values).
# Only runs that completed, tore or localized are used (tearing is a
# result: the depths at which the sheet tore or localized are named in the
# headers, their force that up to tearing); the others are reported on
# stderr. The restraining force includes friction: see docs/user-guide.md for how
# to use the curves.
#
# Options:
#   -o DIR        where to write (default: SWEEPDIR/bead_curves)
#   --no-origin   do not add the point (0, 0) in front of each curve (by
#                 default it is added when the smallest depth is above 0:
#                 no penetration, no bead force)
#   --lcid N      the first LS-DYNA curve id (default 1)
#   -h, --help    this text
#
# Use a free-edge base deck (left_edge = 'free', such as the fig9 decks)
# and a pull distance long enough for the force to level off: with a
# clamped edge the force keeps rising and there is no steady state.
#
# Exit status: 0 on success, 1 when no run gave a curve point, 2 on a
# usage error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

outdir=''
extra=()
sweepdir=''
split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        -o | --output)
            need_value "a directory" "$@"
            outdir=$2
            shift 2
            ;;
        --no-origin)
            extra+=(--no-origin)
            shift
            ;;
        --lcid)
            need_value "a number" "$@"
            check_count --lcid "$2"
            extra+=("--lcid=$2")
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
            [[ -z $sweepdir ]] || die "only one sweep folder, please"
            sweepdir=$1
            shift
            ;;
    esac
done
[[ -n $sweepdir ]] || die "usage: bead_curves.sh [-o DIR] [--no-origin] [--lcid N] SWEEPDIR"
[[ -d $sweepdir ]] || die "no folder '$sweepdir'"
[[ -n $outdir ]] || outdir=$sweepdir/bead_curves

write_statuses "$sweepdir"
python3 "$root/scripts/sweep_tool.py" curves "$sweepdir" "$outdir" "${extra[@]}"
