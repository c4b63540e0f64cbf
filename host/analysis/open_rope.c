/* This file contains the portrait of open ropes: per-rope curvature and
 * torsion profiles, their tables, summary and report (open_rope.h). */
#include "analysis/open_rope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/json.h"
#include "util/text_file.h"

void tr_open_rope_free(tr_open_rope *r)
{
    if (!r)
        return;
    tr_arc_profile_free(&r->prof);
    memset(r, 0, sizeof *r);
}

int tr_open_rope_analyze(const double *x, size_t n, tr_open_rope *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    int rc = tr_arc_profile_compute_open(x, n, &out->prof, err);
    if (rc != TR_OK)
        return rc;
    const tr_arc_profile *p = &out->prof;
    out->n = n;
    out->L = p->L;
    out->kappa_min = out->tau_min = INFINITY;
    out->kappa_max = out->tau_max = -INFINITY;
    double kw = 0.0, dl = 0.0;
    for (size_t k = 0; k < p->n; k++) {
        out->kappa_min = fmin(out->kappa_min, p->kappa[k]);
        out->kappa_max = fmax(out->kappa_max, p->kappa[k]);
        kw += p->kappa[k] * p->dl[k];
        dl += p->dl[k];
    }
    out->kappa_mean = dl > 0 ? kw / dl : 0.0;
    for (size_t k = 0; k < p->nj; k++) {
        out->tau_min = fmin(out->tau_min, p->tau[k]);
        out->tau_max = fmax(out->tau_max, p->tau[k]);
    }
    double ts = 0.0;
    for (size_t k = 0; k < p->nj; k++)
        ts += p->tau[k];
    out->total_torsion = p->nj ? p->alpha[p->nj - 1] : 0.0;
    out->tau_mean = p->nj ? ts / (double)p->nj : 0.0;
    return TR_OK;
}

static int finish(tr_text *b, char **out)
{
    *out = tr_text_take(b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}

int tr_open_rope_curvature_csv(const tr_open_rope *r, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "# open rope: inscribed-arc curvature at the %zu interior vertices (none at the ends); "
                       "l = arclength from the first vertex\n", r->prof.n);
    tr_text_printf(&b, "arc,l,kappa,arc_length\n");
    for (size_t k = 0; k < r->prof.n; k++)
        tr_text_printf(&b, "%zu,%.12g,%.12g,%.6g\n", k, r->prof.pos[k], r->prof.kappa[k], r->prof.dl[k]);
    return finish(&b, out);
}

int tr_open_rope_torsion_csv(const tr_open_rope *r, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "# open rope: torsion at the junctions between interior arcs: angle between osculating "
                       "planes phi, tau = phi/h, accumulated alpha from the first vertex\n");
    tr_text_printf(&b, "junction,l,phi,tau,alpha\n");
    for (size_t k = 0; k < r->prof.nj; k++)
        tr_text_printf(&b, "%zu,%.12g,%.10g,%.10g,%.12g\n", k, r->prof.jpos[k], r->prof.phi[k], r->prof.tau[k],
                       r->prof.alpha[k]);
    return finish(&b, out);
}

static void num(tr_text *b, const char *key, double v)
{
    tr_text_printf(b, "\"%s\": ", key);
    tr_json_number(b, "%.10g", v);
}

int tr_open_rope_summary_json(const tr_open_rope *r, const tr_report_ctx *ctx, const tr_clasp_report *clasp,
                              char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "{\n  \"input\": ");
    tr_json_string(&b, ctx->input ? ctx->input : "");
    tr_text_printf(&b, ",\n  \"component\": %d,\n  \"open\": true,\n  \"vertices\": %zu,\n  \"m\": 1,\n  ",
                   ctx->component, r->n);
    num(&b, "scale_to_unit_thickness", ctx->scale);
    tr_text_printf(&b, ",\n  \"ropelength\": {");
    num(&b, "length", r->L);
    if (ctx->thick) {
        tr_text_printf(&b, ", ");
        num(&b, "minrad", ctx->thick->minrad);
        tr_text_printf(&b, ", ");
        num(&b, "dcsd", ctx->thick->dcsd);
        tr_text_printf(&b, ", ");
        num(&b, "thickness", ctx->thick->thickness);
        tr_text_printf(&b, ", ");
        num(&b, "ropelength", ctx->thick->ropelength);
    }
    tr_text_printf(&b, ", ");
    num(&b, "L_c", r->prof.L_c);
    tr_text_printf(&b, "},\n  \"curvature\": {\"arcs\": %zu, ", r->prof.n);
    num(&b, "min", r->kappa_min);
    tr_text_printf(&b, ", ");
    num(&b, "max", r->kappa_max);
    tr_text_printf(&b, ", ");
    num(&b, "mean", r->kappa_mean);
    tr_text_printf(&b, "},\n  \"torsion\": {\"junctions\": %zu, ", r->prof.nj);
    num(&b, "min", r->tau_min);
    tr_text_printf(&b, ", ");
    num(&b, "max", r->tau_max);
    tr_text_printf(&b, ", ");
    num(&b, "mean", r->tau_mean);
    tr_text_printf(&b, ", ");
    num(&b, "total", r->total_torsion);
    tr_text_printf(&b, "}");
    if (clasp) {
        tr_text_printf(&b, ",\n  ");
        tr_clasp_json(&b, clasp);
    }
    tr_text_printf(&b, "\n}\n");
    return finish(&b, out);
}

int tr_open_rope_report_text(const tr_open_rope *r, const tr_report_ctx *ctx, const tr_clasp_report *clasp,
                             char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "%s, component %d: open rope, %zu vertices, length %.10g (scaled by %.10g)\n",
                   ctx->input ? ctx->input : "", ctx->component, r->n, r->L, ctx->scale);
    if (ctx->thick)
        tr_text_printf(&b, "thickness %.10g (minrad %.10g, dcsd %.10g), ropelength %.10g\n", ctx->thick->thickness,
                       ctx->thick->minrad, ctx->thick->dcsd, ctx->thick->ropelength);
    tr_text_printf(&b, "curvature over %zu interior arcs: min %.10g, max %.10g, mean %.10g\n", r->prof.n,
                   r->kappa_min, r->kappa_max, r->kappa_mean);
    tr_text_printf(&b, "torsion over %zu junctions: min %.10g, max %.10g, mean %.10g, total %.10g rad\n", r->prof.nj,
                   r->tau_min, r->tau_max, r->tau_mean, r->total_torsion);
    if (clasp)
        tr_clasp_text(&b, clasp);
    else
        tr_text_printf(&b, "(open ropes: profiles only; no symmetry, plateaus or contact functions)\n");
    return finish(&b, out);
}
