#!/bin/bash
# tests/continuum.sh -- the continuum cross-check (scripts/continuum_check.sh,
# docs/continuum-check.md) on two small cases with the coarsest continuum
# mesh (--through 2 --per-h 1, time increments of 0.1), and a resumed
# CalculiX job (scripts/ccx_resume.py): about 40 s on a quiet machine.
#
# Usage: tests/continuum.sh [path/to/drawbead]   (run from anywhere)
#
#  a) tests/decks/continuum_strip.nml, a clamped strip pulled to 10% strain:
#     homogeneous plane-strain tension in the shell and in the continuum
#     alike (the end sections stay plane and may thin), so the conversion
#     must give lambda - 1 = 0.1 at every row (to 1e-9), and the restraining
#     force, the thickness strain and the plastic strain of the program
#     within 0.5% (they differ only by the continuum's hypoelastic update,
#     O(sigma/E) = 0.2%);
#  b) tests/decks/continuum_bead_a_short.nml, bead A locked and pulled 0.5h
#     with friction: the run completes, every file has the program's
#     legend line and column count, the centreline over the male top
#     (s = 0) is at the lock depth after locking (within 0.1h: the tools
#     offset by h/2 the right way, the lower tool raised), and the punch
#     force at 98% of the lock and the tension at the end of locking are
#     within 20% of the program's (the shell is 5-10% high here).
#  c) the model (scripts/continuum_model.py, no ccx needed) of that deck
#     locked short of full lock (lock_depth = 3 mm, as the binder-gap case
#     input/cc_fig9c_beadA_steel_free_gap.nml): the lower tool rises by
#     the deck's lock_depth while locking and is held there while pulling;
#  d) (no ccx needed) scripts/continuum_results.py's check that the
#     continuum is a sheet lying in the tools: the flat sheet is, the
#     sheet raised by 3h or stretched by 3 is not, and compare says so and
#     leaves the numbers out; b) is a sheet in the tools.
#  e) (no ccx needed) --contact-slope reaches the model's contact and
#     friction cards (default 1e5 and 1e4 MPa/mm unchanged); 0 is refused.
#  f) scripts/ccx_resume.py: the deck of b) with its pull in two steps
#     (continuum_model.py --pull-steps 2, restart records), run through,
#     then the same job as if killed in the second pull step (its .sta and
#     .dat cut at time 1.7) and resumed: the resume runs the last step
#     only, the joined .dat keeps the first job's blocks to time 1.5
#     exactly, then the resumed job's, and its forces at the end of the
#     pull are the uninterrupted job's within 1e-3 (the resumed job loses
#     the output times that shorten some increments: measured 1.75e-4); the
#     header of an exit state extracted from the joined run
#     (exit_state.py, the model patched at s = 0) says it was resumed; a
#     run that finished has nothing to run (exit 0); a second resume, a
#     folder without restart records and a missing folder are refused
#     (exit 2); restart records cut short make CalculiX fail: exit 1,
#     nothing joined; a SIGTERM reaches CalculiX (a stand-in that waits)
#     and the script ends with 143
# a), b) and f) are skipped (ok) when ccx is not installed. Exit 0 if all
# pass, 1 otherwise.
set -u
cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 2
bin=${1:-bin/drawbead}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0

# c) a lock short of full lock reaches the model
mkdir -p "$work/short/program"
sed 's/^&loading/\&loading\n   lock_depth = 3.0/' tests/decks/continuum_bead_a_short.nml >"$work/short.nml"
"$bin" "$work/short.nml" -o "$work/short/program" >"$work/short/program/run.log" 2>&1
if python3 scripts/continuum_model.py "$work/short/program/run.log" "$work/short/ccx" >/dev/null 2>&1 &&
    python3 - "$work/short/ccx" <<'PY'
import json, sys
d = sys.argv[1]
inp = open(d + '/continuum.inp').read().split('\n')
model = json.load(open(d + '/continuum_model.json'))
# the lower tool's prescribed rise, under the locking amplitude, which
# climbs to 1 over locking (time 0..1) and stays there while pulling (1..2)
rise = [inp[i + 1] for i, l in enumerate(inp) if l == '*BOUNDARY, AMPLITUDE=ALOCK']
amp = [inp[i + 1] for i, l in enumerate(inp) if l == '*AMPLITUDE, NAME=ALOCK']
ok = (abs(model['lock_depth'] - 3.0) < 1e-12 and len(rise) == 1 and rise[0].startswith('NLOWER, 2, 2,')
      and abs(float(rise[0].split(',')[3]) - 3.0) < 1e-12
      and len(amp) == 1 and [float(x) for x in amp[0].split(',')] == [0, 0, 1, 1, 2, 1])
sys.exit(0 if ok else 1)
PY
then
    echo "ok   a deck's lock_depth (3 mm, short of full lock) is the model's rise, locking and pulling"
else
    echo "FAIL a deck's lock_depth (3 mm) is not the continuum model's rise of the lower tool"
    fail=1
fi

# e) the contact's slope (--contact-slope, issue 28 item 12: the stepped
# bead's continuum stopped in the pull with the default 1e5 MPa/mm and goes
# through with 1e4): the default deck keeps 1e5 and the stick slope 1e4; the
# option sets both (stick = K/10) and is named in the model; 0 is refused
if python3 scripts/continuum_model.py "$work/short/program/run.log" "$work/slope" --contact-slope 1e4 \
    >/dev/null 2>&1 && python3 - "$work/short/ccx" "$work/slope" <<'PY'
import json, sys
def cards(d):
    inp = open(d + '/continuum.inp').read().split('\n')
    return (inp[inp.index('*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR') + 1],
            inp[inp.index('*FRICTION') + 1], json.load(open(d + '/continuum_model.json'))['contact_slope'])
ok = (cards(sys.argv[1]) == ('100000, 0.1', '0.1, 10000', 1e5)
      and cards(sys.argv[2]) == ('10000, 0.1', '0.1, 1000', 1e4))
sys.exit(0 if ok else 1)
PY
then
    echo "ok   --contact-slope 1e4 gives the contact slope 1e4 and the stick slope 1e3 MPa/mm (default 1e5, 1e4)"
else
    echo "FAIL --contact-slope does not reach the continuum model's contact and friction cards"
    fail=1
fi
if python3 scripts/continuum_model.py "$work/short/program/run.log" "$work/slope0" --contact-slope 0 \
    >/dev/null 2>"$work/slope0.err"; then
    echo "FAIL --contact-slope 0 accepted"
    fail=1
elif grep -q 'contact-slope needs a positive number' "$work/slope0.err"; then
    echo "ok   --contact-slope 0 refused"
else
    echo "FAIL --contact-slope 0: $(cat "$work/slope0.err")"
    fail=1
fi

# d) is the continuum a sheet lying in the tools? (issue 28, item 12: the
# stepped bead's continuum stood 2-5h above the tools with ln(lambda) =
# 3.6, and comparison.txt compared that without a word)
if python3 - "$work/short/ccx" "$work" <<'PY'
import json, sys
sys.path.insert(0, 'scripts')
import continuum_results as cr
info = json.load(open(sys.argv[1] + '/continuum_model.json'))
h, n_mid = info['thickness'], len(info['mid'])
ids = [int(k) for k in info['node_x']]
flat = {'U': {n: (0.0, 0.0) for n in ids}}
raised = {'U': {n: (0.0, 3.0 * h) for n in ids}}
X = {int(k): v for k, v in info['node_x'].items()}
stretched = {'U': {n: (X[n] * 2.0, 0.0) for n in ids}}
bad = 0
for what, got, want in (
        ('the flat sheet at the start lies in the tools', cr.state_problem(info, flat, 0.0), None),
        ('a sheet raised by 3h stands above the upper tool', cr.state_problem(info, raised, 0.5),
         'stands 3.0h above the upper tool'),
        ('a stretch of 3 is an absurd strain', cr.state_problem(info, stretched, 0.0), 'an absurd strain')):
    ok = got is None if want is None else want in (got or '')
    print(('ok   ' if ok else 'FAIL ') + what + ('' if ok else ': %r' % got))
    bad += not ok
# compare: a continuum state that went wrong is said, not compared silently
w = sys.argv[2]
open(w + '/p.txt', 'w').write('# p\npeak_strain_lock = 7.5e-2\n')
open(w + '/c.txt', 'w').write('# c\npeak_strain_lock = none\ncontinuum_state = not a sheet in the tools '
                              'from time 0.9: the sheet at s = -24.9h stands 2.3h above the upper tool\n')
import io, contextlib
buf = io.StringIO()
with contextlib.redirect_stdout(buf):
    cr.compare(w + '/p.txt', w + '/c.txt')
out = buf.getvalue()
ok = ('# continuum: not a sheet in the tools from time 0.9' in out and 'left out' in out
      and 'continuum_state' not in out)
print(('ok   ' if ok else 'FAIL ') + 'compare says the continuum left the tools and leaves its numbers out'
      + ('' if ok else ':\n' + out))
bad += not ok
sys.exit(1 if bad else 0)
PY
then :; else fail=1; fi

if ! command -v ccx >/dev/null 2>&1; then
    echo "ok   skipped: ccx (CalculiX) is not installed"
    exit $fail
fi
coarse=(--through 2 --per-h 1 --initial-inc 0.05 --max-inc 0.1 --no-plot --bin "$bin")

# CalculiX on both cores (bead A: about 9 s instead of 12 on one)
for case in strip bead_a_short; do
    if ! OMP_NUM_THREADS=2 scripts/continuum_check.sh "tests/decks/continuum_$case.nml" -o "$work/$case" "${coarse[@]}" \
        >"$work/$case.log" 2>&1; then
        echo "FAIL continuum_check.sh on continuum_$case.nml:"
        tail -20 "$work/$case.log"
        fail=1
        continue
    fi
    echo "ok   continuum_check.sh on continuum_$case.nml completed"
    for f in lock.dat pull.dat strain_lock.dat strain_pull.dat; do
        if [[ $(sed -n 2p "$work/$case/$f") != "$(sed -n 2p "$work/$case/program/$f")" ]]; then
            echo "FAIL $case/$f: legend differs from the program's"
            fail=1
        fi
    done
done

if python3 - "$work" <<'PY'
import sys
w = sys.argv[1]
bad = 0


def rows(path):
    return [[float(x) for x in l.split()] for l in open(path) if l.strip() and not l.startswith('#')]


def check(ok, what):
    global bad
    print(('ok   ' if ok else 'FAIL ') + what)
    bad += not ok


def rel(a, b):
    return abs(a - b) / abs(b)


for f, n in (('lock.dat', 9), ('pull.dat', 10), ('strain_lock.dat', 19), ('strain_pull.dat', 19)):
    for case in ('strip', 'bead_a_short'):
        r = rows('%s/%s/%s' % (w, case, f))
        check(all(len(x) == n for x in r), '%s/%s: %d columns in every row' % (case, f, n))

# a) homogeneous tension
c, p = rows(w + '/strip/strain_pull.dat'), rows(w + '/strip/program/strain_pull.dat')
check(max(abs(x[3] - 0.1) for x in c) < 1e-9, 'strip: lambda - 1 = 0.1 at every row')
cn, pn = rows(w + '/strip/pull.dat')[-1], rows(w + '/strip/program/pull.dat')[-1]
check(abs(cn[0] - 1.0) < 1e-9 and rel(cn[2], pn[2]) < 5e-3,
      'strip: N at delta = 1h %.4f N/mm, program %.4f' % (cn[2], pn[2]))
check(rel(c[0][7], p[0][7]) < 5e-3,
      'strip: thickness strain %.6f, program %.6f' % (c[0][7], p[0][7]))
check(rel(c[0][8], p[0][8]) < 5e-3,
      'strip: plastic strain %.6f, program %.6f' % (c[0][8], p[0][8]))

# b) bead A
lock = 4.73964 / 0.762
s = rows(w + '/bead_a_short/strain_lock.dat')
mid = min(s, key=lambda x: abs(x[0]))
check(abs(mid[2] - lock) < 0.1, 'bead A: y/h at s = 0 after locking %.4f, lock depth %.4f' % (mid[2], lock))
state = [l.split(' = ', 1)[1].strip() for l in open(w + '/bead_a_short/continuum_summary.txt')
         if l.startswith('continuum_state = ')]
check(state == ['sheet in the tools'], 'bead A: the continuum is a sheet lying in the tools (%s)' % state)
cl, pl = rows(w + '/bead_a_short/lock.dat'), rows(w + '/bead_a_short/program/lock.dat')


def at(r, x, col):
    for a, b in zip(r, r[1:]):
        if a[0] <= x <= b[0]:
            return a[col] + (b[col] - a[col]) * (x - a[0]) / (b[0] - a[0])
    return float('nan')


fc, fp = at(cl, 0.98 * lock, 2), at(pl, 0.98 * lock, 2)
check(fc > 0 and rel(fp, fc) < 0.2, 'bead A: punch force at 98%% lock %.2f N/mm, program %.2f' % (fc, fp))
nc, np_ = at(cl, 0.98 * lock, 8), at(pl, 0.98 * lock, 8)
check(nc > 0 and rel(np_, nc) < 0.2, 'bead A: tension at 98%% lock %.2f N/mm, program %.2f' % (nc, np_))
sys.exit(1 if bad else 0)
PY
then :; else fail=1; fi

# f) a job killed in its last pull step, resumed
steps=(--through 2 --per-h 1 --initial-inc 0.05 --max-inc 0.1 --pull-steps 2)
r=$work/resume
if python3 scripts/continuum_model.py "$work/bead_a_short/program/run.log" "$r/full" "${steps[@]}" >/dev/null &&
    python3 scripts/exit_state.py patch-inp "$r/full/continuum.inp" "$r/full/continuum_model.json" 0 \
        >/dev/null &&
    (cd "$r/full" && OMP_NUM_THREADS=2 ccx continuum >ccx.log 2>&1); then
    cp -r "$r/full" "$r/cut"
    rm -f "$r/cut/continuum.rout"
    cp -r "$r/full" "$r/killed"
    # killed at time 1.7 (in step 3, the second pull step): the .sta and
    # .dat as far as the job got
    python3 - "$r/killed" <<'PY'
import re
import sys
d = sys.argv[1]
lines = open(d + '/continuum.sta').readlines()
with open(d + '/continuum.sta', 'w') as f:
    for ln in lines:
        w = ln.split()
        if len(w) == 7 and w[0].isdigit() and int(w[0]) == 3 and float(w[4]) > 1.7 + 1e-9:
            continue
        f.write(ln)
head = re.compile(r'for set \S+ and time\s+(\S+)')
keep = True
lines = open(d + '/continuum.dat').readlines()
with open(d + '/continuum.dat', 'w') as f:
    for ln in lines:
        m = head.search(ln)
        if m:
            keep = float(m.group(1)) <= 1.7 + 1e-9
        if keep:
            f.write(ln)
PY
    # the same with its restart records cut short: CalculiX cannot read
    # them; and with a CalculiX that only waits, stopped by SIGTERM
    cp -r "$r/killed" "$r/broken"
    truncate -s 4096 "$r/broken/continuum.rout"
    cp "$r/broken/continuum.dat" "$r/broken_before.dat"
    cp -r "$r/killed" "$r/stopped"
    mkdir -p "$r/fake"
    printf '#!/bin/sh\nexec sleep 60\n' >"$r/fake/ccx"
    chmod +x "$r/fake/ccx"
    python3 scripts/ccx_resume.py "$r/broken" >"$r/broken.log" 2>&1
    rc_broken=$?
    start=$SECONDS
    PATH=$r/fake:$PATH timeout --preserve-status -s TERM 3 python3 scripts/ccx_resume.py "$r/stopped" \
        >"$r/stopped.log" 2>&1
    rc_stopped=$?
    took=$((SECONDS - start))
    OMP_NUM_THREADS=2 python3 scripts/ccx_resume.py "$r/killed" >"$r/resume.log" 2>&1
    rc=$?
    python3 scripts/ccx_resume.py "$r/full" >"$r/finished.log" 2>&1
    rc_done=$?
    python3 scripts/ccx_resume.py "$r/killed" >"$r/again.log" 2>&1
    rc_again=$?
    python3 scripts/ccx_resume.py "$r/cut" >"$r/cut.log" 2>&1
    rc_cut=$?
    python3 scripts/ccx_resume.py "$r/none" >"$r/none.log" 2>&1
    rc_none=$?
    python3 scripts/exit_state.py extract "$r/killed" "$r/exit_state.txt" 0 >/dev/null 2>&1 || :
    if python3 - "$r" "$rc" "$rc_done" "$rc_again" "$rc_cut" "$rc_none" "$rc_broken" "$rc_stopped" "$took" <<'PY'
import json
import re
import sys
sys.path.insert(0, 'scripts')
import continuum_results as cr  # noqa: E402
r, rc, rc_done, rc_again, rc_cut, rc_none, rc_broken, rc_stopped, took = sys.argv[1], *map(int, sys.argv[2:])
bad = 0


def check(ok, what):
    global bad
    print(('ok   ' if ok else 'FAIL ') + 'ccx_resume.py: ' + what)
    bad += not ok


log = open(r + '/resume.log').read()
check(rc == 0 and '2 of 3 steps finished (time 1.5); to run: step 3' in log,
      'the killed job resumed from step 2, step 3 run (exit %d)' % rc)
full, res = cr.read_dat(r + '/full/continuum.dat'), cr.read_dat(r + '/killed/continuum.dat')
check(res.get(1.5) == full.get(1.5), "the first job's blocks to time 1.5 kept")
own = cr.read_dat(r + '/killed/continuum_r.dat')
check(max(res) == 2.0 and sorted(t for t in res if t > 1.5) == sorted(own),
      "the joined results: after time 1.5 the resumed job's, to time 2")



def time_blocks(path, t):
    """How many blocks of a .dat file are headed with time t."""
    head = re.compile(r'for set \S+ and time\s+(\S+)')
    return sum(1 for ln in open(path) for m in [head.search(ln)] if m and float(m.group(1)) == t)


n15 = time_blocks(r + '/full/continuum.dat', 1.5)
check(n15 > 0 and time_blocks(r + '/killed/continuum.dat', 1.5) == n15,
      "step 2's last output (time 1.5) once in the joined .dat (%d blocks)" % n15)
sta = [ln.split() for ln in open(r + '/killed/continuum.sta')]
sta = [w for w in sta if len(w) == 7 and w[0].isdigit() and not w[2].endswith('U')]
times = [float(w[4]) for w in sta]
check(all(a < b for a, b in zip(times, times[1:])) and sta[-1][0] == '3' and abs(times[-1] - 2.0) < 1e-9,
      'the joined .sta: converged increments in increasing time, ending at time 2')
worst = 0.0
for k in ('RF:NRIGHT', 'RF:NLOWER', 'RF:NLEFT', 'RF:NUPPER'):
    a, b = full[2.0][k], res[2.0][k]
    m = max(abs(a[0]), abs(a[1]))
    worst = max(worst, abs(a[0] - b[0]) / m, abs(a[1] - b[1]) / m)
check(worst < 1e-3, 'forces at the end of the pull: largest difference %.2e of the force' % worst)
try:
    head = [ln for ln in open(r + '/exit_state.txt') if ln.startswith('# mesh')]
except OSError:
    head = []
check(any('resumed after step 2 (scripts/ccx_resume.py)' in ln for ln in head),
      'an extracted exit state says it was resumed')
check(rc_done == 0 and 'to run: nothing' in open(r + '/finished.log').read(),
      'a run that finished: nothing to run (exit %d)' % rc_done)
check(rc_again == 2 and 'resumed already' in open(r + '/again.log').read(),
      'a second resume refused (exit %d)' % rc_again)
check(rc_cut == 2 and 'no continuum.rout' in open(r + '/cut.log').read(),
      'a folder without restart records refused (exit %d)' % rc_cut)
check(rc_none == 2 and 'not a continuum run' in open(r + '/none.log').read(),
      'a missing folder refused (exit %d)' % rc_none)
check(rc_broken == 1 and 'nothing joined' in open(r + '/broken.log').read()
      and open(r + '/broken/continuum.dat').read() == open(r + '/broken_before.dat').read()
      and 'resumed_after_step' not in json.load(open(r + '/broken/continuum_model.json')),
      'restart records CalculiX cannot read: exit 1 (%d), nothing joined, the run unmarked' % rc_broken)
check(rc_stopped == 143 and took < 20 and 'stopped by signal 15' in open(r + '/stopped.log').read(),
      'SIGTERM passed on to CalculiX: exit 143 (%d) after %d s' % (rc_stopped, took))
sys.exit(1 if bad else 0)
PY
    then :; else fail=1; fi
else
    echo "FAIL ccx_resume.py: the two-step model of continuum_bead_a_short.nml did not run"
    fail=1
fi
exit $fail
