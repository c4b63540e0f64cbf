/* This file contains the clasp's anatomy as JSON, text and CSV (clasp_report.h). */
#include "analysis/clasp_report.h"

#include <math.h>
#include <stdlib.h>

#include "util/json.h"

static const char *const status_names[] = {"resolved", "dip", "unseen"};

/* The published width of a deep, NAN for the other pieces. */
static double published(int q, double *spfem)
{
    *spfem = q == TR_CLASP_D1 ? TR_CLASP_D1_SPFEM : NAN;
    return q == TR_CLASP_D1 ? TR_CLASP_D1_STAROSTIN : q == TR_CLASP_D2 ? TR_CLASP_D2_STAROSTIN : NAN;
}

static void key(tr_text *b, const char *sep, const char *name, double v)
{
    tr_text_printf(b, "%s\"%s\": ", sep, name);
    tr_json_number(b, "%.10g", v);
}

static void json_match(tr_text *b, const char *name, const tr_clasp_match *m, int partner)
{
    tr_text_printf(b, ",\n    \"%s\": {", name);
    if (partner >= 0)
        tr_text_printf(b, "\"with_component\": %d, ", partner);
    key(b, "", "boundary_diff", m->boundary_diff);
    tr_text_printf(b, ", \"boundary\": ");
    tr_json_string(b, m->boundary);
    key(b, ", ", "boundary_err", m->boundary_err);
    key(b, ", ", "kappa_max_diff", m->kappa_max_diff);
    key(b, ", ", "kappa_max_at", m->kappa_max_at);
    key(b, ", ", "kappa_rms_diff", m->kappa_rms_diff);
    key(b, ", ", "span", m->span);
    key(b, ", ", "length_diff", m->length_diff);
    tr_text_printf(b, "}");
}

void tr_clasp_json(tr_text *b, const tr_clasp_report *c)
{
    const tr_clasp_rope *r = c->rope;
    tr_text_printf(b, "\"clasp\": {\n    \"found\": %s", r->found ? "true" : "false");
    if (!r->found) {
        tr_text_printf(b, ", \"why\": ");
        tr_json_string(b, r->why);
        tr_text_printf(b, "}");
        return;
    }
    key(b, ",\n    ", "edge", r->e);
    tr_text_printf(b, ",\n    \"tip\": {");
    key(b, "", "l", r->tip);
    key(b, ", ", "err", r->tip_err);
    key(b, ", ", "middle", 0.5 * r->L);
    tr_text_printf(b, "},\n    \"shoulder\": {");
    key(b, "", "kappa", r->shoulder_kappa);
    key(b, ", ", "pair_dev", r->shoulder_pair_dev);
    key(b, ", ", "alternation", r->shoulder_alt);
    key(b, ", ", "published", TR_CLASP_SHOULDER_KAPPA);
    tr_text_printf(b, "},\n    \"kink\": {");
    key(b, "", "kappa", r->kink_kappa);
    key(b, ", ", "min", r->kink_min);
    key(b, ", ", "max", r->kink_max);
    key(b, ", ", "published", TR_CLASP_KINK_KAPPA);
    key(b, ", ", "width", r->kink_width);
    key(b, ", ", "err", r->kink_width_err);
    tr_text_printf(b, "},\n    \"halves\": [");
    for (int h = 0; h < 2; h++) {
        const tr_clasp_half *hf = &r->half[h];
        tr_text_printf(b, "%s\n      {\"end_vertex\": %zu", h ? "," : "", hf->end_vertex);
        key(b, ", ", "length", hf->length);
        tr_text_printf(b, ", \"pieces\": [");
        for (int q = 0; q < TR_CLASP_NPIECES; q++) {
            const tr_clasp_piece *pc = &hf->piece[q];
            tr_text_printf(b, "%s\n        {\"piece\": \"%s\", \"status\": \"%s\", \"resolved\": %s", q ? "," : "",
                           tr_clasp_piece_names[q], status_names[pc->status],
                           pc->status == TR_PIECE_RESOLVED ? "true" : "false");
            key(b, ", ", "from", pc->from);
            key(b, ", ", "from_err", pc->from_err);
            key(b, ", ", "to", pc->to);
            key(b, ", ", "to_err", pc->to_err);
            key(b, ", ", "width", pc->width);
            key(b, ", ", "err", pc->err);
            tr_text_printf(b, ", \"arcs\": %zu", pc->arcs);
            key(b, ", ", "kappa_min", pc->kappa_min);
            key(b, ", ", "kappa_mean", pc->kappa_mean);
            key(b, ", ", "kappa_max", pc->kappa_max);
            double spfem, pub = published(q, &spfem);
            if (isfinite(pub))
                key(b, ", ", "published", pub);
            if (isfinite(spfem))
                key(b, ", ", "sp_fem", spfem);
            if (pc->why[0]) {
                tr_text_printf(b, ", \"reason\": ");
                tr_json_string(b, pc->why);
            }
            tr_text_printf(b, "}");
        }
        tr_text_printf(b, "]}");
    }
    tr_text_printf(b, "]");
    if (c->symmetry)
        json_match(b, "symmetry", c->symmetry, -1);
    if (c->congruence)
        json_match(b, "congruence", c->congruence, c->partner);
    tr_text_printf(b, "\n  }");
}

static void text_piece(tr_text *b, const tr_clasp_piece *pc, int q)
{
    tr_text_printf(b, "    %-2s  ", tr_clasp_piece_names[q]);
    if (pc->status == TR_PIECE_UNSEEN)
        tr_text_printf(b, "not resolved: %s", pc->why);
    else
        tr_text_printf(b, "%.6f .. %.6f  width %.6f +- %.2g  (%zu arc%s, kappa %.4g .. %.4g)", pc->from, pc->to,
                       pc->width, pc->err, pc->arcs, pc->arcs == 1 ? "" : "s", pc->kappa_min, pc->kappa_max);
    if (pc->status == TR_PIECE_DIP)
        tr_text_printf(b, "\n          not resolved: %s", pc->why);
    double spfem, pub = published(q, &spfem);
    if (isfinite(pub))
        tr_text_printf(b, "%sStarostin %.2g%s", pc->status == TR_PIECE_RESOLVED ? "  " : "; ", pub,
                       isfinite(spfem) ? ", SP-FEM 0.008 at edge 0.00026" : "");
    tr_text_printf(b, "\n");
}

static void text_match(tr_text *b, const tr_clasp_match *m)
{
    tr_text_printf(b, "boundaries from the tip agree to %.2g (largest at %s, +- %.2g); pair-averaged kappa at equal "
                      "distances differs by at most %.3g (%.4g from the tip), rms %.2g, over %.4g",
                   m->boundary_diff, m->boundary, m->boundary_err, m->kappa_max_diff, m->kappa_max_at,
                   m->kappa_rms_diff, m->span);
}

void tr_clasp_text(tr_text *b, const tr_clasp_report *c)
{
    const tr_clasp_rope *r = c->rope;
    if (!r->found) {
        tr_text_printf(b, "clasp anatomy: not found: %s\n", r->why);
        return;
    }
    tr_text_printf(b, "clasp anatomy (docs/physics.md 6.2, 6.3): edge e = %.4g; positions are arclength from the "
                      "free end; a boundary is +- e/2 with the spread of its estimate\n", r->e);
    tr_text_printf(b, "  tip (middle of K) at l = %.6f +- %.2g from vertex 0 (the rope's middle: %.6f)\n", r->tip,
                   r->tip_err, 0.5 * r->L);
    for (int h = 0; h < 2; h++) {
        const tr_clasp_half *hf = &r->half[h];
        tr_text_printf(b, "  from vertex %zu to the tip (%.6f):\n", hf->end_vertex, hf->length);
        for (int q = 0; q < TR_CLASP_NPIECES; q++)
            text_piece(b, &hf->piece[q], q);
    }
    tr_text_printf(b, "  shoulder kappa %.7f (want 1/2): pair averages within %.2g of 1/2, alternating by +-%.2g\n",
                   r->shoulder_kappa, r->shoulder_pair_dev, r->shoulder_alt);
    tr_text_printf(b, "  kink kappa %.7f (want 1; %.7f .. %.7f), K %.6f +- %.2g wide across the tip\n", r->kink_kappa,
                   r->kink_min, r->kink_max, r->kink_width, r->kink_width_err);
    if (c->symmetry) {
        tr_text_printf(b, "  symmetry about the tip: ");
        text_match(b, c->symmetry);
        tr_text_printf(b, "; the halves' lengths differ by %.2g\n", c->symmetry->length_diff);
    }
    if (c->congruence) {
        tr_text_printf(b, "  congruence with component %d: ", c->partner);
        text_match(b, c->congruence);
        tr_text_printf(b, "; the ropes' lengths differ by %.4g (the clasp slides between the walls at no cost in "
                          "length: E takes the difference)\n", c->congruence->length_diff);
    }
}

int tr_clasp_pieces_csv(const tr_clasp_rope *r, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "# the clasp's pieces (docs/physics.md 6.2) on each half, from the free end at end_vertex to "
                       "the tip; from, to: arclength from that end; status resolved, dip (a straight piece narrower "
                       "than two edges, width from the turning it lacks) or unseen\n");
    tr_text_printf(&b, "half,end_vertex,piece,status,from,from_err,to,to_err,width,err,from_tip,to_tip,arcs,kappa_min,"
                       "kappa_mean,kappa_max\n");
    for (int h = 0; r->found && h < 2; h++)
        for (int q = 0; q < TR_CLASP_NPIECES; q++) {
            const tr_clasp_half *hf = &r->half[h];
            const tr_clasp_piece *pc = &hf->piece[q];
            tr_text_printf(&b, "%d,%zu,%s,%s,%.10g,%.3g,%.10g,%.3g,%.10g,%.3g,%.10g,%.10g,%zu,%.8g,%.8g,%.8g\n", h,
                           hf->end_vertex, tr_clasp_piece_names[q], status_names[pc->status], pc->from, pc->from_err,
                           pc->to, pc->to_err, pc->width, pc->err, hf->length - pc->from, hf->length - pc->to,
                           pc->arcs, pc->kappa_min, pc->kappa_mean, pc->kappa_max);
        }
    *out = tr_text_take(&b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}
