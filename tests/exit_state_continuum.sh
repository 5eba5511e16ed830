#!/usr/bin/env bash
# exit_state_continuum.sh -- the sheet leaving the bead against the CalculiX
# continuum (scripts/exit_state_check.sh, docs/validation.md "The sheet
# leaving the bead"), without CalculiX: the program reruns
# input/exit_fig9c_beadA_steel_free.nml (bead A, DQSK steel, free edge,
# pulled 36h, about 7 s) and its exit_state.dat is compared with the
# continuum's exit state kept in
# docs/validation/continuum/exit_fig9c_beadA_steel_free/exit_state.txt,
# at the same material point (the same reference x):
#   a) the material at the exit station started left of the first radius
#      (it has passed the whole bead)
#   b) thickness within 2%, equivalent plastic strain at the bottom and
#      top faces and at the middle within 10% (--check: exit status 0), the
#      middle's ratio that of the thickness log strain within 3% (the
#      middle's plastic strain is the membrane's)
#   c) the check can fail: the kept continuum with its thickness 4% larger,
#      or with its top face's strain 25% larger, gives exit status 1 and
#      says which
#   d) extract (scripts/exit_state.py) on a continuum.dat written by hand:
#      the integration points of a sheet turned by 10 degrees, numbered in
#      an order of their own, placed by their coordinates (rows bottom to
#      top, columns along the sheet), and the thickness read off the
#      face nodes
#   e) usage errors: no deck, --ccx and --continuum together (exit 2)
#   f) scripts/continuum_model.py --pull-step (the pull as a step of its
#      own) against the one-step model of the same run, and --pull-steps 3
#      (the pull in three steps with restart records) against --pull-step
#   g) bead B (input/exit_fig9d_beadB_steel_free.nml) against its kept
#      continuum exit state: the thickness and the faces within the
#      targets, the middle outside 10% (measured 15.2% low), held at 20%
#   h) bead B with the tools on the reference faces at the continuum's
#      contact stiffness (--also "contact_faces=reference penalty=0.37
#      contact_smoothing=0.001": a variant with three variables): every
#      target met; --also with a list of values is refused (exit 2)
# Usage: tests/exit_state_continuum.sh [binary]   (default: $DRAWBEAD, else bin/drawbead)
# Prints one line per check; exit status 0 if all pass, 1 if any fails,
# 2 if the test cannot run.
set -u

# shellcheck source=tests/lib.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib.bash" || exit 2
test_begin exit_state_continuum.sh "${1:-}"

deck=input/exit_fig9c_beadA_steel_free.nml
kept=docs/validation/continuum/exit_fig9c_beadA_steel_free/exit_state.txt

# a), b) the program against the kept continuum
scripts/exit_state_check.sh "$deck" -o "$tmp/run" --continuum "$kept" --bin "$prog" \
    >"$tmp/table.txt" 2>"$tmp/err.txt"
rc=$?
cat "$tmp/table.txt"
check "exit_state_check.sh with a kept continuum exit state: exit status 0 ($rc)" test "$rc" -eq 0
check "the material at the exit station has passed the whole bead" \
    grep -q '^# passed the whole bead: yes' "$tmp/run/program/exit_state.dat"
# The middle's strain is the membrane's, (2/sqrt 3) |ln(t/h)|: at a thickness
# strain of -0.18 the 2% of the thickness are 11% of it (docs/validation.md,
# "The sheet leaving the bead"): measured 5.0% low against the continuum's
# default mesh, whose sheet is 0.5% thinner than the program's (the
# thickness log strain 2.7% low).
python3 scripts/exit_state.py compare "$tmp/run/program" "$kept" --check >"$tmp/check.txt"
rc=$?
check "thickness within 2%, eqps at the faces and the middle within 10% (exit status $rc)" \
    test "$rc" -eq 0
# ratio ROW: the ratio column of the table's row ROW (its label, fixed width)
ratio() {
    awk -v row="$1" 'substr($0, 1, length(row)) == row { print $(NF - ($0 ~ /%/ ? 1 : 0)); exit }' "$tmp/check.txt"
}
rm_=$(ratio 'eqps, middle')
rt_=$(ratio 'thickness log strain')
check "the middle's eqps ratio ($rm_) is the thickness log strain's ($rt_) within 3%" \
    awk -v a="$rm_" -v b="$rt_" 'BEGIN { exit !(a != "" && b != "" && (a / b - 1) ^ 2 <= 0.03 ^ 2) }'
check "the table: thickness and the three eqps rows" \
    test "$(grep -cE '^(thickness t/h|eqps, (bottom face|middle|top face))' "$tmp/table.txt")" -eq 4

# c) the check can fail
python3 - "$kept" "$tmp" <<'EOF' || exit 2
import math, sys
kept, d = sys.argv[1], sys.argv[2]
lines = open(kept).read().splitlines()
thick, top = [], []
for line in lines:
    w = line.split()
    if w and w[0] == 'thick':
        thick.append('thick %s %s %.9e' % (w[1], w[2], float(w[3]) + math.log(1.04)))
    else:
        thick.append(line)
    if w and w[0] == 'eqps':
        top.append(' '.join(w[:-2] + ['%.9e' % (1.25 * float(v)) for v in w[-2:]]))
    else:
        top.append(line)
open(d + '/thick.txt', 'w').write('\n'.join(thick) + '\n')
open(d + '/top.txt', 'w').write('\n'.join(top) + '\n')
EOF
python3 scripts/exit_state.py compare "$tmp/run/program" "$tmp/thick.txt" --check >"$tmp/thick.out"
rc=$?
check "the continuum 4% thicker: exit status 1 ($rc), the thickness named" \
    bash -c "test $rc -eq 1 && grep -q '^# outside the targets: thickness$' '$tmp/thick.out'"
python3 scripts/exit_state.py compare "$tmp/run/program" "$tmp/top.txt" --check >"$tmp/top.out"
rc=$?
check "the continuum's top face 25% harder: exit status 1 ($rc), the top face named" \
    bash -c "test $rc -eq 1 && grep -q '^# outside the targets: eqps, top face' '$tmp/top.out'"

# d) extract on a continuum written by hand: 2L = 8 mm, h = 1 mm, 20 x 2
# CPE8R elements (0.4 mm along, 0.45 mm through once squeezed: shorter
# along the sheet than through it, so that their points' own scatter
# points across the sheet, as in the default continuum's square elements
# where it gives no direction), turned by 10 degrees about the origin; eqps = 0.1 + the
# reference z/h + 0.01 x the reference x (mm), the face nodes 0.9 mm apart
# (thickness log strain ln 0.9)
mkdir -p "$tmp/ccx"
python3 - "$tmp/ccx" <<'EOF' || exit 2
import json, math, os, sys
d = sys.argv[1]
h, half, nx, ny = 1.0, 4.0, 20, 2
c, s = math.cos(math.radians(10)), math.sin(math.radians(10))
turn = lambda x, y: (c * x - s * y, s * x + c * y)
ni = 2 * nx + 1
mid = [ny * ni + i + 1 for i in range(ni)]
top = [2 * ny * ni + i + 1 for i in range(ni)]
bot = [i + 1 for i in range(ni)]
X = {}
Y = {}
for j, ids in ((0, bot), (ny, mid), (2 * ny, top)):
    for i, n in enumerate(ids):
        X[n], Y[n] = -half + 2 * half * i / (2 * nx), -0.5 * h + h * j / (2 * ny)
json.dump({'deck': 'by hand', 'title': 'by hand', 'thickness': h, 'half_length': half,
           'nx': nx, 'ny': ny, 'per_h': 1, 'contact_slope': 1e5, 'pull_distance': 1.0,
           'node_x': {str(n): v for n, v in X.items()}, 'node_y': {str(n): v for n, v in Y.items()},
           'mid': mid, 'top': top, 'bottom': bot}, open(os.path.join(d, 'continuum_model.json'), 'w'))
g = 1 / math.sqrt(3)
out = [' displacements (vx,vy,vz) for set NSTRAIN and time  2.0000000E+00\n\n']
for n in mid + top + bot:
    # the current place: squeezed to 0.9 through the thickness, then turned
    x, y = turn(X[n], 0.9 * Y[n])
    out.append('%10d  %.9E  %.9E  0.000000E+00\n' % (n, x - X[n], y - Y[n]))
pe = [' equivalent plastic strain (elem, integ.pnt.,pe)for set SHEET and time  2.0000000E+00\n\n']
co = [' global coordinates (elem, integ.pnt.,x,y,z) for set EXITBAND and time  2.0000000E+00\n\n']
# a numbering of the points of our own: (+,+), (-,-), (+,-), (-,+), then the second layer
order = [(1, 1), (-1, -1), (1, -1), (-1, 1)]
for ej in range(ny):
    for ei in range(nx):
        e = ej * nx + ei + 1
        for k in range(8):
            sa, sb = order[k % 4]
            xr = -half + (ei + 0.5) * (2 * half / nx) + sa * g * half / nx
            zr = -0.5 + (ej + 0.5) * 0.5 + sb * 0.25 * g
            x, y = turn(xr, 0.9 * zr)
            pe.append('%10d%5d  %.6E\n' % (e, k + 1, 0.1 + zr + 0.01 * xr))
            co.append('%10d%5d  %.6E  %.6E  %.6E\n' % (e, k + 1, x, y, 0.5 if k < 4 else -0.5))
open(os.path.join(d, 'continuum.dat'), 'w').write(''.join(out + ['\n'] + pe + ['\n'] + co))
EOF
python3 scripts/exit_state.py extract "$tmp/ccx" "$tmp/hand.txt" 0 --band 1.5 >"$tmp/hand.err" 2>&1
rc=$?
check "extract on the hand-written continuum: exit status 0 ($rc)" test "$rc" -eq 0
check "its rows of points at the Gauss heights of the two element rows (bottom to top)" \
    python3 -c "
import math
zs = [float(v) for v in [l for l in open('$tmp/hand.txt') if l.startswith('# rows z/h')][0].split('=')[1].split()]
ref = sorted(-0.5 + (ej + 0.5) * 0.5 + sb * 0.25 / math.sqrt(3) for ej in (0, 1) for sb in (-1, 1))
raise SystemExit(0 if len(zs) == 4 and max(abs(a - b) for a, b in zip(zs, ref)) < 1e-8 else 1)"
check "each point's eqps at its reference place (0.1 + z/h + 0.01 x, to 1e-6)" \
    python3 -c "
zs = [float(v) for v in [l for l in open('$tmp/hand.txt') if l.startswith('# rows z/h')][0].split('=')[1].split()]
cols = [l.split()[1:] for l in open('$tmp/hand.txt') if l.startswith('eqps ')]
bad = [c for c in cols for z, v in zip(zs, c[1:]) if abs(float(v) - (0.1 + z + 0.01 * float(c[0]))) > 1e-6]
raise SystemExit(0 if len(cols) >= 4 and not bad else 1)"
check "the thickness read off the face nodes: ln 0.9 at every row" \
    python3 -c "
import math
t = [float(l.split()[3]) for l in open('$tmp/hand.txt') if l.startswith('thick ')]
raise SystemExit(0 if t and max(abs(v - math.log(0.9)) for v in t) < 1e-8 else 1)"

# e) usage errors
scripts/exit_state_check.sh >/dev/null 2>&1
check "no deck: exit 2" test $? -eq 2
scripts/exit_state_check.sh "$deck" --ccx "$tmp/ccx" --continuum "$kept" --bin "$prog" >/dev/null 2>&1
check "--ccx and --continuum together: exit 2" test $? -eq 2

# f) the pull as a step of its own (continuum_model.py --pull-step, which
# the long exit-state sheets need; docs/continuum-check.md, "Long sheets"):
# two *STATIC steps, the lock's to time 1 and the pull's, the amplitudes and
# the output times in total time, and nothing else changed; without it
# the one-step model
python3 scripts/continuum_model.py "$tmp/run/program/run.log" "$tmp/one" &&
    python3 scripts/continuum_model.py "$tmp/run/program/run.log" "$tmp/two" --pull-step
check "continuum_model.py with and without --pull-step: exit status 0 ($?)" test $? -eq 0
check "one step without --pull-step, no amplitude in total time" \
    bash -c "test \$(grep -c '^\*STEP' '$tmp/one/continuum.inp') -eq 1 && ! grep -q 'TOTAL TIME' '$tmp/one/continuum.inp'"
check "--pull-step: two steps, the lock's ending at time 1, ALOCK, APULL and the output times in total time" \
    bash -c "test \$(grep -c '^\*STEP' '$tmp/two/continuum.inp') -eq 2 &&
        test \$(grep -cE '^\*(AMPLITUDE, NAME=A(LOCK|PULL)|TIME POINTS, NAME=TP), TIME=TOTAL TIME$' '$tmp/two/continuum.inp') -eq 3 &&
        grep -A1 -m1 '^\*STATIC' '$tmp/two/continuum.inp' | grep -q '^0.01, 1, '"
check "--pull-step changes nothing else (the diff: the three cards, the first step's end, the second step)" \
    bash -c "test \$(diff '$tmp/one/continuum.inp' '$tmp/two/continuum.inp' | grep -c '^<') -eq 4"
# --pull-steps 3: the pull in three steps of a third each, a restart record
# asked for at the end of every step, each pull step as --pull-step's but
# for its time, nothing else changed; the json says so; 0 is refused
python3 scripts/continuum_model.py "$tmp/run/program/run.log" "$tmp/three" --pull-steps 3
check "--pull-steps 3: exit status 0 ($?)" test $? -eq 0
check "--pull-steps 3: four steps, *RESTART, WRITE once, in the first, three pull steps of time 1/3" \
    bash -c "test \$(grep -c '^\*STEP' '$tmp/three/continuum.inp') -eq 4 &&
        test \$(grep -c '^\*RESTART, WRITE, FREQUENCY=1$' '$tmp/three/continuum.inp') -eq 1 &&
        awk '/^\*RESTART/ { r = NR } /^\*END STEP/ && !e { e = NR } END { exit !(r && r == e - 1) }' '$tmp/three/continuum.inp' &&
        test \$(grep -A1 '^\*STATIC' '$tmp/three/continuum.inp' | grep -c '^0.01, 0.33333333333333331, ') -eq 3"
check "--pull-steps 3 differs from --pull-step by the restart request and the pull steps only" \
    bash -c "diff <(sed '/^\*RESTART/d' '$tmp/three/continuum.inp' | awk '/^\*STEP/ { n++ } n < 2') \
        <(awk '/^\*STEP/ { n++ } n < 2' '$tmp/two/continuum.inp') >/dev/null &&
        diff <(awk '/^\*STEP/ { n++ } n == 2' '$tmp/three/continuum.inp' | sed 's/^0.01, 0.33333333333333331, /0.01, 1., /') \
        <(awk '/^\*STEP/ { n++ } n == 2' '$tmp/two/continuum.inp') >/dev/null"
check "--pull-steps 3: continuum_model.json has pull_steps = 3" \
    python3 -c "import json, sys; sys.exit(json.load(open('$tmp/three/continuum_model.json')).get('pull_steps') != 3)"
python3 scripts/continuum_model.py "$tmp/run/program/run.log" "$tmp/zero" --pull-steps 0 2>/dev/null
check "--pull-steps 0: exit 2 ($?)" test $? -eq 2
python3 scripts/continuum_model.py "$tmp/run/program/run.log" "$tmp/one_step" --pull-steps 1
check "--pull-steps 1 is --pull-step (the same input)" cmp -s "$tmp/one_step/continuum.inp" "$tmp/two/continuum.inp"

# g) bead B (input/exit_fig9d_beadB_steel_free.nml, 140h pulled 48h, about
# 8 s) against its kept continuum exit state (the default mesh, 4 per h and
# slope 1e5, the pull in 8 steps, resumed after step 6): the thickness
# within 2% and the faces' plastic strain within 10%, the targets; the
# middle's measured 15.2% low (the continuum's sheet is thinner: its
# thickness log strain -0.097 against the program's -0.088;
# docs/validation.md "The sheet leaving the bead"), held here at 20%, and
# named outside 10%.  The station's material started within the span of
# the female's entry corner (x/h -23.0 to -18.3), which the sheet touches
# at the end of the pull: it has passed every radius but part of the first
# (passed the whole bead: no)
deck_b=input/exit_fig9d_beadB_steel_free.nml
kept_b=docs/validation/continuum/exit_fig9d_beadB_steel_free/exit_state.txt
scripts/exit_state_check.sh "$deck_b" -o "$tmp/run_b" --continuum "$kept_b" --bin "$prog" \
    --also "contact_faces=reference penalty=0.37 contact_smoothing=0.001" >"$tmp/table_b.txt" 2>"$tmp/err_b.txt"
rc=$?
check "bead B: exit_state_check.sh with its kept continuum exit state: exit status 0 ($rc)" test "$rc" -eq 0
check "bead B: the exit station's material started within the female's entry corner (passed the whole bead: no)" \
    grep -q '^# passed the whole bead: no' "$tmp/run_b/program/exit_state.dat"
python3 scripts/exit_state.py compare "$tmp/run_b/program" "$kept_b" --check --tol-middle 0.20 \
    >"$tmp/check_b.txt"
rc=$?
check "bead B: thickness within 2%, the faces' eqps within 10%, the middle's within 20% (exit status $rc)" \
    test "$rc" -eq 0
python3 scripts/exit_state.py compare "$tmp/run_b/program" "$kept_b" --check >"$tmp/check_b10.txt"
rc=$?
check "bead B: the middle outside 10% (the target missed, as measured): exit status 1 ($rc), named" \
    bash -c "test $rc -eq 1 && grep -q '^# outside the targets: eqps, middle (z = 0)$' \
        '$tmp/check_b10.txt'"

# h) bead B with the tools on the reference faces at the continuum's
# contact stiffness (its slope 1e5 MPa/mm is penalty = 0.37 E/h for this
# steel; contact_smoothing = 0.001h, without which the first increment of
# locking does not converge at that stiffness), the variant of g)'s run
# (--also with three variables): every target met (measured: thickness
# 0.991, faces 0.938 and 1.068, middle 1.097; on the current faces the top
# face is then 17% high: docs/validation.md "The sheet leaving the bead")
check "bead B at the continuum's contact stiffness: the variant's deck has the three variables" \
    bash -c "grep -q '^ *penalty *= *0.37' '$tmp/run_b/deck_also_1.nml' &&
        grep -q '^ *contact_smoothing *= *0.001' '$tmp/run_b/deck_also_1.nml' &&
        grep -q \"^ *contact_faces *= *'reference'\" '$tmp/run_b/deck_also_1.nml'"
python3 scripts/exit_state.py compare "$tmp/run_b/program_also_1" "$kept_b" --check >"$tmp/check_b37.txt"
rc=$?
check "bead B at the continuum's contact stiffness: thickness within 2%, eqps at the faces and the middle within 10% (exit status $rc)" \
    test "$rc" -eq 0
# --also with a list of values (a sweep, not a variant) is refused
scripts/exit_state_check.sh "$deck_b" -o "$tmp/run_bad" --continuum "$kept_b" --bin "$prog" \
    --also "penalty=0.37,0.2" >"$tmp/bad.txt" 2>&1
rc=$?
check "--also with a list of values: exit status 2 ($rc), named" \
    bash -c "test $rc -eq 2 && grep -q \"needs VAR=VALUE, or several separated by spaces, not 'penalty=0.37,0.2'\" '$tmp/bad.txt'"

echo "exit_state_continuum.sh: $((checks - failures)) of $checks checks passed"
((failures == 0))
