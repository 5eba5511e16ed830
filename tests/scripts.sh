#!/usr/bin/env bash
# scripts.sh -- tests of the batch scripts: scripts/run_paper.sh (with the
# gnuplot scripts scripts/plot_*.gp), scripts/sweep.sh (local and --slurm)
# and scripts/bench.sh (scripts/bead_curves.sh: tests/bead_cards.sh).
#
# Usage: tests/scripts.sh [binary]   (default: $DRAWBEAD, else bin/drawbead)
#
# Runs from the repository root (the parent of this script's directory) on
# small decks written to a temporary directory (about 10 s in all):
#   a) run_paper.sh on reduced copies of fig6 (bead B, 40 elements, pulled
#      1h) and fig7c (40 elements, lock only): exit 0, a run.log and an
#      exit_status per deck, the table with both rows, and (if gnuplot is
#      installed) fig6.png, fig7.png, fig8.png and the bead B shapes as
#      PNG files
#   b) run_paper.sh with a deck the program rejects: non-zero exit, the
#      row says bad_input
#   c) sweep.sh on a 2x2 grid of a 10-element strip: four decks holding
#      the right values (also in the program's resolved input), a
#      four-row table; a sweep with friction=-1 lists that case as
#      bad_input with the program's message, and exits 1; a variable the
#      base deck does not set (snapshot_every, from the program's
#      --list-variables) is added to its group and read by the program; a
#      sweep whose runs tear exits 0, its rows torn, no failure counted;
#      SIGTERM to a sweep stops its runs (exit 4 each, none left going)
#      and writes the table of what finished, marked interrupted (exit 143)
#   d) sweep.sh --slurm: the array range matches the deck count, the
#      script passes bash -n, one task run by hand gives that deck's
#      summary, and --collect builds the table (not_run for the others)
#   f) shellcheck (if installed) finds nothing in the batch scripts, the
#      test scripts and scripts/lib.sh
#   g) bench.sh on a 20-element strip with 1 and 2 threads and a scaling
#      table (10, 20 elements): a row per thread count with the counters
#      from summary.txt and the per-assembly and per-point times, total
#      rows, the scaling rows; --markdown gives the tables as markdown; a
#      bad --threads value is a usage error (exit 2)
# Prints one line per check; exit status 0 if all pass, 1 if any fails,
# 2 if the test cannot run.
set -u

# shellcheck source=tests/lib.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib.bash" || exit 2
test_begin scripts.sh "${1:-}"

# is_png FILE: FILE exists and starts with the PNG signature
is_png() {
    [[ -s $1 ]] && [[ $(head -c 8 "$1" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]]
}

# data_rows FILE: the number of lines not starting with '#'
data_rows() {
    grep -cv '^#' "$1" 2>/dev/null
}

have_gnuplot=0
if command -v gnuplot >/dev/null 2>&1; then
    have_gnuplot=1
fi

# ---------------------------------------------------------------------------
# The small decks
# ---------------------------------------------------------------------------
mkdir -p "$tmp/paper" "$tmp/bad" || exit 2
# bead B on a 40-element sheet; each deck closes &tools itself
beadb_sheet_tools="&sheet
   thickness = 0.762
   length = 45.72
   n_elements = 40
/
&tools
   bead = 'rectangular'
   r1 = 3.55092, r2 = 3.55092, b1 = 9.906, b2 = 13.95984
   h1 = 0.0, h2 = 4.31292"
cat >"$tmp/paper/fig6_beadB_steel.nml" <<EOF
&control
   title = 'test: bead B, steel, clamped, 40 elements, pulled 1h'
/
$beadb_sheet_tools
   friction = 0.1
/
&loading
   pull_distance = 0.762
/
EOF
cat >"$tmp/paper/fig7c_beadB_steel_mu0.nml" <<EOF
&control
   title = 'test: bead B, steel, clamped, 40 elements, lock only'
/
$beadb_sheet_tools
/
&loading
   pull_distance = 0.0
/
EOF
cat >"$tmp/bad/fig5a_beadA_steel.nml" <<'EOF'
&tools
   bead = 'rectangular'
   friction = -1.0
/
EOF
cat >"$tmp/strip.nml" <<'EOF'
&control
   title = 'test: strip, 10 elements'
/
&sheet
   thickness = 0.762
   length = 38.1
   n_elements = 10
/
&tools
   bead = 'none'
/
&loading
   pull_distance = 0.762
   initial_increment = 0.0762
   max_increment = 0.762
/
EOF

# ---------------------------------------------------------------------------
# a) run_paper.sh on two small decks
# ---------------------------------------------------------------------------
echo "== a) run_paper.sh"
paper_opts=()
((have_gnuplot)) || paper_opts=(--no-figures)
scripts/run_paper.sh --bin "$prog" -j 2 "${paper_opts[@]}" -o "$tmp/out" \
    --decks "$tmp/paper/fig6_beadB_steel.nml $tmp/paper/fig7c_beadB_steel_mu0.nml" \
    >"$tmp/a.out" 2>"$tmp/a.err"
rc=$?
check "run_paper.sh exits 0 on good decks (got $rc)" test "$rc" -eq 0
for name in fig6_beadB_steel fig7c_beadB_steel_mu0; do
    check "$name: run.log kept" test -s "$tmp/out/$name/run.log"
    check "$name: exit_status 0" grep -qx 0 "$tmp/out/$name/exit_status"
    check "$name: summary.txt written" test -s "$tmp/out/$name/summary.txt"
    check "$name: a row of the table" grep -q "^$name .* completed\$" "$tmp/out/paper_table.txt"
done
check "the table has a header and two rows" test "$(data_rows "$tmp/out/paper_table.txt")" -eq 2
check "the table is printed" grep -q '^# deck .*cpu_s .*status' "$tmp/a.out"
if ((have_gnuplot)); then
    for png in fig6 fig7 fig8 shape_beadB_lock shape_beadB_pull; do
        check "figure $png.png drawn" is_png "$tmp/out/figures/$png.png"
    done
    check "no figure for decks that did not run (fig9)" test ! -e "$tmp/out/figures/fig9.png"
    # each force figure gives E h in N/mm, from the run's own columns
    # (issue 28: forces were only in N/(E h)); the strain figure's legend
    # is inside the frame (it sat below the x label)
    d7=$tmp/out/fig7c_beadB_steel_mu0
    eh=$(awk '!/^#/ && NF && $2 != 0 { printf "%.0f", $3 / $2; exit }' "$d7/lock.dat")
    gnuplot -c scripts/plot_lock.gp "$d7/lock.dat::bead B" "$tmp/fig7.svg" 2>/dev/null
    check "plot_lock.gp: the legend gives E h = $eh N/mm" grep -q "bead B  (E h = $eh N/mm)" "$tmp/fig7.svg"
    gnuplot -c scripts/plot_pull.gp "$tmp/out/fig6_beadB_steel/pull.dat::bead B" "$tmp/fig8.svg" 2>/dev/null
    check "plot_pull.gp: the legend gives E h = $eh N/mm" grep -q "bead B  (E h = $eh N/mm)" "$tmp/fig8.svg"
    check "plot_strain.gp: the legend inside the frame" grep -q "^pkey = 'inside " scripts/plot_strain.gp
    check "run_paper.sh: Fig. 7's title names its mu = 0.1 curve" \
        grep -q "Fig. 7  Punch force vs. lock depth, clamped edge, μ = 0 (dashed black: μ = 0.1)" scripts/run_paper.sh
else
    echo "skip the figures: gnuplot is not installed"
fi
if ((failures > 0)); then
    echo "--- run_paper.sh stderr:"
    cat "$tmp/a.err"
fi

# ---------------------------------------------------------------------------
# b) a failing run makes run_paper.sh fail
# ---------------------------------------------------------------------------
echo "== b) run_paper.sh with a bad deck"
scripts/run_paper.sh --bin "$prog" -o "$tmp/outbad" --decks "$tmp/bad/fig5a_beadA_steel.nml" \
    >"$tmp/b.out" 2>"$tmp/b.err"
rc=$?
check "run_paper.sh exits non-zero when a run fails (got $rc)" test "$rc" -ne 0
check "the failed run's row says bad_input" grep -q '^fig5a_beadA_steel .*bad_input$' "$tmp/b.out"
check "the failed run's log holds the error" grep -q 'variable friction' "$tmp/outbad/fig5a_beadA_steel/run.log"

# ---------------------------------------------------------------------------
# c) sweep.sh on a 2x2 grid, and a bad value
# ---------------------------------------------------------------------------
echo "== c) sweep.sh"
scripts/sweep.sh --bin "$prog" -j 2 -o "$tmp/sweep" "$tmp/strip.nml" \
    n_elements=10,12 pull_distance=0.381,0.762 >"$tmp/c.out" 2>"$tmp/c.err"
rc=$?
check "sweep.sh exits 0 (got $rc)" test "$rc" -eq 0
ndecks=$(find "$tmp/sweep/decks" -name 'case_*.nml' | wc -l)
check "four decks written (got $ndecks)" test "$ndecks" -eq 4
# case k: n_elements varies slowest
expect_n=(10 10 12 12)
expect_p=(0.381 0.762 0.381 0.762)
for k in 0 1 2 3; do
    deck=$tmp/sweep/decks/case_000$k.nml
    log=$tmp/sweep/runs/case_000$k/run.log
    check "case_000$k deck: n_elements = ${expect_n[k]}" grep -q "^ *n_elements = ${expect_n[k]}\$" "$deck"
    check "case_000$k deck: pull_distance = ${expect_p[k]}" grep -q "^ *pull_distance = ${expect_p[k]}\$" "$deck"
    check "case_000$k: the program read N_ELEMENTS=${expect_n[k]}" grep -q "N_ELEMENTS=${expect_n[k]} *,\$" "$log"
    check "case_000$k: a row with its values" \
        grep -Eq "^case_000$k +${expect_n[k]} +${expect_p[k]} .* (completed|localized)\$" "$tmp/sweep/table.txt"
done
check "the table has four rows" test "$(data_rows "$tmp/sweep/table.txt")" -eq 4
check "the table header names the columns" grep -Eq '^# case +n_elements +pull_distance +steady_force_over_Eh +peak_force_over_Eh +final_lift_over_Eh +delta_cr_over_h +max_thinning +status$' "$tmp/sweep/table.txt"
check "the progress line" grep -q '^done 4/4, 0 failed, eta' "$tmp/c.err"
check "the table is printed" cmp -s "$tmp/c.out" "$tmp/sweep/table.txt"

scripts/sweep.sh --bin "$prog" -o "$tmp/sweepbad" "$tmp/strip.nml" friction=0.1,-1 \
    >"$tmp/c2.out" 2>"$tmp/c2.err"
rc=$?
check "sweep.sh exits 1 when a run fails (got $rc)" test "$rc" -eq 1
check "the bad value is a row with status bad_input" grep -Eq '^case_0001 +-1 .* bad_input$' "$tmp/sweepbad/table.txt"
check "the good value still runs" grep -Eq '^case_0000 +0\.1 .* (completed|localized)$' "$tmp/sweepbad/table.txt"
check "the error message is listed" grep -q '^# case_0001: bad_input: .*variable friction' "$tmp/sweepbad/table.txt"
check "the progress line counts the failure" grep -q '^done 2/2, 1 failed' "$tmp/c2.err"

scripts/sweep.sh --bin "$prog" -o "$tmp/sweepunknown" "$tmp/strip.nml" no_such_variable=1 \
    >/dev/null 2>"$tmp/c3.err"
rc=$?
check "an unknown variable is a usage error (exit 2, got $rc)" test "$rc" -eq 2
check "... naming it" grep -q "unknown variable 'no_such_variable'" "$tmp/c3.err"

# the variables come from the program (--list-variables): one the base deck
# does not set is added to its group
scripts/sweep.sh --bin "$prog" -o "$tmp/sweepnew" "$tmp/strip.nml" snapshot_every=0.1 \
    >/dev/null 2>"$tmp/c4.err"
rc=$?
check "a variable the base deck does not set is swept (snapshot_every; exit 0, got $rc)" test "$rc" -eq 0
check "... added to its group &control" \
    grep -Pzq '&control\n[^/]*\n   snapshot_every = 0\.1\n/' "$tmp/sweepnew/decks/case_0000.nml"
check "... and read by the program (SNAPSHOT_EVERY=0.1)" \
    grep -q '^ *SNAPSHOT_EVERY= *0\.1000' "$tmp/sweepnew/runs/case_0000/run.log"

# tearing is a result, not a failure (issue 28, item 9: a torn run was
# counted failed in the table, and the sweep exited 1)
scripts/sweep.sh --bin "$prog" -j 2 -o "$tmp/sweeptorn" input/strip_tension.nml n_elements=20,30 \
    >"$tmp/c5.out" 2>"$tmp/c5.err"
rc=$?
check "a sweep whose runs tear exits 0 (got $rc)" test "$rc" -eq 0
check "... its rows say torn" test "$(grep -Ec '^case_000[01] .* torn$' "$tmp/sweeptorn/table.txt")" -eq 2
check "... and the table counts no failure" grep -q '^# drawbead sweep: 2 cases, 0 failed, 0 not run' "$tmp/sweeptorn/table.txt"

# SIGTERM stops the runs and writes the table of what finished, marked
# interrupted (issue 28, item 10: sweep.sh exited 143, its runs went on,
# no table); case_0000 is quick, the other two run for minutes
printf '&sheet n_elements = 2000 /\n&loading pull_distance = 0.5 initial_increment = 0.001 max_increment = 0.001 /\n' \
    >"$tmp/slow.nml"
scripts/sweep.sh --bin "$prog" -j 2 -o "$tmp/sweepint" "$tmp/slow.nml" \
    pull_distance=0.001,0.4,0.5 >"$tmp/c6.out" 2>"$tmp/c6.err" &
sweep_pid=$!
for _ in $(seq 300); do
    [[ -s $tmp/sweepint/runs/case_0000/exit_status ]] &&
        grep -qs 'increments = *[1-9]' "$tmp/sweepint/runs/case_0001/summary.txt" &&
        grep -qs 'increments = *[1-9]' "$tmp/sweepint/runs/case_0002/summary.txt" && break
    sleep 0.1
done
kill -TERM "$sweep_pid"
wait "$sweep_pid"
rc=$?
check "SIGTERM: sweep.sh exits 143 (got $rc)" test "$rc" -eq 143
check "... no run of the sweep is left going" test -z "$(pgrep -f -- "--output $tmp/sweepint/runs")"
check "... the stopped runs exited 4 (interrupted)" \
    test "$(cat "$tmp/sweepint/runs/case_0001/exit_status" "$tmp/sweepint/runs/case_0002/exit_status")" = $'4\n4'
check "... the table is written, marked interrupted" \
    grep -q '^# INTERRUPTED: SIGTERM stopped the sweep: 1 of 3 cases finished, 2 stopped, 0 not run' "$tmp/sweepint/table.txt"
check "... with the finished run's row" grep -Eq '^case_0000 +0\.001 .* completed$' "$tmp/sweepint/table.txt"
check "... and the stopped runs' rows" test "$(grep -Ec '^case_000[12] .* interrupted$' "$tmp/sweepint/table.txt")" -eq 2

# ---------------------------------------------------------------------------
# d) sweep.sh --slurm
# ---------------------------------------------------------------------------
echo "== d) sweep.sh --slurm"
scripts/sweep.sh --bin "$prog" --slurm -o "$tmp/slurm" "$tmp/strip.nml" \
    n_elements=10,12,14 >"$tmp/d.out" 2>"$tmp/d.err"
rc=$?
check "sweep.sh --slurm exits 0 (got $rc)" test "$rc" -eq 0
script=$tmp/slurm/sweep.slurm
check "sweep.slurm written" test -s "$script"
check "three decks listed" test "$(wc -l <"$tmp/slurm/decks.txt")" -eq 3
check "#SBATCH --array=0-2 matches the deck count" grep -qx '#SBATCH --array=0-2' "$script"
check "sweep.slurm passes bash -n" bash -n "$script"
check "nothing was run locally" test ! -e "$tmp/slurm/runs"
SLURM_ARRAY_TASK_ID=1 bash "$script" >/dev/null 2>&1
rc=$?
check "task 1 run by hand exits 0 (got $rc)" test "$rc" -eq 0
check "task 1 wrote case_0001's summary" grep -q '^status = ' "$tmp/slurm/runs/case_0001/summary.txt"
check "task 1 ran case_0001's deck (N_ELEMENTS=12)" grep -q 'N_ELEMENTS=12 *,$' "$tmp/slurm/runs/case_0001/run.log"
check "task 0 did not run" test ! -e "$tmp/slurm/runs/case_0000"
scripts/sweep.sh --collect "$tmp/slurm" >"$tmp/d2.out" 2>&1
rc=$?
check "--collect exits 1 while tasks are missing (got $rc)" test "$rc" -eq 1
check "--collect: case_0001 done" grep -Eq '^case_0001 +12 .* (completed|localized)$' "$tmp/slurm/table.txt"
check "--collect: case_0000 not_run" grep -Eq '^case_0000 +10 .* not_run$' "$tmp/slurm/table.txt"
SLURM_ARRAY_TASK_ID=0 bash "$script" >/dev/null 2>&1
SLURM_ARRAY_TASK_ID=2 bash "$script" >/dev/null 2>&1
scripts/sweep.sh --collect "$tmp/slurm" >/dev/null 2>&1
rc=$?
check "--collect exits 0 once every task ran (got $rc)" test "$rc" -eq 0
check "--collect: three rows" test "$(data_rows "$tmp/slurm/table.txt")" -eq 3

# ---------------------------------------------------------------------------
# f) shellcheck
# ---------------------------------------------------------------------------
if command -v shellcheck >/dev/null 2>&1; then
    echo "== f) shellcheck"
    check "shellcheck: every script of scripts/, tests/ (with its lib.bash) and tests/regression/" shellcheck scripts/*.sh tests/*.sh tests/lib.bash tests/regression/*.sh
fi

# ---------------------------------------------------------------------------
# g) bench.sh
# ---------------------------------------------------------------------------
echo "== g) bench.sh"
# (the awk and bash programs below are meant literally: SC2016)
strip=tests/decks/strip_tension.nml
scripts/bench.sh --bin "$prog" -n 2 --threads 1,2 --scaling "$strip" --elements 10,20 "$strip" \
    >"$tmp/g.out" 2>"$tmp/g.err"
rc=$?
check "bench.sh exits 0 (got $rc)" test "$rc" -eq 0
asm=$(awk -F' = ' '$1 == "assemblies" { print $2 }' "$tmp/out/fig6_beadB_steel/summary.txt")
# shellcheck disable=SC2016
check "summary.txt has assemblies, at least one per iteration" \
    awk -v a="$asm" -F' = ' '$1 == "newton_iterations" { ok = (a ~ /^[0-9]+$/ && a + 0 >= $2 + 0) } END { exit !ok }' \
    "$tmp/out/fig6_beadB_steel/summary.txt"
for n in 1 2; do
    # deck threads median min max cpu increments iterations assemblies cutbacks us/asm ns/pt status
    # shellcheck disable=SC2016
    check "bench.sh: a row for $n thread(s) with counters and per-unit times" \
        awk -v n="$n" '$1 == "strip_tension" && $2 == n && $9 ~ /^[0-9]+$/ && $9 + 0 >= $8 + 0 &&
            $11 ~ /^[0-9]+$/ && $12 ~ /^[0-9.]+$/ && $13 == "localized" { found = 1 } END { exit !found }' "$tmp/g.out"
    check "bench.sh: a total row for $n thread(s)" grep -q "^total  *$n " "$tmp/g.out"
    for nel in 10 20; do
        # shellcheck disable=SC2016
        check "bench.sh: a scaling row for $nel elements, $n thread(s)" \
            awk -v n="$n" -v e="$nel" '$1 == e && $2 == n && $7 ~ /^[0-9.]+$/ && $8 ~ /^[0-9.]+$/ { found = 1 } END { exit !found }' "$tmp/g.out"
    done
done
scripts/bench.sh --bin "$prog" -n 1 --threads 2 --no-scaling --markdown "$strip" >"$tmp/g2.out" 2>>"$tmp/g.err"
# shellcheck disable=SC2016
check "bench.sh --markdown: a markdown row, no scaling table" \
    bash -c 'grep -q "^| strip_tension | 2 | " "$1" && ! grep -q "^| elements " "$1"' _ "$tmp/g2.out"
scripts/bench.sh --bin "$prog" --threads 1,x "$strip" >/dev/null 2>&1
rc=$?
check "bench.sh --threads 1,x is a usage error (exit 2, got $rc)" test "$rc" -eq 2
if ((failures > 0)); then
    echo "--- bench.sh stderr:"
    cat "$tmp/g.err"
fi

echo "scripts.sh: $checks checks, $failures failed"
((failures == 0))
