# plot_shape.gp -- the deformed sheet in the tools, to scale, at the end of
# locking or at the end of pulling, for one output folder of drawbead.
#
# Usage:
#   gnuplot -c scripts/plot_shape.gp [--title=TEXT] [--size=W,H] [--margin=M]
#           [--no-marks] DIR lock|pull OUT.png
#
#   DIR       an output folder: tools_lock.dat / tools_pull.dat (block 0 the
#             upper tool, block 1 the lower tool; columns 1:2 = x/h, y/h)
#             and strain_lock.dat / strain_pull.dat (columns 2:3 = x/h, y/h
#             of the sheet's centreline); without tools (bead = 'none') only
#             the sheet is drawn
#   lock|pull the state: end of locking or end of pulling (end of the run)
#   OUT.png   the picture; .png (pngcairo), .pdf (pdfcairo) or .svg
#   --title   the plot title (default: the run's title and the state); a
#             '%s' in it is replaced by the state ('end of locking,
#             H = 6.22h' or 'end of pulling, Delta = 2.05h')
#   --margin  the x range is the sheet's extent plus M sheet thicknesses on
#             each side (default 3)
#   --no-marks  do not mark the tearing point s* of summary.txt
#
# Equal scales on both axes (set size ratio -1). The tool lines are the
# surfaces the sheet's centreline touches (the physical tool surfaces offset
# by h/2 toward the sheet), so the centreline lies on them where in contact.
# Where the paper's pointwise criterion was met in the state drawn, the
# Gauss station s* is marked with a cross.
# Example:
#   gnuplot -c scripts/plot_shape.gp out/fig5a_beadA_steel pull shape.png

if (ARGC < 3) {
    print "usage: gnuplot -c plot_shape.gp [--title=TEXT] [--size=W,H] [--margin=M] [--no-marks] DIR lock|pull OUT.png"
    exit status 1
}

out = ARGV[ARGC]
phase = ARGV[ARGC - 1]
dir = ''
ptitle = '__default__'
psize = ''
margin = 3.0
marks = 1
do for [i = 1:ARGC - 2] {
    a = ARGV[i]
    if (a[1:8] eq '--title=') {
        ptitle = a[9:]
    } else {
        if (a[1:7] eq '--size=') {
            psize = a[8:]
        } else {
            if (a[1:9] eq '--margin=') {
                margin = real(a[10:])
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
if (phase ne 'lock' && phase ne 'pull') {
    print "plot_shape.gp: the state must be 'lock' or 'pull', not '" . phase . "'"
    exit status 1
}
readable(f) = system("test -r '" . f . "' && echo yes") eq 'yes'
fsheet = dir . '/strain_' . phase . '.dat'
ftools = dir . '/tools_' . phase . '.dat'
fsum = dir . '/summary.txt'
if (!readable(fsheet)) {
    print "plot_shape.gp: cannot read '" . fsheet . "'"
    exit status 1
}
has_tools = readable(ftools)
sval(key) = readable(fsum) ? system("awk -F' = ' '$1 == \"" . key . "\" { print $2 }' '" . fsum . "'") : ''
num(s) = (s eq '' || s eq 'none') ? NaN : real(s)

# the state: H/h from the last row of lock.dat, Delta/h from summary.txt
hlock = NaN
if (readable(dir . '/lock.dat')) {
    hlock = num(system("awk '!/^#/ && NF { h = $1 } END { print h }' '" . dir . "/lock.dat'"))
}
delta = num(sval('final_delta_over_h'))
if (phase eq 'lock') {
    state = (hlock == hlock) ? sprintf('end of locking, H = %.2fh', hlock) : 'end of locking'
} else {
    state = (delta == delta) ? sprintf('end of pulling, Δ = %.2fh', delta) : 'end of pulling'
}
if (ptitle eq '__default__') {
    run = readable(fsum) ? system("sed -n '1s/^# drawbead summary: *//p' '" . fsum . "'") : ''
    ptitle = (run eq '') ? state : run . ': ' . state
} else {
    if (strstrt(ptitle, '%s') > 0) {
        ptitle = sprintf(ptitle, state)
    }
}

# x range: the sheet and a margin; y range: what lies in it
stats fsheet using 2 nooutput
xmin = STATS_min - margin
xmax = STATS_max + margin

ext = out[strlen(out) - 3:]
if (ext eq '.pdf') {
    if (psize eq '') { psize = '10,3.6' }
    eval "set terminal pdfcairo noenhanced font 'DejaVu Sans,11' size " . psize
} else {
    if (ext eq '.svg') {
        if (psize eq '') { psize = '1400,500' }
        eval "set terminal svg noenhanced font 'DejaVu Sans,14' size " . psize
    } else {
        if (psize eq '') { psize = '1400,500' }
        eval "set terminal pngcairo noenhanced font 'DejaVu Sans,13' size " . psize
    }
}
set output out

set title ptitle
set xlabel 'x/h  [-]'
set ylabel 'y/h  [-]'
set size ratio -1
set xrange [xmin:xmax]
set offsets 0, 0, 1, 1
set grid lc rgb '#e4e4e4' lw 1
set mxtics 2
set mytics 2
set key below horizontal maxrows 1 nobox samplen 3 width 1

# the tearing point, if it was reached in this state
tear = 0
if (marks) {
    sstar = num(sval('s_star_over_h'))
    lphase = sval('localization_phase')
    if (sstar == sstar && (lphase eq phase || (phase eq 'pull' && lphase eq 'lock'))) {
        tear = 1
    }
}
near(s) = abs(s - sstar) < 1e-6 * (1 + abs(sstar))
upper_fill = '#c8d3de'
lower_fill = '#eadcc4'

if (has_tools) {
    if (tear) {
        plot ftools index 0 using 1:2 with filledcurves x2 fc rgb upper_fill fs solid 1.0 notitle, \
             ftools index 1 using 1:2 with filledcurves x1 fc rgb lower_fill fs solid 1.0 notitle, \
             ftools index 0 using 1:2 with lines lw 1.5 lc rgb '#3b5068' title 'upper (female) tool', \
             ftools index 1 using 1:2 with lines lw 1.5 lc rgb '#8a6d3b' title 'lower (male) tool', \
             fsheet using 2:3 with lines lw 3 lc rgb '#000000' title 'sheet centreline', \
             fsheet using 2:(near($1) ? $3 : NaN) with points pt 2 ps 3 lw 3 lc rgb '#D55E00' \
                 title sprintf('tearing point (s* = %.1fh)', sstar)
    } else {
        plot ftools index 0 using 1:2 with filledcurves x2 fc rgb upper_fill fs solid 1.0 notitle, \
             ftools index 1 using 1:2 with filledcurves x1 fc rgb lower_fill fs solid 1.0 notitle, \
             ftools index 0 using 1:2 with lines lw 1.5 lc rgb '#3b5068' title 'upper (female) tool', \
             ftools index 1 using 1:2 with lines lw 1.5 lc rgb '#8a6d3b' title 'lower (male) tool', \
             fsheet using 2:3 with lines lw 3 lc rgb '#000000' title 'sheet centreline'
    }
} else {
    plot fsheet using 2:3 with lines lw 3 lc rgb '#000000' title 'sheet centreline'
}
unset output
