/* This file contains the analysis's text outputs: CSV tables, summary.json and report.txt, built
 * as strings (analysis_report.h). */
#include "analysis/analysis_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/json.h"
#include "curve/polyline.h"
#include "util/text_file.h"
#include "util/vec3.h"

/* The paper's values (Przybyl & Pieranski 2014, N = 200640, m = 10;
 * docs/physics.md 5.3, 5.4). */
static const double P_L = 32.742934477, P_l1 = 0.158, P_l2 = 0.319, P_dk1 = 0.264, P_dk2 = 0.115,
                    P_da1 = 0.159, P_da2 = 0.062, P_err_l = 0.001, P_err_j = 0.005;
static const double P_c9m[9] = {0.189, 15.674, 32.370, 11.103, 26.588, 10.541, 22.018, 4.759, 21.455};
static const double P_c9p[9] = {32.554, 11.288, 27.984, 10.725, 22.202, 6.155, 21.640, 0.373, 17.069};

/* Every report is formatted into one growing string and handed over whole. */
static int sb_finish(tr_text *b, char **out)
{
    *out = tr_text_take(b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}

static void sb_num(tr_text *b, double v)
{
    tr_json_number(b, "%.10g", v);
}

/* "m = 1 (...)": which averaging block was used and why, so a reader of
 * the report knows whether the paper's window or the caller chose it. */
static void sb_m_reason(tr_text *b, const tr_analysis *a)
{
    double e = a->L / (double)a->n, r = TR_PAPER_WINDOW_ARCLENGTH / e;
    if (!a->m_default)
        tr_text_printf(b, "m = %zu (given; the paper's window of arclength %.4g is %.3g edges e = %.4g)", a->m,
                       TR_PAPER_WINDOW_ARCLENGTH, r, e);
    else
        tr_text_printf(b, "m = %zu (the paper's window of arclength %.4g at e = %.4g: max(1, round(%.3g))%s)",
                       a->m, TR_PAPER_WINDOW_ARCLENGTH, e, r,
                       a->m < floor(r + 0.5) ? ", at most N/4" : "");
}

int tr_report_curvature_csv(const tr_analysis *a, char **out)
{
    tr_text b = {0};
    double six = a->L / 6.0;
    tr_text_printf(&b, "# inscribed-arc knot K_c^(%zu) of the %zu-averaged polygon; l from the origin\n",
              a->m, a->m);
    tr_text_printf(&b, "arc,l,l_reduced,sector,kappa,arc_length\n");
    for (size_t k = 0; k < a->prof.n; k++) {
        int sec = 0;
        double r = a->sym.verdict == TR_SYM_D3 ? tr_symmetry_reduce(a->prof.pos[k], a->L, &sec)
                                               : a->prof.pos[k];
        (void)six;
        tr_text_printf(&b, "%zu,%.12g,%.12g,%d,%.12g,%.6g\n", k, a->prof.pos[k], r, sec, a->prof.kappa[k],
                  a->prof.dl[k]);
    }
    return sb_finish(&b, out);
}

int tr_report_torsion_csv(const tr_analysis *a, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "# torsion at the junctions of K_c^(%zu): angle between osculating planes phi, "
                  "tau = phi/h, accumulated alpha (from the origin)\n",
              a->m);
    tr_text_printf(&b, "junction,l,l_reduced,sector,phi,tau,alpha\n");
    /* alpha from the origin: start the sum at the first junction after l = 0 */
    size_t n = a->prof.n, k0 = 0;
    double lo = INFINITY;
    for (size_t k = 0; k < n; k++)
        if (a->prof.jpos[k] < lo)
            lo = a->prof.jpos[k], k0 = k;
    double alpha = 0.0;
    for (size_t j = 0; j < n; j++) {
        size_t k = (k0 + j) % n;
        alpha += a->prof.phi[k];
        int sec = 0;
        double r = a->sym.verdict == TR_SYM_D3 ? tr_symmetry_reduce(a->prof.jpos[k], a->L, &sec)
                                               : a->prof.jpos[k];
        tr_text_printf(&b, "%zu,%.12g,%.12g,%d,%.10g,%.10g,%.12g\n", k, a->prof.jpos[k], r, sec,
                  a->prof.phi[k], a->prof.tau[k], alpha);
    }
    return sb_finish(&b, out);
}

int tr_report_plateaus_csv(const tr_analysis *a, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "first_arc,last_arc,l1,l2,width\n");
    for (size_t i = 0; i < a->nplateaus; i++) {
        const tr_plateau *p = &a->plateaus[i];
        tr_text_printf(&b, "%zu,%zu,%.10g,%.10g,%.10g\n", p->first, p->last, p->l1, p->l2,
                  tr_wrap(p->l2 - p->l1, a->L));
    }
    return sb_finish(&b, out);
}

int tr_report_symmetry_csv(const tr_analysis *a, char **out)
{
    tr_text b = {0};
    const tr_symmetry *s = &a->sym;
    tr_text_printf(&b, "element,l,axis_x,axis_y,axis_z,angle,rms,rms_over_rg\n");
    tr_text_printf(&b, "C3,,%.12g,%.12g,%.12g,%.12g,%.6g,%.6g\n", s->c3.axis[0], s->c3.axis[1],
              s->c3.axis[2], s->c3.angle, s->c3.rms, s->c3.rms / s->rg);
    for (size_t i = 0; i < s->n_twofold; i++) {
        const tr_twofold *t = &s->twofold[i];
        tr_text_printf(&b, "C2,%.12g,%.12g,%.12g,%.12g,%.12g,%.6g,%.6g\n",
                  tr_symmetry_from_origin(s, t->l), t->axis[0], t->axis[1], t->axis[2], t->angle,
                  t->rms, t->rms / s->rg);
    }
    return sb_finish(&b, out);
}

int tr_report_contacts_csv(const tr_analysis *a, const double *x, size_t n, char **out)
{
    tr_text b = {0};
    double *s = malloc((n + 1) * sizeof *s);
    if (!s)
        return TR_ENOMEM;
    tr_polyline_arclength(x, n, s);
    tr_text_printf(&b, "# struts: ends at l_i, l_j (from the origin), contact point = strut midpoint\n");
    tr_text_printf(&b, "l_i,l_j,dist,l_i_reduced,cx,cy,cz\n");
    for (size_t k = 0; k < a->npairs; k++) {
        const tr_contact_pair *p = &a->pairs[k];
        double pi[3], pj[3];
        tr_polyline_point_at(x, n, s, p->li + a->sym.origin, pi);
        tr_polyline_point_at(x, n, s, p->lj + a->sym.origin, pj);
        double r = a->sym.verdict == TR_SYM_D3 ? tr_symmetry_reduce(p->li, a->L, NULL) : p->li;
        tr_text_printf(&b, "%.12g,%.12g,%.15g,%.12g,%.12g,%.12g,%.12g\n", p->li, p->lj, p->dist, r,
                  0.5 * (pi[0] + pj[0]), 0.5 * (pi[1] + pj[1]), 0.5 * (pi[2] + pj[2]));
    }
    free(s);
    return sb_finish(&b, out);
}

static double power_eval(const tr_contact_fn *f, int power, double l)
{
    for (int k = 0; k < power; k++)
        l = tr_contact_fn_eval(f, l);
    return l;
}

int tr_report_sigma_csv(const tr_analysis *a, size_t samples, char **out)
{
    tr_text b = {0};
    if (!a->have_sigma)
        return sb_finish(&b, out);
    tr_text_printf(&b, "l,sigma_minus,sigma_plus,dsigma_minus,dsigma_plus,sigma_minus_pow%d\n", a->power);
    for (size_t k = 0; k < samples; k++) {
        double l = ((double)k + 0.5) * a->L / (double)samples;
        tr_text_printf(&b, "%.10g,%.10g,%.10g,%.8g,%.8g,%.10g\n", l,
                  tr_contact_fn_eval(&a->sigma_minus, l), tr_contact_fn_eval(&a->sigma_plus, l),
                  tr_contact_fn_slope(&a->sigma_minus, l), tr_contact_fn_slope(&a->sigma_plus, l),
                  power_eval(&a->sigma_minus, a->power, l));
    }
    return sb_finish(&b, out);
}

int tr_report_fixed_points_csv(const tr_analysis *a, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "l,l_reduced,slope,stable,cycle,order\n");
    for (size_t i = 0; i < a->nfixed; i++) {
        const tr_fixed_point *f = &a->fixed[i];
        double r = a->sym.verdict == TR_SYM_D3 ? tr_symmetry_reduce(f->l, a->L, NULL) : f->l;
        tr_text_printf(&b, "%.10g,%.10g,%.8g,%d,%d,%d\n", f->l, r, f->slope, f->stable, f->cycle,
                  f->order);
    }
    return sb_finish(&b, out);
}

int tr_report_is_trefoil_like(const tr_analysis *a, const tr_thickness *t)
{
    return a->sym.verdict == TR_SYM_D3 && t && isfinite(t->ropelength) &&
           fabs(t->ropelength - P_L) < 0.02 * P_L;
}

/* Members of cycle c in the order of successive actions of sigma-. */
static size_t cycle_members(const tr_analysis *a, size_t c, double *l)
{
    size_t m = 0;
    for (int o = 0; o < a->cycles[c].period; o++)
        for (size_t i = 0; i < a->nfixed; i++)
            if (a->fixed[i].cycle == (int)c && a->fixed[i].order == o)
                l[m++] = a->fixed[i].l;
    return m;
}

static void json_jump(tr_text *b, const char *name, const tr_jump_summary *j, int have, double paper,
                      int cmp)
{
    tr_text_printf(b, "    \"%s\": {\"at\": ", name);
    sb_num(b, have ? j->at : NAN);
    tr_text_printf(b, ", \"value\": ");
    sb_num(b, have ? j->jump : NAN);
    tr_text_printf(b, ", \"err\": ");
    sb_num(b, have ? j->err : NAN);
    tr_text_printf(b, ", \"images\": %d", have ? j->images : 0);
    if (cmp) {
        tr_text_printf(b, ", \"paper\": ");
        sb_num(b, paper);
        tr_text_printf(b, ", \"paper_err\": ");
        sb_num(b, P_err_j);
    }
    tr_text_printf(b, "}");
}

int tr_report_summary_json(const tr_analysis *a, const tr_report_ctx *ctx, char **out)
{
    tr_text b = {0};
    const tr_symmetry *s = &a->sym;
    int cmp = ctx->compare_paper;
    tr_text_printf(&b, "{\n  \"input\": ");
    tr_json_string(&b, ctx->input ? ctx->input : "");
    tr_text_printf(&b, ",\n  \"component\": %d,\n  \"vertices\": %zu,\n  \"m\": %zu,\n", ctx->component,
              a->n, a->m);
    /* why this m: the paper's arclength window over the edge, or given */
    tr_text_printf(&b, "  \"m_rule\": \"%s\", \"m_window_arclength\": ", a->m_default ? "paper_window" : "given");
    sb_num(&b, TR_PAPER_WINDOW_ARCLENGTH);
    tr_text_printf(&b, ", \"edge\": ");
    sb_num(&b, a->L / (double)a->n);
    tr_text_printf(&b, ",\n");
    tr_text_printf(&b, "  \"scale_to_unit_thickness\": ");
    sb_num(&b, ctx->scale);
    tr_text_printf(&b, ",\n  \"ropelength\": {");
    if (ctx->thick) {
        const tr_thickness *t = ctx->thick;
        tr_text_printf(&b, "\"length\": ");
        sb_num(&b, t->length);
        tr_text_printf(&b, ", \"minrad\": ");
        sb_num(&b, t->minrad);
        tr_text_printf(&b, ", \"dcsd\": ");
        sb_num(&b, t->dcsd);
        tr_text_printf(&b, ", \"thickness\": ");
        sb_num(&b, t->thickness);
        tr_text_printf(&b, ", \"ropelength\": ");
        sb_num(&b, t->ropelength);
        tr_text_printf(&b, ", \"L_p\": ");
        sb_num(&b, t->L_p);
        tr_text_printf(&b, ", \"L_c\": ");
        sb_num(&b, t->L_c);
        tr_text_printf(&b, ", \"L_a\": ");
        sb_num(&b, t->L_a);
    }
    tr_text_printf(&b, ", \"L_c_averaged\": ");
    sb_num(&b, a->prof.L_c);
    if (cmp)
        tr_text_printf(&b, ", \"paper_L_a\": %.12g", P_L);
    tr_text_printf(&b, "},\n  \"symmetry\": {\"verdict\": \"%s\", \"tol_rel\": ", tr_symmetry_name(s->verdict));
    sb_num(&b, s->tol);
    tr_text_printf(&b, ", \"rg\": ");
    sb_num(&b, s->rg);
    tr_text_printf(&b, ", \"c3_rms\": ");
    sb_num(&b, s->c3.rms);
    tr_text_printf(&b, ", \"c3_rms_rel\": ");
    sb_num(&b, s->c3.rms / s->rg);
    tr_text_printf(&b, ", \"c3_angle\": ");
    sb_num(&b, s->c3.angle);
    tr_text_printf(&b, ", \"c3_axis\": [");
    for (int k = 0; k < 3; k++) {
        tr_text_printf(&b, "%s", k ? ", " : "");
        tr_json_number(&b, "%.12g", s->c3.axis[k]);
    }
    tr_text_printf(&b, "]");
    tr_text_printf(&b, ", \"twofold_points\": %zu, \"twofold_rms_max\": ", s->n_twofold);
    sb_num(&b, s->twofold_rms_max);
    tr_text_printf(&b, ", \"twofold_rms_best\": ");
    sb_num(&b, s->twofold_rms_best);
    tr_text_printf(&b, ", \"origin_input_arclength\": ");
    sb_num(&b, s->origin);
    tr_text_printf(&b, ", \"L\": ");
    sb_num(&b, a->L);
    tr_text_printf(&b, "},\n  \"plateaus\": {\"count\": %zu, \"l1\": ", a->nplateaus);
    sb_num(&b, a->have_l12 ? a->l1 : NAN);
    tr_text_printf(&b, ", \"l1_err\": ");
    sb_num(&b, a->have_l12 ? a->l1_err : NAN);
    tr_text_printf(&b, ", \"l2\": ");
    sb_num(&b, a->have_l12 ? a->l2 : NAN);
    tr_text_printf(&b, ", \"l2_err\": ");
    sb_num(&b, a->have_l12 ? a->l2_err : NAN);
    if (cmp)
        tr_text_printf(&b, ", \"paper_l1\": %g, \"paper_l2\": %g, \"paper_err\": %g", P_l1, P_l2, P_err_l);
    tr_text_printf(&b, "},\n  \"jumps\": {\n    \"window_w\": ");
    sb_num(&b, a->jump_w);
    tr_text_printf(&b, ", \"window_W\": ");
    sb_num(&b, a->jump_W);
    tr_text_printf(&b, ",\n");
    json_jump(&b, "dkappa1", &a->dkappa1, a->have_l12, P_dk1, cmp);
    tr_text_printf(&b, ",\n");
    json_jump(&b, "dkappa2", &a->dkappa2, a->have_l12, P_dk2, cmp);
    tr_text_printf(&b, ",\n");
    json_jump(&b, "dalpha1", &a->dalpha1, a->have_l12, P_da1, cmp);
    tr_text_printf(&b, ",\n");
    json_jump(&b, "dalpha2", &a->dalpha2, a->have_l12, P_da2, cmp);
    for (size_t i = 0; i < a->n_extra; i++) {
        tr_text_printf(&b, ",\n");
        char nm[64];
        snprintf(nm, sizeof nm, "dkappa_at_%zu", i);
        json_jump(&b, nm, &a->extra_kappa[i], 1, NAN, 0);
        tr_text_printf(&b, ",\n");
        snprintf(nm, sizeof nm, "dalpha_at_%zu", i);
        json_jump(&b, nm, &a->extra_alpha[i], 1, NAN, 0);
    }
    tr_text_printf(&b, "\n  },\n  \"contacts\": {\"struts\": %zu, \"contact_functions\": %s", a->npairs,
              a->have_sigma ? "true" : "false");
    if (!a->have_sigma) {
        tr_text_printf(&b, ", \"why_not\": ");
        tr_json_string(&b, a->sigma_msg);
    } else {
        tr_text_printf(&b, ", \"sigma_inverse_err\": ");
        sb_num(&b, a->sigma_inverse_err);
        tr_text_printf(&b, ", \"rotation_number\": ");
        sb_num(&b, a->rotation_number);
        tr_text_printf(&b, ", \"power_minus_identity_min\": ");
        sb_num(&b, a->gap_min);
        tr_text_printf(&b, ", \"power_minus_identity_max\": ");
        sb_num(&b, a->gap_max);
        tr_text_printf(&b, ", \"power\": %d, \"fixed_points\": %zu, \"stable\": ", a->power, a->nfixed);
        size_t ns = 0;
        for (size_t i = 0; i < a->nfixed; i++)
            ns += a->fixed[i].stable;
        tr_text_printf(&b, "%zu, \"cycles\": [", ns);
        double *l = malloc((a->nfixed + 1) * sizeof *l);
        for (size_t c = 0; c < a->ncycles && l; c++) {
            size_t m = cycle_members(a, c, l);
            tr_text_printf(&b, "%s\n      {\"period\": %d, \"stable\": %d, \"members\": [", c ? "," : "",
                      a->cycles[c].period, a->cycles[c].stable);
            for (size_t i = 0; i < m; i++)
                tr_text_printf(&b, "%s%.6g", i ? ", " : "", l[i]);
            tr_text_printf(&b, "], \"reduced\": [");
            for (size_t i = 0; i < m; i++)
                tr_text_printf(&b, "%s%.6g", i ? ", " : "",
                          s->verdict == TR_SYM_D3 ? tr_symmetry_reduce(l[i], a->L, NULL) : l[i]);
            tr_text_printf(&b, "]}");
        }
        free(l);
        tr_text_printf(&b, "]");
        if (cmp) {
            tr_text_printf(&b, ", \"sigma_minus_at_0.189\": %.8g, \"paper_sigma_minus_at_0.189\": 15.674",
                      tr_contact_fn_eval(&a->sigma_minus, 0.189));
            tr_text_printf(&b, ", \"sigma_minus_at_0.3185\": %.8g, \"paper_sigma_minus_at_0.3185\": 16.7467",
                      tr_contact_fn_eval(&a->sigma_minus, 0.3185));
            tr_text_printf(&b, ", \"sigma_plus_at_0.189\": %.8g, \"paper_sigma_plus_at_0.189\": 21.455",
                      tr_contact_fn_eval(&a->sigma_plus, 0.189));
            tr_text_printf(&b, ", \"paper_fixed_points\": 18, \"paper_C9_minus\": [");
            for (int i = 0; i < 9; i++)
                tr_text_printf(&b, "%s%g", i ? ", " : "", P_c9m[i]);
            tr_text_printf(&b, "], \"paper_C9_plus\": [");
            for (int i = 0; i < 9; i++)
                tr_text_printf(&b, "%s%g", i ? ", " : "", P_c9p[i]);
            tr_text_printf(&b, "]");
        }
    }
    tr_text_printf(&b, "}\n}\n");
    return sb_finish(&b, out);
}

static void txt_val(tr_text *b, const char *name, double v, double e, int have, double pv, double pe,
                    int cmp)
{
    tr_text_printf(b, "  %-22s", name);
    if (have && isfinite(v))
        tr_text_printf(b, "%10.4f +- %-8.4f", v, e);
    else
        tr_text_printf(b, "%21s", "n/a");
    if (cmp)
        tr_text_printf(b, "   paper %.3f +- %.3f", pv, pe);
    tr_text_printf(b, "\n");
}

int tr_report_text(const tr_analysis *a, const tr_report_ctx *ctx, char **out)
{
    tr_text b = {0};
    const tr_symmetry *s = &a->sym;
    int cmp = ctx->compare_paper;
    tr_text_printf(&b, "shape analysis of %s, component %d: N = %zu, ", ctx->input, ctx->component, a->n);
    sb_m_reason(&b, a);
    tr_text_printf(&b, "\n");
    if (ctx->thick) {
        const tr_thickness *t = ctx->thick;
        tr_text_printf(&b, "  scaled by %.10g to thickness 1: length %.10g, MinRad %.10g, shortest strut %.10g,\n"
                      "  thickness %.10g, ropelength %.10g ",
                  ctx->scale, t->length, t->minrad, t->dcsd, t->thickness, t->ropelength);
        /* the paper's lengths exist only for near-equilateral polygons */
        if (isfinite(t->L_p) && isfinite(t->L_c) && isfinite(t->L_a))
            tr_text_printf(&b, "(L_p %.10g, L_c %.10g, L_a %.10g)\n", t->L_p, t->L_c, t->L_a);
        else
            tr_text_printf(&b, "(L_p, L_c, L_a: n/a, the polygon is not near-equilateral)\n");
        if (cmp)
            tr_text_printf(&b, "  paper (N = 200640): L_a = %.9f\n", P_L);
    }
    tr_text_printf(&b, "symmetry: %s  (C3 residual %.3g = %.3g rg, %zu twofold points, worst %.3g, "
                  "threshold %.3g rg)\n",
              tr_symmetry_name(s->verdict), s->c3.rms, s->c3.rms / s->rg, s->n_twofold,
              s->n_twofold ? s->twofold_rms_max : s->twofold_rms_best, s->tol);
    tr_text_printf(&b, "  origin at input arclength %.10g; positions below are from it\n", s->origin);
    tr_text_printf(&b, "curvature plateaus (kappa >= 1 - eps): %zu\n", a->nplateaus);
    txt_val(&b, "l1", a->l1, a->l1_err, a->have_l12, P_l1, P_err_l, cmp);
    txt_val(&b, "l2", a->l2, a->l2_err, a->have_l12, P_l2, P_err_l, cmp);
    txt_val(&b, "dkappa1", a->dkappa1.jump, a->dkappa1.err, a->have_l12, P_dk1, P_err_j, cmp);
    txt_val(&b, "dkappa2", a->dkappa2.jump, a->dkappa2.err, a->have_l12, P_dk2, P_err_j, cmp);
    txt_val(&b, "dalpha1", a->dalpha1.jump, a->dalpha1.err, a->have_l12, P_da1, P_err_j, cmp);
    txt_val(&b, "dalpha2", a->dalpha2.jump, a->dalpha2.err, a->have_l12, P_da2, P_err_j, cmp);
    tr_text_printf(&b, "  (one-sided quadratic fits on [l-%.4g, l-%.4g] and [l+%.4g, l+%.4g], lines on the inner\n"
                       "   %.4g of each as the model check)\n",
                   2.0 * a->jump_W - a->jump_w, a->jump_w, a->jump_w, 2.0 * a->jump_W - a->jump_w, a->jump_W - a->jump_w);
    for (size_t i = 0; i < a->n_extra; i++)
        tr_text_printf(&b, "  at l = %.6g: dkappa %.5f +- %.5f, dalpha %.5f +- %.5f\n",
                  a->extra_kappa[i].at, a->extra_kappa[i].jump, a->extra_kappa[i].err,
                  a->extra_alpha[i].jump, a->extra_alpha[i].err);
    tr_text_printf(&b, "contacts: %zu struts\n", a->npairs);
    if (!a->have_sigma) {
        tr_text_printf(&b, "  no contact functions: %s\n", a->sigma_msg);
    } else {
        size_t ns = 0;
        for (size_t i = 0; i < a->nfixed; i++)
            ns += a->fixed[i].stable;
        tr_text_printf(&b, "  max |sigma+(sigma-(l)) - l| = %.3g\n", a->sigma_inverse_err);
        if (cmp) /* paper: sigma-(0.189), sigma-(l2 = 0.3185), and sigma+(0.189) from C9- closing */
            tr_text_printf(&b, "  sigma-(0.189) = %.4f (paper 15.674), sigma-(0.3185) = %.4f (paper 16.7467), "
                          "sigma+(0.189) = %.4f (paper 21.455)\n",
                      tr_contact_fn_eval(&a->sigma_minus, 0.189),
                      tr_contact_fn_eval(&a->sigma_minus, 0.3185),
                      tr_contact_fn_eval(&a->sigma_plus, 0.189));
        tr_text_printf(&b, "  rotation number of sigma-: %.6f%s\n", a->rotation_number,
                  cmp ? "   (4/9 = 0.444444 for the paper's 9-cycles)" : "");
        tr_text_printf(&b, "  sigma-^%d(l) - l ranges over [%.4g, %.4g] (mod L)\n", a->power, a->gap_min,
                  a->gap_max);
        tr_text_printf(&b, "  fixed points of sigma-^%d: %zu (%zu stable)%s\n", a->power, a->nfixed, ns,
                  cmp ? "   paper: 18 (9 stable)" : "");
        double *l = malloc((a->nfixed + 1) * sizeof *l);
        for (size_t c = 0; c < a->ncycles && l; c++) {
            size_t m = cycle_members(a, c, l);
            tr_text_printf(&b, "  cycle %zu (period %d, %s):", c, a->cycles[c].period,
                      a->cycles[c].stable == 1 ? "stable" : a->cycles[c].stable == 0 ? "unstable" : "mixed");
            for (size_t i = 0; i < m; i++)
                tr_text_printf(&b, " %.3f", l[i]);
            tr_text_printf(&b, "\n");
        }
        free(l);
        if (cmp) {
            tr_text_printf(&b, "  paper C9-:");
            for (int i = 0; i < 9; i++)
                tr_text_printf(&b, " %.3f", P_c9m[i]);
            tr_text_printf(&b, "\n  paper C9+:");
            for (int i = 0; i < 9; i++)
                tr_text_printf(&b, " %.3f", P_c9p[i]);
            tr_text_printf(&b, "\n");
        }
    }
    return sb_finish(&b, out);
}
