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
it in the header of the exit state it extracts); each file is written
under a temporary name and then renamed, so that a join cut short leaves
either file whole. Only a second job that ends normally is joined: if
CalculiX stops with an error (or is stopped), DIR keeps the first job's
files as they were, the second's are left as continuum_r.* beside them,
the exit status is 1, and the resume can be run again.

What the second job does differently (measured, CalculiX 2.20): it takes
the uninterrupted job's increments up to the first output time of the
model (*TIME POINTS) it would have stopped at, then its own: the time
points do not survive the restart, so CalculiX prints every increment and
no longer shortens an increment to reach an output time. On the coarse
bead A of tests/continuum.sh the forces at the end of the pull differ
from the uninterrupted job's by 1.75e-4 of their value. The second job
writes restart records of its own (continuum_r.rout); this script resumes
from the first job's only: a resumed job stopped again goes on again from
step k.

--dry-run  print what would be done (the steps finished, the time T_k, the
           steps to run) and write continuum_r.inp, without running.

Exit status: 0 done (or nothing left to run), 1 CalculiX stopped with an
error (nothing joined), 128 + N stopped by signal N, 2 no run to resume (a
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


def sta_step(line):
    """The step of a .sta file's increment line (STEP INC ATT ITRS TOT TIME
    STEP TIME INC TIME), None for its other lines."""
    w = line.split()
    return int(w[0]) if len(w) == 7 and w[0].isdigit() else None


def finished_steps(sta_path, periods):
    """How many steps, in order, continuum.sta shows finished (the last
    converged increment of step k at its step time periods[k-1])."""
    last = {}
    with open(sta_path) as f:
        for line in f:
            w = line.split()
            if sta_step(line) is None or w[2].endswith('U'):
                continue
            try:
                last[int(w[0])] = float(w[5])
            except ValueError:
                continue
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
    or SIGINT to this script is passed on to it. Returns its exit status
    and the signal received (0: none)."""
    env = dict(os.environ)
    env.setdefault('OMP_NUM_THREADS', '1')
    got = [0]
    with open(os.path.join(d, 'ccx_r.log'), 'w') as log:
        proc = subprocess.Popen(['ccx', 'continuum_r'], cwd=d, env=env, stdout=log,
                                stderr=subprocess.STDOUT)

        def forward(signum, _frame):
            # only pass it on: the wait below returns once ccx has gone
            # (waiting here too would block on the lock the wait holds)
            got[0] = signum
            proc.send_signal(signum)
        old = {s: signal.signal(s, forward) for s in (signal.SIGTERM, signal.SIGINT)}
        try:
            rc = proc.wait()
        finally:
            for s, h in old.items():
                signal.signal(s, h)
    return rc, got[0]


def write_then_rename(path, write):
    """write(f) into PATH.tmp, then rename it to PATH."""
    with open(path + '.tmp', 'w') as f:
        write(f)
    os.replace(path + '.tmp', path)


def keep_copy(src, dst):
    """DST the same file as SRC (a hard link; a copy where links fail)."""
    if os.path.lexists(dst):
        os.remove(dst)
    try:
        os.link(src, dst)
    except OSError:
        shutil.copyfile(src, dst)


def join(d, k, t_k):
    """The two jobs' results under the usual names (module header); the
    json's mark last, so that a join cut short can be run again."""
    dat, sta = os.path.join(d, 'continuum.dat'), os.path.join(d, 'continuum.sta')
    old_dat = os.path.join(d, 'continuum_interrupted.dat')
    old_sta = os.path.join(d, 'continuum_interrupted.sta')
    keep_copy(dat, old_dat)
    keep_copy(sta, old_sta)

    def write_dat(out):
        copy_dat_until(old_dat, t_k, out)
        with open(os.path.join(d, 'continuum_r.dat')) as f:
            shutil.copyfileobj(f, out)

    def write_sta(out):
        # the first job's header lines and its increments of steps 1..k
        with open(old_sta) as f:
            for line in f:
                step = sta_step(line)
                if step is None or step <= k:
                    out.write(line)
        with open(os.path.join(d, 'continuum_r.sta')) as f:
            for line in f:
                if sta_step(line) is not None:
                    out.write(line)
    write_then_rename(dat, write_dat)
    write_then_rename(sta, write_sta)
    jpath = os.path.join(d, 'continuum_model.json')
    with open(jpath) as f:
        info = json.load(f)
    info['resumed_after_step'] = k
    write_then_rename(jpath, lambda f: json.dump(info, f))


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
    k = finished_steps(os.path.join(d, 'continuum.sta'), periods)
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
    keep_copy(os.path.join(d, 'continuum.rout'), os.path.join(d, 'continuum_r.rin'))
    rc, sig = run_ccx(d)
    if sig:
        fail('stopped by signal %d: CalculiX stopped with it (status %d); %s keeps the first '
             "job's files, the second's are continuum_r.*" % (sig, rc, d), 128 + sig)
    if rc != 0 or not (os.path.isfile(os.path.join(d, 'continuum_r.dat'))
                       and os.path.isfile(os.path.join(d, 'continuum_r.sta'))):
        fail("CalculiX stopped with status %d (log: %s/ccx_r.log): nothing joined; %s keeps the "
             "first job's files, the second's are continuum_r.*" % (rc, d, d), 1)
    join(d, k, t_k)
    print('ccx_resume.py: done; %s/continuum.dat and continuum.sta hold the whole run' % d)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
