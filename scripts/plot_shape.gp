# plot_shape.gp -- the deformed sheet in the tools, to scale, at the end of
# locking or at the end of pulling, for one output folder of drawbead: the
# sheet drawn with its current thickness and coloured by its equivalent
# plastic strain, the tools as grey solids.
#
# Usage:
#   gnuplot -c scripts/plot_shape.gp [--title=TEXT] [--size=W,H] [--margin=M]
#           [--pad=P] [--full] [--no-marks] DIR lock|pull OUT.png
#
#   DIR       an output folder: strain_lock.dat / strain_pull.dat (columns
#             2:3 = x/h, y/h of the sheet's centreline, 8 the thickness log
#             strain, 9 the largest equivalent plastic strain through the
#             thickness) and tools_lock.dat / tools_pull.dat (block 0 the
#             upper tool, block 1 the lower tool); without tools
#             (bead = 'none') only the sheet is drawn
#   lock|pull the state: end of locking or end of pulling (end of the run)
#   OUT.png   the picture; .png (pngcairo), .pdf (pdfcairo) or .svg
#   --title   the plot title (default: the run's title and the state); a
#             '%s' in it is replaced by the state ('end of locking,
#             H = 6.22h' or 'end of pulling, Delta = 2.05h')
#   --size    the canvas, in pixels (PNG, SVG) or inches (PDF); default
#             1400 pixels (10 inches) wide and as high as the window needs
#   --margin  the x range is the bead (where a tool leaves its binder
#             level) plus M sheet thicknesses on each side (default 3),
#             widened to hold the tearing point
#   --pad     the y range is the sheet's height in that x range plus P
#             thicknesses above and below (default 1.5)
#   --full    the x range is the whole sheet plus M on each side
#   --no-marks  do not mark the tearing point s* of summary.txt
#
# Equal scales on both axes (set size ratio -1). The sheet's faces lie h/2
# times its current thickness ratio exp(column 8) each side of the
# centreline, along its normal; the tools are their physical surfaces (the
# tools files hold the surfaces the centreline touches, offset by h/2
# toward the sheet). The polygons come from scripts/shape_polygons.py
# (python3, next to this script), read through pipes. Where the paper's pointwise criterion
# was met in the state drawn, the Gauss station s* is marked with a cross.
# Example:
#   gnuplot -c scripts/plot_shape.gp out/fig5a_beadA_steel pull shape.png

if (ARGC < 3) {
    print "usage: gnuplot -c plot_shape.gp [--title=TEXT] [--size=W,H] [--margin=M] [--pad=P] [--full] [--no-marks] DIR lock|pull OUT.png"
    exit status 1
}

out = ARGV[ARGC]
phase = ARGV[ARGC - 1]
dir = ''
ptitle = '__default__'
psize = ''
margin = 3.0
pad = 1.5
full = 0
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
                if (a[1:6] eq '--pad=') {
                    pad = real(a[7:])
                } else {
                    if (a eq '--full') {
                        full = 1
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

# the tearing point, if it was reached in this state
tear = 0
sstar = NaN
if (marks) {
    sstar = num(sval('s_star_over_h'))
    lphase = sval('localization_phase')
    if (sstar == sstar && (lphase eq phase || (phase eq 'pull' && lphase eq 'lock'))) {
        tear = 1
    }
}
# its station: the current x/h, y/h of the row whose s/h is s*
xtear = NaN
ytear = NaN
if (tear) {
    xy = system(sprintf("awk '!/^#/ && NF && ($1 - (%.10g))^2 < 1e-10 * (1 + ($1)^2) { print $2, $3; exit }' '%s'", sstar, fsheet))
    if (words(xy) == 2) {
        xtear = real(word(xy, 1))
        ytear = real(word(xy, 2))
    } else {
        tear = 0
    }
}

# the sheet with its thickness and the tools' surfaces as polygons, and the
# window (the bead, the tearing point, the sheet's height) from the data,
# read from scripts/shape_polygons.py through pipes
helper = "python3 '" . system("dirname '" . ARG0 . "'") . "/shape_polygons.py' "
hargs = sprintf("--margin=%g --pad=%g", margin, pad)
if (tear) { hargs = hargs . sprintf(" --keep=%.10g", xtear) }
if (full) { hargs = hargs . ' --full' }
hfiles = " '" . fsheet . "'" . (has_tools ? " '" . ftools . "'" : '')
win = system(helper . hargs . hfiles . ' || echo failed')
if (words(win) != 5) {
    print 'plot_shape.gp: shape_polygons.py failed: ' . win
    exit status 1
}
xmin = real(word(win, 1))
xmax = real(word(win, 2))
ymin = real(word(win, 3))
ymax = real(word(win, 4))
epmax = real(word(win, 5))
fpoly = '< ' . helper . '--print=sheet' . hfiles
fline = '< ' . helper . '--print=outline' . hfiles
ftool = '< ' . helper . '--print=tools' . hfiles

# the canvas: its width, and a height that holds the window at equal
# scales with nothing to spare; the margins (title; axis labels and the
# colour box below the axes) in the canvas's units (pixels, or inches for
# PDF)
ext = out[strlen(out) - 3:]
if (ext eq '.pdf') {
    mleft = 0.75
    mright = 0.35
    mtop = 0.5
    mbottom = 1.5
    wdef = 10.0
    term = "pdfcairo noenhanced font 'DejaVu Sans,11'"
} else {
    mleft = 80.0
    mright = 40.0
    mtop = 50.0
    mbottom = 150.0
    wdef = 1400.0
    if (ext eq '.svg') {
        term = "svg noenhanced font 'DejaVu Sans,14'"
    } else {
        term = "pngcairo noenhanced font 'DejaVu Sans,13'"
    }
}
if (psize eq '') {
    cw = wdef
    ch = mtop + mbottom + (cw - mleft - mright) * (ymax - ymin) / (xmax - xmin)
    if (ext ne '.pdf') { ch = ceil(ch) }
    psize = sprintf('%g,%g', cw, ch)
} else {
    comma = strstrt(psize, ',')
    if (comma == 0) {
        print "plot_shape.gp: --size=W,H, not '" . psize . "'"
        exit status 1
    }
    cw = real(psize[1:comma - 1])
    ch = real(psize[comma + 1:])
}
eval 'set terminal ' . term . ' size ' . psize
set output out

set title ptitle
set xlabel 'x/h  [-]' offset 0, 0.3
set ylabel 'y/h  [-]'
set lmargin at screen mleft / cw
set rmargin at screen 1 - mright / cw
set tmargin at screen 1 - mtop / ch
set bmargin at screen mbottom / ch
set size ratio -1
set xrange [xmin:xmax]
set yrange [ymin:ymax]
# y tics at least 24 pixels (1/3 inch) apart: a step of 1, 2 or 5 times a
# power of 10
ystep = 24.0 / (ext eq '.pdf' ? 72.0 : 1.0) * (xmax - xmin) / (cw - mleft - mright)
ydec = 10.0**floor(log10(ystep))
ystep = (ystep <= ydec) ? ydec : ((ystep <= 2 * ydec) ? 2 * ydec : ((ystep <= 5 * ydec) ? 5 * ydec : 10 * ydec))
set ytics ystep
set tics front
set grid front lc rgb '#80ffffff' lw 0.5
set mxtics 2
set mytics 2
unset key

# the sheet coloured by the equivalent plastic strain (viridis)
set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')
set cbrange [0:(epmax > 0 ? epmax : 1e-3)]
set cblabel 'equivalent plastic strain  [-]' offset 0, 0.6
# a horizontal colour box under the x label, a third of the axes wide
set colorbox horizontal user origin screen (mleft + 0.33 * (cw - mleft - mright)) / cw, \
    screen 0.4 * mbottom / ch size screen 0.34 * (cw - mleft - mright) / cw, screen 0.09 * mbottom / ch
set cbtics nomirror
set format cb '%g'

tool_fill = '#c4c4c4'
tool_edge = '#555555'
if (has_tools) {
    set label 1 'upper tool' at graph 0, graph 1 left front tc rgb '#303030' offset 1.2, -1
    set label 2 'lower tool' at graph 0, graph 0 left front tc rgb '#303030' offset 1.2, 0.8
}
if (tear) {
    # below the sheet, on the side facing the middle of the window
    tjust = (xtear > 0.5 * (xmin + xmax)) ? 'right' : 'left'
    eval sprintf("set label 3 'tearing point (s* = %.1fh) ' at %.10g, %.10g %s front tc rgb '#b00000' offset %s, -1.6 point pt 2 ps 2.5 lw 3 lc rgb '#d00000'", \
        sstar, xtear, ytear, tjust, (tjust eq 'right') ? '1.2' : '-1.2')
}

if (has_tools) {
    # both tools in one pass (each block its own polygon): a pipe is read
    # once, to its end
    plot ftool using 1:2 with filledcurves closed fc rgb tool_fill fs solid 1.0 border lc rgb tool_edge lw 1.5, \
         fpoly using 1:2:3 with filledcurves closed fc palette z fs solid 1.0 noborder, \
         fline using 1:2 with lines lw 1 lc rgb '#000000'
} else {
    plot fpoly using 1:2:3 with filledcurves closed fc palette z fs solid 1.0 noborder, \
         fline using 1:2 with lines lw 1 lc rgb '#000000'
}
unset output
