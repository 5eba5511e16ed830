#!/usr/bin/env python3
"""f90deps.py -- write make dependencies between Fortran objects.

Purpose
    Read free-form Fortran sources, find the modules each one defines
    (``module <name>``, ``submodule (<ancestor>[:<parent>]) <name>``) and the
    modules each one uses (``use <name>``, ``use <name>, only: ...``,
    ``use :: <name>``, ``use, non_intrinsic :: <name>``; ``use, intrinsic ::``
    is skipped), and write one make rule per source::

        <objdir>/a.o: <objdir>/b.o <objdir>/c.o

    meaning "a.f90 needs the .mod files that compiling b.f90 and c.f90
    writes".  Modules that no listed source defines (iso_fortran_env,
    library modules, ...) are ignored.

Inputs
    --objdir DIR   directory that holds the objects (default: build)
    -o FILE        output file (default: stdout); written atomically and only
                   when its content changes
    sources        the .f90 files

Outputs
    The rules, plus ``DEPS_SRCS := <sources>`` so that the Makefile can see
    when the set of sources has changed and regenerate the file.

Python 3 standard library only.
"""

import argparse
import os
import re
import sys

USE_RE = re.compile(
    r"^use\b\s*(?:,\s*(?P<nature>intrinsic|non_intrinsic)\s*)?(?:::)?\s*"
    r"(?P<name>[a-z_]\w*)",
    re.IGNORECASE,
)
MODULE_RE = re.compile(r"^module\s+(?P<name>[a-z_]\w*)\s*$", re.IGNORECASE)
SUBMODULE_RE = re.compile(
    r"^submodule\s*\(\s*(?P<ancestor>[a-z_]\w*)\s*(?::\s*(?P<parent>[a-z_]\w*)\s*)?\)"
    r"\s*(?P<name>[a-z_]\w*)\s*$",
    re.IGNORECASE,
)
# "module procedure foo" and friends are not module definitions
NOT_MODULE_NAMES = {"procedure", "function", "subroutine"}


def strip_comment(line):
    """Return line without its trailing ``!`` comment (quotes respected)."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None  # a doubled quote re-opens at the next char
        elif ch in ("'", '"'):
            quote = ch
        elif ch == "!":
            return line[:i]
    return line


def split_statements(text):
    """Yield the statements of free-form source: continuations joined,
    comments removed, ``;``-separated statements split."""
    pending = ""
    for raw in text.splitlines():
        line = strip_comment(raw).strip()
        if pending and not line:
            continue  # comment or blank line between continuation lines
        if pending and line.startswith("&"):
            line = line[1:].lstrip()
        if line.endswith("&"):
            pending += line[:-1] + " "
            continue
        line = pending + line
        pending = ""
        for stmt in split_semicolons(line):
            stmt = stmt.strip()
            if stmt:
                yield stmt
    if pending.strip():
        yield pending.strip()


def split_semicolons(line):
    """Split a line at ``;`` outside character constants."""
    parts, quote, start = [], None, 0
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in ("'", '"'):
            quote = ch
        elif ch == ";":
            parts.append(line[start:i])
            start = i + 1
    parts.append(line[start:])
    return parts


def scan(path):
    """Return (defined, used) module-name sets of one source file.

    For a submodule, ``defined`` gets ``ancestor:name`` (what a child
    submodule names as its parent) and ``used`` gets the parent it extends.
    """
    defined, used = set(), set()
    with open(path, encoding="utf-8", errors="replace") as handle:
        text = handle.read()
    for stmt in split_statements(text):
        match = MODULE_RE.match(stmt)
        if match and match.group("name").lower() not in NOT_MODULE_NAMES:
            defined.add(match.group("name").lower())
            continue
        match = SUBMODULE_RE.match(stmt)
        if match:
            ancestor = match.group("ancestor").lower()
            parent = match.group("parent")
            defined.add(ancestor + ":" + match.group("name").lower())
            used.add(ancestor + ":" + parent.lower() if parent else ancestor)
            continue
        match = USE_RE.match(stmt)
        if match and (match.group("nature") or "").lower() != "intrinsic":
            used.add(match.group("name").lower())
    return defined, used


def object_name(objdir, path):
    base = os.path.splitext(os.path.basename(path))[0]
    return objdir.rstrip("/") + "/" + base + ".o" if objdir else base + ".o"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--objdir", default="build")
    parser.add_argument("-o", "--output")
    parser.add_argument("sources", nargs="*")
    args = parser.parse_args(argv)

    provider = {}
    uses = {}
    status = 0
    for src in args.sources:
        defined, used = scan(src)
        uses[src] = used
        for mod in defined:
            if mod in provider and provider[mod] != src:
                sys.stderr.write(
                    "f90deps.py: module '%s' is defined in both %s and %s\n"
                    % (mod, provider[mod], src)
                )
                status = 1
            provider.setdefault(mod, src)

    if status:
        return status  # leave the old file alone: make stops here

    lines = [
        "# Generated by scripts/f90deps.py -- do not edit.",
        "DEPS_SRCS := " + " ".join(args.sources),
    ]
    for src in args.sources:
        deps = sorted(
            {object_name(args.objdir, provider[m]) for m in uses[src] if m in provider}
            - {object_name(args.objdir, src)}
        )
        if deps:
            lines.append(object_name(args.objdir, src) + ": " + " ".join(deps))
    text = "\n".join(lines) + "\n"

    if not args.output:
        sys.stdout.write(text)
        return 0
    try:
        with open(args.output, encoding="utf-8") as handle:
            if handle.read() == text:
                os.utime(args.output)  # up to date: just refresh the time
                return 0
    except OSError:
        pass
    tmp = args.output + ".tmp"
    with open(tmp, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(tmp, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
