#!/usr/bin/env python3
"""continuum_results.py -- CalculiX results of the continuum cross-check as
the program's own result files, and the numbers compared with the program.

Usage:
    continuum_results.py convert CCX_DIR OUT_DIR [--program PATH]
    continuum_results.py metrics RUN_DIR MODEL_JSON [--title TEXT]
    continuum_results.py compare PROGRAM_METRICS CONTINUUM_SUMMARY [LABEL1 LABEL2]

convert   reads CCX_DIR/continuum.dat, continuum.sta and continuum_model.json
          (written by scripts/continuum_model.py and ccx) and writes into
          OUT_DIR lock.dat, pull.dat, strain_lock.dat, strain_pull.dat (the
          columns, units and header style of docs/output-reference.md; the
          columns a continuum cannot give are NaN, see docs/continuum-check.md;
          the column headers are the program's own, `PATH --columns FILE`,
          PATH the program, default bin/drawbead of the repository)
          and continuum_summary.txt. Each output time's state is checked
          to be a sheet lying in the tools (state_problem): from the first
          time it is not, the continuum's numbers are left out of its
          summary (none), and continuum_state says when and why.
metrics   prints, in the format of continuum_summary.txt, the same numbers
          read off any folder holding lock.dat, pull.dat and strain_lock.dat
          (a run of bin/drawbead), for the comparison; MODEL_JSON gives the
          thickness, the half-length and the bead's half-width.
compare   prints a table: each number of both files and the ratio
          first / second (columns headed LABEL1, LABEL2; default program,
          continuum), e.g. two continuum meshes; a line under it says
          when the continuum's state was not a sheet in the tools (its
          numbers from then on left out).

Exit status 0; 2 on a missing or unreadable file.
"""

import json
import math
import os
import re
import subprocess
import sys

NAN = float('nan')


def fail(msg):
    """Print 'continuum_results.py: MSG' on stderr and exit 2."""
    sys.stderr.write('continuum_results.py: %s\n' % msg)
    sys.exit(2)


def es(v):
    """A number as the program writes it: 1x, es24.16e3 (NaN for none)."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return ' ' + 'NaN'.rjust(24)
    m, e = ('%.16E' % v).split('E')
    return ' ' + ('%sE%+04d' % (m, int(e))).rjust(24)


def write_table(path, header, rows):
    """Write a column file: '#' header lines, then one row per item."""
    with open(path, 'w') as f:
        for line in header:
            f.write('# ' + line + '\n')
        for r in rows:
            f.write(''.join(es(v) for v in r) + '\n')


# ---------------------------------------------------------------------------
# Reading CalculiX's output
# ---------------------------------------------------------------------------

def read_dat(path):
    """Blocks of a .dat file: {time: {'RF:SET': (fx, fy), 'U': {node: (ux, uy)},
    'PEEQ': {elem: max over its integration points}}}."""
    out = {}
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail('cannot read %s: %s' % (path, e))
    head = re.compile(r'^\s*(total force|displacements|equivalent plastic strain|'
                      r'global coordinates|forces).*?for set (\S+) and time\s+(\S+)')
    i, n = 0, len(lines)
    while i < n:
        m = head.match(lines[i])
        if not m:
            i += 1
            continue
        kind, name, t = m.group(1), m.group(2), float(m.group(3))
        blk = out.setdefault(t, {})
        i += 1
        rows = []
        while i < n and not head.match(lines[i]):
            w = lines[i].split()
            if w:
                rows.append(w)
            i += 1
        if kind == 'total force':
            blk['RF:' + name] = (float(rows[0][0]), float(rows[0][1]))
        elif kind == 'displacements':
            blk['U'] = {int(r[0]): (float(r[1]), float(r[2])) for r in rows}
        elif kind == 'equivalent plastic strain':
            pe = blk.setdefault('PEEQ', {})
            for r in rows:
                e = int(r[0])
                pe[e] = max(pe.get(e, 0.0), float(r[2]))
    return out


def read_sta(path):
    """Increments of a .sta file: [(total time, iterations of all attempts)]
    for the converged increments, in order."""
    res, pending = [], 0
    try:
        with open(path) as f:
            for line in f:
                w = line.split()
                if len(w) != 7 or not w[0].isdigit():
                    continue
                pending += int(w[3])
                if not w[2].endswith('U'):
                    res.append((float(w[4]), pending))
                    pending = 0
    except OSError:
        pass
    return res


# ---------------------------------------------------------------------------
# Is the continuum a sheet lying in the tools?
# ---------------------------------------------------------------------------

# a mid-surface node more than this many h above the upper tool's chain or
# below the lower tool's (the chains are where the centreline lies in
# contact): the sheet has left the tools (penetration or a gap of a
# fraction of h is contact as modelled)
OUT_OF_TOOLS_H = 1.0
# |ln lambda| or |thickness log strain| beyond this: no sheet in forming
# (a thinning or stretch by the factor e)
ABSURD_LOG_STRAIN = 1.0


def state_problem(info, blk, t):
    """None if the state at time t (a .dat block with U) is a sheet lying
    in the tools, else why not, in words: a mid-surface node more than
    OUT_OF_TOOLS_H h above the upper tool or below the lower one (at its
    current x, the tools' chains taken over x +- h, the lower one raised by
    the lock lift H = lock_depth min(t, 1)), or a strain beyond
    ABSURD_LOG_STRAIN."""
    h = info['thickness']
    rows = strain_rows(info, blk)
    for r in rows:
        if abs(r[4]) > ABSURD_LOG_STRAIN or abs(r[7]) > ABSURD_LOG_STRAIN:
            return ('an absurd strain at s = %.1fh: ln(lambda) = %.3g, thickness log strain %.3g'
                    % (r[0], r[4], r[7]))
    grid = info.get('tool_grid')
    if not grid:
        return None
    xs, up, lo = grid['x'], grid['upper'], grid['lower']
    dx = xs[1] - xs[0]
    lift = info['lock_depth'] * min(t, 1.0)
    X = {int(k): v for k, v in info['node_x'].items()}
    Y = {int(k): v for k, v in info['node_y'].items()}
    u = blk['U']
    worst = None
    for n in info['mid']:
        x, y = X[n] + u[n][0], Y[n] + u[n][1]
        k0 = min(max(int(math.floor((x - h - xs[0]) / dx)), 0), len(xs) - 1)
        k1 = min(max(int(math.ceil((x + h - xs[0]) / dx)), 0), len(xs) - 1)
        y_up = max(up[k0:k1 + 1])
        y_lo = min(lo[k0:k1 + 1]) + lift
        off = max(y - y_up, y_lo - y)
        if off > OUT_OF_TOOLS_H * h and (worst is None or off > worst[0]):
            worst = (off, X[n], 'above the upper' if y > y_up else 'below the lower')
    if worst:
        return ('the sheet at s = %.1fh stands %.1fh %s tool' % (worst[1] / h, worst[0] / h, worst[2]))
    return None


# ---------------------------------------------------------------------------
# Conversion
# ---------------------------------------------------------------------------

def strain_rows(info, blk):
    """Rows of a strain file from the displacements (and plastic strains) of
    one output time: one row per pair of neighbouring mid-surface nodes."""
    h = info['thickness']
    nx, ny = info['nx'], info['ny']
    u = blk['U']
    pe = blk.get('PEEQ', {})
    X = {int(k): v for k, v in info['node_x'].items()}
    Y = {int(k): v for k, v in info['node_y'].items()}

    def cur(n):
        return X[n] + u[n][0], Y[n] + u[n][1]

    mid, top, bot = info['mid'], info['top'], info['bottom']
    nseg = len(mid) - 1
    theta, rows = [], []
    for k in range(nseg):
        a, b = cur(mid[k]), cur(mid[k + 1])
        theta.append(math.atan2(b[1] - a[1], b[0] - a[0]))
    for k in range(1, nseg):
        while theta[k] - theta[k - 1] > math.pi:
            theta[k] -= 2 * math.pi
        while theta[k] - theta[k - 1] < -math.pi:
            theta[k] += 2 * math.pi
    ref = [0.5 * (X[mid[k]] + X[mid[k + 1]]) for k in range(nseg)]
    for k in range(nseg):
        d_ref = X[mid[k + 1]] - X[mid[k]]
        a, b = cur(mid[k]), cur(mid[k + 1])
        ds = math.hypot(b[0] - a[0], b[1] - a[1])
        lam = ds / d_ref
        ta, tb = cur(top[k]), cur(top[k + 1])
        ba, bb = cur(bot[k]), cur(bot[k + 1])
        lt = math.log(math.hypot(tb[0] - ta[0], tb[1] - ta[1]) / d_ref)
        lb = math.log(math.hypot(bb[0] - ba[0], bb[1] - ba[1]) / d_ref)
        tx, ty = (b[0] - a[0]) / ds, (b[1] - a[1]) / ds
        dx = 0.5 * (ta[0] + tb[0] - ba[0] - bb[0])
        dy = 0.5 * (ta[1] + tb[1] - ba[1] - bb[1])
        thick = abs(dx * (-ty) + dy * tx)
        k0, k1 = max(0, k - 1), min(nseg - 1, k + 1)
        rho = -(theta[k1] - theta[k0]) / (ref[k1] - ref[k0])
        ei = k // 2
        peeq = [pe[ej * nx + ei + 1] for ej in range(ny) if ej * nx + ei + 1 in pe]
        rows.append([ref[k] / h, 0.5 * (a[0] + b[0]) / h, 0.5 * (a[1] + b[1]) / h,
                     lam - 1.0, math.log(lam), lt, lb, math.log(thick / h),
                     max(peeq) if peeq else NAN, rho * h, NAN, NAN, NAN, NAN, NAN,
                     NAN, NAN, NAN, NAN])
    return rows


def program_legend(program, name):
    """The column header lines of result file name as the program writes
    them (`program --columns name`), without their '# '."""
    try:
        out = subprocess.run([program, '--columns', name], capture_output=True, text=True,
                             check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        fail('cannot get the columns of %s from %s: %s' % (name, program, e))
    return [line[2:] if line.startswith('# ') else line for line in out.splitlines() if line.strip()]


CONTINUUM_NOTE = ('CalculiX plane-strain continuum (scripts/continuum_check.sh): one row per pair '
                  'of neighbouring mid-surface nodes; NaN = not given by the continuum '
                  '(docs/continuum-check.md)')


def convert(ccx_dir, out_dir, program=None):
    """Write the four column files and continuum_summary.txt (see header)."""
    try:
        with open(os.path.join(ccx_dir, 'continuum_model.json')) as f:
            info = json.load(f)
    except (OSError, ValueError) as e:
        fail('cannot read %s/continuum_model.json: %s' % (ccx_dir, e))
    dat = read_dat(os.path.join(ccx_dir, 'continuum.dat'))
    sta = read_sta(os.path.join(ccx_dir, 'continuum.sta'))
    h, eh = info['thickness'], info['youngs_modulus'] * info['thickness']
    lock, pull = info['lock_depth'], info['pull_distance']
    title = 'continuum (CalculiX) %s' % info.get('title', '')
    times = sorted(t for t in dat if any(k.startswith('RF:') for k in dat[t]))
    lock_rows, pull_rows = [], []
    t_prev = 0.0
    for t in times:
        b = dat[t]
        n = b.get('RF:NRIGHT', (NAN, NAN))[0]
        f_punch = b.get('RF:NLOWER', (NAN, NAN))[1]
        lift = -b.get('RF:NUPPER', (NAN, NAN))[1]
        its = sum(i for (ti, i) in sta if t_prev + 1e-9 < ti <= t + 1e-9)
        if t <= 1.0 + 1e-9:
            if lock == 0.0:
                t_prev = t
                continue
            lock_rows.append([lock * t / h, f_punch / eh, f_punch, its, lock * (t - t_prev) / h,
                              NAN, NAN, n / eh, n])
        else:
            d0 = max(t_prev, 1.0)
            pull_rows.append([pull * (t - 1.0) / h, n / eh, n, its, pull * (t - d0) / h, NAN,
                              lift / eh, lift, NAN, f_punch / eh])
        t_prev = t
    os.makedirs(out_dir, exist_ok=True)
    if program is None:
        program = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                               'bin', 'drawbead')
    write_table(os.path.join(out_dir, 'lock.dat'),
                ['drawbead locking: %s' % title] + program_legend(program, 'lock.dat') + [CONTINUUM_NOTE],
                lock_rows)
    write_table(os.path.join(out_dir, 'pull.dat'),
                ['drawbead pulling: %s' % title] + program_legend(program, 'pull.dat') + [CONTINUUM_NOTE],
                pull_rows)
    strain_legend = program_legend(program, 'strain_lock.dat')
    u_times = sorted(t for t in dat if 'U' in dat[t])
    t_lock = max([t for t in u_times if t <= 1.0 + 1e-9], default=None)
    t_last = u_times[-1] if u_times else None
    for name, t, what in (('strain_lock.dat', t_lock, 'after locking'),
                          ('strain_pull.dat', t_last, 'after pulling')):
        rows = strain_rows(info, dat[t]) if t is not None else []
        write_table(os.path.join(out_dir, name), [
            'drawbead strain distribution %s: %s' % (what, title)] + strain_legend + [
            CONTINUUM_NOTE + '; time %s of 2' % ('none' if t is None else '%.6g' % t)], rows)
    # the first output time whose state is not a sheet in the tools: the
    # continuum's numbers from then on are left out of its summary
    t_bad, why = None, ''
    for t in u_times:
        why = state_problem(info, dat[t], t)
        if why:
            t_bad = t
            break
    t_end = 2.0 if pull > 0 else 1.0
    done = bool(times) and abs(times[-1] - t_end) < 1e-6
    state = ('sheet in the tools' if t_bad is None else
             'not a sheet in the tools from time %.6g: %s' % (t_bad, why))
    extra = [('continuum_state', state),
             ('status', 'completed' if done else 'no_convergence'),
             ('final_time', '%.6g' % (times[-1] if times else 0.0)),
             ('increments', str(len(sta))),
             ('newton_iterations', str(sum(i for _, i in sta))),
             ('mesh', '%d x %d CPE8R (%d per h along, %d through the thickness)'
              % (info['nx'], info['ny'], info['per_h'], info['through'])
              + ('' if info.get('contact_slope', 1e5) == 1e5 else
                 '; contact slope %.6g MPa/mm' % info['contact_slope']))]
    text = summary_text(out_dir, info, 'continuum (CalculiX): %s' % info.get('title', ''), extra,
                        valid_until=t_bad)
    with open(os.path.join(out_dir, 'continuum_summary.txt'), 'w') as f:
        f.write(text)


# ---------------------------------------------------------------------------
# The compared numbers
# ---------------------------------------------------------------------------

def read_rows(path):
    """The numeric rows of a column file (NaN kept); [] if it is missing."""
    rows = []
    try:
        with open(path) as f:
            for line in f:
                if line.startswith('#') or not line.strip():
                    continue
                rows.append([float(x) for x in line.split()])
    except OSError:
        pass
    return rows


def interp(xs, ys, x):
    """Linear interpolation of ys(xs) at x (None outside the range)."""
    for k in range(1, len(xs)):
        if xs[k - 1] <= x <= xs[k] + 1e-12:
            if xs[k] == xs[k - 1]:
                return ys[k]
            return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1])
    return None


def summary_text(run_dir, info, title, extra=(), valid_until=None):
    """The compared numbers of a run folder as 'key = value' lines.

    punch force at 98% of the lock depth and at full lock (lock.dat),
    sheet tension N at the end of locking and at 98% of the lock depth
    (where the binder faces do not yet squeeze the sheet), the largest restraining force
    and the pull at which it occurs (vertex of the parabola through the
    largest row and its neighbours), the peak mid-surface strain lambda-1
    after locking and the straight-part strain: the median of lambda-1
    over the stations whose current |x| is more than 1h outside the bead
    (|x| > bead half-width + h) and whose |s| is more than 1h inside the
    sheet's ends.

    valid_until: a time (locking 0..1, pulling 1..2) from which the run's
    state is not a sheet in the tools (a continuum that went wrong): the
    rows from then on are left out, and the strains after locking too
    if it is 1 or less."""
    h, eh = info['thickness'], info['youngs_modulus'] * info['thickness']
    lock = read_rows(os.path.join(run_dir, 'lock.dat'))
    pull = read_rows(os.path.join(run_dir, 'pull.dat'))
    strain = read_rows(os.path.join(run_dir, 'strain_lock.dat'))
    if valid_until is not None:
        tol = 1e-9
        if info['lock_depth'] > 0:
            lock = [r for r in lock if r[0] * h / info['lock_depth'] < valid_until - tol]
        if info['pull_distance'] > 0:
            pull = [r for r in pull if 1.0 + r[0] * h / info['pull_distance'] < valid_until - tol]
        if valid_until <= 1.0 + tol:
            strain = []
    vals = []
    full = info['lock_depth'] / h
    if lock:
        xs, fs = [r[0] for r in lock], [r[2] for r in lock]
        f98 = interp(xs, fs, 0.98 * full)
        vals += [('punch_force_98_N_per_mm', f98),
                 ('punch_force_98_over_Eh', None if f98 is None else f98 / eh),
                 ('punch_force_full_lock_N_per_mm',
                  fs[-1] if abs(xs[-1] - full) < 1e-6 * max(1.0, full) else None),
                 ('lock_tension_N_per_mm', lock[-1][8]),
                 ('lock_tension_over_Eh', lock[-1][8] / eh),
                 ('lock_tension_98_N_per_mm', interp(xs, [r[8] for r in lock], 0.98 * full)),
                 ('lock_reached_over_h', xs[-1])]
    else:
        vals += [(k, None) for k in ('punch_force_98_N_per_mm', 'punch_force_98_over_Eh',
                                     'punch_force_full_lock_N_per_mm', 'lock_tension_N_per_mm',
                                     'lock_tension_over_Eh', 'lock_tension_98_N_per_mm',
                                     'lock_reached_over_h')]
    if pull:
        ds, ns = [r[0] for r in pull], [r[2] for r in pull]
        k = max(range(len(ns)), key=lambda i: ns[i])
        d_pk, n_pk = ds[k], ns[k]
        if 0 < k < len(ns) - 1:
            x0, x1, x2 = ds[k - 1], ds[k], ds[k + 1]
            y0, y1, y2 = ns[k - 1], ns[k], ns[k + 1]
            den = (x0 - x1) * (x0 - x2) * (x1 - x2)
            a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / den
            b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / den
            # the vertex, kept between the outer two points; a vertex
            # more than 0.5% above the largest row comes from a dip of a
            # noisy force next to it (unevenly spaced rows), and the row
            # itself is kept
            if a < 0:
                dv = min(max(-b / (2 * a), x0), x2)
                nv = y0 + (a * (dv ** 2 - x0 ** 2) + b * (dv - x0))
                if nv <= 1.005 * y1:
                    d_pk, n_pk = dv, nv
        # the lift (pull.dat column 8, N/mm): at the largest restraining
        # force and at 0.5h, 1h and 2h of pull (where the run got there)
        lifts = [r[7] for r in pull]
        vals += [('max_restraining_force_N_per_mm', n_pk),
                 ('max_restraining_force_over_Eh', n_pk / eh),
                 ('max_restraining_force_at_delta_over_h', d_pk),
                 ('max_restraining_force_is_last_row', 'yes' if k == len(ns) - 1 else 'no'),
                 ('final_delta_over_h', ds[-1]),
                 ('lift_at_max_restraining_N_per_mm', interp(ds, lifts, d_pk)),
                 ('lift_at_half_h_N_per_mm', interp(ds, lifts, 0.5)),
                 ('lift_at_1h_N_per_mm', interp(ds, lifts, 1.0)),
                 ('lift_at_2h_N_per_mm', interp(ds, lifts, 2.0))]
    else:
        vals += [(k, None) for k in ('max_restraining_force_N_per_mm',
                                     'max_restraining_force_over_Eh',
                                     'max_restraining_force_at_delta_over_h',
                                     'max_restraining_force_is_last_row', 'final_delta_over_h',
                                     'lift_at_max_restraining_N_per_mm', 'lift_at_half_h_N_per_mm',
                                     'lift_at_1h_N_per_mm', 'lift_at_2h_N_per_mm')]
    if strain:
        lim_x = info['bead_half_width'] / h + 1.0
        lim_s = info['half_length'] / h - 1.0
        peak = max(r[3] for r in strain)
        flat = sorted(r[3] for r in strain if abs(r[1]) > lim_x and abs(r[0]) < lim_s)
        med = None
        if flat:
            m = len(flat)
            med = flat[m // 2] if m % 2 else 0.5 * (flat[m // 2 - 1] + flat[m // 2])
        peak_s = [r[0] for r in strain if r[3] == peak][0]
        vals += [('peak_strain_lock', peak), ('peak_strain_lock_at_s_over_h', peak_s),
                 ('straight_strain_lock', med)]
    else:
        vals += [('peak_strain_lock', None), ('peak_strain_lock_at_s_over_h', None),
                 ('straight_strain_lock', None)]
    out = ['# drawbead continuum summary: %s' % title]
    for k, v in list(vals) + list(extra):
        if v is None or (isinstance(v, float) and math.isnan(v)):
            s = 'none'
        elif isinstance(v, str):
            s = v
        else:
            s = es(v).strip()
        out.append('%s = %s' % (k, s))
    return '\n'.join(out) + '\n'


def read_summary(path):
    """'key = value' lines of a summary as an ordered list of pairs."""
    res = []
    try:
        with open(path) as f:
            for line in f:
                if line.startswith('#') or '=' not in line:
                    continue
                k, v = line.split('=', 1)
                res.append((k.strip(), v.strip()))
    except OSError as e:
        fail('cannot read %s: %s' % (path, e))
    return res


def compare(prog_path, cont_path, labels=('program', 'continuum')):
    """Print the table first / second of two summaries (column headings labels)."""
    p, c = dict(read_summary(prog_path)), read_summary(cont_path)
    print('%-40s %16s %16s %10s' % ('quantity', labels[0], labels[1], 'ratio'))
    notes = []
    for k, cv in c:
        if k == 'continuum_state':
            if cv != 'sheet in the tools':
                notes.append('# %s: %s; its numbers from then on are left out (none)' % (labels[1], cv))
            continue
        if k not in p:
            continue
        pv = p[k]
        try:
            ratio = '%10.4f' % (float(pv) / float(cv))
        except (ValueError, ZeroDivisionError):
            ratio = '%10s' % '-'
        print('%-40s %16s %16s %s' % (k, short(pv), short(cv), ratio))
    for line in notes:
        print(line)


def short(v):
    """A value for the table: 6 significant digits when a number."""
    try:
        return '%.6g' % float(v)
    except ValueError:
        return v


def main(argv):
    """Command line: see the module header."""
    if len(argv) == 3 and argv[0] == 'convert':
        convert(argv[1], argv[2])
    elif len(argv) == 5 and argv[0] == 'convert' and argv[3] == '--program':
        convert(argv[1], argv[2], argv[4])
    elif len(argv) in (3, 5) and argv[0] == 'metrics':
        try:
            with open(argv[2]) as f:
                info = json.load(f)
        except (OSError, ValueError) as e:
            fail('cannot read %s: %s' % (argv[2], e))
        title = argv[4] if len(argv) == 5 and argv[3] == '--title' else argv[1]
        sys.stdout.write(summary_text(argv[1], info, title))
    elif len(argv) in (3, 5) and argv[0] == 'compare':
        compare(argv[1], argv[2], tuple(argv[3:5]) or ('program', 'continuum'))
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
