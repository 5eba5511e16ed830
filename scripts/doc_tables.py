#!/usr/bin/env python3
"""doc_tables.py -- the numbers of the documents, produced by the program.

Usage:
  scripts/doc_tables.py [--bin PATH] [-j N] NAME...     regenerate blocks in place
  scripts/doc_tables.py [--bin PATH] [-j N] --check NAME...
  scripts/doc_tables.py --check-links
  scripts/doc_tables.py --list

Every table of results in README.md and docs/*.md sits between the lines
  <!-- BEGIN scripts/doc_tables.py NAME -->
  <!-- END scripts/doc_tables.py NAME -->
and is written by this script (NAME `all`: every block).  A block is
produced by running bin/drawbead (or --bin PATH; $DRAWBEAD if set) on the
decks of input/, or by running one of the study scripts (convergence.sh,
bench.sh) and copying its output verbatim.  Run it from anywhere: paths
are those of the repository holding this script.

--check NAME...  regenerates the blocks without writing them and compares
    them with the documents: text must be the same, and every number must
    equal the program's value to the digits the document shows (so the
    round-off of another compiler or of the checked build passes).  Exit 1
    on a difference, listing it.  `bench` (timings) cannot be checked and
    is skipped with a note.
--check-links  checks that every relative link and image of README.md and
    docs/*.md points at an existing file (and a `#anchor` into a markdown
    file at one of its headings), that every block marker names a known
    block and is closed, and that README.md is at most 10 KB.
--list  prints the blocks, the files that hold them and what they run.

Exit status: 0 success, 1 a check failed or a run failed, 2 usage error.
"""

import concurrent.futures
import math
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

import continuum_results

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = ["README.md"] + sorted(
    os.path.join("docs", f) for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md"))
MARK = "scripts/doc_tables.py"
README_LIMIT = 10240

PAPER_DECKS = [
    "fig5a_beadA_steel", "fig5b_beadA_brass", "fig6_beadB_steel",
    "fig7a_beadA_brass_mu0", "fig7b_beadA_steel_mu0", "fig7c_beadB_steel_mu0",
    "fig7d_beadA_steel_mu01", "fig9a_beadA_brass_free", "fig9b_beadA_steel_free_mu02",
    "fig9c_beadA_steel_free", "fig9d_beadB_steel_free", "strip_tension",
]

class Num:
    """A number of a table: its value and the format it is shown with."""

    def __init__(self, value, fmt):
        self.value = value
        self.fmt = fmt

    def text(self, raw):
        if self.value is None:
            return "none"
        return repr(self.value) if raw else format(self.value, self.fmt)


def cell(x, raw):
    return x.text(raw) if isinstance(x, Num) else str(x)


def markdown_table(header, align, rows, raw):
    """A markdown table; header and align are lists of str, rows of cells."""
    lines = ["| " + " | ".join(header) + " |", "| " + " | ".join(align) + " |"]
    for row in rows:
        lines.append("| " + " | ".join(cell(x, raw) for x in row) + " |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# Running the program
# ---------------------------------------------------------------------------

def read_summary(path):
    """summary.txt as a dict of strings."""
    values = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#") or " = " not in line:
                continue
            key, value = line.rstrip("\n").split(" = ", 1)
            values[key.strip()] = value.strip()
    return values


def real(summary, key):
    value = summary.get(key, "none")
    return None if value == "none" else float(value)


def quotient(a, b):
    """a / b, or None when either is None (a value a run did not reach)."""
    return None if a is None or b is None else a / b


def run_deck(program, deck_text_or_path, outdir, name, one_thread=False):
    """Run one deck (a path, or the text of a deck) into outdir/name;
    return its summary and the exit status.  one_thread: with
    OMP_NUM_THREADS=1 (runs that share the machine)."""
    run_dir = os.path.join(outdir, name)
    if "\n" in deck_text_or_path:
        deck = os.path.join(outdir, name + ".nml")
        with open(deck, "w", encoding="utf-8") as f:
            f.write(deck_text_or_path)
    else:
        deck = deck_text_or_path
    with open(os.path.join(outdir, name + ".log"), "w", encoding="utf-8") as log:
        env = dict(os.environ, OMP_NUM_THREADS="1") if one_thread else None
        status = subprocess.call([program, deck, "--output", run_dir], cwd=ROOT, env=env,
                                 stdout=log, stderr=subprocess.STDOUT)
    summary_path = os.path.join(run_dir, "summary.txt")
    summary = read_summary(summary_path) if os.path.exists(summary_path) else {}
    return summary, status


def run_many(program, jobs, outdir, workers):
    """jobs: list of (name, deck path or text); returns {name: summary}."""
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(run_deck, program, deck, outdir, name, workers > 1): name
                   for name, deck in jobs}
        for fut in concurrent.futures.as_completed(futures):
            name = futures[fut]
            summary, status = fut.result()
            if status != 0 or not summary:
                raise RuntimeError(f"run {name} exited with status {status} "
                                   f"(log: {os.path.join(outdir, name + '.log')})")
            results[name] = summary
    return results


def gen_readme_example(ctx):
    """README.md: the first example, fig5a, a few lines of its summary.txt."""
    s = run_many(ctx.program, [("fig5a", "input/fig5a_beadA_steel.nml")], ctx.tmp, 1)["fig5a"]
    shown = [("status", None), ("localization_phase", None),
             ("delta_cr_over_h", ".4g"), ("s_star_over_h", ".4g"),
             ("lock_force_over_Eh", ".4e"), ("peak_force_over_Eh", ".4e"),
             ("max_thinning", ".3f"), ("energy_balance_error", ".1e")]

    def text(raw):
        lines = ["```", "$ cat out/fig5a_beadA_steel/summary.txt     # (an excerpt)",
                 "# drawbead summary: Fig. 5a: bead A, mild steel (DQSK), clamped, mu = 0.1"]
        for key, fmt in shown:
            value = s[key] if fmt is None else Num(real(s, key), fmt).text(raw)
            lines.append(f"{key} = {value}")
        lines.append("```")
        return "\n".join(lines)
    return text


# decks whose place of localization round-off picks: the uniform strip, where
# every element reaches the maximum load together (the -O0 and the -O2
# builds put it 29h apart; tests/regression/decks.txt skips it too)
PLACE_BY_ROUND_OFF = {"strip_tension"}


def gen_paper_table(ctx):
    """docs/validation.md: every deck of the paper (and the strip), as shipped."""
    jobs = [(d, f"input/{d}.nml") for d in PAPER_DECKS]
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for d in PAPER_DECKS:
        s = res[d]
        place = ("any (round-off)" if d in PLACE_BY_ROUND_OFF
                 else Num(real(s, "s_star_over_h"), ".2f"))
        rows.append([d, s["status"], Num(real(s, "delta_cr_over_h"), ".3f"),
                     place,
                     Num(real(s, "delta_cr_nonlocal_over_h"), ".3f"),
                     Num(real(s, "lock_force_over_Eh"), ".4e"),
                     Num(real(s, "peak_force_over_Eh"), ".4e"),
                     Num(real(s, "steady_force_over_Eh"), ".4e"),
                     Num(real(s, "steady_reached_at_delta_over_h"), ".2f"),
                     Num(real(s, "max_thinning"), ".3f"),
                     Num(real(s, "energy_balance_error"), ".1e")])
    header = ["deck", "status", "Δcr/h", "s*/h", "Δcr/h (averaged)", "F/(E h) at lock",
              "peak N/(E h)", "steady N/(E h)", "steady from Δ/h", "max thinning",
              "energy balance"]
    align = ["---", "---"] + ["---:"] * 9
    return lambda raw: markdown_table(header, align, rows, raw)


def script_output(ctx, args):
    """The stdout of one of the study scripts, run from the repository."""
    env = dict(os.environ)
    proc = subprocess.run(args, cwd=ROOT, env=env, stdout=subprocess.PIPE, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} exited with status {proc.returncode}")
    return proc.stdout.rstrip("\n")


def verbatim_block(ctx, args, shown):
    """The stdout of the command ARGS as a code block under the command
    line SHOWN."""
    return "```\n$ " + shown + "\n" + script_output(ctx, args) + "\n```"


def gen_continuum_table(ctx):
    """docs/validation.md: scripts/validation_table.sh (every case kept under
    docs/validation/continuum/cc_*, the program with both sections against
    it), its markdown table verbatim."""
    text = script_output(ctx, ["scripts/validation_table.sh", "--bin", ctx.program])
    return lambda raw: text


def gen_step_study(ctx):
    """docs/validation.md: scripts/convergence.sh -s (every increment control
    halved) on every paper deck and contact-section deck, verbatim."""
    decks = sorted(f"input/{f}" for f in os.listdir(os.path.join(ROOT, "input"))
                   if f.endswith(".nml") and (f.startswith("fig") or f.startswith("cc_")))
    out = script_output(ctx, ["scripts/convergence.sh", "-s", "-o", os.path.join(ctx.tmp, "step")]
                        + decks)
    text = "```\n$ scripts/convergence.sh -s input/fig*.nml input/cc_*.nml\n" + out + "\n```"
    return lambda raw: text


def gen_paper_criterion_steps(ctx):
    """docs/validation.md: the step study of fig5a down to every increment
    divided by 8 (scripts/convergence.sh -s -f "1 0.5 0.25 0.125"), verbatim,
    then from each run's pull.dat the smallest localization indicator (7.2)
    at 0.5h, 1h and 1.5h of pull (linear between increments), and the place
    s* of the paper's criterion."""
    deck = "input/fig5a_beadA_steel.nml"
    factors = ["1", "0.5", "0.25", "0.125"]
    outdir = os.path.join(ctx.tmp, "paper_steps")
    out = script_output(ctx, ["scripts/convergence.sh", "-s", "-f", " ".join(factors), "-o", outdir, deck])
    marks = [0.5, 1.0, 1.5]
    lines = ["", "factor   g(0.5h)   g(1.0h)   g(1.5h)    s*/h"]
    for f in factors:
        run = os.path.join(outdir, f"fig5a_beadA_steel_step{f}")
        found = {}
        last = None
        with open(os.path.join(run, "pull.dat")) as pull:
            for line in pull:
                if line.startswith("#") or not line.strip():
                    continue
                cols = line.split()
                delta, g = float(cols[0]), float(cols[5])
                for mark in marks:
                    if mark not in found and last is not None and last[0] < mark <= delta:
                        # linear between the increments around the mark
                        w = (mark - last[0])/(delta - last[0])
                        found[mark] = last[1] + w*(g - last[1])
                last = (delta, g)
        star = read_summary(os.path.join(run, "summary.txt")).get("s_star_over_h", "none")
        cells = ["%9.2e" % found[m] if m in found else "%9s" % "-" for m in marks]
        lines.append("%-6s %s %7s" % (f, " ".join(cells), "%.2f" % float(star) if star != "none" else star))
    text = ("```\n$ scripts/convergence.sh -s -f \"1 0.5 0.25 0.125\" input/fig5a_beadA_steel.nml\n"
            + out + "\n" + "\n".join(lines) + "\n```")
    return lambda raw: text


def gen_convergence(ctx):
    """docs/validation.md: scripts/convergence.sh on fig5a and fig9c, verbatim."""
    out = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "conv"),
                              "input/fig5a_beadA_steel.nml", "input/fig9c_beadA_steel_free.nml"])
    text = "```\n$ scripts/convergence.sh -m input/fig5a_beadA_steel.nml " \
           "input/fig9c_beadA_steel_free.nml\n" + out + "\n```"
    return lambda raw: text


def gen_convergence_shipped(ctx):
    """docs/validation.md: the free-edge bead A mesh as shipped (96), doubled twice."""
    out = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "conv96"),
                              "-n", "96 192 384", "input/fig9c_beadA_steel_free.nml"])
    text = '```\n$ scripts/convergence.sh -m -n "96 192 384" ' \
           "input/fig9c_beadA_steel_free.nml\n" + out + "\n```"
    return lambda raw: text


def gen_tearing_convergence(ctx):
    """docs/validation.md: scripts/convergence.sh -m on the clamped steel
    continuum-check decks on their uniform mesh (copies with refine_exit =
    .false., named like the decks), 80 to 640 elements, verbatim."""
    ndir = os.path.join(ctx.tmp, "uniform_decks")
    os.makedirs(ndir, exist_ok=True)
    decks = []
    for deck in ["input/cc_fig5a_beadA_steel.nml", "input/cc_fig6_beadB_steel.nml",
                 "input/cc_beadA_steel_mu0.nml"]:
        copy = os.path.join(ndir, os.path.basename(deck))
        with open(copy, "w") as out:
            out.write(read_doc(deck).replace("\n&sheet\n", "\n&sheet\n   refine_exit = .false.\n", 1))
        decks.append(copy)
    out = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "tear"),
                              "-n", "80 160 320 640"] + decks)
    text = ('```\n$ scripts/convergence.sh -m -n "80 160 320 640" <the decks with refine_exit = .false.>\n'
            + out + "\n```")
    return lambda raw: text


NECK_DECKS = ["input/cc_fig5a_beadA_steel.nml", "input/cc_fig6_beadB_steel.nml",
              "input/cc_beadA_steel_mu0.nml"]


def neck_decks(ctx, folder, zone_h=None):
    """Copies of the clamped steel continuum-check decks with &sheet
    refine_neck = .true. (and refine_element = zone_h if given), stopped at
    the tearing point (stop_at_localization = .true.)."""
    ndir = os.path.join(ctx.tmp, folder)
    os.makedirs(ndir, exist_ok=True)
    decks = []
    for deck in NECK_DECKS:
        text = read_doc(deck)
        if "\n&sheet\n" not in text or "stop_at_localization = .false." not in text:
            raise RuntimeError(f"{deck}: no &sheet line of its own or no stop_at_localization = .false.")
        extra = "   refine_neck = .true.\n"
        if zone_h is not None:
            extra += "   refine_element = %g\n" % zone_h
        text = text.replace("\n&sheet\n", "\n&sheet\n" + extra, 1)
        text = text.replace("stop_at_localization = .false.", "stop_at_localization = .true.")
        copy = os.path.join(ndir, os.path.basename(deck)[:-4] + "_neck.nml")
        with open(copy, "w") as out:
            out.write(text)
        decks.append(copy)
    return decks


def stopped_decks(ctx, folder, decks):
    """Copies of decks stopped at the tearing point (stop_at_localization =
    .true.), named like the decks, in folder."""
    ndir = os.path.join(ctx.tmp, folder)
    os.makedirs(ndir, exist_ok=True)
    copies = []
    for deck in decks:
        text = read_doc(deck)
        if "stop_at_localization = .false." not in text:
            raise RuntimeError(f"{deck}: no stop_at_localization = .false.")
        copy = os.path.join(ndir, os.path.basename(deck))
        with open(copy, "w") as out:
            out.write(text.replace("stop_at_localization = .false.", "stop_at_localization = .true."))
        copies.append(copy)
    return copies


DEFAULT_DECKS = NECK_DECKS + ["input/cc_beadA_aluminium.nml", "input/cc_beadB_aluminium.nml",
                              "input/cc_beadA_hss.nml", "input/cc_beadB_hss.nml"]


def gen_tearing_default(ctx):
    """docs/validation.md: the tearing point on the default path (refine_exit,
    theory 7.6): the clamped continuum-check decks stopped at the tearing
    point, scripts/convergence.sh -m -n "80 160 320 640" and -s, verbatim,
    then from the 80-element summaries the phase, the tearing point, the
    first split's pull, the splits, the split span and the elements."""
    decks = stopped_decks(ctx, "default_decks", [d for d in DEFAULT_DECKS if os.path.exists(os.path.join(ROOT, d))])
    mesh = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "default_mesh"),
                               "-n", "80 160 320 640"] + decks)
    steps = script_output(ctx, ["scripts/convergence.sh", "-s", "-o", os.path.join(ctx.tmp, "default_step")]
                          + decks)
    lines = ["", "%-22s %6s %8s %8s %8s %6s %9s %9s %8s" % ("deck (80 elements)", "phase", "tear/h", "lock/h",
                                                             "split/h", "splits", "from/h", "to/h", "elements")]
    for deck in decks:
        name = os.path.basename(deck)[:-4]
        summ = read_summary(os.path.join(ctx.tmp, "default_mesh", f"{name}_80", "summary.txt"))

        def num(key, fmt):
            v = summ.get(key, "none")
            return fmt % float(v) if v != "none" else fmt.replace(".3f", "s").replace(".2f", "s") % v
        lines.append("%-22s %6s %s %s %s %6s %s %s %8s" % (name, summ.get("tearing_phase"),
                                                         num("tearing_delta_over_h", "%8.3f"),
                                                         num("tearing_lock_over_h", "%8.3f"),
                                                         num("split_load_over_h", "%8.3f"), summ.get("split_count"),
                                                         num("split_from_over_h", "%9.2f"),
                                                         num("split_to_over_h", "%9.2f"), summ.get("elements")))
    text = ('```\n$ scripts/convergence.sh -m -n "80 160 320 640" <the decks, stop_at_localization = .true.>\n'
            + mesh + "\n\n$ scripts/convergence.sh -s <the same decks>\n" + steps + "\n" + "\n".join(lines)
            + "\n```")
    return lambda raw: text


# the strain-gradient coefficient's share in the tearing point (theory
# 12.7): the clamped continuum-check decks that neck in the pull and the
# double bead, stopped at tearing, with &sheet strain_gradient scaled
GRADIENT_DECKS = ["input/cc_fig5a_beadA_steel.nml", "input/cc_fig6_beadB_steel.nml",
                  "input/cc_beadA_steel_mu0.nml", "input/cc_beadA_aluminium.nml",
                  "input/cc_beadB_aluminium.nml", "input/cc_beadB_hss.nml", "input/cc_double_bead.nml",
                  # beyond the validation table: beads with tighter radii (their
                  # continuum checks kept in docs/validation/continuum/<name>/)
                  "docs/validation/continuum/decks/tight_beadA_steel.nml",
                  "docs/validation/continuum/decks/tight_beadA_hsla.nml",
                  "docs/validation/continuum/decks/tight_round_aluminium.nml",
                  # the cases beyond the tables (docs/validation.md)
                  "docs/validation/continuum/decks/unseen_beadA_aa5754.nml",
                  "docs/validation/continuum/decks/unseen_beadC_steel.nml",
                  "docs/validation/continuum/decks/unseen_beadB_aa6111_mu015.nml",
                  "docs/validation/continuum/decks/unseen_beadC_stainless.nml"]
GRADIENT_VALUES = [0.25, 0.5, 1.0, 2.0]


def matching_value(values, tears, target):
    """The coefficient at which the tearing point meets target, linear in
    log(coefficient) between the neighbouring values of the study whose
    tearing points bracket it (tearing points rise with the coefficient);
    a bound ("< v", "> v") outside the range studied."""
    pairs = [(v, t) for v, t in zip(values, tears) if t is not None]
    if not pairs or target is None:
        return "none"
    for (v0, t0), (v1, t1) in zip(pairs, pairs[1:]):
        if t0 <= target <= t1 and t1 > t0:
            w = (target - t0) / (t1 - t0)
            return "%.2f" % math.exp(math.log(v0) + w * (math.log(v1) - math.log(v0)))
    return "< %g" % pairs[0][0] if target < pairs[0][1] else "> %g" % pairs[-1][0]


def continuum_neck(name):
    """The continuum's neck of the case NAME kept under
    docs/validation/continuum/NAME/: the pull (delta/h) at its largest
    restraining force, from its continuum_summary.txt."""
    cont = read_summary(os.path.join(ROOT, "docs", "validation", "continuum", name, "continuum_summary.txt"))
    return real(cont, "max_restraining_force_at_delta_over_h")


def gen_strain_gradient_study(ctx):
    """docs/theory.md 12.7: the tearing point (tearing_delta_over_h) of the
    GRADIENT_DECKS, 80 elements, stopped at tearing, with strain_gradient =
    each of GRADIENT_VALUES, against the continuum's neck (the pull at its
    largest restraining force, docs/validation/continuum/<deck>/
    continuum_summary.txt), and the coefficient that would meet it."""
    decks = stopped_decks(ctx, "gradient_decks", GRADIENT_DECKS)
    jobs = []
    for deck in decks:
        text = read_doc(deck)
        if "\n&sheet\n" not in text:
            raise RuntimeError(f"{deck}: no &sheet line of its own")
        base = os.path.basename(deck)[:-4]
        for value in GRADIENT_VALUES:
            jobs.append((f"gradient_{base}_{value:g}",
                         text.replace("\n&sheet\n", "\n&sheet\n   strain_gradient = %g\n" % value, 1)))
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for deck in decks:
        base = os.path.basename(deck)[:-4]
        neck = continuum_neck(base)
        tears = [real(res[f"gradient_{base}_{v:g}"], "tearing_delta_over_h") for v in GRADIENT_VALUES]
        ratios = [quotient(t, neck) for t in tears]
        rows.append([base, Num(neck, ".3f")] + [Num(t, ".3f") for t in tears]
                    + [Num(r, ".2f") for r in ratios] + [matching_value(GRADIENT_VALUES, tears, neck)])
    header = (["deck (stopped at tearing, 80 elements)", "continuum's neck Δ/h"]
              + ["tearing Δ/h, c × %g" % v for v in GRADIENT_VALUES]
              + ["/ continuum, c × %g" % v for v in GRADIENT_VALUES] + ["c × that meets it"])
    align = ["---"] + ["---:"] * (2 + 2 * len(GRADIENT_VALUES))
    return lambda raw: markdown_table(header, align, rows, raw)


# the element counts of the neck-element study (theory 7.6): uniform
# meshes, refine_exit off, and refine_neck's 0.08h zone at the neck as the
# fine reference
NECK_ELEMENT_COUNTS = [40, 80, 160]


def gen_neck_element_study(ctx):
    """docs/theory.md 7.6: on how long elements the tearing point converges
    at the neck: the GRADIENT_DECKS stopped at tearing on NECK_ELEMENT_COUNTS
    uniform elements (&sheet refine_exit = .false.; the deck's own
    increments) and with refine_neck (its zone of 0.08h at the neck), the
    tearing point over the continuum's neck, the element length at the
    tearing point, and each uniform mesh's tearing point against
    refine_neck's."""
    decks = stopped_decks(ctx, "neck_element_decks", GRADIENT_DECKS)
    jobs = []
    for deck in decks:
        text = read_doc(deck)
        if "\n&sheet\n" not in text or "n_elements = 80" not in text:
            raise RuntimeError(f"{deck}: no &sheet line of its own or no n_elements = 80")
        base = os.path.basename(deck)[:-4]
        for n in NECK_ELEMENT_COUNTS:
            jobs.append((f"neck_element_{base}_{n}",
                         text.replace("n_elements = 80", "n_elements = %d" % n, 1)
                         .replace("\n&sheet\n", "\n&sheet\n   refine_exit = .false.\n", 1)))
        jobs.append((f"neck_element_{base}_zone", text.replace("\n&sheet\n", "\n&sheet\n   refine_neck = .true.\n", 1)))
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for deck in decks:
        base = os.path.basename(deck)[:-4]
        neck = continuum_neck(base)
        names = [f"neck_element_{base}_{n}" for n in NECK_ELEMENT_COUNTS] + [f"neck_element_{base}_zone"]
        tears = [real(res[name], "tearing_delta_over_h") for name in names]
        elements = [real(res[name], "tearing_element_over_h") for name in names[:-1]]
        zone = tears[-1]
        rows.append([base, Num(neck, ".3f")]
                    + [Num(quotient(t, neck), ".3f") for t in tears]
                    + [Num(e, ".2f") for e in elements]
                    + [Num(100.0 * (quotient(t, zone) - 1.0) if quotient(t, zone) is not None else None, "+.1f")
                       for t in tears[:-1]])
    header = (["deck (stopped at tearing)", "continuum's neck Δ/h"]
              + ["/ continuum, %d elements" % n for n in NECK_ELEMENT_COUNTS] + ["/ continuum, refine_neck"]
              + ["element at the tearing point / h, %d" % n for n in NECK_ELEMENT_COUNTS]
              + ["against refine_neck, %%, %d" % n for n in NECK_ELEMENT_COUNTS])
    align = ["---"] + ["---:"] * (1 + 1 + 3 * len(NECK_ELEMENT_COUNTS))
    return lambda raw: markdown_table(header, align, rows, raw)


def pull_force_curve(path):
    """(delta/h, N) of a pull.dat (the program's or the continuum's, columns
    1 and 3; continuum_results' reader), rows with a non-finite value there
    left out."""
    rows = [r for r in continuum_results.read_rows(path) if math.isfinite(r[0]) and math.isfinite(r[2])]
    return [r[0] for r in rows], [r[2] for r in rows]


def plateau(xs, ys, share):
    """The span of delta/h around the largest N over which N stays within
    share of it (the rows on either side of the largest, the ends where it
    leaves interpolated linearly), as text "first-last"; an end the curve
    does not leave before its first or last row is that row's, marked
    "(end)"."""
    if not ys:
        raise RuntimeError("plateau: a force curve with no rows")
    k = max(range(len(ys)), key=lambda i: ys[i])
    level = ys[k] * (1.0 - share)
    ends = []
    for step in (-1, 1):
        i = k
        while 0 <= i + step < len(ys) and ys[i + step] >= level:
            i += step
        j = i + step
        if 0 <= j < len(ys) and ys[j] != ys[i]:
            ends.append("%.2f" % (xs[i] + (level - ys[i]) / (ys[j] - ys[i]) * (xs[j] - xs[i])))
        else:
            ends.append("%.2f (end)" % xs[i])
    return ends[0] + "-" + ends[1]


# the share of the largest restraining force within which tearing_flatness
# gives each model's span around its maximum (a quarter of the 1% that
# confirms a neck, theory 7.4)
FLATNESS_SHARE = 0.0025


def gen_tearing_flatness(ctx):
    """docs/validation.md: how flat the restraining force is at the tearing
    point: the GRADIENT_DECKS stopped at tearing (80 elements, as shipped)
    against their kept continuum runs: the tearing point and the
    continuum's neck, the continuum's force at the program's tearing point
    and the program's at the continuum's neck (each over its own largest),
    the span of the pull over which each model's force is within
    FLATNESS_SHARE of its largest, and the largest forces' ratio."""
    decks = stopped_decks(ctx, "flatness_decks", GRADIENT_DECKS)
    jobs = [("flatness_" + os.path.basename(d)[:-4], d) for d in decks]
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for deck in decks:
        base = os.path.basename(deck)[:-4]
        folder = os.path.join(ROOT, "docs", "validation", "continuum", base)
        cont = read_summary(os.path.join(folder, "continuum_summary.txt"))
        neck = real(cont, "max_restraining_force_at_delta_over_h")
        tear = real(res["flatness_" + base], "tearing_delta_over_h")
        cx, cy = pull_force_curve(os.path.join(folder, "pull.dat"))
        px, py = pull_force_curve(os.path.join(ctx.tmp, "flatness_" + base, "pull.dat"))
        c_at = continuum_results.interp(cx, cy, tear) if tear is not None else None
        p_at = continuum_results.interp(px, py, neck) if neck is not None else None
        if not cy or not py:
            raise RuntimeError(f"{base}: no pull rows (program or continuum)")
        rows.append([base, Num(neck, ".3f"), Num(tear, ".3f"), Num(quotient(tear, neck), ".3f"),
                     Num(quotient(c_at, max(cy)), ".4f"), Num(quotient(p_at, max(py)), ".4f"),
                     plateau(cx, cy, FLATNESS_SHARE), plateau(px, py, FLATNESS_SHARE),
                     Num(quotient(max(py), max(cy)), ".4f")])
    pct = "%g%%" % (100.0 * FLATNESS_SHARE)
    header = ["deck (stopped at tearing, 80 elements)", "continuum's neck Δ/h", "tearing Δ/h",
              "/ continuum", "continuum's N at the tearing point / its largest",
              "program's N at the continuum's neck / its largest",
              f"continuum's N within {pct} of its largest, Δ/h",
              f"program's N within {pct} of its largest, Δ/h", "largest N, program / continuum"]
    align = ["---"] + ["---:"] * 8
    return lambda raw: markdown_table(header, align, rows, raw)


# the stainless-like sheet pulled 4.8h, before the continuum's maximum
# (docs/validation/continuum/decks/unseen_beadC_stainless_pull4.8h.nml),
# and the reference positions s/h of its strain rows: upstream of the
# neck, through it, and the straight sheet downstream
STAINLESS_EARLY_DECK = "docs/validation/continuum/decks/unseen_beadC_stainless_pull4.8h.nml"
STAINLESS_EARLY_S = [4.0, 5.0, 6.0, 6.5, 7.0, 7.25, 7.5, 7.75, 8.0, 8.5, 9.0, 10.0, 12.0, 14.0]


# variants of the stainless-like deck: (what, text of the deck, its
# replacement); none: the deck as it is
STAINLESS_VARIANTS = [(None, None, None),
                      ("n_elements = 160", "n_elements = 80", "n_elements = 160"),
                      ("thickness_points = 41", "\n&material\n", "\n&material\n   thickness_points = 41,\n"),
                      ("penalty = 0.1", "\n&tools\n", "\n&tools\n   penalty = 0.1,\n"),
                      ("penalty = 0.37, contact_smoothing = 0.001", "\n&tools\n",
                       "\n&tools\n   penalty = 0.37, contact_smoothing = 0.001,\n"),
                      ("contact_faces = 'reference'", "\n&tools\n", "\n&tools\n   contact_faces = 'reference',\n")]


def strain_rows(path):
    """(s/h, ln(lambda), thickness log strain) of a strain file's rows
    (columns 1, 5 and 8; continuum_results' reader), non-finite rows left
    out."""
    return [(r[0], r[4], r[7]) for r in continuum_results.read_rows(path)
            if all(math.isfinite(v) for v in (r[0], r[4], r[7]))]


def gen_stainless_early(ctx):
    """docs/validation.md: the stainless-like sheet on bead C pulled 4.8h
    (STAINLESS_EARLY_DECK), the program against its kept continuum run:
    the restraining force at the end of the pull, and the stretch and
    thickness strain at STAINLESS_EARLY_S (linear between each model's
    rows)."""
    res = run_many(ctx.program, [("stainless_early", STAINLESS_EARLY_DECK)], ctx.tmp, 1)
    assert res
    folder = os.path.join(ROOT, "docs", "validation", "continuum", "unseen_beadC_stainless_pull4.8h")
    run = os.path.join(ctx.tmp, "stainless_early")
    cont = strain_rows(os.path.join(folder, "strain_pull.dat"))
    prog = strain_rows(os.path.join(run, "strain_pull.dat"))
    cx, cy = pull_force_curve(os.path.join(folder, "pull.dat"))
    px, py = pull_force_curve(os.path.join(run, "pull.dat"))
    p48, c48 = continuum_results.interp(px, py, 4.8), continuum_results.interp(cx, cy, 4.8)
    rows = [["restraining force, N/mm", Num(p48, ".1f"), Num(c48, ".1f"), Num(quotient(p48, c48), ".3f")]]
    for s in STAINLESS_EARLY_S:
        for col, what in ((1, "ln(λ)"), (2, "thickness log strain")):
            p = continuum_results.interp([r[0] for r in prog], [r[col] for r in prog], s)
            c = continuum_results.interp([r[0] for r in cont], [r[col] for r in cont], s)
            rows.append([f"{what} at s/h = {s:g}", Num(p, ".3f"), Num(c, ".3f"), Num(quotient(p, c), ".3f")])
    header = ["at 4.8h of pull", "program", "continuum", "program / continuum"]
    # the whole deck stopped at tearing, as it is and with the variants of
    # STAINLESS_VARIANTS: the tearing point and the force at 4h of pull
    base = read_doc(stopped_decks(ctx, "stainless_decks",
                                  ["docs/validation/continuum/decks/unseen_beadC_stainless.nml"])[0])
    jobs = []
    for k, (_, was, now) in enumerate(STAINLESS_VARIANTS):
        text = base
        if was is not None:
            if was not in text:
                raise RuntimeError(f"unseen_beadC_stainless.nml: {was.strip()} expected")
            text = text.replace(was, now, 1)
        jobs.append((f"stainless_{k}", text))
    vres = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    neck = real(read_summary(os.path.join(ROOT, "docs", "validation", "continuum", "unseen_beadC_stainless",
                                          "continuum_summary.txt")), "max_restraining_force_at_delta_over_h")
    fx, fy = pull_force_curve(os.path.join(ROOT, "docs", "validation", "continuum", "unseen_beadC_stainless",
                                           "pull.dat"))
    f4 = continuum_results.interp(fx, fy, 4.0)
    vrows = []
    for k, (what, _, _) in enumerate(STAINLESS_VARIANTS):
        tear = real(vres[f"stainless_{k}"], "tearing_delta_over_h")
        vx, vy = pull_force_curve(os.path.join(ctx.tmp, f"stainless_{k}", "pull.dat"))
        n4 = continuum_results.interp(vx, vy, 4.0)
        vrows.append([what or "the deck as it is", Num(tear, ".3f"),
                      Num(quotient(tear, neck), ".3f"), Num(n4, ".1f"), Num(quotient(n4, f4), ".3f")])
    vheader = ["unseen_beadC_stainless, stopped at tearing", "tearing Δ/h", "/ continuum's neck",
               "N at 4h, N/mm", "/ continuum's"]

    def text(raw):
        return (markdown_table(header, ["---", "---:", "---:", "---:"], rows, raw) + "\n\n"
                + markdown_table(vheader, ["---", "---:", "---:", "---:", "---:"], vrows, raw))
    return text


FRICTION_CASES = [(0.0, "cc_beadA_steel_mu0"), (0.05, "friction_beadA_mu0.05"),
                  (0.1, "cc_fig5a_beadA_steel"), (0.2, "friction_beadA_mu0.2")]
FRICTION_ELEMENTS = [80, 160, 640]


def continuum_neck_place(folder):
    """The reference s/h of the continuum's thinnest mid-surface row at the
    end of its pull (strain_pull.dat column 8, NaN rows left out): where it
    necked."""
    with open(os.path.join(folder, "strain_pull.dat"), encoding="utf-8") as f:
        rows = [ln.split() for ln in f if ln.strip() and not ln.startswith("#")]
    rows = [cols for cols in rows if math.isfinite(float(cols[7]))]
    return float(min(rows, key=lambda cols: float(cols[7]))[0]) if rows else None


def gen_tearing_friction(ctx):
    """docs/validation.md: the tearing point of input/cc_fig5a_beadA_steel.nml
    with friction = each mu of FRICTION_CASES, pulled 4h and stopped at
    tearing, on FRICTION_ELEMENTS elements (the default path): 80 as
    shipped, the finer meshes with the largest increment 0.1h * 80 / n as
    scripts/convergence.sh -m runs them; against the continuum's neck kept
    in docs/validation/continuum/<case>/ (the pull at its largest
    restraining force, and where its sheet necked)."""
    base = read_doc(stopped_decks(ctx, "friction_decks", ["input/cc_fig5a_beadA_steel.nml"])[0])
    for old in ("friction = 0.1\n", "pull_distance = 2.286", "n_elements = 80"):
        if old not in base:
            raise RuntimeError(f"input/cc_fig5a_beadA_steel.nml: {old.strip()} expected")
    h = float(re.search(r"thickness\s*=\s*([0-9.]+)", base).group(1))
    jobs = []
    for mu, _ in FRICTION_CASES:
        for n in FRICTION_ELEMENTS:
            loading = "pull_distance = %.8g" % (4.0 * h)
            if n != FRICTION_ELEMENTS[0]:
                loading += ", max_increment = %.8g" % (0.1 * h * FRICTION_ELEMENTS[0] / n)
            text = (base.replace("friction = 0.1\n", "friction = %g\n" % mu, 1)
                    .replace("pull_distance = 2.286", loading, 1)
                    .replace("n_elements = 80", "n_elements = %d" % n, 1))
            jobs.append((f"friction_{mu:g}_{n}", text))
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for mu, case in FRICTION_CASES:
        folder = os.path.join(ROOT, "docs", "validation", "continuum", case)
        cont = read_summary(os.path.join(folder, "continuum_summary.txt"))
        neck = real(cont, "max_restraining_force_at_delta_over_h")
        tears = [real(res[f"friction_{mu:g}_{n}"], "tearing_delta_over_h") for n in FRICTION_ELEMENTS]
        first = res[f"friction_{mu:g}_{FRICTION_ELEMENTS[0]}"]
        rows.append(["%g" % mu, Num(neck, ".3f"), Num(continuum_neck_place(folder), ".1f")]
                    + [Num(t, ".3f") for t in tears]
                    + [Num(quotient(tears[0], neck), ".2f"),
                       Num(None if quotient(tears[0], tears[-1]) is None
                           else 100.0 * (quotient(tears[0], tears[-1]) - 1.0), "+.1f"),
                       Num(real(first, "tearing_s_over_h"), ".1f"), first.get("tearing_mesh_dependent", "none")])
    header = (["μ", "continuum's neck Δ/h", "its place s/h", "tearing Δ/h, %d elements as shipped" % FRICTION_ELEMENTS[0]]
              + ["%d elements (-m)" % n for n in FRICTION_ELEMENTS[1:]]
              + ["as shipped / continuum", "as shipped against %d (-m), %%" % FRICTION_ELEMENTS[-1],
                 "place s/h (as shipped)", "mesh dependent (as shipped)"])
    align = ["---:"] * (len(header) - 1) + ["---"]
    return lambda raw: markdown_table(header, align, rows, raw)


# cases the program was not tuned on, chosen after its defaults were set:
# their decks in docs/validation/continuum/decks/, their continuum checks
# kept in docs/validation/continuum/<name>/ (docs/validation.md, cases
# beyond the tables)
UNSEEN_CASES = ["unseen_beadA_aa5754", "unseen_beadC_steel", "unseen_beadB_aa6111_mu015",
                "unseen_beadC_stainless"]
UNSEEN_ELEMENTS = [80, 160, 640]
# the compared numbers (continuum_results.py metrics): label, key
UNSEEN_RATIOS = [("punch force, 98% of lock", "punch_force_98_N_per_mm"),
                 ("tension, 98% of lock", "lock_tension_98_N_per_mm"),
                 ("largest restraining force", "max_restraining_force_N_per_mm"),
                 ("lift at 1h", "lift_at_1h_N_per_mm"),
                 ("peak strain after locking", "peak_strain_lock")]


def gen_unseen_cases(ctx):
    """docs/validation.md: the UNSEEN_CASES against their kept continuum
    checks: the deck as it is (pulled through, not stopped) read by
    scripts/continuum_results.py metrics as scripts/validation_table.sh
    reads the table's cases, its ratios to the continuum's numbers; and
    the tearing point of the deck stopped at it, scripts/convergence.sh -m
    on UNSEEN_ELEMENTS and -s (every increment halved), against the
    continuum's neck (the pull at its largest restraining force)."""
    names = UNSEEN_CASES
    for n in names:
        if not os.path.exists(os.path.join(ROOT, "docs", "validation", "continuum", n, "continuum_summary.txt")):
            raise RuntimeError(f"unseen_cases: no kept continuum check docs/validation/continuum/{n}/")
    decks = [os.path.join("docs", "validation", "continuum", "decks", n + ".nml") for n in names]
    stopped = stopped_decks(ctx, "unseen_stopped", decks)
    counts = " ".join(str(n) for n in UNSEEN_ELEMENTS)
    script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "unseen_mesh"), "-n", counts]
                  + stopped)
    script_output(ctx, ["scripts/convergence.sh", "-s", "-o", os.path.join(ctx.tmp, "unseen_step")] + stopped)
    rows = []
    for name, deck in zip(names, decks):
        out = os.path.join(ctx.tmp, "unseen_whole", name)
        os.makedirs(out, exist_ok=True)
        summary, status = run_deck(ctx.program, deck, out, "run", one_thread=True)
        if status != 0 or not summary:
            raise RuntimeError(f"unseen_cases: {deck} exited with status {status}")
        subprocess.run([sys.executable, "scripts/continuum_model.py", os.path.join(out, "run.log"),
                        os.path.join(out, "model")], cwd=ROOT, stdout=subprocess.DEVNULL, check=True)
        metrics = subprocess.run([sys.executable, "scripts/continuum_results.py", "metrics", os.path.join(out, "run"),
                                  os.path.join(out, "model", "continuum_model.json")], cwd=ROOT, check=True,
                                 stdout=subprocess.PIPE, text=True).stdout
        prog = {}
        for line in metrics.splitlines():
            if " = " in line and not line.startswith("#"):
                key, value = line.split(" = ", 1)
                prog[key.strip()] = value.strip()
        cont = read_summary(os.path.join(ROOT, "docs", "validation", "continuum", name, "continuum_summary.txt"))
        neck = real(cont, "max_restraining_force_at_delta_over_h")
        tears = [real(read_summary(os.path.join(ctx.tmp, "unseen_mesh", f"{name}_{n}", "summary.txt")),
                      "tearing_delta_over_h") for n in UNSEEN_ELEMENTS]
        own, halved = [real(read_summary(os.path.join(ctx.tmp, "unseen_step", f"{name}_step{f}", "summary.txt")),
                            "tearing_delta_over_h") for f in ("1", "0.5")]
        first = read_summary(os.path.join(ctx.tmp, "unseen_mesh", f"{name}_{UNSEEN_ELEMENTS[0]}", "summary.txt"))

        def pct(a, b):
            q = quotient(a, b)
            return Num(None if q is None else 100.0 * (q - 1.0), "+.1f")
        rows.append([name, first.get("tearing_phase", "none"), Num(neck, ".3f")] + [Num(x, ".3f") for x in tears]
                    + [Num(quotient(tears[0], neck), ".2f"), pct(tears[0], tears[-1]), pct(tears[1], tears[-1]),
                       pct(halved, own)]
                    + [Num(quotient(real(prog, key), real(cont, key)), ".3f") for _, key in UNSEEN_RATIOS])
    header = (["case", "phase", "continuum's neck Δ/h"] + ["tearing Δ/h, %d el." % n for n in UNSEEN_ELEMENTS]
              + ["%d el. / continuum" % UNSEEN_ELEMENTS[0],
                 "%d against %d, %%" % (UNSEEN_ELEMENTS[0], UNSEEN_ELEMENTS[-1]),
                 "%d against %d, %%" % (UNSEEN_ELEMENTS[1], UNSEEN_ELEMENTS[-1]),
                 "steps halved, %"]
              + [label + ", / continuum" for label, _ in UNSEEN_RATIOS])
    align = ["---", "---"] + ["---:"] * (len(header) - 2)
    return lambda raw: markdown_table(header, align, rows, raw)


def gen_tearing_step_sweep(ctx):
    """docs/validation.md: scripts/convergence.sh -s with the increments
    halved three times on the clamped bead A steel deck stopped at its
    tearing point (the default path), verbatim."""
    decks = stopped_decks(ctx, "step_sweep_decks", ["input/cc_fig5a_beadA_steel.nml"])
    out = script_output(ctx, ["scripts/convergence.sh", "-s", "-f", "1 0.5 0.25 0.125",
                              "-o", os.path.join(ctx.tmp, "step_sweep")] + decks)
    text = ('```\n$ scripts/convergence.sh -s -f "1 0.5 0.25 0.125" <cc_fig5a_beadA_steel, '
            'stop_at_localization = .true.>\n' + out + "\n```")
    return lambda raw: text


def gen_tearing_neck(ctx):
    """docs/validation.md: the clamped steel continuum-check decks with
    refine_neck, stopped at the tearing point, scripts/convergence.sh -m -n
    "80 160 320 640" (the zone's elements stay 0.08h; at 640 the uniform
    elements are already shorter and there is no zone), verbatim, then from
    the summaries the first pass's tearing point and place, the zone, the
    run proper's place of the neck (s/h) and elements, and the assemblies
    of the first pass (asm1) and of the run proper (asm)."""
    decks = neck_decks(ctx, "neck_decks")
    outdir = os.path.join(ctx.tmp, "neck")
    counts = ["80", "160", "320", "640"]
    out = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", outdir, "-n", " ".join(counts)] + decks)
    lines = ["", "%-28s %5s %9s %9s %9s %9s %9s %8s %8s %8s" % ("deck", "n", "first/h", "s1/h", "zone_from",
                                                                 "zone_to", "s/h", "elements", "asm1", "asm")]
    for deck in decks:
        name = os.path.basename(deck)[:-4]
        for n in counts:
            summ = read_summary(os.path.join(outdir, f"{name}_{n}", "summary.txt"))

            def num(key, fmt="%9.3f"):
                v = summ.get(key, "none")
                return fmt % float(v) if v != "none" else "%9s" % v
            lines.append("%-28s %5s %s %s %s %s %s %8s %8s %8s" % (name, n, num("coarse_tearing_delta_over_h"),
                                                                    num("coarse_tearing_s_over_h"),
                                                                    num("neck_zone_from_over_h"),
                                                                    num("neck_zone_to_over_h"),
                                                                    num("tearing_s_over_h"), summ.get("elements"),
                                                                    summ.get("coarse_assemblies"),
                                                                    summ.get("assemblies")))
    text = ('```\n$ scripts/convergence.sh -m -n "80 160 320 640" <the decks with refine_neck = .true., '
            "stop_at_localization = .true.>\n" + out + "\n" + "\n".join(lines) + "\n```")
    return lambda raw: text


def gen_tearing_neck_steps(ctx):
    """docs/validation.md: the step study (every increment halved) of the
    clamped steel continuum-check decks with refine_neck, stopped at the
    tearing point, scripts/convergence.sh -s, verbatim."""
    decks = neck_decks(ctx, "neck_step_decks")
    out = script_output(ctx, ["scripts/convergence.sh", "-s", "-o", os.path.join(ctx.tmp, "neck_step")]
                        + decks)
    text = ("```\n$ scripts/convergence.sh -s <the decks with refine_neck = .true., "
            "stop_at_localization = .true.>\n" + out + "\n```")
    return lambda raw: text


def gen_tearing_neck_zone(ctx):
    """docs/validation.md: the clamped steel continuum-check decks with
    refine_neck and refine_element = 0.16, every element halved twice
    (scripts/convergence.sh -m -n "80 160 320": the zone's elements 0.16h,
    0.08h, 0.04h), verbatim."""
    decks = neck_decks(ctx, "neck_zone_decks", 0.16)
    out = script_output(ctx, ["scripts/convergence.sh", "-m", "-o", os.path.join(ctx.tmp, "neck_zone"),
                              "-n", "80 160 320"] + decks)
    text = ("```\n$ scripts/convergence.sh -m -n \"80 160 320\" <the decks with refine_neck = .true., "
            "refine_element = 0.16, stop_at_localization = .true.>\n" + out + "\n```")
    return lambda raw: text


def gen_bench(ctx):
    """docs/performance.md: scripts/bench.sh --markdown, verbatim."""
    out = script_output(ctx, ["scripts/bench.sh", "--markdown", "-n", "5",
                              "--keep", os.path.join(ctx.tmp, "bench")])
    return lambda raw: out


def gen_contact_cost(ctx):
    """docs/performance.md: the paper decks with the paper's section and with
    the contact section (copies with normal_stress = 'contact'), one
    thread, scripts/bench.sh --markdown, verbatim."""
    decks = []
    cdir = os.path.join(ctx.tmp, "contact_decks")
    os.makedirs(cdir, exist_ok=True)
    for f in sorted(os.listdir(os.path.join(ROOT, "input"))):
        if not (f.startswith("fig") and f.endswith(".nml")):
            continue
        text = read_doc(os.path.join("input", f))
        if "normal_stress = 'none'" not in text:
            raise RuntimeError(f"input/{f} does not set normal_stress = 'none'")
        copy = os.path.join(cdir, f[:-4] + "_contact.nml")
        with open(copy, "w") as out:
            out.write(text.replace("normal_stress = 'none'", "normal_stress = 'contact'"))
        decks += [os.path.join("input", f), copy]
    out = script_output(ctx, ["scripts/bench.sh", "--markdown", "-n", "5", "--threads", "1",
                              "--no-scaling", "--keep", os.path.join(ctx.tmp, "cost")] + decks)
    return lambda raw: out


# the variants of input/cc_fig5a_beadA_steel.nml of the laws' cost (name:
# the groups merged into the deck's own)
LAWS_COST_VARIANTS = {
    "j2": "",
    "j2_uniform": "&sheet refine_exit = .false. /\n",
    "combined_no_back_stress": "&material model = 'combined' /\n",
    # the material of input/cc_fig5a_beadA_steel_kinematic.nml (the
    # continuum-checked combined deck): one linear back stress
    "combined_linear_kinematic": "&material model = 'combined', kinematic_c = 1000.0, kinematic_gamma = 0.0 /\n",
    "combined_armstrong_frederick": ("&material model = 'combined', kinematic_c = 20000.0, 2000.0, "
                                     "kinematic_gamma = 200.0, 0.0 /\n"),
    "j2_mu_p": ("&tools friction_law = 'power', friction_p_ref = 10.0, friction_m = 0.8, "
                "friction_mu_min = 0.05, friction_mu_max = 0.3 /\n"),
}


# Gauss stations per element (src/hermite.f90 n_gauss), each with
# thickness_points material points
GAUSS_STATIONS = 4


def laws_cost_decks(ctx, names, extra_control=""):
    """The decks of LAWS_COST_VARIANTS named in NAMES, written under
    ctx.tmp/laws_cost_decks (pulled 2h instead of 3h), with EXTRA_CONTROL
    merged into &control; their paths."""
    cdir = os.path.join(ctx.tmp, "laws_cost_decks")
    os.makedirs(cdir, exist_ok=True)
    base = read_doc("input/cc_fig5a_beadA_steel.nml")
    decks = []
    for name in names:
        extras = [LAWS_COST_VARIANTS[name]] + ([extra_control] if extra_control else [])
        path = os.path.join(cdir, "cc_fig5a_" + name + ".nml")
        text = base
        # merge the variant's group into the deck's own
        for extra in extras:
            if not extra:
                continue
            group = extra.split()[0]
            body = extra[len(group):].rstrip().rstrip("/").strip()
            if group not in text:
                raise RuntimeError(f"input/cc_fig5a_beadA_steel.nml has no {group} group")
            text = text.replace(group, group + " " + body + ",", 1)
        if "pull_distance = 2.286" not in text:
            raise RuntimeError("input/cc_fig5a_beadA_steel.nml: pull_distance = 2.286 expected")
        text = text.replace("pull_distance = 2.286", "pull_distance = 1.524", 1)
        with open(path, "w") as out:
            out.write(text)
        decks.append(path)
    return decks


def gen_laws_cost(ctx):
    """docs/performance.md: the cost of the material and friction laws on
    input/cc_fig5a_beadA_steel.nml (bead A, clamped, mu = 0.1, the contact
    section): as shipped (the paper's J2 law), the same on its 80 uniform
    elements (refine_exit = .false.: the mesh of the runs with back
    stresses, which do not tear), with model = 'combined' and no back
    stress (law_combined's return mapping, the same material), with the
    one linear back stress of input/cc_fig5a_beadA_steel_kinematic.nml,
    with two Armstrong-Frederick back stresses (C = 20000, 2000 MPa,
    gamma = 200, 0), and with the power-law mu(p) of friction_power; each
    stopped at 2h of pull, one thread, five runs, scripts/bench.sh
    --markdown, verbatim."""
    decks = laws_cost_decks(ctx, list(LAWS_COST_VARIANTS))
    # five runs: single runs of the same deck vary by up to 20% on the
    # 2-core virtual machine of docs/performance.md
    out = script_output(ctx, ["scripts/bench.sh", "--markdown", "-n", "5", "--threads", "1",
                              "--no-scaling", "--keep", os.path.join(ctx.tmp, "laws_cost")] + decks)
    return lambda raw: out


def gen_laws_yielding(ctx):
    """docs/performance.md: how many material points yield in an assembly
    of the laws' cost decks on the 80 uniform elements (the J2 law, one
    linear back stress, two Armstrong-Frederick back stresses), from the
    counts that &control log_residuals prints per Newton iteration
    (converged increments; the failed attempts' are not printed)."""
    names = ["j2_uniform", "combined_linear_kinematic", "combined_armstrong_frederick"]
    decks = laws_cost_decks(ctx, names, "&control log_residuals = .true. /\n")
    odir = os.path.join(ctx.tmp, "laws_yielding")
    os.makedirs(odir, exist_ok=True)
    rows = []
    first = None
    for name, deck in zip(names, decks):
        summary, status = run_deck(ctx.program, deck, odir, name, one_thread=True)
        if status != 0 or not summary:
            raise RuntimeError(f"laws_yielding: {name} exited with status {status}")
        counts = []
        npt = None
        with open(os.path.join(odir, name + ".log"), encoding="utf-8") as log:
            for line in log:
                m = re.search(r"THICKNESS_POINTS\s*=\s*(\d+)", line)
                if m:
                    npt = int(m.group(1))
                w = line.split()
                if w and w[0] == "plastic:":
                    counts += [int(x) for x in w[1:]]
        if npt is None or not counts:
            raise RuntimeError(f"laws_yielding: {name}: no thickness_points echo or no counts")
        points = npt*GAUSS_STATIONS*int(summary["elements"])
        mean = sum(counts)/len(counts)
        first = first if first is not None else mean
        rows.append([name, summary["elements"], str(len(counts)), Num(mean, ".0f"),
                     Num(mean/points, ".3f"), Num(mean/first, ".2f")])
    header = ["deck (cc_fig5a_...)", "elements", "assemblies of the accepted attempts", "yielding points per assembly",
              "of all points", "against j2_uniform"]
    align = ["---", "---:", "---:", "---:", "---:", "---:"]
    return lambda raw: markdown_table(header, align, rows, raw)


# the continuum-check decks compared with the tools on the reference and
# on the current faces (theory 5.1), and the pulls they are read at (h)
# (not cc_beadA_hss: its continuum necks while the bead closes, so the
# pull's forces compare a necked sheet)
FACES_DECKS = ["cc_fig5a_beadA_steel", "cc_fig6_beadB_steel", "cc_beadA_steel_mu0",
               "cc_fig5b_beadA_brass", "cc_beadA_aluminium", "cc_beadB_aluminium", "cc_beadB_hss",
               "cc_double_bead", "cc_fig9c_beadA_steel_free", "cc_fig9c_beadA_steel_free_gap",
               "cc_round_bead", "cc_stepped_bead"]
# of these, the decks whose continuum necks in the pull (the others draw
# on: their largest restraining force is no neck)
FACES_NECKING = {"cc_fig5a_beadA_steel", "cc_fig6_beadB_steel", "cc_beadA_steel_mu0",
                 "cc_beadA_aluminium", "cc_beadB_aluminium", "cc_beadB_hss", "cc_double_bead"}
FACES_PULLS = [0.5, 1.0, 2.0]


def faces_jobs(decks, prefix):
    """run_many's jobs for each input/<deck>.nml of DECKS as shipped, the
    tools on the current faces (name PREFIX_<deck>_current), and with
    &tools contact_faces = 'reference' (PREFIX_<deck>_reference)."""
    jobs = []
    for deck in decks:
        text = read_doc(f"input/{deck}.nml")
        if "\n&tools\n" not in text:
            raise RuntimeError(f"input/{deck}.nml: no &tools line of its own")
        jobs.append((f"{prefix}_{deck}_reference",
                     text.replace("\n&tools\n", "\n&tools\n   contact_faces = 'reference'\n", 1)))
        jobs.append((f"{prefix}_{deck}_current", f"input/{deck}.nml"))
    return jobs


def pull_value_at(path, column, delta):
    """Column COLUMN (1-based) of the pull.dat at PATH, linear in column 1
    (delta/h) at DELTA (continuum_results' reader and interpolation); None
    when the run did not get there."""
    rows = continuum_results.read_rows(path)
    return continuum_results.interp([r[0] for r in rows], [r[column - 1] for r in rows], delta)


def gen_contact_faces(ctx):
    """docs/validation.md: the continuum-check decks FACES_DECKS as shipped
    (the tools on the current faces, theory 5.1) and with &tools
    contact_faces = 'reference': restraining force and lift over the kept
    continuum's at FACES_PULLS h of pull (pull.dat columns 3 and 8, linear
    in the pull), the tearing point against the continuum's neck (its
    largest restraining force, where it necks), and the energy balance."""
    res = run_many(ctx.program, faces_jobs(FACES_DECKS, "faces"), ctx.tmp, ctx.workers)
    rows = []
    for deck in FACES_DECKS:
        cdir = os.path.join(ROOT, "docs", "validation", "continuum", deck)
        cont = read_summary(os.path.join(cdir, "continuum_summary.txt"))
        neck = real(cont, "max_restraining_force_at_delta_over_h") if deck in FACES_NECKING else None
        cpull = os.path.join(cdir, "pull.dat")
        for faces in ("reference", "current"):
            name = f"faces_{deck}_{faces}"
            ppull = os.path.join(ctx.tmp, name, "pull.dat")
            ratios = []
            for column in (3, 8):
                for delta in FACES_PULLS:
                    ratios.append(Num(quotient(pull_value_at(ppull, column, delta),
                                               pull_value_at(cpull, column, delta)), ".3f"))
            summary = res[name]
            rows.append([deck, faces] + ratios
                        + [Num(real(summary, "tearing_delta_over_h"), ".2f"), Num(neck, ".2f"),
                           Num(real(summary, "energy_balance_error"), ".1e")])
    header = (["deck", "faces"] + [f"N / continuum at {d:g}h" for d in FACES_PULLS]
              + [f"lift / continuum at {d:g}h" for d in FACES_PULLS]
              + ["tearing Δ/h", "continuum's neck Δ/h", "energy balance"])
    align = ["---", "---"] + ["---:"] * (2*len(FACES_PULLS) + 3)
    return lambda raw: markdown_table(header, align, rows, raw)


# the long pulls of the exit-state decks (the continuum's pull.dat kept
# beside its exit state) and the pulls they are read at (h)
LONG_PULL_DECKS = ["exit_fig9c_beadA_steel_free", "exit_fig9d_beadB_steel_free"]
LONG_PULLS = [2.0, 8.0, 16.0, 24.0, 32.0]


def gen_long_pull(ctx):
    """docs/validation.md: the exit-state decks (free edges pulled 36h and
    48h) as shipped (the current faces) and with &tools contact_faces =
    'reference': restraining
    force and lift over the kept default-mesh continuum's
    (docs/validation/continuum/<deck>/pull.dat) at LONG_PULLS h, linear in
    the pull."""
    run_many(ctx.program, faces_jobs(LONG_PULL_DECKS, "long"), ctx.tmp, ctx.workers)
    rows = []
    for deck in LONG_PULL_DECKS:
        cpull = os.path.join(ROOT, "docs", "validation", "continuum", deck, "pull.dat")
        for faces in ("reference", "current"):
            ppull = os.path.join(ctx.tmp, f"long_{deck}_{faces}", "pull.dat")
            ratios = []
            for column in (3, 8):
                for delta in LONG_PULLS:
                    ratios.append(Num(quotient(pull_value_at(ppull, column, delta),
                                               pull_value_at(cpull, column, delta)), ".3f"))
            rows.append([deck, faces] + ratios)
    header = (["deck", "faces"] + [f"N / continuum at {d:g}h" for d in LONG_PULLS]
              + [f"lift / continuum at {d:g}h" for d in LONG_PULLS])
    align = ["---", "---"] + ["---:"] * (2*len(LONG_PULLS))
    return lambda raw: markdown_table(header, align, rows, raw)


def gen_neck_cost(ctx):
    """docs/performance.md: the clamped steel continuum-check decks stopped
    at the tearing point, on their uniform mesh (refine_exit = .false.), on
    the default path (refine_exit, theory 7.6) and with refine_neck
    (neck_decks), 1 and 2 threads, three runs each, scripts/bench.sh
    --markdown --no-scaling, verbatim."""
    default = stopped_decks(ctx, "default_cost_decks", NECK_DECKS)
    uniform = []
    for deck in default:
        copy = deck[:-4] + "_uniform.nml"
        with open(deck) as src, open(copy, "w") as out:
            out.write(src.read().replace("\n&sheet\n", "\n&sheet\n   refine_exit = .false.\n", 1))
        uniform.append(copy)
    decks = [d for triple in zip(uniform, default, neck_decks(ctx, "neck_cost_decks")) for d in triple]
    out = script_output(ctx, ["scripts/bench.sh", "--markdown", "-n", "3", "--no-scaling",
                              "--keep", os.path.join(ctx.tmp, "neck_cost")] + decks)
    return lambda raw: out


# issue 25's cost target: the default path (refine_exit, theory 7.6) at
# most 1.5 times the uniform run of the commit before it
COST_BASE_COMMIT = "3df1877"
COST_DECKS = NECK_DECKS + ["input/cc_beadA_aluminium.nml", "input/cc_beadB_aluminium.nml",
                           "input/cc_beadB_hss.nml", "input/cc_beadA_hss.nml"]


def cost_base_binary(ctx):
    """The binary of commit COST_BASE_COMMIT, built once per run of this
    script from the repository's history (git archive, make) in ctx.tmp."""
    base = os.path.join(ctx.tmp, "cost_base")
    base_bin = os.path.join(base, "bin", "drawbead")
    if not os.path.exists(base_bin):
        os.makedirs(base, exist_ok=True)
        archive = subprocess.run(["git", "archive", COST_BASE_COMMIT], cwd=ROOT, stdout=subprocess.PIPE,
                                 check=True)
        subprocess.run(["tar", "-x", "-C", base], input=archive.stdout, check=True)
        subprocess.run(["make", "-s", "all"], cwd=base, stdout=subprocess.DEVNULL, check=True)
    return base_bin


def load_average():
    """The machine's 1, 5 and 15 minute load averages, as text."""
    with open("/proc/loadavg", encoding="utf-8") as f:
        return " ".join(f.read().split()[:3])


def bench_row(ctx, binary, deck, threads, runs, keep):
    """(median wall s, assemblies, status) of DECK by scripts/bench.sh --bin
    BINARY with THREADS threads and RUNS runs, the runs kept under KEEP
    (KEEP/<deck>/t<threads>/run<k>)."""
    out = script_output(ctx, ["scripts/bench.sh", "--bin", binary, "-n", str(runs), "--threads", str(threads),
                              "--no-scaling", "--keep", keep, deck])
    name = os.path.basename(deck)[:-4]
    for line in out.splitlines():
        w = line.split()
        if w and w[0] == name:
            return float(w[2]), int(w[8]), w[12]
    raise RuntimeError(f"scripts/bench.sh printed no row for {name}")


def phase_iterations(run):
    """Newton iterations (failed attempts included: column 4 of lock.dat and
    pull.dat, since commit 4244918) of a run while locking, while pulling up
    to its tearing point (tearing_delta_over_h; all of the pull without
    one) and past it.  Not in them: a split's re-equilibration, and the
    failed attempts that end a run without convergence."""
    h = real(read_summary(os.path.join(run, "summary.txt")), "tearing_delta_over_h")
    counts = [0, 0, 0]
    for name, k in (("lock.dat", 0), ("pull.dat", 1)):
        path = os.path.join(run, name)
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("#") or not line.strip():
                    continue
                w = line.split()
                past = k == 1 and h is not None and float(w[0]) > h
                counts[2 if past else k] += int(float(w[3]))
    return counts


def gen_default_path_cost(ctx):
    """docs/performance.md: the default path's wall time against the uniform
    run of commit COST_BASE_COMMIT (before refine_exit), whose binary is
    built here from the repository's history (git archive, make): the
    clamped continuum-check decks stopped at tearing and
    input/double_bead.nml, scripts/bench.sh --bin on each binary, five runs,
    2 threads and 1, the two binaries one after the other deck by deck (so
    that both see the same load); medians, assemblies and their ratio; and
    the default path's Newton iterations by phase (phase_iterations) and
    in its splits' re-equilibration (the rest of summary.txt's)."""
    base_bin = cost_base_binary(ctx)
    decks = stopped_decks(ctx, "default_path_cost_decks", COST_DECKS) + ["input/double_bead.nml"]
    probe = script_output(ctx, ["scripts/bench.sh", "--bin", ctx.program, "-n", "1", "--threads", "1",
                                "--no-scaling", "input/fig7b_beadA_steel_mu0.nml"])
    machine = next(ln[2:] for ln in probe.splitlines() if ln.startswith("# host:")).split(", load average")[0]
    load_before = load_average()
    rows, phases = [], []
    keep_base, keep_now = os.path.join(ctx.tmp, "cost_runs_base"), os.path.join(ctx.tmp, "cost_runs_now")
    for threads in (2, 1):
        for deck in decks:
            tb, ab, _ = bench_row(ctx, base_bin, deck, threads, 5, keep_base)
            td, ad, status = bench_row(ctx, ctx.program, deck, threads, 5, keep_now)
            name = os.path.basename(deck)[:-4]
            rows.append([name, threads, Num(tb, ".3f"), ab, Num(td, ".3f"), ad,
                         Num(td / tb, ".2f"), Num(ad / ab, ".2f"), status])
            if threads == 1:
                run = os.path.join(keep_now, name, "t1", "run1")
                pn = phase_iterations(run)
                total = int(float(read_summary(os.path.join(run, "summary.txt"))["newton_iterations"]))
                phases.append([name] + pn + [total - sum(pn), total])
    header = ["deck", "threads", f"uniform ({COST_BASE_COMMIT}), s", "assemblies", "default path, s",
              "assemblies", "time ratio", "assemblies ratio", "status"]
    align = ["---", "---:", "---:", "---:", "---:", "---:", "---:", "---:", "---"]
    pheader = ["deck", "locking", "pulling to the tearing point", "pulling past it (to its confirmation)",
               "in no row (the splits' re-equilibration)", "in all"]

    load_after = load_average()
    host = (f"{machine}, load average {load_before} before the runs, {load_after} after them"
            f" (their own included), {time.strftime('%Y-%m-%d %H:%M')}")

    def text(raw):
        return "\n".join([f"<!-- {host} -->", "", markdown_table(header, align, rows, raw), "",
                          "The default path's Newton iterations (failed attempts included), one thread:", "",
                          markdown_table(pheader, ["---"] + ["---:"] * 5, phases, raw)])
    return text


# the decks of input/ that other_decks_cost times: all but the clamped
# continuum-check decks of COST_DECKS and the double bead (the default
# path's own table) and the decks COST_BASE_COMMIT does not read
OTHER_COST_RUNS = 11


def interleaved_times(runs, jobs, outdir):
    """Wall seconds of each (binary, deck) job of JOBS run RUNS times, one
    thread, the jobs taking turns run by run (so that all see the same
    load); {job index: [seconds]} and each job's last exit status."""
    times = {k: [] for k in range(len(jobs))}
    status = {}
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for _ in range(runs):
        for k, (binary, deck) in enumerate(jobs):
            start = time.perf_counter()
            status[k] = subprocess.call([binary, deck, "--output", os.path.join(outdir, f"job{k}")], cwd=ROOT,
                                        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times[k].append(time.perf_counter() - start)
    return times, status


def gen_other_decks_cost(ctx):
    """docs/performance.md: every deck of input/ but the clamped ones of
    COST_DECKS and the double bead, one thread, this version against
    COST_BASE_COMMIT's binary (built as default_path_cost builds it), the
    two taking turns run by run, OTHER_COST_RUNS runs each: medians, their
    ratio, assemblies and status of each; a deck the old binary does not
    read (its variables are newer) is left out, and said so."""
    base_bin = cost_base_binary(ctx)
    skip = set(COST_DECKS) | {"input/double_bead.nml"}
    decks = sorted(os.path.join("input", f) for f in os.listdir(os.path.join(ROOT, "input"))
                   if f.endswith(".nml") and os.path.join("input", f) not in skip)
    load_before = load_average()
    rows, unread = [], []
    odir = os.path.join(ctx.tmp, "other_cost")
    os.makedirs(odir, exist_ok=True)
    for deck in decks:
        name = os.path.basename(deck)[:-4]
        # a deck the old binary does not read writes no summary: one probe
        # run, not the interleaved seven
        os.makedirs(os.path.join(odir, name), exist_ok=True)
        run_deck(base_bin, deck, os.path.join(odir, name), "probe", True)
        if not os.path.exists(os.path.join(odir, name, "probe", "summary.txt")):
            unread.append(name)
            continue
        times, status = interleaved_times(OTHER_COST_RUNS, [(base_bin, deck), (ctx.program, deck)],
                                          os.path.join(odir, name))
        # (a run that stops early with a non-zero status keeps its summary:
        # its row says so in its status column)
        for k, who in ((0, COST_BASE_COMMIT), (1, "this version")):
            if not os.path.exists(os.path.join(odir, name, f"job{k}", "summary.txt")):
                raise RuntimeError(f"{deck}: {who} wrote no summary.txt (exit status {status[k]})")
        sb = read_summary(os.path.join(odir, name, "job0", "summary.txt"))
        sn = read_summary(os.path.join(odir, name, "job1", "summary.txt"))
        mb, mn = statistics.median(times[0]), statistics.median(times[1])
        rows.append([name, Num(mb, ".3f"), sb.get("assemblies", "none"), sb.get("status", "none"),
                     Num(mn, ".3f"), sn.get("assemblies", "none"), sn.get("status", "none"), Num(mn / mb, ".2f")])
    load_after = load_average()
    host = (f"host: load average {load_before} before the runs, {load_after} after them (their own included),"
            f" {time.strftime('%Y-%m-%d %H:%M')}")
    header = ["deck", f"{COST_BASE_COMMIT}, s", "assemblies", "status", "this version, s", "assemblies", "status",
              "time ratio"]

    def text(raw):
        lines = [f"<!-- {host} -->", "", markdown_table(header, ["---"] + ["---:"] * 2 + ["---"] + ["---:"] * 2
                                                          + ["---", "---:"], rows, raw)]
        if unread:
            lines += ["", f"Not read by {COST_BASE_COMMIT} (newer variables): " + ", ".join(unread) + "."]
        return "\n".join(lines)
    return text


def gen_bead_cards(ctx):
    """docs/user-guide.md: the worked example of an equivalent bead: a
    lock_depth sweep of fig9c, scripts/bead_curves.sh on it, its
    bead_table.txt as a table and the cards of drawbead.k and
    drawbead_radioss.rad (without their comment lines)."""
    sweep = os.path.join(ctx.tmp, "sweep_a")
    script_output(ctx, ["scripts/sweep.sh", "--bin", ctx.program, "-j", str(ctx.workers), "-o", sweep,
                        "input/fig9c_beadA_steel_free.nml", "lock_depth=1,2,3,4,4.6"])
    script_output(ctx, ["scripts/bead_curves.sh", "--bin", ctx.program, "-j", str(ctx.workers), sweep])
    out = os.path.join(sweep, "bead_curves")
    with open(os.path.join(out, "bead_table.txt"), encoding="utf-8") as f:
        table = [[float(x) for x in ln.split()] for ln in f if ln.strip() and not ln.startswith("#")]
    rows = [[Num(r[0], ".1f"), Num(r[1], ".2f"), Num(r[2], ".2f"), Num(r[3], ".2f"), Num(r[4], ".2f"),
             Num(r[5], ".3f")] for r in table]
    header = ["penetration (mm)", "total (N/mm)", "bending (N/mm)", "friction part (N/mm)",
              "lift (N/mm)", "effective friction coefficient"]

    def cards(name, first):
        with open(os.path.join(out, name), encoding="utf-8") as f:
            lines = [ln.rstrip("\n") for ln in f]
        start = next(i for i, ln in enumerate(lines) if ln.startswith(first))
        return lines[start:]
    k = cards("drawbead.k", "*PARAMETER")
    rad = cards("drawbead_radioss.rad", "/INTER/TYPE8")

    def text(raw):
        return "\n".join([markdown_table(header, ["---:"] * 6, rows, raw), "",
                          "`drawbead.k` from `*PARAMETER` on (above it, the comments say where the numbers come from and what to fill in):", "",
                          "```"] + k + ["```", "", "`drawbead_radioss.rad` from `/INTER/TYPE8` on:", "",
                                        "```"] + rad + ["```"])
    return text


def gen_ccx_combined_element(ctx):
    """docs/continuum-check.md: tests/ccx_combined_element.sh (CalculiX's
    combined hardening in one element against its closed form, and the laws
    the cross-check refuses), verbatim; needs ccx."""
    text = verbatim_block(ctx, ["bash", "tests/ccx_combined_element.sh", ctx.program],
                          "tests/ccx_combined_element.sh")
    return lambda raw: text


def gen_neck_bifurcation(ctx):
    """docs/theory.md: scripts/neck_bifurcation.py (the long-wave neck of a
    plane-strain strip against the expansion (12.10)), verbatim."""
    text = verbatim_block(ctx, ["python3", "scripts/neck_bifurcation.py"], "scripts/neck_bifurcation.py")
    return lambda raw: text


# the lift traced tool by tool: the decks and the program variants compared
LIFT_TRACE_OPTIONS = ["--offset", "0.05", "--also", "normal_stress=none", "--also", "n_elements=240",
                      "--also", "contact_faces=reference"]
# (deck, options): the profile beads kept with --at 0.5,1,2 (their lift
# departs after 1h; the stepped bead's continuum with --contact-slope 1e4);
# --offset needs a rectangular bead
LIFT_TRACE_CASES = [("cc_fig5a_beadA_steel", LIFT_TRACE_OPTIONS), ("cc_fig6_beadB_steel", LIFT_TRACE_OPTIONS),
                    ("cc_round_bead", ["--at", "0.5,1,2", "--also", "normal_stress=none"]),
                    ("cc_stepped_bead", ["--at", "0.5,1,2", "--also", "normal_stress=none"]),
                    # the free edge: its lift at full lock is the binder faces' squeeze,
                    # which the contact stiffness sets
                    ("cc_fig9c_beadA_steel_free", ["--at", "0.5,1,2", "--offset", "0.05", "--also", "normal_stress=none",
                                                   "--also", "contact_faces=reference", "--also", "penalty=0.01",
                                                   "--also", "penalty=0.2"]),
                    # ... against its continuum with the contact slope 1e4 (kept apart)
                    ("cc_fig9c_beadA_steel_free", ["--at", "0.5,1,2"], "lift_trace_slope1e4"),
                    # ... and with the binder gap that leaves it unsqueezed
                    ("cc_fig9c_beadA_steel_free_gap", ["--at", "0.5,1,2", "--also", "contact_faces=reference",
                                                       "--also", "n_elements=320", "--also", "penalty=0.2"])]


def quoted_runs(ctx, runs, work):
    """The verbatim outputs of the study scripts' command lines RUNS (each
    (args, scratch name); the program and an output folder under ctx.tmp
    WORK/<scratch name> are added), each after its command line (quoted
    as a shell needs it), as one code block."""
    parts = []
    for args, scratch in runs:
        out = script_output(ctx, args[:1] + ["-o", os.path.join(ctx.tmp, work, scratch),
                                             "--bin", ctx.program] + args[1:])
        parts.append("$ " + shlex.join(args) + "\n" + out)
    return "```\n" + "\n\n".join(parts) + "\n```"


def kept_continuum_runs(ctx, script, cases, kept_flag, kept_path, work):
    """quoted_runs of SCRIPT on each (deck, options) of CASES against the
    continuum results kept under docs/validation/continuum/ (KEPT_FLAG
    KEPT_PATH formatted with the deck; no CalculiX run); WORK names the
    scratch folder."""
    runs = []
    for case in cases:
        # (deck, options) or (deck, options, the kept folder in place of
        # KEPT_PATH's last part)
        deck, options = case[:2]
        kept = kept_path.format(deck=deck)
        scratch = deck
        if len(case) > 2:
            kept = os.path.join(os.path.dirname(kept), case[2])
            scratch = deck + "_" + case[2]
        runs.append(([script, f"input/{deck}.nml", kept_flag, kept] + options, scratch))
    return quoted_runs(ctx, runs, work)


def gen_lift_trace(ctx):
    """docs/validation.md: scripts/lift_trace.sh on the clamped steel beads A
    and B, the round and stepped profile beads and the free-edge bead A against the continuum runs kept in
    docs/validation/continuum/<deck>/lift_trace/ (no CalculiX run), verbatim."""
    text = kept_continuum_runs(ctx, "scripts/lift_trace.sh", LIFT_TRACE_CASES, "--ccx",
                               "docs/validation/continuum/{deck}/lift_trace", "lift")
    return lambda raw: text

# the sheet leaving the bead against the continuum: the decks (their kept
# continuum exit states in docs/validation/continuum/<deck>/exit_state.txt),
# each with its variants (the mesh doubled, the paper's section, the tools
# moved toward the sheet)
# the continuum's contact stiffness: its slope, 1e5 MPa/mm, is 0.37 E/h
# for this steel; at that penalty the first increment of locking converges
# with the penalty's onset smoothed over 0.001h
EXIT_STATE_STIFF = "penalty=0.37 contact_smoothing=0.001"
EXIT_STATE_CASES = [
    ("exit_fig9c_beadA_steel_free", ["--also", "n_elements=424", "--also", "normal_stress=none",
                                     "--also", "penalty=0.1", "--also", EXIT_STATE_STIFF,
                                     "--offset", "0.05"]),
    ("exit_fig9d_beadB_steel_free", ["--also", "n_elements=448", "--also", "normal_stress=none",
                                     "--also", "penalty=0.1", "--also", EXIT_STATE_STIFF,
                                     "--offset", "0.05"]),
]


def gen_exit_state(ctx):
    """docs/validation.md: scripts/exit_state_check.sh on the free-edge
    exit-state decks against the continuum's exit states kept in
    docs/validation/continuum/<deck>/exit_state.txt (no CalculiX run),
    verbatim."""
    text = kept_continuum_runs(ctx, "scripts/exit_state_check.sh",
                               EXIT_STATE_CASES, "--continuum",
                               "docs/validation/continuum/{deck}/exit_state.txt", "exit_state")
    return lambda raw: text


# the continuum's mesh and contact-slope study of bead B's exit state: a 12h
# pull of the exit-state deck, its continuum with 4 and 8 elements per h and
# with the contact slope 1e4 kept beside it
EXIT_MESH_DECK = "docs/validation/continuum/mesh_study/exit_fig9d_beadB_steel_free_pull12h.nml"
# (the scratch folder's name, the kept exit state, the program's variants)
EXIT_MESH_KEPT = [("perh4", "docs/validation/continuum/mesh_study/exit_fig9d_pull12h_perh4.txt",
                   ["--also", "penalty=0.1"]),
                  ("perh8", "docs/validation/continuum/mesh_study/exit_fig9d_pull12h_perh8.txt", []),
                  ("slope1e4", "docs/validation/continuum/mesh_study/exit_fig9d_pull12h_slope1e4.txt",
                   ["--also", "penalty=0.1"])]


def gen_exit_state_mesh(ctx):
    """docs/validation.md: scripts/exit_state_check.sh on EXIT_MESH_DECK against
    its continuum exit states with 4 and 8 elements per h along the sheet and
    with the contact slope 1e4 (EXIT_MESH_KEPT; no CalculiX run), verbatim."""
    text = quoted_runs(ctx, [(["scripts/exit_state_check.sh", EXIT_MESH_DECK, "--continuum", kept] + variants, name)
                             for name, kept, variants in EXIT_MESH_KEPT], "exit_mesh")
    return lambda raw: text


# ---------------------------------------------------------------------------
# What the laws change (docs/validation.md): the clamped and free beads A and
# B with the published material sets and a pressure-dependent friction
# ---------------------------------------------------------------------------

# The bases: the continuum-check decks of beads A and B (clamped, free), and
# the paper's free bead B, each run with the contact section and stopped at
# its tearing point (stop_at_localization = .true.; the paper's deck of the
# free bead B with the defaults' section and criterion).
LAWS_BASES = [("A clamped", "input/cc_fig5a_beadA_steel.nml"),
              ("B clamped", "input/cc_fig6_beadB_steel.nml"),
              ("A free", "input/cc_fig9c_beadA_steel_free.nml"),
              ("B free", "input/fig9d_beadB_steel_free.nml")]

# Yoshida and Uemori (2002), Fig. 7: their IH+NLK model (Voce isotropic part
# Y + Rsat (1 - exp(-m p)), one Armstrong-Frederick back stress
# dalpha = C ((2/3) a dep - alpha dp)), E0 of their Table 1; in the deck's
# terms kinematic_c = C a, kinematic_gamma = C.  nu = 0.3 (not given).
LAWS_SPCC = dict(E=206000.0, y=120.0, q=166.0, b=8.4, c=390.0 * 43.0, g=390.0)
LAWS_SPFC = dict(E=206000.0, y=410.0, q=157.0, b=16.0, c=70.0 * 144.0, g=70.0)
# Vegter and van den Boogaard (2006), Table 2: an IF (deep-drawing) steel.
LAWS_R0, LAWS_R90 = 1.85, 2.51
# mu(p): a round set of the power law's form (no published parameter set
# found): 0.1 at 10 MPa, m = 0.8, within [0.05, 0.2].
LAWS_MU_P = ("   friction_law = 'power', friction_p_ref = 10.0, friction_m = 0.8\n"
             "   friction_mu_min = 0.05, friction_mu_max = 0.2\n")


def laws_material(m, kinematic=True, r=None):
    """The &material group of a published set (m: LAWS_SPCC or LAWS_SPFC)."""
    lines = ["&material"]
    lines.append("   model = 'combined'" if kinematic or r else "   model = 'j2'")
    lines += [f"   youngs_modulus = {m['E']}", "   poissons_ratio = 0.3", "   hardening = 'voce'",
              f"   voce_sigma0 = {m['y']}, voce_q = {m['q']}, voce_b = {m['b']}"]
    if kinematic:
        lines += [f"   kinematic_c = {m['c']}", f"   kinematic_gamma = {m['g']}"]
    if r:
        lines += [f"   r0 = {LAWS_R0}, r90 = {LAWS_R90}", f"   drawing_direction = '{r}'"]
    return "\n".join(lines + ["/"])


def laws_monotonic(m, name):
    """&material of an isotropic law with the combined set's monotonic
    curve, Y + Rsat (1 - exp(-m p)) + (C/gamma) (1 - exp(-gamma p)), as a
    curve file (hardening = 'table', written into the run folder at
    gen_laws_table's start): the same curve in tension, no Bauschinger
    effect."""
    return ("&material\n   model = 'j2'\n   youngs_modulus = %s\n   poissons_ratio = 0.3\n"
            "   hardening = 'table'\n   curve_file = '{TMP}/%s.curve'\n/" % (m['E'], name))


def laws_curve_text(m):
    """The curve file of laws_monotonic: 0 to 2 in plastic strain, steps
    of 1/(20 gamma) where the back stress saturates, then of 0.01."""
    ps = [k / (20.0 * m['g']) for k in range(0, 200)]
    ps += [ps[-1] + 0.01 * k for k in range(1, int((2.0 - ps[-1]) / 0.01) + 1)]
    lines = ["# plastic strain, flow stress (MPa): the monotonic curve of a combined set"]
    for p in ps:
        sy = m['y'] + m['q'] * (1 - math.exp(-m['b'] * p)) + m['c'] / m['g'] * (1 - math.exp(-m['g'] * p))
        lines.append("%.8f %.6f" % (p, sy))
    return "\n".join(lines) + "\n"


LAWS_VARIANTS = [
    ("DQSK isotropic, Coulomb (the deck)", None, False),
    ("DQSK isotropic, mu(p)", None, True),
    ("SPCC isotropic part", laws_material(LAWS_SPCC, kinematic=False), False),
    ("SPCC isotropic, combined's monotonic curve", laws_monotonic(LAWS_SPCC, "spcc"), False),
    ("SPCC combined", laws_material(LAWS_SPCC), False),
    ("SPCC combined, r0/r90 rolling", laws_material(LAWS_SPCC, r="rolling"), False),
    ("SPCC combined, r0/r90 transverse", laws_material(LAWS_SPCC, r="transverse"), False),
    ("DP590 isotropic part", laws_material(LAWS_SPFC, kinematic=False), False),
    ("DP590 isotropic, combined's monotonic curve", laws_monotonic(LAWS_SPFC, "spfc"), False),
    ("DP590 combined", laws_material(LAWS_SPFC), False),
]


def laws_deck(base_path, material, mu_p):
    """The text of a study deck: the base deck stopped at its tearing point,
    with the contact section, its &material replaced and mu(p) added."""
    with open(os.path.join(ROOT, base_path), encoding="utf-8") as f:
        text = f.read()
    text = text.replace("stop_at_localization = .false.", "stop_at_localization = .true.")
    text = re.sub(r"\n\s*tearing_criterion = 'section'", "", text)
    text = re.sub(r"\n\s*normal_stress = 'none'", "", text)
    if material:
        text = re.sub(r"&material.*?\n/", lambda _: material, text, count=1, flags=re.S)
    if mu_p:
        text = text.replace("&tools\n", "&tools\n" + LAWS_MU_P, 1)
    return text


def laws_metrics(run_dir, log_path, summary):
    """The numbers of a run: punch force at 98% of the lock depth (lock.dat),
    the largest restraining force, its pull and the lift there (pull.dat),
    the peak mid-surface strain after locking (strain_lock.dat), the
    tearing point (summary.txt)."""
    def rows(name):
        path = os.path.join(run_dir, name)
        if not os.path.exists(path):
            return []
        with open(path, encoding="utf-8") as f:
            return [[float(x) for x in ln.split()] for ln in f if ln.strip() and not ln.startswith("#")]
    resolved = {}
    with open(log_path, encoding="utf-8") as f:
        for ln in f:
            m = re.match(r"\s*(LOCK_DEPTH|THICKNESS)=\s*([-+0-9.Ee]+)", ln)
            if m:
                resolved[m.group(1)] = float(m.group(2))
    full = resolved["LOCK_DEPTH"] / resolved["THICKNESS"]
    lock, pull, strain = rows("lock.dat"), rows("pull.dat"), rows("strain_lock.dat")
    f98 = None
    for a, b in zip(lock, lock[1:]):
        if a[0] <= 0.98 * full <= b[0]:
            f98 = a[2] + (b[2] - a[2]) * (0.98 * full - a[0]) / (b[0] - a[0])
    n_max = d_max = lift = None
    if pull:
        k = max(range(len(pull)), key=lambda i: pull[i][2])
        n_max, d_max, lift = pull[k][2], pull[k][0], pull[k][7]
    peak = max(r[3] for r in strain) if strain and lock and lock[-1][0] >= full * (1 - 1e-9) else None
    if real(summary, "tearing_delta_over_h") is not None:
        tear = "Δ = %.2fh" % real(summary, "tearing_delta_over_h")
    elif real(summary, "tearing_lock_over_h") is not None:
        tear = "lock, H = %.2fh" % real(summary, "tearing_lock_over_h")
    else:
        tear = "none"
    return f98, n_max, d_max, lift, peak, tear


def gen_laws_table(ctx):
    """docs/validation.md: the beads of LAWS_BASES with each of
    LAWS_VARIANTS (decks written by laws_deck into the run folder), side
    by side."""
    jobs, names = [], []
    for name, m in (("spcc", LAWS_SPCC), ("spfc", LAWS_SPFC)):
        with open(os.path.join(ctx.tmp, name + ".curve"), "w", encoding="utf-8") as f:
            f.write(laws_curve_text(m))
    for bi, (bead, base) in enumerate(LAWS_BASES):
        for vi, (variant, material, mu_p) in enumerate(LAWS_VARIANTS):
            name = f"laws_{bi}_{vi}"
            if material:
                material = material.replace("{TMP}", ctx.tmp)
            jobs.append((name, laws_deck(base, material, mu_p)))
            names.append((name, bead, variant))
    res = run_many(ctx.program, jobs, ctx.tmp, ctx.workers)
    rows = []
    for name, bead, variant in names:
        s = res[name]
        f98, n_max, d_max, lift, peak, tear = laws_metrics(
            os.path.join(ctx.tmp, name), os.path.join(ctx.tmp, name + ".log"), s)
        rows.append([bead, variant, s["status"], Num(f98, ".1f"), Num(n_max, ".1f"), Num(d_max, ".2f"),
                     Num(lift, ".1f"), Num(peak, ".4f"), tear])
    header = ["bead", "law", "status", "punch force at 98% of full lock (N/mm)",
              "largest restraining force (N/mm)", "at Δ/h", "lift there (N/mm)",
              "peak strain after locking", "tearing"]
    align = ["---", "---", "---"] + ["---:"] * 5 + ["---"]
    return lambda raw: markdown_table(header, align, rows, raw)


LAWS_BEAD_LAWS = [("DQSK isotropic, Coulomb", None, False),
                  ("DQSK isotropic, mu(p)", None, True),
                  ("SPCC combined", laws_material(LAWS_SPCC), False)]


def gen_laws_bead_curves(ctx):
    """docs/validation.md: scripts/sweep.sh over lock_depth = 2, 3, 4 mm of
    the free bead A (input/cc_fig9c_beadA_steel_free.nml as laws_deck writes
    it) with each of LAWS_BEAD_LAWS, scripts/bead_curves.sh on each sweep,
    their bead_table.txt side by side."""
    tables = []
    for li, (law, material, mu_p) in enumerate(LAWS_BEAD_LAWS):
        base = os.path.join(ctx.tmp, f"laws_bead_{li}.nml")
        with open(base, "w", encoding="utf-8") as f:
            f.write(laws_deck("input/cc_fig9c_beadA_steel_free.nml", material, mu_p))
        sweep = os.path.join(ctx.tmp, f"laws_sweep_{li}")
        script_output(ctx, ["scripts/sweep.sh", "--bin", ctx.program, "-j", str(ctx.workers), "-o", sweep,
                            base, "lock_depth=2,3,4"])
        script_output(ctx, ["scripts/bead_curves.sh", "--bin", ctx.program, "-j", str(ctx.workers), sweep])
        with open(os.path.join(sweep, "bead_curves", "bead_table.txt"), encoding="utf-8") as f:
            tables.append([[float(x) for x in ln.split()] for ln in f
                           if ln.strip() and not ln.startswith("#")])
    rows = []
    for k, r in enumerate(tables[0]):
        for (law, _, _), t in zip(LAWS_BEAD_LAWS, tables):
            row = next((x for x in t if abs(x[0] - r[0]) < 1e-9), None)
            rows.append([Num(r[0], ".1f"), law] + ([Num(row[i], ".1f") for i in (1, 2, 3, 4)]
                                                  + [Num(row[5], ".3f")] if row else ["none"] * 5))
    header = ["penetration (mm)", "law", "total (N/mm)", "bending (N/mm)", "friction part (N/mm)",
              "lift (N/mm)", "effective friction coefficient"]
    return lambda raw: markdown_table(header, ["---:", "---"] + ["---:"] * 5, rows, raw)

GENERATORS = {
    "readme_example": ("README.md", gen_readme_example, "bin/drawbead on input/fig5a_beadA_steel.nml"),
    "paper_table": ("docs/validation.md", gen_paper_table, "every input/fig*.nml and strip_tension.nml"),
    "step_study": ("docs/validation.md", gen_step_study,
                   "scripts/convergence.sh -s on every input/fig*.nml and input/cc_*.nml"),
    "paper_criterion_steps": ("docs/validation.md", gen_paper_criterion_steps,
                              "scripts/convergence.sh -s to 1/8 of the increments on fig5a, and its indicator"),
    "convergence": ("docs/validation.md", gen_convergence, "scripts/convergence.sh -m on fig5a, fig9c"),
    "convergence_shipped": ("docs/validation.md", gen_convergence_shipped,
                            "scripts/convergence.sh -m -n \"96 192 384\" on fig9c"),
    "tearing_convergence": ("docs/validation.md", gen_tearing_convergence,
                            "scripts/convergence.sh -m -n \"80 160 320 640\" on the clamped cc_ steel decks, uniform"),
    "continuum_table": ("docs/validation.md", gen_continuum_table,
                        "scripts/validation_table.sh: the cc_ cases kept under docs/validation/continuum/"
                        " against the program with both sections"),
    "tearing_default": ("docs/validation.md", gen_tearing_default,
                        "scripts/convergence.sh -m and -s on the clamped cc_ decks stopped at tearing (refine_exit)"),
    "tearing_friction": ("docs/validation.md", gen_tearing_friction,
                         "cc_fig5a with friction 0, 0.05, 0.1 and 0.2 stopped at tearing on 80, 160, 640 elements"
                         " against the kept continuum necks"),
    "unseen_cases": ("docs/validation.md", gen_unseen_cases,
                     "the cases beyond the tables (docs/validation/continuum/decks/unseen_*) against their kept"
                     " continuum checks; convergence.sh -m and -s stopped at tearing"),
    "tearing_flatness": ("docs/validation.md", gen_tearing_flatness,
                         "the clamped cc_ decks, the double bead and the other continuum-checked necks stopped"
                         " at tearing: how flat each model's restraining force is at the other's maximum"),
    "stainless_early": ("docs/validation.md", gen_stainless_early,
                        "the stainless-like sheet on bead C pulled 4.8h against its kept continuum run"),
    "tearing_step_sweep": ("docs/validation.md", gen_tearing_step_sweep,
                           "scripts/convergence.sh -s -f \"1 0.5 0.25 0.125\" on cc_fig5a stopped at tearing"),
    "neck_element_study": ("docs/theory.md", gen_neck_element_study,
                           "the clamped cc_ decks, the double bead and the other continuum-checked necks stopped"
                           " at tearing on 40, 80 and 160 uniform elements and with refine_neck"),
    "strain_gradient_study": ("docs/theory.md", gen_strain_gradient_study,
                              "the clamped cc_ decks and the double bead stopped at tearing,"
                              " strain_gradient x 0.25 to 2, against the continuum's neck"),
    "tearing_neck": ("docs/validation.md", gen_tearing_neck,
                     "scripts/convergence.sh -m -n \"80 160 320 640\" on the clamped cc_ steel decks with refine_neck"),
    "tearing_neck_steps": ("docs/validation.md", gen_tearing_neck_steps,
                           "scripts/convergence.sh -s on the clamped cc_ steel decks with refine_neck"),
    "tearing_neck_zone": ("docs/validation.md", gen_tearing_neck_zone,
                          "scripts/convergence.sh -m on the clamped cc_ steel decks with refine_neck,"
                          " zone elements 0.16h halved twice"),
    "contact_cost": ("docs/performance.md", gen_contact_cost,
                     "scripts/bench.sh on every input/fig*.nml and its copy with the contact section"
                     " (not checkable)"),
    "neck_cost": ("docs/performance.md", gen_neck_cost,
                  "scripts/bench.sh on the clamped cc_ steel decks stopped at tearing: uniform, default path, refine_neck"
                  " (not checkable)"),
    "default_path_cost": ("docs/performance.md", gen_default_path_cost,
                          f"scripts/bench.sh on the clamped cc_ decks stopped at tearing and double_bead,"
                          f" this version against {COST_BASE_COMMIT}'s uniform run (not checkable)"),
    "other_decks_cost": ("docs/performance.md", gen_other_decks_cost,
                         f"every other deck of input/, one thread, this version against {COST_BASE_COMMIT}'s"
                         " binary, interleaved runs (not checkable)"),
    "laws_cost": ("docs/performance.md", gen_laws_cost,
                  "scripts/bench.sh on cc_fig5a with the J2 law, combined hardening with and without"
                  " back stresses, and mu(p) (not checkable)"),
    "long_pull": ("docs/validation.md", gen_long_pull,
                  "the exit-state decks' long pulls with the tools on the reference and on the current faces"),
    "contact_faces": ("docs/validation.md", gen_contact_faces,
                      "the continuum-check decks with the tools on the reference and on the current faces"),
    "laws_yielding": ("docs/performance.md", gen_laws_yielding,
                      "the yielding points per assembly of the laws' cost decks on 80 elements"),
    "bead_cards": ("docs/user-guide.md", gen_bead_cards,
                   "scripts/sweep.sh over lock_depth on fig9c and scripts/bead_curves.sh on it"),
    "neck_bifurcation": ("docs/theory.md", gen_neck_bifurcation,
                         "scripts/neck_bifurcation.py: the plane-strain strip's long-wave neck against (12.10)"),
    "ccx_combined_element": ("docs/continuum-check.md", gen_ccx_combined_element,
                             "tests/ccx_combined_element.sh: CalculiX's combined hardening in one element"),
    "lift_trace": ("docs/validation.md", gen_lift_trace,
                   ("scripts/lift_trace.sh on the clamped steel beads, the round and stepped beads "
                    "and the free-edge bead A with and without its binder gap against their kept continuum runs")),
    "exit_state": ("docs/validation.md", gen_exit_state,
                   "scripts/exit_state_check.sh on the free-edge exit-state decks against their kept continuum exit states"),
    "exit_state_mesh": ("docs/validation.md", gen_exit_state_mesh,
                        "scripts/exit_state_check.sh on bead B's exit-state deck pulled 12h against its"
                        " continuum with 4 and 8 elements per h and with the contact slope 1e4 (kept)"),
    "laws_table": ("docs/validation.md", gen_laws_table,
                   "the cc_ beads A and B, clamped and free, and fig9d, with published hardening sets and mu(p)"),
    "laws_bead_curves": ("docs/validation.md", gen_laws_bead_curves,
                         "scripts/sweep.sh over lock_depth and scripts/bead_curves.sh on the free bead A with three laws"),
    "bench": ("docs/performance.md", gen_bench, "scripts/bench.sh --markdown -n 5: 1 and 2 threads, scaling (not checkable)"),
}
UNCHECKABLE = {"bench", "contact_cost", "neck_cost", "laws_cost", "default_path_cost", "other_decks_cost"}


# ---------------------------------------------------------------------------
# Blocks in the documents
# ---------------------------------------------------------------------------

def block_span(text, name):
    """(start, end) of the body of block name in text, or None."""
    begin = f"<!-- BEGIN {MARK} {name} -->\n"
    end = f"<!-- END {MARK} {name} -->"
    i = text.find(begin)
    if i < 0:
        return None
    j = text.find(end, i)
    if j < 0:
        return None
    return i + len(begin), j


NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def tokens(text):
    return [t for t in re.split(r"[\s|`]+", text) if t]


def shown_step(token):
    """Half a unit in the last digit a number token shows."""
    mant, _, exp = token.lower().lstrip("+-").partition("e")
    decimals = len(mant.split(".", 1)[1]) if "." in mant else 0
    return 0.5 * 10.0 ** (-decimals + (int(exp) if exp else 0))


def compare(doc, fresh_shown, fresh_raw):
    """Differences between a document block and the regenerated one."""
    a, b, c = tokens(doc), tokens(fresh_shown), tokens(fresh_raw)
    problems = []
    if len(a) != len(b) or len(b) != len(c):
        return [f"the block has {len(a)} fields, the program's {len(b)}"]
    for t_doc, t_new, t_raw in zip(a, b, c):
        core_doc, core_raw = t_doc.rstrip("%"), t_raw.rstrip("%")
        if NUMBER.match(core_doc) and NUMBER.match(core_raw):
            # half a unit of the last digit shown against the full value; a
            # whole unit against a script's own rounded output
            value, step = float(core_raw), shown_step(core_doc)
            if t_new == t_raw:
                step *= 2.0
            if not math.isfinite(value) or abs(float(core_doc) - value) > step * (1 + 1e-9) + 1e-300:
                problems.append(f"{t_doc} in the document, the program gives {t_new} ({t_raw})")
        elif t_doc != t_new:
            problems.append(f"'{t_doc}' in the document, '{t_new}' from the program")
    return problems


def read_doc(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def check_links():
    """Links, images, block markers and the README's size."""
    problems = []
    headings = {}
    for doc in DOCS:
        slugs = set()
        in_code = False
        for line in read_doc(doc).splitlines():
            if line.startswith("```"):
                in_code = not in_code
            if not in_code and line.startswith("#"):
                title = line.lstrip("#").strip().lower()
                title = re.sub(r"[^\w\- ]", "", title.replace("`", ""))
                slugs.add(title.replace(" ", "-"))
        headings[doc] = slugs
    for doc in DOCS:
        text = read_doc(doc)
        body = re.sub(r"```.*?```", "", text, flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", body):
            if re.match(r"^[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
            if not os.path.exists(os.path.join(ROOT, full)):
                problems.append(f"{doc}: link to {target}: no such file {full}")
            elif anchor and full.endswith(".md") and anchor not in headings.get(full, set()):
                problems.append(f"{doc}: link to {target}: no heading #{anchor} in {full}")
        for name in re.findall(rf"<!-- BEGIN {re.escape(MARK)} (\S+) -->", text):
            if name not in GENERATORS:
                problems.append(f"{doc}: block {name}: no such block in {MARK}")
            elif GENERATORS[name][0] != doc:
                problems.append(f"{doc}: block {name} belongs in {GENERATORS[name][0]}")
            elif block_span(text, name) is None:
                problems.append(f"{doc}: block {name} is not closed")
    size = os.path.getsize(os.path.join(ROOT, "README.md"))
    if size > README_LIMIT:
        problems.append(f"README.md: {size} bytes, more than {README_LIMIT}")
    return problems


class Context:
    def __init__(self, program, workers, tmp):
        self.program, self.workers, self.tmp = program, workers, tmp


def main(argv):
    program = os.environ.get("DRAWBEAD") or os.path.join(ROOT, "bin", "drawbead")
    workers = 2
    check = False
    names = []
    args = list(argv)
    while args:
        a = args.pop(0)
        if a in ("-h", "--help"):
            print(__doc__)
            return 0
        if a == "--bin" and args:
            program = os.path.abspath(args.pop(0))
        elif a == "-j" and args:
            workers = int(args.pop(0))
        elif a == "--check":
            check = True
        elif a == "--check-links":
            problems = check_links()
            for p in problems:
                print(f"doc_tables.py: {p}", file=sys.stderr)
            return 1 if problems else 0
        elif a == "--list":
            for name, (doc, _, what) in GENERATORS.items():
                print(f"{name:20s} {doc:22s} {what}")
            return 0
        elif a.startswith("-"):
            print(f"doc_tables.py: unknown option {a} (see --help)", file=sys.stderr)
            return 2
        else:
            names.append(a)
    if names == ["all"]:
        names = list(GENERATORS)
    unknown = [n for n in names if n not in GENERATORS]
    if not names or unknown:
        print(f"doc_tables.py: give block names ({', '.join(GENERATORS)}) or all"
              + (f"; unknown: {' '.join(unknown)}" if unknown else ""), file=sys.stderr)
        return 2
    if not os.access(program, os.X_OK):
        print(f"doc_tables.py: {program} is not an executable program (make first)",
              file=sys.stderr)
        return 2

    failed = False
    with tempfile.TemporaryDirectory(prefix="doc_tables.") as tmp:
        ctx = Context(program, workers, tmp)
        for name in names:
            doc, gen, _ = GENERATORS[name]
            if check and name in UNCHECKABLE:
                print(f"skip: {name} (timings: regenerate with scripts/doc_tables.py {name})")
                continue
            text = read_doc(doc)
            span = block_span(text, name)
            if span is None:
                print(f"doc_tables.py: {doc} has no block {name}", file=sys.stderr)
                failed = True
                continue
            try:
                render = gen(ctx)
            except RuntimeError as err:
                print(f"doc_tables.py: {name}: {err}", file=sys.stderr)
                failed = True
                continue
            shown = render(False)
            if check:
                problems = compare(text[span[0]:span[1]], shown, render(True))
                for p in problems:
                    print(f"doc_tables.py: {doc}, block {name}: {p}", file=sys.stderr)
                print(f"{'FAILED' if problems else 'ok'}: {name} ({doc})")
                failed = failed or bool(problems)
            else:
                text = text[:span[0]] + shown + "\n" + text[span[1]:]
                with open(os.path.join(ROOT, doc), "w", encoding="utf-8") as f:
                    f.write(text)
                print(f"written: {name} ({doc})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
