/* This file contains the whole portrait of one closed component: symmetry, averaged curvature
 * and torsion, plateaus, jumps, contacts (portrait.h). */
#include "analysis/portrait.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/polyline.h"

void tr_analysis_free(tr_analysis *a)
{
    if (!a)
        return;
    tr_averaged_knot_free(&a->avg);
    tr_arc_profile_free(&a->prof);
    free(a->plateaus);
    free(a->extra_kappa);
    free(a->extra_alpha);
    free(a->pairs);
    tr_contact_fn_free(&a->sigma_minus);
    tr_contact_fn_free(&a->sigma_plus);
    free(a->fixed);
    free(a->cycles);
    memset(a, 0, sizeof *a);
}

/* Images of a representative point r in [0, L/6) under D3: sector k holds
 * r + kL/6 (k even) or (k+1)L/6 - r (k odd); the direction of travel is
 * reversed in the odd sectors. Without D3 only r itself. */
static int images(const tr_analysis *a, double r, double *pos, int *rev)
{
    if (a->sym.verdict != TR_SYM_D3) {
        pos[0] = r;
        rev[0] = 0;
        return 1;
    }
    double six = a->L / 6.0;
    for (int k = 0; k < 6; k++) {
        pos[k] = tr_wrap(k % 2 == 0 ? r + k * six : (k + 1) * six - r, a->L);
        rev[k] = k % 2;
    }
    return 6;
}

/* plateau_sign: +1 if the plateau lies to the right of r in sector 0 (an
 * entry, l1), -1 if to the left (an exit, l2), 0 for no plateau convention. */
static int summarise_jump(const tr_analysis *a, tr_jump_quantity q, double r, int plateau_sign,
                          tr_jump_summary *out, tr_error *err)
{
    double pos[6], sum = 0.0, sum2 = 0.0, esum = 0.0;
    int rev[6], n = images(a, r, pos, rev), got = 0;
    memset(out, 0, sizeof *out);
    out->at = r;
    for (int k = 0; k < n; k++) {
        tr_jump j;
        if (tr_profile_measure_jump(&a->prof, q, pos[k], a->jump_w, a->jump_W, &j, err) != TR_OK)
            continue;
        double v = j.jump;
        if (q == TR_JUMP_KAPPA) {
            if (rev[k]) /* reversed travel: right and left swap */
                v = -v;
            if (plateau_sign < 0)
                v = -v;
        }
        sum += v, sum2 += v * v, esum += j.err * j.err;
        got++;
    }
    out->images = got;
    if (!got) {
        out->jump = out->err = NAN;
        return TR_EGEOMETRY;
    }
    out->jump = sum / got;
    double var = got > 1 ? fmax(0.0, (sum2 - got * out->jump * out->jump) / (got - 1)) : 0.0;
    out->err = sqrt(var + esum / got);
    return TR_OK;
}

size_t tr_analysis_default_m(double L, size_t n)
{
    if (n < 4 || !(L > 0) || !isfinite(L))
        return 1;
    /* s / e = s n / L, in double before any conversion: a curve given in
     * tiny units (a library caller's, not at thickness 1) would overflow size_t */
    double q = floor(TR_PAPER_WINDOW_ARCLENGTH * (double)n / L + 0.5);
    double cap = (double)(n / 4);
    if (!(q >= 1.0))
        return 1;
    return q > cap ? n / 4 : (size_t)q;
}

int tr_analyze_component(const double *x, size_t n, const tr_contact_pair *pairs, size_t npairs,
                         const tr_analysis_opts *opts, tr_analysis *out, tr_error *err)
{
    memset(out, 0, sizeof *out);
    tr_analysis_opts o = opts ? *opts : (tr_analysis_opts){0};
    if (!o.m) { /* a fixed arclength window, not a fixed count (tr_analysis_default_m) */
        double *s0 = malloc((n + 1) * sizeof *s0);
        if (!s0)
            return tr_fail(err, TR_ENOMEM, "out of memory");
        tr_polyline_arclength(x, n, s0);
        o.m = tr_analysis_default_m(s0[n], n);
        free(s0);
        out->m_default = 1;
    }
    if (!(o.plateau_eps > 0))
        o.plateau_eps = 1e-4;
    if (!o.plateau_min)
        o.plateau_min = 2;
    if (!(o.plateau_edge > 0))
        o.plateau_edge = 0.02;
    if (o.plateau_edge < o.plateau_eps)
        o.plateau_edge = o.plateau_eps;
    if (!o.power)
        o.power = 9;
    /* Caller's values that would make the analysis meaningless or unbounded;
     * the averaging block is checked by tr_shape_average. */
    if (o.power < 1 || o.power > TR_CONTACT_POWER_MAX)
        return tr_fail(err, TR_EINVAL, "functional power %d outside [1, %d]", o.power,
                       TR_CONTACT_POWER_MAX);
    if (!(o.plateau_eps < 1.0))
        return tr_fail(err, TR_EINVAL, "plateau tolerance %g must be below 1 (plateau level 1 - eps > 0)",
                       o.plateau_eps);
    if (o.plateau_min > n)
        return tr_fail(err, TR_EINVAL, "plateaus of at least %zu arcs on a knot of %zu vertices",
                       o.plateau_min, n);
    out->n = n;
    out->m = o.m;
    out->power = o.power;
    int rc;
    tr_symmetry_opts so = {o.sym_tol, 0};
    if ((rc = tr_symmetry_find(x, n, &so, &out->sym, err)) != TR_OK)
        return rc;
    double L = out->L = out->sym.L;
    double e = L / (double)n;
    if (o.contact_bin > 0 &&
        !(o.contact_bin >= TR_CONTACT_BIN_MIN_REL * L && o.contact_bin <= TR_CONTACT_BIN_MAX_REL * L)) {
        rc = tr_fail(err, TR_EINVAL, "contact-function bin %g outside [%g, %g] (L x %g to L x %g)",
                     o.contact_bin, TR_CONTACT_BIN_MIN_REL * L, TR_CONTACT_BIN_MAX_REL * L,
                     TR_CONTACT_BIN_MIN_REL, TR_CONTACT_BIN_MAX_REL);
        goto fail;
    }
    /* Origin from the curvature of the averaged knot near the twofold points. */
    tr_averaged_knot av0;
    if ((rc = tr_shape_average(x, n, o.m, 0, &av0, err)) != TR_OK)
        goto fail;
    tr_arc_profile p0;
    rc = tr_arc_profile_compute(av0.w, av0.n, av0.pos, av0.L, &p0, err);
    tr_averaged_knot_free(&av0);
    if (rc != TR_OK)
        goto fail;
    tr_symmetry_choose_origin(&out->sym, &p0);
    tr_arc_profile_free(&p0);
    /* Blocks aligned so that one is centred at the origin vertex. */
    double *s = malloc((n + 1) * sizeof *s);
    if (!s) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
        goto fail;
    }
    tr_polyline_arclength(x, n, s);
    size_t i0 = 0;
    double best = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double d = fabs(tr_wrap_signed(s[i] - out->sym.origin, L));
        if (d < best)
            best = d, i0 = i;
    }
    free(s);
    size_t first = (i0 + n - (o.m - 1) / 2) % n;
    if ((rc = tr_shape_average(x, n, o.m, first, &out->avg, err)) != TR_OK)
        goto fail;
    for (size_t k = 0; k < out->avg.n; k++)
        out->avg.pos[k] = tr_symmetry_from_origin(&out->sym, out->avg.pos[k]);
    if ((rc = tr_arc_profile_compute(out->avg.w, out->avg.n, out->avg.pos, L, &out->prof, err)) !=
        TR_OK)
        goto fail;

    /* Plateaus and their representative ends. */
    if ((rc = tr_profile_find_plateaus_margin(&out->prof, 1.0 - o.plateau_eps, 1.0 - o.plateau_edge,
                                              o.plateau_min, &out->plateaus, &out->nplateaus, err)) != TR_OK)
        goto fail;
    /* The inscribed-arc curvature of arc k uses two averaged edges and each
     * averaged vertex smears over m edges: a step in kappa is spread over
     * about +-1.5 m e, and a plateau end is known to half an arc, so the fits
     * start 2 m e away. The lines reach 0.03 or 4 m e further and the
     * quadratics twice that (profile_features.c): kappa is curved just
     * outside the plateau, and over 8 m e (the old reach) a line leaned by
     * more than the jumps' targets (the solver's N = 4800 trefoil: Delta
     * kappa_1 0.331 against 0.283 over 4 m e; the paper's 0.264). */
    out->jump_w = o.jump_w > 0 ? o.jump_w : 2.0 * o.m * e;
    out->jump_W = o.jump_W > 0 ? o.jump_W : out->jump_w + fmax(0.03, 4.0 * o.m * e);
    if (out->jump_W > 0.2 * L)
        out->jump_W = 0.2 * L;
    if (out->jump_w >= out->jump_W)
        out->jump_w = 0.5 * out->jump_W;
    {
        double s1 = 0, s1q = 0, s2 = 0, s2q = 0;
        int cnt = 0;
        for (size_t i = 0; i < out->nplateaus; i++) {
            double a = out->plateaus[i].l1, b = out->plateaus[i].l2;
            if (out->plateaus[i].first == 0 && out->plateaus[i].last == out->prof.n - 1)
                continue; /* the whole curve */
            double ra = a, rb = b;
            if (out->sym.verdict == TR_SYM_D3) {
                int ka, kb;
                ra = tr_symmetry_reduce(a, L, &ka);
                rb = tr_symmetry_reduce(b, L, &kb);
                if (ka != kb)
                    continue; /* straddles a twofold point: not a sector-I plateau */
                if (ra > rb) {
                    double t = ra;
                    ra = rb, rb = t;
                }
            } else {
                /* without D3: the plateau through the origin, else the first after it */
                size_t pick = 0;
                for (size_t q = 0; q < out->nplateaus; q++) {
                    const tr_plateau *P = &out->plateaus[q], *B = &out->plateaus[pick];
                    int through = P->l1 > P->l2, bthrough = B->l1 > B->l2;
                    if ((through && !bthrough) || (through == bthrough && P->l1 < B->l1))
                        pick = q;
                }
                if (i != pick)
                    continue;
            }
            s1 += ra, s1q += ra * ra, s2 += rb, s2q += rb * rb;
            cnt++;
        }
        if (cnt) {
            out->have_l12 = 1;
            out->l1 = s1 / cnt, out->l2 = s2 / cnt;
            out->l1_err = cnt > 1 ? sqrt(fmax(0.0, (s1q - cnt * out->l1 * out->l1) / (cnt - 1))) : 0.0;
            out->l2_err = cnt > 1 ? sqrt(fmax(0.0, (s2q - cnt * out->l2 * out->l2) / (cnt - 1))) : 0.0;
            /* one arc is the resolution of an end */
            out->l1_err = hypot(out->l1_err, 0.5 * o.m * e);
            out->l2_err = hypot(out->l2_err, 0.5 * o.m * e);
            tr_error jerr;
            summarise_jump(out, TR_JUMP_KAPPA, out->l1, +1, &out->dkappa1, &jerr);
            summarise_jump(out, TR_JUMP_KAPPA, out->l2, -1, &out->dkappa2, &jerr);
            summarise_jump(out, TR_JUMP_ALPHA, out->l1, 0, &out->dalpha1, &jerr);
            summarise_jump(out, TR_JUMP_ALPHA, out->l2, 0, &out->dalpha2, &jerr);
        }
    }
    if (o.n_jump_at) {
        out->extra_kappa = calloc(o.n_jump_at, sizeof *out->extra_kappa);
        out->extra_alpha = calloc(o.n_jump_at, sizeof *out->extra_alpha);
        if (!out->extra_kappa || !out->extra_alpha) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
            goto fail;
        }
        out->n_extra = o.n_jump_at;
        for (size_t i = 0; i < o.n_jump_at; i++) {
            tr_error jerr;
            summarise_jump(out, TR_JUMP_KAPPA, o.jump_at[i], 0, &out->extra_kappa[i], &jerr);
            summarise_jump(out, TR_JUMP_ALPHA, o.jump_at[i], 0, &out->extra_alpha[i], &jerr);
        }
    }

    /* Contacts. */
    if (npairs) {
        out->pairs = malloc(npairs * sizeof *out->pairs);
        if (!out->pairs) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory");
            goto fail;
        }
        for (size_t k = 0; k < npairs; k++) {
            out->pairs[k] = pairs[k];
            out->pairs[k].li = tr_symmetry_from_origin(&out->sym, pairs[k].li);
            out->pairs[k].lj = tr_symmetry_from_origin(&out->sym, pairs[k].lj);
        }
        out->npairs = npairs;
    }
    double bin = o.contact_bin > 0 ? o.contact_bin : fmax(4.0 * e, L / 4000.0);
    tr_error cerr;
    if (tr_contact_functions_build(out->pairs, out->npairs, L, bin, &out->sigma_minus,
                                   &out->sigma_plus, &cerr) != TR_OK) {
        snprintf(out->sigma_msg, sizeof out->sigma_msg, "%s", cerr.msg);
    } else {
        out->have_sigma = 1;
        double emax = 0.0;
        for (int k = 0; k < 2000; k++) {
            double l = (k + 0.5) * L / 2000.0;
            double b = tr_contact_fn_eval(&out->sigma_plus, tr_contact_fn_eval(&out->sigma_minus, l));
            emax = fmax(emax, fabs(tr_wrap_signed(b - l, L)));
        }
        out->sigma_inverse_err = emax;
        /* Rotation number: mean advance of the lift over many turns, after a
         * transient (on a mode-locked map the orbit first has to reach its
         * cycle; then the estimate is exact to rounding). */
        double y = 0.0;
        for (int k = 0; k < 1000; k++)
            y = tr_contact_fn_lift(&out->sigma_minus, y);
        double y0 = y;
        const int turns = 9 * 1000;
        for (int k = 0; k < turns; k++)
            y = tr_contact_fn_lift(&out->sigma_minus, y);
        out->rotation_number = (y - y0) / ((double)turns * L);
        out->gap_min = INFINITY, out->gap_max = -INFINITY;
        for (int k = 0; k < 4000; k++) {
            double l = (k + 0.5) * L / 4000.0, z = l;
            for (int q = 0; q < o.power; q++)
                z = tr_contact_fn_lift(&out->sigma_minus, z);
            double g = tr_wrap_signed(z - l, L);
            out->gap_min = fmin(out->gap_min, g);
            out->gap_max = fmax(out->gap_max, g);
        }
        if (tr_power_fixed_points(&out->sigma_minus, o.power, 20000, &out->fixed, &out->nfixed,
                                  &out->cycles, &out->ncycles, &cerr) != TR_OK) {
            out->have_sigma = 0;
            snprintf(out->sigma_msg, sizeof out->sigma_msg, "%s", cerr.msg);
        }
    }
    return TR_OK;
fail:
    tr_analysis_free(out);
    return rc;
}
