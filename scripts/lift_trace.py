#!/usr/bin/env python3
"""lift_trace.py -- the lift force traced tool by tool: the vertical force of
each tool on the sheet, split by the pieces of the tool (binder faces, radii,
walls, crest), and the vertical reactions at the sheet's edges, in the
program and in the CalculiX continuum at the same instants of the pull
(scripts/lift_trace.sh runs both; docs/validation.md, "The lift force").

Usage:
    lift_trace.py trace PROGRAM_DIR CCX_DIR [--at D1,D2,...]
    lift_trace.py summary LABEL PROGRAM_DIR CCX_DIR [--at D1,D2,...]
    lift_trace.py ccx-forces CCX_DIR
    lift_trace.py patch-inp CONTINUUM_INP
    lift_trace.py trim-ccx CCX_DIR OUT_DIR [--at D1,D2,...]
    lift_trace.py offset-deck RUN_LOG VARIABLES DECK OUT DELTA_OVER_H

trace       PROGRAM_DIR: a run of bin/drawbead with &control snapshot_every
            small enough that each converged increment of the pull has its
            block in snapshots.dat (run.log, pull.dat, snapshots.dat);
            CCX_DIR: the continuum run of the same deck
            (scripts/continuum_model.py's continuum.inp and
            continuum_model.json, and CalculiX's continuum.dat with the
            per-node reactions RF of the node sets NUPPER and NLOWER, as
            patch-inp asks for them, or the part of it trim-ccx keeps).
            Prints, for each instant (pull delta/h of --at, default 0.5,1,
            and each model's largest restraining force), one row per tool
            piece: the normal part of its vertical force on the sheet
            (N/mm, upward positive) in the program and in the continuum,
            their difference and ratio, and the continuum's friction part
            (c.fric); per tool the normal parts summed, the friction part
            and the total (the punch force F of the lower tool, the lift =
            minus the upper tool's); the edges' vertical reactions; the
            program's sheet thickness next to and in the bead; and the
            steepest slope of the mid-surface on each side (the free
            spans) in both models.
summary     one line: the lift at the instants and at the largest
            restraining force, and the largest restraining force, program
            / continuum (totals only: any run of the program, no snapshots
            needed).
ccx-forces  the continuum's totals per output time (time, delta/h, N, F,
            lift, the two edges' vertical reactions) and the sums of the
            per-node reactions of each tool: a check of the .dat reading.
patch-inp   adds the per-node reactions of NUPPER and NLOWER to the
            output requests of a continuum.inp (once).
trim-ccx    writes into OUT_DIR the part of a continuum run that trace and
            summary read at the instants of --at: the totals at every
            output time, the loaded tool nodes' reactions and the
            mid-surface nodes' displacements within the bead at the output
            times around each instant (about 130 kB).
offset-deck writes OUT: DECK (a rectangular bead) with both tools'
            centreline chains moved by DELTA_OVER_H h toward the tools (the
            tools a sheet thinned by twice that lies on), from the resolved
            input of RUN_LOG; VARIABLES is `drawbead --list-variables`.

How the program's forces are rebuilt (docs/output-reference.md, strain
files): at each Gauss station the normal force per unit reference length
is f_n = p Lambda_f (p, columns 16 and 17: the tool's normal force per unit
current face area; Lambda_f = exp of the face's log strain, columns 6 and
7) along the tool's normal at the nearest point of its centreline chain,
the stations weighted by the four-point Gauss rule on each element (four
rows per element). The friction force is not in the strain files (only
the coefficient: the factor f(u_T) of theory (6.2), which remembers the
sliding while locking, is not), so each tool's friction part is its
total (pull.dat's F, lift) less its normal parts; with mu = 0 that
remainder is below 0.5% of F (tests/lift_trace.sh).

The continuum's forces: CalculiX's reactions of the tool nodes (every node
of a tool strip is prescribed, so the reaction of a node is the force of
the sheet's contact on it, with the sign of the tool's force on the sheet:
docs/continuum-check.md, "How the columns are filled"), each node given to
the piece of the centreline chain nearest to it (the physical surface is
the chain offset by h/2, so an arc keeps its centre and its angles) and
split along the chain's tangent there into its normal and friction
parts. The edges' vertical reactions are the totals of the node sets
NLEFT, NRIGHT.

Exit status 0; 2 on a usage error or a missing or unreadable file.
"""

import bisect
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import continuum_model as cm  # noqa: E402  (parse_resolved, the chains)

GAUSS_X = (-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526)
GAUSS_W = (0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538)


def fail(msg):
    """Print 'lift_trace.py: MSG' on stderr and exit 2."""
    sys.stderr.write('lift_trace.py: %s\n' % msg)
    sys.exit(2)


def read_text(path):
    """The text of a file; fails with its name."""
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        fail('cannot read %s: %s' % (path, e.strerror))
    return ''


# ---------------------------------------------------------------------------
# The tools: centreline chains, their pieces named, nearest piece of a point
# ---------------------------------------------------------------------------

RECT_NAMES = {
    'upper': ['binder, entry side', 'entry radius R2', 'wall, entry side', 'groove bottom',
              'wall, exit side', 'exit radius R2', 'binder, exit side'],
    'lower': ['binder, entry side', 'side, entry', 'corner R1, entry side', 'crest',
              'corner R1, exit side', 'side, exit', 'binder, exit side'],
}


def case_tools(nml):
    """(h, lock, {'upper': pieces, 'lower': pieces}, {'upper': names, ...}) of
    the resolved input nml (lengths in mm; the lower chain at H = 0)."""
    h = float(nml['sheet']['thickness'])
    tools, load = nml['tools'], nml['loading']
    bead = str(tools['bead']).lower()
    if bead == 'rectangular':
        up, lo = cm.rectangular_chains(tools)
    elif bead == 'profile':
        _, up = cm.read_profile(tools['upper_profile'])
        _, lo = cm.read_profile(tools['lower_profile'])
    else:
        fail("bead = '%s': only tools ('rectangular', 'profile') have pieces to trace" % bead)
    chains = {'upper': up, 'lower': lo}
    names = {}
    for side, ch in chains.items():
        if bead == 'rectangular':
            # zero-length pieces (bead B's sides, H1 = 0) were left out
            full = RECT_NAMES[side]
            b1, h1 = float(tools['b1']), float(tools['h1'])
            keep = [True] * 7
            if side == 'lower' and h1 == 0.0:
                keep[1] = keep[5] = False
            if side == 'lower' and b1 == 0.0:
                keep[3] = False
            nm = [n for n, k in zip(full, keep) if k]
            if len(nm) != len(ch):
                nm = [piece_label(p, h) for p in ch]
        else:
            nm = [piece_label(p, h) for p in ch]
        names[side] = nm
    return h, float(load['lock_depth']), chains, names


def piece_label(p, h):
    """A generic name of a piece: kind and x-range in h."""
    xa, xb = sorted((p[1][0] / h, p[2][0] / h))
    if p[0] == 'arc':
        r = math.hypot(p[1][0] - p[3][0], p[1][1] - p[3][1]) / h
        return 'arc R=%.3gh x/h %.3g..%.3g' % (r, xa, xb)
    return 'line x/h %.3g..%.3g' % (xa, xb)


def nearest(pieces, x, y):
    """(index of the nearest piece, unit tangent (left to right), unit normal
    of the chain) at the nearest point to (x, y); the end pieces are
    continued along their tangents. The normal is the tangent turned
    counter-clockwise (for the upper tool it points into the tool's
    material, for the lower one out of it: cm.material_normal)."""
    best = None
    n = len(pieces)
    for k, p in enumerate(pieces):
        if p[0] == 'line':
            (x0, y0), (x1, y1) = p[1], p[2]
            dx, dy = x1 - x0, y1 - y0
            ll = math.hypot(dx, dy)
            tx, ty = dx / ll, dy / ll
            s = (x - x0) * tx + (y - y0) * ty
            lo_s = -math.inf if k == 0 else 0.0
            hi_s = math.inf if k == n - 1 else ll
            s = min(max(s, lo_s), hi_s)
            qx, qy = x0 + s * tx, y0 + s * ty
        else:
            _, p0, _, c, ccw = p
            r = math.hypot(p0[0] - c[0], p0[1] - c[1])
            a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
            sw = cm.arc_sweep(p)
            a = math.atan2(y - c[1], x - c[0])
            # the angle from the start along the sweep, clamped to the arc
            rel = (a - a0) if sw > 0 else (a0 - a)
            rel %= 2 * math.pi
            if rel > abs(sw):
                rel = abs(sw) if rel - abs(sw) < 2 * math.pi - rel else 0.0
            aq = a0 + (rel if sw > 0 else -rel)
            qx, qy = c[0] + r * math.cos(aq), c[1] + r * math.sin(aq)
            rx, ry = qx - c[0], qy - c[1]
            tx, ty = ((-ry, rx) if ccw else (ry, -rx))
            tx, ty = tx / r, ty / r
        d = math.hypot(x - qx, y - qy)
        if best is None or d < best[0] - 1e-12:
            best = (d, k, (tx, ty))
    _, k, (tx, ty) = best
    return k, (tx, ty), (-ty, tx)


# ---------------------------------------------------------------------------
# The program: pull.dat, snapshots.dat, the forces per station
# ---------------------------------------------------------------------------

def read_rows(path):
    """Numeric rows of a column file."""
    rows = []
    for line in read_text(path).splitlines():
        w = line.split()
        if w and not line.lstrip().startswith('#'):
            rows.append([float(v) for v in w])
    return rows


def read_snapshots(path):
    """Pull blocks of snapshots.dat: [(delta/h, rows)] in run order."""
    blocks = []
    cur = None
    with open(path) as f:
        for line in f:
            if line.startswith('# block'):
                w = line.split()
                cur = None
                if w[3] == 'pull':
                    cur = []
                    blocks.append((float(w[4]), cur))
                continue
            if cur is None or line.startswith('#'):
                continue
            w = line.split()
            if w:
                cur.append([float(v) for v in w])
    return blocks


def program_forces(rows, h, lock, chains):
    """Per tool and piece, the normal force of the tool on the sheet
    (N/mm), rebuilt from the strain rows of one state:
    {side: [[fx, fy] per piece]}."""
    out = {s: [[0.0, 0.0] for _ in chains[s]] for s in chains}
    if len(rows) % 4:
        fail('a snapshot block has %d rows, not four per element' % len(rows))
    for e in range(0, len(rows), 4):
        el = rows[e:e + 4]
        # the element's reference length from its first and last station
        le = 2.0 * (el[3][0] - el[0][0]) * h / (GAUSS_X[3] - GAUSS_X[0])
        for i, r in enumerate(el):
            wgt = GAUSS_W[i] * 0.5 * le
            for side, pcol, fcol, shift in (('upper', 15, 5, 0.0), ('lower', 16, 6, lock)):
                p = r[pcol]
                if p <= 0.0:
                    continue
                fn = p * math.exp(r[fcol]) * wgt
                k, _, (nx, ny) = nearest(chains[side], r[1] * h, r[2] * h - shift)
                # the chain's normal toward the sheet: out of the tool
                if side == 'upper':
                    nx, ny = -nx, -ny
                out[side][k][0] += fn * nx
                out[side][k][1] += fn * ny
    return out


def interp_blocks(blocks, d, fn):
    """fn applied to the two blocks around delta/h = d, interpolated
    linearly (dicts of lists of lists of numbers); None outside."""
    ds = [b[0] for b in blocks]
    k = bisect.bisect_left(ds, d)
    if k >= len(ds):
        return None
    if abs(ds[k] - d) < 1e-12 or k == 0:
        if k == 0 and ds[0] > d + 1e-9:
            return None
        return fn(blocks[k][1])
    a, b = fn(blocks[k - 1][1]), fn(blocks[k][1])
    w = (d - ds[k - 1]) / (ds[k] - ds[k - 1])
    return {s: [[(1 - w) * u + w * v for u, v in zip(pa, pb)] for pa, pb in zip(a[s], b[s])]
            for s in a}


def interp(xs, ys, x):
    """Linear interpolation of ys(xs) at x (None outside)."""
    for k in range(1, len(xs)):
        if xs[k - 1] <= x <= xs[k] + 1e-12:
            if xs[k] == xs[k - 1]:
                return ys[k]
            return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1])
    return None


def peak_delta(ds, ns):
    """delta/h of the largest restraining force: the vertex of the parabola
    through the largest row and its neighbours (as continuum_results.py)."""
    k = max(range(len(ns)), key=lambda i: ns[i])
    if 0 < k < len(ns) - 1:
        x0, x1, x2 = ds[k - 1], ds[k], ds[k + 1]
        y0, y1, y2 = ns[k - 1], ns[k], ns[k + 1]
        den = (x0 - x1) * (x0 - x2) * (x1 - x2)
        a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / den
        b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / den
        if a < 0:
            dv = min(max(-b / (2 * a), x0), x2)
            nv = y0 + (a * (dv ** 2 - x0 ** 2) + b * (dv - x0))
            if nv <= 1.005 * y1:
                return dv
    return ds[k]


# ---------------------------------------------------------------------------
# The continuum: node coordinates, per-node and total reactions
# ---------------------------------------------------------------------------

def read_inp_nodes(path):
    """{node: (x, y)} of the *NODE block of continuum.inp, and the node sets
    NUPPER, NLOWER as lists."""
    nodes, sets = {}, {}
    mode, cur = None, None
    for line in read_text(path).splitlines():
        s = line.strip()
        if not s or s.startswith('**'):
            continue
        if s.startswith('*'):
            key = s.upper()
            mode = None
            if key.startswith('*NODE,') and 'PRINT' not in key:
                mode = 'node'
            elif key.startswith('*NSET'):
                m = re.search(r'NSET\s*=\s*(\w+)', key)
                if m and m.group(1) in ('NUPPER', 'NLOWER'):
                    mode, cur = 'set', m.group(1)
                    sets[cur] = []
            continue
        if mode == 'node':
            w = s.split(',')
            nodes[int(w[0])] = (float(w[1]), float(w[2]))
        elif mode == 'set':
            sets[cur] += [int(v) for v in s.split(',') if v.strip()]
    return nodes, sets


def read_ccx_forces(path):
    """{time: {'total': {SET: (fx, fy)}, 'node': {SET: {node: (fx, fy)}},
    'U': {node: (ux, uy)}}} from continuum.dat (its 'total force', 'forces'
    and 'displacements' blocks)."""
    out = {}
    head = re.compile(r'^\s*(total force|forces|displacements|equivalent plastic strain|'
                      r'stresses|contact)\b.*?for set (\S+) and time\s+(\S+)')
    kind = None
    blk = None
    name = None
    try:
        f = open(path)
    except OSError as e:
        fail('cannot read %s: %s' % (path, e.strerror))
    with f:
        for line in f:
            m = head.match(line)
            if m:
                kind, name, t = m.group(1), m.group(2), float(m.group(3))
                blk = out.setdefault(t, {'total': {}, 'node': {}, 'U': {}})
                if kind == 'forces':
                    blk['node'][name] = {}
                continue
            if kind not in ('total force', 'forces', 'displacements'):
                continue
            w = line.split()
            if not w:
                continue
            if kind == 'total force':
                blk['total'][name] = (float(w[0]), float(w[1]))
                kind = None
            elif kind == 'forces':
                blk['node'][name][int(w[0])] = (float(w[1]), float(w[2]))
            else:
                blk['U'][int(w[0])] = (float(w[1]), float(w[2]))
    return out


def steepest(points, x_max):
    """The steepest slope (degrees, absolute) of a polyline [(x, y)] between
    neighbouring points on each side of the bead: (entry side x < 0, exit
    side x > 0), within |x| < x_max."""
    out = [0.0, 0.0]
    for a, b in zip(points, points[1:]):
        xm = 0.5 * (a[0] + b[0])
        if abs(xm) >= x_max or b[0] == a[0]:
            continue
        ang = abs(math.degrees(math.atan2(b[1] - a[1], b[0] - a[0])))
        k = 0 if xm < 0 else 1
        out[k] = max(out[k], ang)
    return out


def continuum_pieces(nodes, sets, chains):
    """{side: {node: piece index}} for the tool strips' nodes."""
    out = {}
    for side, set_name in (('upper', 'NUPPER'), ('lower', 'NLOWER')):
        out[side] = {n: nearest(chains[side], *nodes[n])[0] for n in sets.get(set_name, [])}
    return out


def continuum_state(blk, owner, chains, nodes):
    """Per tool and piece, the force of the tool on the sheet (N/mm) split
    into its normal and tangential (friction) parts along the chain at the
    node: {side: [[normal_x, normal_y, friction_x, friction_y] per piece]}."""
    out = {s: [[0.0] * 4 for _ in chains[s]] for s in chains}
    for side, set_name in (('upper', 'NUPPER'), ('lower', 'NLOWER')):
        for n, (fx, fy) in blk['node'].get(set_name, {}).items():
            k = owner[side].get(n)
            if k is None:
                continue
            _, (tx, ty), _ = nearest(chains[side], *nodes[n])
            ft = fx * tx + fy * ty
            acc = out[side][k]
            acc[0] += fx - ft * tx
            acc[1] += fy - ft * ty
            acc[2] += ft * tx
            acc[3] += ft * ty
    return out


# ---------------------------------------------------------------------------
# Commands
# ---------------------------------------------------------------------------

def load_continuum(ccx_dir):
    """(info: continuum_model.json, the output times with totals, the
    data of read_ccx_forces) of a continuum run."""
    try:
        info = json.loads(read_text(os.path.join(ccx_dir, 'continuum_model.json')))
    except ValueError as e:
        fail('cannot read %s/continuum_model.json: %s' % (ccx_dir, e))
    dat = read_ccx_forces(os.path.join(ccx_dir, 'continuum.dat'))
    times = sorted(t for t in dat if dat[t]['total'])
    return info, times, dat


def cmd_ccx_forces(args):
    if len(args) != 1:
        fail('usage: lift_trace.py ccx-forces CCX_DIR')
    info, times, dat = load_continuum(args[0])
    h, pull = info['thickness'], info['pull_distance']
    print('# time delta/h N F lift R_left_y R_right_y sum_node_upper_y sum_node_lower_y')
    for t in times:
        b = dat[t]
        tot = b['total']
        nu = sum(v[1] for v in b['node'].get('NUPPER', {}).values()) if 'NUPPER' in b['node'] else float('nan')
        nl = sum(v[1] for v in b['node'].get('NLOWER', {}).values()) if 'NLOWER' in b['node'] else float('nan')
        d = max(0.0, t - 1.0) * pull / h
        print('%.6g %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f' % (
            t, d, tot.get('NRIGHT', (math.nan,))[0], tot.get('NLOWER', (0, math.nan))[1],
            -tot.get('NUPPER', (0, math.nan))[1], tot.get('NLEFT', (0, math.nan))[1],
            tot.get('NRIGHT', (0, math.nan))[1], nu, nl))
    return 0


def fmt(v, w=8, p=1):
    """A number in a fixed width, '-' for none."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return '-'.rjust(w)
    if abs(v) < 0.5 * 10.0 ** -p:
        v = 0.0          # no '-0.00'
    return ('%*.*f' % (w, p, v))


def cmd_trace(args):
    at = [0.5, 1.0]
    pos = []
    i = 0
    while i < len(args):
        if args[i] == '--at':
            if i + 1 >= len(args):
                fail('--at needs a list of delta/h')
            try:
                at = [float(v) for v in args[i + 1].split(',') if v.strip()]
            except ValueError:
                fail("--at needs numbers, not '%s'" % args[i + 1])
            i += 2
        else:
            pos.append(args[i])
            i += 1
    if len(pos) != 2:
        fail('usage: lift_trace.py trace PROGRAM_DIR CCX_DIR [--at D1,D2,...]')
    prog_dir, ccx_dir = pos
    nml = cm.parse_resolved(read_text(os.path.join(prog_dir, 'run.log')))
    if not nml or 'tools' not in nml:
        fail('%s/run.log holds no resolved input' % prog_dir)
    h, lock, chains, names = case_tools(nml)
    e_h = float(nml['material']['youngs_modulus']) * h

    # the program
    pull = read_rows(os.path.join(prog_dir, 'pull.dat'))
    if not pull:
        fail('%s/pull.dat has no rows' % prog_dir)
    snap_path = os.path.join(prog_dir, 'snapshots.dat')
    if not os.path.exists(snap_path):
        fail('%s has no snapshots.dat (run with &control snapshot_every > 0)' % prog_dir)
    blocks = read_snapshots(snap_path)
    # one block per increment: the last block at each pull (a refine_exit
    # re-equilibration writes its own)
    dedup = {}
    for d, rows in blocks:
        dedup[round(d, 12)] = (d, rows)
    blocks = [dedup[k] for k in sorted(dedup)]
    p_ds, p_ns = [r[0] for r in pull], [r[2] for r in pull]
    p_lift, p_f = [r[7] for r in pull], [r[9] * e_h for r in pull]

    # the continuum
    info, times, dat = load_continuum(ccx_dir)
    if not any('NUPPER' in dat[t]['node'] for t in times):
        fail('%s/continuum.dat has no per-node reactions of NUPPER, NLOWER '
             '(run the continuum with scripts/lift_trace.sh)' % ccx_dir)
    nodes, sets = read_inp_nodes(os.path.join(ccx_dir, 'continuum.inp'))
    owner = continuum_pieces(nodes, sets, chains)
    # the largest restraining force from every output time, the pieces
    # from those with the per-node reactions (all of them, or those a
    # trimmed copy kept: trim-ccx)
    c_all = [t for t in times if t > 1.0 + 1e-9]
    c_all_ds = [(t - 1.0) * info['pull_distance'] / h for t in c_all]
    c_ns = [dat[t]['total']['NRIGHT'][0] for t in c_all]
    c_times = [t for t in c_all if 'NUPPER' in dat[t]['node']]
    c_ds = [(t - 1.0) * info['pull_distance'] / h for t in c_times]

    def c_at(d):
        """Continuum per piece (interpolated) and edges' y reactions at d."""
        k = bisect.bisect_left(c_ds, d - 1e-9)
        if k >= len(c_ds) or (k == 0 and c_ds[0] > d + 1e-9):
            return None, None
        pairs = [(k, 1.0)] if abs(c_ds[k] - d) < 1e-9 or k == 0 else \
            [(k - 1, (c_ds[k] - d) / (c_ds[k] - c_ds[k - 1])),
             (k, (d - c_ds[k - 1]) / (c_ds[k] - c_ds[k - 1]))]
        acc, edges = None, [0.0, 0.0]
        for j, w in pairs:
            blk = dat[c_times[j]]
            st = continuum_state(blk, owner, chains, nodes)
            if acc is None:
                acc = {s: [[0.0] * 4 for _ in st[s]] for s in st}
            for s in st:
                for a, b in zip(acc[s], st[s]):
                    for q in range(4):
                        a[q] += w * b[q]
            edges[0] += w * blk['total']['NLEFT'][1]
            edges[1] += w * blk['total']['NRIGHT'][1]
        return acc, edges

    instants = [('%gh' % d, d, d) for d in at]
    instants.append(('largest N', peak_delta(p_ds, p_ns), peak_delta(c_all_ds, c_ns)))
    title = re.sub(r'\s*\[case_\d+ [^]]*\]$', '', str(nml['control'].get('title', '')))
    print('# lift traced tool by tool: %s' % title)
    print('# vertical force of the tools on the sheet, N/mm, upward positive (the lift is '
          'minus the upper tool\'s); per piece of each tool its normal part (program: '
          'rebuilt from the contact pressures of snapshots.dat; continuum: the tool nodes\' '
          'RF along the chain\'s normal), per tool the friction part (program: its total '
          'less the normal parts; continuum: RF along the chain) and the total')
    fmt_row = '%-6s %-30s %9s %9s %8s %7s %9s'
    x_max = info['bead_half_width']
    if x_max <= 0:
        fail('the model has no bead half-width')

    def spans_program(d):
        blk = min(blocks, key=lambda b: abs(b[0] - d))
        return blk[0], steepest([(r[1] * h, r[2] * h) for r in blk[1]], x_max)

    def spans_continuum(d):
        j = min(range(len(c_ds)), key=lambda i: abs(c_ds[i] - d))
        u = dat[c_times[j]]['U']
        pts = [(info['node_x'][str(n)] + u[n][0], info['node_y'][str(n)] + u[n][1])
               for n in info['mid'] if n in u]
        return c_ds[j], steepest(pts, x_max)
    for label, dp, dc in instants:
        pst = interp_blocks(blocks, dp, lambda rows: program_forces(rows, h, lock, chains))
        cst, cedge = c_at(dc)
        print('')
        print('## %s: program at delta/h = %.3f, continuum at %.3f' % (label, dp, dc))
        print(fmt_row % ('tool', 'piece', 'program', 'continuum', 'diff', 'ratio',
                         'c.fric'))
        if pst is None or cst is None:
            print('# not reached by %s' % ('the program' if pst is None else 'the continuum'))
            continue
        lift_p, f_p = interp(p_ds, p_lift, dp), interp(p_ds, p_f, dp)
        totals_p = {'lower': f_p, 'upper': -lift_p}

        def row(side, name, pv, cv, sign=1.0, cf=None):
            ratio = pv / cv if abs(cv) > 1.0 else None
            print((fmt_row % (side, name, fmt(sign * pv, 9, 2), fmt(sign * cv, 9, 2),
                              fmt(sign * (pv - cv), 8, 2), fmt(ratio, 7, 3),
                              '' if cf is None else fmt(cf, 9, 2))).rstrip())
        for side in ('lower', 'upper'):
            for k, nm in enumerate(names[side]):
                pv, cv = pst[side][k][1], cst[side][k][1]
                if abs(pv) < 0.05 and abs(cv) < 0.05:
                    continue
                row(side, nm + ' (normal)', pv, cv, cf=cst[side][k][3])
            np_, nc = sum(v[1] for v in pst[side]), sum(v[1] for v in cst[side])
            fc = sum(v[3] for v in cst[side])
            row(side, 'normal, all pieces', np_, nc)
            row(side, 'friction', totals_p[side] - np_, fc)
            if side == 'lower':
                row(side, 'total: punch force F', totals_p[side], nc + fc)
            else:
                row(side, 'total: lift (minus the force)', totals_p[side], nc + fc, -1.0)
        print((fmt_row % ('edges', 'R_left + R_right', fmt(lift_p - f_p, 9, 2),
                          fmt(cedge[0] + cedge[1], 9, 2),
                          fmt(lift_p - f_p - cedge[0] - cedge[1], 8, 2), '', '')).rstrip())
        print('# continuum edges: R_left %.2f, R_right %.2f; the program\'s edges are '
              'lift - F (pull.dat)' % (cedge[0], cedge[1]))
        blk = min(blocks, key=lambda b: abs(b[0] - dp))[1]
        xb = x_max / h
        near = [math.exp(r[7]) for r in blk if xb < abs(r[1]) < xb + 2.0]
        inside = [math.exp(r[7]) for r in blk if abs(r[1]) <= xb]
        if near and inside:
            print('# the program\'s sheet thickness t/h: %.3f-%.3f on the binders within 2h of '
                  'the bead, %.3f-%.3f in the bead' % (min(near), max(near), min(inside),
                                                       max(inside)))
        sdp, sp = spans_program(dp)
        sdc, sc = spans_continuum(dc)
        print('# steepest slope of the mid-surface (the free spans between the tools), '
              'entry and exit side: program %.2f, %.2f deg (delta/h %.3f), continuum '
              '%.2f, %.2f deg (delta/h %.3f); sin ratio %.4f, %.4f'
              % (sp[0], sp[1], sdp, sc[0], sc[1], sdc,
                 math.sin(math.radians(sp[0])) / math.sin(math.radians(sc[0])),
                 math.sin(math.radians(sp[1])) / math.sin(math.radians(sc[1]))))
    return 0


def split_at(args):
    """The --at D1,D2,... option (default 0.5h and 1h) and the positional
    arguments of a subcommand."""
    at, pos = [0.5, 1.0], []
    i = 0
    while i < len(args):
        if args[i] == '--at' and i + 1 < len(args):
            at = [float(v) for v in args[i + 1].split(',') if v.strip()]
            i += 2
        else:
            pos.append(args[i])
            i += 1
    return at, pos


def cmd_summary(args):
    at, pos = split_at(args)
    if len(pos) != 3:
        fail('usage: lift_trace.py summary LABEL PROGRAM_DIR CCX_DIR [--at D1,D2,...]')
    label, prog_dir, ccx_dir = pos
    nml = cm.parse_resolved(read_text(os.path.join(prog_dir, 'run.log')))
    if not nml:
        fail('%s/run.log holds no resolved input' % prog_dir)
    h = float(nml['sheet']['thickness'])
    pull = read_rows(os.path.join(prog_dir, 'pull.dat'))
    if not pull:
        fail('%s/pull.dat has no rows' % prog_dir)
    info, times, dat = load_continuum(ccx_dir)
    c_times = [t for t in times if t > 1.0 + 1e-9]
    c_ds = [(t - 1.0) * info['pull_distance'] / h for t in c_times]
    c_ns = [dat[t]['total']['NRIGHT'][0] for t in c_times]
    c_lift = [-dat[t]['total']['NUPPER'][1] for t in c_times]
    p_ds, p_ns, p_lift = [r[0] for r in pull], [r[2] for r in pull], [r[7] for r in pull]
    parts = []
    for d in at:
        lp, lc = interp(p_ds, p_lift, d), interp(c_ds, c_lift, d)
        parts.append('lift at %gh %s / %s = %s' % (
            d, fmt(lp, 1, 1).strip(), fmt(lc, 1, 1).strip(),
            fmt(None if lp is None or lc is None else lp / lc, 1, 3).strip()))
    dp, dc = peak_delta(p_ds, p_ns), peak_delta(c_ds, c_ns)
    lp, lc = interp(p_ds, p_lift, dp), interp(c_ds, c_lift, dc)
    np_, nc = interp(p_ds, p_ns, dp), interp(c_ds, c_ns, dc)
    parts.append('at the largest N %s / %s = %s' % (fmt(lp, 1, 1).strip(), fmt(lc, 1, 1).strip(),
                                                   fmt(lp / lc, 1, 3).strip()))
    parts.append('largest N %s / %s = %s' % (fmt(np_, 1, 1).strip(), fmt(nc, 1, 1).strip(),
                                           fmt(np_ / nc, 1, 3).strip()))
    print('%s: %s (program / continuum, N/mm)' % (label, '; '.join(parts)))
    return 0


def cmd_trim_ccx(args):
    at, pos = split_at(args)
    if len(pos) != 2:
        fail('usage: lift_trace.py trim-ccx CCX_DIR OUT_DIR [--at D1,D2,...]')
    src, dst = pos
    info, times, dat = load_continuum(src)
    h = info['thickness']
    nodes, sets = read_inp_nodes(os.path.join(src, 'continuum.inp'))
    pulled = [t for t in times if t > 1.0 + 1e-9]
    ds = [(t - 1.0) * info['pull_distance'] / h for t in pulled]
    ns = [dat[t]['total']['NRIGHT'][0] for t in pulled]
    keep = set()
    for d in at + [peak_delta(ds, ns)]:
        k = bisect.bisect_left(ds, d - 1e-9)
        if k < len(ds):
            keep.add(pulled[k])
            if abs(ds[k] - d) > 1e-9 and k > 0:
                keep.add(pulled[k - 1])
    os.makedirs(dst, exist_ok=True)
    # the tool nodes that carry a force at a kept time, the mid-surface
    # nodes within the bead (where the spans' slopes are read, with 2h to
    # spare)
    # (below 1e-6 of the tool's largest nodal force: round-off of the
    # rigid strip's prescribed motion, left out)
    loaded = set()
    for t in keep:
        for name in ('NUPPER', 'NLOWER'):
            fs = dat[t]['node'][name]
            big = max((math.hypot(*f) for f in fs.values()), default=0.0)
            loaded |= {n for n, f in fs.items() if math.hypot(*f) > 1e-6 * big}
    for name in ('NUPPER', 'NLOWER'):
        sets[name] = [n for n in sets.get(name, []) if n in loaded]
    tool = sets['NUPPER'] + sets['NLOWER']
    x_in = info['bead_half_width'] + 2 * h
    with open(os.path.join(dst, 'continuum.inp'), 'w') as f:
        f.write('** the loaded tool nodes of the continuum model of %s (scripts/lift_trace.py '
                'trim-ccx)\n*NODE, NSET=NALL\n' % info.get('deck', '?'))
        f.writelines('%d, %.12g, %.12g\n' % (n, nodes[n][0], nodes[n][1]) for n in tool)
        for name in ('NUPPER', 'NLOWER'):
            f.write('*NSET, NSET=%s\n' % name)
            ids = sets.get(name, [])
            f.writelines(', '.join(str(n) for n in ids[j:j + 8]) + '\n'
                         for j in range(0, len(ids), 8))
    mid = [n for n in info['mid'] if abs(info['node_x'][str(n)]) < x_in]
    small = {k: info[k] for k in ('deck', 'title', 'thickness', 'half_length', 'youngs_modulus',
                                  'lock_depth', 'pull_distance', 'bead_half_width')
             if k in info}
    small['mid'] = mid
    small['node_x'] = {str(n): info['node_x'][str(n)] for n in mid}
    small['node_y'] = {str(n): info['node_y'][str(n)] for n in mid}
    with open(os.path.join(dst, 'continuum_model.json'), 'w') as f:
        json.dump(small, f)
    with open(os.path.join(dst, 'continuum.dat'), 'w') as f:
        f.write(' the pull of the continuum run of %s: the totals at every output time, the '
                'tools\' per-node reactions (non-zero) and the mid-surface displacements at '
                'those around delta/h %s and the largest restraining force '
                '(scripts/lift_trace.py trim-ccx)\n\n'
                % (info.get('deck', '?'), ', '.join('%g' % d for d in at)))
        for t in pulled:
            b = dat[t]
            for name in ('NRIGHT', 'NLEFT', 'NUPPER', 'NLOWER'):
                fx, fy = b['total'][name]
                f.write(' total force (fx,fy,fz) for set %s and time  %.7E\n\n'
                        '  %.6E  %.6E  0.000000E+00\n\n' % (name, t, fx, fy))
            if t not in keep:
                continue
            for name in ('NUPPER', 'NLOWER'):
                f.write(' forces (fx,fy,fz) for set %s and time  %.7E\n\n' % (name, t))
                f.writelines('%10d  %.6E  %.6E  0.000000E+00\n' % (n, fx, fy)
                             for n, (fx, fy) in sorted(b['node'][name].items())
                             if n in loaded)
                f.write('\n')
            f.write(' displacements (vx,vy,vz) for set NSTRAIN and time  %.7E\n\n' % t)
            f.writelines('%10d  %.6E  %.6E  0.000000E+00\n' % (n, b['U'][n][0], b['U'][n][1])
                         for n in mid if n in b['U'])
            f.write('\n')
    return 0


def cmd_patch_inp(args):
    if len(args) != 1:
        fail('usage: lift_trace.py patch-inp CONTINUUM_INP')
    text = read_text(args[0])
    if re.search(r'^\*NODE PRINT, NSET=NUPPER, TIME POINTS=TP$', text, re.M):
        return 0
    key = '*NODE PRINT, NSET=NSTRAIN'
    k = text.find(key)
    if k < 0 or '*NSET, NSET=NUPPER' not in text:
        fail('%s is not a model of scripts/continuum_model.py with tools' % args[0])
    add = ''.join('*NODE PRINT, NSET=%s, TIME POINTS=TP\nRF\n' % n for n in ('NUPPER', 'NLOWER'))
    with open(args[0], 'w') as f:
        f.write(text[:k] + add + text[k:])
    return 0


def cmd_offset_deck(args):
    if len(args) != 5:
        fail('usage: lift_trace.py offset-deck RUN_LOG VARIABLES DECK OUT DELTA_OVER_H')
    run_log, variables, deck, out, dh = args
    try:
        delta_h = float(dh)
    except ValueError:
        fail("the offset needs a number, not '%s'" % dh)
    nml = cm.parse_resolved(read_text(run_log))
    if not nml or str(nml.get('tools', {}).get('bead', '')).lower() != 'rectangular':
        fail('--offset needs a rectangular bead (the deck of %s)' % run_log)
    import sweep_tool as sw
    sw.read_variables(variables)
    t = nml['tools']
    h = float(nml['sheet']['thickness'])
    d = delta_h * h
    r1, r2, b2, h1, h2 = (float(t[k]) for k in ('r1', 'r2', 'b2', 'h1', 'h2'))
    lock = float(nml['loading']['lock_depth'])
    if d >= min(r1, r2):
        fail('the offset %g h is not below the radii' % delta_h)
    # both tools' centreline chains moved by d toward the tools (each arc
    # keeps its centre, its radius less d; the walls and sides move out,
    # the lower binder face down), all heights then lowered by d so that
    # the upper binder face stays at y = 0: the lower binder face ends 2d
    # below it at the same lock
    new = {'r1': r1 - d, 'r2': r2 - d, 'b2': b2 + d, 'h1': h1 + d, 'h2': h2 + d,
           'lock_depth': lock - 2 * d}
    text = read_text(deck)
    for var, val in new.items():
        text = sw.override(text, var, '%.9g' % val)
    head = ('! %s with the tools\' centreline chains offset by %g h toward the tools '
            '(scripts/lift_trace.sh --offset): %s\n'
            % (deck, delta_h, ', '.join('%s = %.9g' % kv for kv in new.items())))
    with open(out, 'w') as f:
        f.write(head + text)
    return 0


def main(argv):
    if not argv or argv[0] in ('-h', '--help'):
        print(__doc__)
        return 0 if argv else 2
    cmd, args = argv[0], argv[1:]
    if cmd == 'trace':
        return cmd_trace(args)
    if cmd == 'ccx-forces':
        return cmd_ccx_forces(args)
    if cmd == 'patch-inp':
        return cmd_patch_inp(args)
    if cmd == 'offset-deck':
        return cmd_offset_deck(args)
    if cmd == 'summary':
        return cmd_summary(args)
    if cmd == 'trim-ccx':
        return cmd_trim_ccx(args)
    fail("unknown command '%s' (trace, ccx-forces)" % cmd)
    return 2


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
