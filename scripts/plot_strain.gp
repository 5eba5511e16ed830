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
#   --key     a gnuplot "set key" position (default 'inside top left Left reverse',
#             in the frame where the sheet's left end is straight)
#   --no-marks  do not mark the tearing points s* of summary.txt
#
# Columns used: 1 (s/h, reference position) and 4 (lambda - 1). The pull
# curve is left out when the run did no pulling (final_delta_over_h = 0).
# The tearing point s* of the paper's pointwise criterion and that of the
# mesh-objective averaged-strain criterion are marked by dotted vertical
# lines, each labelled with s* and the pull Delta_cr (or lock depth H) at
# which it was met; the x range holds both ends of the sheet with 1h to
# spare, so that a mark at an end is seen.
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
pkey = 'inside top left Left reverse'
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
set offsets 0, 0, graph 0.2, 0
set yrange [*<0:*]
set mxtics 2
set mytics 2
set xzeroaxis lt -1 lw 0.5

# the stations at both ends lie 1h inside the frame, so that a tearing
# point at an end (the averaged criterion may pick one) is seen
stats flock using 1 nooutput
smin = STATS_min
smax = STATS_max
smid = 0.5 * (smin + smax)
set xrange [smin - 1:smax + 1]

# tearing points: a dotted vertical line for each criterion met (the paper's
# pointwise one, and the mesh-objective averaged-strain one), labelled at
# the top of the frame on the side facing the middle of the sheet
# tear_label(NAME, S, DELTA, H): the label text
tear_label(name, s, d, h) = sprintf(' %s: s* = %.1fh', name, s) . \
    ((d == d) ? sprintf(', Δcr = %.2fh ', d) : ((h == h) ? sprintf(', at H = %.2fh ', h) : ' '))
# mark(TAG, S, AT, LABEL, COLOUR, HEIGHT): the line at S and its label
# ending (or starting) at AT
mark(tag, s, at, lab, col, y) = sprintf("set arrow %d from %.10g, graph 0 to %.10g, graph 1 nohead dt 3 lw 2 lc rgb '%s' back; ", tag, s, s, col) . \
    sprintf("set label %d '%s' at %.10g, graph %g %s tc rgb '%s' front", tag, lab, at, y, (at < smid) ? 'left' : 'right', col)
if (marks) {
    sstar = num(sval('s_star_over_h'))
    snl = num(sval('s_star_nonlocal_over_h'))
    # two marks on the same side of the middle: both labels clear of both
    # lines
    both = (sstar == sstar) && (snl == snl) && ((sstar < smid) == (snl < smid))
    at1 = !both ? sstar : (((sstar < smid) == (sstar > snl)) ? sstar : snl)
    at2 = !both ? snl : at1
    if (sstar == sstar) {
        eval mark(1, sstar, at1, tear_label('pointwise', sstar, num(sval('delta_cr_over_h')), num(sval('lock_cr_over_h'))), '#D55E00', 0.96)
    }
    if (snl == snl) {
        eval mark(2, snl, at2, tear_label('averaged', snl, num(sval('delta_cr_nonlocal_over_h')), num(sval('lock_cr_nonlocal_over_h'))), '#009E73', 0.895)
    }
}

if (with_pull) {
    plot flock using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 1 title lock_title, \
         fpull using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 2 title pull_title
} else {
    plot flock using 1:4 with lines lw 2.5 lc rgb '#0072B2' dt 1 title lock_title
}
unset output
