# plot_lock.gp -- punch force F/(E h) against the rise of the lower tool H/h
# (the paper's Fig. 7), from one or more lock.dat files.
#
# Usage:
#   gnuplot -c scripts/plot_lock.gp [--title=TEXT] [--size=W,H] [--key=POS]
#           LOCK.dat[::LABEL[::STYLE]] ... OUT.png
#
#   LOCK.dat  a lock.dat written by drawbead (column 1: H/h,
#             column 2: F/(E h)); LABEL is its legend entry (default: the
#             run's title, from the file's first line); STYLE is extra
#             gnuplot line style text, e.g. 'dt 2 lw 1 lc rgb "black"'.
#             Each legend entry ends with the run's E h in N/mm (column 3
#             over column 2 of the file: the force in N/mm over the force
#             over E h), for reading a force in N/mm off the plot.
#   OUT.png   the picture; .png (pngcairo), .pdf (pdfcairo) or .svg.
#   --title   the plot title (default: none); --size in pixels (PNG, SVG)
#             or inches (PDF); --key a gnuplot "set key" position such as
#             'bottom right' (default 'top left').
#
# gnuplot -c passes at most 9 arguments: up to 8 files, fewer with options.
# Explicit column numbers throughout: the files' '#' header lines are
# skipped by gnuplot (never use columnhead with them).
# Example:
#   gnuplot -c scripts/plot_lock.gp out/fig7b_beadA_steel_mu0/lock.dat \
#       'out/fig7d_beadA_steel_mu01/lock.dat::mu = 0.1::dt 2 lw 1' fig7.png

if (ARGC < 2) {
    print "usage: gnuplot -c plot_lock.gp [--title=TEXT] [--size=W,H] [--key=POS] LOCK.dat[::LABEL[::STYLE]] ... OUT.png"
    exit status 1
}

out = ARGV[ARGC]
ptitle = ''
psize = ''
pkey = 'top left'
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
                    print "plot_lock.gp: cannot read '" . f . "', skipped"
                } else {
                    if (system("grep -vc '^#' '" . f . "' || true") + 0 == 0) {
                        print "plot_lock.gp: no data rows in '" . f . "', skipped"
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
# E h of each run, N/mm (column 3 over column 2: the force in N/mm and
# over E h, of the deck's E and h), in its legend entry: a force in N/mm
# is the plotted value times E h
do for [i = 1:n] {
    eh = real(system("awk '!/^#/ && NF && $2 != 0 { printf \"%.10g\", $3 / $2; exit }' '" . files[i] . "'"))
    labels[i] = labels[i] . sprintf('  (E h = %.0f N/mm)', eh)
}
if (n == 0) {
    print "plot_lock.gp: nothing to plot"
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
set xlabel 'rise of the lower tool  H/h  [-]'
set ylabel 'punch force  F/(E h)  [-]   (E h in the legend)'
set format y '%g'
set grid lc rgb '#dddddd' lw 1
set key box opaque samplen 3 spacing 1.2
eval 'set key ' . pkey
set xrange [0:*]
set yrange [0:*]
set offsets 0, 0, graph 0.05, 0
set mxtics 2
set mytics 2

cmd = 'plot '
do for [i = 1:n] {
    cmd = cmd . sprintf("files[%d] using 1:2 with lines lt %d %s title labels[%d]", i, i, styles[i], i)
    if (i < n) { cmd = cmd . ', ' }
}
eval cmd
unset output
