#!/usr/bin/env bash
# make_docs_figures.sh -- regenerate docs/figures/ (the pictures embedded in
# README.md) from the figures of scripts/run_paper.sh.
#
# Usage: scripts/make_docs_figures.sh [--run] [-j N] [FIGDIR]
#
# Copies the paper's figures (fig5a, fig5b, fig6, fig7, fig8, fig9 and the
# sheet in beads A and B at the end of locking and of pulling, as PNG) from
# FIGDIR (default: out/figures of the repository) into docs/figures/.
# With --run it first runs scripts/run_paper.sh (all the paper's decks,
# -j N at a time) into out/. Look at the pictures before committing them.
#
# Exit status: 0 when every figure was copied; 1 when run_paper.sh failed
# or a figure is missing (the others are still copied); 2 on a usage error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

run=0
jobs=()
figdir=$root/out/figures
split_options "$@"
set -- "${split_args[@]}"
while (($# > 0)); do
    case $1 in
        --run)
            run=1
            shift
            ;;
        -j)
            need_value "a number" "$@"
            check_count -j "$2"
            jobs=(-j "$2")
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
            figdir=$1
            shift
            ;;
    esac
done

status=0
if ((run)); then
    "$root/scripts/run_paper.sh" "${jobs[@]}" -o "$root/out" || status=1
    figdir=$root/out/figures
fi

figures=(fig5a fig5b fig6 fig7 fig8 fig9
    shape_beadA_lock shape_beadA_pull shape_beadB_lock shape_beadB_pull)
dest=$root/docs/figures
mkdir -p "$dest" || exit 2
copied=0
for f in "${figures[@]}"; do
    if [[ -s $figdir/$f.png ]]; then
        cp "$figdir/$f.png" "$dest/$f.png" || status=1
        copied=$((copied + 1))
    else
        note "missing $figdir/$f.png"
        status=1
    fi
done
note "copied $copied of ${#figures[@]} figures into $dest"
exit "$status"
