# shellcheck shell=bash
# lib.sh -- the shared part of the batch scripts (scripts/*.sh and
# tests/regression/run.sh): messages and help, option checks, the build,
# running one deck, a pool of runs, reading summary.txt and naming exit
# statuses. Source it, do not run it:
#
#   # shellcheck source=scripts/lib.sh
#   source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" || exit 2
#
# Sourcing sets root (the repository top) and me (the script's file name,
# for messages). Every function is small and documented where it is
# defined; the sourcing script owns the global variables named in each
# function's comment.

# shellcheck disable=SC2034 # root, me and the exit_* names are for the sourcing script
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd) || exit 2
me=$(basename "${BASH_SOURCE[1]:-$0}")

# The program's exit statuses (src/errors.f90, README: 0 success, also
# after tearing or a localization; 1 the deck was rejected; 2 no
# convergence; 3 a result file could not be written; 4 stopped by SIGTERM
# or SIGINT; 5 out of memory)
exit_ok=0
exit_bad_input=1
exit_no_convergence=2
exit_write=3
exit_interrupted=4
exit_memory=5

# The files a run writes into its output folder (with run.log and
# exit_status, which run_deck adds); run_deck removes them before a run so
# that a failed run cannot leave stale results behind.
run_outputs=(lock.dat pull.dat strain_lock.dat strain_pull.dat tools_lock.dat tools_pull.dat
    snapshots.dat summary.txt exit_status)

# ---------------------------------------------------------------------------
# Messages and options
# ---------------------------------------------------------------------------

# note MESSAGE...: "ME: MESSAGE" on stderr
note() {
    echo "$me: $*" >&2
}

# die MESSAGE...: "ME: MESSAGE" on stderr, then exit 2 (the scripts' status
# for a usage, deck or build error)
die() {
    note "$@"
    exit 2
}

# usage: print the calling script's help, its header comment from line 2
# down to the line before the first 'set -'
usage() {
    sed -n '2,/^set -/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
}

# split_options ARGS...: the arguments in the array split_args, with every
# --option=value before a '--' split into --option value
split_options() {
    split_args=()
    while (($# > 0)); do
        if [[ $1 == -- ]]; then
            split_args+=("$@")
            return 0
        elif [[ $1 == --*=* ]]; then
            split_args+=("${1%%=*}" "${1#*=}")
        else
            split_args+=("$1")
        fi
        shift
    done
}

# need_value WHAT OPTION [VALUE...]: die "OPTION needs WHAT" unless the
# option has a value after it (pass the parser's "$@")
need_value() {
    (($# >= 3)) || die "$2 needs $1"
}

# check_count OPTION VALUE: die unless VALUE is a positive integer
check_count() {
    [[ $2 =~ ^[1-9][0-9]*$ ]] || die "$1 needs a positive integer, not '$2'"
}

# model_option OPTION VALUE: one option of the continuum model
# (scripts/continuum_model.py: --through, --per-h and --pull-steps counts,
# --initial-inc, --max-inc, --min-inc, --output-every and --contact-slope
# positive numbers), checked and appended to the caller's array model_opts
model_option() {
    case $1 in
        --through | --per-h | --pull-steps) check_count "$1" "$2" ;;
        *) [[ $2 =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]] || die "$1 needs a positive number, not '$2'" ;;
    esac
    model_opts+=("$1" "$2")
}

# variant_option OPTION VALUE: --also VAR=VALUE (one variable, or several
# separated by spaces for one variant; a value holds no comma or space) or --offset D
# (a positive number of h), checked and appended to the caller's array
# also or offsets (run_variants runs them)
variant_option() {
    case $1 in
        --also)
            [[ $2 =~ ^[a-z_][a-z0-9_]*=[^,[:space:]]+(\ +[a-z_][a-z0-9_]*=[^,[:space:]]+)*$ ]] ||
                die "--also needs VAR=VALUE, or several separated by spaces, not '$2'"
            also+=("$2")
            ;;
        *)
            [[ $2 =~ ^[0-9]*\.?[0-9]+$ ]] || die "--offset needs a positive number, not '$2'"
            offsets+=("$2")
            ;;
    esac
}

# ---------------------------------------------------------------------------
# The program
# ---------------------------------------------------------------------------

# build_program [MAKE ARGUMENTS...]: make -s in the repository (output to
# stderr); dies if the build fails
build_program() {
    note "make -s${*:+ $*}"
    make -s -C "$root" "$@" >&2 || die "the build failed"
}

# find_program BIN BUILD: set bin to the program to run, as an absolute
# path: BIN if given, else bin/drawbead of the repository, built first
# when BUILD is 1; dies if it is not executable
find_program() {
    bin=$1
    if [[ -z $bin ]]; then
        bin=$root/bin/drawbead
        if (($2)); then build_program all; fi
    fi
    [[ -x $bin ]] || die "no executable program '$bin' (build it with make)"
    [[ $bin == /* ]] || bin=$PWD/$bin
}

# ---------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------

# wait_passing_signals PID: wait for the background job PID and return its
# exit status; a SIGTERM or SIGINT to this shell meanwhile is passed on to
# it (a wait cut short by the signal waits again for the job's status)
wait_passing_signals() {
    local pid=$1 rc signalled
    # shellcheck disable=SC2064 # the pid is fixed now
    trap "signalled=1; kill -TERM $pid 2>/dev/null" TERM INT
    while :; do
        signalled=0
        wait "$pid"
        rc=$?
        ((signalled)) || break
    done
    trap - TERM INT
    return "$rc"
}

# run_deck BIN DECK DIR: run BIN on DECK into DIR, one thread (the runs of
# a batch share the machine), with stdout and stderr in DIR/run.log and
# the exit status in DIR/exit_status; removes the outputs of an earlier
# run first. A SIGTERM or SIGINT to the shell running it is passed on to
# the program, which stops at a converged increment (status interrupted,
# exit 4), and its status is still written. Returns the program's exit
# status.
run_deck() {
    local bin=$1 deck=$2 dir=$3 rc f
    mkdir -p "$dir" || return 1
    for f in "${run_outputs[@]}"; do rm -f "${dir:?}/$f"; done
    OMP_NUM_THREADS=1 "$bin" "$deck" --output "$dir" >"$dir/run.log" 2>&1 &
    wait_passing_signals $!
    rc=$?
    echo "$rc" >"$dir/exit_status"
    return "$rc"
}

# run_ccx DIR: CalculiX on DIR/continuum.inp (OMP_NUM_THREADS threads,
# default 1), its output in DIR/ccx.log, the results of an earlier run
# removed first; the start and the exit status go to the log. A SIGTERM
# or SIGINT to the shell running it is passed on to ccx (which would
# otherwise keep running after the script is gone). Returns ccx's status.
run_ccx() {
    local dir=$1 f rc start=$SECONDS
    for f in continuum.dat continuum.sta continuum.frd continuum.cvg; do rm -f "${dir:?}/$f"; done
    note "running ccx in $dir (log: ccx.log)"
    (cd "$dir" && OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} exec ccx continuum >ccx.log 2>&1) &
    wait_passing_signals $!
    rc=$?
    note "ccx exited with status $rc after $((SECONDS - start)) s"
    return "$rc"
}

# run_variants ON_RUN: the program on variants of a deck (globals bin,
# deck, dir, also, offsets, root): with each entry of also[] set, one
# VAR=VALUE or several separated by spaces ("penalty=0.37
# contact_smoothing=0.001": one variant with both), (dir/deck_also_K.nml,
# run into dir/program_also_K) and with both tools'
# centreline chains moved by each value of offsets[] (in h, toward the
# tools: lift_trace.py offset-deck, from dir/program/run.log; into
# dir/program_offset_K). Needs dir/variables.txt (bin --list-variables).
# After each run "ON_RUN LABEL RUN_DIR" compares it; a deck that cannot be
# written or a run that does not end normally stops the script.
run_variants() {
    local on_run=$1 k=0 spec off
    local -a settings
    # shellcheck disable=SC2154 # also and offsets are the caller's
    for spec in "${also[@]}"; do
        k=$((k + 1))
        rm -rf "$dir/sweep"
        read -ra settings <<<"$spec"
        python3 "$root/scripts/sweep_tool.py" decks "$dir/sweep" "$dir/variables.txt" "$deck" \
            "${settings[@]}" >/dev/null || die "cannot write the deck with $spec"
        mv "$dir/sweep/decks/case_0000.nml" "$dir/deck_also_$k.nml" && rm -rf "$dir/sweep"
        run_variant "$on_run" "also_$k" "$spec" "$spec"
    done
    k=0
    # shellcheck disable=SC2154 # the caller's
    for off in "${offsets[@]}"; do
        k=$((k + 1))
        python3 "$root/scripts/lift_trace.py" offset-deck "$dir/program/run.log" "$dir/variables.txt" \
            "$deck" "$dir/deck_offset_$k.nml" "$off" || die "cannot offset the tools by $off h"
        run_variant "$on_run" "offset_$k" "the tools offset by $off h" "tools offset by ${off}h"
    done
}

# run_variant ON_RUN NAME WHAT LABEL: run dir/deck_NAME.nml into
# dir/program_NAME ("running the program with WHAT"), stop the script if
# it does not end normally, then "ON_RUN LABEL RUN_DIR" (run_variants).
run_variant() {
    local on_run=$1 name=$2 what=$3 label=$4 rc
    note "running the program with $what into $dir/program_$name"
    run_deck "$bin" "$dir/deck_$name.nml" "$dir/program_$name"
    rc=$?
    ((rc == exit_ok)) || die "the program exited with status $rc with $what"
    "$on_run" "$label" "$dir/program_$name"
}

# run_pool JOBS ON_DONE: run_deck "$bin" pool_decks[i] pool_dirs[i] for
# every i, at most JOBS at a time (globals bin, pool_decks, pool_dirs), and
# call "ON_DONE i STATUS" in this shell as each run ends. Returns the
# number of runs that exited non-zero (at most 255). pool_stop_runs (a
# signal trap may call it) stops the runs going (run_deck passes SIGTERM
# on to the program) and starts no more; run_pool then returns once they
# have ended, and pool_stopped is 1.
pool_decks=()
pool_dirs=()
pool_stopped=0
pool_stop_runs() {
    local pid
    pool_stopped=1
    for pid in $(jobs -p); do kill -TERM "$pid" 2>/dev/null; done
}
run_pool() {
    # the locals are prefixed: ON_DONE sees them (bash scopes dynamically)
    local pool_jobs=$1 pool_done=$2 pool_total=${#pool_decks[@]} pool_next=0 pool_failed=0
    local pool_pid pool_rc pool_running
    local -A pool_index=()
    while (((!pool_stopped && pool_next < pool_total) || ${#pool_index[@]} > 0)); do
        while ((!pool_stopped && ${#pool_index[@]} < pool_jobs && pool_next < pool_total)); do
            run_deck "$bin" "${pool_decks[pool_next]}" "${pool_dirs[pool_next]}" &
            pool_index[$!]=$pool_next
            pool_next=$((pool_next + 1))
        done
        pool_running=" $(jobs -rp | tr '\n' ' ') "
        for pool_pid in "${!pool_index[@]}"; do
            [[ $pool_running == *" $pool_pid "* ]] && continue
            wait "$pool_pid"
            pool_rc=$?
            ((pool_rc == 0)) || pool_failed=$((pool_failed + 1))
            "$pool_done" "${pool_index[$pool_pid]}" "$pool_rc"
            unset "pool_index[$pool_pid]"
        done
        ((${#pool_index[@]} > 0)) && sleep 0.05
    done
    return $((pool_failed > 255 ? 255 : pool_failed))
}

# ---------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------

# summary_value FILE KEY: the value of 'KEY = value' in FILE (a
# summary.txt), blanks trimmed; prints nothing if FILE or KEY is missing
summary_value() {
    [[ -r $1 ]] || return 0
    awk -v key="$2" '
        /^#/ { next }
        { k = $0; sub(/=.*/, "", k); gsub(/^[ \t]+|[ \t]+$/, "", k) }
        k == key && index($0, "=") { v = substr($0, index($0, "=") + 1); gsub(/^[ \t]+|[ \t]+$/, "", v); print v; exit }
    ' "$1"
}

# run_status DIR: the state of a run made by run_deck, one word: the
# summary's status (completed, torn, localized, no_convergence,
# interrupted, write_failed, out_of_memory) after exit 0, 2, 3, 4 or 5;
# without a summary no_convergence, write_failed, interrupted,
# out_of_memory (exit 2, 3, 4, 5) or no_summary (exit 0); bad_input (exit
# 1), not_run (no exit_status yet) or failed_exit_N (a crash or signal)
run_status() {
    local rc s
    rc=$(cat "$1/exit_status" 2>/dev/null) || rc=''
    case $rc in
        "$exit_ok" | "$exit_no_convergence" | "$exit_write" | "$exit_interrupted" | "$exit_memory")
            s=$(summary_value "$1/summary.txt" status)
            if [[ -n $s && $s != running ]]; then
                echo "$s"
            else
                case $rc in
                    "$exit_no_convergence") echo no_convergence ;;
                    "$exit_write") echo write_failed ;;
                    "$exit_interrupted") echo interrupted ;;
                    "$exit_memory") echo out_of_memory ;;
                    *) echo no_summary ;;
                esac
            fi
            ;;
        "$exit_bad_input") echo bad_input ;;
        '') echo not_run ;;
        *) echo "failed_exit_$rc" ;;
    esac
}

# write_statuses SWEEPDIR: SWEEPDIR/status.tsv, one line "case<TAB>status"
# (run_status of SWEEPDIR/runs/<case>) per deck of SWEEPDIR/decks.txt, for
# scripts/sweep_tool.py; dies if there is no deck list
write_statuses() {
    local deck name
    [[ -r $1/decks.txt ]] || die "no $1/decks.txt: not a sweep folder"
    while read -r deck; do
        name=$(basename "$deck" .nml)
        printf '%s\t%s\n' "$name" "$(run_status "$1/runs/$name")"
    done <"$1/decks.txt" >"$1/status.tsv" || die "cannot write $1/status.tsv"
}
