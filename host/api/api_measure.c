/* The public API's measures: the thickness oracle (thickness.h) and the
 * KKT certificate (kkt.h), the numbers `tightrope measure --json` prints. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "api/api_internal.h"
#include "oracle/kkt.h"
#include "oracle/thickness.h"

static void strut_out(const tr_strut *s, tightrope_strut *o)
{
    o->edges[0] = s->ei;
    o->edges[1] = s->ej;
    o->positions[0] = s->si;
    o->positions[1] = s->sj;
    o->length = s->dist;
}

int tightrope_measure(const tightrope_curve *h, int component, tightrope_measurement *out, tightrope_error *err)
{
    tr_error e = {{0}};
    if (!h || !out || component < -1 || component >= h->c.ncomp)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "no curve, no result or no component %d", component), &e);
    tr_thickness m;
    /* measure's --per-component: a knot's one component is the whole curve */
    int rc = component < 0 || h->c.ncomp == 1 ? tr_thickness_measure(&h->c, NULL, &m, NULL, &e)
                                              : tr_thickness_measure_component(&h->c, component, &m, &e);
    if (rc)
        return tr_api_fail(err, rc, &e);
    memset(out, 0, sizeof *out);
    out->vertices = m.vertices;
    out->length = m.length;
    out->minrad = m.minrad;
    out->dcsd = m.dcsd;
    out->thickness = m.thickness;
    out->ropelength = m.ropelength;
    out->L_p = m.L_p;
    out->L_c = m.L_c;
    out->L_a = m.L_a;
    out->minrad_vertex = m.minrad_vertex;
    out->has_shortest_strut = isfinite(m.dcsd);
    if (out->has_shortest_strut)
        strut_out(&m.shortest, &out->shortest_strut);
    return TIGHTROPE_OK;
}

int tightrope_struts(const tightrope_curve *h, double rel_tol, tightrope_strut **struts, size_t *n,
                     tightrope_error *err)
{
    tr_error e = {{0}};
    if (!h || !struts || !n || !(rel_tol >= 0.0))
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "struts need a curve, outputs and a tolerance >= 0"), &e);
    *struts = NULL;
    *n = 0;
    tr_thickness m;
    tr_strut_list sl = {0};
    tr_thickness_opts opts = {.strut_rel_tol = rel_tol};
    int rc = tr_thickness_measure(&h->c, &opts, &m, &sl, &e);
    if (rc) {
        tr_strut_list_free(&sl);
        return tr_api_fail(err, rc, &e);
    }
    tightrope_strut *s = malloc((sl.n ? sl.n : 1) * sizeof *s);
    if (!s) {
        tr_strut_list_free(&sl);
        return tr_api_fail(err, tr_fail(&e, TR_ENOMEM, "out of memory"), &e);
    }
    for (size_t i = 0; i < sl.n; i++)
        strut_out(&sl.s[i], &s[i]);
    *struts = s;
    *n = sl.n;
    tr_strut_list_free(&sl);
    return TIGHTROPE_OK;
}

void tightrope_free(void *p) { free(p); }

int tightrope_certify(const tightrope_curve *h, double band, tightrope_kkt *out, double *tension, double *unresolved,
                      tightrope_error *err)
{
    tr_error e = {{0}};
    if (!h || !out || band > 1.0 || band != band)
        return tr_api_fail(err, tr_fail(&e, TR_EINVAL, "certify needs a curve, a result and a band <= 1"), &e);
    tr_kkt_params p;
    tr_kkt_params_default(&p);
    if (band > 0.0)
        p.band = band;
    tr_kkt k;
    int rc = tr_kkt_certify_forces(&h->c, &p, &k, tension, unresolved, &e);
    if (rc)
        return tr_api_fail(err, rc, &e);
    memset(out, 0, sizeof *out);
    out->residual = k.residual;
    out->band = p.band;
    out->radius = k.radius;
    out->tension = k.force;
    out->strut_rows = k.strut_rows;
    out->strut_active = k.strut_active;
    out->minrad_rows = k.minrad_rows;
    out->minrad_active = k.minrad_active;
    out->strut_force_max = k.strut_force_max;
    out->optimality = k.optimality;
    out->converged = k.converged;
    return TIGHTROPE_OK;
}
