#!/usr/bin/env bash
# validation_table.sh -- the table of docs/validation.md "The contact section
# against the continuum": each case kept under docs/validation/continuum/
# (the converted CalculiX results of scripts/continuum_check.sh) against the
# program on the same deck (input/<case>.nml) with the paper's section
# (normal_stress = 'none') and with the contact section ('contact').
#
# Usage: scripts/validation_table.sh [--keep DIR] [--figures DIR] [--bin PATH]
#   --bin PATH     the program to run (default bin/drawbead, built first)
#   --keep DIR     keep the program's runs under DIR (default: a temporary
#                  directory, removed at the end)
#   --figures DIR  also draw, per case, the continuum and the program with
#                  both sections together: DIR/continuum_<case>_lock.png
#                  (punch force), _pull.png (restraining force, with the
#                  contact section's run with refine_neck too) and
#                  _strain.png (mid-surface strain after locking and after
#                  pulling); needs gnuplot
# Prints a markdown table: the continuum's value and the program's two, each
# with its ratio to the continuum's, and a last row per case: the tearing
# point of the contact section with &sheet refine_neck = .true. (the neck
# resolved, docs/theory.md §7.5) against the continuum's largest
# restraining force, where the pull necks (when the force falls clearly
# after it).  The runs of a case go
# together (three at a time), one thread each.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
keep=""
figures=""
bin=""
while (($# > 0)); do
    case $1 in
        --keep) keep=${2:?--keep needs a folder}; shift 2 ;;
        --figures) figures=${2:?--figures needs a folder}; shift 2 ;;
        --bin) bin=${2:?--bin needs a program}; shift 2 ;;
        *) echo "validation_table.sh: unknown argument '$1' (usage: [--keep DIR] [--figures DIR] [--bin PATH])" >&2; exit 2 ;;
    esac
done
work=${keep:-$(mktemp -d)}
[[ -n $keep ]] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
cd "$root"
if [[ -z $bin ]]; then
    make -s >/dev/null
    bin=bin/drawbead
fi
for cdir in docs/validation/continuum/cc_*/; do
    case=$(basename "$cdir")
    deck=input/$case.nml
    [[ -f $deck ]] || { echo "validation_table.sh: no deck $deck for $cdir" >&2; exit 1; }
    for v in none contact neck; do
        out=$work/${case}_$v
        mkdir -p "$out"
        if [[ $v == neck ]]; then
            sed "s/^&sheet/\&sheet\n   normal_stress = 'contact', refine_neck = .true./" "$deck" >"$out/deck.nml"
        else
            sed "s/^&sheet/\&sheet\n   normal_stress = '$v'/" "$deck" >"$out/deck.nml"
        fi
        (
            OMP_NUM_THREADS=1 "$bin" "$out/deck.nml" -o "$out/run" >"$out/log" 2>&1 || true
            python3 scripts/continuum_model.py "$out/log" "$out/model" >/dev/null
            python3 scripts/continuum_results.py metrics "$out/run" "$out/model/continuum_model.json" \
                >"$out/metrics.txt"
        ) &
    done
    wait
    # numbers the kept continuum summary predates (the tension at 98% of
    # full lock): the same metrics from the continuum's converted files
    python3 scripts/continuum_results.py metrics "$cdir" "$work/${case}_contact/model/continuum_model.json" \
        >"$work/${case}_continuum_metrics.txt"
done
if [[ -n $figures ]]; then
    mkdir -p "$figures"
    for cdir in docs/validation/continuum/cc_*/; do
        case=$(basename "$cdir")
        none=$work/${case}_none/run
        contact=$work/${case}_contact/run
        gnuplot -c scripts/plot_lock.gp --title="$case: punch force" \
            "${cdir}lock.dat::continuum::lw 2 dt 2 lc rgb '#D55E00'" \
            "$none/lock.dat::paper section::lw 2 lc rgb '#999999'" \
            "$contact/lock.dat::contact section::lw 2 lc rgb '#0072B2'" \
            "$figures/continuum_${case}_lock.png" >/dev/null
        neck=$work/${case}_neck/run
        gnuplot -c scripts/plot_pull.gp --title="$case: restraining force" --key='bottom right' \
            "${cdir}pull.dat::continuum::lw 2 dt 2 lc rgb '#D55E00'" \
            "$none/pull.dat::paper section::lw 2 lc rgb '#999999'" \
            "$contact/pull.dat::contact section::lw 2 lc rgb '#0072B2'" \
            "$neck/pull.dat::contact section, refine_neck::lw 2 dt 3 lc rgb '#009E73'" \
            "$figures/continuum_${case}_pull.png" >/dev/null
        plots=()
        for phase in lock pull; do
            plots+=("set title 'after ${phase}ing'; plot '${cdir}strain_$phase.dat' using 1:4 with lines lw 2 dt 2 lc rgb '#D55E00' title 'continuum', '$none/strain_$phase.dat' using 1:4 with lines lw 2 lc rgb '#999999' title 'paper section', '$contact/strain_$phase.dat' using 1:4 with lines lw 2 lc rgb '#0072B2' title 'contact section'")
        done
        gnuplot -e "set terminal pngcairo size 900,800 noenhanced; set output '$figures/continuum_${case}_strain.png';
            set multiplot layout 2,1 title '$case: mid-surface strain lambda - 1';
            set xlabel 's/h'; set ylabel 'lambda - 1'; set key top left; set grid;
            ${plots[0]}; ${plots[1]}; unset multiplot"
    done
fi
python3 - "$work" <<'PY'
import glob, os, sys
work = sys.argv[1]
def read(path):
    d = {}
    for line in open(path):
        if '=' in line and not line.startswith('#'):
            k, v = line.split('=', 1)
            d[k.strip()] = v.strip()
    return d
rows = [('punch force at 98% of the lock depth, N/mm', 'punch_force_98_N_per_mm'),
        ('punch force at the lock depth (end of locking), N/mm', 'punch_force_full_lock_N_per_mm'),
        ('sheet tension at 98% of the lock depth, N/mm', 'lock_tension_98_N_per_mm'),
        ('sheet tension at the lock depth (end of locking), N/mm', 'lock_tension_N_per_mm'),
        ('largest restraining force, N/mm', 'max_restraining_force_N_per_mm'),
        ('... at pull delta/h (clamped: the continuum necks)', 'max_restraining_force_at_delta_over_h'),
        ('lift force at the largest restraining force, N/mm', 'lift_at_max_restraining_N_per_mm'),
        ('lift force at 0.5h of pull, N/mm', 'lift_at_half_h_N_per_mm'),
        ('lift force at 1h of pull, N/mm', 'lift_at_1h_N_per_mm'),
        ('lift force at 2h of pull, N/mm', 'lift_at_2h_N_per_mm'),
        ('peak mid-surface strain after locking', 'peak_strain_lock'),
        ('straight-part mid-surface strain after locking', 'straight_strain_lock')]
print('| case | quantity | continuum | paper section | ratio | contact section | ratio |')
print('| --- | --- | ---: | ---: | ---: | ---: | ---: |')
for cdir in sorted(glob.glob("docs/validation/continuum/cc_*/")):
    case = os.path.basename(cdir.rstrip('/'))
    c = read(os.path.join(cdir, 'continuum_summary.txt'))
    for k, v in read(os.path.join(work, case + '_continuum_metrics.txt')).items():
        c.setdefault(k, v)
    p = {v: read(os.path.join(work, case + '_' + v, 'metrics.txt')) for v in ('none', 'contact')}
    s = {v: read(os.path.join(work, case + '_' + v, 'run', 'summary.txt')) for v in ('none', 'contact')}
    def cell(d, k):
        try:
            x = float(d[k]); return x
        except (KeyError, ValueError):
            return None
    for label, key in rows:
        cv = cell(c, key)
        vals = [cell(p[v], key) for v in ('none', 'contact')]
        out = ['%.4g' % cv if cv is not None else 'none']
        for x in vals:
            out.append('%.4g' % x if x is not None else 'none')
            out.append('%.3f' % (x / cv) if x is not None and cv else '')
        print('| %s | %s | %s |' % (case, label, ' | '.join(out)))
    # after the largest force: the continuum's neck takes the force down
    # within about 1h, the shell's drawing neck does not
    def past(pull):
        rows = [l.split() for l in open(pull) if l.strip() and not l.startswith('#')]
        d = [float(r[0]) for r in rows]; f = [float(r[2]) for r in rows]
        if not f:
            return None
        i = max(range(len(f)), key=lambda k: f[k])
        t = d[i] + 1.0
        for k in range(i + 1, len(d)):
            if d[k] >= t:
                w = (t - d[k - 1]) / (d[k] - d[k - 1])
                return (f[k - 1] + w * (f[k] - f[k - 1])) / f[i]
        return None
    cv = past(os.path.join(cdir, 'pull.dat'))
    vals = [past(os.path.join(work, case + '_' + v, 'run', 'pull.dat')) for v in ('none', 'neck')]
    out = ['%.3f' % cv if cv is not None else 'none']
    for x in vals:
        out += ['%.3f' % x if x is not None else 'none', '']
    print('| %s | restraining force 1h past its largest / the largest (contact section: with refine_neck) | %s |'
          % (case, ' | '.join(out)))
    tear = ['%.3g' % float(s[v]['tearing_delta_over_h']) if s[v].get('tearing_delta_over_h', 'none') != 'none'
            else 'none' for v in ('none', 'contact')]
    cr = ['%.3g' % float(s[v]['delta_cr_over_h']) if s[v].get('delta_cr_over_h', 'none') != 'none'
          else 'none' for v in ('none', 'contact')]
    print('| %s | tearing_delta_over_h (delta_cr_over_h) | | %s (%s) | | %s (%s) | |'
          % (case, tear[0], cr[0], tear[1], cr[1]))
    n = read(os.path.join(work, case + '_neck', 'run', 'summary.txt'))
    nt = cell(n, 'tearing_delta_over_h')
    # the continuum necks at its largest restraining force when the force
    # falls clearly after it: below 0.9 of it 1h later (brass draws on to
    # the end; a free edge draws steadily, without a neck, unless its bead
    # holds it: the double bead)
    cv = cell(c, 'max_restraining_force_at_delta_over_h')
    fall = past(os.path.join(cdir, 'pull.dat'))
    if cv is None or fall is None or fall >= 0.9:
        cv = None
    print('| %s | tearing_delta_over_h with refine_neck (%s), continuum: its neck | %s | | | %s | %s |'
          % (case, n.get('neck_refinement', 'none'), '%.4g' % cv if cv is not None else 'none',
             '%.4g' % nt if nt is not None else 'none',
             '%.3f' % (nt / cv) if nt is not None and cv else ''))
PY
