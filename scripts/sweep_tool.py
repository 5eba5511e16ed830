#!/usr/bin/env python3
"""sweep_tool.py -- the python half of scripts/sweep.sh (scripts/bead_tool.py,
the half of scripts/bead_curves.sh, uses its deck and result readers).

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


def main(argv):
    if len(argv) < 2 or argv[1] in ('-h', '--help'):
        sys.stdout.write(__doc__)
        return 0 if len(argv) >= 2 else 2
    cmd, args = argv[1], argv[2:]
    if cmd == 'decks':
        cmd_decks(args)
    elif cmd == 'collect':
        return cmd_collect(args)
    else:
        die("unknown subcommand '%s'" % cmd)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
