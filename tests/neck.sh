#!/usr/bin/env bash
# neck.sh -- &sheet refine_neck (docs/theory.md §7.5) on the small deck
# tests/decks/neck_bead_b.nml (20 elements of 3h, zone elements of 0.5h):
#   - the first pass on the uniform mesh writes its results and summary
#     into OUTDIR/coarse and tears there; the run proper has the zone
#     neck_half_width = 2h either side of the uniform mesh's node nearest
#     that neck, and its summary says so (neck_refinement = zone, the
#     coarse tearing point, the zone);
#   - the run proper is the run of the same deck with that zone given by
#     hand (refine_from, refine_to): the same results to 1e-9;
#   - uniform elements no longer than refine_element (60 elements of 1h,
#     refine_element = 1): no first pass, no zone (neck_refinement = none),
#     the results of the deck without refine_neck;
#   - a first pass that does not tear (a pull too short; completed, or
#     localized by the paper's pointwise criterion, which it also reports):
#     no zone, the uniform mesh's results;
#   - SIGTERM in the first pass: exit 4, the run's summary.txt says
#     interrupted (replacing an earlier run's), and so does the first
#     pass's; a failed write in it: exit 3, write_failed; no convergence
#     in it within the deck's pull: exit 2, no_convergence;
#   - a run without refine_neck removes an earlier run's first pass.
# Usage: tests/neck.sh [path/to/drawbead]   (run from anywhere)
set -u
cd "$(dirname "$0")/.." || exit 2
bin=${1:-bin/drawbead}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
deck=tests/decks/neck_bead_b.nml
fails=0
value() { awk -F' = ' -v k="$2" '$1 == k { print $2 }' "$1"; }
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
# same KEY DIR1 DIR2: the two summaries' KEY agree to 1e-9 relative (or
# are the same text)
same() {
    local a b
    a=$(value "$2/summary.txt" "$1"); b=$(value "$3/summary.txt" "$1")
    if [ "$a" = "$b" ]; then return 0; fi
    awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; m = (a < 0 ? -a : a);
        if ((b < 0 ? -b : b) > m) m = (b < 0 ? -b : b); exit !(a != "none" && b != "none" && d <= 1e-9 * m) }'
}
# run NAME DECK: run DECK into $out/NAME; fails the test on a non-zero exit
run() {
    if ! "$bin" "$2" --output "$out/$1" > "$out/$1.log" 2>&1; then
        fail "$1: exit status not 0:"; tail -5 "$out/$1.log"; return 1
    fi
}

# 1. the first pass tears; the zone is centred on its neck
run neck "$deck" || exit 1
s=$out/neck/summary.txt
c=$out/neck/coarse/summary.txt
if [ ! -f "$c" ] || [ "$(value "$c" status)" != torn ] || [ "$(value "$c" elements)" != 20 ]; then
    fail "neck: the first pass's summary $c: missing, not torn or not 20 elements"
fi
if [ "$(value "$s" neck_refinement)" != zone ] || [ "$(value "$s" coarse_elements)" != 20 ] ||
    [ "$(value "$s" coarse_tearing_delta_over_h)" != "$(value "$c" tearing_delta_over_h)" ] ||
    [ "$(value "$s" coarse_tearing_s_over_h)" != "$(value "$c" tearing_s_over_h)" ] ||
    [ "$(value "$s" coarse_assemblies)" != "$(value "$c" assemblies)" ]; then
    fail "neck: the summary does not report the first pass:"; grep -E '^(neck|coarse)' "$s"
fi
from=$(value "$s" neck_zone_from_over_h); to=$(value "$s" neck_zone_to_over_h)
star=$(value "$c" tearing_s_over_h)
# the zone: 2h either side of the node of the uniform mesh (3h elements on
# [-30h, 30h]) nearest the first pass's neck
if ! awk -v a="$from" -v b="$to" -v s="$star" 'BEGIN { c = -30 + 3 * int((s + 30) / 3 + 0.5);
        e = a - (c - 2); f = b - (c + 2); exit !(e * e < 1e-20 && f * f < 1e-20) }'; then
    fail "neck: zone [$from, $to] is not 2h either side of the node nearest the first pass's neck $star"
fi
# 16 of 3h outside the zone (rounded to whole elements), 8 of 0.5h in it
if [ "$(value "$s" elements)" != 26 ] || [ "$(value "$s" status)" != torn ]; then
    fail "neck: expected a torn run on 26 elements, got $(value "$s" status) on $(value "$s" elements)"
fi
echo "ok   neck: first pass torn at s/h = $star, zone [$from, $to], run proper torn at" \
    "delta/h = $(value "$s" tearing_delta_over_h)"

# 2. the same zone by hand: the same results
sed -e "s/refine_neck = .true., refine_element = 0.5/refine_from = $from, refine_to = $to, refine_element = 0.5/" \
    "$deck" > "$out/hand.nml"
if run hand "$out/hand.nml"; then
    for k in status tearing_delta_over_h tearing_s_over_h lock_force_over_Eh peak_force_over_Eh elements; do
        same "$k" "$out/neck" "$out/hand" || fail "neck against the zone by hand: $k differs:" \
            "$(value "$s" "$k") against $(value "$out/hand/summary.txt" "$k")"
    done
    if [ "$(value "$out/hand/summary.txt" neck_refinement)" != off ]; then
        fail "hand: neck_refinement is not off"
    fi
    echo "ok   neck: the results of the zone given by hand"
fi

# 3. uniform elements of 1h (60 elements) against refine_element = 1:
# nothing to refine
sed -e 's/refine_element = 0.5/refine_element = 1.0/' -e 's/n_elements = 20/n_elements = 60/' "$deck" > "$out/fine.nml"
sed -e 's/refine_neck = .true., refine_element = 0.5/refine_exit = .false./' -e 's/n_elements = 20/n_elements = 60/' "$deck" \
    > "$out/plain60.nml"
sed -e 's/refine_neck = .true., refine_element = 0.5/refine_exit = .false./' "$deck" > "$out/plain.nml"
if run fine "$out/fine.nml" && run plain60 "$out/plain60.nml"; then
    if [ "$(value "$out/fine/summary.txt" neck_refinement)" != none ] || [ -e "$out/fine/coarse" ]; then
        fail "fine: expected neck_refinement = none and no first pass"
    fi
    for k in status tearing_delta_over_h peak_force_over_Eh elements; do
        same "$k" "$out/fine" "$out/plain60" || fail "fine against plain: $k differs"
    done
    echo "ok   neck: elements no longer than refine_element: no first pass, the uniform mesh's results"
fi

# 4. a pull of 1h: the first pass (1.5h) does not tear, the mesh stays uniform
sed -e 's/pull_distance = 3.81/pull_distance = 0.762/' "$deck" > "$out/short.nml"
sed -e 's/pull_distance = 3.81/pull_distance = 0.762/' "$out/plain.nml" > "$out/short_plain.nml"
if run short "$out/short.nml" && run short_plain "$out/short_plain.nml"; then
    if [ "$(value "$out/short/summary.txt" neck_refinement)" != none ] ||
        ! grep -qE '^status = (completed|localized)$' "$out/short/coarse/summary.txt" ||
        [ "$(value "$out/short/summary.txt" coarse_tearing_delta_over_h)" != none ]; then
        fail "short: expected neck_refinement = none after a first pass without tearing"
    fi
    for k in status final_force_over_Eh peak_force_over_Eh elements; do
        same "$k" "$out/short" "$out/short_plain" || fail "short against plain: $k differs"
    done
    echo "ok   neck: a first pass without a neck: no zone, the uniform mesh's results"
fi
# 5. SIGTERM in the first pass: exit 4; summary.txt of the run says
# interrupted (no increment of the run proper) in place of an earlier
# run's, whose other results are gone; the first pass's own summary too
sed -e 's/^&sheet$/\&sheet\n   refine_neck = .true./' input/cc_fig5a_beadA_steel.nml > "$out/term.nml"
mkdir -p "$out/term"
printf 'status = completed\n' > "$out/term/summary.txt"
printf 'stale\n' > "$out/term/snapshots.dat"
"$bin" "$out/term.nml" -o "$out/term" > "$out/term.log" 2>&1 &
pid=$!
for _ in $(seq 200); do
    grep -q 'increments = *[1-9]' "$out/term/coarse/summary.txt" 2>/dev/null && break
    sleep 0.01
done
kill -TERM "$pid"
wait "$pid"
status=$?
if ((status == 4)) && [ "$(value "$out/term/summary.txt" status)" = interrupted ] &&
    [ "$(value "$out/term/summary.txt" increments)" = 0 ] &&
    [ "$(value "$out/term/coarse/summary.txt" status)" = interrupted ] && [ ! -e "$out/term/snapshots.dat" ]; then
    echo "ok   neck: SIGTERM in the first pass: exit 4, both summaries say interrupted, no stale result"
else
    fail "neck: SIGTERM in the first pass: exit $status, summary status $(value "$out/term/summary.txt" status)," \
        "first pass $(value "$out/term/coarse/summary.txt" status); snapshots.dat $(ls "$out/term/snapshots.dat" 2>&1)"
fi
# 6. a run without refine_neck into a directory with an earlier run's
# first pass: those results are removed too
mkdir -p "$out/stale/coarse"
printf 'status = torn\n' > "$out/stale/coarse/summary.txt"
printf 'stale\n' > "$out/stale/coarse/pull.dat"
if run stale "$out/plain.nml"; then
    if [ -e "$out/stale/coarse/summary.txt" ] || [ -e "$out/stale/coarse/pull.dat" ]; then
        fail "stale: an earlier first pass's results were left in coarse/"
    else
        echo "ok   neck: an earlier run's first pass is removed by a run without it"
    fi
fi

# 7. a write that fails in the first pass (file-size limit): exit 3, and
# the run's summary.txt says write_failed, not running
(ulimit -f 8; "$bin" "$deck" -o "$out/full" > "$out/full.log" 2>&1)
status=$?
if ((status == 3)) && [ "$(value "$out/full/summary.txt" status)" = write_failed ] &&
    [ "$(value "$out/full/summary.txt" neck_refinement)" = first ]; then
    echo "ok   neck: a failed write in the first pass: exit 3, summary.txt says write_failed"
else
    fail "neck: a failed write in the first pass: exit $status, status $(value "$out/full/summary.txt" status)"
fi

# 8. no convergence in the first pass within the deck's pull (2 Newton
# iterations): exit 2, both summaries say no_convergence
sed -e 's/^&loading$/\&loading\n   max_iterations = 2/' "$deck" > "$out/noconv.nml"
"$bin" "$out/noconv.nml" -o "$out/noconv" > "$out/noconv.log" 2>&1
status=$?
if ((status == 2)) && [ "$(value "$out/noconv/summary.txt" status)" = no_convergence ] &&
    [ "$(value "$out/noconv/coarse/summary.txt" status)" = no_convergence ] &&
    [ "$(value "$out/noconv/summary.txt" neck_refinement)" = first ]; then
    echo "ok   neck: no convergence in the first pass: exit 2, both summaries say no_convergence"
else
    fail "neck: no convergence in the first pass: exit $status, status $(value "$out/noconv/summary.txt" status)"
fi
exit $((fails > 0))
