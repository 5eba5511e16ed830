#!/bin/bash
# tests/exit_state.sh -- the state of the sheet leaving the bead
# (docs/theory.md §9.1): a free-edge bead A deck pulled 4h writes
# exit_state.dat and exit_state.k; the cards, read back in LS-DYNA's
# fixed 10-character fields, carry the table's numbers (T, SIGXX = tau11,
# SIGYY = tau33, SIGZZ = tau22, EPS = the plastic strain) to their five
# significant digits; NTHICK is the table's row count; the station lies
# 3h past the exit of the last radius; the thickness of the table is the
# strain file's at that station.  A deck without tools, or a run that
# tears while the bead closes (it never pulls), writes neither.
#
# Usage: tests/exit_state.sh [path/to/drawbead]   (run from anywhere)
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2
bin=${1:-bin/drawbead}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/free.nml" <<'NML'
&control title = 'exit state test' /
&sheet n_elements = 60, left_edge = 'free' /
&tools bead = 'rectangular', friction = 0.1 /
&loading pull_distance = 3.048 /
NML
if ! "$bin" "$work/free.nml" -o "$work/free" >"$work/free.log" 2>&1; then
    echo "FAIL the free-edge run failed"
    tail -5 "$work/free.log"
    exit 1
fi
python3 - "$work/free" <<'PY'
import sys
d = sys.argv[1]
bad = 0
def check(what, ok):
    global bad
    print(('ok   ' if ok else 'FAIL ') + what)
    bad += not ok
table = [list(map(float, l.split())) for l in open(d + '/exit_state.dat') if not l.startswith('#')]
head = [l for l in open(d + '/exit_state.dat') if l.startswith('#')]
check('exit_state.dat: 21 thickness points (the deck\'s thickness_points)', len(table) == 21)
lines = open(d + '/exit_state.k').read().split('\n')
i = lines.index('*INITIAL_STRESS_SHELL_SET')
cards = [l for l in lines[i + 1:] if l and not l.startswith('$')]
f = lambda l, k: l[10 * k:10 * k + 10]
c1 = cards[0]
check('card 1: SID &SHELLSET, NPLANE 1, NTHICK 21, NHISV NTENSR LARGE NTHINT NTHHSV 0',
      f(c1, 0).strip() == '&SHELLSET' and int(f(c1, 1)) == 1 and int(f(c1, 2)) == len(table)
      and all(int(f(c1, k)) == 0 for k in range(3, 8)))
check('*PARAMETER SHELLSET, an integer placeholder', 'I SHELLSET         0' in lines)
rows = cards[1:]
check('one stress card per thickness point', len(rows) == len(table))
scale = max(abs(r[4]) for r in table)
worst = 0.0
for r, c in zip(table, rows):
    got = [float(f(c, k)) for k in range(8)]
    want = [r[2], r[4], r[6], r[5], 0.0, 0.0, 0.0, max(r[3], 0.0)]
    for k, (g, w) in enumerate(zip(got, want)):
        ref = scale if k in (1, 2, 3) else max(abs(w), 1.0)
        worst = max(worst, abs(g - w) / ref)
# five significant digits: 5e-5 of the value (1e-4 with the rounding of T near 1)
check('the cards carry the table (largest relative difference %.1e <= 1e-4)' % worst, worst <= 1e-4)
check('T from -1 (bottom) to 1 (top)', abs(table[0][2] + 1) < 1e-12 and abs(table[-1][2] - 1) < 1e-12)
check('plastic strain at the faces (the sheet bent and unbent through the bead)',
      table[0][3] > 0.01 and table[-1][3] > 0.01)
# the station and its thickness against strain_pull.dat (column 2 x/h,
# column 8 the mid-surface thickness strain)
st = [l for l in head if l.startswith('# station:')][0]
x = float(st.split('x/h = ')[1].split(',')[0])
x_exit = float(st.split('(x/h = ')[1].split(')')[0])
check('the station 3h past the exit of the last radius (x/h %.3f, exit %.3f)' % (x, x_exit),
      abs(x - x_exit - 3.0) < 1.0)
strain = [list(map(float, l.split())) for l in open(d + '/strain_pull.dat') if not l.startswith('#')]
row = min(strain, key=lambda r: abs(r[1] - x))
th = [l for l in head if l.startswith('# thickness/h')][0]
e22 = float(th.split('thickness log strain = ')[1])
check('its thickness strain is strain_pull.dat\'s at that station (%.6g, %.6g)' % (e22, row[7]),
      abs(e22 - row[7]) <= 1e-8)
sys.exit(1 if bad else 0)
PY
rc=$?
"$bin" input/strip_tension.nml -o "$work/strip" >/dev/null 2>&1
if [[ -e $work/strip/exit_state.dat || -e $work/strip/exit_state.k ]]; then
    echo "FAIL a deck without tools wrote an exit state"
    rc=1
else
    echo "ok   no tools: no exit state"
fi
# a run that tears while the bead closes never pulls: no exit state
"$bin" tests/regression/decks/lock_tear_hss.nml -o "$work/lock_tear" >/dev/null 2>&1
if grep -q '^tearing_phase = lock' "$work/lock_tear/summary.txt" && [[ ! -e $work/lock_tear/exit_state.dat ]]; then
    echo "ok   torn while locking: no pull, no exit state"
else
    echo "FAIL a run torn while locking wrote an exit state (or did not tear while locking)"
    rc=1
fi
exit $rc
