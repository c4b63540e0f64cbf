/* This file contains analyze's part for a simple clasp: anatomy, comparisons, plots (cli_clasp.h). */
#include "cli/cli_clasp.h"

#include <string.h>

#include "analysis/clasp_plots.h"
#include "cli/cli_gnuplot.h"

int tr_cli_clasp_read(const tr_arc_profile *p0, const tr_arc_profile *p1, tr_cli_clasp *c, tr_error *err)
{
    memset(c, 0, sizeof *c);
    const tr_arc_profile *p[2] = {p0, p1};
    for (int q = 0; q < 2; q++) {
        int rc = tr_clasp_rope_anatomy(p[q], &c->rope[q], err);
        if (rc == TR_OK && c->rope[q].found)
            rc = tr_clasp_symmetry(p[q], &c->rope[q], &c->sym[q], err);
        if (rc != TR_OK)
            return rc;
    }
    c->have_cong = c->rope[0].found && c->rope[1].found;
    if (c->have_cong) {
        int rc = tr_clasp_congruence(p0, &c->rope[0], p1, &c->rope[1], &c->cong[0], err);
        if (rc == TR_OK)
            rc = tr_clasp_congruence(p1, &c->rope[1], p0, &c->rope[0], &c->cong[1], err);
        if (rc != TR_OK)
            return rc;
    }
    return TR_OK;
}

tr_clasp_report tr_cli_clasp_view(const tr_cli_clasp *c, int q, const int comp[2])
{
    return (tr_clasp_report){&c->rope[q], c->rope[q].found ? &c->sym[q] : NULL, c->have_cong ? &c->cong[q] : NULL,
                             comp[!q]};
}

int tr_cli_clasp_draw(const char *dir, const tr_clasp_rope *r, const char *title, tr_error *err)
{
    if (!tr_gnuplot_available())
        return tr_fail(err, TR_EUNSUPPORTED, "gnuplot not found on PATH (Debian package gnuplot-nox)");
    tr_plot_script ps;
    int rc = tr_clasp_plots_script(dir, r, title, &ps, err);
    if (rc != TR_OK)
        return rc;
    return tr_gnuplot_draw(dir, "plots.gp", "gnuplot.log", &ps, err);
}
