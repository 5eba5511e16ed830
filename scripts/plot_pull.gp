# plot_pull.gp -- restraining force N/(E h) against the pull displacement
# Delta/h (the paper's Figs. 8 and 9), from one or more pull.dat files.
#
# Usage:
#   gnuplot -c scripts/plot_pull.gp [--title=TEXT] [--size=W,H] [--key=POS]
#           [--no-marks] PULL.dat[::LABEL[::STYLE]] ... OUT.png
#
#   PULL.dat  a pull.dat written by drawbead (column 1: Delta/h,
#             column 2: N/(E h)); LABEL is its legend entry (default: the
#             run's title, from the file's first line); STYLE is extra
#             gnuplot line style text, e.g. 'dt 2 lw 1 lc rgb "black"'.
#             Each legend entry ends with the run's E h in N/mm (column 3
#             over column 2 of the file: the force in N/mm over the force
#             over E h), for reading a force in N/mm off the plot.
#   OUT.png   the picture; .png (pngcairo), .pdf (pdfcairo) or .svg.
#   --title   the plot title (default: none); --size in pixels (PNG, SVG)
#             or inches (PDF); --key a gnuplot "set key" position such as
#             'top left' (default 'bottom right').
#   --no-marks  do not mark where the curves tear
#
# Where a run tore while pulling (summary.txt beside its pull.dat gives
# delta_cr_over_h, the paper's pointwise criterion, and
# delta_cr_nonlocal_over_h, the averaged-strain criterion), its curve
# carries a filled dot at Delta_cr, labelled with its value, and an open
# circle where the averaged criterion was met.
#
# gnuplot -c passes at most 9 arguments: up to 8 files, fewer with options.
# Explicit column numbers throughout: the files' '#' header lines are
# skipped by gnuplot (never use columnhead with them).
# Example:
#   gnuplot -c scripts/plot_pull.gp out/fig9c_beadA_steel_free/pull.dat \
#       'out/fig9b_beadA_steel_free_mu02/pull.dat::mu = 0.2' fig9.png

if (ARGC < 2) {
    print "usage: gnuplot -c plot_pull.gp [--title=TEXT] [--size=W,H] [--key=POS] [--no-marks] PULL.dat[::LABEL[::STYLE]] ... OUT.png"
    exit status 1
}

out = ARGV[ARGC]
ptitle = ''
psize = ''
pkey = 'bottom right'
marks = 1
array files[9]
array labels[9]
array styles[9]
n = 0
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
                p = strstrt(a, '::')
                f = a
                lab = ''
                sty = ''
                if (p > 0) {
                    f = a[1:p - 1]
                    rest = a[p + 2:]
                    q = strstrt(rest, '::')
                    lab = rest
                    if (q > 0) {
                        lab = rest[1:q - 1]
                        sty = rest[q + 2:]
                    }
                }
                if (system("test -r '" . f . "' && echo yes") ne 'yes') {
                    print "plot_pull.gp: cannot read '" . f . "', skipped"
                } else {
                    if (system("grep -vc '^#' '" . f . "' || true") + 0 == 0) {
                        print "plot_pull.gp: no data rows in '" . f . "', skipped"
                    } else {
                        if (lab eq '') {
                            lab = system("sed -n '1s/^# drawbead [a-z]*: *//p' '" . f . "'")
                        }
                        n = n + 1
                        files[n] = f
                        labels[n] = lab
                        styles[n] = sty
                    }
                }
              }
            }
        }
    }
}
# E h of each run, N/mm (column 3 over column 2: the force in N/mm and
# over E h, of the deck's E and h), in its legend entry: a force in N/mm
# is the plotted value times E h
do for [i = 1:n] {
    eh = real(system("awk '!/^#/ && NF && $2 != 0 { printf \"%.10g\", $3 / $2; exit }' '" . files[i] . "'"))
    labels[i] = labels[i] . sprintf('  (E h = %.0f N/mm)', eh)
}
if (n == 0) {
    print "plot_pull.gp: nothing to plot"
    exit status 1
}

# terminal from the output file's extension
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

# colour-blind safe colours (Okabe-Ito), each with its own dash pattern
set linetype 1 lc rgb '#0072B2' lw 2.5 dt 1
set linetype 2 lc rgb '#D55E00' lw 2.5 dt 2
set linetype 3 lc rgb '#009E73' lw 2.5 dt 4
set linetype 4 lc rgb '#CC79A7' lw 2.5 dt 5
set linetype 5 lc rgb '#E69F00' lw 2.5 dt 3
set linetype 6 lc rgb '#56B4E9' lw 2.5 dt 1
set linetype 7 lc rgb '#000000' lw 2.5 dt 2
set linetype 8 lc rgb '#999999' lw 2.5 dt 4

set title ptitle
set xlabel 'pull displacement of the right edge  Δ/h  [-]'
set ylabel 'restraining force  N/(E h)  [-]   (E h in the legend)'
set format y '%g'
set grid lc rgb '#dddddd' lw 1
set key box opaque samplen 3 spacing 1.2
eval 'set key ' . pkey
set xrange [0:*]
set yrange [0:*]
set offsets 0, 0, graph 0.05, 0
set mxtics 2
set mytics 2

# where each curve tears: N/(E h) at Delta_cr interpolated in its pull.dat
readable(f) = system("test -r '" . f . "' && echo yes") eq 'yes'
num(s) = (s eq '' || s eq 'none') ? NaN : real(s)
# sval(FILE, KEY): a value of the summary.txt FILE ('' if missing)
sval(f, key) = readable(f) ? system("awk -F' = ' '$1 == \"" . key . "\" { print $2 }' '" . f . "'") : ''
# at(FILE, D): column 2 of FILE at column 1 = D (linear interpolation)
at(f, d) = real(system(sprintf("awk -v d=%.10g '!/^#/ && NF { if ($1 >= d) { print (n ? y + (d - x) * ($2 - y) / ($1 - x) : $2); done = 1; exit } x = $1; y = $2; n = 1 } END { if (!done) print y }' '%s'", d, f)))
ntear = 0
if (marks) {
    ymax = real(system("awk '!/^#/ && NF && $2 > m { m = $2 } END { print m + 0 }' '" . files[1] . "'"))
    do for [i = 2:n] {
        m = real(system("awk '!/^#/ && NF && $2 > m { m = $2 } END { print m + 0 }' '" . files[i] . "'"))
        ymax = (m > ymax) ? m : ymax
    }
    do for [i = 1:n] {
        f = files[i]
        fsum = (strstrt(f, '/') > 0 ? system("dirname '" . f . "'") : '.') . '/summary.txt'
        d1 = num(sval(fsum, 'delta_cr_over_h'))
        d2 = num(sval(fsum, 'delta_cr_nonlocal_over_h'))
        if (d2 == d2) {
            ntear = ntear + 1
            eval sprintf("set label %d '' at %.10g, %.10g point lt %d pt 6 ps 2.2 lw 2 front", 100 + i, d2, at(f, d2), i)
        }
        if (d1 == d1) {
            ntear = ntear + 1
            y1 = at(f, d1)
            eval sprintf("set label %d '' at %.10g, %.10g point lt %d pt 7 ps 1.6 front", 200 + i, d1, y1, i)
            # the value, upright, above the dot (below it near the top)
            up = (y1 < 0.6 * ymax)
            eval sprintf("set label %d 'Δcr = %.2fh' at %.10g, %.10g rotate by 90 %s offset 0, %s tc lt %d front", \
                300 + i, d1, d1, y1, up ? 'left' : 'right', up ? '1.2' : '-1.2', i)
        }
    }
}

cmd = 'plot '
do for [i = 1:n] {
    cmd = cmd . sprintf("files[%d] using 1:2 with lines lt %d %s title labels[%d]", i, i, styles[i], i)
    if (i < n) { cmd = cmd . ', ' }
}
if (ntear > 0) {
    # room right of a mark at the end of the longest curve
    set offsets 0, graph 0.02, graph 0.05, 0
    cmd = cmd . ", NaN with points pt 7 ps 1.6 lc rgb '#000000' title 'tears (pointwise criterion, Δcr)'"
    cmd = cmd . ", NaN with points pt 6 ps 2.2 lw 2 lc rgb '#000000' title 'tears (averaged-strain criterion)'"
}
eval cmd
unset output
