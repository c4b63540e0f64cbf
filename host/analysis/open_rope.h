/* Open ropes in the portrait: the inscribed-arc curvature and
 * torsion of each open component along its arclength, with no averaging and
 * no turning angle at the two end vertices, and the tables, summary and report
 * that analyze writes for it (the same file names as a closed component's). */
#ifndef TR_OPEN_ROPE_H
#define TR_OPEN_ROPE_H

#include <stddef.h>

#include "analysis/analysis_report.h"
#include "analysis/arc_profile.h"
#include "analysis/clasp_report.h"
#include "util/error.h"

typedef struct tr_open_rope {
    size_t n;             /* vertices */
    double L;             /* polyline length */
    tr_arc_profile prof;  /* arcs at vertices 1 .. n - 2, positions from vertex 0 */
    double kappa_min, kappa_max, kappa_mean; /* over arcs, weighted by arc length */
    double tau_min, tau_max, tau_mean;       /* over junctions (plain mean of tau) */
    double total_torsion;                    /* sum of the junction angles */
} tr_open_rope;

/* x: open polyline of n >= 4 vertices. */
int tr_open_rope_analyze(const double *x, size_t n, tr_open_rope *out, tr_error *err);
void tr_open_rope_free(tr_open_rope *r);

/* Each returns a malloc'd string in *out, or TR_ENOMEM. clasp: the rope's
 * anatomy when it is one of a clasp's two ropes (clasp_report.h), else NULL. */
int tr_open_rope_curvature_csv(const tr_open_rope *r, char **out);
int tr_open_rope_torsion_csv(const tr_open_rope *r, char **out);
int tr_open_rope_summary_json(const tr_open_rope *r, const tr_report_ctx *ctx, const tr_clasp_report *clasp,
                              char **out);
int tr_open_rope_report_text(const tr_open_rope *r, const tr_report_ctx *ctx, const tr_clasp_report *clasp,
                             char **out);

#endif
