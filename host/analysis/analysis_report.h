/* Text outputs of the shape analysis: CSV tables, summary.json and a short
 * human-readable report, built as strings (the command writes them). The
 * paper's trefoil values (docs/physics.md 5.4) are set beside ours when asked. */
#ifndef TR_ANALYSIS_REPORT_H
#define TR_ANALYSIS_REPORT_H

#include "analysis/portrait.h"
#include "oracle/thickness.h"

typedef struct tr_report_ctx {
    const char *input;             /* file name */
    int component;                 /* which component */
    double scale;                  /* factor applied to reach thickness 1 */
    const tr_thickness *thick;     /* oracle figures of the scaled curve; may be NULL */
    int compare_paper;             /* set the paper's trefoil values beside ours */
} tr_report_ctx;

/* Each returns a malloc'd NUL-terminated string in *out, or TR_ENOMEM. */
int tr_report_curvature_csv(const tr_analysis *a, char **out);   /* per arc */
int tr_report_torsion_csv(const tr_analysis *a, char **out);     /* per junction */
int tr_report_plateaus_csv(const tr_analysis *a, char **out);
int tr_report_symmetry_csv(const tr_analysis *a, char **out);    /* the axes */
int tr_report_contacts_csv(const tr_analysis *a, const double *x, size_t n, char **out);
int tr_report_sigma_csv(const tr_analysis *a, size_t samples, char **out);
int tr_report_fixed_points_csv(const tr_analysis *a, char **out);
int tr_report_summary_json(const tr_analysis *a, const tr_report_ctx *ctx, char **out);
int tr_report_text(const tr_analysis *a, const tr_report_ctx *ctx, char **out);

/* Whether the knot looks like the paper's trefoil: D3 and ropelength within
 * 2% of 32.743. */
int tr_report_is_trefoil_like(const tr_analysis *a, const tr_thickness *t);

#endif
