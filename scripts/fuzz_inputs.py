#!/usr/bin/env python3
"""fuzz_inputs.py -- mutated input files for tests/fuzz.sh.

Usage:
  fuzz_inputs.py generate --out DIR [--seed N] [--cases N] [--first K] [--root DIR]

generate: writes DIR/case_KKKKK/ for K = first .. first+cases-1, each a
self-contained case: deck.nml, the profile or curve files it names (copied
next to it and named without a directory), and what.txt (the base files and
the mutations applied).  A case is run from its own directory as
    drawbead -o out deck.nml
Case K depends only on (seed, K): `--first 1234 --cases 1` regenerates case
1234 of a longer run exactly.

The bases are the shipped decks (input/*.nml), the regression decks
(tests/regression/decks/*.nml) and the good decks of tests/decks; the
profiles (input/profiles/*.prof) are mutated through the profile decks that
name them, the curve file (tests/regression/decks/table_curve.txt and
variants of it written in the other accepted layouts) through a deck with
hardening = 'table'.  Each base deck is first made cheap (at most 24
elements, 5 stations through the thickness, a pull of at most 1 h, a lock
of at most 1.5 mm when no profile is involved), then 1 to 3 mutations are
applied to the deck or to one of its files: truncation, byte flips, a line
deleted, duplicated, swapped or inserted, two values swapped (and so their
types), a number replaced by an extreme (0, -1, 1e300, nan, huge integers,
...) or scaled (by 10, 0.1, -1, ...), a deck variable set to such a value
(set in the deck or not), text in a numeric field, a number in a text
field, a name replaced by another, namelist oddities (repeat counts, array
indices).

Standard library only.
"""

import argparse
import math
import random
import re
import sys
from pathlib import Path

EXTREMES = ['0', '-1', '0.0', '-0.0', '1e300', '-1e300', '1e-300', '4.9e-324',
            '1e309', '1d300', 'nan', 'NaN', 'inf', '-Infinity', '2147483647',
            '2147483648', '-2147483649', '99999999999999999999', '1.0e-30',
            '3', '1e6']

TEXTS = ["'abc'", 'abc', '.true.', '.false.', "''", '1.0.0', '1e', '+', '*',
         '-', "'1.0'", '"', "'", '1,2', '2*1.0', '&', '/', '!', '1 2',
         "'" + 'x' * 600 + "'"]

JUNK_LINES = ['&sheet', '/', '&end', '$end', 'garbage', 'n_elements = 5 6',
              '&loading pull_distance = 0.1 /', 'x = 1', '= 1', '&',
              'side upper', 'line 0 0 1 1', 'arc 0 0 1 1 0 0 cw',
              '0.5 300.0', '# comment', '! comment', '\t', '\x00\x01\x02',
              'thickness(2) = 1.0', 'thickness%x = 1.0', 'n_elements = 3*4',
              "bead = 'profile'", "hardening = 'table'", "left_edge = 'free'"]

NUMBER_RE = re.compile(rb'[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?')
ASSIGN_RE = re.compile(rb'([A-Za-z_][A-Za-z0-9_]*)\s*=\s*([^,\n/]*)')
QUOTED_RE = re.compile(rb"'[^'\n]*'")
NAME_RE = re.compile(rb'[A-Za-z_][A-Za-z0-9_]*')
FILE_VARS = (b'curve_file', b'upper_profile', b'lower_profile')

# the deck variables (bin/drawbead --list-variables) and their groups
GROUP_OF = {}
for _group, _names in ((b'control', b'title output_dir stop_at_localization tearing_length '
                        b'fold_curvature log_residuals predictor snapshot_every'),
                       (b'sheet', b'thickness length n_elements mesh_beta left_edge back_tension'),
                       (b'material', b'model umat_props youngs_modulus poissons_ratio r_value hardening swift_k '
                        b'swift_eps0 swift_n voce_sigma0 voce_q voce_b curve_file thickness_points'),
                       (b'tools', b'bead r1 r2 b1 b2 h1 h2 upper_profile lower_profile penalty '
                        b'friction friction_eps contact_smoothing'),
                       (b'loading', b'lock_depth pull_distance initial_increment min_increment '
                        b'max_increment max_iterations tolerance squeeze_force_change '
                        b'max_force_change branch_increment')):
    for _name in _names.split():
        GROUP_OF[_name] = _group
# names a rename may put in place of another: the variables, the groups,
# the keywords of a profile file, and one the program does not know
VARIABLES = sorted(GROUP_OF) + [b'control', b'sheet', b'material', b'tools', b'loading',
                                b'side', b'line', b'arc', b'cw', b'ccw', b'upper',
                                b'lower', b'nosuch']


# ---------------------------------------------------------------------------
# Decks as bytes: find, set and insert `name = value`
# ---------------------------------------------------------------------------
def find_value(deck, name):
    """The value text of the first `name = value` of deck, or None."""
    m = _assignment(name).search(deck)
    return m.group(2).strip() if m else None


def _assignment(name):
    """`name = value` on a line, outside a comment: groups (head, value)."""
    return re.compile(rb'(?im)^([^!\n]*?\b' + name + rb'\s*=\s*)(\'[^\'\n]*\'|"[^"\n]*"|[^,\n/!]*)')


def set_value(deck, group, name, value):
    """deck with `name = value`: replaced where set, else added to &group
    (the group is appended when the deck has none)."""
    pat = _assignment(name)
    if pat.search(deck):
        return pat.sub(lambda m: m.group(1) + value, deck, count=1)
    line = b'   ' + name + b' = ' + value + b'\n'
    g = re.search(rb'(?im)^\s*&' + group + rb'\b[^\n]*\n', deck)
    if g:
        return deck[:g.end()] + line + deck[g.end():]
    return deck + b'&' + group + b'\n' + line + b'/\n'


def as_float(text, default):
    try:
        return float(text.replace(b'd', b'e').replace(b'D', b'e'))
    except (AttributeError, ValueError):
        return default


def unquote(text):
    return text.strip().strip(b"'\"")


def make_cheap(deck, has_profile):
    """deck with a small mesh, few stations and a short pull (and lock)."""
    h = as_float(find_value(deck, b'thickness'), 0.762)
    n = int(as_float(find_value(deck, b'n_elements'), 80))
    deck = set_value(deck, b'sheet', b'n_elements', str(min(n, 24)).encode())
    deck = set_value(deck, b'material', b'thickness_points', b'5')
    pull = as_float(find_value(deck, b'pull_distance'), 10 * h)
    deck = set_value(deck, b'loading', b'pull_distance', repr(min(pull, h)).encode())
    if not has_profile:
        bead = find_value(deck, b'bead')
        if bead is not None and b'rectangular' in bead:
            lock = as_float(find_value(deck, b'lock_depth'), 4.7)
            deck = set_value(deck, b'loading', b'lock_depth', repr(min(lock, 1.5)).encode())
    return deck


def curve_variants(curve):
    """The curve file as shipped and in the other layouts the reader takes."""
    rows = [ln.split() for ln in curve.splitlines()
            if ln.strip() and not ln.lstrip().startswith(b'#')]
    commas = b'# ep, sigma\n' + b''.join(b', '.join(r) + b'\n' for r in rows)
    tabs = b''.join(b'\t'.join(r) + b'   ! a comment\n' for r in rows)
    dense = b'# many points\n' + b''.join(
        f'{e:.4f} {183.0 + 300.0 * (1.0 - math.exp(-8.0 * e)):.3f}\n'.encode()
        for e in (0.01 * k for k in range(60)))
    return [curve, commas, tabs, dense]


# ---------------------------------------------------------------------------
# Mutations: each takes (rng, data) and returns (data, description)
# ---------------------------------------------------------------------------
def _lines(data):
    return data.split(b'\n')


def m_truncate(rng, data):
    k = rng.randrange(len(data) + 1)
    return data[:k], f'truncate at byte {k}'


def m_byte_flip(rng, data):
    if not data:
        return data, 'byte flip (empty)'
    b = bytearray(data)
    spots = []
    for _ in range(rng.randint(1, 4)):
        k = rng.randrange(len(b))
        if rng.random() < 0.5:
            b[k] ^= 1 << rng.randrange(8)
        else:
            b[k] = rng.randrange(256)
        spots.append(k)
    return bytes(b), f'byte flips at {spots}'


def m_delete_line(rng, data):
    ls = _lines(data)
    k = rng.randrange(len(ls))
    del ls[k]
    return b'\n'.join(ls), f'delete line {k + 1}'


def m_duplicate_line(rng, data):
    ls = _lines(data)
    k = rng.randrange(len(ls))
    ls.insert(rng.randrange(len(ls) + 1), ls[k])
    return b'\n'.join(ls), f'duplicate line {k + 1}'


def m_swap_lines(rng, data):
    ls = _lines(data)
    i, j = rng.randrange(len(ls)), rng.randrange(len(ls))
    ls[i], ls[j] = ls[j], ls[i]
    return b'\n'.join(ls), f'swap lines {i + 1} and {j + 1}'


def m_insert_line(rng, data):
    ls = _lines(data)
    k = rng.randrange(len(ls) + 1)
    junk = rng.choice(JUNK_LINES).encode('latin-1')
    ls.insert(k, junk)
    return b'\n'.join(ls), f'insert line {k + 1}: {junk!r}'


def _replace_span(data, span, new):
    return data[:span[0]] + new + data[span[1]:]


def m_swap_values(rng, data):
    spans = [m.span(2) for m in ASSIGN_RE.finditer(data) if m.group(2).strip()]
    if len(spans) < 2:
        # profiles and curves: swap two fields of the data lines
        spans = [m.span() for m in re.finditer(rb'\S+', data)]
    if len(spans) < 2:
        return data, 'swap values (too few)'
    a, b = sorted(rng.sample(spans, 2))
    va, vb = data[a[0]:a[1]], data[b[0]:b[1]]
    data = data[:a[0]] + vb + data[a[1]:b[0]] + va + data[b[1]:]
    return data, f'swap values {va[:40]!r} and {vb[:40]!r}'


def m_extreme_number(rng, data):
    spans = [m.span() for m in NUMBER_RE.finditer(data)]
    if not spans:
        return data, 'extreme number (none)'
    span = rng.choice(spans)
    new = rng.choice(EXTREMES).encode()
    return _replace_span(data, span, new), f'number {data[span[0]:span[1]]!r} -> {new!r}'


def m_text_in_number(rng, data):
    spans = [m.span() for m in NUMBER_RE.finditer(data)]
    if not spans:
        return data, 'text in number (none)'
    span = rng.choice(spans)
    new = rng.choice(TEXTS).encode()
    return _replace_span(data, span, new), f'number {data[span[0]:span[1]]!r} -> {new[:40]!r}'


def m_number_in_text(rng, data):
    spans = [m.span() for m in QUOTED_RE.finditer(data)]
    if not spans:
        spans = [m.span() for m in re.finditer(rb'(?m)^\s*(side|line|arc)\b', data)]
    if not spans:
        return data, 'number in text (none)'
    span = rng.choice(spans)
    new = rng.choice(EXTREMES + TEXTS).encode()
    return _replace_span(data, span, new), f'text {data[span[0]:span[1]][:40]!r} -> {new[:40]!r}'


def m_rename(rng, data):
    spans = [m.span() for m in NAME_RE.finditer(data)]
    if not spans:
        return data, 'rename (none)'
    span = rng.choice(spans)
    new = rng.choice(VARIABLES)
    return _replace_span(data, span, new), f'name {data[span[0]:span[1]]!r} -> {new!r}'


def m_namelist_oddity(rng, data):
    spans = [m for m in ASSIGN_RE.finditer(data)]
    if not spans:
        return m_insert_line(rng, data)
    m = rng.choice(spans)
    name, value = m.group(1), m.group(2).strip()
    forms = [name + b'(2) = ' + value, name + b'(0) = ' + value,
             name + b' = 2*' + value, name + b' = ' + value + b', ' + value,
             name + b' = ' + value + b' ' + value, name + b'%x = ' + value,
             name + b' = ', name + b' ' + value, name.upper() + b' = ' + value,
             name + b'=' + value + b'/', name + b' = ,']
    new = rng.choice(forms)
    return _replace_span(data, m.span(), new), f'{m.group(0)[:40]!r} -> {new[:40]!r}'


ODD_VALUES = ['1e-6', '1e-3', '0.5', '2', '10', '100', '1e4', '-0.5', '-1e-6']


def m_set_variable(rng, data):
    """A deck variable, set or not in the deck, given an extreme or odd value
    in its group (the deck's setting replaced)."""
    name = rng.choice(sorted(GROUP_OF))
    new = rng.choice(EXTREMES + ODD_VALUES + TEXTS[:6]).encode()
    return set_value(data, GROUP_OF[name], name, new), f'set {name.decode()} = {new[:40]!r}'


def m_scale_number(rng, data):
    """A number of the file multiplied by a factor (10, 0.1, -1, ...)."""
    spans = [m.span() for m in NUMBER_RE.finditer(data)]
    if not spans:
        return data, 'scale number (none)'
    span = rng.choice(spans)
    x = as_float(data[span[0]:span[1]], 1.0)
    factor = rng.choice([10.0, 0.1, -1.0, 2.0, 0.5, 1000.0, 1e-3, 1.0 + 1e-9])
    new = repr(x * factor).encode()
    return _replace_span(data, span, new), f'number {data[span[0]:span[1]]!r} -> {new!r}'


DECK_MUTATIONS = [m_truncate, m_byte_flip, m_delete_line, m_duplicate_line,
                  m_swap_lines, m_insert_line, m_swap_values, m_extreme_number,
                  m_extreme_number, m_extreme_number, m_text_in_number,
                  m_number_in_text, m_rename, m_namelist_oddity, m_scale_number,
                  m_scale_number, m_set_variable, m_set_variable, m_set_variable,
                  m_set_variable]
FILE_MUTATIONS = [m_truncate, m_byte_flip, m_delete_line, m_duplicate_line,
                  m_swap_lines, m_insert_line, m_swap_values, m_extreme_number,
                  m_extreme_number, m_extreme_number, m_text_in_number,
                  m_number_in_text, m_rename, m_scale_number, m_scale_number]


# ---------------------------------------------------------------------------
# Cases
# ---------------------------------------------------------------------------
class Bases:
    """The files the cases start from (read once)."""

    def __init__(self, root):
        self.root = root
        decks = sorted(root.glob('input/*.nml')) + sorted(root.glob('tests/regression/decks/*.nml'))
        decks += [p for p in sorted(root.glob('tests/decks/*.nml'))
                  if not p.name.startswith(('bad_', 'fuzz_'))]
        if not decks:
            raise SystemExit(f'fuzz_inputs: no decks under {root}')
        self.decks = [(p.relative_to(root).as_posix(), p.read_bytes()) for p in decks]
        self.profile_decks = [d for d in self.decks if b'upper_profile' in d[1]]
        curve = root / 'tests/regression/decks/table_curve.txt'
        self.curves = curve_variants(curve.read_bytes()) if curve.is_file() else []
        self.table_decks = [d for d in self.decks if b'curve_file' in d[1]]

    def read(self, path):
        p = self.root / path
        return p.read_bytes() if p.is_file() else None


def make_case(bases, seed, k):
    """Case k: (deck bytes, {file name: bytes}, description lines)."""
    rng = random.Random(f'{seed}:{k}')
    target = rng.random()
    if target < 0.2 and bases.profile_decks:
        name, deck = rng.choice(bases.profile_decks)
        kind = 'profile'
    elif target < 0.35 and bases.curves:
        name, deck = rng.choice(bases.table_decks or bases.decks)
        kind = 'curve'
    else:
        name, deck = rng.choice(bases.decks)
        kind = 'deck'
    what = [f'seed {seed} case {k}', f'base deck {name}']

    # the deck's files, copied beside it under their base names
    files = {}
    for var in FILE_VARS:
        value = find_value(deck, var)
        if not value:
            continue
        path = unquote(value).decode('latin-1')
        local = Path(path).name
        data = bases.read(path)
        if data is None:
            continue
        files[local] = data
        deck = set_value(deck, GROUP_OF[var], var, b"'" + local.encode('latin-1') + b"'")
        what.append(f'{var.decode()} = {path} (copied as {local})')
    if kind == 'curve':
        curve = rng.choice(bases.curves)
        files = {k2: v for k2, v in files.items() if not k2.endswith('.txt')}
        files['curve.txt'] = curve
        deck = set_value(deck, b'material', b'hardening', b"'table'")
        deck = set_value(deck, b'material', b'curve_file', b"'curve.txt'")
        what.append(f'curve.txt: variant {bases.curves.index(curve)} of table_curve.txt')

    deck = make_cheap(deck, bool(files) and kind != 'curve')

    # mutate the deck, or one of its files
    if kind != 'deck' and files:
        targets = sorted(files)
        if kind == 'curve':
            targets = ['curve.txt']
        victim = rng.choice(targets)
        data = files[victim]
        for _ in range(rng.choice((1, 1, 1, 2, 2, 3))):
            data, desc = rng.choice(FILE_MUTATIONS)(rng, data)
            what.append(f'{victim}: {desc}')
        files[victim] = data
    else:
        for _ in range(rng.choice((1, 1, 1, 2, 2, 3))):
            deck, desc = rng.choice(DECK_MUTATIONS)(rng, deck)
            what.append(f'deck.nml: {desc}')
    return deck, files, what


def generate(args):
    root = Path(args.root).resolve()
    out = Path(args.out)
    bases = Bases(root)
    for k in range(args.first, args.first + args.cases):
        deck, files, what = make_case(bases, args.seed, k)
        d = out / f'case_{k:05d}'
        d.mkdir(parents=True, exist_ok=True)
        (d / 'deck.nml').write_bytes(deck)
        for name, data in files.items():
            (d / name).write_bytes(data)
        (d / 'what.txt').write_text('\n'.join(what) + '\n', encoding='utf-8',
                                    errors='backslashreplace')
    return 0


def main(argv):
    p = argparse.ArgumentParser(description='mutated inputs for tests/fuzz.sh')
    sub = p.add_subparsers(dest='command', required=True)
    g = sub.add_parser('generate', help='write the cases')
    g.add_argument('--out', required=True, help='directory of the cases')
    g.add_argument('--seed', type=int, default=1)
    g.add_argument('--cases', type=int, default=300)
    g.add_argument('--first', type=int, default=0, help='number of the first case')
    g.add_argument('--root', default=str(Path(__file__).resolve().parent.parent),
                   help='repository top (default: the parent of scripts/)')
    args = p.parse_args(argv)
    return generate(args)


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
