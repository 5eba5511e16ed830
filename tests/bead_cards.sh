#!/usr/bin/env bash
# bead_cards.sh -- tests of scripts/bead_curves.sh: the frictionless
# companions, the bending and total curves, and the LS-DYNA and Radioss
# cards read back field by field.
#
# Usage: tests/bead_cards.sh [binary]   (default: $DRAWBEAD, else bin/drawbead)
#
# Runs from the repository root on a sweep of a small free-edge bead A
# deck (40 elements, pulled 2h: about 3 s in all) over friction = 0, 0.1,
# 0.15 and lock_depth = 2.5, 4.7:
#   a) bead_curves.sh exits 0 and runs two frictionless companions (the
#      cases with friction 0.1 and 0.15 share one per depth; those with
#      friction 0 are their own), with friction = 0.0 in their decks;
#      companions.tsv names them; a second call runs none again
#   b) for each friction value, the files: restraining_total (saying
#      TOTAL, for Radioss Ft), restraining_bending (BENDING, for LS-DYNA
#      LCIDRF), lift, bead_table, closing, drawbead.k, drawbead_radioss.rad
#   c) drawbead.k read in fixed 10-character columns (curve points in 20):
#      *PARAMETER BEADNS and BLANKID, *CONTACT_DRAWBEAD's four cards
#      (SSID &BEADNS, MSID &BLANKID, SSTYP 4, MSTYP 3; FS = FD; SFS ... VSF;
#      LCIDRF, LCIDNF, DBDTH, DFSCL, NUMINT) and the two curves they name;
#      the numbers against the runs, computed here from each run's
#      summary.txt and pull.dat (the runs are too short for a steady
#      state: the peak force times E h, the lift of the peak row): the
#      bending curve from the frictionless companions, the normal-force
#      curve from the runs with friction, DBDTH the deepest depth, FS =
#      (total - bending) / lift there (0 with friction 0, where bending =
#      total)
#   d) drawbead_radioss.rad read in its columns (10 on the first card, 20
#      on the others): /INTER/TYPE8 grnd_IDs, surf_IDm, Iform = 2; Fn =
#      the lift, Ft = the total, DEPTH; Fn_last = Ft_last = 0; the /FUNCT
#      curves: the total and the lift
#   e) --depth 3.6 --bead-nodes 7 --blank 3 --lcid 10: the ids in the
#      cards (no *PARAMETER), DBDTH = DEPTH = 3.6, the forces and FS
#      interpolated between the swept depths; --depth 9 (outside) is a
#      usage error (exit 2), and so is a sweep not over lock_depth (before
#      any companion runs)
# Prints one line per check; exit status 0 if all pass, 1 if any fails,
# 2 if the test cannot run.
set -u

# shellcheck source=tests/lib.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib.bash" || exit 2
test_begin bead_cards.sh "${1:-}"

cat >"$tmp/beadA_free.nml" <<'EOF'
&control
   title = 'test: bead A, steel, free edge, 40 elements'
/
&sheet
   thickness = 0.762
   length = 38.1
   n_elements = 40
   left_edge = 'free'
/
&tools
   bead = 'rectangular'
   friction = 0.1
/
&loading
   pull_distance = 1.524
/
EOF

# ---------------------------------------------------------------------------
# a) the companions
# ---------------------------------------------------------------------------
echo "== a) the frictionless companions"
sweep=$tmp/sweep
scripts/sweep.sh --bin "$prog" -j 2 -o "$sweep" "$tmp/beadA_free.nml" \
    friction=0,0.1,0.15 lock_depth=2.5,4.7 >/dev/null 2>"$tmp/a.err"
rc=$?
check "the sweep runs (got $rc)" test "$rc" -eq 0
scripts/bead_curves.sh --bin "$prog" -j 2 "$sweep" >"$tmp/a.out" 2>>"$tmp/a.err"
rc=$?
check "bead_curves.sh exits 0 (got $rc)" test "$rc" -eq 0
ncomp=$(find "$sweep/frictionless/decks" -name 'case_*.nml' | wc -l)
check "two companion decks (got $ncomp)" test "$ncomp" -eq 2
check "... run by bead_curves.sh" grep -q 'running 2 frictionless companion' "$tmp/a.err"
for c in case_0002 case_0003; do
    check "$c (friction 0.1) has a companion deck with friction = 0.0" \
        grep -q '^ *friction = 0\.0$' "$sweep/frictionless/decks/$c.nml"
    check "... that completed" grep -qx completed <(cut -f2 <(grep "^$c" "$sweep/frictionless/status.tsv"))
done
# cases 0, 1: friction 0; 2, 3: 0.1; 4, 5: 0.15 (lock_depth 2.5, 4.7)
expect=$'case_0000\truns/case_0000\ncase_0001\truns/case_0001\ncase_0002\tfrictionless/runs/case_0002\ncase_0003\tfrictionless/runs/case_0003\ncase_0004\tfrictionless/runs/case_0002\ncase_0005\tfrictionless/runs/case_0003'
check "companions.tsv: friction 0 its own, 0.1 and 0.15 share one per depth" \
    test "$(cat "$sweep/frictionless/companions.tsv")" == "$expect"
scripts/bead_curves.sh --bin "$prog" "$sweep" >/dev/null 2>"$tmp/a2.err"
rc=$?
check "a second call exits 0 (got $rc) ..." test "$rc" -eq 0
no_run() { ! grep -q running "$1"; }
check "... and runs no companion again" no_run "$tmp/a2.err"

# ---------------------------------------------------------------------------
# b) - d) the files and the cards
# ---------------------------------------------------------------------------
echo "== b) - d) the files, drawbead.k and drawbead_radioss.rad"
cat >"$tmp/read_cards.py" <<'EOF'
"""read_cards.py SWEEP OUTDIR SUFFIX CASE_SHALLOW CASE_DEEP DEPTH IDS
Reads OUTDIR/drawbead SUFFIX .k and drawbead_radioss SUFFIX .rad in their
fixed columns and checks them against the runs of SWEEP (the two cases
with friction, their companions from frictionless/companions.tsv). DEPTH:
the working penetration asked for; IDS: 'none' (placeholders) or
'NODES,BLANK,LCID'. Prints ok/FAIL lines; exit status 1 on a failure."""
import os
import sys

sweep, outdir, sfx, c1, c2, depth, ids = sys.argv[1:8]
depth = float(depth)
fails = 0


def check(what, ok):
    global fails
    print('%s %s' % ('ok  ' if ok else 'FAIL', what))
    fails += 0 if ok else 1


def close(a, b, rel=2e-6):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-12)


def summary(run):
    vals = {}
    with open(os.path.join(run, 'summary.txt')) as f:
        for ln in f:
            if ' = ' in ln and not ln.startswith('#'):
                k, v = ln.split(' = ', 1)
                vals[k.strip()] = v.strip()
    return vals


def point(run):
    """(restraining force, lift) in N/mm of a run without a steady state:
    peak_force_over_Eh times E h, and pull.dat column 8 of the peak row."""
    s = summary(run)
    assert s['steady_force_over_Eh'] == 'none', run + ' has a steady state'
    rows = [[float(x) for x in ln.split()] for ln in open(os.path.join(run, 'pull.dat'))
            if not ln.startswith('#') and ln.strip()]
    eh = rows[0][2] / rows[0][1]
    peak = max(rows, key=lambda r: r[1])
    return float(s['peak_force_over_Eh']) * eh, peak[7]


companions = dict(ln.rstrip('\n').split('\t') for ln in open(os.path.join(sweep, 'frictionless',
                                                                          'companions.tsv')))
depths = [2.5, 4.7]
total, lift, bending = [], [], []
for c in (c1, c2):
    t, n = point(os.path.join(sweep, 'runs', c))
    b, _ = point(os.path.join(sweep, companions[c]))
    total.append(t)
    lift.append(n)
    bending.append(b)


def at(values):
    """Linear between the two depths (the origin is not needed: depth >= 2.5)."""
    return values[0] + (values[1] - values[0]) * (depth - depths[0]) / (depths[1] - depths[0])


t_d, b_d, n_d = at(total), at(bending), at(lift)
fs = (t_d - b_d) / n_d

# --- LS-DYNA: cards are the lines that are not comments, keyword by keyword
cards = {}
key = None
for ln in open(os.path.join(outdir, 'drawbead%s.k' % sfx)):
    ln = ln.rstrip('\n')
    if ln.startswith('$'):
        continue
    check_width = len(ln) <= 80
    if not check_width:
        check('LS-DYNA line within 80 columns: %r' % ln, False)
    if ln.startswith('*'):
        key = ln
        cards.setdefault(key, []).append([])
    else:
        cards[key][-1].append(ln)


def cols(line, width, n):
    return [line[i * width:(i + 1) * width] for i in range(n)]


def num(text):
    return float(text)


if ids == 'none':
    ns, blank, lcid = '&BEADNS', '&BLANKID', 1
    par = cards.get('*PARAMETER', [[]])[0]
    got = {cols(p, 10, 2)[0].strip(): int(cols(p, 10, 2)[1]) for p in par}
    check('*PARAMETER: I BEADNS and I BLANKID, 0 (placeholders)',
          got == {'I BEADNS': 0, 'I BLANKID': 0})
else:
    ns, blank, lcid = ids.split(',')
    lcid = int(lcid)
    check('no *PARAMETER when the ids are given', '*PARAMETER' not in cards)
contact = cards['*CONTACT_DRAWBEAD'][0]
check('*CONTACT_DRAWBEAD: four cards', len(contact) == 4)
c1f = [f.strip() for f in cols(contact[0], 10, 8)]
check('card 1: SSID %s MSID %s SSTYP 4 MSTYP 3, boxes and SPR/MPR 0 (%s)' % (ns, blank, c1f),
      c1f == [ns, blank, '4', '3', '0', '0', '0', '0'])
c2f = cols(contact[1], 10, 8)
check('card 2: FS = FD = (total - bending) / lift at %g mm = %.7g (got %s)'
      % (depth, fs, c2f[0].strip()), close(num(c2f[0]), fs) and num(c2f[1]) == num(c2f[0]))
check('card 2: DC VC VDC 0, PENCHK 0, BT 0, DT 1e20',
      [num(f) for f in c2f[2:5]] == [0, 0, 0] and c2f[5].strip() == '0' and num(c2f[6]) == 0
      and num(c2f[7]) == 1e20)
check('card 3: SFS SFM 1, SST MST 0, SFST SFMT FSF VSF 1',
      [num(f) for f in cols(contact[2], 10, 8)] == [1, 1, 0, 0, 1, 1, 1, 1])
c4f = cols(contact[3], 10, 5)
check('card 4: LCIDRF %d LCIDNF %d' % (lcid, lcid + 1),
      int(c4f[0]) == lcid and int(c4f[1]) == lcid + 1)
check('card 4: DBDTH = %g (got %s)' % (depth, c4f[2].strip()), close(num(c4f[2]), depth, 1e-12))
check('card 4: DFSCL 1, NUMINT 0', num(c4f[3]) == 1.0 and c4f[4].strip() == '0')

curves = {}
for cv in cards['*DEFINE_CURVE_TITLE']:
    head = cols(cv[1], 10, 7)
    curves[int(head[0])] = (cv[0], head, [(num(a), num(b)) for a, b in
                                          (cols(p, 20, 2) for p in cv[2:])])
check('two curves, ids LCIDRF and LCIDNF', sorted(curves) == [lcid, lcid + 1])
for k, (title, head, _) in curves.items():
    check('curve %d: SIDR 0, SFA SFO 1, OFFA OFFO 0, DATTYP 0' % k,
          int(head[1]) == 0 and [num(f) for f in head[2:6]] == [1, 1, 0, 0] and int(head[6]) == 0)
want_b = [(0.0, 0.0)] + list(zip(depths, bending))
want_n = [(0.0, 0.0)] + list(zip(depths, lift))
got_b, got_n = curves[lcid][2], curves[lcid + 1][2]


def same_curve(got, want):
    return len(got) == len(want) and all(close(a, c) and close(b, d)
                                         for (a, b), (c, d) in zip(got, want))


check('LCIDRF: the bending curve of the frictionless companions %s' % [round(b, 4) for b in bending],
      'bending' in curves[lcid][0] and same_curve(got_b, want_b))
check('LCIDNF: the lift of the runs with friction %s' % [round(n, 4) for n in lift],
      'normal' in curves[lcid + 1][0] and same_curve(got_n, want_n))

# --- Radioss
lines = [ln.rstrip('\n') for ln in open(os.path.join(outdir, 'drawbead_radioss%s.rad' % sfx))]
check('Radioss lines within 100 columns', all(len(ln) <= 100 for ln in lines))
body = [ln for ln in lines if not ln.startswith('#')]
blocks = {}
for ln in body:
    if ln.startswith('/'):
        key = ln
        blocks[key] = []
    else:
        blocks[key].append(ln)
inter = blocks.get('/INTER/TYPE8/%d' % lcid)
check('/INTER/TYPE8/%d: a title and three cards' % lcid, inter is not None and len(inter) == 4)
r1 = cols(inter[1], 10, 4)
want_ids = ['0', '0'] if ids == 'none' else [ns, blank]
check('card 1: grnd_IDs %s surf_IDm %s, blank, Iform 2' % tuple(want_ids),
      [f.strip() for f in r1] == want_ids + ['', '2'])
r2 = [num(f) for f in cols(inter[2], 20, 5)]
check('card 2: Fn = the lift at %g mm = %.7g (got %.7g)' % (depth, n_d, r2[0]), close(r2[0], n_d))
check('card 2: Ft = the total at %g mm = %.7g (got %.7g)' % (depth, t_d, r2[1]), close(r2[1], t_d))
check('card 2: DEPTH %g, Tstart 0, Tstop 0' % depth,
      close(r2[2], depth, 1e-12) and r2[3:] == [0.0, 0.0])
check('card 3: Fn_last Ft_last 0', [num(f) for f in cols(inter[3], 20, 2)] == [0.0, 0.0])
want_t = [(0.0, 0.0)] + list(zip(depths, total))
for fid, want, what in ((lcid, want_t, 'total'), (lcid + 1, want_n, 'lift')):
    fb = blocks.get('/FUNCT/%d' % fid)
    check('/FUNCT/%d: the %s curve' % (fid, what),
          fb is not None and same_curve([(num(a), num(b)) for a, b in
                                         (cols(p, 20, 2) for p in fb[1:])], want))
sys.exit(1 if fails else 0)
EOF

# check_files SUFFIX: the tables of one friction value exist and say what they are
check_files() {
    local d=$sweep/bead_curves sfx=$1
    check "restraining_total$sfx.txt says TOTAL, for Radioss Ft" \
        grep -q '^# TOTAL: .*Radioss /INTER/TYPE8 Ft.*NOT for LS-DYNA LCIDRF' "$d/restraining_total$sfx.txt"
    check "restraining_bending$sfx.txt says BENDING, for LS-DYNA LCIDRF" \
        grep -q '^# BENDING: the frictionless companion runs.*LS-DYNA \*CONTACT_DRAWBEAD LCIDRF' \
        "$d/restraining_bending$sfx.txt"
    check "units in the headers (mm, N/mm)" \
        grep -q '^# 1: penetration = lock_depth \[mm\] *2: total restraining force \[N/mm\]' \
        "$d/restraining_total$sfx.txt"
    check "lift$sfx.txt, bead_table$sfx.txt, closing$sfx.txt written" \
        test -s "$d/lift$sfx.txt" -a -s "$d/bead_table$sfx.txt" -a -s "$d/closing$sfx.txt"
    check "restraining curves: origin and two depths" \
        test "$(grep -cv '^#' "$d/restraining_bending$sfx.txt")" -eq 3
}

for f in 0:case_0000:case_0001 0.1:case_0002:case_0003 0.15:case_0004:case_0005; do
    IFS=: read -r mu shallow deep <<<"$f"
    echo "-- friction = $mu"
    check_files "_friction-$mu"
    python3 "$tmp/read_cards.py" "$sweep" "$sweep/bead_curves" "_friction-$mu" "$shallow" "$deep" 4.7 none \
        >"$tmp/cards.out" 2>&1
    rc=$?
    cat "$tmp/cards.out"
    checks=$((checks + $(grep -c '^ok \|^FAIL' "$tmp/cards.out")))
    ((rc == 0)) || failures=$((failures + $(grep -c '^FAIL' "$tmp/cards.out") + 1))
done
check "friction 0: the bending curve is the total" \
    cmp -s <(grep -v '^#' "$sweep/bead_curves/restraining_total_friction-0.txt") \
    <(grep -v '^#' "$sweep/bead_curves/restraining_bending_friction-0.txt")
check "friction 0: FS = 0" grep -q '^ *0\.0 *0\.0 ' "$sweep/bead_curves/drawbead_friction-0.k"

# ---------------------------------------------------------------------------
# e) a depth between the swept ones, the ids given
# ---------------------------------------------------------------------------
echo "== e) --depth 3.6 --bead-nodes 7 --blank 3 --lcid 10"
scripts/bead_curves.sh --bin "$prog" -o "$tmp/ids" --depth 3.6 --bead-nodes 7 --blank 3 --lcid 10 \
    "$sweep" >/dev/null 2>"$tmp/e.err"
rc=$?
check "bead_curves.sh exits 0 (got $rc)" test "$rc" -eq 0
python3 "$tmp/read_cards.py" "$sweep" "$tmp/ids" "_friction-0.1" case_0002 case_0003 3.6 7,3,10 \
    >"$tmp/cards.out" 2>&1
rc=$?
cat "$tmp/cards.out"
checks=$((checks + $(grep -c '^ok \|^FAIL' "$tmp/cards.out")))
((rc == 0)) || failures=$((failures + $(grep -c '^FAIL' "$tmp/cards.out") + 1))
scripts/bead_curves.sh --bin "$prog" -o "$tmp/out9" --depth 9 "$sweep" >/dev/null 2>"$tmp/e2.err"
rc=$?
check "--depth 9 (outside 0 to 4.7 mm) is a usage error (exit 2, got $rc)" test "$rc" -eq 2
check "... saying so" grep -q 'outside the depths of the sweep' "$tmp/e2.err"
scripts/sweep.sh --bin "$prog" -o "$tmp/nolock" "$tmp/beadA_free.nml" friction=0.1 >/dev/null 2>&1
scripts/bead_curves.sh --bin "$prog" "$tmp/nolock" >/dev/null 2>"$tmp/e3.err"
rc=$?
check "a sweep not over lock_depth is a usage error (exit 2, got $rc) ..." test "$rc" -eq 2
check "... found before any companion runs" test ! -e "$tmp/nolock/frictionless/runs"

# a run that tore keeps its point: tearing is a result (issue 28, item 9)
cp -r "$sweep" "$tmp/torn"
# (the status comes from the run's summary.txt: scripts/lib.sh's run_status)
sed -i 's/^status = .*/status = torn/' "$tmp/torn/runs/case_0002/summary.txt"
scripts/bead_curves.sh --bin "$prog" -o "$tmp/torn/curves" "$tmp/torn" >/dev/null 2>"$tmp/e4.err"
rc=$?
check "bead_curves.sh with a torn run exits 0 (got $rc)" test "$rc" -eq 0
check "... keeps every depth of the torn run's combination" \
    test "$(cat "$tmp"/torn/curves/restraining_total*.txt | grep -vc '^#')" -eq 9
check "... and says where the sheet localized or tore" grep -q 'localized (may tear) at lock_depth' \
    "$tmp"/torn/curves/restraining_total*.txt

if ((failures > 0)); then
    echo "--- stderr:"
    cat "$tmp/a.err" "$tmp/e.err"
fi
echo "bead_cards.sh: $checks checks, $failures failed"
((failures == 0))
