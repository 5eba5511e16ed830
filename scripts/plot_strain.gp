# plot_strain.gp -- mid-surface strain lambda - 1 over the sheet after
# locking (solid) and after pulling (dashed), as in the paper's Figs. 5
# and 6, from the strain_lock.dat and strain_pull.dat of one output folder.
#
# Usage:
#   gnuplot -c scripts/plot_strain.gp [--title=TEXT] [--size=W,H] [--key=POS]
#           [--no-marks] DIR OUT.png
#
#   DIR       an output folder of drawbead (strain_lock.dat, strain_pull.dat;
#             summary.txt and lock.dat, if present, give the lock depth,
#             the pull distance and the tearing point for the legend)
#   OUT.png   the picture; .png (pngcairo), .pdf (pdfcairo) or .svg
#   --title   the plot title (default: the run's title, from summary.txt)
#   --key     a gnuplot "set key" position (default 'below': under the axes)
#   --no-marks  do not mark the tearing points s* of summary.txt
#
# Columns used: 1 (s/h, reference position) and 4 (lambda - 1). The pull
# curve is left out when the run did no pulling (final_delta_over_h = 0).
# The tearing point s* of the paper's pointwise criterion (and that of the
# mesh-objective averaged-strain criterion, if it differs) is marked by a
# dotted vertical line.
# Example:
#   gnuplot -c scripts/plot_strain.gp out/fig5a_beadA_steel fig5a.png

if (ARGC < 2) {
    print "usage: gnuplot -c plot_strain.gp [--title=TEXT] [--size=W,H] [--key=POS] [--no-marks] DIR OUT.png"
    exit status 1
}

out = ARGV[ARGC]
dir = ''
ptitle = '__default__'
psize = ''
pkey = 'below'
marks = 1
do for [i = 1:ARGC - 1] {
    a = ARGV[i]
    if (a[1:8] eq '--title=') {
        ptitle = a[9:]
    } else {
        if (a[1:7] eq '--size=') {
            psize = a[8:]
        } else {
            if (a[1:6] eq '--key=') {
                pkey = a[7:]
            } else {
                if (a eq '--no-marks') {
                    marks = 0
                } else {
                    dir = a
                }
            }
        }
    }
}
flock = dir . '/strain_lock.dat'
fpull = dir . '/strain_pull.dat'
fsum = dir . '/summary.txt'
readable(f) = system("test -r '" . f . "' && echo yes") eq 'yes'
if (!readable(flock)) {
    print "plot_strain.gp: cannot read '" . flock . "'"
    exit status 1
}
# a summary.txt value ('' if the file or the key is missing)
sval(key) = readable(fsum) ? system("awk -F' = ' '$1 == \"" . key . "\" { print $2 }' '" . fsum . "'") : ''
num(s) = (s eq '' || s eq 'none') ? NaN : real(s)

if (ptitle eq '__default__') {
    ptitle = readable(fsum) ? system("sed -n '1s/^# drawbead summary: *//p' '" . fsum . "'") : ''
}
delta = num(sval('final_delta_over_h'))
# lock depth H/h: the last row of lock.dat (no locking: no row)
hlock = NaN
flockdat = dir . '/lock.dat'
if (readable(flockdat)) {
    s = system("awk '!/^#/ && NF { h = $1 } END { print h }' '" . flockdat . "'")
    hlock = num(s)
}
lock_title = (hlock == hlock) ? sprintf('after locking (H = %.2fh)', hlock) : 'after locking'
with_pull = readable(fpull) && (delta == delta) && delta > 0
pull_title = with_pull ? sprintf('after pulling (Δ = %.2fh)', delta) : ''

ext = out[strlen(out) - 3:]
if (ext eq '.pdf') {
    if (psize eq '') { psize = '7,4.5' }
    eval "set terminal pdfcairo noenhanced font 'DejaVu Sans,11' size " . psize
} else {
    if (ext eq '.svg') {
        if (psize eq '') { psize = '900,600' }
        eval "set terminal svg noenhanced font 'DejaVu Sans,14' size " . psize
    } else {
        if (psize eq '') { psize = '900,600' }
        eval "set terminal pngcairo noenhanced font 'DejaVu Sans,13' size " . psize
    }
}
set output out

set title ptitle
set xlabel 'reference position along the sheet  s/h  [-]   (bead centre at 0)'
set ylabel 'mid-surface strain  λ − 1  [-]'
set grid lc rgb '#dddddd' lw 1
set key nobox samplen 3 spacing 1.2 width 2
eval 'set key ' . pkey
set offsets 0, 0, graph 0.15, 0
set yrange [*<0:*]
set mxtics 2
set mytics 2
set xzeroaxis lt -1 lw 0.5

# tearing points, labelled on the side facing the middle of the sheet
stats flock using 1 nooutput
smid = 0.5 * (STATS_min + STATS_max)
if (marks) {
    sstar = num(sval('s_star_over_h'))
    snl = num(sval('s_star_nonlocal_over_h'))
    dcr = num(sval('delta_cr_over_h'))
    if (sstar == sstar) {
        set arrow 1 from sstar, graph 0 to sstar, graph 1 nohead dt 3 lw 1.5 lc rgb '#D55E00' back
        lab = (dcr == dcr) ? sprintf(' s* = %.1fh (Δcr = %.2fh)', sstar, dcr) : sprintf(' s* = %.1fh', sstar)
        if (sstar < smid) {
            set label 1 lab . ' ' at sstar, graph 0.96 left tc rgb '#D55E00' front
        } else {
            set label 1 lab . ' ' at sstar, graph 0.96 right tc rgb '#D55E00' front
        }
    }
    if (snl == snl && !(sstar == sstar && abs(snl - sstar) < 0.5)) {
        set arrow 2 from snl, graph 0 to snl, graph 1 nohead dt 3 lw 1.5 lc rgb '#009E73' back
        lab = sprintf(' s* averaged = %.1fh ', snl)
        if (snl < smid) {
            set label 2 lab at snl, graph 0.90 left tc rgb '#009E73' front
        } else {
            set label 2 lab at snl, graph 0.90 right tc rgb '#009E73' front
        }
    }
}

if (with_pull) {
    plot flock using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 1 title lock_title, \
         fpull using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 2 title pull_title
} else {
    plot flock using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 1 title lock_title
}
unset output
