#!/usr/bin/env python3
"""ccx_resume.py -- go on with a CalculiX continuum run stopped in its pull,
from the last step it finished (docs/continuum-check.md, "Long sheets").

Usage:
    ccx_resume.py DIR [--dry-run]

DIR   a continuum run of scripts/continuum_model.py --pull-steps N
      (continuum.inp, continuum_model.json, continuum.rout, continuum.sta,
      continuum.dat: the ccx/ folder of scripts/continuum_check.sh or
      scripts/exit_state_check.sh) whose CalculiX job stopped (killed, the
      machine shut down) after finishing at least its first step.

The steps finished are read off continuum.sta: step k is finished when
its last converged increment ends at the step's time (the second value of
its *STATIC card). The job goes on as continuum_r in DIR: continuum_r.inp
is '*RESTART, READ, STEP=k' (k the last step finished, whose state
continuum.rout holds; copied to continuum_r.rin) followed by the steps of
continuum.inp after k; CalculiX runs it (OMP_NUM_THREADS threads, default
1; its output in ccx_r.log; a SIGTERM or SIGINT is passed on to it).

Then the two jobs' results are joined under the usual names, so that the
scripts that read DIR (continuum_results.py, exit_state.py, the --ccx
option of exit_state_check.sh) see one run: continuum.dat keeps the first
job's blocks up to the end of step k (total time T_k) and takes the
second job's after them; continuum.sta its increments of steps 1 to k and
the second job's. The first job's files are kept as
continuum_interrupted.dat and continuum_interrupted.sta, and
continuum_model.json records 'resumed_after_step': k (exit_state.py puts
it in the header of the exit state it extracts). A CalculiX job that
stops early leaves its results up to there; they are joined all the same
(as continuum_check.sh compares such a run) and the exit status is 1.

What the second job does differently (measured, CalculiX 2.20): it takes
the uninterrupted job's increments up to the first output time of the
model (*TIME POINTS) it would have stopped at, then its own: the time
points do not survive the restart, so CalculiX prints every increment and
no longer shortens an increment to reach an output time. On the coarse
bead A of tests/continuum.sh the forces at the end of the pull differ
from the uninterrupted job's by 2e-4 of their value. The second job
writes restart records of its own (continuum_r.rout); this script resumes
from the first job's only: a resumed job stopped again goes on again from
step k.

--dry-run  print what would be done (the steps finished, the time T_k, the
           steps to run) and write continuum_r.inp, without running.

Exit status: 0 done (or nothing left to run), 1 CalculiX stopped with an
error (its results joined, as far as they go), 2 no run to resume (a
missing file, no restart records asked for in continuum.inp, the first
step not finished, a run resumed already, CalculiX not installed).
"""

import json
import os
import re
import shutil
import signal
import subprocess
import sys


def fail(msg, status=2):
    """Print 'ccx_resume.py: MSG' on stderr and exit with STATUS."""
    sys.stderr.write('ccx_resume.py: %s\n' % msg)
    sys.exit(status)


def steps_of(inp_text):
    """The *STEP ... *END STEP blocks of an input: [(start, period)],
    start the offset of the '*STEP' line, period the second value of the
    step's *STATIC data line."""
    steps = []
    for m in re.finditer(r'^\*STEP\b.*?^\*END STEP[^\n]*\n', inp_text, re.M | re.S | re.I):
        s = re.search(r'^\*STATIC[^\n]*\n([^\n]*)', m.group(0), re.M | re.I)
        if not s:
            fail('a step of continuum.inp has no *STATIC card')
        try:
            period = float(s.group(1).split(',')[1])
        except (IndexError, ValueError):
            fail("a *STATIC card of continuum.inp has no step time: '%s'" % s.group(1))
        steps.append((m.start(), period))
    return steps


def sta_increments(path):
    """The converged increments of a .sta file: [(step, step time, line)]."""
    out = []
    with open(path) as f:
        for line in f:
            w = line.split()
            if len(w) != 7 or not w[0].isdigit() or w[2].endswith('U'):
                continue
            try:
                out.append((int(w[0]), float(w[5]), line))
            except ValueError:
                continue
    return out


def finished_steps(increments, periods):
    """How many steps, in order, the increments show finished (the last
    converged increment of step k at its step time periods[k-1])."""
    last = {}
    for step, t, _ in increments:
        last[step] = t
    k = 0
    for step, period in enumerate(periods, start=1):
        if step not in last or last[step] < period * (1.0 - 1e-6):
            break
        k = step
    return k


def copy_dat_until(dat_path, t_end, out):
    """Copy the blocks of a CalculiX .dat file up to total time t_end
    (their headers end in 'and time  T') to the open file out."""
    head = re.compile(r'for set \S+ and time\s+(\S+)\s*$')
    keep = True
    with open(dat_path) as f:
        for line in f:
            m = head.search(line)
            if m:
                keep = float(m.group(1)) <= t_end * (1.0 + 1e-9) + 1e-12
            if keep:
                out.write(line)


def run_ccx(d):
    """CalculiX on DIR/continuum_r.inp, its output in ccx_r.log; a SIGTERM
    or SIGINT to this script stops it too. Returns its exit status."""
    env = dict(os.environ)
    env.setdefault('OMP_NUM_THREADS', '1')
    with open(os.path.join(d, 'ccx_r.log'), 'w') as log:
        proc = subprocess.Popen(['ccx', 'continuum_r'], cwd=d, env=env, stdout=log,
                                stderr=subprocess.STDOUT)

        def stop(signum, _frame):
            proc.send_signal(signum)
            proc.wait()
            sys.exit(128 + signum)
        old = {s: signal.signal(s, stop) for s in (signal.SIGTERM, signal.SIGINT)}
        try:
            return proc.wait()
        finally:
            for s, h in old.items():
                signal.signal(s, h)


def join(d, k, t_k):
    """The two jobs' results under the usual names (module header)."""
    dat, sta = os.path.join(d, 'continuum.dat'), os.path.join(d, 'continuum.sta')
    old_dat = os.path.join(d, 'continuum_interrupted.dat')
    old_sta = os.path.join(d, 'continuum_interrupted.sta')
    os.replace(dat, old_dat)
    os.replace(sta, old_sta)
    with open(dat, 'w') as out:
        copy_dat_until(old_dat, t_k, out)
        with open(os.path.join(d, 'continuum_r.dat')) as f:
            shutil.copyfileobj(f, out)
    with open(sta, 'w') as out:
        # the first job's header lines and its increments of steps 1..k
        with open(old_sta) as f:
            for line in f:
                w = line.split()
                if len(w) == 7 and w[0].isdigit() and int(w[0]) > k:
                    continue
                out.write(line)
        with open(os.path.join(d, 'continuum_r.sta')) as f:
            for line in f:
                w = line.split()
                if len(w) == 7 and w[0].isdigit():
                    out.write(line)
    jpath = os.path.join(d, 'continuum_model.json')
    with open(jpath) as f:
        info = json.load(f)
    info['resumed_after_step'] = k
    with open(jpath, 'w') as f:
        json.dump(info, f)


def main(argv):
    """Command line: see the module header."""
    if '-h' in argv or '--help' in argv:
        print(__doc__)
        return 0
    args = [a for a in argv if not a.startswith('-')]
    unknown = [a for a in argv if a.startswith('-') and a != '--dry-run']
    if unknown or len(args) != 1:
        fail('usage: ccx_resume.py DIR [--dry-run]')
    d, dry = args[0], '--dry-run' in argv
    for name in ('continuum.inp', 'continuum_model.json', 'continuum.sta', 'continuum.dat'):
        if not os.path.isfile(os.path.join(d, name)):
            fail("'%s' holds no %s: not a continuum run" % (d, name))
    with open(os.path.join(d, 'continuum.inp')) as f:
        inp = f.read()
    if not re.search(r'^\*RESTART,\s*WRITE', inp, re.M | re.I):
        fail("'%s/continuum.inp' asks for no restart records: make the model with "
             "scripts/continuum_model.py --pull-steps N" % d)
    with open(os.path.join(d, 'continuum_model.json')) as f:
        if 'resumed_after_step' in json.load(f):
            fail("'%s' was resumed already (continuum_model.json: resumed_after_step); "
                 "its restart records are the first job's" % d)
    if not os.path.isfile(os.path.join(d, 'continuum.rout')):
        fail("'%s' holds no continuum.rout: the first step never finished" % d)
    steps = steps_of(inp)
    periods = [p for _, p in steps]
    k = finished_steps(sta_increments(os.path.join(d, 'continuum.sta')), periods)
    if k == 0:
        fail("'%s': the first step did not finish: run the model again" % d)
    t_k = sum(periods[:k])
    left = list(range(k + 1, len(steps) + 1))
    print('ccx_resume.py: %d of %d steps finished (time %.9g); to run: %s'
          % (k, len(steps), t_k, ', '.join('step %d' % i for i in left) or 'nothing'))
    if not left:
        return 0
    with open(os.path.join(d, 'continuum_r.inp'), 'w') as f:
        f.write('*RESTART, READ, STEP=%d\n' % k)
        f.write(inp[steps[k][0]:])
    if dry:
        return 0
    if shutil.which('ccx') is None:
        fail('ccx (CalculiX) is not installed: apt-get install calculix-ccx')
    for name in ('continuum_r.dat', 'continuum_r.sta'):
        if os.path.exists(os.path.join(d, name)):
            os.remove(os.path.join(d, name))
    shutil.copyfile(os.path.join(d, 'continuum.rout'), os.path.join(d, 'continuum_r.rin'))
    rc = run_ccx(d)
    if not (os.path.isfile(os.path.join(d, 'continuum_r.dat'))
            and os.path.isfile(os.path.join(d, 'continuum_r.sta'))):
        fail("CalculiX wrote no results (status %d; log: %s/ccx_r.log)" % (rc, d), 1)
    join(d, k, t_k)
    if rc != 0:
        fail("CalculiX stopped with status %d (log: %s/ccx_r.log); its results up to there "
             "are joined in %s" % (rc, d, d), 1)
    print('ccx_resume.py: done; %s/continuum.dat and continuum.sta hold the whole run' % d)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
