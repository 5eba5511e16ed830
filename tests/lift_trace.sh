#!/usr/bin/env bash
# lift_trace.sh -- test of scripts/lift_trace.sh and scripts/lift_trace.py
# (the lift traced tool by tool, docs/validation.md "The lift force").
#
# Usage: tests/lift_trace.sh [binary]   (default: $DRAWBEAD, else bin/drawbead)
#
# Without CalculiX (a few seconds): the program on a small frictionless
# copy of the bead A deck (40 elements, pulled 0.6h), against a continuum
# run written by hand (--ccx): a continuum.inp with four tool nodes, a
# continuum_model.json and a continuum.dat with the totals, the per-node
# reactions of the tools and the mid-surface displacements at two times.
#   a) the script runs the program with a snapshot at every increment and
#      prints the table at 0.5h and at the largest restraining force
#   b) the program's side: with mu = 0 the friction rows (each tool's
#      total less its rebuilt normal forces) are below 0.5% of the punch
#      force: the normal forces rebuilt from the contact pressures of
#      snapshots.dat (Gauss weights, face stretch, tool normals) add up
#      to pull.dat's F and lift
#   c) the continuum's side: each node given to its tool piece (entry
#      radius, exit binder, crest, exit corner), its reaction split along
#      the chain into normal and friction parts, interpolated linearly
#      between the two times, the totals F and lift, the edges' vertical
#      reactions and the steepest slopes of the mid-surface (45 and 30
#      degrees) as written by hand
#   d) usage errors: no deck, a --ccx folder without a run (exit 2)
# Prints one line per check; exit status 0 if all pass, 1 if any fails,
# 2 if the test cannot run.
set -u

# shellcheck source=tests/lib.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib.bash" || exit 2
test_begin lift_trace.sh "${1:-}"

# the deck: bead A steel, clamped, mu = 0, 40 elements, pulled 0.6h, its
# increments at most 0.01 mm: a station's pressure is per unit area of its
# face at the start of the increment (theory §12.1: the face stretch
# lagged), the rebuild takes the face stretch of the snapshot, its end, so
# the rebuilt forces differ by the face's stretch over one increment (0.5%
# of F on the pull's own increments with the tools on the current faces,
# 0.07% on these)
sed -e 's/n_elements = 80/n_elements = 40/' -e 's/pull_distance = 2.286/pull_distance = 0.4572/' \
    -e 's/^&loading$/\&loading\n   max_increment = 0.01/' input/cc_beadA_steel_mu0.nml >"$tmp/small.nml"

# the continuum written by hand (h = 0.762 mm; bead A: r1 = r2 = 3.55092,
# b1 = 3.16992, b2 = 6.72846): four tool nodes on the physical surfaces
# (the centreline chains offset by h/2 toward the tools), the reactions at
# times 1.1 and 1.3 of a continuum pulled 3h (delta/h 0.3 and 0.9)
mkdir -p "$tmp/ccx"
python3 - "$tmp/ccx" <<'EOF' || exit 2
import json, math, os, sys
d = sys.argv[1]
h, r, b1, b2 = 0.762, 3.55092, 3.16992, 6.72846
xo = b2 + r
c45 = math.sqrt(0.5)
# upper entry radius at -45 deg about (-xo, r); lower exit corner at 45 deg about (b1, -r)
up_arc = (-xo + (r - h / 2) * c45, r - (r - h / 2) * c45)
lo_arc = (b1 + (r - h / 2) * c45, -r + (r - h / 2) * c45)
nodes = {9001: up_arc, 9002: (20 * h, h / 2), 9101: (0.0, -h / 2), 9102: lo_arc}
with open(os.path.join(d, 'continuum.inp'), 'w') as f:
    f.write('** by hand\n*NODE, NSET=NALL\n')
    for n, (x, y) in nodes.items():
        f.write('%d, %.12g, %.12g\n' % (n, x, y))
    f.write('*NSET, NSET=NUPPER\n9001, 9002\n*NSET, NSET=NLOWER\n9101, 9102\n')
mid = [1, 2, 3, 4]
pts = [(-3 * h, 0.0), (-2 * h, h), (2 * h, h), (3 * h, h - h * math.tan(math.radians(30)))]
json.dump({'thickness': h, 'pull_distance': 3 * h, 'bead_half_width': xo + 0.0,
           'mid': mid, 'node_x': {str(n): p[0] for n, p in zip(mid, pts)},
           'node_y': {str(n): p[1] for n, p in zip(mid, pts)}},
          open(os.path.join(d, 'continuum_model.json'), 'w'))
out = []
for t, k in ((1.1, 1.0), (1.3, 1.3)):
    # entry radius: normal 100 k away from the centre, friction 10 k against +t
    fn, ff = 100 * k, 10 * k
    f9001 = (fn * c45 - ff * c45, -fn * c45 - ff * c45)
    f9002 = (-0.5, -5.0)
    f9101 = (0.0, 80.0)
    nl = 50 if t < 1.2 else 60
    f9102 = (nl * c45, nl * c45)
    forces = {9001: f9001, 9002: f9002, 9101: f9101, 9102: f9102}
    tot = {'NRIGHT': (100 if t < 1.2 else 120, -1.0 if t < 1.2 else -1.2), 'NLEFT': (-50, -0.1),
           'NUPPER': tuple(sum(forces[n][i] for n in (9001, 9002)) for i in (0, 1)),
           'NLOWER': tuple(sum(forces[n][i] for n in (9101, 9102)) for i in (0, 1))}
    for s in ('NRIGHT', 'NLEFT', 'NUPPER', 'NLOWER'):
        out.append(' total force (fx,fy,fz) for set %s and time  %.7E\n\n  %.6E  %.6E  0.000000E+00\n\n'
                   % (s, t, tot[s][0], tot[s][1]))
    for s, ns in (('NUPPER', (9001, 9002)), ('NLOWER', (9101, 9102))):
        out.append(' forces (fx,fy,fz) for set %s and time  %.7E\n\n' % (s, t))
        out += ['%10d  %.6E  %.6E  0.000000E+00\n' % (n, forces[n][0], forces[n][1]) for n in ns]
        out.append('\n')
    out.append(' displacements (vx,vy,vz) for set NSTRAIN and time  %.7E\n\n' % t)
    out += ['%10d  0.000000E+00  0.000000E+00  0.000000E+00\n' % n for n in mid]
    out.append('\n')
open(os.path.join(d, 'continuum.dat'), 'w').write(''.join(out))
EOF

# a) the script
scripts/lift_trace.sh "$tmp/small.nml" -o "$tmp/out" --ccx "$tmp/ccx" --at 0.5 --bin "$prog" \
    >"$tmp/table.txt" 2>"$tmp/err.txt"
rc=$?
check "lift_trace.sh with a kept continuum: exit status 0 ($rc)" test "$rc" -eq 0
check "a snapshot at every increment of the pull" \
    test "$(grep -c '^# block [0-9]* pull' "$tmp/out/program/snapshots.dat")" -gt 5
check "the table at 0.5h and at the largest restraining force" \
    bash -c "grep -q '^## 0.5h: program at delta/h = 0.500, continuum at 0.500' '$tmp/table.txt' &&
             grep -q '^## largest N: ' '$tmp/table.txt'"

# value BLOCK TOOL PIECE COLUMN: column 1..5 (program, continuum, diff,
# ratio, c.fric) of the row TOOL PIECE of block BLOCK (the piece names
# hold blanks: the tool is characters 1-6, the piece 8-37, the numbers
# start at character 39)
value() {
    awk -v blk="$1" -v tool="$2" -v piece="$3" -v col="$4" '
        /^## / { inblk = index($0, "## " blk ":") == 1 }
        inblk && substr($0, 1, 6) ~ "^" tool " *$" && substr($0, 8, 30) ~ "^" piece " *$" {
            split(substr($0, 39), w, " "); print w[col]; exit }
    ' "$tmp/table.txt"
}
# near A B TOL: |A - B| <= TOL
near() {
    awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= t) }'
}

# b) the program's rebuilt normal forces close on pull.dat's F and lift (mu = 0)
f=$(value 0.5h lower 'total: punch force F' 1)
fl=$(value 0.5h lower 'friction' 1)
check "program F at 0.5h = $f N/mm, its friction row (lower tool) $fl: below 0.5%" \
    near "$fl" 0 "$(awk -v f="$f" 'BEGIN { print 0.005 * f }')"
fu=$(value 0.5h upper 'friction' 1)
check "upper tool's friction row at 0.5h $fu: below 0.5% of F" \
    near "$fu" 0 "$(awk -v f="$f" 'BEGIN { print 0.005 * f }')"
ce=$(value 0.5h lower 'corner R1, entry side \(normal\)' 1)
cx=$(value 0.5h lower 'corner R1, exit side \(normal\)' 1)
check "the program's male corners carry the punch force ($ce, $cx of $f N/mm)" \
    awk -v a="$ce" -v b="$cx" -v f="$f" 'BEGIN { exit !(a > 0.4 * f && b > 0.4 * f) }'

# c) the continuum's side, by hand: at 0.5h the weights 2/3, 1/3 of times 1.1 and 1.3
check "entry radius: normal -77.78 (100 x 1.1 along the normal at -45 deg), friction -7.78" \
    bash -c "$(declare -f near); near '$(value 0.5h upper 'entry radius R2 \(normal\)' 2)' -77.78 0.01 &&
             near '$(value 0.5h upper 'entry radius R2 \(normal\)' 5)' -7.78 0.01"
check "exit binder: normal -5, no vertical friction" \
    bash -c "$(declare -f near); near '$(value 0.5h upper 'binder, exit side \(normal\)' 2)' -5 0.01 &&
             near '$(value 0.5h upper 'binder, exit side \(normal\)' 5)' 0 0.01"
check "crest 80, exit corner 37.71 (53.33 at 45 deg)" \
    bash -c "$(declare -f near); near '$(value 0.5h lower 'crest \(normal\)' 2)' 80 0.01 &&
             near '$(value 0.5h lower 'corner R1, exit side \(normal\)' 2)' 37.71 0.01"
check "continuum F 117.71, lift 90.56" \
    bash -c "$(declare -f near); near '$(value 0.5h lower 'total: punch force F' 2)' 117.71 0.01 &&
             near '$(value 0.5h upper 'total: lift \(minus the force\)' 2)' 90.56 0.01"
check "continuum edges: R_left -0.10, R_right -1.07" \
    grep -q '^# continuum edges: R_left -0.10, R_right -1.07;' "$tmp/table.txt"
check "steepest slopes of the continuum's mid-surface: 45 and 30 degrees" \
    grep -q 'continuum 45.00, 30.00 deg' "$tmp/table.txt"
check "the largest restraining force of the continuum: its last row (delta/h 0.9)" \
    grep -q '^## largest N: program at delta/h = [0-9.]*, continuum at 0.900' "$tmp/table.txt"
check "ccx-forces: the per-node reactions add up to the totals" \
    bash -c "python3 scripts/lift_trace.py ccx-forces '$tmp/ccx' | awk '!/^#/ { if ((\$8 + \$5) ^ 2 > 1e-6 || (\$9 - \$4) ^ 2 > 1e-6) bad = 1; n++ } END { exit !(n == 2 && !bad) }'"

# d) usage errors
scripts/lift_trace.sh >/dev/null 2>&1
check "no deck: exit 2" test $? -eq 2
scripts/lift_trace.sh "$tmp/small.nml" -o "$tmp/out2" --ccx "$tmp" --bin "$prog" >/dev/null 2>&1
check "--ccx without a continuum run: exit 2" test $? -eq 2

echo "lift_trace.sh: $((checks - failures)) of $checks checks passed"
((failures == 0))
