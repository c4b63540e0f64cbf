/* The OpenCL backend against the serial reference, operation by operation,
 * on the same states: a simple clasp (two open ropes with ends on planes), a
 * trefoil and a two-component link (Hopf), at the smallest legal sizes, at
 * sizes that are (1024) and are not (1021) multiples of the work-group size;
 * then a whole tightening run of a few hundred steps on both backends, whose
 * ropelengths (measured by the thickness oracle) must agree to 1e-9.
 * Skips (77) without a usable OpenCL device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/backend.h"
#include "backend/opencl/backend_opencl.h"
#include "backend/opencl/cl_device.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "testlib.h"
#include "oracle/thickness.h"

/* Norm-wise comparison with a label; prints the worst difference on failure. */
static void compare(const char *what, const double *got, const double *want, size_t n, double rtol,
                    double atol)
{
    double diff;
    int ok = tr_test_allclose(got, want, n, rtol, atol, &diff);
    if (!ok) {
        tr_test_failures++;
        fprintf(stderr, "%s: max |got - want| = %.3g exceeds rtol %.1g atol %.1g\n", what, diff, rtol,
                atol);
    }
}

static void compare1(const char *what, double got, double want, double rtol)
{
    double g[1] = {got}, w[1] = {want};
    if (isinf(got) && isinf(want) && got == want)
        return;
    compare(what, g, w, 1, rtol, 0.0);
}

typedef struct pair {
    tr_backend ref, dev;
    size_t nv;
    int ncomp;
    double *xr, *xd;
} pair;

static int open_pair(pair *p, const tr_curve *c)
{
    tr_error err;
    memset(p, 0, sizeof *p);
    if (tr_backend_open("reference", c, &p->ref, &err) != TR_OK ||
        tr_backend_opencl_open("opencl", c, &p->dev, &err) != TR_OK) {
        fprintf(stderr, "open: %s\n", err.msg);
        tr_test_failures++;
        return 0;
    }
    p->nv = c->nv;
    p->ncomp = c->ncomp;
    p->xr = malloc(3 * c->nv * sizeof(double));
    p->xd = malloc(3 * c->nv * sizeof(double));
    return 1;
}

static void close_pair(pair *p)
{
    tr_backend_close(&p->ref);
    tr_backend_close(&p->dev);
    free(p->xr);
    free(p->xd);
}

/* Positions of both backends: rtol relative to the largest coordinate. */
static void compare_x(pair *p, const char *what, double rtol)
{
    tr_error err;
    double er[8], ed[8];
    CHECK_OK(p->ref.ops->download(p->ref.state, p->xr, er, &err));
    CHECK_OK(p->dev.ops->download(p->dev.state, p->xd, ed, &err));
    compare(what, p->xd, p->xr, 3 * p->nv, rtol, 0.0);
    char w2[128];
    snprintf(w2, sizeof w2, "%s (ebar)", what);
    compare(w2, ed, er, (size_t)p->ncomp, rtol, 0.0);
}

static void compare_measure(pair *p, const char *what)
{
    tr_error err;
    tr_measure mr, md;
    double lr[8], ld[8];
    CHECK_OK(p->ref.ops->measure(p->ref.state, &mr, lr, NULL, &err));
    CHECK_OK(p->dev.ops->measure(p->dev.state, &md, ld, NULL, &err));
    char w[160];
    /* Lengths: the reference sums edges one after another, the device in a
     * tree (Neumaier across work-groups); each sum of n positive terms is off
     * by at most n eps of the total, n <= 2048 here: 2048 * 1.1e-16 = 2.3e-13. */
    snprintf(w, sizeof w, "%s: length", what);
    compare1(w, md.length, mr.length, 2.5e-13);
    snprintf(w, sizeof w, "%s: component lengths", what);
    compare(w, ld, lr, (size_t)p->ncomp, 2.5e-13, 0.0);
    /* Per-item values computed with the same operations (no contraction):
     * max/min of identical numbers, identical bits. */
    snprintf(w, sizeof w, "%s: edge_dev", what);
    compare1(w, md.edge_dev, mr.edge_dev, 0.0);
    snprintf(w, sizeof w, "%s: min_minrad", what);
    compare1(w, md.min_minrad, mr.min_minrad, 0.0);
    snprintf(w, sizeof w, "%s: min_strut", what);
    compare1(w, md.min_strut, mr.min_strut, 0.0);
    snprintf(w, sizeof w, "%s: max_disp", what);
    compare1(w, md.max_disp, mr.max_disp, 0.0);
}

static const tr_correct_params correct_params = {
    .max_newton = 8, .max_cg = 200, .cg_rtol = 1e-10, .viol_tol = 1e-11, .active_strut = 0.01,
    .active_curv = 0.01, .strut_dist = 2.0, .minrad = 1.0, .ebar_weight = 1.0, .reg = 1e-12,
    .max_step = 0.05};

/* Every operation once on both backends, compared after each. */
static void ops_case(const char *name, const tr_curve *c, double cutoff, int cg_checks)
{
    pair p;
    if (!open_pair(&p, c))
        return;
    tr_error err;
    char w[160];
    const tr_backend_ops *R = p.ref.ops, *D = p.dev.ops;
    void *rs = p.ref.state, *ds = p.dev.state;

    snprintf(w, sizeof w, "%s n=%zu open", name, c->nv);
    compare_x(&p, w, 0.0); /* the same snapped start and ebar, bit for bit */
    compare_measure(&p, w);

    /* neighbour search: the same list (count, closest distance) */
    int gap[8];
    for (int k = 0; k < c->ncomp; k++)
        gap[k] = (int)ceil(3.14159265358979 / (tr_comp_length(c, k) / (double)tr_comp_ne(c, k)));
    tr_contact_params cp = {.cutoff = cutoff, .exclude_gap = gap};
    tr_contact_stats csr, csd;
    CHECK_OK(R->find_contacts(rs, &cp, &csr, &err));
    CHECK_OK(D->find_contacts(ds, &cp, &csd, &err));
    CHECK(csr.pairs == csd.pairs);
    snprintf(w, sizeof w, "%s n=%zu contacts min", name, c->nv);
    compare1(w, csd.min_dist, csr.min_dist, 0.0);
    if (csr.pairs != csd.pairs)
        fprintf(stderr, "%s: %zu pairs on the device, %zu in the reference\n", w, csd.pairs, csr.pairs);
    /* the engine's tilted list (the same definition, evaluated alike) */
    {
        tr_contact_params ct = cp;
        ct.tilt = 0.1;
        tr_contact_stats ctr, ctd;
        CHECK_OK(R->find_contacts(rs, &ct, &ctr, &err));
        CHECK_OK(D->find_contacts(ds, &ct, &ctd, &err));
        CHECK(ctr.pairs == ctd.pairs && ctr.pairs <= csr.pairs);
        snprintf(w, sizeof w, "%s n=%zu tilted contacts min", name, c->nv);
        compare1(w, ctd.min_dist, ctr.min_dist, 0.0);
        CHECK_OK(R->find_contacts(rs, &cp, &csr, &err));
        CHECK_OK(D->find_contacts(ds, &cp, &csd, &err));
    }

    /* force evaluation: per-vertex arithmetic identical, so positions agree
     * bit for bit; the stats are sums (tree vs sequential): n eps relative */
    tr_tension_params tp = {.h = 0.05, .max_move = 0.01, .smooth_passes = 3};
    tr_tension_stats tsr, tsd;
    CHECK_OK(R->save(rs, &err));
    CHECK_OK(D->save(ds, &err));
    CHECK_OK(R->tension_step(rs, &tp, &tsr, &err));
    CHECK_OK(D->tension_step(ds, &tp, &tsd, &err));
    snprintf(w, sizeof w, "%s n=%zu tension", name, c->nv);
    compare_x(&p, w, 0.0);
    compare1(w, tsd.force2, tsr.force2, 2.5e-13);
    compare1(w, tsd.predicted, tsr.predicted, 2.5e-13);
    compare1(w, tsd.max_move, tsr.max_move, 0.0);
    compare_measure(&p, w);

    /* restore gives back the saved state on both */
    CHECK_OK(R->restore(rs, &err));
    CHECK_OK(D->restore(ds, &err));
    snprintf(w, sizeof w, "%s n=%zu restore", name, c->nv);
    compare_x(&p, w, 0.0);
    CHECK_OK(R->tension_step(rs, &tp, &tsr, &err));
    CHECK_OK(D->tension_step(ds, &tp, &tsd, &err));

    /* projection + curvature moments, one Gauss-Newton iteration. (1) One CG
     * iteration: per-row and per-vertex arithmetic is the reference's, only
     * the dot products and the per-component ebar sums are added in another
     * order (backend.h allows it): n eps of |y| terms that partly cancel;
     * 1e-12 of the coordinates bounds it with room. */
    tr_correct_stats crr, crd;
    tr_correct_params one = correct_params;
    one.max_newton = 1;
    one.max_cg = 1;
    CHECK_OK(R->save(rs, &err));
    CHECK_OK(D->save(ds, &err));
    CHECK_OK(R->correct(rs, &one, &crr, &err));
    CHECK_OK(D->correct(ds, &one, &crd, &err));
    snprintf(w, sizeof w, "%s n=%zu correct (1 cg)", name, c->nv);
    compare_x(&p, w, 1e-12);
    CHECK(crr.active_rows == crd.active_rows && crr.cg_iters == crd.cg_iters);
    compare1(w, crd.viol_before, crr.viol_before, 0.0);
    if (!cg_checks) {
        /* The triangle's curvature rows are violated by O(1): CG converges to
         * rounding within its 6 rows, and later iterations (and releases of
         * rows whose multiplier is rounding noise) are noise in both backends. */
        close_pair(&p);
        return;
    }
    /* (2) Two CG iterations: the reordered dot products now pass through the
     * CG recurrence (including the preconditioner's second application).
     * Beyond that the comparison measures CG's own rounding sensitivity, not
     * the port: on the 1021-vertex trefoil (far from converged, losing
     * orthogonality) the backends differ by 1e-16, 4e-16, 9e-16, 4e-13, 2e-9,
     * 3e-7 after 1..6 iterations; on the 1020-vertex Hopf link, converged to
     * 4e-15 after one iteration, the noise-driven second and third iterations
     * differ by 5e-13 and 6e-10 and agree again (3e-15) from the fourth. Two
     * iterations: 1e-11 of the coordinates. With the PCR edge-block solver
     * the preconditioner itself rounds differently (by eps times the block's
     * condition, ~n^2/pi^2 for the near-straight chain: 1e-11 at n = 1024),
     * which the Hopf link's noise-driven second iteration carries into y:
     * 1e-10 of the coordinates (observed 2.2e-11 relative), as for the
     * projected tension step below. The twisted factorisation eliminates
     * from both ends instead of one: the same eps-times-condition bound, so
     * PCR's tolerance. */
    const char *solver = tr_backend_opencl_tridiag(&p.dev);
    int pcr = strcmp(solver, "thomas") != 0; /* the reference's arithmetic, or not */
    CHECK_OK(R->restore(rs, &err));
    CHECK_OK(D->restore(ds, &err));
    one.max_cg = 2;
    CHECK_OK(R->correct(rs, &one, &crr, &err));
    CHECK_OK(D->correct(ds, &one, &crd, &err));
    {
        tr_measure mr;
        CHECK_OK(R->measure(rs, &mr, NULL, NULL, &err));
        double er[8], ed[8];
        CHECK_OK(R->download(rs, p.xr, er, &err));
        CHECK_OK(D->download(ds, p.xd, ed, &err));
        double scale = 0;
        for (size_t i = 0; i < 3 * p.nv; i++)
            scale = fmax(scale, fabs(p.xr[i]));
        (void)mr;
        snprintf(w, sizeof w, "%s n=%zu correct (2 cg)", name, c->nv);
        double tol = (pcr ? 1e-10 : 1e-11) * scale;
        compare(w, p.xd, p.xr, 3 * p.nv, 0.0, tol);
        compare(w, ed, er, (size_t)p.ncomp, 0.0, tol); /* ebar moves with dx */
    }
    CHECK(crr.active_rows == crd.active_rows);
    /* as the positions: their tolerance of |x| ~ 5, twice */
    compare(w, &crd.viol_after, &crr.viol_after, 1, 1e-6, pcr ? 1e-9 : 1e-10);
    printf("%s [%s]: pairs %zu, correct cg %d/%d viol %.2g -> %.2g / %.2g\n", w, solver, csr.pairs,
           crr.cg_iters, crd.cg_iters, crr.viol_before, crr.viol_after, crd.viol_after);

    /* force evaluation with the tangent projection (2b): the same rows, CG
     * and release of pulling rows; (a) one CG iteration per pass: only the
     * reordered dot products differ, 1e-12 of the coordinates; the ebar
     * velocity and the resolved force as well. */
    /* Start both from the reference's state (the ten-CG correction above
     * left them ~1e-9 apart in the ill-conditioned cases). */
    {
        double eb[8];
        CHECK_OK(R->download(rs, p.xr, eb, &err));
        CHECK_OK(R->upload(rs, p.xr, eb, &err));
        CHECK_OK(D->upload(ds, p.xr, eb, &err));
        CHECK_OK(R->find_contacts(rs, &cp, &csr, &err));
        CHECK_OK(D->find_contacts(ds, &cp, &csd, &err));
        CHECK(csr.pairs == csd.pairs);
    }
    CHECK_OK(R->save(rs, &err));
    CHECK_OK(D->save(ds, &err));
    tr_correct_params proj = correct_params;
    proj.max_newton = 2;
    proj.max_cg = 1;
    tp.project = &proj;
    CHECK_OK(R->tension_step(rs, &tp, &tsr, &err));
    CHECK_OK(D->tension_step(ds, &tp, &tsd, &err));
    snprintf(w, sizeof w, "%s n=%zu tension projected (1 cg)", name, c->nv);
    compare_x(&p, w, 1e-12);
    compare1(w, tsd.smooth2, tsr.smooth2, 2.5e-13);
    compare1(w, tsd.free2, tsr.free2, 1e-12);
    /* (b) two CG iterations per pass: as for correct (2 cg) above */
    CHECK_OK(R->restore(rs, &err));
    CHECK_OK(D->restore(ds, &err));
    proj.max_cg = 2;
    CHECK_OK(R->tension_step(rs, &tp, &tsr, &err));
    CHECK_OK(D->tension_step(ds, &tp, &tsd, &err));
    {
        /* scale of the step before projection: h |G|, G the smoothed force */
        double step = tp.h * sqrt(tsr.smooth2);
        double er[8], ed[8];
        CHECK_OK(R->download(rs, p.xr, er, &err));
        CHECK_OK(D->download(ds, p.xd, ed, &err));
        double scale = 0;
        for (size_t i = 0; i < 3 * p.nv; i++)
            scale = fmax(scale, fabs(p.xr[i]));
        snprintf(w, sizeof w, "%s n=%zu tension projected (2 cg)", name, c->nv);
        /* the projection cancels most of G (the Hopf link's edges take up
         * nearly all of the force), so the comparison is against the
         * coordinates, 1e-10 (observed 2e-10 of |x| ~ 5 at worst) */
        (void)step;
        compare(w, p.xd, p.xr, 3 * p.nv, 0.0, 1e-10 * scale);
        compare(w, ed, er, (size_t)p.ncomp, 0.0, 1e-10 * scale);
        compare(w, &tsd.free2, &tsr.free2, 1, 1e-9, 1e-10 * tsr.smooth2);
    }
    close_pair(&p);
}

/* A few hundred steps of a plain tightening loop on both backends. */
static void run_case(const char *name, const tr_curve *c, int steps, double h)
{
    pair p;
    if (!open_pair(&p, c))
        return;
    tr_error err;
    int gap[8];
    for (int k = 0; k < c->ncomp; k++)
        gap[k] = (int)ceil(3.14159265358979 / (tr_comp_length(c, k) / (double)tr_comp_ne(c, k)));
    tr_contact_params cp = {.cutoff = 2.5, .exclude_gap = gap};
    tr_tension_params tp = {.h = h, .max_move = 0.01, .smooth_passes = 2};
    tr_backend *b[2] = {&p.ref, &p.dev};
    for (int which = 0; which < 2; which++) {
        const tr_backend_ops *o = b[which]->ops;
        void *st = b[which]->state;
        for (int s = 0; s < steps; s++) {
            tr_contact_stats cs;
            tr_tension_stats ts;
            tr_correct_stats cr;
            if (s % 10 == 0)
                CHECK_OK(o->find_contacts(st, &cp, &cs, &err));
            CHECK_OK(o->tension_step(st, &tp, &ts, &err));
            CHECK_OK(o->correct(st, &correct_params, &cr, &err));
        }
    }
    /* converging corrections at every step: the trajectories stay within
     * rounding of each other (observed ~1e-13); the issue asks 1e-9 of the
     * ropelength, checked below with the thickness oracle */
    compare_x(&p, name, 1e-9);
    tr_curve cr, cd;
    CHECK_OK(tr_curve_copy(&cr, c, &err));
    CHECK_OK(tr_curve_copy(&cd, c, &err));
    CHECK_OK(p.ref.ops->download(p.ref.state, cr.x, NULL, &err));
    CHECK_OK(p.dev.ops->download(p.dev.state, cd.x, NULL, &err));
    tr_thickness tr, td;
    CHECK_OK(tr_thickness_measure(&cr, NULL, &tr, NULL, &err));
    CHECK_OK(tr_thickness_measure(&cd, NULL, &td, NULL, &err));
    tr_thickness t0;
    CHECK_OK(tr_thickness_measure(c, NULL, &t0, NULL, &err));
    printf("%s: %d steps, ropelength %.12f -> reference %.12f, opencl %.12f\n", name, steps,
           t0.ropelength, tr.ropelength, td.ropelength);
    CHECK_NEAR(td.ropelength, tr.ropelength, 1e-9);
    tr_curve_free(&cr);
    tr_curve_free(&cd);
    close_pair(&p);
}

int main(void)
{
    tr_error err;
    tr_device_choice ch;
    if (tr_device_select("opencl", &ch, &err) != TR_OK) {
        printf("no usable opencl device: skipped (%s)\n", err.msg);
        return TR_SKIP;
    }
    tr_curve c;
    /* smallest legal curves: a triangle, two open 2-vertex ropes */
    {
        size_t n = 3;
        unsigned char closed = 1;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
        const double tri[9] = {0, 0, 0, 3, 0, 0, 0, 4, 0};
        memcpy(c.x, tri, sizeof tri);
        ops_case("triangle", &c, 3.0, 0);
        tr_curve_free(&c);
        size_t nv[2] = {2, 2};
        unsigned char op[2] = {0, 0};
        CHECK_OK(tr_curve_alloc(&c, 2, nv, op, &err));
        const double ropes[12] = {0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 1};
        memcpy(c.x, ropes, sizeof ropes);
        ops_case("two segments", &c, 3.0, 1);
        tr_curve_free(&c);
    }
    /* A few vertices and every pair past the index gap listed: one index per
     * work-item (TIGHTROPE_CL_ITEMS=one) pads the chain rows' and the strut
     * rows' partial results to 64 each, more than the rows themselves. */
    {
        /* a 16-gon along T(2,3), scaled to mean edge 0.9: the index gap is
         * ceil(pi / 0.9) = 4, so 16 x 9 / 2 = 72 pairs */
        size_t n = 16;
        unsigned char closed = 1;
        CHECK_OK(tr_curve_alloc(&c, 1, &n, &closed, &err));
        double len = 0.0;
        for (size_t i = 0; i < n; i++) {
            double t = 2.0 * 3.14159265358979 * (double)i / (double)n;
            c.x[3 * i] = (2.0 + cos(3.0 * t)) * cos(2.0 * t);
            c.x[3 * i + 1] = (2.0 + cos(3.0 * t)) * sin(2.0 * t);
            c.x[3 * i + 2] = sin(3.0 * t);
        }
        for (size_t i = 0; i < n; i++) {
            size_t j = (i + 1) % n;
            len += sqrt(pow(c.x[3 * j] - c.x[3 * i], 2) + pow(c.x[3 * j + 1] - c.x[3 * i + 1], 2) +
                        pow(c.x[3 * j + 2] - c.x[3 * i + 2], 2));
        }
        for (size_t i = 0; i < 3 * n; i++)
            c.x[i] *= 0.9 * (double)n / len;
        ops_case("small trefoil", &c, 50.0, 0);
        tr_curve_free(&c);
    }
    /* TIGHTROPE_TEST_SMALL (Oclgrind): 253 and 256 are still several
     * work-groups, one not a multiple of the group size */
    const int small = tr_test_small();
    const size_t sizes[] = {120, small ? 253 : 1021, small ? 256 : 1024};
    const int big = small ? 256 : 1024;
    for (size_t s = 0; s < 3; s++) {
        if (tr_make_clasp(&c, sizes[s] / 2, 4.0, &err) == TR_OK) {
            ops_case("clasp", &c, 2.4, 1);
            tr_curve_free(&c);
        } else {
            tr_test_failures++;
            fprintf(stderr, "clasp: %s\n", err.msg);
        }
        if (tr_make_torus(&c, 2, 3, sizes[s], &err) == TR_OK) {
            ops_case("trefoil", &c, 2.6, 1);
            tr_curve_free(&c);
        } else {
            tr_test_failures++;
            fprintf(stderr, "trefoil: %s\n", err.msg);
        }
        if (tr_make_hopf(&c, sizes[s] / 2, &err) == TR_OK) {
            ops_case("hopf", &c, 2.6, 1);
            tr_curve_free(&c);
        } else {
            tr_test_failures++;
            fprintf(stderr, "hopf: %s\n", err.msg);
        }
    }
    /* A trefoil with constrained vertices inside the chain (a plane, a line,
     * a fixed point), where the CPU kernels' four-vertex blocks hold them:
     * block_flags' JT_FREE must send them through tr_project_motion. */
    if (tr_make_torus(&c, 2, 3, (size_t)big, &err) == TR_OK) {
        const int at[3] = {41, 82, 123};
        for (int m = 0; m < 3; m++) {
            const double *xv = c.x + 3 * at[m];
            tr_constraint k = {.kind = (tr_cst_kind)(TR_CST_PLANE - m), .id = m + 1,
                               .p = {xv[0], xv[1], xv[2]}, .u = {0.0, 0.0, 1.0}, .d = xv[2]};
            if (m == 1)
                k.u[0] = 1.0, k.u[2] = 0.0; /* the line through it along x */
            int ki = tr_curve_add_constraint(&c, &k, &err);
            CHECK(ki >= 0);
            if (ki >= 0)
                c.vcst[at[m]] = ki;
        }
        ops_case("constrained trefoil", &c, 2.6, 1);
        tr_curve_free(&c);
    } else {
        tr_test_failures++;
        fprintf(stderr, "constrained trefoil: %s\n", err.msg);
    }
    /* A tight trefoil (ropelength 32.74): thousands of listed pairs and
     * hundreds in the band of active struts, where the rows' local-minimum
     * test (rows_strut_min, with the neighbours' distances looked up in the
     * list where it holds them) decides which are active. */
    {
        char path[1024];
        snprintf(path, sizeof path, "%s/bench/data/trefoil_2400.vect", TR_SOURCE_DIR);
        if (tr_curve_read(path, TR_FORMAT_AUTO, &c, &err) == TR_OK) {
            /* small: the same knot at a quarter of its vertices, still
             * thousands of listed pairs */
            size_t quarter = c.nv / 4;
            tr_curve r;
            int rrc = small ? tr_resample(&c, &quarter, &r, &err) : TR_OK;
            CHECK_OK(rrc);
            if (small && rrc == TR_OK) {
                tr_curve_free(&c);
                c = r;
            }
            ops_case("tight trefoil", &c, 2.1, 1);
            tr_curve_free(&c);
        } else {
            tr_test_failures++;
            fprintf(stderr, "tight trefoil: %s\n", err.msg);
        }
    }
    /* small: a twentieth of the steps (two contact searches in the longer
     * runs); under Oclgrind the runs took two thirds of the test at a tenth */
    const int steps = small ? 20 : 1;
    if (tr_make_torus(&c, 2, 3, 96, &err) == TR_OK) {
        run_case("trefoil run", &c, 300 / steps, 0.01);
        tr_curve_free(&c);
    }
    if (tr_make_clasp(&c, 40, 4.0, &err) == TR_OK) {
        run_case("clasp run", &c, 300 / steps, 0.002);
        tr_curve_free(&c);
    }
    if (tr_make_hopf(&c, 48, &err) == TR_OK) {
        run_case("hopf run", &c, 200 / steps, 0.004);
        tr_curve_free(&c);
    }
    return tr_test_finish("test_opencl_backend");
}
