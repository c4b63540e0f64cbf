/* This file contains the gnuplot script of the clasp's Fig. 3 and Fig. 4 (clasp_plots.h). */
#include "analysis/clasp_plots.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/text_file.h"

/* s as a gnuplot double-quoted string: '\\' and '"' escaped, a newline
 * written as \n (a title's second line). */
static void quoted(tr_text *b, const char *s)
{
    tr_text_printf(b, "\"");
    for (; *s; s++) {
        if (*s == '\\' || *s == '"')
            tr_text_printf(b, "\\%c", *s);
        else if (*s == '\n')
            tr_text_printf(b, "\\n");
        else
            tr_text_printf(b, "%c", *s);
    }
    tr_text_printf(b, "\"");
}

/* Dashed lines at half 0's boundaries inside [x0, x1], the pieces' names
 * above them (a deep's lower down: it is far narrower than its name), each
 * name kept inside the window. */
static void mark_pieces(tr_text *b, const tr_clasp_half *h, double x0, double x1)
{
    int arrow = 1;
    double pad = 0.04 * (x1 - x0);
    for (int q = 0; q < TR_CLASP_NPIECES; q++) {
        const tr_clasp_piece *pc = &h->piece[q];
        if (pc->status == TR_PIECE_UNSEEN || pc->to < x0 || pc->from > x1)
            continue;
        if (q > 0 && pc->from >= x0)
            tr_text_printf(b, "set arrow %d from %.15g, graph 0 to %.15g, graph 1 nohead dt 2 lc rgb 'gray40'\n",
                           arrow++, pc->from, pc->from);
        int deep = q == TR_CLASP_D1 || q == TR_CLASP_D2;
        double at = fmin(fmax(0.5 * (pc->from + pc->to), x0 + pad), x1 - pad);
        tr_text_printf(b, "set label %d '%s' at %.15g, graph %s center\n", q + 1, tr_clasp_piece_names[q], at,
                       deep ? "0.86" : "0.95");
    }
}

/* The caption's line about a deep (D1 or D2): its width and error, or why
 * it is not resolved, beside the published width. */
static void deep_caption(char *out, size_t size, const char *name, const char *between, const tr_clasp_piece *d,
                         double e, const char *published)
{
    if (d->status == TR_PIECE_RESOLVED)
        snprintf(out, size, "%s %.4g +- %.2g wide (%s)", name, d->width, d->err, published);
    else if (d->status != TR_PIECE_UNSEEN)
        snprintf(out, size, "%s %.4g +- %.2g wide, a dip narrower than two edges (e = %.3g): not resolved (%s)", name,
                 d->width, d->err, e, published);
    else
        snprintf(out, size, "%s not resolved: no dip between %s at e = %.3g (%s)", name, between, e, published);
}

/* One deep enlarged (the paper's Fig. 4 for D1; D2 likewise): the window
 * centred on it, or on where the pieces either side meet when no dip shows
 * (after), at least eight edges either side of it and min_half wide, the
 * deep shaded, each arc's curvature over its cell. */
static void deep_plot(tr_text *b, const char *png, const tr_clasp_rope *r, const char *title, int q, int after,
                      double min_half, double ymax, const char *what, const char *published)
{
    const tr_clasp_half *h = &r->half[0];
    const tr_clasp_piece *d = &h->piece[q];
    int seen = d->status != TR_PIECE_UNSEEN;
    double c = seen ? 0.5 * (d->from + d->to) : h->piece[after].to;
    double hw = fmax(min_half, 8.0 * r->e);
    char cap[512], t[1024];
    char between[32];
    snprintf(between, sizeof between, "%s and %s", tr_clasp_piece_names[after], tr_clasp_piece_names[q + 1]);
    deep_caption(cap, sizeof cap, tr_clasp_piece_names[q], between, d, r->e, published);
    tr_text_printf(b, "unset label\nunset arrow\nunset object\nset output '%s'\nset title ", png);
    snprintf(t, sizeof t, "%s: %s\n%s", title, what, cap);
    quoted(b, t);
    tr_text_printf(b, "\nset xrange [%.15g:%.15g]\nset yrange [-0.05:%.15g]\n", c - hw, c + hw, ymax);
    if (seen)
        tr_text_printf(b, "set object 1 rect from %.15g, graph 0 to %.15g, graph 1 fc rgb '#ffe0a0' fs solid 0.6 "
                          "noborder behind\n",
                       d->from, d->to);
    mark_pieces(b, h, c - hw, c + hw);
    tr_text_printf(b, "plot 'curvature.csv' every ::1 using (s0($2)):3 with histeps lw 2 lc rgb '#1f4e9c' title "
                      "'half from vertex 0: each arc over its cell', '' every ::1 using (s0($2)):3 with points pt 7 "
                      "ps 0.8 lc rgb '#1f4e9c' notitle, '' every ::1 using (s1($2)):3 with points pt 6 ps 1.4 lc "
                      "rgb '#e07020' title 'half from vertex %zu', 0.5 dt 3 lc rgb 'black' title 'kappa = 1/2'%s\n",
                   r->half[1].end_vertex, ymax > 1 ? ", 1 dt 3 lc rgb 'black' notitle" : "");
}

int tr_clasp_plots_script(const char *dir, const tr_clasp_rope *r, const char *title, tr_plot_script *ps,
                          tr_error *err)
{
    if (!r->found)
        return tr_fail(err, TR_EINVAL, "no clasp anatomy to plot: %s", r->why);
    static const char *const names[3] = {TR_CLASP_PLOT_CURVATURE, TR_CLASP_PLOT_D1, TR_CLASP_PLOT_D2};
    int rc = tr_plot_reserve(dir, names, 3, ps, err);
    if (rc != TR_OK)
        return rc;
    const tr_clasp_half *h = &r->half[0];

    tr_text b = {0};
    tr_text_printf(&b, "# written by tightrope analyze; run in this directory: gnuplot plots.gp\n"
                       "# (tightrope writes each plot to a temporary name and renames it when gnuplot is done)\n"
                       "set datafile separator ','\n"
                       "set datafile commentschars '#'\n"
                       "set terminal pngcairo size 1100,700 noenhanced font ',11'\n"
                       "L = %.15g; TIP = %.15g\n"
                       "s0(l) = (l <= TIP ? l : 1/0)      # half 0: arclength from vertex 0\n"
                       "s1(l) = (l >= TIP ? L - l : 1/0)  # half 1: from the last vertex\n"
                       "set grid\n"
                       "set key tmargin right horizontal\n"
                       "set xlabel 'arclength s from the free end'\n"
                       "set ylabel 'curvature kappa'\n",
                   r->L, r->tip);
    /* Fig. 3 */
    tr_text_printf(&b, "set output '%s'\nset title ", tr_plot_tmp_base(ps, dir, 0));
    char t[768];
    snprintf(t, sizeof t, "%s: curvature of half a rope, free end to tip (the paper's Fig. 3)", title);
    quoted(&b, t);
    tr_text_printf(&b, "\nset xrange [0:%.15g]\nset yrange [-0.05:1.12]\n", h->length);
    mark_pieces(&b, h, 0.0, h->length);
    tr_text_printf(&b, "plot 'curvature.csv' every ::1 using (s0($2)):3 with lines lw 2 lc rgb '#1f4e9c' title "
                       "'half from vertex 0', '' every ::1 using (s1($2)):3 with points pt 7 ps 0.3 lc rgb '#e07020' "
                       "title 'half from vertex %zu', 0.5 dt 3 lc rgb 'black' title 'kappa = 1/2, 1', 1 dt 3 lc rgb "
                       "'black' notitle\n",
                   r->half[1].end_vertex);
    /* Fig. 4, D1 between the shoulder (1/2) and G; and D2, which the
     * paper's edge (0.00026) could not resolve, between G and the kink (1):
     * 0.0004 wide, so its window is a tenth of D1's */
    deep_plot(&b, tr_plot_tmp_base(ps, dir, 1), r, title, TR_CLASP_D1, TR_CLASP_S, 0.02, 0.62,
              "the region of D1 enlarged (the paper's Fig. 4)", "Starostin 0.0078; SP-FEM 0.008");
    deep_plot(&b, tr_plot_tmp_base(ps, dir, 2), r, title, TR_CLASP_D2, TR_CLASP_G, 0.002, 1.12,
              "the region of D2 enlarged (between G and the kink)", "Starostin 0.0004");

    char path[4096];
    int m = snprintf(path, sizeof path, "%s/plots.gp", dir);
    if (m < 0 || (size_t)m >= sizeof path) {
        free(tr_text_take(&b, NULL));
        rc = tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
    } else {
        rc = tr_text_write_atomic(&b, path, err);
    }
    if (rc != TR_OK)
        tr_plot_discard(ps);
    return rc;
}
