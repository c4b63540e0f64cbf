/* This file contains the analysis plots: gnuplot scripts drawn from the CSV files analyze writes
 * (analysis_plots.h). */
#include "analysis/analysis_plots.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"
#include "analysis/symmetry.h"

/* The plots, the names gnuplot writes them under, and what is in each. */
enum { PLOT_CT, PLOT_ZOOM, PLOT_ALPHA, PLOT_MAP, PLOT_SIGMA, NPLOTS };
_Static_assert(NPLOTS <= TR_PLOTS_MAX, "tr_plot_script holds every plot");
static const char *const plot_names[NPLOTS] = {"curvature_torsion.png", "plateau_zoom.png",
                                               "accumulated_torsion.png", "contact_map.png",
                                               "sigma9.png"};

/* The zoomed window [z0, z1] of the plateau plot, in the plotted coordinate
 * (D3: l reduced to [0, L/6); otherwise l from the origin, where a window
 * across the origin reaches below 0 and the data there are drawn at l - L).
 * With a plateau: the plateau and at least four averaged arcs either side;
 * without: the curvature maximum and at least four averaged arcs either
 * side. The window always spans eight averaged arcs (or the whole range), so
 * it always holds data, however coarse the polygon. */
static void zoom_window(const tr_analysis *a, int d3, double xmax, double *z0, double *z1,
                        double *kmax_at, double *kmax)
{
    double arc = (double)a->m * a->L / (double)a->n; /* one averaged arc */
    double pad = 4.0 * arc;
    *kmax = -INFINITY, *kmax_at = 0.0;
    for (size_t k = 0; k < a->prof.n; k++) {
        double l = d3 ? tr_symmetry_reduce(a->prof.pos[k], a->L, NULL) : a->prof.pos[k];
        if (a->prof.kappa[k] > *kmax)
            *kmax = a->prof.kappa[k], *kmax_at = l;
    }
    double lo, hi;
    if (a->have_l12) {
        lo = a->l1, hi = a->l2;
        if (hi < lo) /* a plateau through the origin (not D3) */
            lo -= a->L;
        pad = fmax(pad, 0.6 * (hi - lo));
    } else {
        lo = hi = *kmax_at;
        if (!d3 && lo > 0.5 * a->L)
            lo = hi = lo - a->L;
        pad = fmax(pad, 0.3);
    }
    lo -= pad, hi += pad;
    if (d3) {
        /* [0, L/6) is closed under the reflections of D3: no wrapping */
        lo = fmax(lo, 0.0), hi = fmin(hi, xmax);
    } else if (hi - lo > a->L) {
        lo = 0.0, hi = a->L;
    } else if (lo < -0.5 * a->L || hi > a->L) {
        /* keep the window inside one turn, [-L/2, L] */
        double sh = lo < -0.5 * a->L ? -0.5 * a->L - lo : a->L - hi;
        lo += sh, hi += sh;
    }
    *z0 = lo, *z1 = hi;
}

int tr_analysis_plots_script(const char *dir, const tr_analysis *a, tr_plot_script *ps, tr_error *err)
{
    double L6 = a->L / 6.0;
    int d3 = a->sym.verdict == TR_SYM_D3;
    double xmax = d3 ? L6 : a->L;
    double z0, z1, kmax_at, kmax;
    zoom_window(a, d3, xmax, &z0, &z1, &kmax_at, &kmax);
    /* l1, l2 as drawn in the zoom (a plateau through the origin starts below 0) */
    double zl1 = a->have_l12 && !d3 && a->l1 > a->l2 ? a->l1 - a->L : a->l1;

    size_t nplots = a->have_sigma ? NPLOTS : PLOT_MAP;
    const char *base[NPLOTS];
    char *s = NULL;
    int rc = tr_plot_reserve(dir, plot_names, nplots, ps, err);
    if (rc != TR_OK)
        return rc;
    for (size_t i = 0; i < nplots; i++)
        base[i] = tr_plot_tmp_base(ps, dir, i);

    /* The D3 plots fold all six sectors onto [0, L/6) and draw sector I as the
     * line; without D3 there is one curve over [0, L). */
    char kfold[256], tfold[256], kzoom[256], tzoom[256];
    if (d3) {
        snprintf(kfold, sizeof kfold, "%s", "'curvature.csv' every ::1 using 3:5 with points pt 7 ps 0.3 lc rgb '#a0b4d8' title 'all six sectors, folded', ");
        snprintf(tfold, sizeof tfold, "%s", "'torsion.csv' every ::1 using 3:6 with points pt 7 ps 0.3 lc rgb '#e0b0a0' title 'all six sectors, folded', ");
        snprintf(kzoom, sizeof kzoom, "%s", "'curvature.csv' every ::1 using 3:5 with points pt 7 ps 0.4 lc rgb '#a0b4d8' title 'all six sectors, folded', ");
        snprintf(tzoom, sizeof tzoom, "%s", "'torsion.csv' every ::1 using 3:6 with points pt 7 ps 0.4 lc rgb '#e0b0a0' title 'all six sectors, folded', ");
    } else {
        kfold[0] = tfold[0] = kzoom[0] = tzoom[0] = '\0';
    }
    const char *ksrc = d3 ? "''" : "'curvature.csv'", *tsrc = d3 ? "''" : "'torsion.csv'";
    const char *kname = d3 ? "kappa (sector I)" : "kappa", *tname = d3 ? "tau (sector I)" : "tau";
    char ztitle[512];
    if (a->have_l12) {
        char wrapped[64] = "";
        if (zl1 != a->l1)
            snprintf(wrapped, sizeof wrapped, " (drawn at l1 - L = %.4g)", zl1);
        snprintf(ztitle, sizeof ztitle, "kappa = 1 plateau: l1 = %.4g%s, l2 = %.4g (dashed%s)", a->l1,
                 wrapped, a->l2, d3 ? "; averaged over the symmetry images" : "");
    } else {
        int whole = 0;
        for (size_t i = 0; i < a->nplateaus; i++)
            whole |= a->plateaus[i].first == 0 && a->plateaus[i].last == a->prof.n - 1;
        snprintf(ztitle, sizeof ztitle, "%s: the curvature maximum, kappa = %.4g at l = %.4g",
                 whole ? "kappa at the plateau level along the whole curve, no plateau ends"
                 : a->nplateaus ? "no plateau inside one symmetry sector"
                                : "no kappa = 1 plateau found",
                 kmax, kmax_at);
    }

    size_t cap = 32768;
    s = malloc(cap);
    if (!s) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the plot script");
        goto out;
    }
    int n = snprintf(s, cap,
        "# written by tightrope analyze; run in this directory: gnuplot plots.gp\n"
        "# (tightrope writes each plot to a temporary name and renames it when gnuplot is done)\n"
        "set datafile separator ','\n"
        "set datafile commentschars '#'\n"
        "set terminal pngcairo size 1100,700 noenhanced font ',11'\n"
        "L = %.15g; XM = %.15g; l1 = %.15g; l2 = %.15g; have12 = %d\n"
        "Z0 = %.15g; Z1 = %.15g; zl1 = %.15g\n"
        "set grid\n"
        "set key tmargin right horizontal  # above each panel: over the data it hid the kappa = 1 line\n"
        "set offsets 0, 0, graph 0.05, graph 0.05\n"
        "sec0(x, s) = (s == 0 ? x : 1/0)\n"
        "zx(x) = (Z0 < 0 && x > L/2 ? x - L : x)  # a zoom window across the origin starts below 0\n"
        "if (have12) { set arrow 1 from l1, graph 0 to l1, graph 1 nohead dt 2 lc rgb 'gray40'; "
        "set arrow 2 from l2, graph 0 to l2, graph 1 nohead dt 2 lc rgb 'gray40' }\n"
        /* 1: curvature and torsion over the representative interval */
        "set output '%s'\n"
        "set multiplot layout 2,1 title 'K_c^(%zu): curvature and torsion over [0, %s)'\n"
        "set xrange [0:XM]\n"
        "set ylabel 'curvature kappa'\n"
        "plot %s%s every ::1 using (sec0($2,$4)):5 with lines lw 2 lc rgb '#1f4e9c' title '%s', 1 dt 3 lc rgb 'black' title 'kappa = 1'\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'torsion tau'\n"
        "plot %s%s every ::1 using (sec0($2,$4)):6 with lines lw 2 lc rgb '#b03020' title '%s'\n"
        "unset multiplot\n"
        /* 2: the plateau region, or the curvature maximum */
        "unset xlabel\n"
        "set output '%s'\n"
        "set multiplot layout 2,1 title '%s'\n"
        "if (have12) { set arrow 1 from zl1, graph 0 to zl1, graph 1 nohead dt 2 lc rgb 'gray40' }\n"
        "set xrange [Z0:Z1]\n"
        "set ylabel 'curvature kappa'\n"
        "plot %s%s every ::1 using (zx(sec0($2,$4))):5 smooth unique with linespoints pt 7 ps 0.5 lc rgb '#1f4e9c' title '%s', 1 dt 3 lc rgb 'black' title 'kappa = 1'\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'torsion tau'\n"
        "plot %s%s every ::1 using (zx(sec0($2,$4))):6 smooth unique with linespoints pt 7 ps 0.5 lc rgb '#b03020' title '%s'\n"
        "unset multiplot\n"
        "if (have12) { set arrow 1 from l1, graph 0 to l1, graph 1 nohead dt 2 lc rgb 'gray40' }\n"
        /* 3: accumulated torsion */
        "set output '%s'\n"
        "set title 'accumulated torsion alpha(l) from the origin'\n"
        "set xrange [0:XM]\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'alpha (rad)'\n"
        "plot 'torsion.csv' every ::1 using (sec0($2,$4)):7 with lines lw 2 lc rgb '#207020' title 'alpha'\n"
        "unset arrow\n"
        "unset title\n",
        a->L, xmax, a->have_l12 ? a->l1 : 0.0, a->have_l12 ? a->l2 : 0.0, a->have_l12, z0, z1,
        a->have_l12 ? zl1 : 0.0, base[PLOT_CT], a->m, d3 ? "L/6" : "L", kfold, ksrc, kname, tfold,
        tsrc, tname, base[PLOT_ZOOM], ztitle, kzoom, ksrc, kname, tzoom, tsrc, tname,
        base[PLOT_ALPHA]);
    if (n < 0 || (size_t)n >= cap) {
        rc = tr_fail(err, TR_EINVAL, "plot script too long");
        goto out;
    }
    size_t len = (size_t)n;
    if (a->have_sigma) {
        size_t ns = 0;
        for (size_t i = 0; i < a->nfixed; i++)
            ns += a->fixed[i].stable != 0;
        char stable_txt[96] = "";
        if (a->nfixed)
            snprintf(stable_txt, sizeof stable_txt, " (%zu stable: filled circles)", ns);
        int k = snprintf(s + len, cap - len,
            /* 4: contact-function image */
            "set terminal pngcairo size 800,800 noenhanced font ',11'\n"
            "set output '%s'\n"
            "set title 'contact-function image: struts (l_i, l_j) and (l_j, l_i)'\n"
            "set xrange [0:L]; set yrange [0:L]; set size square\n"
            "set offsets 0, 0, 0, 0\n"
            "set key inside top left vertical opaque\n"
            "set xlabel 'l (from the origin)'; set ylabel 'partner l'\n"
            "plot 'contacts.csv' every ::1 using 1:2 with points pt 7 ps 0.5 lc rgb '#b8b8b8' title 'struts', "
            "'' every ::1 using 2:1 with points pt 7 ps 0.5 lc rgb '#b8b8b8' notitle, "
            "'sigma.csv' every ::1 using 1:2 with points pt 7 ps 0.15 lc rgb '#1f4e9c' title 'sigma-(l)', "
            "'' every ::1 using 1:3 with points pt 7 ps 0.15 lc rgb '#b03020' title 'sigma+(l)'\n"
            /* 5: sigma-^power against the diagonal */
            "set output '%s'\n"
            "set title 'sigma-^%d(l) against the diagonal: %zu fixed points%s'\n"
            "set xlabel 'l (from the origin)'; set ylabel 'sigma-^%d(l)'\n"
            "set samples 1000\n"
            "plot 'sigma.csv' every ::1 using 1:6 with points pt 7 ps 0.15 lc rgb '#1f4e9c' title 'sigma-^%d(l)', "
            "x with lines lc rgb 'black' title 'diagonal'%s\n",
            base[PLOT_MAP], base[PLOT_SIGMA], a->power, a->nfixed, stable_txt, a->power, a->power,
            a->nfixed ? ", 'fixed_points.csv' every ::1 using 1:($4 == 1 ? $1 : 1/0) with points pt 7 ps 1.2 lc rgb '#b03020' title 'stable', "
                        "'' every ::1 using 1:($4 == 0 ? $1 : 1/0) with points pt 6 ps 1.2 lc rgb '#b03020' title 'unstable'"
                      : "");
        if (k < 0 || (size_t)k >= cap - len) {
            rc = tr_fail(err, TR_EINVAL, "plot script too long");
            goto out;
        }
        len += (size_t)k;
    }
    char path[4096];
    int m = snprintf(path, sizeof path, "%s/plots.gp", dir);
    if (m < 0 || (size_t)m >= sizeof path) {
        rc = tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
        goto out;
    }
    rc = tr_write_file_atomic(path, s, len, err);
out:
    if (rc != TR_OK) /* else the temporaries are the caller's now */
        tr_plot_discard(ps);
    free(s);
    return rc;
}
