/* analyze on a simple clasp (two open ropes): each rope's anatomy, its
 * symmetry and the two ropes' congruence (analysis/clasp_*.h), and the
 * gnuplot run that draws the paper's Fig. 3 and Fig. 4 for a rope. */
#ifndef TIGHTROPE_CLI_CLASP_H
#define TIGHTROPE_CLI_CLASP_H

#include "analysis/clasp_report.h"

typedef struct tr_cli_clasp {
    tr_clasp_rope rope[2];
    tr_clasp_match sym[2], cong[2];
    int have_cong;
} tr_cli_clasp;

/* Both ropes' anatomies, and what can be compared: a rope whose anatomy is
 * not found says why in its summary, the rest stands. Errors are memory's. */
int tr_cli_clasp_read(const tr_arc_profile *p0, const tr_arc_profile *p1, tr_cli_clasp *c, tr_error *err);

/* What rope q's summary and report show (its own anatomy, the other's component number). */
tr_clasp_report tr_cli_clasp_view(const tr_cli_clasp *c, int q, const int comp[2]);

/* Writes DIR/plots.gp for rope r and has gnuplot draw DIR/clasp_curvature.png
 * and DIR/clasp_d1.png (its output in DIR/gnuplot.log). TR_EUNSUPPORTED if
 * gnuplot is missing, TR_EIO if it fails. */
int tr_cli_clasp_draw(const char *dir, const tr_clasp_rope *r, const char *title, tr_error *err);

#endif
