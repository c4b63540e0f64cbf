/* The public API's analyze: one component's portrait (portrait.h) or, for
 * an open rope, its profiles (open_rope.h), found as `tightrope analyze`
 * finds them (cli_analyze.c): the component alone, scaled to thickness 1,
 * its struts within the tolerance of the shortest as the contacts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis_report.h"
#include "analysis/contact_functions.h"
#include "analysis/open_rope.h"
#include "analysis/portrait.h"
#include "api/api_internal.h"
#include "oracle/thickness.h"

/* analyze's --strut-tol default: a converged knot's contact set */
#define DEFAULT_STRUT_TOL 1e-4

struct tightrope_analysis {
    int open;
    tr_analysis an;     /* closed */
    tr_open_rope rope;  /* open */
    double *contacts;   /* 3 per contact */
    size_t ncontacts;
    char *summary;
};

void tightrope_analysis_free(tightrope_analysis *a)
{
    if (!a)
        return;
    tr_analysis_free(&a->an);
    tr_open_rope_free(&a->rope);
    free(a->contacts);
    free(a->summary);
    free(a);
}

/* Component k of c alone, scaled to thickness 1 unless no_scale; *th its
 * oracle figures, with the struts within strut_tol of the shortest in sl. */
static int component_alone(const tr_curve *c, int k, int no_scale, double strut_tol, tr_curve *one, double *scale,
                           tr_thickness *th, tr_strut_list *sl, tr_error *e)
{
    int rc = tr_curve_component(one, c, k, e);
    if (rc)
        return rc;
    *scale = 1.0;
    if ((rc = tr_thickness_measure(one, NULL, th, NULL, e)))
        return rc;
    if (no_scale && tr_curve_scale_exponent(one))
        return tr_fail(e, TR_EINVAL, "component %d has thickness %.3g, too far from 1 to analyse in its own units; "
                                     "scale it", k, th->thickness);
    if (!no_scale) {
        if (!(th->thickness > 0) || !isfinite(th->thickness))
            return tr_fail(e, TR_EGEOMETRY, "component %d has no finite thickness", k);
        *scale = 1.0 / th->thickness;
        tr_curve_scale_by(one, *scale);
    }
    tr_thickness_opts to = {.strut_rel_tol = strut_tol};
    return tr_thickness_measure(one, &to, th, sl, e);
}

static int analyze_closed(tightrope_analysis *a, const tr_curve *one, const tr_thickness *th,
                          const tr_strut_list *sl, double strut_tol, size_t m, tr_error *e)
{
    size_t nv = one->nv;
    int rc;
    tr_contact_pair *pairs = NULL;
    size_t np = 0;
    double dmax = isfinite(th->dcsd) ? (1.0 + strut_tol) * th->dcsd : INFINITY;
    if ((rc = tr_contact_pairs_from_struts(one->x, nv, 0, sl->s, sl->n, dmax, &pairs, &np, e)))
        return rc;
    tr_analysis_opts ao = {.m = m};
    rc = tr_analyze_component(one->x, nv, pairs, np, &ao, &a->an, e);
    free(pairs);
    if (rc)
        return rc;
    a->ncontacts = a->an.npairs;
    if (!(a->contacts = malloc((a->ncontacts ? a->ncontacts : 1) * 3 * sizeof *a->contacts)))
        return tr_fail(e, TR_ENOMEM, "out of memory");
    for (size_t i = 0; i < a->ncontacts; i++) {
        a->contacts[3 * i] = a->an.pairs[i].li;
        a->contacts[3 * i + 1] = a->an.pairs[i].lj;
        a->contacts[3 * i + 2] = a->an.pairs[i].dist;
    }
    return TR_OK;
}

int tightrope_analyze(const tightrope_curve *h, int component, const tightrope_analyze_options *opt,
                      tightrope_analysis **out, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!h || !out || component < 0 || component >= h->c.ncomp)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "analyze needs a curve, an output and a component in "
                                                        "[0, %d)", h ? h->c.ncomp : 0), &e);
    *out = NULL;
    tightrope_analyze_options o = {0};
    if (opt)
        o = *opt;
    double strut_tol = o.strut_tol > 0 ? o.strut_tol : DEFAULT_STRUT_TOL;
    if (strut_tol > 1.0)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "strut_tol %g: at most 1", strut_tol), &e);
    size_t nv = tr_comp_nv(&h->c, component);
    if (nv < 4 || (o.m && o.m > nv / 4))
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, nv < 4 ? "component %d has %zu vertices; analyze needs 4"
                                                              : "component %d: m at most N/4 = %zu",
                                        component, nv < 4 ? nv : nv / 4), &e);
    tightrope_analysis *a = calloc(1, sizeof *a);
    if (!a)
        return tr_api_fail(err, tr_fail(&e, TR_ENOMEM, "out of memory"), &e);
    a->open = !h->c.closed[component];
    tr_curve one = {0};
    tr_strut_list sl = {0};
    tr_thickness th;
    double scale;
    int rc = component_alone(&h->c, component, o.no_scale, strut_tol, &one, &scale, &th, &sl, &e);
    if (rc == TR_OK)
        rc = a->open ? tr_open_rope_analyze(one.x, one.nv, &a->rope, &e)
                     : analyze_closed(a, &one, &th, &sl, strut_tol, o.m, &e);
    if (rc == TR_OK) {
        tr_report_ctx ctx = {"", component, scale, &th, 0};
        if (!a->open)
            ctx.compare_paper = tr_report_is_trefoil_like(&a->an, &th);
        int fmt = a->open ? tr_open_rope_summary_json(&a->rope, &ctx, NULL, &a->summary)
                          : tr_report_summary_json(&a->an, &ctx, &a->summary);
        if (fmt)
            rc = tr_fail(&e, TR_ENOMEM, "out of memory");
    }
    tr_strut_list_free(&sl);
    tr_curve_free(&one);
    if (rc) {
        tightrope_analysis_free(a);
        return tr_api_fail(err, rc, &e);
    }
    *out = a;
    return TIGHTROPE_OK;
}

const double *tightrope_analysis_profile(const tightrope_analysis *a, tightrope_profile which, size_t *n)
{
    const tr_arc_profile *p = a->open ? &a->rope.prof : &a->an.prof;
    size_t dummy;
    if (!n)
        n = &dummy;
    *n = which <= TIGHTROPE_ARC_LENGTH ? p->n : p->nj;
    switch (which) {
    case TIGHTROPE_ARC_POSITION: return p->pos;
    case TIGHTROPE_ARC_CURVATURE: return p->kappa;
    case TIGHTROPE_ARC_LENGTH: return p->dl;
    case TIGHTROPE_JUNCTION_POSITION: return p->jpos;
    case TIGHTROPE_JUNCTION_TORSION: return p->tau;
    case TIGHTROPE_JUNCTION_ANGLE: return p->phi;
    case TIGHTROPE_JUNCTION_ACCUMULATED: return p->alpha;
    case TIGHTROPE_CONTACTS:
        *n = 3 * a->ncontacts;
        return a->contacts;
    }
    *n = 0;
    return NULL;
}

const char *tightrope_analysis_summary(const tightrope_analysis *a) { return a->summary; }
