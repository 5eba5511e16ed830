#!/usr/bin/env bash
# run_paper.sh -- run the paper's decks in parallel, draw the paper's
# figures with gnuplot and print a table of the results.
#
# Usage: scripts/run_paper.sh [options]
#
# Builds the program if needed (make -s), runs every paper deck
# (input/fig*.nml) with as many runs at a time as there are cores (one
# thread each), each
# into OUT/<deck>/ (OUT = out/ of the repository by default) with its log
# (stdout and stderr) in OUT/<deck>/run.log and the exit status in
# OUT/<deck>/exit_status, then draws the paper's figures into OUT/figures/
# with the gnuplot scripts scripts/plot_*.gp:
#   fig5a.png fig5b.png fig6.png   mid-surface strain after locking and
#                                  after pulling (plot_strain.gp)
#   fig7.png                       punch force F/(E h) against H/h, mu = 0
#                                  (fig7a-c) and mu = 0.1 (fig7d, thin
#                                  dashed) (plot_lock.gp)
#   fig8.png                       restraining force N/(E h) against
#                                  Delta/h, clamped (fig5b, fig5a, fig6)
#   fig9.png                       the same, free edge (fig9a-d)
#                                  (plot_pull.gp)
#   shape_beadA_lock.png, shape_beadA_pull.png (fig5a),
#   shape_beadB_lock.png, shape_beadB_pull.png (fig6)
#                                  the sheet in the tools (plot_shape.gp)
# A figure is drawn with the curves of the decks of this batch that left
# data (decks are recognised by their file name: fig5a_beadA_steel.nml
# and so on); a figure none of whose decks ran is skipped. Finally it
# prints a table of every run (also written to OUT/paper_table.txt): deck,
# delta_cr/h, s*/h, delta_cr_nonlocal/h, peak and steady N/(E h), final
# lock force F/(E h), cpu_seconds and status, all from summary.txt.
#
# Options:
#   -j N            runs at a time (default: nproc)
#   --decks "LIST"  run these decks (blank-separated paths) instead of
#                   input/fig*.nml (env PAPER_DECKS does the same)
#   -o, --output DIR  the output root (default: out/ of the repository)
#   --bin PATH      the program to run (default: $DRAWBEAD if set, else
#                   bin/drawbead of the repository, built with make -s)
#   --no-build      do not run make (use the existing program)
#   --no-figures    run and tabulate only
#   --no-run        do not run anything: draw the figures and the table
#                   from the outputs already in OUT (of the decks given)
#   --markdown      print the table as a GitHub markdown table
#   -h, --help      this text
#
# Deck paths are taken relative to the current directory, as are file
# names inside the decks.
#
# Exit status: 0 when every run exited 0 and every figure was drawn; 1
# when a run exited otherwise (1 bad input, 2 no convergence: its row
# says so) or a figure failed; 2 on a usage or build error.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2
scripts=$root/scripts

jobs_max=$(nproc 2>/dev/null || echo 2)
deck_list=${PAPER_DECKS:-}
outroot=$root/out
program=${DRAWBEAD:-}
do_build=1
do_figures=1
do_run=1
markdown=0

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
        --decks)
            need_value "a list of decks" "$@"
            deck_list=$2
            shift 2
            ;;
        -o | --output)
            need_value "a directory" "$@"
            outroot=$2
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
        --no-figures)
            do_figures=0
            shift
            ;;
        --no-run)
            do_run=0
            do_build=0
            shift
            ;;
        --markdown)
            markdown=1
            shift
            ;;
        -h | --help)
            usage
            exit 0
            ;;
        *)
            die "unknown argument '$1' (see --help)"
            ;;
    esac
done

check_count -j "$jobs_max"
if ((do_run)); then find_program "$program" "$do_build"; fi

# ---------------------------------------------------------------------------
# The decks
# ---------------------------------------------------------------------------
decks=()
if [[ -n $deck_list ]]; then
    read -r -a decks <<<"$deck_list"
else
    shopt -s nullglob
    decks=("$root"/input/fig*.nml)
    shopt -u nullglob
fi
((${#decks[@]} > 0)) || die "no decks to run"

declare -A seen=()
names=()
for deck in "${decks[@]}"; do
    [[ -r $deck ]] || die "cannot read deck '$deck'"
    name=$(basename "$deck" .nml)
    [[ -z ${seen[$name]:-} ]] || die "two decks named '$name' (their outputs would collide)"
    seen[$name]=1
    names+=("$name")
done

mkdir -p "$outroot" || die "cannot create '$outroot'"

# ---------------------------------------------------------------------------
# The runs, jobs_max at a time
# ---------------------------------------------------------------------------
total=${#decks[@]}
t0=$SECONDS
finished=0
failed=0
if ((do_run)); then
    note "$total decks, $jobs_max at a time, into $outroot/ ($bin)"
else
    # the outputs already there: count the runs that failed or are missing
    finished=$total
    for name in "${names[@]}"; do
        [[ $(cat "$outroot/$name/exit_status" 2>/dev/null) == "$exit_ok" ]] || failed=$((failed + 1))
    done
fi
# reported INDEX STATUS: count a finished run and report it
# shellcheck disable=SC2317 # called by run_pool
reported() {
    finished=$((finished + 1))
    (($2 == 0)) || failed=$((failed + 1))
    printf '%s: [%d/%d] %-30s exit %d  %s\n' "$me" "$finished" "$total" "${names[$1]}" \
        "$2" "$(run_status "$outroot/${names[$1]}")" >&2
}
if ((do_run)); then
    pool_decks=("${decks[@]}")
    pool_dirs=()
    for name in "${names[@]}"; do pool_dirs+=("$outroot/$name"); done
    run_pool "$jobs_max" reported
fi
((do_run)) && note "runs finished in $((SECONDS - t0)) s, $failed failed"

# ---------------------------------------------------------------------------
# The figures
# ---------------------------------------------------------------------------
figdir=$outroot/figures
figure_failures=0

# ran NAME: true if deck NAME was in this batch
ran() {
    [[ -n ${seen[$1]:-} ]]
}

# has_rows FILE: true if FILE exists and holds a data row
has_rows() {
    [[ -r $1 ]] && grep -qv '^#' "$1"
}

# gp_draw SCRIPT ARGS...: run a gnuplot script; exit status 0 if it drew
# its output (the last argument), 1 otherwise, with the messages on stderr
# (each figure's error file is its own: the figures are drawn in parallel)
gp_draw() {
    local script=$1 out=${*: -1} err status=0
    shift
    err=$out.gnuplot.err
    if gnuplot -c "$scripts/$script" "$@" 2>"$err"; then
        if [[ -s $out ]]; then
            note "drew $out"
        else
            note "gnuplot wrote no $out"
            status=1
        fi
    else
        note "gnuplot failed on $out:"
        sed 's/^/    /' "$err" >&2
        status=1
    fi
    # gnuplot's warnings (a skipped file, ...) are worth seeing
    if [[ -s $err ]]; then
        sed 's/^/    gnuplot: /' "$err" >&2
    fi
    rm -f "$err"
    return "$status"
}

# gp SCRIPT ARGS...: draw a figure in the background, at most jobs_max at a
# time (gnuplot takes about 0.4 s a figure); gp_wait collects them
gp_pids=()
gp() {
    while (($(jobs -rp | wc -l) >= jobs_max)); do wait -n; done
    gp_draw "$@" &
    gp_pids+=("$!")
}

# gp_wait: wait for every figure, counting the failures
gp_wait() {
    local pid
    for pid in "${gp_pids[@]}"; do
        wait "$pid" || figure_failures=$((figure_failures + 1))
    done
    gp_pids=()
}

# curves FILE NAME:LABEL[:STYLE]...: gnuplot arguments FILE::LABEL[::STYLE]
# for each deck NAME of this batch whose OUT/NAME/FILE has data
curve_args=()
curves() {
    local file=$1 spec name rest
    shift
    curve_args=()
    for spec in "$@"; do
        name=${spec%%:*}
        rest=${spec#*:}
        ran "$name" || continue
        has_rows "$outroot/$name/$file" || continue
        curve_args+=("$outroot/$name/$file::${rest/:/::}")
    done
}

strain_figure() {
    local name=$1 out=$2 title=$3
    ran "$name" && has_rows "$outroot/$name/strain_lock.dat" || return 0
    gp plot_strain.gp "--title=$title" "$outroot/$name" "$figdir/$out"
}

shape_figures() {
    local name=$1 bead=$2 what=$3 phase
    ran "$name" || return 0
    for phase in lock pull; do
        has_rows "$outroot/$name/strain_$phase.dat" || continue
        [[ -r $outroot/$name/tools_$phase.dat ]] || continue
        gp plot_shape.gp "--title=Bead $bead in the tools ($what): %s" \
            "$outroot/$name" "$phase" "$figdir/shape_bead${bead}_$phase.png"
    done
}

if ((do_figures)); then
    if ! command -v gnuplot >/dev/null; then
        note "gnuplot not found (apt-get install gnuplot-nox): no figures"
        figure_failures=1
    else
        mkdir -p "$figdir" || die "cannot create '$figdir'"

        strain_figure fig5a_beadA_steel fig5a.png \
            'Fig. 5(a)  Strain distribution: bead A, mild steel, clamped, μ = 0.1'
        strain_figure fig5b_beadA_brass fig5b.png \
            'Fig. 5(b)  Strain distribution: bead A, brass, clamped, μ = 0.1'
        strain_figure fig6_beadB_steel fig6.png \
            'Fig. 6  Strain distribution: bead B, mild steel, clamped, μ = 0.1'

        curves lock.dat \
            'fig7a_beadA_brass_mu0:(a) bead A, brass' \
            'fig7b_beadA_steel_mu0:(b) bead A, mild steel' \
            'fig7c_beadB_steel_mu0:(c) bead B, mild steel' \
            "fig7d_beadA_steel_mu01:bead A, mild steel, μ = 0.1:lw 1.2 dt 2 lc rgb '#000000'"
        if ((${#curve_args[@]} > 0)); then
            gp plot_lock.gp '--title=Fig. 7  Punch force vs. lock depth, clamped edge, μ = 0 (dashed black: μ = 0.1)' \
                "${curve_args[@]}" "$figdir/fig7.png"
        fi

        curves pull.dat \
            'fig5b_beadA_brass:(a) bead A, brass' \
            'fig5a_beadA_steel:(b) bead A, mild steel' \
            'fig6_beadB_steel:(c) bead B, mild steel'
        if ((${#curve_args[@]} > 0)); then
            gp plot_pull.gp '--title=Fig. 8  Restraining force vs. pull displacement, clamped edge, μ = 0.1' \
                "${curve_args[@]}" "$figdir/fig8.png"
        fi

        curves pull.dat \
            'fig9a_beadA_brass_free:(a) bead A, brass, μ = 0.1' \
            'fig9b_beadA_steel_free_mu02:(b) bead A, mild steel, μ = 0.2' \
            'fig9c_beadA_steel_free:(c) bead A, mild steel, μ = 0.1' \
            'fig9d_beadB_steel_free:(d) bead B, mild steel, μ = 0.1'
        if ((${#curve_args[@]} > 0)); then
            gp plot_pull.gp '--title=Fig. 9  Restraining force vs. pull displacement, free edge' \
                "${curve_args[@]}" "$figdir/fig9.png"
        fi

        shape_figures fig5a_beadA_steel A 'mild steel, clamped, μ = 0.1'
        shape_figures fig6_beadB_steel B 'mild steel, clamped, μ = 0.1'
        gp_wait
    fi
fi

# ---------------------------------------------------------------------------
# The table
# ---------------------------------------------------------------------------
# fmt FORMAT VALUE: printf a number, or pass 'none' / '' through
fmt() {
    if [[ -z $2 ]]; then
        echo '-'
    elif [[ $2 == none ]]; then
        echo none
    else
        # shellcheck disable=SC2059 # the format is the caller's
        printf "$1" "$2"
    fi
}

header=(deck 'delta_cr/h' 's*/h' 'delta_cr_nonlocal/h' 'peak_N/(Eh)' 'steady_N/(Eh)'
    'lock_F/(Eh)' 'cpu_s' status)
rows=()
for name in "${names[@]}"; do
    dir=$outroot/$name
    row=("$name"
        "$(fmt %.3f "$(summary_value "$dir/summary.txt" delta_cr_over_h)")"
        "$(fmt %.2f "$(summary_value "$dir/summary.txt" s_star_over_h)")"
        "$(fmt %.3f "$(summary_value "$dir/summary.txt" delta_cr_nonlocal_over_h)")"
        "$(fmt %.4e "$(summary_value "$dir/summary.txt" peak_force_over_Eh)")"
        "$(fmt %.4e "$(summary_value "$dir/summary.txt" steady_force_over_Eh)")"
        "$(fmt %.4e "$(summary_value "$dir/summary.txt" lock_force_over_Eh)")"
        "$(fmt %.2f "$(summary_value "$dir/summary.txt" cpu_seconds)")"
        "$(run_status "$dir")")
    rows+=("$(printf '%s\t' "${row[@]}")")
done

# align_columns: tab-separated lines on stdin, printed in aligned columns
align_columns() {
    awk -F'\t' '
        { n[NR] = NF; for (i = 1; i <= NF; i++) { c[NR, i] = $i; if (length($i) > w[i]) w[i] = length($i) } }
        END {
            for (r = 1; r <= NR; r++) {
                line = ""
                for (i = 1; i <= n[r]; i++) if (c[r, i] != "" || i < n[r]) line = line sprintf("%-" w[i] + 2 "s", c[r, i])
                sub(/ +$/, "", line)
                print line
            }
        }'
}

print_table() {
    if ((markdown)); then
        printf '| %s ' "${header[@]}"
        echo '|'
        printf '| --- '
        printf '| ---: %.0s' "${header[@]:1:${#header[@]}-2}"
        echo '| --- |'
        local r
        for r in "${rows[@]}"; do
            local fields
            IFS=$'\t' read -r -a fields <<<"$r"
            printf '| %s ' "${fields[@]}"
            echo '|'
        done
    else
        {
            printf '%s\t' "# ${header[0]}" "${header[@]:1}"
            echo
            printf '%s\n' "${rows[@]}"
        } | align_columns
    fi
}

print_table | tee "$outroot/paper_table.txt"

status=0
if ((failed > 0)); then
    note "$failed of $total runs failed (see $outroot/<deck>/run.log)"
    status=1
fi
if ((figure_failures > 0)); then
    note "$figure_failures figures failed"
    status=1
fi
exit "$status"
