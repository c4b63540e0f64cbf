/* Text outputs of the clasp's anatomy: the "clasp" object of a rope's
 * summary.json, its part of report.txt, and pieces.csv (one row per piece
 * and half). The published values (clasp_anatomy.h) are set beside ours. */
#ifndef TR_CLASP_REPORT_H
#define TR_CLASP_REPORT_H

#include "analysis/clasp_anatomy.h"
#include "analysis/clasp_compare.h"
#include "util/text_file.h"

typedef struct tr_clasp_report {
    const tr_clasp_rope *rope;
    const tr_clasp_match *symmetry;   /* NULL when the anatomy was not found */
    const tr_clasp_match *congruence; /* NULL when either rope's anatomy was not found */
    int partner;                      /* the other rope's component */
} tr_clasp_report;

/* Appends `"clasp": {...}` (no separator before or after). */
void tr_clasp_json(tr_text *b, const tr_clasp_report *c);
/* Appends the report's lines. */
void tr_clasp_text(tr_text *b, const tr_clasp_report *c);
/* A malloc'd table in *out, or TR_ENOMEM. */
int tr_clasp_pieces_csv(const tr_clasp_rope *r, char **out);

#endif
