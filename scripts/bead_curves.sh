#!/usr/bin/env bash
# bead_curves.sh -- an equivalent bead from a sweep over lock_depth: its
# curves, friction counted once, and the cards of LS-DYNA and Radioss.
#
# Usage: scripts/bead_curves.sh [-o DIR] [-j N] [--bin PATH] [--no-build]
#                               [--depth D] [--bead-nodes ID] [--blank ID]
#                               [--lcid N] [--no-origin] SWEEPDIR
#
# SWEEPDIR is a folder made by scripts/sweep.sh with lock_depth among the
# swept variables (run it first, e.g.
#   scripts/sweep.sh -o out/sweep_a input/fig9c_beadA_steel_free.nml \
#       lock_depth=1,2,3,4,4.6
# ). Run it from the directory the sweep was run from (file names in the
# decks, such as profiles, mean what they meant for the sweep).
#
# First it runs, beside every case whose friction is not 0, its
# frictionless companion: the same deck with friction = 0 and friction_law = 'coulomb' (cases that
# differ only in friction share one), into SWEEPDIR/frictionless/ (decks/,
# runs/, decks.txt, status.tsv, companions.tsv). Companions already run
# from the same deck are not run again. Then, for each combination of the
# other swept variables (if any: the files get a suffix _VAR-VALUE...), it
# writes into DIR tables with '#' header lines giving the units, the
# source and what the numbers are for:
#   restraining_total.txt    the TOTAL restraining force per unit bead
#       length (N/mm) against the penetration = lock_depth (mm): bending
#       and friction, the runs of the sweep: for codes that take the whole
#       force (Radioss /INTER/TYPE8 Ft). The steady restraining force
#       (steady_force_over_Eh) where the run and its companion found one,
#       else the peak force (peak_force_over_Eh) of both; the header says
#       which
#   restraining_bending.txt  the BENDING part: the same from the
#       frictionless companions, for codes that add friction themselves
#       (LS-DYNA *CONTACT_DRAWBEAD LCIDRF)
#   lift.txt                 the lift (binder-opening, normal) force per
#       unit bead length (N/mm) of the runs with friction: pull.dat column
#       8, averaged over the window of the steady force, or at the peak
#   bead_table.txt           per depth: total, bending, friction part
#       (their difference), lift and the effective friction coefficient
#       (friction part / lift)
#   closing.txt              the closing (punch) force per unit bead length
#       against the rise H (mm) while the bead is pressed in, from lock.dat
#       of the deepest run
#   drawbead.k               LS-DYNA: *PARAMETER placeholders BEADNS and
#       BLANKID (unless --bead-nodes and --blank give them), the bending
#       (LCIDRF) and normal-force (LCIDNF) curves as *DEFINE_CURVE_TITLE
#       (ids N and N+1), and *CONTACT_DRAWBEAD with DBDTH = D and
#       FS = FD = the effective friction coefficient at D
#   drawbead_radioss.rad     Radioss Starter include: /INTER/TYPE8/N with
#       Fn (lift), Ft (total) and DEPTH at D, and the total and lift curves
#       as /FUNCT/N and N+1 (for reference)
# The forces are in N/mm (E h of each run times the normalized values).
# Only runs that completed or localized, with a companion that did, are
# used (the depths at which the sheet localized are named in the
# headers); the others are reported on stderr.
#
# Options:
#   -o DIR          where to write (default: SWEEPDIR/bead_curves)
#   -j N            companion runs at a time (default: nproc)
#   --bin PATH      the program (default: $DRAWBEAD if set, else
#                   bin/drawbead of the repository, built with make -s)
#   --no-build      do not run make
#   --depth D       the working penetration (mm) of the cards: the
#                   restraining force, lift and FS are read there (linear
#                   between the swept depths); default: the deepest depth
#   --bead-nodes ID the node set (LS-DYNA *SET_NODE, Radioss /GRNOD) along
#                   the bead line, written into the cards
#   --blank ID      the blank's part (LS-DYNA) and surface (Radioss /SURF)
#   --lcid N        the first curve id (default 1): LS-DYNA curves N, N+1;
#                   Radioss /INTER/TYPE8/N and /FUNCT/N, N+1
#   --no-origin     do not add the point (0, 0) in front of each curve (by
#                   default it is added when the smallest depth is above 0:
#                   no penetration, no bead force)
#   -h, --help      this text
#
# Use a free-edge base deck (left_edge = 'free', such as the fig9 decks)
# and a pull distance long enough for the force to level off: with a
# clamped edge the force keeps rising and there is no steady state.
#
# Exit status: 0 on success, 1 when no run gave a curve point (or a
# companion run failed), 2 on a usage or build error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2
tool=$root/scripts/bead_tool.py

outdir=''
extra=()
sweepdir=''
jobs_max=$(nproc 2>/dev/null || echo 2)
program=${DRAWBEAD:-}
do_build=1
split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        -o | --output)
            need_value "a directory" "$@"
            outdir=$2
            shift 2
            ;;
        -j)
            need_value "a number" "$@"
            jobs_max=$2
            shift 2
            ;;
        -j*)
            jobs_max=${1#-j}
            shift
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
        --no-origin)
            extra+=(--no-origin)
            shift
            ;;
        --lcid | --bead-nodes | --blank)
            need_value "a number" "$@"
            check_count "$1" "$2"
            extra+=("$1=$2")
            shift 2
            ;;
        --depth)
            need_value "a penetration in mm" "$@"
            [[ $2 =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$|^[0-9]+\.$ ]] ||
                die "--depth needs a penetration in mm, not '$2'"
            extra+=("--depth=$2")
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
[[ -n $sweepdir ]] || die "usage: bead_curves.sh [-o DIR] [-j N] [--depth D] ... SWEEPDIR (see --help)"
[[ -d $sweepdir ]] || die "no folder '$sweepdir'"
check_count -j "$jobs_max"
[[ -n $outdir ]] || outdir=$sweepdir/bead_curves

write_statuses "$sweepdir"

# ---------------------------------------------------------------------------
# The frictionless companions: written by bead_tool.py, which lists those
# to run (new, changed or never run)
# ---------------------------------------------------------------------------
todo=$(python3 "$tool" companions "$sweepdir") || exit 2
mapfile -t pool_decks < <(printf '%s' "$todo" | sed '/^$/d')
companion_failed=0
if ((${#pool_decks[@]} > 0)); then
    find_program "$program" "$do_build"
    pool_dirs=()
    for deck in "${pool_decks[@]}"; do
        pool_dirs+=("$sweepdir/frictionless/runs/$(basename "$deck" .nml)")
    done
    note "running ${#pool_decks[@]} frictionless companion(s) into $sweepdir/frictionless/runs/"
    # companion_done INDEX STATUS: one line per finished companion
    # shellcheck disable=SC2317 # called by run_pool
    companion_done() {
        (($2 == 0)) || companion_failed=$((companion_failed + 1))
        note "companion $(basename "${pool_decks[$1]}" .nml): exit status $2"
    }
    run_pool "$jobs_max" companion_done
fi
write_statuses "$sweepdir/frictionless"

python3 "$tool" curves "$sweepdir" "$outdir" "${extra[@]}"
status=$?
((status == 0 && companion_failed > 0)) && status=1
exit "$status"
