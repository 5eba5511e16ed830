#!/usr/bin/env python3
"""bead_tool.py -- the python half of scripts/bead_curves.sh: equivalent
beads from a sweep over lock_depth (see scripts/bead_curves.sh --help).

Subcommands:

  companions SWEEPDIR
      Write the frictionless companion of every case of the sweep whose
      friction is not 0 (or whose friction_law is not 'coulomb'): its deck
      with friction = 0 (and friction_law = 'coulomb'), one per combination
      of the swept values other than friction (cases that differ only in
      friction share it), into SWEEPDIR/frictionless/decks/<case>.nml
      (named after the first such case), the list of these decks into
      SWEEPDIR/frictionless/decks.txt, and SWEEPDIR/frictionless/
      companions.tsv: one line "case<TAB>run folder of its companion"
      (relative to SWEEPDIR: frictionless/runs/<case>, or runs/<case> for
      a case whose friction is already 0). Prints the companion decks that
      must be run: new or changed decks, and decks whose run has no
      exit_status.

  curves SWEEPDIR OUTDIR [--no-origin] [--lcid=N] [--depth=D]
                         [--bead-nodes=ID] [--blank=ID]
      For each combination of the swept variables other than lock_depth:
      the curves (total and bending restraining force, lift, closing
      force), the table of both restraining forces with the effective
      friction coefficient, and the cards: LS-DYNA (*PARAMETER,
      *DEFINE_CURVE_TITLE, *CONTACT_DRAWBEAD) and Radioss (/INTER/TYPE8,
      /FUNCT). D is the working penetration (mm) the cards are written
      for (default: the deepest depth of the sweep). Exit status 1 if no
      run gave a curve point, 2 on a usage error (such as D outside the
      swept depths).

Field layouts (fixed columns, checked against the codes' input readers;
docs/user-guide.md names the sources):
  *DEFINE_CURVE_TITLE  title (A80); LCID SIDR SFA SFO OFFA OFFO DATTYP
                       (7 x 10); then A1 O1 (2 x 20) per point
  *CONTACT_DRAWBEAD    card 1 SSID MSID SSTYP MSTYP SBOXID MBOXID SPR MPR,
                       card 2 FS FD DC VC VDC PENCHK BT DT,
                       card 3 SFS SFM SST MST SFST SFMT FSF VSF,
                       card 4 LCIDRF LCIDNF DBDTH DFSCL NUMINT (8 x 10 each)
  *PARAMETER           PRMR1 VAL1 ... (10 + 10): 'I' and the name, value
  /INTER/TYPE8/id      title (100); grnd_IDs surf_IDm (blank) Iform (4 x 10);
                       Fn Ft DEPTH Tstart Tstop (5 x 20); Fn_last Ft_last
                       (2 x 20, 0: the same force all along the bead)
  /FUNCT/id            title (100); X Y (2 x 20) per point
"""

import os
import re
import sys

import sweep_tool as st


def die(msg, status=2):
    sys.stderr.write('bead_curves: %s\n' % msg)
    sys.exit(status)


def parse_real(text):
    """A Fortran real constant of a deck (1.0, 1d-1, .5) as a float, or
    None if it is not one."""
    try:
        return float(text.strip().lower().replace('d', 'e'))
    except (ValueError, AttributeError):
        return None


# ---------------------------------------------------------------------------
# The frictionless companions
# ---------------------------------------------------------------------------
def read_decks(sweepdir):
    """case name -> deck path, from SWEEPDIR/decks.txt."""
    path = os.path.join(sweepdir, 'decks.txt')
    try:
        with open(path) as f:
            decks = [ln.strip() for ln in f if ln.strip()]
    except OSError:
        die('no %s: not a sweep folder' % path)
    return {os.path.basename(d)[:-len('.nml')]: d for d in decks}


def read_text(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        die('cannot read %s: %s' % (path, e.strerror))
    return ''


def cmd_companions(args):
    if len(args) != 1:
        die('usage: bead_tool.py companions SWEEPDIR')
    sweepdir = args[0]
    names, cases = st.read_cases(sweepdir)
    if 'lock_depth' not in names:
        die('%s is not a sweep over lock_depth (swept: %s)' % (sweepdir, ', '.join(names) or 'nothing'))
    decks = read_decks(sweepdir)
    fdir = os.path.join(sweepdir, 'frictionless')
    os.makedirs(os.path.join(fdir, 'decks'), exist_ok=True)
    others = [i for i, n in enumerate(names) if n != 'friction']
    first = {}            # swept values other than friction -> companion case
    rows, companion_decks, to_run = [], [], []
    for c in cases:
        if c[0] not in decks:
            die('case %s is not in %s/decks.txt' % (c[0], sweepdir))
        text = read_text(decks[c[0]])
        mu = st.deck_value(text, 'friction')
        law = (st.deck_value(text, 'friction_law') or "'coulomb'").strip('\'" ').lower()
        if (mu is None or parse_real(mu) == 0.0) and law == 'coulomb':
            rows.append((c[0], 'runs/' + c[0]))       # its own companion
            continue
        key = tuple(c[1 + i] for i in others)
        if key not in first:
            name = first[key] = c[0]
            new = st.override(text, 'friction', '0.0')
            if law != 'coulomb':
                # mu(p) has its bounds, a table its own mu: Coulomb with 0
                new = st.override(new, 'friction_law', "'coulomb'")
            title = st.deck_value(new, 'title')
            if title and title[0] in '\'"':
                title = title[1:-1]
            title = ('frictionless companion of %s: %s' % (name, title or 'sweep case'))[:255]
            new = st.override(new, 'title', "'" + title.replace("'", "''") + "'")
            new = ('! frictionless companion of %s (written by scripts/bead_curves.sh): '
                   'friction = 0\n' % decks[c[0]]) + new
            path = os.path.abspath(os.path.join(fdir, 'decks', name + '.nml'))
            old = None
            if os.path.exists(path):
                old = read_text(path)
            if old != new:
                with open(path, 'w') as f:
                    f.write(new)
            done = os.path.exists(os.path.join(fdir, 'runs', name, 'exit_status'))
            if old != new or not done:
                to_run.append(path)
            companion_decks.append(path)
        rows.append((c[0], 'frictionless/runs/' + first[key]))
    with open(os.path.join(fdir, 'decks.txt'), 'w') as f:
        f.write(''.join(p + '\n' for p in companion_decks))
    with open(os.path.join(fdir, 'companions.tsv'), 'w') as f:
        f.write(''.join('%s\t%s\n' % r for r in rows))
    for p in to_run:
        print(p)


# ---------------------------------------------------------------------------
# Reading the runs
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
                    h = parse_real(m.group(1))
                    break
    except OSError:
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


def bead_point(summ, rows, peak=False):
    """(restraining force, lift force) in N/mm and 'steady' or 'peak', from a
    run's summary values and pull.dat rows; None if there is no pulling.
    The steady force where the run found one (the lift averaged over the
    two thicknesses of pull before it was reached), else (or with peak)
    the peak force (and the lift of that row)."""
    eh = [r[2] / r[1] for r in rows if r[1] != 0.0]
    if not eh:
        return None
    eh = sorted(eh)[len(eh) // 2]              # E h, N/mm
    steady = summ.get('steady_force_over_Eh', 'none')
    at = summ.get('steady_reached_at_delta_over_h', 'none')
    if steady != 'none' and at != 'none' and not peak:
        at = float(at)
        lift = window_mean(rows, 4, at - 2.0, at)
        if lift is not None:
            return float(steady) * eh, lift, 'steady'
    peak = max(rows, key=lambda r: r[1])
    return peak[1] * eh, peak[4], 'peak'


def run_point(sweepdir, rel, statuses, peak=False):
    """(status, point or None) of the run in SWEEPDIR/rel (a case's run or
    its companion's); statuses: case -> status of that folder's runs;
    peak: the peak force even where the run found a steady one."""
    rundir = os.path.join(sweepdir, rel)
    status = statuses.get(os.path.basename(rel), 'not_run')
    summ = st.read_summary(os.path.join(rundir, 'summary.txt'))
    if summ is None or status not in ('completed', 'localized', 'torn'):
        return status, None
    return status, bead_point(summ, read_pull(rundir), peak)


# ---------------------------------------------------------------------------
# Cards
# ---------------------------------------------------------------------------
def field(x, width):
    """x right-justified in width characters, a blank in front, with at
    most 8 significant digits (far below the model's own error; enough to
    read the numbers back to 1e-7) and as many as fit; always readable as
    a real (a '.' or an exponent)."""
    for s in ['%.*g' % (digits, x) for digits in range(8, 0, -1)]:
        if '.' not in s and 'e' not in s and 'n' not in s:
            s += '.0' if len(s) + 2 < width else '.'
        if len(s) < width:
            return s.rjust(width)
    die('cannot write %r in %d columns' % (x, width))
    return ''


def ifield(n, width=10):
    s = str(n)
    if len(s) >= width:
        die('the id %s does not fit in %d columns' % (s, width))
    return s.rjust(width)


def interpolate(points, x):
    """Piecewise-linear value at x of points [(x, y), ...] sorted by x;
    None if x is outside them."""
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 - 1e-12 <= x <= x1 + 1e-12:
            return y0 if x1 == x0 else y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    if len(points) == 1 and abs(points[0][0] - x) <= 1e-12:
        return points[0][1]
    return None


def lsdyna_curve(lcid, title, points):
    out = ['*DEFINE_CURVE_TITLE', title[:80],
           '$     LCID      SIDR       SFA       SFO      OFFA      OFFO    DATTYP',
           ifield(lcid) + ifield(0) + field(1.0, 10) + field(1.0, 10) + field(0.0, 10)
           + field(0.0, 10) + ifield(0),
           '$                 A1                  O1']
    out += [field(x, 20) + field(y, 20) for x, y in points]
    return out


def radioss_funct(fid, title, points):
    out = ['/FUNCT/%d' % fid, title[:100],
           '#                  X                   Y']
    out += [field(x, 20) + field(y, 20) for x, y in points]
    return out


def lsdyna_cards(w):
    """The LS-DYNA keyword file of one combination (w: a dict of what is
    written, see cmd_curves)."""
    ns = '&BEADNS' if w['bead_nodes'] is None else w['bead_nodes']
    blank = '&BLANKID' if w['blank'] is None else w['blank']
    out = ['*KEYWORD',
           '$ Equivalent drawbead from the drawbead sweep %s%s' % (w['sweep'], w['desc']),
           '$ written by scripts/bead_curves.sh; the LS-DYNA 971 keyword layout (see',
           '$ docs/user-guide.md, "Equivalent beads for LS-DYNA and Radioss")',
           '$ units: mm and N: forces per unit bead length (N/mm) against the',
           '$ penetration (mm); use it in a model in mm and N (tonne and s, or ms)',
           '$',
           '$ Friction is counted once. LCIDRF (curve %d) is the BENDING part of the'
           % w['lcid'],
           '$ restraining force: the frictionless companion runs (friction = 0).',
           '$ LS-DYNA adds the contact\'s friction to it, FS times the normal force',
           '$ (LCIDNF, curve %d: the lift of the runs with friction). FS is the friction'
           % (w['lcid'] + 1),
           '$ coefficient that makes bending + FS * normal force the total restraining',
           '$ force of the runs with friction at the working penetration DBDTH = %s mm:'
           % field(w['depth'], 10).strip(),
           '$   FS = (total - bending) / lift = (%s - %s) / %s = %s'
           % tuple(field(v, 10).strip() for v in (w['total'], w['bending'], w['lift'], w['fs'])),
           '$ (the Coulomb coefficient of the sweep itself: %s; restraining_total*.txt'
           % w['mu'],
           '$ holds the total, for codes that take it whole). See bead_table*.txt for',
           '$ the effective coefficient at every depth.',
           '$']
    if w['bead_nodes'] is None or w['blank'] is None:
        out += ['$ FILL IN the placeholders of *PARAMETER (0 until you do):']
        if w['bead_nodes'] is None:
            out += ['$   BEADNS   the *SET_NODE of the nodes along the bead line (the slave',
                    '$            side, SSTYP = 4), attached to the tool that carries the bead']
        if w['blank'] is None:
            out += ['$   BLANKID  the part of the blank (the master side, MSTYP = 3; for a',
                    '$            part set make MSTYP 2)']
        out += ['*PARAMETER', '$    PRMR1      VAL1']
        if w['bead_nodes'] is None:
            out.append('%-10s%s' % ('I BEADNS', ifield(0)))
        if w['blank'] is None:
            out.append('%-10s%s' % ('I BLANKID', ifield(0)))
    out += lsdyna_curve(w['lcid'], 'drawbead bending force N/mm vs penetration mm' + w['tag'],
                        w['bending_curve'])
    out += lsdyna_curve(w['lcid'] + 1, 'drawbead normal force N/mm vs penetration mm' + w['tag'],
                        w['lift_curve'])
    out += ['*CONTACT_DRAWBEAD',
            '$     SSID      MSID     SSTYP     MSTYP    SBOXID    MBOXID       SPR       MPR',
            ifield(ns) + ifield(blank) + ifield(4) + ifield(3) + ifield(0) + ifield(0)
            + ifield(0) + ifield(0),
            '$       FS        FD        DC        VC       VDC    PENCHK        BT        DT',
            field(w['fs'], 10) + field(w['fs'], 10) + field(0.0, 10) + field(0.0, 10)
            + field(0.0, 10) + ifield(0) + field(0.0, 10) + field(1e20, 10),
            '$      SFS       SFM       SST       MST      SFST      SFMT       FSF       VSF',
            ''.join(field(v, 10) for v in (1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0)),
            '$   LCIDRF    LCIDNF     DBDTH     DFSCL    NUMINT',
            ifield(w['lcid']) + ifield(w['lcid'] + 1) + field(w['depth'], 10)
            + field(1.0, 10) + ifield(0),
            '*END']
    return out


def radioss_cards(w):
    """The Radioss Starter include file of one combination."""
    out = ['# Equivalent drawbead from the drawbead sweep %s%s' % (w['sweep'], w['desc']),
           '# written by scripts/bead_curves.sh: a Radioss Starter include file',
           '# (#include it between /BEGIN and /END), layout of the 2022 input format',
           '# and later (OpenRadioss; see docs/user-guide.md, "Equivalent beads for',
           '# LS-DYNA and Radioss")',
           '# units: mm and N: Fn, Ft per unit bead length (N/mm), DEPTH (mm); use it',
           '# in a model in mm and N (/BEGIN with mm, s or ms, and Mg)',
           '#',
           '# Ft is the TOTAL restraining force (bending and friction, the sweep\'s',
           '# friction %s): /INTER/TYPE8 adds no friction of its own. Fn is the lift'
           % w['mu'],
           '# (normal) force, Fn and Ft read at the working penetration DEPTH = %s mm.'
           % field(w['depth'], 20).strip(),
           '# The /FUNCT below hold the whole curves against the penetration, for',
           '# reference (/INTER/TYPE8 takes single values).',
           '#']
    if w['bead_nodes'] is None or w['blank'] is None:
        out += ['# FILL IN the placeholders of the first card (0 until you do):']
        if w['bead_nodes'] is None:
            out += ['#   grnd_IDs  an unsorted /GRNOD of the nodes along the bead line']
        if w['blank'] is None:
            out += ['#   surf_IDm  the /SURF of the blank (normals toward the bead nodes)']
    out += ['/INTER/TYPE8/%d' % w['lcid'],
            ('drawbead' + w['tag'])[:100],
            '# grnd_IDs  surf_IDm               Iform',
            ifield(w['bead_nodes'] or 0) + ifield(w['blank'] or 0) + ' ' * 10 + ifield(2),
            '#                 Fn                  Ft               DEPTH              Tstart'
            '               Tstop',
            ''.join(field(v, 20) for v in (w['lift'], w['total'], w['depth'], 0.0, 0.0)),
            '#            Fn_last             Ft_last',
            field(0.0, 20) + field(0.0, 20)]
    out += radioss_funct(w['lcid'], 'drawbead total restraining force N/mm vs penetration mm'
                         + w['tag'], w['total_curve'])
    out += radioss_funct(w['lcid'] + 1, 'drawbead normal force N/mm vs penetration mm'
                         + w['tag'], w['lift_curve'])
    return out


# ---------------------------------------------------------------------------
# curves
# ---------------------------------------------------------------------------
def read_companions(sweepdir):
    path = os.path.join(sweepdir, 'frictionless', 'companions.tsv')
    try:
        with open(path) as f:
            return dict(ln.rstrip('\n').split('\t', 1) for ln in f if '\t' in ln)
    except OSError:
        die('no %s: run scripts/bead_curves.sh (it runs the frictionless companions)' % path)
    return {}


def read_status_file(path):
    try:
        with open(path) as f:
            return dict(ln.rstrip('\n').split('\t', 1) for ln in f if '\t' in ln)
    except OSError:
        return {}


def write_table(path, title, lines, columns, points):
    with open(path, 'w') as f:
        f.write('# equivalent drawbead: %s\n' % title)
        f.write(''.join('# %s\n' % ln for ln in lines))
        f.write('# %s\n' % columns)
        for p in points:
            f.write(' '.join('%16.6f' % v if i else '%14.6f' % v for i, v in enumerate(p)) + '\n')


def cmd_curves(args):
    opts = {'origin': True, 'lcid': 1, 'depth': None, 'bead_nodes': None, 'blank': None}
    rest = []
    for a in args:
        if a == '--no-origin':
            opts['origin'] = False
        elif a.startswith('--') and '=' in a:
            name, value = a[2:].split('=', 1)
            name = name.replace('-', '_')
            if name in ('lcid', 'bead_nodes', 'blank'):
                if not re.fullmatch(r'[1-9][0-9]{0,9}', value):
                    die('--%s needs a positive integer, not \'%s\'' % (name.replace('_', '-'), value))
                opts[name] = int(value)
            elif name == 'depth':
                opts['depth'] = parse_real(value)
                if opts['depth'] is None or opts['depth'] < 0:
                    die('--depth needs a penetration in mm (>= 0), not \'%s\'' % value)
            else:
                die('unknown option %s' % a)
        else:
            rest.append(a)
    if len(rest) != 2:
        die('usage: bead_tool.py curves SWEEPDIR OUTDIR [--no-origin] [--lcid=N] [--depth=D] '
            '[--bead-nodes=ID] [--blank=ID]')
    sweepdir, outdir = rest
    names, cases = st.read_cases(sweepdir)
    statuses = st.read_statuses(sweepdir)
    fstatuses = read_status_file(os.path.join(sweepdir, 'frictionless', 'status.tsv'))
    companions = read_companions(sweepdir)
    if 'lock_depth' not in names:
        die('%s is not a sweep over lock_depth (swept: %s)' % (sweepdir, ', '.join(names) or 'nothing'))
    decks = read_decks(sweepdir)
    ilock = names.index('lock_depth')
    others = [n for n in names if n != 'lock_depth']
    groups = {}
    for c in cases:
        key = tuple(v for n, v in zip(names, c[1:]) if n != 'lock_depth')
        groups.setdefault(key, []).append(c)
    os.makedirs(outdir, exist_ok=True)
    written, skipped = [], []
    for key in sorted(groups):
        tag = '_'.join('%s-%s' % (n, re.sub(r'[^A-Za-z0-9.+-]', '', v)) for n, v in zip(others, key))
        desc = ', '.join('%s = %s' % (n, v) for n, v in zip(others, key))
        rows, peak_total, peak_bending, torn = [], [], [], []
        mus = set()
        for c in groups[key]:
            depth = float(c[1 + ilock])
            what = '%s (lock_depth = %s)' % (c[0], c[1 + ilock])
            status, point = run_point(sweepdir, os.path.join('runs', c[0]), statuses)
            if point is None:
                skipped.append('%s: %s' % (what, status if status not in ('completed', 'localized', 'torn')
                                           else 'no pulling results'))
                continue
            rel = companions.get(c[0])
            if rel is None:
                die('case %s has no frictionless companion in %s/frictionless/companions.tsv: '
                    'run scripts/bead_curves.sh again' % (c[0], sweepdir))
            fst = statuses if rel.startswith('runs/') else fstatuses
            fstatus, fpoint = run_point(sweepdir, rel, fst)
            if fpoint is None:
                skipped.append('%s: its frictionless companion %s: %s'
                               % (what, rel, fstatus if fstatus not in ('completed', 'localized', 'torn')
                                  else 'no pulling results'))
                continue
            # the same measure for a run and its companion: the peak for
            # both unless both found a steady force
            if point[2] != fpoint[2]:
                if point[2] == 'steady':
                    status, point = run_point(sweepdir, os.path.join('runs', c[0]), statuses, True)
                else:
                    fstatus, fpoint = run_point(sweepdir, rel, fst, True)
            mu = st.deck_value(read_text(decks[c[0]]), 'friction')
            mus.add('0' if mu is None else mu)
            if point[2] == 'peak':
                peak_total.append('%g' % depth)
            if fpoint[2] == 'peak':
                peak_bending.append('%g' % depth)
            if status in ('localized', 'torn'):
                torn.append('%g' % depth)
            rows.append((depth, point[0], fpoint[0], point[1]))
        if not rows:
            continue
        rows.sort()
        origin = opts['origin'] and rows[0][0] > 0
        lead = [(0.0, 0.0)] if origin else []
        total_curve = lead + [(r[0], r[1]) for r in rows]
        bending_curve = lead + [(r[0], r[2]) for r in rows]
        lift_curve = lead + [(r[0], r[3]) for r in rows]
        depth = rows[-1][0] if opts['depth'] is None else opts['depth']
        values = [interpolate(cv, depth) for cv in (total_curve, bending_curve, lift_curve)]
        if None in values:
            die('--depth %g mm is outside the depths of the sweep%s (%g to %g mm)'
                % (depth, (' (%s)' % desc) if desc else '', total_curve[0][0], total_curve[-1][0]))
        total, bending, lift = values
        fs = (total - bending) / lift if lift > 0 else 0.0
        if lift <= 0:
            sys.stderr.write('bead_curves: the lift at %g mm is not positive: FS = 0 written\n' % depth)

        # the tables
        common = ['from the sweep %s%s' % (os.path.abspath(sweepdir), (' (%s)' % desc) if desc else ''),
                  'per unit bead length (the plane-strain results are per unit width)']
        if torn:
            common.append('the sheet localized (may tear) at lock_depth = %s mm: see delta_cr_over_h '
                          'in the sweep table' % ', '.join(torn))
        if origin:
            common.append('first point (0, 0) added: no penetration, no bead force (--no-origin '
                          'leaves it out)')

        def source(peaks):
            if not peaks:
                return 'steady_force_over_Eh (summary.txt) times E h at every depth'
            return ('steady_force_over_Eh where both the run and its frictionless companion found '
                    'one, else peak_force_over_Eh (for both): peak used at lock_depth = %s mm'
                    % ', '.join(peaks))
        sfx = ('_' + tag) if tag else ''
        mu_text = ', '.join(sorted(mus))
        files = {
            'total': os.path.join(outdir, 'restraining_total%s.txt' % sfx),
            'bending': os.path.join(outdir, 'restraining_bending%s.txt' % sfx),
            'lift': os.path.join(outdir, 'lift%s.txt' % sfx),
            'table': os.path.join(outdir, 'bead_table%s.txt' % sfx),
            'k': os.path.join(outdir, 'drawbead%s.k' % sfx),
            'rad': os.path.join(outdir, 'drawbead_radioss%s.rad' % sfx),
        }
        write_table(files['total'], 'TOTAL restraining force per unit bead length vs penetration',
                    common + ['TOTAL: bending and friction (the runs of the sweep, friction = %s): '
                              'for codes that take the whole force, such as Radioss /INTER/TYPE8 Ft; '
                              'NOT for LS-DYNA LCIDRF, which would add friction a second time'
                              % mu_text,
                              'restraining force: ' + source(peak_total)],
                    '1: penetration = lock_depth [mm]   2: total restraining force [N/mm]',
                    total_curve)
        write_table(files['bending'], 'BENDING part of the restraining force per unit bead length '
                    'vs penetration',
                    common + ['BENDING: the frictionless companion runs (the same decks with '
                              'friction = 0, in frictionless/ of the sweep): for codes that add '
                              'friction themselves, such as LS-DYNA *CONTACT_DRAWBEAD LCIDRF',
                              'restraining force: ' + source(peak_bending)],
                    '1: penetration = lock_depth [mm]   2: bending restraining force [N/mm]',
                    bending_curve)
        write_table(files['lift'], 'lift (normal) force per unit bead length vs penetration',
                    common + ['lift force: the force of the sheet opening the binder (pull.dat '
                              'column 8) in the runs with friction, averaged over the steady-force '
                              'window where the restraining force is the steady one, else at the '
                              'peak restraining force',
                              'for LS-DYNA *CONTACT_DRAWBEAD LCIDNF, Radioss /INTER/TYPE8 Fn'],
                    '1: penetration = lock_depth [mm]   2: lift force [N/mm]', lift_curve)
        table_rows = [(r[0], r[1], r[2], r[1] - r[2], r[3], (r[1] - r[2]) / r[3] if r[3] > 0 else 0.0)
                      for r in rows]
        write_table(files['table'], 'both restraining forces and the friction coefficient that goes '
                    'with the bending part',
                    common[:2] + ['total: the runs with friction (%s); bending: their frictionless '
                                  'companions; friction part = total - bending; effective friction '
                                  'coefficient = friction part / lift (the FS that makes LS-DYNA\'s '
                                  'bending + FS * normal force the total)' % mu_text],
                    '1: penetration [mm]  2: total [N/mm]  3: bending [N/mm]  4: friction part [N/mm]'
                    '  5: lift [N/mm]  6: effective friction coefficient [-]', table_rows)
        written += [files['total'], files['bending'], files['lift'], files['table']]

        deepest = max(groups[key], key=lambda c: float(c[1 + ilock]))
        closing = read_closing(os.path.join(sweepdir, 'runs', deepest[0]))
        if closing:
            if opts['origin'] and closing[0][0] > 0:
                closing.insert(0, (0.0, 0.0))
            f3 = os.path.join(outdir, 'closing%s.txt' % sfx)
            write_table(f3, 'closing (punch) force per unit bead length while the bead is pressed in',
                        common[:2] + ['from lock.dat of %s (lock_depth = %s mm): F (column 3) against '
                                      'H (column 1 times h)' % (deepest[0], deepest[1 + ilock]),
                                      'the force bending the sheet into the bead as the binder closes; '
                                      'lift.txt is the force during drawing'],
                        '1: penetration = H [mm]   2: closing force [N/mm]', closing)
            written.append(f3)

        w = {'sweep': os.path.abspath(sweepdir), 'desc': (' (%s)' % desc) if desc else '',
             'tag': (' ' + tag) if tag else '', 'lcid': opts['lcid'], 'depth': depth,
             'total': total, 'bending': bending, 'lift': lift, 'fs': fs, 'mu': mu_text,
             'bead_nodes': opts['bead_nodes'], 'blank': opts['blank'],
             'total_curve': total_curve, 'bending_curve': bending_curve, 'lift_curve': lift_curve}
        with open(files['k'], 'w') as f:
            f.write('\n'.join(lsdyna_cards(w)) + '\n')
        with open(files['rad'], 'w') as f:
            f.write('\n'.join(radioss_cards(w)) + '\n')
        written += [files['k'], files['rad']]
    for s in skipped:
        sys.stderr.write('bead_curves: left out %s\n' % s)
    if not written:
        die('no completed runs (with completed frictionless companions) with pulling results in %s'
            % sweepdir, 1)
    for path in written:
        print(path)


def main(argv):
    if len(argv) < 2 or argv[1] in ('-h', '--help'):
        sys.stdout.write(__doc__)
        return 0 if len(argv) >= 2 else 2
    cmd, args = argv[1], argv[2:]
    if cmd == 'companions':
        cmd_companions(args)
    elif cmd == 'curves':
        cmd_curves(args)
    else:
        die("unknown subcommand '%s'" % cmd)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
