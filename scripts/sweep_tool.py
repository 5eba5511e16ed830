#!/usr/bin/env python3
"""sweep_tool.py -- the python half of scripts/sweep.sh and scripts/bead_curves.sh.

Subcommands:

  decks OUTDIR VARIABLES BASE.nml VAR=V1,V2,... [VAR=...]
      VARIABLES is the output of `drawbead --list-variables` (one line per
      deck variable: group, name, type). Write one deck per combination of the values (cartesian product, the
      first variable varying slowest) into OUTDIR/decks/case_NNNN.nml, by
      overriding the named namelist variables of the base deck; write the
      list of deck paths (absolute, one per line, line k+1 for case k) to
      OUTDIR/decks.txt and the swept values to OUTDIR/cases.tsv. Prints the
      number of decks. Exit status 2 on a usage error (unknown variable,
      empty value list, unreadable deck).

  collect OUTDIR [--interrupted SIGNAL]
      Build OUTDIR/table.txt from cases.tsv, status.tsv (each case's
      status, written by scripts/lib.sh's write_statuses) and
      OUTDIR/runs/<case>/ (summary.txt, run.log) and print it. A run
      that completed, tore or localized is a result (RESULT_STATUSES); a
      run that failed keeps its row, with its status (bad_input,
      no_convergence, ...) and the program's first error message in a
      '#' line below the table. With --interrupted, the table's first
      line says that SIGNAL stopped the sweep (its stopped runs have
      status interrupted, the rest not_run). Exit status 1 if any case
      failed or has not run yet.

  curves SWEEPDIR OUTDIR [--no-origin]
      Equivalent-bead load curves from a sweep over lock_depth: for each
      combination of the other swept variables, two-column tables
      (restraining force and lift force per unit bead length, N/mm, against
      the lock depth, mm; the closing force F(H) of the deepest run) and an
      LS-DYNA keyword file with the first two as *DEFINE_CURVE_TITLE. See
      scripts/bead_curves.sh.

Overriding a variable: the group holding it in the base deck is used (its
value replaced in place, comments kept); a variable the base deck does not
set is added to its group (from the program's list of variables), and a
missing group is appended. Text values are
quoted if they are not already; logicals may be given as true/false.
"""

import itertools
import os
import re
import sys

# Variable -> (namelist group, type), from the program's own list
# (bin/drawbead --list-variables, read by read_variables)
VARIABLES = {}
TYPES = ('real', 'integer', 'logical', 'text')

# the statuses of summary.txt that are results (the run went to its end,
# or to where the sheet tears: the program's exit status 0), not failures
RESULT_STATUSES = ('completed', 'torn', 'localized')

# the columns of table.txt after the swept variables
RESULT_KEYS = ['steady_force_over_Eh', 'peak_force_over_Eh', 'final_lift_over_Eh',
               'delta_cr_over_h', 'max_thinning']


def die(msg, status=2):
    sys.stderr.write('sweep: %s\n' % msg)
    sys.exit(status)


def read_variables(path):
    """Fill VARIABLES from the program's list of deck variables: lines
    'group variable type', type one of TYPES."""
    try:
        with open(path) as f:
            lines = [ln.split() for ln in f if ln.strip()]
    except OSError as e:
        die('cannot read the list of deck variables %s: %s' % (path, e.strerror))
    for fields in lines:
        if len(fields) != 3 or fields[2] not in TYPES:
            die("the program's list of deck variables (%s) has a line '%s', not "
                "'group variable type'" % (path, ' '.join(fields)))
        VARIABLES[fields[1]] = (fields[0], fields[2])
    if not VARIABLES:
        die("the program's list of deck variables (%s) is empty" % path)


def unknown_variable(var):
    die("unknown variable '%s': not in the base deck, and not one of %s"
        % (var, ', '.join(sorted(VARIABLES))))


# ---------------------------------------------------------------------------
# Namelist text
# ---------------------------------------------------------------------------
class Group:
    """A namelist group of a deck: its name and the character span of its
    body (from after '&name' to the closing '/', exclusive)."""

    def __init__(self, name, start, body_start, end):
        self.name = name          # lower case, without '&'
        self.start = start        # index of '&'
        self.body_start = body_start
        self.end = end            # index of the closing '/'


def scan(text, start=0, stop=None):
    """Yield (index, char) of the characters of text[start:stop] that are
    outside quoted strings and '!' comments."""
    stop = len(text) if stop is None else stop
    i = start
    quote = None
    while i < stop:
        c = text[i]
        if quote:
            if c == quote:
                if i + 1 < stop and text[i + 1] == quote:   # doubled quote
                    i += 2
                    continue
                quote = None
            i += 1
            continue
        if c in '\'"':
            quote = c
            i += 1
            continue
        if c == '!':
            while i < stop and text[i] != '\n':
                i += 1
            continue
        yield i, c
        i += 1


def find_groups(text):
    groups = []
    it = scan(text)
    for i, c in it:
        if c != '&':
            continue
        m = re.match(r'&([A-Za-z_][A-Za-z0-9_]*)', text[i:])
        if not m:
            continue
        name = m.group(1).lower()
        body_start = i + m.end()
        end = None
        for j, d in it:
            if j < body_start:
                continue
            if d == '/':
                end = j
                break
        if end is None:
            die("group &%s has no closing '/'" % name)
        groups.append(Group(name, i, body_start, end))
    return groups


def find_assignment(text, group, var):
    """The span (start, end) of the value assigned to var in group, or None."""
    pat = re.compile(r'(?<![A-Za-z0-9_])' + re.escape(var) + r'\s*=', re.IGNORECASE)
    outside = {i for i, _ in scan(text, group.body_start, group.end)}
    for m in pat.finditer(text, group.body_start, group.end):
        if m.start() not in outside:
            continue
        # the value: a quoted string or a run of characters up to a blank,
        # a comma, a '/', a '!' or a line end
        k = m.end()
        while k < group.end and text[k] in ' \t':
            k += 1
        if k < group.end and text[k] in '\'"':
            q = text[k]
            e = k + 1
            while e < len(text):
                if text[e] == q:
                    if e + 1 < len(text) and text[e + 1] == q:
                        e += 2
                        continue
                    break
                e += 1
            return k, e + 1
        e = k
        while e < group.end and text[e] not in ' \t,/!\n\r':
            e += 1
        return k, e
    return None


def format_value(var, value):
    v = value.strip()
    kind = VARIABLES.get(var, ('', ''))[1]
    if kind == 'text':
        if len(v) >= 2 and v[0] == v[-1] and v[0] in '\'"':
            return v
        return "'" + v.replace("'", "''") + "'"
    if kind == 'logical':
        low = v.lower()
        if low in ('true', 't', 'yes', '1', '.true.'):
            return '.true.'
        if low in ('false', 'f', 'no', '0', '.false.'):
            return '.false.'
    return v


def override(text, var, value):
    """Return text with var set to value (already formatted)."""
    groups = find_groups(text)
    for g in groups:
        span = find_assignment(text, g, var)
        if span:
            return text[:span[0]] + value + text[span[1]:]
    if var not in VARIABLES:
        unknown_variable(var)
    group = VARIABLES[var][0]
    for g in groups:
        if g.name == group:
            # insert on its own line before the closing '/'
            line_start = text.rfind('\n', 0, g.end) + 1
            if text[line_start:g.end].strip() == '':
                return text[:line_start] + '   %s = %s\n' % (var, value) + text[line_start:]
            return text[:g.end] + '\n   %s = %s\n' % (var, value) + text[g.end:]
    if not text.endswith('\n'):
        text += '\n'
    return text + '&%s\n   %s = %s\n/\n' % (group, var, value)


def deck_value(text, var):
    """The value of var in the deck text (as written), or None."""
    for g in find_groups(text):
        span = find_assignment(text, g, var)
        if span:
            return text[span[0]:span[1]]
    return None


def cmd_decks(args):
    if len(args) < 4:
        die('usage: sweep_tool.py decks OUTDIR VARIABLES BASE.nml VAR=V1,V2,... ...')
    outdir, base = args[0], args[2]
    read_variables(args[1])
    try:
        with open(base) as f:
            base_text = f.read()
    except OSError as e:
        die('cannot read the base deck %s: %s' % (base, e.strerror))
    find_groups(base_text)          # a malformed base deck stops here
    names, lists = [], []
    for spec in args[3:]:
        if '=' not in spec:
            die("'%s' is not VAR=V1,V2,..." % spec)
        var, values = spec.split('=', 1)
        var = var.strip().lower()
        if not re.fullmatch(r'[a-z_][a-z0-9_]*', var):
            die("'%s' is not a variable name" % var)
        if var in names:
            die("variable '%s' given twice" % var)
        if var == 'output_dir':
            die('output_dir cannot be swept: each case writes to OUTDIR/runs/<case>')
        vals = [v.strip() for v in values.split(',')]
        if not values.strip() or any(v == '' for v in vals):
            die("empty value in '%s'" % spec)
        if deck_value(base_text, var) is None and var not in VARIABLES:
            unknown_variable(var)
        names.append(var)
        lists.append(vals)

    deckdir = os.path.join(outdir, 'decks')
    os.makedirs(deckdir, exist_ok=True)
    for old in os.listdir(deckdir):
        if re.fullmatch(r'case_\d+\.nml', old):
            os.remove(os.path.join(deckdir, old))
    base_title = deck_value(base_text, 'title')
    if base_title and base_title[0] in '\'"':
        base_title = base_title[1:-1]
    paths, rows = [], []
    for k, combo in enumerate(itertools.product(*lists)):
        case = 'case_%04d' % k
        text = base_text
        for var, val in zip(names, combo):
            text = override(text, var, format_value(var, val))
        if 'title' not in names:
            tag = ' '.join('%s=%s' % (n, v) for n, v in zip(names, combo))
            title = ('%s [%s %s]' % (base_title or 'sweep', case, tag))[:255]
            text = override(text, 'title', format_value('title', title))
        header = ('! %s: generated by scripts/sweep.sh from %s\n! %s\n'
                  % (case, base, ', '.join('%s = %s' % (n, v) for n, v in zip(names, combo))))
        path = os.path.abspath(os.path.join(deckdir, case + '.nml'))
        with open(path, 'w') as f:
            f.write(header + text)
        paths.append(path)
        rows.append([case] + list(combo))
    with open(os.path.join(outdir, 'decks.txt'), 'w') as f:
        f.write(''.join(p + '\n' for p in paths))
    with open(os.path.join(outdir, 'cases.tsv'), 'w') as f:
        f.write('\t'.join(['case'] + names) + '\n')
        for r in rows:
            f.write('\t'.join(r) + '\n')
    print(len(paths))


# ---------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------
def read_summary(path):
    vals = {}
    try:
        with open(path) as f:
            for line in f:
                if '=' in line and not line.startswith('#'):
                    k, v = line.split('=', 1)
                    vals[k.strip()] = v.strip()
    except OSError:
        return None
    return vals


def read_cases(outdir):
    path = os.path.join(outdir, 'cases.tsv')
    try:
        with open(path) as f:
            lines = [ln.rstrip('\n') for ln in f if ln.strip()]
    except OSError:
        die('no %s: not a sweep folder (or the decks were never written)' % path)
    names = lines[0].split('\t')[1:]
    cases = [ln.split('\t') for ln in lines[1:]]
    return names, cases


def read_statuses(outdir):
    """case -> status of each run, from OUTDIR/status.tsv (written by
    write_statuses of scripts/lib.sh, which names the exit statuses)."""
    path = os.path.join(outdir, 'status.tsv')
    try:
        with open(path) as f:
            return dict(ln.rstrip('\n').split('\t', 1) for ln in f if '\t' in ln)
    except OSError:
        die('no %s: run the sweep through scripts/sweep.sh' % path)


def run_result(outdir, case, statuses):
    """(status, summary dict or None, first error line or '') of one case."""
    rundir = os.path.join(outdir, 'runs', case)
    summ = read_summary(os.path.join(rundir, 'summary.txt'))
    status = statuses.get(case, 'not_run')
    err = ''
    try:
        with open(os.path.join(rundir, 'run.log'), errors='replace') as f:
            for line in f:
                if '*ERROR*' in line:
                    err = line.strip()
                    break
    except OSError:
        pass
    if status.startswith('failed_exit_') and not err:
        err = ('the program stopped with exit status %s (crash or signal?)'
               % status[len('failed_exit_'):])
    return status, summ, err


def fmt_num(s):
    if s is None or s == '':
        return '-'
    try:
        x = float(s)
    except ValueError:
        return s
    return '%.6g' % x


def table_value(v):
    return v if v and not any(c.isspace() for c in v) else "'%s'" % v


def cmd_collect(args):
    interrupted = None
    if len(args) == 3 and args[1] == '--interrupted':
        interrupted = args[2]
        args = args[:1]
    if len(args) != 1:
        die('usage: sweep_tool.py collect OUTDIR [--interrupted SIGNAL]')
    outdir = args[0]
    names, cases = read_cases(outdir)
    statuses = read_statuses(outdir)
    header = ['case'] + names + RESULT_KEYS + ['status']
    rows, notes, not_run, stopped = [], [], [], []
    failed = 0
    for c in cases:
        status, summ, err = run_result(outdir, c[0], statuses)
        vals = [fmt_num((summ or {}).get(k)) for k in RESULT_KEYS]
        rows.append([c[0]] + [table_value(v) for v in c[1:]] + vals + [status])
        if status == 'not_run':
            not_run.append(c[0])
        elif status == 'interrupted' and interrupted:
            stopped.append(c[0])
        elif status not in RESULT_STATUSES:
            failed += 1
            where = os.path.join(outdir, 'runs', c[0], 'run.log')
            notes.append('# %s: %s: %s (log: %s)' % (c[0], status, err or 'no error message', where))
    if stopped:
        notes.append('# stopped by %s (status interrupted, results so far in their folders): %s'
                     % (interrupted, ', '.join(stopped)))
    if not_run:
        notes.append('# not run (no exit_status yet): %s' % ', '.join(not_run))
    widths = [max(len(r[i]) for r in [header] + rows) for i in range(len(header))]
    widths[0] = max(widths[0], len('# case'))
    lines = []
    if interrupted:
        lines.append('# INTERRUPTED: %s stopped the sweep: %d of %d cases finished, %d stopped, '
                     '%d not run' % (interrupted, len(cases) - len(stopped) - len(not_run),
                                     len(cases), len(stopped), len(not_run)))
    lines.append('# drawbead sweep: %d cases, %d failed, %d not run; columns: the swept values, '
                 'then summary.txt keys' % (len(cases), failed, len(not_run)))
    head = ['# case'] + header[1:]
    lines.append('  '.join(h.ljust(w) for h, w in zip(head, widths)).rstrip())
    for r in rows:
        lines.append('  '.join(v.ljust(w) for v, w in zip(r, widths)).rstrip())
    lines += notes
    text = '\n'.join(lines) + '\n'
    with open(os.path.join(outdir, 'table.txt'), 'w') as f:
        f.write(text)
    sys.stdout.write(text)
    return 1 if failed or not_run or stopped else 0


# ---------------------------------------------------------------------------
# Equivalent-bead curves
# ---------------------------------------------------------------------------
def read_table(path, columns):
    """The given 0-based columns of a drawbead .dat file as tuples of floats,
    one per data row ('#' lines and blank lines skipped); [] if the file is
    missing or a row is short or not numeric."""
    rows = []
    try:
        with open(path) as f:
            for line in f:
                if line.startswith('#') or not line.strip():
                    continue
                c = line.split()
                rows.append(tuple(float(c[i]) for i in columns))
    except (OSError, ValueError, IndexError):
        return []
    return rows


def read_pull(rundir):
    """Rows (delta/h, N/(E h), N [N/mm], lift/(E h), lift [N/mm]) of pull.dat."""
    return read_table(os.path.join(rundir, 'pull.dat'), (0, 1, 2, 6, 7))


def read_closing(rundir):
    """(H [mm], F [N/mm]) of lock.dat, H from H/h and the thickness echoed
    at the top of run.log; [] if either is missing."""
    h = None
    try:
        with open(os.path.join(rundir, 'run.log'), errors='replace') as f:
            for line in f:
                m = re.match(r'\s*THICKNESS\s*=\s*([-+0-9.EeDd]+)', line)
                if m:
                    h = float(m.group(1).replace('D', 'E').replace('d', 'e'))
                    break
    except (OSError, ValueError):
        return []
    if h is None:
        return []
    return [(hh * h, f) for hh, f in read_table(os.path.join(rundir, 'lock.dat'), (0, 2))]


def window_mean(rows, col, lo, hi):
    """Mean of column col over lo <= delta/h <= hi (trapezoidal in delta)."""
    pts = [(r[0], r[col]) for r in rows if lo - 1e-9 <= r[0] <= hi + 1e-9]
    if len(pts) == 1:
        return pts[0][1]
    if not pts:
        return None
    area = sum(0.5 * (y0 + y1) * (x1 - x0) for (x0, y0), (x1, y1) in zip(pts, pts[1:]))
    width = pts[-1][0] - pts[0][0]
    return area / width if width > 0 else sum(p[1] for p in pts) / len(pts)


def bead_point(summ, rows):
    """(restraining force, lift force) in N/mm and 'steady' or 'peak', from a
    run's summary values and pull.dat rows; None if there is no pulling."""
    eh = [r[2] / r[1] for r in rows if r[1] != 0.0]
    if not eh:
        return None
    eh = sorted(eh)[len(eh) // 2]              # E h, N/mm
    steady = summ.get('steady_force_over_Eh', 'none')
    at = summ.get('steady_reached_at_delta_over_h', 'none')
    if steady != 'none' and at != 'none':
        at = float(at)
        lift = window_mean(rows, 4, at - 2.0, at)
        if lift is not None:
            return float(steady) * eh, lift, 'steady'
    peak = max(rows, key=lambda r: r[1])
    return peak[1] * eh, peak[4], 'peak'


def lsdyna_curve(lcid, title, points):
    out = ['*DEFINE_CURVE_TITLE', title[:80],
           '$#    lcid      sidr       sfa       sfo      offa      offo    dattyp',
           '%10d%10d%10.4g%10.4g%10.4g%10.4g%10d' % (lcid, 0, 1.0, 1.0, 0.0, 0.0, 0),
           '$#                a1                  o1']
    for x, y in points:
        out.append('%20.8g%20.8g' % (x, y))
    return out


def cmd_curves(args):
    origin = True
    lcid0 = 1
    rest = []
    for a in args:
        if a == '--no-origin':
            origin = False
        elif a.startswith('--lcid='):
            lcid0 = int(a.split('=', 1)[1])
        else:
            rest.append(a)
    if len(rest) != 2:
        die('usage: sweep_tool.py curves SWEEPDIR OUTDIR [--no-origin] [--lcid=N]')
    sweepdir, outdir = rest
    names, cases = read_cases(sweepdir)
    statuses = read_statuses(sweepdir)
    if 'lock_depth' not in names:
        die('%s is not a sweep over lock_depth (swept: %s)' % (sweepdir, ', '.join(names) or 'nothing'))
    ilock = names.index('lock_depth')
    others = [n for n in names if n != 'lock_depth']
    groups = {}
    for c in cases:
        key = tuple(v for n, v in zip(names, c[1:]) if n != 'lock_depth')
        groups.setdefault(key, []).append(c)
    os.makedirs(outdir, exist_ok=True)
    written = []
    keyword = ['*KEYWORD',
               '$ Equivalent drawbead curves from a drawbead sweep (%s)' % os.path.abspath(sweepdir),
               '$ units: mm, N (force per unit bead length N/mm against penetration mm)']
    lcid = lcid0
    skipped = []
    for key in sorted(groups):
        tag = '_'.join('%s-%s' % (n, re.sub(r'[^A-Za-z0-9.+-]', '', v)) for n, v in zip(others, key))
        desc = ', '.join('%s = %s' % (n, v) for n, v in zip(others, key))
        rf, nf, used_peak, torn = [], [], [], []
        for c in groups[key]:
            depth = float(c[1 + ilock])
            status, summ, _ = run_result(sweepdir, c[0], statuses)
            if summ is None or status not in RESULT_STATUSES:
                skipped.append('%s (lock_depth = %s): %s' % (c[0], c[1 + ilock], status))
                continue
            point = bead_point(summ, read_pull(os.path.join(sweepdir, 'runs', c[0])))
            if point is None:
                skipped.append('%s (lock_depth = %s): no pulling results' % (c[0], c[1 + ilock]))
                continue
            if point[2] == 'peak':
                used_peak.append('%g' % depth)
            if status in ('localized', 'torn'):
                torn.append('%g' % depth)
            rf.append((depth, point[0]))
            nf.append((depth, point[1]))
        if not rf:
            continue
        # the closing force F(H) while locking, from the deepest run
        deepest = max(groups[key], key=lambda c: float(c[1 + ilock]))
        closing = read_closing(os.path.join(sweepdir, 'runs', deepest[0]))
        rf.sort()
        nf.sort()
        if origin and rf[0][0] > 0:
            rf.insert(0, (0.0, 0.0))
            nf.insert(0, (0.0, 0.0))
        src = ('steady_force_over_Eh (summary.txt) times E h at every depth' if not used_peak else
               'steady_force_over_Eh where present, else peak_force_over_Eh: peak used at '
               'lock_depth = %s mm (no steady state)' % ', '.join(used_peak))
        common = ['# from the sweep %s%s' % (os.path.abspath(sweepdir), (' (%s)' % desc) if desc else ''),
                  '# per unit bead length (the plane-strain results are per unit width)']
        if torn:
            common.append('# the sheet tore or localized at lock_depth = %s mm (the force up to '
                          'there): see delta_cr_over_h in the sweep table' % ', '.join(torn))
        if origin and rf[0] == (0.0, 0.0):
            common.append('# first point (0, 0) added: no penetration, no bead force (--no-origin leaves it out)')
        suffix = ('_' + tag) if tag else ''
        f1 = os.path.join(outdir, 'restraining%s.txt' % suffix)
        f2 = os.path.join(outdir, 'lift%s.txt' % suffix)
        with open(f1, 'w') as f:
            f.write('# equivalent drawbead: restraining force per unit bead length vs penetration\n')
            f.write('\n'.join(common) + '\n')
            f.write('# restraining force: %s; it includes friction\n' % src)
            f.write('# for LS-DYNA *CONTACT_DRAWBEAD LCIDRF, Radioss /INTER/TYPE8 Ft\n')
            f.write('# 1: penetration = lock_depth [mm]   2: restraining force [N/mm]\n')
            for x, y in rf:
                f.write('%14.6f %16.6f\n' % (x, y))
        with open(f2, 'w') as f:
            f.write('# equivalent drawbead: lift (normal) force per unit bead length vs penetration\n')
            f.write('\n'.join(common) + '\n')
            f.write('# lift force: the force of the sheet opening the binder (pull.dat column 8), '
                    'averaged over the steady-force window where the restraining force is the steady '
                    'one, else at the peak restraining force\n')
            f.write('# for LS-DYNA *CONTACT_DRAWBEAD LCIDNF, Radioss /INTER/TYPE8 Fn\n')
            f.write('# 1: penetration = lock_depth [mm]   2: lift force [N/mm]\n')
            for x, y in nf:
                f.write('%14.6f %16.6f\n' % (x, y))
        if closing:
            f3 = os.path.join(outdir, 'closing%s.txt' % suffix)
            with open(f3, 'w') as f:
                f.write('# equivalent drawbead: closing (punch) force per unit bead length while the '
                        'bead is pressed in\n')
                f.write('\n'.join(common[:2]) + '\n')
                f.write('# from lock.dat of %s (lock_depth = %s mm): F (column 3) against H '
                        '(column 1 times h)\n' % (deepest[0], deepest[1 + ilock]))
                f.write('# the force bending the sheet into the bead as the binder closes (LS-DYNA\'s '
                        'description of LCIDNF); lift.txt is the force during drawing\n')
                f.write('# 1: penetration = H [mm]   2: closing force [N/mm]\n')
                if origin and closing[0][0] > 0:
                    f.write('%14.6f %16.6f\n' % (0.0, 0.0))
                for x, y in closing:
                    f.write('%14.6f %16.6f\n' % (x, y))
            written.append(f3)
        keyword += ['$', '$ %s' % (desc or 'all cases'),
                    '$ LCID %d: restraining force (LCIDRF), LCID %d: normal force (LCIDNF)' % (lcid, lcid + 1)]
        keyword += lsdyna_curve(lcid, 'drawbead restraining force N/mm vs mm' + (' ' + tag if tag else ''), rf)
        keyword += lsdyna_curve(lcid + 1, 'drawbead normal force N/mm vs mm' + (' ' + tag if tag else ''), nf)
        lcid += 2
        written += [f1, f2]
    if not written:
        die('no completed runs with pulling results in %s' % sweepdir, 1)
    keyword.append('*END')
    kfile = os.path.join(outdir, 'drawbead_curves.k')
    with open(kfile, 'w') as f:
        f.write('\n'.join(keyword) + '\n')
    written.append(kfile)
    for w in written:
        print(w)
    for s in skipped:
        sys.stderr.write('bead_curves: left out %s\n' % s)


def main(argv):
    if len(argv) < 2 or argv[1] in ('-h', '--help'):
        sys.stdout.write(__doc__)
        return 0 if len(argv) >= 2 else 2
    cmd, args = argv[1], argv[2:]
    if cmd == 'decks':
        cmd_decks(args)
    elif cmd == 'collect':
        return cmd_collect(args)
    elif cmd == 'curves':
        cmd_curves(args)
    else:
        die("unknown subcommand '%s'" % cmd)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
