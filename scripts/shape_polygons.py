#!/usr/bin/env python3
"""shape_polygons.py -- the sheet with its current thickness and the
physical tool surfaces as polygons, for scripts/plot_shape.gp.

Usage:
    scripts/shape_polygons.py [--print=WHAT] [--margin=M] [--keep=X] ...
                              [--pad=P] [--full] STRAIN.dat [TOOLS.dat]

    STRAIN.dat  a strain file of drawbead (strain_lock.dat, strain_pull.dat,
                ...): columns 2:3 the centreline x/h, y/h of each Gauss
                station, column 8 the thickness log strain of the
                mid-surface, column 9 the largest equivalent plastic strain
                through the thickness
    TOOLS.dat   optional: the tools file of the same state (tools_lock.dat
                or tools_pull.dat; block 0 the upper tool's centreline
                surface, block 1 the lower tool's)
    --print     what to write on standard output (default window):
        window   one line XMIN XMAX YMIN YMAX EPMAX: the window to draw
                 (x/h and y/h) and the largest equivalent plastic strain of
                 the sheet (0 if it stayed elastic)
        sheet    one quadrilateral per pair of neighbouring stations
                 (blocks separated by a blank line, each closed), columns
                 x/h, y/h and the mean equivalent plastic strain of the two
                 stations: plot with filledcurves closed fc palette z
        outline  the sheet's outline (upper face left to right, lower face
                 back), closed
        tools    (with TOOLS.dat) block 0 the upper tool, block 1 the lower
                 tool (separated by two blank lines), each its physical
                 surface (the centreline surface offset by h/2 away from
                 the sheet) closed far above or below the window: plot
                 with filledcurves closed
    --margin    the window is the bead (where a tool leaves its flat
                binder level) and M thicknesses on each side (default 3);
                without tools, the whole sheet and M on each side
    --keep      an abscissa x/h the window must hold (with 2h to spare),
                e.g. the tearing point; may be given several times
    --pad       the window's height is the sheet's, within the window, and
                P thicknesses above and below (default 1.5)
    --full      the window is the whole sheet and M on each side

gnuplot reads the output through a pipe ('< python3 ...'), so that no
temporary file is left behind.

All lengths are in units of the initial thickness h: the current thickness
of a station is exp(column 8), laid off by half each side of the
centreline along its normal (the normal from the neighbouring stations).

Exit status: 0 on success; 1 when a file cannot be read or holds too few
rows; 2 on a usage error.
"""

import bisect
import math
import sys

# the binder level is where a tool is flat; a tool point further than this
# from it (in h) belongs to the bead
FLAT_TOL = 1e-6
# the sampling of the eroded tool surfaces, in h
STEP = 0.01
# a far-away ordinate closing the tool polygons (gnuplot clips them)
FAR = 1.0e3


def die(message, status):
    """Print MESSAGE on standard error and exit with STATUS."""
    print("shape_polygons.py: " + message, file=sys.stderr)
    sys.exit(status)


def read_blocks(path, ncol):
    """The rows of PATH (the first NCOL numbers of each line that is not a
    '#' comment), split into blocks at blank lines: a list of lists."""
    blocks = [[]]
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("#"):
                    continue
                fields = line.split()
                if not fields:
                    if blocks[-1]:
                        blocks.append([])
                    continue
                if len(fields) < ncol:
                    die(f"'{path}': a row with fewer than {ncol} columns", 1)
                try:
                    blocks[-1].append([float(v) for v in fields[:ncol]])
                except ValueError:
                    die(f"'{path}': not a number in '{line.strip()}'", 1)
    except OSError as e:
        die(f"cannot read '{path}': {e.strerror}", 1)
    return [b for b in blocks if b]


def normals(xs, ys):
    """The unit left normals (-t_y, t_x) of the polyline (XS, YS), the
    tangent t from the neighbouring points (one-sided at the ends)."""
    n = len(xs)
    out = []
    for i in range(n):
        a = max(i - 1, 0)
        b = min(i + 1, n - 1)
        tx = xs[b] - xs[a]
        ty = ys[b] - ys[a]
        norm = math.hypot(tx, ty)
        if norm == 0.0:
            # coincident neighbours: keep the previous normal
            out.append(out[-1] if out else (0.0, 1.0))
        else:
            out.append((-ty / norm, tx / norm))
    return out


def mitre(xs, ys, dist):
    """The polyline (XS, YS) offset by DIST along its left normal: each
    vertex where the offset lines of its two segments meet (a mitre, so
    that a sharp corner stays sharp), along the segment's normal at the
    ends."""
    seg = []
    for i in range(len(xs) - 1):
        tx = xs[i + 1] - xs[i]
        ty = ys[i + 1] - ys[i]
        norm = math.hypot(tx, ty)
        if norm > 0.0:
            seg.append((i, -ty / norm, tx / norm))
    if not seg:
        return list(xs), list(ys)
    # the normal of the segment before and after each vertex
    before = [None] * len(xs)
    after = [None] * len(xs)
    for i, nx, ny in seg:
        after[i] = (nx, ny)
        before[i + 1] = (nx, ny)
    for i in range(1, len(xs)):
        if before[i] is None:
            before[i] = before[i - 1]
    for i in range(len(xs) - 2, -1, -1):
        if after[i] is None:
            after[i] = after[i + 1]
    ox = []
    oy = []
    for i, (x, y) in enumerate(zip(xs, ys)):
        n1 = before[i] or after[i]
        n2 = after[i] or before[i]
        cos = n1[0] * n2[0] + n1[1] * n2[1]
        # a mitre longer than twice the offset (a turn past 120 degrees)
        # is cut back to that length
        scale = dist / max(1.0 + cos, 0.5)
        ox.append(x + scale * (n1[0] + n2[0]))
        oy.append(y + scale * (n1[1] + n2[1]))
    return ox, oy


def erode(xs, ys, dist, side):
    """The physical surface under (SIDE = -1) or over (SIDE = +1) the
    centreline surface (XS, YS), a function of x (XS not decreasing): the
    boundary of the tool eroded by a disc of radius DIST, sampled every
    STEP. Exact where the offset of mitre() is not: at sharp corners and
    steps sampled by a single steep segment."""
    pts = []
    for i in range(len(xs) - 1):
        length = math.hypot(xs[i + 1] - xs[i], ys[i + 1] - ys[i])
        k = max(1, math.ceil(length / STEP))
        for j in range(k):
            t = j / k
            pts.append((xs[i] + t * (xs[i + 1] - xs[i]), ys[i] + t * (ys[i + 1] - ys[i])))
    pts.append((xs[-1], ys[-1]))
    px = [p[0] for p in pts]
    n = max(2, math.ceil((xs[-1] - xs[0]) / STEP) + 1)
    ox = []
    oy = []
    for g in range(n):
        x = xs[0] + (xs[-1] - xs[0]) * g / (n - 1)
        best = None
        for j in range(bisect.bisect_left(px, x - dist), bisect.bisect_right(px, x + dist)):
            dx = pts[j][0] - x
            y = pts[j][1] + side * math.sqrt(max(dist * dist - dx * dx, 0.0))
            if best is None or side * (y - best) > 0.0:
                best = y
        ox.append(x)
        oy.append(best)
    return ox, oy


def write_polygon(f, xs, ys, extra=None):
    """Write the closed polygon (XS, YS) as one block of F, with EXTRA as a
    third column on every row if given."""
    tail = "" if extra is None else f" {extra:.6e}"
    for x, y in zip(xs + xs[:1], ys + ys[:1]):
        f.write(f"{x:.6e} {y:.6e}{tail}\n")
    f.write("\n")


def bead_span(block):
    """The x extent of the points of a tool BLOCK away from its binder
    level (the height at both ends), or None if it is flat."""
    level = block[0][1]
    xs = [p[0] for p in block if abs(p[1] - level) > FLAT_TOL]
    return (min(xs), max(xs)) if xs else None


def sheet_faces(rows):
    """The upper and lower faces of the sheet, lists of (x, y), from the
    strain file's ROWS: the current thickness exp(column 8) laid off by
    half each side of the centreline along its normal."""
    xs = [r[1] for r in rows]
    ys = [r[2] for r in rows]
    half = [0.5 * math.exp(r[7]) for r in rows]
    ns = normals(xs, ys)
    top = [(x + t * nx, y + t * ny) for x, y, t, (nx, ny) in zip(xs, ys, half, ns)]
    bot = [(x - t * nx, y - t * ny) for x, y, t, (nx, ny) in zip(xs, ys, half, ns)]
    return top, bot


def write_tools(f, blocks):
    """Write the physical surfaces of the tool BLOCKS (upper, lower) on F
    as closed polygons."""
    for k, (block, side) in enumerate(zip(blocks, (1.0, -1.0))):
        tx = [p[0] for p in block]
        ty = [p[1] for p in block]
        # the upper tool lies above the sheet: its surface is the
        # centreline surface moved up (left normal, x increasing)
        if tx[-1] < tx[0]:
            tx.reverse()
            ty.reverse()
        if all(b >= a for a, b in zip(tx, tx[1:])):
            px, py = erode(tx, ty, 0.5, side)
        else:
            # a tool that is no function of x (an overhang)
            px, py = mitre(tx, ty, 0.5 * side)
        px += [px[-1], px[0]]
        py += [side * FAR, side * FAR]
        write_polygon(f, px, py)
        if k == 0:
            f.write("\n")


def window(top, bot, blocks, margin, pad, keep, full):
    """The window (XMIN, XMAX, YMIN, YMAX) around the sheet's faces TOP and
    BOT: the bead of the tool BLOCKS (None: no tools) or, if FULL or
    without tools, the sheet, MARGIN on each side, widened to hold each x
    of KEEP with 2 to spare; the sheet's height in it and PAD."""
    span = None
    for block in blocks or []:
        s = bead_span(block)
        if s is not None:
            span = s if span is None else (min(span[0], s[0]), max(span[1], s[1]))
    sheet_x = [p[0] for p in top + bot]
    if span is None or full:
        span = (min(sheet_x), max(sheet_x))
    xmin = span[0] - margin
    xmax = span[1] + margin
    for k in keep:
        xmin = min(xmin, k - 2.0)
        xmax = max(xmax, k + 2.0)
    # never wider than the sheet and its margin
    xmin = max(xmin, min(sheet_x) - margin)
    xmax = min(xmax, max(sheet_x) + margin)
    inside = [p[1] for p in top + bot if xmin <= p[0] <= xmax]
    if not inside:
        inside = [p[1] for p in top + bot]
    return xmin, xmax, min(inside) - pad, max(inside) + pad


def main(argv):
    """Parse ARGV and print what --print asks for."""
    what = "window"
    margin = 3.0
    pad = 1.5
    keep = []
    full = False
    files = []
    for a in argv:
        try:
            if a.startswith("--print="):
                what = a[8:]
            elif a.startswith("--margin="):
                margin = float(a[9:])
            elif a.startswith("--pad="):
                pad = float(a[6:])
            elif a == "--full":
                full = True
            elif a.startswith("--keep="):
                keep.append(float(a[7:]))
            elif a.startswith("-"):
                die(f"unknown option '{a}'", 2)
            else:
                files.append(a)
        except ValueError:
            die(f"not a number in '{a}'", 2)
    if len(files) not in (1, 2):
        die("usage: shape_polygons.py [--print=window|sheet|outline|tools] "
            "[--margin=M] [--keep=X] ... [--pad=P] [--full] STRAIN.dat [TOOLS.dat]", 2)
    if what not in ("window", "sheet", "outline", "tools"):
        die(f"--print: not window, sheet, outline or tools: '{what}'", 2)
    if not (math.isfinite(margin) and math.isfinite(pad)) or \
            not all(math.isfinite(k) for k in keep):
        die("--margin, --pad and --keep must be finite numbers", 2)
    if what == "tools" and len(files) == 1:
        die("--print=tools needs TOOLS.dat", 2)

    rows = [r for b in read_blocks(files[0], 9) for r in b]
    if len(rows) < 2:
        die(f"'{files[0]}': fewer than two stations", 1)
    top, bot = sheet_faces(rows)
    blocks = None
    if len(files) == 2:
        blocks = read_blocks(files[1], 2)
        if len(blocks) != 2 or min(len(b) for b in blocks) < 2:
            die(f"'{files[1]}': not two tool blocks", 1)

    out = sys.stdout
    if what == "window":
        w = window(top, bot, blocks, margin, pad, keep, full)
        epmax = max(max(r[8] for r in rows), 0.0)
        out.write(" ".join(f"{v:.6g}" for v in w) + f" {epmax:.6g}\n")
    elif what == "sheet":
        eps = [r[8] for r in rows]
        for i in range(len(rows) - 1):
            quad = [top[i], top[i + 1], bot[i + 1], bot[i]]
            write_polygon(out, [p[0] for p in quad], [p[1] for p in quad],
                          0.5 * (eps[i] + eps[i + 1]))
    elif what == "outline":
        ring = top + bot[::-1]
        write_polygon(out, [p[0] for p in ring], [p[1] for p in ring])
    else:
        write_tools(out, blocks)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
