#!/usr/bin/env python3
"""pfunit_lite.py -- build pFUnit .pf test suites without pFUnit.

Purpose
    Turn a pFUnit test file ``test_X.pf`` into plain Fortran that uses the
    `funit` module of tests/funit_lite.f90, and write a driver program that
    runs every test of every suite.

Usage
    pfunit_lite.py convert tests/test_X.pf build/tests/test_X.f90
    pfunit_lite.py driver build/tests/run_tests.f90 tests/test_*.pf

Inputs (the .pf subset; the same rules pFUnit enforces)
    * ``module test_X`` ... ``end module test_X``; the module name must be the
      file name; ``use funit`` inside.  Test procedures must be public.
    * ``@test`` on the line before ``subroutine name()`` (no arguments, no
      prefix such as ``pure``: pFUnit 4.14's funitproc would not see the
      test and take the next plain subroutine instead); ``@disable`` between
      ``@test`` and the subroutine disables it (pFUnit ignores
      ``@test(disable)`` and runs the test, so options of @test are
      refused); ``@before`` / ``@after`` before the set-up / tear-down
      subroutine run around every test of the module.
    * No local variable, dummy argument or procedure may take a name that
      pFUnit's ``funit`` exports (fHamcrest's ``is``, ``equal_to``, ``not``,
      ``near``, ...; pFUnit's ``Test``, ``run``, ...: the list and where it
      comes from are in tests/funit_lite.f90): see Outputs.
    * One directive per line, never continued with ``&``, nothing after the
      closing parenthesis (no trailing comment):
        @assertEqual(expected, actual [, tolerance] [, message=...])
        @assertTrue(cond [, message=...])   @assertFalse(...)
        @assertLessThan(a, b)  @assertLessThanOrEqual(a, b)
        @assertGreaterThan(a, b)  @assertGreaterThanOrEqual(a, b)
        @assertRelativelyEqual(expected, actual, tolerance)
        @assertIsNaN(x)  @assertIsFinite(x)

Outputs
    convert: the .f90 file, line for line with the .pf file (so compiler
        messages give the .pf line numbers).  ``@test``/``@disable``/
        ``@before``/``@after`` become comments; an assertion becomes
            call assertX(args, location=SourceLocation('<pf>', <line>)); if (anyExceptions()) return
        and every procedure statement (subroutine or function, interface
        bodies included) gets ``; use funit`` at its end, so that a local
        that takes a name funit exports is a compile error in that
        procedure ("Symbol 'is' ... conflicts with symbol from module
        'funit'") and not only, as with the module's own ``use funit``, a
        host name the local quietly hides.
    driver: a program that calls funit_run_test for each test (set-up and
        tear-down included), prints failures, then as its last line
        ``N passed, M failed``, and ends with ``stop 1`` if M > 0.
        Its first command-line argument, if given, runs only the tests whose
        ``suite.test`` name contains it.  The file is rewritten only when
        its content changes.
    Errors in a .pf file are reported as ``file:line: error: ...`` and the
    script exits with status 1.

Python 3 standard library only.
"""

import os
import re
import sys

ASSERTIONS = {
    name.lower(): name
    for name in (
        "assertEqual",
        "assertTrue",
        "assertFalse",
        "assertLessThan",
        "assertLessThanOrEqual",
        "assertGreaterThan",
        "assertGreaterThanOrEqual",
        "assertRelativelyEqual",
        "assertIsNaN",
        "assertIsFinite",
    )
}
# minimum and maximum number of arguments, keywords included
ARG_COUNTS = {
    "assertequal": (2, 4),
    "asserttrue": (1, 2),
    "assertfalse": (1, 2),
    "assertlessthan": (2, 3),
    "assertlessthanorequal": (2, 3),
    "assertgreaterthan": (2, 3),
    "assertgreaterthanorequal": (2, 3),
    "assertrelativelyequal": (3, 4),
    "assertisnan": (1, 2),
    "assertisfinite": (1, 2),
}

DIRECTIVE_RE = re.compile(r"^(\s*)@(\w+)(.*)$")
MODULE_RE = re.compile(r"^\s*module\s+([a-z_]\w*)\s*(!.*)?$", re.IGNORECASE)
SUBROUTINE_RE = re.compile(
    r"^\s*(?:(?:pure|impure|elemental|recursive|module)\s+)*subroutine\s+([a-z_]\w*)\s*(\(([^)]*)\))?",
    re.IGNORECASE,
)
# How pFUnit 4.14's funitproc recognises the subroutine of a @test,
# @before or @after (bin/funit/pFUnitParser.py, getSubroutineName): a line
# that does not match is not taken (a @test then silently takes the next
# plain subroutine, or none).
FUNITPROC_SUBROUTINE_RE = re.compile(
    r"^\s*subroutine\s+(\w*)\s*(\([\w\s,]*\))?\s*(!.*)*$", re.IGNORECASE
)
# The start of any procedure statement: optional prefixes (pure, elemental,
# a type such as real(dp) or character(len=*)), then subroutine or function
# and the name.
PROCEDURE_RE = re.compile(
    r"^\s*(?:(?:pure|impure|elemental|recursive|non_recursive|module)\s+"
    r"|(?:integer|real|logical|complex|character|double\s+precision|type|class)"
    r"\s*(?:\((?:[^()]|\([^()]*\))*\))?\s*)*"
    r"(?:subroutine|function)\s+[a-z_]\w*\s*(?:[(&!]|$)",
    re.IGNORECASE,
)
USE_FUNIT_RE = re.compile(
    r"^\s*use\s*(,\s*non_intrinsic\s*)?(::)?\s*funit\b", re.IGNORECASE
)
COMMENT_OR_BLANK_RE = re.compile(r"^\s*(!.*)?$")


class PfError(Exception):
    """An error in a .pf file, with its place."""

    def __init__(self, path, line, message):
        super().__init__("%s:%d: error: %s" % (path, line, message))


class Suite:
    """What the driver needs to know about one .pf file."""

    def __init__(self, path):
        self.path = path
        self.module = None
        self.tests = []  # (name, disabled)
        self.before = None
        self.after = None


def split_args(text, path, lineno):
    """Split ``text`` (what is inside the outer parentheses) at top-level
    commas; parentheses, brackets and character constants are respected."""
    args, depth, quote, start, i = [], 0, None, 0, 0
    while i < len(text):
        ch = text[i]
        if quote:
            if ch == quote:
                if i + 1 < len(text) and text[i + 1] == quote:
                    i += 1  # doubled quote inside a constant
                else:
                    quote = None
        elif ch in ("'", '"'):
            quote = ch
        elif ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
            if depth < 0:
                raise PfError(path, lineno, "unbalanced ')'")
        elif ch == "," and depth == 0:
            args.append(text[start:i].strip())
            start = i + 1
        i += 1
    if quote:
        raise PfError(path, lineno, "unterminated character constant")
    if depth:
        raise PfError(path, lineno, "unbalanced '('")
    args.append(text[start:].strip())
    if any(not a for a in args):
        raise PfError(path, lineno, "empty argument")
    return args


def parenthesised(rest, path, lineno, what):
    """``rest`` is what follows ``@name``: return the text inside the
    parentheses, checking that nothing but blanks follows them."""
    rest = rest.strip()
    if not rest.startswith("("):
        raise PfError(path, lineno, "expected '(' after @%s" % what)
    depth, quote, i = 0, None, 0
    while i < len(rest):
        ch = rest[i]
        if quote:
            if ch == quote:
                if i + 1 < len(rest) and rest[i + 1] == quote:
                    i += 1
                else:
                    quote = None
        elif ch in ("'", '"'):
            quote = ch
        elif ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                tail = rest[i + 1 :].strip()
                if tail.endswith("&") or (not tail and rest.endswith("&")):
                    raise PfError(
                        path, lineno, "@%s: '&' continuation is not allowed" % what
                    )
                if tail:
                    raise PfError(
                        path,
                        lineno,
                        "@%s: unexpected text after ')': %r "
                        "(one directive per line, no trailing comment)" % (what, tail),
                    )
                return rest[1:i]
        i += 1
    if rest.endswith("&"):
        raise PfError(path, lineno, "@%s: '&' continuation is not allowed" % what)
    raise PfError(path, lineno, "@%s: missing ')'" % what)


def fortran_string(text):
    return "'" + text.replace("'", "''") + "'"


def unquoted_index(text, char):
    """Index of the first ``char`` in ``text`` that is not inside a
    character constant (one that opens in ``text``), or -1."""
    quote = None
    for i, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None  # a doubled quote closes and reopens: same result
        elif ch in ("'", '"'):
            quote = ch
        elif ch == char:
            return i
    return -1


def split_code(line):
    """Split a free-form line into (code, comment)."""
    i = unquoted_index(line, "!")
    return (line, "") if i < 0 else (line[:i], line[i:])


def procedure_statement_ends(lines):
    """Indices of the lines on which a procedure statement (subroutine or
    function) ends: its first line, or its last continuation line."""
    ends = set()
    continued = False  # the previous line ended with '&'
    start = None
    for index, line in enumerate(lines):
        code = split_code(line)[0].rstrip()
        if not code.strip():
            continue  # comment lines do not end a continued statement
        if not continued and PROCEDURE_RE.match(code):
            start = index
        continued = code.endswith("&")
        if start is not None and not continued:
            ends.add(index)
            start = None
    return ends


def add_use_funit(line):
    """Append ``; use funit`` to the procedure statement that ends on
    ``line``: before a trailing comment, and before a ``;`` that would
    start another statement on the same line."""
    code, comment = split_code(line)
    i = unquoted_index(code, ";")
    head, tail = (code, "") if i < 0 else (code[:i], code[i:])
    text = head.rstrip() + "; use funit" + tail
    if comment:
        text += " " + comment
    return text


def next_subroutine(lines, start, path, directive, lineno, allowed=()):
    """Name of the subroutine that follows a @test/@before/@after line.
    Directives named in ``allowed`` (lower case) may come in between."""
    for j in range(start, len(lines)):
        line = lines[j]
        if COMMENT_OR_BLANK_RE.match(line):
            continue
        directive_match = DIRECTIVE_RE.match(line)
        if directive_match and directive_match.group(2).lower() in allowed:
            continue
        match = SUBROUTINE_RE.match(line)
        if not match:
            raise PfError(
                path, lineno, "@%s must be followed by a subroutine" % directive
            )
        if not FUNITPROC_SUBROUTINE_RE.match(line):
            raise PfError(
                path,
                j + 1,
                "subroutine %s: write a test, set-up or tear-down procedure's "
                "first line as 'subroutine %s()', nothing before it and "
                "nothing but a comment after it (pFUnit's funitproc does not "
                "see it otherwise)" % (match.group(1), match.group(1)),
            )
        if match.group(3) and match.group(3).strip():
            raise PfError(
                path,
                j + 1,
                "subroutine %s: test procedures take no arguments here "
                "(test cases with 'this' are not supported)" % match.group(1),
            )
        return match.group(1)
    raise PfError(path, lineno, "@%s at the end of the file" % directive)


def convert(path, location_name=None):
    """Return (fortran_text, Suite) for one .pf file."""
    with open(path, encoding="utf-8") as handle:
        lines = handle.read().splitlines()
    suite = Suite(location_name or path)
    stem = os.path.splitext(os.path.basename(path))[0]
    location_file = fortran_string(location_name or path)
    out = []
    seen = set()
    use_funit_at = procedure_statement_ends(lines)
    disable_ok = set()  # lines where @disable may stand (after a @test)
    for index, line in enumerate(lines):
        lineno = index + 1
        if suite.module is None:
            match = MODULE_RE.match(line)
            if match and match.group(1).lower() != "procedure":
                suite.module = match.group(1)
                if suite.module.lower() != stem.lower():
                    raise PfError(
                        path,
                        lineno,
                        "module '%s' must be named like its file ('%s')"
                        % (suite.module, stem),
                    )
        match = DIRECTIVE_RE.match(line)
        if not match:
            out.append(add_use_funit(line) if index in use_funit_at else line)
            continue
        indent, name, rest = match.groups()
        key = name.lower()
        if key == "test":
            if rest.strip():
                raise PfError(
                    path,
                    lineno,
                    "@test options are not supported (pFUnit ignores "
                    "@test(disable) and runs the test: write @disable on "
                    "the line after @test)",
                )
            test = next_subroutine(
                lines, index + 1, path, name, lineno, allowed=("disable",)
            )
            if test.lower() in seen:
                raise PfError(path, lineno, "test %s appears twice" % test)
            seen.add(test.lower())
            disabled = False
            for j in range(index + 1, len(lines)):
                if SUBROUTINE_RE.match(lines[j]):
                    break
                directive_match = DIRECTIVE_RE.match(lines[j])
                if directive_match and directive_match.group(2).lower() == "disable":
                    disabled = True
                    disable_ok.add(j)
            suite.tests.append((test, disabled))
            out.append(indent + "!" + line.strip())
        elif key == "disable":
            if rest.strip():
                raise PfError(path, lineno, "@disable takes no arguments")
            if index not in disable_ok:
                raise PfError(
                    path,
                    lineno,
                    "@disable must stand between @test and its subroutine "
                    "(pFUnit ignores it anywhere else)",
                )
            out.append(indent + "!" + line.strip())
        elif key in ("before", "after"):
            if rest.strip():
                raise PfError(path, lineno, "@%s takes no arguments" % name)
            proc = next_subroutine(lines, index + 1, path, name, lineno)
            if getattr(suite, key) is not None:
                raise PfError(path, lineno, "second @%s in one module" % name)
            setattr(suite, key, proc)
            out.append(indent + "!" + line.strip())
        elif key in ASSERTIONS:
            args = split_args(parenthesised(rest, path, lineno, name), path, lineno)
            low, high = ARG_COUNTS[key]
            if not low <= len(args) <= high:
                raise PfError(
                    path,
                    lineno,
                    "@%s takes %d to %d arguments, got %d"
                    % (name, low, high, len(args)),
                )
            out.append(
                "%scall %s(%s, location=SourceLocation(%s, %d)); "
                "if (anyExceptions()) return"
                % (indent, ASSERTIONS[key], ", ".join(args), location_file, lineno)
            )
        else:
            raise PfError(
                path, lineno, "@%s is not supported by pfunit_lite" % name
            )
    if suite.module is None:
        raise PfError(path, 1, "no 'module %s' found" % stem)
    if not any(USE_FUNIT_RE.match(line) for line in lines):
        raise PfError(path, 1, "module %s must 'use funit'" % suite.module)
    return "\n".join(out) + "\n", suite


def driver(suites):
    """Return the text of the driver program."""
    out = [
        "! Generated by tests/pfunit_lite.py -- do not edit.",
        "program run_tests",
        "   use funit, only: funit_run_test, funit_skip_test, funit_summary",
    ]
    calls = []
    for s_index, suite in enumerate(suites, start=1):
        renames = []
        prefix = "s%03d_" % s_index
        if suite.before:
            renames.append("%sbefore => %s" % (prefix, suite.before))
        if suite.after:
            renames.append("%safter => %s" % (prefix, suite.after))
        fixtures = ""
        if suite.before:
            fixtures += ", setup=%sbefore" % prefix
        if suite.after:
            fixtures += ", teardown=%safter" % prefix
        for t_index, (test, disabled) in enumerate(suite.tests, start=1):
            names = "%s, %s" % (fortran_string(suite.module), fortran_string(test))
            if disabled:
                calls.append("   call funit_skip_test(%s)" % names)
                continue
            local = "%st%03d" % (prefix, t_index)
            renames.append("%s => %s" % (local, test))
            calls.append(
                "   call funit_run_test(%s, %s, %s%s)"
                % (names, fortran_string(suite.path), local, fixtures)
            )
        if renames:
            out.append("   use %s, only: &" % suite.module)
            for k, rename in enumerate(renames):
                sep = ", &" if k + 1 < len(renames) else ""
                out.append("      " + rename + sep)
    out += ["   implicit none", "   integer :: n_failed", ""]
    out += calls
    out += [
        "",
        "   call funit_summary(n_failed)",
        "   if (n_failed > 0) stop 1",
        "end program run_tests",
    ]
    return "\n".join(out) + "\n"


def write_if_changed(path, text):
    try:
        with open(path, encoding="utf-8") as handle:
            if handle.read() == text:
                return
    except OSError:
        pass
    directory = os.path.dirname(path)
    if directory:
        os.makedirs(directory, exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(tmp, path)


def main(argv):
    if len(argv) == 3 and argv[0] == "convert":
        text, _ = convert(argv[1])
        write_if_changed(argv[2], text)
        os.utime(argv[2])  # newer than the .pf, for make
        return 0
    if len(argv) >= 2 and argv[0] == "driver":
        suites = [convert(path)[1] for path in argv[2:]]
        write_if_changed(argv[1], driver(suites))
        return 0
    sys.stderr.write(__doc__.split("Inputs")[0])
    return 2


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except PfError as err:
        sys.stderr.write(str(err) + "\n")
        sys.exit(1)
    except OSError as err:
        sys.stderr.write("pfunit_lite.py: %s\n" % err)
        sys.exit(1)
