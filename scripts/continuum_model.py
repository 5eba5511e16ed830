#!/usr/bin/env python3
"""continuum_model.py -- a CalculiX plane-strain continuum model of a drawbead deck.

Usage:
    continuum_model.py RUN_LOG OUT_DIR [--through N] [--per-h M]
                       [--initial-inc T] [--max-inc T] [--min-inc T]
                       [--output-every T] [--contact-slope K] [--pull-step]
                       [--pull-steps N]

RUN_LOG   the standard output of bin/drawbead on the deck: its "resolved input"
          namelist echo (every variable, defaults filled in, checked by the
          program) is the case read here, so the defaults and the checks are
          the program's own (docs/output-reference.md, "The run log").
OUT_DIR   gets continuum.inp (the CalculiX input) and continuum_model.json
          (what scripts/continuum_results.py needs to convert the results).

Options:
    --through N      CPE8R elements through the thickness (even; default 4)
    --per-h M        CPE8R elements per thickness h along the sheet (default 4)
    --initial-inc T  first time increment (default 0.01); the step runs in
                     time 0..1 for locking and 1..2 for pulling
    --max-inc T      largest time increment (default 0.02)
    --min-inc T      smallest time increment (default 1e-7)
    --output-every T results every T of time (rounded to divide 1; default
                     --max-inc): CalculiX prints at these time points only
    --contact-slope K  the slope of the linear pressure-overclosure law, MPa/mm
                     (default 1e5); the friction's stick slope is K/10.
                     CalculiX pairs each sheet node with one tool facet and
                     re-pairs it in each of the first iterations of an
                     increment; the force of a node paired anew changes by
                     up to K x (the change of its overclosure) x (the facet's
                     area), and on tight, closed tools (the stepped bead) the
                     default slope makes that jump too large for Newton
                     (docs/continuum-check.md, "Contact stiffness")
    --pull-step      the pull as a *STATIC step of its own after the lock's
                     (amplitudes and output times in total time, the same
                     loads; the pull starts again from --initial-inc).
                     In one step CalculiX starts each increment from the
                     last one's displacements extrapolated; at time 1 that
                     carries on the lock's last motion (the sheet riding up
                     with the lower tool, the binder faces closing) into
                     tools that have stopped: on the long exit-state sheets,
                     pinched over tens of h between closed binder faces, the
                     first pull increment then never converges
                     (docs/continuum-check.md, "Long sheets")
    --pull-steps N   the pull as N *STATIC steps of equal time after the
                     lock's (N >= 1; 1 is --pull-step), with a restart
                     record written at the end of every step
                     (*RESTART, WRITE: continuum.rout, about 30 MB per step
                     on the exit-state sheets): a run stopped in the pull
                     (an hours-long one, killed) can go on from the last
                     step it finished (docs/continuum-check.md, "Long
                     sheets")

The model (docs/continuum-check.md): the sheet is a rectangle [-L, L] x
[-h/2, h/2] of CPE8R elements, thickness 1 mm (forces per mm width). The
deck's tools describe the surfaces that the sheet centreline touches
(docs/theory.md section 5, docs/PROFILE_FORMAT.md); the physical surfaces
are these offset by h/2 away from the sheet, meshed as thin strips of CPE4
elements whose nodes are all prescribed (rigid tools). NODE TO SURFACE
penalty contact, linear pressure-overclosure, Coulomb friction. The material
(material_cards): J2 with the deck's isotropic curve, and for model
'combined' with linear back stresses CalculiX's combined hardening (the
kinematic curve under *PLASTIC, HARDENING=COMBINED, the isotropic one under
*CYCLIC HARDENING). One *STATIC
step: the lower tool rises by lock_depth in time 0..1 (right edge held),
then the right edge is pulled by pull_distance in time 1..2 (tools held);
with --pull-step the pull is a second step (the same loads in total time).

Exit status: 0 done, 2 a case the model does not support (named by deck,
group and variable) or a file problem.
"""

import json
import math
import os
import re
import sys

# contact and tool-strip constants (docs/continuum-check.md, "The model")
CONTACT_SLOPE = 1.0e5      # MPa/mm, linear pressure-overclosure slope (default of --contact-slope)
CONTACT_TENSION = 0.1      # MPa, sigma_inf of the node-to-surface law
STICK_RATIO = 0.1          # the friction law's stick slope / the contact slope (1e4 MPa/mm by default)
FIELD_FORCE = 20.0         # N, fixed reference force of the field check
TOOL_E = 2.0e7             # MPa, the strips (every node prescribed anyway)


def fail(msg):
    """Print 'continuum_model.py: MSG' on stderr and exit 2."""
    sys.stderr.write("continuum_model.py: %s\n" % msg)
    sys.exit(2)


def parse_resolved(text):
    """The resolved-input namelist echo of a run log as {group: {VAR: value}}.

    text: the run log. Values are strings (quotes removed), ints, floats or
    bools; a repeated-value array (64*x) is kept as a string. The deck's
    name comes from the "! deck 'NAME'" line, under key '_deck'.
    """
    groups = {}
    deck = ''
    start = text.find('! resolved input')
    if start < 0:
        return None
    group = None
    for line in text[start:].splitlines():
        m = re.match(r"^! deck '(.*)'\s*$", line)
        if m:
            deck = m.group(1)
            continue
        s = line.strip()
        if s.startswith('&'):
            group = s[1:].strip().lower()
            groups[group] = {}
            continue
        if s == '/':
            group = None
            continue
        if group is None:
            if groups and not s.startswith('!'):
                break
            continue
        m = re.match(r'^([A-Za-z_][A-Za-z_0-9]*)\s*=\s*(.*?)\s*,?\s*$', s)
        if not m:
            continue
        name, val = m.group(1).lower(), m.group(2).strip()
        if val.startswith('"') or val.startswith("'"):
            v = val[1:-1] if len(val) >= 2 else ''
        elif val in ('T', 'F'):
            v = val == 'T'
        elif '*' in val:
            v = val
        else:
            try:
                v = int(val)
            except ValueError:
                try:
                    v = float(val)
                except ValueError:
                    v = val
        groups[group][name] = v
    groups['_deck'] = deck
    return groups


# ---------------------------------------------------------------------------
# Tool chains: pieces ('line', p0, p1) or ('arc', p0, p1, c, ccw)
# ---------------------------------------------------------------------------

def rectangular_chains(t):
    """The centreline chains (upper, lower at H = 0) of the paper's
    rectangular bead, as src/bead_builder.f90 builds them (zero-length
    pieces left out). t: the &tools group. Lengths in mm."""
    r1, r2, b1, b2, h1, h2 = (float(t[k]) for k in ('r1', 'r2', 'b1', 'b2', 'h1', 'h2'))
    xo, top, xi, base = b2 + r2, h2 + r2, b1 + r1, -(h1 + r1)
    up = [('line', (-1e3, 0.0), (-xo, 0.0)),
          ('arc', (-xo, 0.0), (-b2, r2), (-xo, r2), True),
          ('line', (-b2, r2), (-b2, top)),
          ('line', (-b2, top), (b2, top)),
          ('line', (b2, top), (b2, r2)),
          ('arc', (b2, r2), (xo, 0.0), (xo, r2), True),
          ('line', (xo, 0.0), (1e3, 0.0))]
    lo = [('line', (-1e3, base), (-xi, base)),
          ('line', (-xi, base), (-xi, -r1)),
          ('arc', (-xi, -r1), (-b1, 0.0), (-b1, -r1), False),
          ('line', (-b1, 0.0), (b1, 0.0)),
          ('arc', (b1, 0.0), (xi, -r1), (b1, -r1), False),
          ('line', (xi, -r1), (xi, base)),
          ('line', (xi, base), (1e3, base))]
    return [p for p in up if piece_length(p) > 0], [p for p in lo if piece_length(p) > 0]


def read_profile(path):
    """The pieces and side ('upper'/'lower') of a profile file
    (docs/PROFILE_FORMAT.md; the program has checked it already)."""
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail("cannot read profile '%s': %s" % (path, e))
    side, pieces = None, []
    for raw in lines:
        s = raw.split('#', 1)[0].strip()
        if not s:
            continue
        w = [x for x in re.split(r'[\s,]+', s) if x]
        key = w[0].lower()
        if key == 'side':
            side = w[1].lower()
        elif key == 'line':
            v = [float(x) for x in w[1:5]]
            pieces.append(('line', (v[0], v[1]), (v[2], v[3])))
        elif key == 'arc':
            v = [float(x) for x in w[1:7]]
            pieces.append(('arc', (v[0], v[1]), (v[2], v[3]), (v[4], v[5]), w[7].lower() == 'ccw'))
    return side, pieces


def arc_sweep(p):
    """Signed sweep angle of an arc piece (positive counter-clockwise)."""
    _, p0, p1, c, ccw = p
    a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
    a1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    d = a1 - a0
    if ccw:
        while d <= 0:
            d += 2 * math.pi
    else:
        while d >= 0:
            d -= 2 * math.pi
    return d


def piece_length(p):
    """Length of a piece."""
    if p[0] == 'line':
        return math.hypot(p[2][0] - p[1][0], p[2][1] - p[1][1])
    return abs(arc_sweep(p)) * math.hypot(p[1][0] - p[3][0], p[1][1] - p[3][1])


def tangent(p, end):
    """Unit tangent of a piece at its start (end=False) or end (end=True)."""
    if p[0] == 'line':
        dx, dy = p[2][0] - p[1][0], p[2][1] - p[1][1]
    else:
        q, c = (p[2] if end else p[1]), p[3]
        rx, ry = q[0] - c[0], q[1] - c[1]
        dx, dy = (-ry, rx) if p[4] else (ry, -rx)
    n = math.hypot(dx, dy)
    return dx / n, dy / n


def material_normal(tx, ty, side):
    """Unit normal toward the tool's material: on the left of the direction
    of travel for 'upper', on the right for 'lower'."""
    return (-ty, tx) if side == 'upper' else (ty, -tx)


def physical_points(pieces, side, d, x_lo, x_hi, ds):
    """Points along the physical tool surface: the centreline chain offset by
    d (= h/2) toward the tool's material, sampled at most ds apart.

    Lines are shifted, arcs change radius by d; at a corner turning away
    from the material (re-entrant) the physical surface is an arc of radius
    d about the corner, at a corner turning toward it (convex, sharp) the
    two shifted pieces are cut at their tangent lines' intersection. The end
    pieces are continued along their tangents to cover [x_lo, x_hi]."""
    pieces = list(pieces)
    # extend the end pieces along their tangents (the program does the same)
    t0 = tangent(pieces[0], False)
    if pieces[0][1][0] > x_lo and abs(t0[0]) > 1e-12:
        p0 = pieces[0][1]
        k = (p0[0] - x_lo) / t0[0]
        pieces.insert(0, ('line', (p0[0] - k * t0[0], p0[1] - k * t0[1]), p0))
    t1 = tangent(pieces[-1], True)
    if pieces[-1][2][0] < x_hi and abs(t1[0]) > 1e-12:
        p1 = pieces[-1][2]
        k = (x_hi - p1[0]) / t1[0]
        pieces.append(('line', p1, (p1[0] + k * t1[0], p1[1] + k * t1[1])))
    runs = []
    for p in pieces:
        if p[0] == 'line':
            n = material_normal(*tangent(p, False), side)
            a = (p[1][0] + d * n[0], p[1][1] + d * n[1])
            b = (p[2][0] + d * n[0], p[2][1] + d * n[1])
            m = max(1, int(math.ceil(piece_length(p) / ds)))
            runs.append([(a[0] + (b[0] - a[0]) * i / m, a[1] + (b[1] - a[1]) * i / m)
                         for i in range(m + 1)])
        else:
            _, p0, _, c, _ = p
            r = math.hypot(p0[0] - c[0], p0[1] - c[1])
            n = material_normal(*tangent(p, False), side)
            towards_centre = n[0] * (c[0] - p0[0]) + n[1] * (c[1] - p0[1]) > 0
            rp = r - d if towards_centre else r + d
            if rp <= 0:
                fail("an arc of radius %.6g mm is smaller than h/2 = %.6g mm: "
                     "its physical surface does not exist" % (r, d))
            a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
            sw = arc_sweep(p)
            m = max(2, int(math.ceil(abs(sw) * rp / ds)))
            runs.append([(c[0] + rp * math.cos(a0 + sw * i / m),
                          c[1] + rp * math.sin(a0 + sw * i / m)) for i in range(m + 1)])
    pts = list(runs[0])
    for k in range(1, len(pieces)):
        ta, tb = tangent(pieces[k - 1], True), tangent(pieces[k], False)
        cross = ta[0] * tb[1] - ta[1] * tb[0]
        nxt = runs[k]
        if abs(cross) < 1e-9:
            pts.extend(nxt[1:])
            continue
        turns_left = cross > 0
        convex = turns_left == (side == 'upper')
        if convex:
            # cut both shifted pieces at the intersection of their tangents
            a, b = pts[-1], nxt[0]
            det = ta[0] * (-tb[1]) - ta[1] * (-tb[0])
            s = ((b[0] - a[0]) * (-tb[1]) - (b[1] - a[1]) * (-tb[0])) / det
            q = (a[0] + s * ta[0], a[1] + s * ta[1])
            pts[-1] = q
            pts.extend(nxt[1:])
        else:
            # re-entrant corner: an arc of radius d about the corner point
            cpt = pieces[k][1]
            na = material_normal(*ta, side)
            nb = material_normal(*tb, side)
            a0 = math.atan2(na[1], na[0])
            a1 = math.atan2(nb[1], nb[0])
            sw = a1 - a0
            while sw > math.pi:
                sw -= 2 * math.pi
            while sw < -math.pi:
                sw += 2 * math.pi
            m = max(2, int(math.ceil(abs(sw) * d / ds)))
            pts.extend((cpt[0] + d * math.cos(a0 + sw * i / m),
                        cpt[1] + d * math.sin(a0 + sw * i / m)) for i in range(1, m))
            pts.extend(nxt)
    # keep [x_lo, x_hi] with one point to spare at each end
    return pts


def chain_height(pieces, x, h):
    """Height of a centreline chain at abscissa x (its end pieces continued
    along their tangents; at a vertical wall the first crossing counts)."""
    pts = physical_points(pieces, 'upper', 0.0, x - h, x + h, h / 8)
    for a, b in zip(pts, pts[1:]):
        lo, hi = min(a[0], b[0]), max(a[0], b[0])
        if lo <= x <= hi and hi > lo:
            return a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0])
    fail('a tool chain does not reach the sheet edge at x = %.6g mm' % x)


def edge_heights(up, lo, x, lock):
    """Time points and heights of an edge's centreline while locking
    (docs/theory.md (8.1)): w = min(max(y_lower(x) + H, 0), y_upper(x)),
    H = lock t the lower tool's lift; piecewise linear in t."""
    yl, yu = chain_height(lo, x, 1.0), chain_height(up, x, 1.0)

    def w(t):
        return min(max(yl + lock * t, 0.0), yu)
    ts = {0.0, 1.0}
    if lock != 0.0:
        for t in (-yl / lock, (yu - yl) / lock):
            if 0.0 < t < 1.0:
                ts.add(t)
    return [(t, w(t)) for t in sorted(ts)]


# ---------------------------------------------------------------------------
# Material
# ---------------------------------------------------------------------------

# the program's "not given" (-huge(1.0_dp)) as the resolved echo prints it
UNSET_BELOW = -1.0e300


def real_list(value, n):
    """The n reals of an array in the resolved echo ('1.5, 2*-1.79E+308' or
    one number); None for an entry the echo marks as not given."""
    out = []
    for item in str(value).split(','):
        item = item.strip()
        if not item:
            continue
        count, _, x = item.rpartition('*')
        out += [float(x)] * (int(count) if count else 1)
    out = (out + [UNSET_BELOW * 2] * n)[:n]
    return [None if x < UNSET_BELOW else x for x in out]


def yield_surface_check(deck, mat):
    """Refuse a yield surface other than von Mises, naming the variable:
    model 'j2' r_value = 1; model 'combined' r0 = r90 = 1 (each defaults
    to r_value)."""
    names = ['r_value']
    if str(mat.get('model', 'j2')).lower() == 'combined':
        names = []
        for name in ('r0', 'r90'):
            v = real_list(mat.get(name, UNSET_BELOW * 2), 1)[0]
            names.append(name if v is not None else 'r_value')
    for name in names:
        r = float(mat[name])
        if abs(r - 1.0) > 1e-12:
            fail("deck '%s', group &material, variable %s: only a von Mises yield surface "
                 "(r0 = r90 = r_value = 1) is modelled, not %g" % (deck, name, r))


def kinematic_modulus(deck, mat):
    """The slope C (MPa) of the uniaxial back stress X = C p that CalculiX's
    combined hardening can take: the sum of the deck's kinematic_c(i), each
    linear (kinematic_gamma(i) = 0; a back stress with C = 0 adds nothing).
    An Armstrong-Frederick back stress (gamma > 0) is refused: CalculiX's
    kinematic curve is a function of the equivalent plastic strain, its back
    stress never recovers."""
    c = real_list(mat.get('kinematic_c', ''), 3)
    gamma = real_list(mat.get('kinematic_gamma', ''), 3)
    total = 0.0
    for i, (ci, gi) in enumerate(zip(c, gamma)):
        if ci is None:
            continue
        if gi is not None and gi > 0.0 and ci > 0.0:
            fail("deck '%s', group &material, variable kinematic_gamma(%d): only linear (Prager) "
                 "back stresses, kinematic_gamma = 0, are modelled (CalculiX's combined hardening "
                 "has no Armstrong-Frederick recovery), not %g" % (deck, i + 1, gi))
        total += ci
    return total


def material_cards(deck, mat):
    """The lines of the sheet's material after *MATERIAL: *ELASTIC and the
    plasticity of the deck's law (docs/continuum-check.md, "The material").

    model 'j2': *PLASTIC, the isotropic curve (hardening_table).
    model 'combined' with linear back stresses of total slope C > 0:
    *PLASTIC, HARDENING=COMBINED with the kinematic curve, the uniaxial yield
    stress of a purely kinematic law, sigma_y(0) + C p, at the first and last
    plastic strain of the isotropic curve (CalculiX uses its slope only: the
    back stress grows by (2/3) C d eps_p, X = C p in uniaxial tension; it
    stays constant past the last point), and *CYCLIC HARDENING with the
    isotropic curve. C = 0 is the isotropic law. Anything else is refused
    (fail) naming deck, group and variable.
    """
    model = str(mat.get('model', 'j2')).lower()
    if model not in ('j2', 'combined'):
        fail("deck '%s', group &material, variable model: only 'j2' and 'combined' are modelled, "
             "not '%s' (a user UMAT has no CalculiX counterpart here)" % (deck, model))
    yield_surface_check(deck, mat)
    iso = hardening_table(deck, mat)
    lines = ['*ELASTIC', '%.12g, %.12g' % (float(mat['youngs_modulus']), float(mat['poissons_ratio']))]
    c = kinematic_modulus(deck, mat) if model == 'combined' else 0.0
    if c > 0.0:
        (s0, e0), e1 = iso[0], iso[-1][1]
        lines += ['*PLASTIC, HARDENING=COMBINED',
                  '%.12g, %.12g' % (s0, e0), '%.12g, %.12g' % (s0 + c * (e1 - e0), e1),
                  '*CYCLIC HARDENING']
    else:
        lines.append('*PLASTIC')
    lines += ['%.12g, %.12g' % (s, ep) for s, ep in iso]
    return lines, c


def hardening_table(deck, mat):
    """(stress, plastic strain) rows of *PLASTIC for the deck's hardening law."""
    law = str(mat['hardening']).lower()
    if law in ('swift', 'voce'):
        eps = [0.0] + [10 ** (-5 + 5.5 * i / 59) for i in range(60)]  # 1e-5 .. ~3.2
        if law == 'swift':
            k, e0, n = float(mat['swift_k']), float(mat['swift_eps0']), float(mat['swift_n'])
            return [(k * (e0 + e) ** n, e) for e in eps]
        s0, q, b = float(mat['voce_sigma0']), float(mat['voce_q']), float(mat['voce_b'])
        return [(s0 + q * (1 - math.exp(-b * e)), e) for e in eps]
    if law == 'table':
        path = mat['curve_file']
        rows = []
        try:
            with open(path) as f:
                for raw in f:
                    s = raw.split('#', 1)[0].strip()
                    if s:
                        w = [x for x in re.split(r'[\s,]+', s) if x]
                        rows.append((float(w[1]), float(w[0])))
        except (OSError, ValueError, IndexError) as e:
            fail("deck '%s', group &material, variable curve_file: cannot read '%s': %s"
                 % (deck, path, e))
        # the program extends the last segment beyond the last point
        (s1, e1), (s2, e2) = rows[-2], rows[-1]
        e_end = max(3.0, e2 + 1.0)
        rows.append((s2 + (s2 - s1) / (e2 - e1) * (e_end - e2), e_end))
        return rows
    fail("deck '%s', group &material, variable hardening: '%s' is not supported "
         "(swift, voce, table)" % (deck, law))
    return []


# ---------------------------------------------------------------------------
# The model
# ---------------------------------------------------------------------------

def write_lines(f, items, per_line=8):
    """Write integers or text items comma-separated, per_line to a line."""
    items = list(items)
    for i in range(0, len(items), per_line):
        f.write(', '.join(str(x) for x in items[i:i + per_line]) + '\n')


def build(nml, out_dir, through, per_h, inc0, inc_max, inc_min, out_every, slope=CONTACT_SLOPE,
          pull_steps=0):
    """Write OUT_DIR/continuum.inp and continuum_model.json for the case;
    slope: the contact's pressure-overclosure slope, MPa/mm (the stick slope
    is STICK_RATIO times it); pull_steps: 0 the lock and the pull one
    step, 1 the pull a step of its own (--pull-step), more: the pull in
    that many steps with restart records."""
    pull_step = pull_steps >= 1
    deck = nml.get('_deck', '?')
    sheet, mat, tools, load = nml['sheet'], nml['material'], nml['tools'], nml['loading']
    sheet_material, kinematic_c = material_cards(deck, mat)
    h = float(sheet['thickness'])
    half = 0.5 * float(sheet['length'])
    left_free = str(sheet['left_edge']).lower() == 'free'
    back = float(sheet.get('back_tension', 0.0)) if left_free else 0.0
    bead = str(tools['bead']).lower()
    lock = float(load['lock_depth']) if bead != 'none' else 0.0
    pull = float(load['pull_distance'])
    mu = float(tools.get('friction', 0.0))
    e_mod = float(mat['youngs_modulus'])

    nx = max(1, int(round(2 * half / h * per_h)))
    ny = through
    ni, nj = 2 * nx + 1, 2 * ny + 1

    def nid(i, j):
        return j * ni + i + 1

    nodes = []
    for j in range(nj):
        for i in range(ni):
            if i % 2 == 1 and j % 2 == 1:
                continue
            nodes.append((nid(i, j), -half + 2 * half * i / (2 * nx), -0.5 * h + h * j / (2 * ny)))
    elems = []
    eid = 0
    for ej in range(ny):
        for ei in range(nx):
            eid += 1
            i0, j0 = 2 * ei, 2 * ej
            elems.append((eid, [nid(i0, j0), nid(i0 + 2, j0), nid(i0 + 2, j0 + 2), nid(i0, j0 + 2),
                                nid(i0 + 1, j0), nid(i0 + 2, j0 + 1), nid(i0 + 1, j0 + 2),
                                nid(i0, j0 + 1)]))
    n_sheet_elems = eid
    next_node = nj * ni + 1

    mid = [nid(i, ny) for i in range(ni)]
    top = [nid(i, 2 * ny) for i in range(ni)]
    bot = [nid(i, 0) for i in range(ni)]
    left = [nid(0, j) for j in range(nj)]
    right = [nid(2 * nx, j) for j in range(nj)]

    # tools: physical surfaces, strips of CPE4 elements behind them
    tool_nodes, tool_elems, tool_faces = {}, {}, {}
    if bead != 'none':
        if bead == 'rectangular':
            up, lo = rectangular_chains(tools)
        elif bead == 'profile':
            su, up = read_profile(tools['upper_profile'])
            sl, lo = read_profile(tools['lower_profile'])
            if su != 'upper' or sl != 'lower':
                fail("deck '%s', group &tools: upper_profile must be 'side upper' and "
                     "lower_profile 'side lower'" % deck)
        else:
            fail("deck '%s', group &tools, variable bead: '%s' is not supported" % (deck, bead))
        x_lo, x_hi = -half - 3 * h, half + pull + 3 * h
        strip = 0.25 * h
        for side, chain in (('upper', up), ('lower', lo)):
            pts = physical_points(chain, side, 0.5 * h, x_lo, x_hi, h / 8)
            # drop points far outside the sheet's reach (the long binder ends)
            keep = [k for k, p in enumerate(pts) if x_lo - h <= p[0] <= x_hi + h]
            pts = pts[max(0, keep[0] - 1):keep[-1] + 2]
            # the tool strip: each surface point (h/8 apart) and its partner a
            # strip's width inside the tool, along the surface's normal
            ids_p, ids_q, coords = [], [], []
            for k, p in enumerate(pts):
                if k == 0:
                    ta = (pts[1][0] - p[0], pts[1][1] - p[1])
                elif k == len(pts) - 1:
                    ta = (p[0] - pts[k - 1][0], p[1] - pts[k - 1][1])
                else:
                    ta = (pts[k + 1][0] - pts[k - 1][0], pts[k + 1][1] - pts[k - 1][1])
                nrm = math.hypot(*ta)
                n = material_normal(ta[0] / nrm, ta[1] / nrm, side)
                q = (p[0] + strip * n[0], p[1] + strip * n[1])
                ids_p.append(next_node)
                coords.append((next_node, p[0], p[1]))
                ids_q.append(next_node + 1)
                coords.append((next_node + 1, q[0], q[1]))
                next_node += 2
            els, faces = [], []
            for k in range(len(pts) - 1):
                eid += 1
                if side == 'upper':
                    conn = [ids_p[k], ids_p[k + 1], ids_q[k + 1], ids_q[k]]
                else:
                    conn = [ids_p[k + 1], ids_p[k], ids_q[k], ids_q[k + 1]]
                els.append((eid, conn))
                faces.append(eid)
            tool_nodes[side], tool_elems[side], tool_faces[side] = coords, els, faces

    # the edges' heights while locking (docs/theory.md (8.1)): y = 0 for the
    # paper's beads, on the lower tool's face where it rises above y = 0
    # (a lock step at the edge), never above the upper tool's face
    edge_amp = {}
    # the tools' centreline chains (where the sheet's centreline lies in
    # contact) on a grid of h/4, for continuum_results.py's check that the
    # continuum is a sheet lying in the tools
    tool_grid = None
    if tool_nodes:
        xs = [-half - 3 * h + 0.25 * h * k for k in range(int((2 * half + pull + 6 * h) / (0.25 * h)) + 1)]
        tool_grid = {'x': xs, 'upper': [chain_height(up, x, h) for x in xs],
                     'lower': [chain_height(lo, x, h) for x in xs]}
    if tool_nodes:
        for name, x in (('LEFT', -half), ('RIGHT', half)):
            pts = edge_heights(up, lo, x, lock)
            if any(abs(wv) > 1e-12 for _, wv in pts):
                edge_amp[name] = pts

    path = os.path.join(out_dir, 'continuum.inp')
    with open(path, 'w') as f:
        f.write('** drawbead continuum cross-check (scripts/continuum_model.py)\n')
        f.write('** deck %s: h = %.9g mm, 2L = %.9g mm, %d x %d CPE8R\n' % (deck, h, 2 * half, nx, ny))
        f.write('*NODE, NSET=NALL\n')
        for n, x, y in nodes:
            f.write('%d, %.12g, %.12g\n' % (n, x, y))
        for side in tool_nodes:
            for n, x, y in tool_nodes[side]:
                f.write('%d, %.12g, %.12g\n' % (n, x, y))
        f.write('*ELEMENT, TYPE=CPE8R, ELSET=SHEET\n')
        for e, c in elems:
            f.write('%d, %s\n' % (e, ', '.join(str(x) for x in c)))
        for side in tool_elems:
            f.write('*ELEMENT, TYPE=CPE4, ELSET=T%s\n' % side.upper())
            for e, c in tool_elems[side]:
                f.write('%d, %s\n' % (e, ', '.join(str(x) for x in c)))
        for name, ids in (('NMID', mid), ('NTOP', top), ('NBOT', bot),
                          ('NLEFT', left), ('NRIGHT', right)):
            f.write('*NSET, NSET=%s\n' % name)
            write_lines(f, ids)
        f.write('*NSET, NSET=NSTRAIN\nNMID, NTOP, NBOT\n')
        for side in tool_nodes:
            f.write('*NSET, NSET=N%s\n' % side.upper())
            write_lines(f, [n for n, _, _ in tool_nodes[side]])
        f.write('*MATERIAL, NAME=SHEETMAT\n')
        f.write('\n'.join(sheet_material) + '\n')
        f.write('*SOLID SECTION, ELSET=SHEET, MATERIAL=SHEETMAT\n1.\n')
        if tool_elems:
            f.write('*MATERIAL, NAME=TOOLMAT\n*ELASTIC\n%.6g, 0.3\n' % TOOL_E)
            for side in tool_elems:
                f.write('*SOLID SECTION, ELSET=T%s, MATERIAL=TOOLMAT\n1.\n' % side.upper())
            f.write('*SURFACE, NAME=STOP, TYPE=NODE\nNTOP\n')
            f.write('*SURFACE, NAME=SBOT, TYPE=NODE\nNBOT\n')
            for side in tool_faces:
                f.write('*SURFACE, NAME=M%s, TYPE=ELEMENT\n' % side.upper())
                for e in tool_faces[side]:
                    f.write('%d, S1\n' % e)
            f.write('*SURFACE INTERACTION, NAME=SI\n')
            f.write('*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n%.6g, %.6g\n'
                    % (slope, CONTACT_TENSION))
            if mu > 0:
                f.write('*FRICTION\n%.12g, %.6g\n' % (mu, STICK_RATIO * slope))
            f.write('*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE\nSTOP, MUPPER\n')
            f.write('*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE\nSBOT, MLOWER\n')
        # the edges (docs/theory.md section 1): the centreline point held at
        # y = 0 (w = 0), the end section kept vertical (w' = 0: every node of
        # it has the same u1) but free to thin; a free left edge moves as one
        # under the back tension, a clamped one is held
        lmid, rmid = left[ny], right[ny]
        if left_free:
            f.write('*EQUATION\n')
            for n in left:
                if n != lmid:
                    f.write('2\n%d, 1, 1., %d, 1, -1.\n' % (n, lmid))
        # two steps (pull_step): the amplitudes and output times in total time
        two = pull_step and pull != 0.0
        total = ', TIME=TOTAL TIME' if two else ''
        f.write('*AMPLITUDE, NAME=ALOCK%s\n0., 0., 1., 1., 2., 1.\n' % total)
        f.write('*AMPLITUDE, NAME=APULL%s\n0., 0., 1., 0., 2., 1.\n' % total)
        for name, pts in edge_amp.items():
            f.write('*AMPLITUDE, NAME=AEDGE%s%s\n' % (name, total))
            write_lines(f, ['%.12g, %.12g' % p for p in pts + [(2.0, pts[-1][1])]], per_line=4)
        f.write('*BOUNDARY\n')
        for name, n in (('LEFT', lmid), ('RIGHT', rmid)):
            if name not in edge_amp:
                f.write('%d, 2, 2\n' % n)
        if not left_free:
            f.write('NLEFT, 1, 1\n')
        if tool_nodes:
            f.write('NUPPER, 1, 2\nNLOWER, 1, 1\n')
        # output at fixed time points (CalculiX applies TIME POINTS to every
        # print request): n_out per phase, t = 1 (end of locking) among them
        t_end = 2.0 if pull > 0 else 1.0
        n_out = max(1, int(math.ceil(1.0 / out_every - 1e-9)))
        f.write('*TIME POINTS, NAME=TP%s\n' % total)
        write_lines(f, ['%.12g' % (k / n_out) for k in range(1, int(round(t_end * n_out)) + 1)])
        f.write('*STEP, NLGEOM, INC=100000\n*STATIC\n%.6g, %.6g, %.6g, %.6g\n'
                % (inc0, 1.0 if two else t_end, inc_min, inc_max))
        controls = ('*CONTROLS, PARAMETERS=FIELD\n0.005, 0.01, %.6g, %.6g, 0.02, 1.e-5, 1.e-3, 1.e-8\n'
                    % (FIELD_FORCE, FIELD_FORCE)
                    + '*CONTROLS, PARAMETERS=TIME INCREMENTATION\n4, 8, 9, 30, 10, 4, , 10\n')
        f.write(controls)
        if tool_nodes and lock != 0.0:
            f.write('*BOUNDARY, AMPLITUDE=ALOCK\nNLOWER, 2, 2, %.12g\n' % lock)
        elif tool_nodes:
            f.write('*BOUNDARY\nNLOWER, 2, 2\n')
        for name, n in (('LEFT', lmid), ('RIGHT', rmid)):
            if name in edge_amp:
                f.write('*BOUNDARY, AMPLITUDE=AEDGE%s\n%d, 2, 2, 1.\n' % (name, n))
        if pull != 0.0:
            f.write('*BOUNDARY, AMPLITUDE=APULL\nNRIGHT, 1, 1, %.12g\n' % pull)
        else:
            f.write('*BOUNDARY\nNRIGHT, 1, 1\n')
        if left_free and back > 0:
            f.write('*CLOAD\n%d, 1, %.12g\n' % (lmid, -back))
        for name in ('NRIGHT', 'NLEFT') + tuple('N%s' % s.upper() for s in tool_nodes):
            f.write('*NODE PRINT, NSET=%s, TOTALS=ONLY, TIME POINTS=TP\nRF\n' % name)
        f.write('*NODE PRINT, NSET=NSTRAIN\nU\n')
        f.write('*EL PRINT, ELSET=SHEET\nPEEQ\n')
        if two and pull_steps > 1:
            # a restart record at the end of every step (the request holds
            # for the steps after this one; docs/continuum-check.md, "Long sheets")
            f.write('*RESTART, WRITE, FREQUENCY=1\n')
        f.write('*END STEP\n')
        if two and pull_steps > 1:
            # the pull in pull_steps steps of equal time, each starting
            # afresh from inc0 (the loads in total time)
            for _ in range(pull_steps):
                # (the period in full: the steps' times add up to 1)
                f.write('*STEP, NLGEOM, INC=100000\n*STATIC\n%.6g, %.17g, %.6g, %.6g\n'
                        % (inc0, 1.0 / pull_steps, inc_min, inc_max))
                f.write(controls)
                f.write('*END STEP\n')
        elif two:
            # the pull as a step of its own: CalculiX starts it without
            # extrapolating the lock's last increment (the tools stop, the
            # edge starts), from the first increment inc0 again
            f.write('*STEP, NLGEOM, INC=100000\n*STATIC\n%.6g, 1., %.6g, %.6g\n'
                    % (inc0, inc_min, inc_max))
            f.write(controls)
            f.write('*END STEP\n')

    info = {
        'deck': deck, 'title': nml.get('control', {}).get('title', ''),
        'thickness': h, 'half_length': half, 'youngs_modulus': e_mod,
        'kinematic_c': kinematic_c,
        'lock_depth': lock, 'pull_distance': pull, 'left_edge_free': left_free,
        'back_tension': back, 'friction': mu, 'bead': bead, 'nx': nx, 'ny': ny,
        'through': through, 'per_h': per_h, 'has_tools': bool(tool_nodes),
        'contact_slope': slope,
        'node_x': {str(n): x for n, x, _ in nodes if n in set(mid) | set(top) | set(bot)},
        'node_y': {str(n): y for n, _, y in nodes if n in set(mid) | set(top) | set(bot)},
        'mid': mid, 'top': top, 'bottom': bot, 'n_sheet_elements': n_sheet_elems,
        'bead_half_width': bead_half_width(tools, bead, h),
        'edge_heights': {k.lower(): v for k, v in edge_amp.items()},
        'tool_grid': tool_grid,
    }
    if pull_step:
        info['pull_step'] = True
    if pull_steps > 1 and pull != 0.0:
        info['pull_steps'] = pull_steps
    with open(os.path.join(out_dir, 'continuum_model.json'), 'w') as f:
        json.dump(info, f)
    return path


def bead_half_width(tools, bead, h):
    """Half-width of the bead region, mm: B2 + R2 for the rectangular bead;
    for profiles the largest |x| at which the upper chain leaves the height
    of its ends; 0 without tools."""
    if bead == 'rectangular':
        return float(tools['b2']) + float(tools['r2'])
    if bead == 'profile':
        _, up = read_profile(tools['upper_profile'])
        y0 = up[0][1][1]
        xs = [q[0] for p in up for q in (p[1], p[2]) if abs(q[1] - y0) > 1e-9 * max(1.0, h)]
        return max((abs(x) for x in xs), default=0.0)
    return 0.0


def main(argv):
    """Command line: see the module header."""
    args, opts = [], {'--through': 4, '--per-h': 4, '--initial-inc': 0.01,
                      '--max-inc': 0.02, '--min-inc': 1e-7, '--output-every': 0.0,
                      '--contact-slope': CONTACT_SLOPE,
                      '--pull-step': False, '--pull-steps': 0}
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == '--pull-step':
            opts[a] = True
            i += 1
        elif a in opts:
            if i + 1 >= len(argv):
                fail('%s needs a value' % a)
            try:
                opts[a] = type(opts[a])(argv[i + 1])
            except ValueError:
                fail("%s needs a number, not '%s'" % (a, argv[i + 1]))
            i += 2
        elif a in ('-h', '--help'):
            print(__doc__)
            return 0
        else:
            args.append(a)
            i += 1
    if len(args) != 2:
        fail('usage: continuum_model.py RUN_LOG OUT_DIR [options]')
    if opts['--through'] < 2 or opts['--through'] % 2:
        fail('--through needs an even number >= 2 (the mid-surface is a row of nodes)')
    if opts['--per-h'] < 1:
        fail('--per-h needs a positive integer')
    if '--pull-steps' in argv and opts['--pull-steps'] < 1:
        fail('--pull-steps needs a positive integer')
    if not opts['--contact-slope'] > 0 or math.isinf(opts['--contact-slope']):
        fail('--contact-slope needs a positive number of MPa/mm, not %r' % opts['--contact-slope'])
    try:
        with open(args[0]) as f:
            nml = parse_resolved(f.read())
    except OSError as e:
        fail('cannot read %s: %s' % (args[0], e))
    if not nml or 'sheet' not in nml:
        fail('%s holds no resolved input (did the program accept the deck?)' % args[0])
    os.makedirs(args[1], exist_ok=True)
    build(nml, args[1], opts['--through'], opts['--per-h'], opts['--initial-inc'],
          opts['--max-inc'], opts['--min-inc'], opts['--output-every'] or opts['--max-inc'],
          opts['--contact-slope'], opts['--pull-steps'] or int(opts['--pull-step']))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
