#!/usr/bin/env bash
# convergence.sh -- mesh and increment convergence study of one or more decks.
#
# Usage: scripts/convergence.sh [-o OUTDIR] [-n "80 160 320"] DECK...
#
# For each deck and each element count n it writes a copy of the deck with
# n_elements = n and max_increment = 0.1h * (n0/n) (n0 = the first count: the
# largest increment is halved whenever the elements are doubled), runs it
# (two at a time, one thread each) into OUTDIR/<deck>_<n>/ (with its log in
# run.log there) and prints one table row per run: punch force at full
# lock, peak and steady restraining force, the paper's pointwise tearing
# point delta_cr and the mesh-objective one, and the change of each force
# from the previous mesh, in percent.
set -u -o pipefail

# shellcheck source=scripts/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2

outdir=out/convergence
counts="80 160 320"
while getopts "o:n:h" opt; do
    case $opt in
        o) outdir=$OPTARG ;;
        n) counts=$OPTARG ;;
        *) usage; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ]; then
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

pool_decks=()
pool_dirs=()
for deck in "$@"; do
    name=$(basename "$deck" .nml)
    read -r n0 _ <<< "$counts"
    h=$(awk -F'=' '/^ *thickness *=/ { gsub(/ /, "", $2); print $2; exit }' "$deck")
    for n in $counts; do
        inc=$(awk -v h="$h" -v n0="$n0" -v n="$n" 'BEGIN { printf "%.6g", 0.1 * h * n0 / n }')
        sed -e "s/^ *n_elements *=.*/   n_elements = $n/" \
            -e "s/^&loading/\&loading\n   max_increment = $inc/" "$deck" > "$outdir/${name}_$n.nml" ||
            die "cannot write '$outdir/${name}_$n.nml'"
        pool_decks+=("$outdir/${name}_$n.nml")
        pool_dirs+=("$outdir/${name}_$n")
    done
done
ran() { :; }
run_pool 2 ran

# change OLD NEW: the change in percent, or -
change() {
    if [ -z "$1" ] || [ "$1" = none ] || [ "$2" = none ]; then echo "-"; else
        awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", 100 * (b - a) / a }'; fi
}

printf '%-28s %5s %12s %12s %12s %10s %10s %8s %8s %8s\n' deck n F_lock/Eh N_peak/Eh N_steady/Eh dcr/h dcr_nl/h dF% dNpk% dNst%
for deck in "$@"; do
    name=$(basename "$deck" .nml)
    prev_f=""; prev_p=""; prev_s=""
    for n in $counts; do
        s="$outdir/${name}_$n/summary.txt"
        f=$(value "$s" lock_force_over_Eh); p=$(value "$s" peak_force_over_Eh)
        st=$(value "$s" steady_force_over_Eh); dcr=$(value "$s" delta_cr_over_h)
        dnl=$(value "$s" delta_cr_nonlocal_over_h)
        printf '%-28s %5s %12.5g %12.5g %12.5g %10.4g %10.4g %8s %8s %8s\n' "$name" "$n" \
            "${f/none/nan}" "${p/none/nan}" "${st/none/nan}" "${dcr/none/nan}" "${dnl/none/nan}" \
            "$(change "$prev_f" "$f")" "$(change "$prev_p" "$p")" "$(change "$prev_s" "$st")"
        prev_f=$f; prev_p=$p; prev_s=$st
    done
done
