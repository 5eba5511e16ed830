# drawbead -- build and test (GNU make >= 4.0; see README.md)
#
#   make                 build bin/drawbead (release flags) in build/
#   make -j2 test        build, run the .pf suites and the tests/*.sh scripts
#   make check-build     build bin/drawbead-check in build-check/ (checked flags)
#   make test-check      run the whole test suite with the checked build
#   make run [DECK=...]  run bin/drawbead on $(DECK)
#   make UMAT=my_umat.f90  build bin/drawbead with a user's material routine
#   make valgrind [DECK=...]  build bin/drawbead-generic in build-generic/
#                        (ARCH_FLAGS empty) and run $(DECK) under valgrind
#   make clean           remove build/, build-check/, bin/ and out/
#   OMP_NUM_THREADS=n bin/drawbead ...  run the assembly on n threads (default 1)
#   make help            list the targets and variables
#
# Variables (override on the command line): FC, FFLAGS, ARCH_FLAGS, OPENMP_FLAGS, CHECK_FFLAGS,
# LDFLAGS, LDLIBS, DECK, PFUNIT_DIR (a pFUnit 4 install: the folder holding
# include/PFUNIT.mk; without it the tests use tests/pfunit_lite.py), UMAT,
# UMAT_FFLAGS.

# make's built-in FC is f77 (origin "default"; "undefined" under make -R)
ifneq (,$(filter default undefined,$(origin FC)))
FC := gfortran
endif
AR ?= ar
PYTHON ?= python3

# Release code generation: the material loops of a section are vectorized
# (libmvec's pow and log; -fno-trapping-math lets gfortran if-convert them),
# -ffpe-summary=none: if-converted code evaluates both branches, so a flag
# such as division by zero is raised for lanes whose result is discarded
# (penalty_energy's d^3/(6 delta) with delta = 0), and gfortran's note of
# the flags at the end of every run would report nothing wrong; the
# checked build traps real ones (-ffpe-trap), and the program checks its
# residuals for NaN.  Automatic arrays live on the stack, and ARCH_FLAGS picks the vector width
# of the build machine.  Give ARCH_FLAGS= for a binary that runs on any
# machine of the architecture (e.g. a cluster whose nodes differ).
# -flto inlines across modules (one module per concern puts the hardening
# law, the distance helpers and their callers in different files: without
# it fig9d took 4% longer).  -O3: the element's and the section's small
# fixed-size loops unrolled and inlined; measured on one thread against
# the same source at -O2 (interleaved runs, fastest user time): fig5a,
# fig6 and fig7d 5-7% faster, the J2 law's per assembly on the laws' cost
# deck too, the combined law's unchanged; the regression decks within
# their tolerance (1e-6; 3e-10 at most, as at -O2).
#
# OPENMP_FLAGS: the assembly runs its elements on OMP_NUM_THREADS threads
# (one if it is unset; the results do not depend on the number:
# docs/performance.md); it is
# part of the release and checked flags and of the link.  Give
# OPENMP_FLAGS= for a serial program.  An FFLAGS of your own needs
# -fopenmp in it for threads.
ARCH_FLAGS ?= -march=native
OPENMP_FLAGS ?= -fopenmp
RELEASE_FFLAGS := -std=f2008 -fimplicit-none -Wall -Wextra -Wimplicit-interface -O3 -g \
                  -fvect-cost-model=dynamic -fno-trapping-math -ffpe-summary=none -fstack-arrays \
                  -flto=auto $(ARCH_FLAGS) \
                  $(OPENMP_FLAGS)
CHECK_FFLAGS ?= -std=f2008 -fimplicit-none -Wall -Wextra -Wimplicit-interface \
                -O0 -g -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace \
                -finit-real=snan $(OPENMP_FLAGS)
FFLAGS ?= $(RELEASE_FFLAGS)
LDFLAGS ?= $(OPENMP_FLAGS)
LDLIBS ?= -llapack -lblas
DECK ?= input/fig5a_beadA_steel.nml

# Where this build goes; check-build and test-check re-run make with
# BUILD=build-check BIN=bin/drawbead-check FFLAGS=$(CHECK_FFLAGS).
BUILD ?= build
BIN ?= bin/drawbead

# ---------------------------------------------------------------------------
# Sources: every src/*.f90 goes into the library except the main program
# ---------------------------------------------------------------------------
MAIN_SRC := src/drawbead.f90
ALL_SRCS := $(sort $(wildcard src/*.f90))
LIB_SRCS := $(filter-out $(MAIN_SRC),$(ALL_SRCS))
LIB_OBJS := $(patsubst src/%.f90,$(BUILD)/%.o,$(LIB_SRCS))
MAIN_OBJ := $(BUILD)/drawbead.o
LIB := $(BUILD)/libdrawbead.a
DEPS := $(BUILD)/deps.mk

# The material routine umat (module law_umat) is an external subroutine,
# linked with the program and kept out of the library: UMAT=path names a
# user's file (compiled with UMAT_FFLAGS, e.g. for a fixed-form, implicitly
# typed Abaqus routine) linked with src/user/umat_linked.f90
# (user_umat_linked() = .true.); without it src/user/umat_none.f90 is
# linked (umat an error path, user_umat_linked() = .false.).  The test
# runner links the example input/umat_linear_hardening.f90.
UMAT ?=
UMAT_FFLAGS ?= $(FFLAGS)
UMAT_DIR := $(BUILD)/user
UMAT_STAMP := $(UMAT_DIR)/umat_path.txt
UMAT_EXAMPLE := input/umat_linear_hardening.f90
ifneq (,$(strip $(UMAT)))
BIN_UMAT_OBJS := $(UMAT_DIR)/user_umat.o $(UMAT_DIR)/umat_linked.o
else
BIN_UMAT_OBJS := $(UMAT_DIR)/umat_none.o
endif
TEST_UMAT_OBJS := $(UMAT_DIR)/umat_example.o $(UMAT_DIR)/umat_linked.o

# Tests: the .pf suites (tests/unit: one per module; tests/verification:
# problem-level checks), compiled without -std=f2008 and with long lines;
# the shell tests (tests/*.sh, tests/regression/*.sh) run the program.
PF_DIRS := tests/unit tests/verification
PF_SRCS := $(sort $(wildcard $(addsuffix /test_*.pf,$(PF_DIRS))))
TEST_SCRIPTS := $(sort $(wildcard tests/*.sh tests/regression/*.sh))
TEST_DIR := $(BUILD)/tests
TEST_FFLAGS = $(filter-out -std=%,$(FFLAGS)) -ffree-line-length-none

# Goals that need no generated makefiles in $(BUILD) (the checked goals
# re-run make with BUILD=build-check, which does generate them there)
NO_DEPS_GOALS := clean help check-build test-check generic-build valgrind
NEED_DEPS := $(filter-out $(NO_DEPS_GOALS),$(or $(MAKECMDGOALS),all))

.PHONY: all release lib check-build test test-check generic-build valgrind run clean help FORCE
.DELETE_ON_ERROR:

all: $(BIN)

release: all

lib: $(LIB)

# ---------------------------------------------------------------------------
# Library and program
# ---------------------------------------------------------------------------
# $(FLAGS_STAMP) holds the compiler and flags of the last build here; it is
# rewritten (and everything recompiled) when they change.
FLAGS_STAMP := $(BUILD)/flags.txt
ifneq (,$(NEED_DEPS))
$(shell mkdir -p $(BUILD) && { echo '$(FC) $(FFLAGS)' | cmp -s - $(FLAGS_STAMP) || echo '$(FC) $(FFLAGS)' > $(FLAGS_STAMP); })
endif

$(FLAGS_STAMP):
	@mkdir -p $(@D)
	echo '$(FC) $(FFLAGS)' > $@

$(BUILD)/%.o: src/%.f90 $(FLAGS_STAMP)
	$(FC) $(FFLAGS) -J $(BUILD) -c -o $@ $<

# An object whose module file is missing (an interrupted build, two makes
# at once in one tree, a deleted .mod) is removed before make decides
# anything, so that it is rebuilt with its module: else every object that
# uses the module fails with "Cannot open module file" until make clean
# (every src/ file but the main program holds one module named like it).
ifneq (,$(NEED_DEPS))
ORPHAN_OBJS := $(strip $(foreach o,$(wildcard $(LIB_OBJS)),$(if $(wildcard $(o:.o=.mod)),,$(o))))
ifneq (,$(ORPHAN_OBJS))
$(info make: $(notdir $(ORPHAN_OBJS:.o=.mod)) missing: $(notdir $(ORPHAN_OBJS)) rebuilt)
$(shell rm -f $(ORPHAN_OBJS))
endif
endif

# Rebuilt from scratch so that objects of deleted sources do not linger;
# $(DEPS) changes whenever the list of sources does.
$(LIB): $(LIB_OBJS) $(DEPS)
	rm -f $@
	$(AR) rcs $@ $(LIB_OBJS)

ifneq (,$(wildcard $(MAIN_SRC)))
$(BIN): $(MAIN_OBJ) $(LIB) $(BIN_UMAT_OBJS) $(UMAT_STAMP)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) $(LDFLAGS) -o $@ $(MAIN_OBJ) $(BIN_UMAT_OBJS) $(LIB) $(LDLIBS)
TEST_NEEDS_BIN := $(BIN)
else
$(BIN):
	@echo "make: $(MAIN_SRC) (the main program) does not exist yet" >&2; exit 1
TEST_NEEDS_BIN :=
endif

# The external umat files (they may use the library's modules, e.g. kinds;
# a module of their own goes to $(UMAT_DIR)).  $(UMAT_STAMP) holds the
# UMAT path (and flags) of the last build, so that another UMAT= relinks
# the program.
ifneq (,$(NEED_DEPS))
$(shell mkdir -p $(UMAT_DIR) && { echo '$(UMAT) $(UMAT_FFLAGS)' | cmp -s - $(UMAT_STAMP) || echo '$(UMAT) $(UMAT_FFLAGS)' > $(UMAT_STAMP); })
endif

$(UMAT_STAMP):
	@mkdir -p $(@D)
	echo '$(UMAT) $(UMAT_FFLAGS)' > $@

$(UMAT_DIR)/%.o: src/user/%.f90 $(BUILD)/kinds.o $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) -I $(BUILD) -J $(UMAT_DIR) -c -o $@ $<

# umat_none reports its error through module errors
$(UMAT_DIR)/umat_none.o: $(BUILD)/errors.o

$(UMAT_DIR)/umat_example.o: $(UMAT_EXAMPLE) $(BUILD)/kinds.o $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(FC) $(FFLAGS) -I $(BUILD) -J $(UMAT_DIR) -c -o $@ $<

ifneq (,$(strip $(UMAT)))
$(UMAT_DIR)/user_umat.o: $(UMAT) $(UMAT_STAMP) $(BUILD)/kinds.o $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(FC) $(UMAT_FFLAGS) -I $(BUILD) -J $(UMAT_DIR) -c -o $@ $<
endif

# Module dependencies (object -> object) from Debian's makedepf90 (it
# misses `use :: mod`: write `use mod, only: ...`).  deps.mk records the
# source list it was made from; a changed list (file added or removed)
# forces it to be regenerated.
$(DEPS): $(ALL_SRCS)
	@mkdir -p $(@D)
	{ makedepf90 -b $(BUILD) $(ALL_SRCS) && echo 'DEPS_SRCS := $(ALL_SRCS)'; } > $@.tmp
	mv $@.tmp $@

ifneq (,$(NEED_DEPS))
include $(DEPS)
ifneq ($(strip $(DEPS_SRCS)),$(strip $(ALL_SRCS)))
$(DEPS): FORCE
endif
endif

FORCE:

# ---------------------------------------------------------------------------
# Tests
# ---------------------------------------------------------------------------
ifneq (,$(strip $(PFUNIT_DIR)))
# Real pFUnit: tests/Makefile runs inside $(BUILD)/pfunit (it finds the .pf
# files through vpath) and links $(BUILD)/pfunit/drawbead_tests.
RUNNER := $(BUILD)/pfunit/drawbead_tests

$(RUNNER): $(LIB) $(TEST_UMAT_OBJS) FORCE
	@mkdir -p $(BUILD)/pfunit
	$(MAKE) -C $(BUILD)/pfunit -f $(CURDIR)/tests/Makefile drawbead_tests \
	    PFUNIT_DIR='$(abspath $(PFUNIT_DIR))' TESTS_DIR='$(CURDIR)/tests' \
	    FC='$(FC)' PF_FFLAGS='$(TEST_FFLAGS) -I$(abspath $(BUILD))' \
	    DRAWBEAD_LIB='$(abspath $(LIB))' LDLIBS='$(LDLIBS) $(LDFLAGS)' \
	    UMAT_OBJS='$(abspath $(TEST_UMAT_OBJS))'
else
# pfunit_lite: tests/test_X.pf -> $(TEST_DIR)/test_X.f90, plus a driver
# $(TEST_DIR)/run_tests.f90 and the funit module of tests/funit_lite.f90.
LITE := tests/pfunit_lite.py
vpath %.pf $(PF_DIRS)
PF_F90 := $(patsubst %.pf,$(TEST_DIR)/%.f90,$(notdir $(PF_SRCS)))
PF_OBJS := $(PF_F90:.f90=.o)
RUNNER := $(TEST_DIR)/run_tests
PF_LIST := $(TEST_DIR)/pf_list.txt

# a file holding the list of suites, rewritten only when the list changes,
# so that adding or removing a .pf file regenerates the driver
ifneq (,$(NEED_DEPS))
$(shell mkdir -p $(TEST_DIR) && { echo '$(PF_SRCS)' | cmp -s - $(PF_LIST) || echo '$(PF_SRCS)' > $(PF_LIST); })
endif

$(PF_LIST):
	@mkdir -p $(@D)
	echo '$(PF_SRCS)' > $@

$(TEST_DIR)/%.f90: %.pf $(LITE)
	$(PYTHON) $(LITE) convert $< $@

$(TEST_DIR)/funit.o: tests/funit_lite.f90 $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(FC) $(TEST_FFLAGS) -J $(TEST_DIR) -c -o $@ $<

$(PF_OBJS): $(TEST_DIR)/%.o: $(TEST_DIR)/%.f90 $(TEST_DIR)/funit.o $(LIB)
	$(FC) $(TEST_FFLAGS) -I $(BUILD) -J $(TEST_DIR) -c -o $@ $<

$(TEST_DIR)/run_tests.f90: $(PF_SRCS) $(PF_LIST) $(LITE)
	$(PYTHON) $(LITE) driver $@ $(PF_SRCS)

$(TEST_DIR)/run_tests.o: $(TEST_DIR)/run_tests.f90 $(PF_OBJS) $(TEST_DIR)/funit.o
	$(FC) $(TEST_FFLAGS) -J $(TEST_DIR) -c -o $@ $<

$(RUNNER): $(TEST_DIR)/run_tests.o $(PF_OBJS) $(TEST_DIR)/funit.o $(LIB) $(TEST_UMAT_OBJS)
	$(FC) $(TEST_FFLAGS) $(LDFLAGS) -o $@ $(TEST_DIR)/run_tests.o $(PF_OBJS) \
	    $(TEST_DIR)/funit.o $(TEST_UMAT_OBJS) $(LIB) $(LDLIBS)
endif

# Runs every suite, then every tests/*.sh (with bash, from the top directory;
# the program's absolute path is both the first argument and $DRAWBEAD);
# fails if anything fails.  The suites' tests of warnings make the program
# print *WARNING* lines on purpose: they go to $(RUNNER_WARNINGS), and the
# log says how many (all of the runner's stderr is shown when it fails).
RUNNER_WARNINGS := $(BUILD)/tests/expected_warnings.txt
test: $(RUNNER) $(TEST_NEEDS_BIN)
	@status=0; \
	echo "== $(RUNNER)"; \
	mkdir -p $(dir $(RUNNER_WARNINGS)); \
	if DRAWBEAD='$(abspath $(BIN))' $(RUNNER) 2>$(RUNNER_WARNINGS); then \
	    echo "($$(grep -c '^\*WARNING\*' $(RUNNER_WARNINGS)) *WARNING* lines of tests that warn on purpose, expected: $(RUNNER_WARNINGS))"; \
	    grep -v '^\*WARNING\*' $(RUNNER_WARNINGS) >&2; \
	else \
	    status=1; cat $(RUNNER_WARNINGS) >&2; \
	fi; \
	for script in $(TEST_SCRIPTS); do \
	    echo "== bash $$script"; \
	    if DRAWBEAD='$(abspath $(BIN))' bash "$$script" '$(abspath $(BIN))'; then \
	        echo "ok: $$script"; \
	    else \
	        echo "FAILED: $$script"; status=1; \
	    fi; \
	done; \
	if [ $$status -ne 0 ]; then echo "make test: FAILURES (see above)"; fi; \
	exit $$status

# ---------------------------------------------------------------------------
# Checked build: the same rules, another build directory and flags
# ---------------------------------------------------------------------------
CHECK_VARS = BUILD=build-check BIN=bin/drawbead-check FFLAGS='$(CHECK_FFLAGS)'

check-build:
	$(MAKE) $(CHECK_VARS) all

test-check:
	$(MAKE) $(CHECK_VARS) test

# ---------------------------------------------------------------------------
# Memory checking: valgrind (3.19) stops with SIGILL on the AVX-512
# instructions of a -march=native build, so `make valgrind` builds a generic
# binary (release flags, ARCH_FLAGS empty) in build-generic/ and runs $(DECK)
# under valgrind into out/valgrind/; exit status 99 on any memory error or
# leak.  tests/valgrind.sh does the same on a small deck in make test.
# ---------------------------------------------------------------------------
GENERIC_VARS = BUILD=build-generic BIN=bin/drawbead-generic ARCH_FLAGS=
VALGRIND ?= valgrind
VALGRIND_FLAGS ?= --error-exitcode=99 --leak-check=full

generic-build:
	$(MAKE) $(GENERIC_VARS) all

# One OpenMP thread: libgomp's pool thread is never joined and would count
# as a possible leak.
valgrind: generic-build
	OMP_NUM_THREADS=1 $(VALGRIND) $(VALGRIND_FLAGS) bin/drawbead-generic -o out/valgrind $(DECK)

# ---------------------------------------------------------------------------
run: $(BIN)
	$(BIN) $(DECK)

clean:
	rm -rf build build-check build-generic bin out

help:
	@echo "Targets:"
	@echo "  all (default), release  build $(BIN) with FFLAGS in $(BUILD)/"
	@echo "  lib                     build $(LIB) only"
	@echo "  test                    build and run tests/{unit,verification}/test_*.pf and the tests/ scripts"
	@echo "  check-build             build bin/drawbead-check in build-check/ with CHECK_FFLAGS"
	@echo "  test-check              run the whole test suite with the checked build"
	@echo "  generic-build           build bin/drawbead-generic in build-generic/ with ARCH_FLAGS empty"
	@echo "  valgrind                run bin/drawbead-generic $(DECK) under $(VALGRIND) $(VALGRIND_FLAGS)"
	@echo "  run                     run $(BIN) $(DECK)"
	@echo "  clean                   remove build/ build-check/ build-generic/ bin/ out/"
	@echo "Variables: FC=$(FC) LDLIBS=$(LDLIBS) DECK=$(DECK) PFUNIT_DIR=$(PFUNIT_DIR)"
	@echo "  UMAT=$(UMAT) (a user's material routine, e.g. $(UMAT_EXAMPLE); empty: none)"
	@echo "  UMAT_FFLAGS=$(UMAT_FFLAGS) (flags for the UMAT file)"
	@echo "  FFLAGS=$(FFLAGS)"
	@echo "  ARCH_FLAGS=$(ARCH_FLAGS) (part of the release FFLAGS; empty: a portable binary)"
	@echo "  OPENMP_FLAGS=$(OPENMP_FLAGS) (part of FFLAGS and LDFLAGS; empty: a serial program)"
	@echo "  CHECK_FFLAGS=$(CHECK_FFLAGS)"
