#!/usr/bin/env python3
"""exit_state.py -- the state of the sheet leaving the bead, program against
the CalculiX continuum, at the same material point (scripts/exit_state_check.sh
runs both; docs/validation.md, "The sheet leaving the bead").

Usage:
    exit_state.py station PROGRAM_DIR
    exit_state.py patch-inp CONTINUUM_INP MODEL_JSON S_OVER_H [--band B]
    exit_state.py extract CCX_DIR OUT_FILE S_OVER_H [--band B]
    exit_state.py summary LABEL PROGRAM_DIR CONTINUUM_FILE
    exit_state.py compare PROGRAM_DIR CONTINUUM_FILE [--check]
                          [--tol-thickness T] [--tol-eqps E] [--tol-middle M]

station    prints the reference s/h of the program's exit station (the
           '# station:' line of PROGRAM_DIR/exit_state.dat).
patch-inp  adds to a continuum.inp (scripts/continuum_model.py) an element
           set EXITBAND, the sheet's elements (every row through the
           thickness) whose reference x lies within B h (default 4) of
           S_OVER_H h, and the output of their integration points'
           equivalent plastic strain and current coordinates (once).
extract    reads the continuum's last output time (CCX_DIR/continuum.dat,
           continuum_model.json) and writes OUT_FILE, a small text file:
           per column of integration points of EXITBAND within B h of the
           station (reference x), their equivalent plastic strain at each
           reference height z (the continuum's rows of integration
           points), and per pair of neighbouring mid-surface nodes the
           thickness (measured normal to the mid-surface, as
           scripts/continuum_results.py's strain files) and the current x.
           The integration points are placed from their current
           coordinates (side of the element's centre along and across the
           current mid-surface), not from CalculiX's numbering.
compare    the program's exit_state.dat (PROGRAM_DIR) against OUT_FILE,
           the continuum interpolated (linearly along the reference x) at
           the program's station: the same material, the same reference x.
           Prints the thickness, the equivalent plastic strain at the
           bottom face, the middle and the top face (the continuum's face
           values extrapolated linearly from the outer element's two rows
           of integration points, its middle the mean of the two rows next
           to it), and the profile at the continuum's rows, program
           interpolated linearly in z; each with program / continuum.
           Also the thickness log strain ln(t/h) of both: in the middle
           the plastic strain is the membrane's, (2/sqrt 3) |ln(t/h)| in
           plane strain, so its ratio is the middle eqps ratio's.
           With --check the exit status is 1 when the thickness ratio is
           off 1 by more than T (default 0.02), an eqps ratio at a face by
           more than E (default 0.10) or at the middle by more than M
           (default E).
summary    one line LABEL: the thickness and the eqps at the faces and the
           middle, program / continuum, as compare reads them (for the
           variants of exit_state_check.sh --also and --offset; the
           continuum at each variant's own station).

Exit status 0; 1 a --check failed; 2 a missing or unreadable file, or a
station outside the continuum's kept band.
"""

import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import continuum_results  # noqa: E402  (read_dat, strain_rows)

GAUSS = 1.0 / math.sqrt(3.0)


def fail(msg):
    """Print 'exit_state.py: MSG' on stderr and exit 2."""
    sys.stderr.write('exit_state.py: %s\n' % msg)
    sys.exit(2)


def read_exit_state(run_dir):
    """The program's exit_state.dat: (header dict, rows)."""
    path = os.path.join(run_dir, 'exit_state.dat')
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail('cannot read %s: %s' % (path, e))
    head = {}
    rows = []
    for line in lines:
        if line.startswith('# station:'):
            head['s'] = float(re.search(r's/h = (\S+)', line).group(1))
            head['x'] = float(re.search(r', x/h = (\S+),', line).group(1))
            head['x_exit'] = float(re.search(r'\(x/h = (\S+)\)', line).group(1))
        elif line.startswith('# passed the whole bead:'):
            head['passed'] = line.split(':')[1].split()[0]
            head['x_first'] = float(re.search(r'x/h = (\S+)\)', line).group(1))
        elif line.startswith('# thickness/h'):
            head['thickness'] = float(re.search(r'thickness/h = ([^,]+),', line).group(1))
        elif not line.startswith('#') and line.strip():
            rows.append([float(w) for w in line.split()])
    if 's' not in head or 'thickness' not in head or not rows:
        fail('%s: no station, thickness or rows' % path)
    return head, rows


def elements_in_band(info, s_over_h, band):
    """Sheet element numbers (every row) whose reference x range comes
    within BAND h of S_OVER_H h."""
    h, half, nx, ny = info['thickness'], info['half_length'], info['nx'], info['ny']
    dx = 2 * half / nx
    lo, hi = (s_over_h - band) * h, (s_over_h + band) * h
    cols = [ei for ei in range(nx) if -half + (ei + 1) * dx >= lo and -half + ei * dx <= hi]
    return [ej * nx + ei + 1 for ej in range(ny) for ei in cols]


def patch_inp(inp, model_json, s_over_h, band):
    """Add EXITBAND and its integration-point output to INP (once)."""
    info = json.load(open(model_json))
    text = open(inp).read()
    if 'ELSET=EXITBAND' in text:
        return
    elems = elements_in_band(info, s_over_h, band)
    if not elems:
        fail('no sheet element within %gh of s/h = %g' % (band, s_over_h))
    lines = ['*ELSET, ELSET=EXITBAND']
    for k in range(0, len(elems), 8):
        lines.append(', '.join(str(e) for e in elems[k:k + 8]))
    lines.append('*EL PRINT, ELSET=EXITBAND\nCOORD')
    pos = text.index('*END STEP')
    # the element set before the step, the output request inside it
    step = text.index('*STEP')
    text = (text[:step] + lines[0] + '\n' + '\n'.join(lines[1:-1]) + '\n' + text[step:pos]
            + lines[-1] + '\n' + text[pos:])
    open(inp, 'w').write(text)


def read_ip_blocks(path, kind, ncol):
    """The integration-point blocks of one kind in a .dat file ('global
    coordinates', 'equivalent plastic strain'): {time: {(elem, ip): the
    NCOL values after the two indices}}."""
    head = re.compile(r'^\s*(\S.*?)\s*\(.*for set (\S+) and time\s+(\S+)')
    blocks = {}
    cur = None
    with open(path) as f:
        for line in f:
            m = head.match(line)
            if m:
                cur = blocks.setdefault(float(m.group(3)), {}) if m.group(1) == kind else None
                continue
            if cur is not None:
                w = line.split()
                if len(w) >= 2 + ncol:
                    cur[(int(w[0]), int(w[1]))] = tuple(float(v) for v in w[2:2 + ncol])
    return blocks


def read_coord(path):
    """The integration points' coordinates of the last output time in a
    .dat file: (time, {(elem, ip): (x, y)})."""
    blocks = read_ip_blocks(path, 'global coordinates', 2)
    if not blocks:
        fail('%s holds no integration-point coordinates (was the input patched?)' % path)
    t = max(blocks)
    return t, blocks[t]


def read_peeq(path, t_want):
    """Per integration point PEEQ at time T_WANT: {(elem, ip): value}."""
    for t, block in read_ip_blocks(path, 'equivalent plastic strain', 1).items():
        if abs(t - t_want) <= 1e-9 * max(1.0, t_want):
            return {k: v[0] for k, v in block.items()}
    return {}


def extract(ccx_dir, out_file, s_over_h, band):
    """Write the continuum's exit-state band at its last output time."""
    info = json.load(open(os.path.join(ccx_dir, 'continuum_model.json')))
    dat = os.path.join(ccx_dir, 'continuum.dat')
    h, half, nx, ny = info['thickness'], info['half_length'], info['nx'], info['ny']
    dx, dz = 2 * half / nx, h / ny
    t, coord = read_coord(dat)
    peeq = read_peeq(dat, t)
    blocks = continuum_results.read_dat(dat)
    tb = min(blocks, key=lambda v: abs(v - t))
    if abs(tb - t) > 1e-9 * max(1.0, t) or 'U' not in blocks[tb]:
        fail('no displacements at the last time %g' % t)
    srows = continuum_results.strain_rows(info, blocks[tb])
    # the current mid-surface direction along the band (straight past the bead)
    elems = sorted({e for e, _ in coord})
    per = {}
    for (e, ip), xy in coord.items():
        per.setdefault(e, []).append((ip, xy))
    # each element's centre (the mean of its points)
    centre = {}
    for e in elems:
        pts = per[e]
        centre[e] = (sum(p[1][0] for p in pts) / len(pts), sum(p[1][1] for p in pts) / len(pts))
    data = {}    # (column of points, row of points) -> [reference x, reference z, peeq]
    for e in elems:
        pts = per[e]
        ei, ej = (e - 1) % nx, (e - 1) // nx
        cx, cy = centre[e]
        # the element's current axis: from the centre of its neighbour
        # before it in its layer to that of the one after it (the direction
        # of growing reference x; the points' own scatter gives no
        # direction in a square element, 4 per h along and 4 through)
        e0 = e - 1 if ei > 0 and (e - 1) in centre else e
        e1 = e + 1 if ei < nx - 1 and (e + 1) in centre else e
        tx, ty = centre[e1][0] - centre[e0][0], centre[e1][1] - centre[e0][1]
        norm = math.hypot(tx, ty)
        if not norm > 0.0:
            fail('element %d: no neighbour to give the sheet\'s direction' % e)
        tx, ty = tx / norm, ty / norm
        for ip, (x, y) in pts:
            a = (x - cx) * tx + (y - cy) * ty
            b = -(x - cx) * ty + (y - cy) * tx
            sa, sb = (1 if a > 0 else 0), (1 if b > 0 else 0)
            key = (2 * ei + sa, 2 * ej + sb)
            xr = -half + (ei + 0.5) * dx + (1 if sa else -1) * 0.5 * dx * GAUSS
            zr = -0.5 * h + (ej + 0.5) * dz + (1 if sb else -1) * 0.5 * dz * GAUSS
            if (e, ip) not in peeq:
                fail('no PEEQ for element %d point %d at time %g' % (e, ip, t))
            data.setdefault(key, [xr, zr, []])[2].append(peeq[(e, ip)])
    # each in-plane point twice (the expanded element's two layers): equal
    for key, (xr, zr, vals) in data.items():
        if len(vals) != 2 or abs(vals[0] - vals[1]) > 1e-6 * max(1.0, abs(vals[0])):
            fail('integration points not placed as expected at %s: %s' % (key, vals))
    cols = sorted({k[0] for k in data})
    nrow = 2 * ny
    lo, hi = (s_over_h - band) * h, (s_over_h + band) * h
    pull = info['pull_distance']
    with open(out_file, 'w') as f:
        f.write('# drawbead exit state: the CalculiX continuum (scripts/exit_state.py extract)\n')
        f.write('# deck %s: %s\n' % (info['deck'], info['title']))
        steps = ((', the pull in %d steps' % info['pull_steps']) if info.get('pull_steps')
                 else ', the pull a step of its own' if info.get('pull_step') else '')
        if info.get('resumed_after_step'):
            steps += ', resumed after step %d (scripts/ccx_resume.py)' % info['resumed_after_step']
        f.write('# mesh = %d x %d CPE8R (%d per h along, %d through the thickness), '
                'contact slope %g MPa/mm%s\n'
                % (nx, ny, info['per_h'], ny, info['contact_slope'], steps))
        f.write('# time = %.9g, delta/h = %.9g, station band: s/h %.6g .. %.6g\n'
                % (t, max(0.0, t - 1.0) * pull / h, s_over_h - band, s_over_h + band))
        f.write('# rows z/h (reference) = %s\n'
                % ' '.join('%.9f' % (data[(cols[0], r)][1] / h) for r in range(nrow)))
        f.write('# 1:s/h (reference x of a column of integration points) '
                '2..%d: equivalent plastic strain at each row z/h, bottom to top\n' % (nrow + 1))
        for c in cols:
            xr = data[(c, 0)][0]
            if not lo - dx <= xr <= hi + dx:
                continue
            f.write('eqps %.9f %s\n' % (xr / h, ' '.join('%.9e' % (sum(data[(c, r)][2]) / 2)
                                                          for r in range(nrow))))
        f.write('# 1:s/h (reference) 2:x/h (current) 3:ln(t/h) (thickness normal to the mid-surface)\n')
        for r in srows:
            if lo - dx <= r[0] * h <= hi + dx:
                f.write('thick %.9f %.9f %.9e\n' % (r[0], r[1], r[7]))


def read_continuum(path):
    """OUT_FILE of extract: (z rows, eqps columns [(s, [values])],
    thickness rows [(s, x, ln t/h)], header lines)."""
    zs, cols, thick, head = None, [], [], []
    try:
        with open(path) as f:
            for line in f:
                w = line.split()
                if line.startswith('# rows z/h'):
                    zs = [float(v) for v in line.split('=')[1].split()]
                if line.startswith('#'):
                    head.append(line.rstrip('\n'))
                elif w and w[0] == 'eqps':
                    cols.append((float(w[1]), [float(v) for v in w[2:]]))
                elif w and w[0] == 'thick':
                    thick.append((float(w[1]), float(w[2]), float(w[3])))
    except OSError as e:
        fail('cannot read %s: %s' % (path, e))
    if not zs or not cols or not thick:
        fail('%s: no rows, columns or thickness' % path)
    return zs, cols, thick, head


def interp(xs, ys, x):
    """Linear interpolation in increasing XS; None outside."""
    if x < xs[0] - 1e-12 or x > xs[-1] + 1e-12:
        return None
    for k in range(len(xs) - 1):
        if x <= xs[k + 1]:
            w = (x - xs[k]) / (xs[k + 1] - xs[k])
            return ys[k] + w * (ys[k + 1] - ys[k])
    return ys[-1]


def summary(label, run_dir, cont_file):
    """Print one line: thickness and eqps (faces, middle), program /
    continuum, at the program's station."""
    head, rows = read_exit_state(run_dir)
    zs, cols, thick, _ = read_continuum(cont_file)
    s = head['s']
    cs = [c[0] for c in cols]
    prof = [interp(cs, [c[1][r] for c in cols], s) for r in range(len(zs))]
    lt = interp([v[0] for v in thick], [v[2] for v in thick], s)
    if lt is None or None in prof:
        fail('the program\'s station s/h = %g lies outside the continuum\'s band' % s)
    n = len(zs)
    cont = [math.exp(lt), prof[0] + (prof[1] - prof[0]) * (-0.5 - zs[0]) / (zs[1] - zs[0]),
            0.5 * (prof[n // 2 - 1] + prof[n // 2]),
            prof[-1] + (prof[-1] - prof[-2]) * (0.5 - zs[-1]) / (zs[-1] - zs[-2])]
    pz = [r[0] for r in rows]
    prog = [head['thickness'], rows[0][3], interp(pz, [r[3] for r in rows], 0.0), rows[-1][3]]
    parts = ['%s %.4f / %.4f = %.3f' % (name, p, c, p / c) for name, p, c in
             zip(('thickness', 'eqps bottom', 'middle', 'top'), prog, cont)]
    print('%s (station s/h = %.2f, passed the whole bead: %s): %s (program / continuum)'
          % (label, s, head.get('passed', '?'), '; '.join(parts)))


def compare(run_dir, cont_file, check, tol_t, tol_e, tol_m):
    """Print the table; return the exit status."""
    head, rows = read_exit_state(run_dir)
    zs, cols, thick, chead = read_continuum(cont_file)
    s = head['s']
    cs = [c[0] for c in cols]
    prof = []
    for r in range(len(zs)):
        v = interp(cs, [c[1][r] for c in cols], s)
        if v is None:
            fail('the program\'s station s/h = %g lies outside the continuum\'s band %g .. %g'
                 % (s, cs[0], cs[-1]))
        prof.append(v)
    ts = [t[0] for t in thick]
    lt = interp(ts, [t[2] for t in thick], s)
    xc = interp(ts, [t[1] for t in thick], s)
    if lt is None:
        fail('the program\'s station s/h = %g lies outside the continuum\'s thickness rows' % s)
    # the continuum's faces: linear from the outer element's two rows; middle: mean of the two
    n = len(zs)
    bottom = prof[0] + (prof[1] - prof[0]) * (-0.5 - zs[0]) / (zs[1] - zs[0])
    top = prof[-1] + (prof[-1] - prof[-2]) * (0.5 - zs[-1]) / (zs[-1] - zs[-2])
    middle = 0.5 * (prof[n // 2 - 1] + prof[n // 2])
    pz = [r[0] for r in rows]
    pe = [r[3] for r in rows]
    p_at = [interp(pz, pe, z) for z in zs]
    bad = []

    def ratio(a, b):
        return a / b if b != 0 else float('nan')

    print('# the sheet leaving the bead, program against the continuum at the same material point')
    for line in chead[1:4]:
        print('#   continuum %s' % line[2:])
    print('# station: s/h = %.4f (reference), program x/h = %.3f (%.1fh past the exit of the last '
          'radius, x/h = %.3f), continuum x/h = %.3f; passed the whole bead: %s (started at '
          'x/h %.3f, first radius at %.3f)' % (s, head['x'], head['x'] - head['x_exit'],
                                              head['x_exit'], xc, head.get('passed', '?'), s,
                                              head.get('x_first', float('nan'))))
    print('%-34s %12s %12s %8s %8s' % ('quantity', 'program', 'continuum', 'ratio', 'target'))
    tc = math.exp(lt)
    rt = ratio(head['thickness'], tc)
    ok = abs(rt - 1) <= tol_t
    bad += [] if ok else ['thickness']
    print('%-34s %12.5f %12.5f %8.4f %8s' % ('thickness t/h', head['thickness'], tc, rt,
                                            ('%g%%' % (100 * tol_t)) + ('' if ok else ' !')))
    lp = math.log(head['thickness'])
    print('%-34s %12.5f %12.5f %8.4f' % ('thickness log strain ln(t/h)', lp, lt, ratio(lp, lt)))
    for label, pv, cv, tol in (('eqps, bottom face (z = -h/2)', pe[0], bottom, tol_e),
                               ('eqps, middle (z = 0)', interp(pz, pe, 0.0), middle, tol_m),
                               ('eqps, top face (z = +h/2)', pe[-1], top, tol_e)):
        rv = ratio(pv, cv)
        ok = abs(rv - 1) <= tol
        bad += [] if ok else [label]
        print('%-34s %12.5f %12.5f %8.4f %8s' % (label, pv, cv, rv,
                                                ('%g%%' % (100 * tol)) + ('' if ok else ' !')))
    print('# the profile at the continuum\'s rows of integration points (reference z/h)')
    for z, pv, cv in zip(zs, p_at, prof):
        print('%-34s %12.5f %12.5f %8.4f' % ('eqps at z/h = %+.4f' % z, pv, cv, ratio(pv, cv)))
    if bad:
        print('# outside the targets: %s' % ', '.join(bad))
    else:
        print('# within the targets')
    return 1 if (check and bad) else 0


def option(argv, name, default, kind=float):
    """Remove '--NAME VALUE' from ARGV and return VALUE (or DEFAULT)."""
    if name in argv:
        k = argv.index(name)
        if k + 1 >= len(argv):
            fail('%s needs a value' % name)
        try:
            v = kind(argv[k + 1])
        except ValueError:
            fail("%s needs a number, not '%s'" % (name, argv[k + 1]))
        del argv[k:k + 2]
        return v
    return default


def main(argv):
    """Command line: see the module header."""
    argv = list(argv)
    if not argv or argv[0] in ('-h', '--help'):
        print(__doc__)
        return 0 if argv else 2
    cmd, rest = argv[0], argv[1:]
    band = option(rest, '--band', 4.0)
    tol_t = option(rest, '--tol-thickness', 0.02)
    tol_e = option(rest, '--tol-eqps', 0.10)
    tol_m = option(rest, '--tol-middle', tol_e)
    check = '--check' in rest
    rest = [a for a in rest if a != '--check']
    try:
        if cmd == 'station' and len(rest) == 1:
            print('%.9g' % read_exit_state(rest[0])[0]['s'])
            return 0
        if cmd == 'patch-inp' and len(rest) == 3:
            patch_inp(rest[0], rest[1], float(rest[2]), band)
            return 0
        if cmd == 'extract' and len(rest) == 3:
            extract(rest[0], rest[1], float(rest[2]), band)
            return 0
        if cmd == 'summary' and len(rest) == 3:
            summary(rest[0], rest[1], rest[2])
            return 0
        if cmd == 'compare' and len(rest) == 2:
            return compare(rest[0], rest[1], check, tol_t, tol_e, tol_m)
    except (OSError, ValueError, KeyError) as e:
        fail(str(e))
    fail('usage: see exit_state.py --help')
    return 2


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
