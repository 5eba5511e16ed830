#!/usr/bin/env bash
# convergence.sh -- mesh and step convergence study of one or more decks.
#
# Usage: scripts/convergence.sh [-m | -s] [-o OUTDIR] [-n "80 160 320"]
#                               [-f "1 0.5"] DECK...
#
# Both studies by default, one after the other; -m the mesh study alone,
# -s the step study alone. The runs go two at a time, one thread each.
#
# Mesh study: for each deck and each element count n of -n it writes a
# copy of the deck with n_elements = n and max_increment = 0.1h * (n0/n)
# (n0 = the first count: the largest increment is halved whenever the
# elements are doubled) and, if the deck has a refined zone, its
# refine_element times n0/n (every element is refined), runs it into
# OUTDIR/<deck>_<n>/ (with its log in run.log there) and prints one table row per run: punch force at full
# lock, peak and steady restraining force, the paper's pointwise tearing
# point delta_cr and the averaged-strain one, the tearing prediction
# (tearing_delta_over_h), and the change of each force and of the tearing
# prediction from the previous mesh, in percent.
#
# Step study (docs/theory.md §8.3): for each deck and each factor f of -f
# (default "1 0.5": every increment halved) a copy of the deck on its own
# mesh with every increment control scaled: initial_increment,
# max_increment, branch_increment, max_force_change and
# squeeze_force_change times f, and
# step_tolerance (a bound on a local error of second order in the
# increment) times f^2, each from the deck's value or the default. It runs
# them into OUTDIR/<deck>_step<f>/ and prints one row per run: increments,
# Newton iterations, the punch force at full lock, the peak and steady
# restraining forces, the tearing point (tearing_delta_over_h) and the
# paper's delta_cr, then the change of each from the first factor, in
# percent ("-" where either is none).
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

outdir=out/convergence
counts="80 160 320"
factors="1 0.5"
mesh=1
step=1
while getopts "msf:o:n:h" opt; do
    case $opt in
        m) step=0 ;;
        s) mesh=0 ;;
        f) factors=$OPTARG ;;
        o) outdir=$OPTARG ;;
        n) counts=$OPTARG ;;
        *) usage; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ] || { [ $mesh = 0 ] && [ $step = 0 ]; }; then
    usage
    exit 2
fi
find_program '' 1
mkdir -p "$outdir" || die "cannot create '$outdir'"

# value FILE KEY: the summary value, or none
value() {
    local v
    v=$(summary_value "$1" "$2")
    echo "${v:-none}"
}

# change OLD NEW: the change in percent, or -
change() {
    if [ -z "$1" ] || [ "$1" = none ] || [ "$2" = none ]; then echo "-"; else
        awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", 100 * (b - a) / a }'; fi
}

# thickness DECK: the deck's sheet thickness
thickness() {
    awk -F'=' '/^ *thickness *=/ { gsub(/[ ,]/, "", $2); print $2; exit }' "$1"
}

ran() { :; }

mesh_study() {
    local deck name n0 h n inc zone s f p st dcr dnl tear prev_f prev_p prev_s prev_t
    pool_decks=()
    pool_dirs=()
    for deck in "$@"; do
        name=$(basename "$deck" .nml)
        read -r n0 _ <<< "$counts"
        h=$(thickness "$deck")
        for n in $counts; do
            inc=$(awk -v h="$h" -v n0="$n0" -v n="$n" 'BEGIN { printf "%.6g", 0.1 * h * n0 / n }')
            # the deck's refine_element (any case, not in a comment; a d
            # exponent read as e)
            zone=$(awk -v n0="$n0" -v n="$n" '{ sub(/!.*/, ""); l = tolower($0) }
                match(l, /refine_element *= *[0-9.ed+-]+/) {
                v = substr(l, RSTART, RLENGTH); sub(/.*= */, "", v); gsub(/d/, "e", v)
                printf "%.6g", v * n0 / n; exit }' "$deck")
            sed -e "s/^ *n_elements *=.*/   n_elements = $n/" \
                -e "s/^\([^!]*\)refine_element *= *[0-9.eEdD+-]*/\1refine_element = ${zone:-0}/I" \
                -e "s/^&loading/\&loading\n   max_increment = $inc/" "$deck" > "$outdir/${name}_$n.nml" ||
                die "cannot write '$outdir/${name}_$n.nml'"
            pool_decks+=("$outdir/${name}_$n.nml")
            pool_dirs+=("$outdir/${name}_$n")
        done
    done
    run_pool 2 ran

    printf '%-28s %5s %12s %12s %12s %10s %10s %10s %8s %8s %8s %8s\n' deck n F_lock/Eh N_peak/Eh \
        N_steady/Eh dcr/h dcr_nl/h tear/h dF% dNpk% dNst% dtear%
    for deck in "$@"; do
        name=$(basename "$deck" .nml)
        prev_f=""; prev_p=""; prev_s=""; prev_t=""
        for n in $counts; do
            s="$outdir/${name}_$n/summary.txt"
            f=$(value "$s" lock_force_over_Eh); p=$(value "$s" peak_force_over_Eh)
            st=$(value "$s" steady_force_over_Eh); dcr=$(value "$s" delta_cr_over_h)
            dnl=$(value "$s" delta_cr_nonlocal_over_h); tear=$(value "$s" tearing_delta_over_h)
            printf '%-28s %5s %12.5g %12.5g %12.5g %10.4g %10.4g %10.4g %8s %8s %8s %8s\n' "$name" "$n" \
                "${f/none/nan}" "${p/none/nan}" "${st/none/nan}" "${dcr/none/nan}" "${dnl/none/nan}" \
                "${tear/none/nan}" "$(change "$prev_f" "$f")" "$(change "$prev_p" "$p")" \
                "$(change "$prev_s" "$st")" "$(change "$prev_t" "$tear")"
            prev_f=$f; prev_p=$p; prev_s=$st; prev_t=$tear
        done
    done
}

# loading_value DECK KEY DEFAULT: the deck's value of the &loading control
# KEY (set on a line of its own, as the shipped decks do) or DEFAULT
loading_value() {
    local v
    v=$(awk -F'=' -v k="$2" '$1 ~ "^ *" k " *$" { gsub(/[ ,]/, "", $2); print $2; exit }' "$1")
    echo "${v:-$3}"
}

# step_deck DECK F OUT: DECK with every increment control scaled by F
# (step_tolerance by F^2), written to OUT; the defaults are those of
# docs/input-reference.md
step_deck() {
    local deck=$1 f=$2 h ii mi bi mf sf st lines
    h=$(thickness "$deck")
    ii=$(loading_value "$deck" initial_increment "$(awk -v h="${h:-1}" 'BEGIN { print 0.05 * h }')")
    mi=$(loading_value "$deck" max_increment "$(awk -v h="${h:-1}" 'BEGIN { print 0.2 * h }')")
    bi=$(loading_value "$deck" branch_increment "$(awk -v h="${h:-1}" 'BEGIN { print 0.008 * h }')")
    mf=$(loading_value "$deck" max_force_change 0.1)
    sf=$(loading_value "$deck" squeeze_force_change 0.04)
    st=$(loading_value "$deck" step_tolerance 5e-3)
    lines=$(awk -v f="$f" -v ii="$ii" -v mi="$mi" -v bi="$bi" -v mf="$mf" -v sf="$sf" -v st="$st" 'BEGIN {
        printf "   initial_increment = %.8g\\n   max_increment = %.8g\\n", ii * f, mi * f
        printf "   branch_increment = %.8g\\n", bi * f
        printf "   max_force_change = %.8g\\n   squeeze_force_change = %.8g\\n", mf * f, sf * f
        printf "   step_tolerance = %.8g", st * f * f }')
    sed -e '/^ *\(initial_increment\|max_increment\|branch_increment\|max_force_change\|squeeze_force_change\|step_tolerance\) *=/d' \
        -e "s/^&loading.*/&\n$lines/" "$deck" > "$3"
}

step_study() {
    local deck name f f0 s base keys k v b row
    keys=(lock_force_over_Eh peak_force_over_Eh steady_force_over_Eh tearing_delta_over_h delta_cr_over_h)
    pool_decks=()
    pool_dirs=()
    for deck in "$@"; do
        name=$(basename "$deck" .nml)
        for f in $factors; do
            step_deck "$deck" "$f" "$outdir/${name}_step$f.nml" ||
                die "cannot write '$outdir/${name}_step$f.nml'"
            pool_decks+=("$outdir/${name}_step$f.nml")
            pool_dirs+=("$outdir/${name}_step$f")
        done
    done
    run_pool 2 ran

    read -r f0 _ <<< "$factors"
    printf '%-28s %5s %5s %6s %11s %11s %11s %8s %8s %7s %7s %7s %7s %7s\n' deck f incr iters \
        F_lock/Eh N_peak/Eh N_steady/Eh tear/h dcr/h dF% dNpk% dNst% dtear% ddcr%
    for deck in "$@"; do
        name=$(basename "$deck" .nml)
        base="$outdir/${name}_step$f0/summary.txt"
        for f in $factors; do
            s="$outdir/${name}_step$f/summary.txt"
            row=$(printf '%-28s %5s %5s %6s' "$name" "$f" "$(value "$s" increments)" \
                "$(value "$s" newton_iterations)")
            for k in "${keys[@]}"; do
                v=$(value "$s" "$k")
                case $k in
                    tearing_delta_over_h | delta_cr_over_h) row+=$(printf ' %8.4g' "${v/none/nan}") ;;
                    *) row+=$(printf ' %11.5g' "${v/none/nan}") ;;
                esac
            done
            for k in "${keys[@]}"; do
                v=$(value "$s" "$k"); b=$(value "$base" "$k")
                row+=$(printf ' %7s' "$(change "$b" "$v")")
            done
            echo "$row"
        done
    done
}

if [ $mesh = 1 ]; then mesh_study "$@"; fi
if [ $mesh = 1 ] && [ $step = 1 ]; then echo; fi
if [ $step = 1 ]; then step_study "$@"; fi
