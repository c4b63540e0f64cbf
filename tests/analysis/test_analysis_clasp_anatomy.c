/* The clasp's anatomy (clasp_anatomy.h) on open curves built from pieces of
 * known length and curvature, sampled at equal arclength: a straight end E,
 * an arc of curvature 1/2 (S), a straight D1, a piece whose curvature grows
 * linearly (G), a straight D2 and an arc of curvature 1 (half of K), and the
 * same pieces mirrored after the tip. The closed form is the lengths the
 * curve is built with: every piece found within one edge of its length, the
 * tip at the middle, the shoulder and kink at 1/2 and 1. A curve sampled as
 * coarsely as the engine's 2 x 2000 clasp (edge 0.00714) with Starostin's D1
 * (0.0078) and D2 (0.0004): D1 a dip of about an edge, not resolved but
 * measured from the turning it lacks; D2 never reported as resolved. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/clasp_anatomy.h"
#include "analysis/clasp_compare.h"
#include "testlib.h"

typedef struct piece_def {
    double len, k0, k1; /* curvature from k0 to k1, linearly */
} piece_def;

typedef struct clasp_def {
    piece_def p[TR_CLASP_NPIECES]; /* from the end to the tip: E S D1 G D2 K/2 */
} clasp_def;

/* curvature at s along the whole rope (the half, then the half mirrored) */
static double kappa_at(const clasp_def *c, double s, double half)
{
    if (s > half)
        s = 2.0 * half - s;
    for (int q = 0; q < TR_CLASP_NPIECES; q++) {
        if (s <= c->p[q].len || q == TR_CLASP_NPIECES - 1)
            return c->p[q].k0 + (c->p[q].k1 - c->p[q].k0) * fmin(s / c->p[q].len, 1.0);
        s -= c->p[q].len;
    }
    return 0.0;
}

/* The planar curve sampled at n vertices equally spaced in arclength. The
 * tangent angle integrates kappa; the position integrates the tangent, by
 * Simpson's rule on 64 steps between neighbouring vertices, each step kept
 * inside one piece (kappa is linear on it, the integrand smooth). */
static double *build(const clasp_def *c, size_t n, double *total)
{
    double half = 0.0;
    for (int q = 0; q < TR_CLASP_NPIECES; q++)
        half += c->p[q].len;
    *total = 2.0 * half;
    double *x = calloc(3 * n, sizeof *x);
    double h = *total / (double)(n - 1), phi = 0.0, px = 0.0, py = 0.0, s = 0.0;
    /* breakpoints: the piece boundaries on both halves */
    double br[2 * TR_CLASP_NPIECES + 1];
    size_t nb = 0;
    double acc = 0.0;
    for (int q = 0; q < TR_CLASP_NPIECES; q++) {
        acc += c->p[q].len;
        br[nb++] = acc;
    }
    for (int q = TR_CLASP_NPIECES - 2; q >= 0; q--)
        br[nb++] = *total - br[q];
    for (size_t i = 1; i < n; i++) {
        double target = h * (double)i;
        while (s < target) {
            double next = target;
            for (size_t b = 0; b < nb; b++)
                if (br[b] > s + 1e-15 && br[b] < next)
                    next = br[b];
            int m = 64;
            double dt = (next - s) / m, sx = 0.0, sy = 0.0, ph = phi;
            double fx[65], fy[65];
            for (int j = 0; j <= m; j++) {
                double t = s + dt * j;
                if (j > 0) /* the angle by Simpson's rule on kappa over [t - dt, t] */
                    ph += dt / 6.0 *
                          (kappa_at(c, t - dt, half) + 4.0 * kappa_at(c, t - 0.5 * dt, half) + kappa_at(c, t, half));
                fx[j] = cos(ph), fy[j] = sin(ph);
            }
            for (int j = 0; j <= m; j++) {
                double wgt = j == 0 || j == m ? 1.0 : j % 2 ? 4.0 : 2.0;
                sx += wgt * fx[j], sy += wgt * fy[j];
            }
            px += sx * dt / 3.0, py += sy * dt / 3.0;
            phi = ph;
            s = next;
        }
        x[3 * i] = px, x[3 * i + 1] = py;
    }
    return x;
}

static void check_half(const tr_clasp_half *h, const clasp_def *c, double e, const char *what)
{
    double from = 0.0;
    for (int q = 0; q < TR_CLASP_NPIECES; q++) {
        const tr_clasp_piece *pc = &h->piece[q];
        double want = c->p[q].len;
        if (pc->status == TR_PIECE_UNSEEN) {
            tr_test_report(__FILE__, __LINE__, "%s: %s not seen: %s", what, tr_clasp_piece_names[q], pc->why);
            tr_test_failures++;
        } else {
            CHECK_NEAR(pc->width, want, e);
            CHECK_NEAR(pc->from, from, e);
            /* the uncertainty it states covers the error and is about an edge */
            CHECK(fabs(pc->width - want) <= pc->err && pc->err <= 2.0 * e);
        }
        printf("%s: %-2s width %.6f +- %.6f, built %.6f\n", what, tr_clasp_piece_names[q], pc->width, pc->err, want);
        from += want;
    }
    CHECK_NEAR(h->length, from, e);
}

/* The rope c built with n vertices (its length *total, edge *e), its
 * profile *p and its anatomy *r; returns the vertices (the caller frees). */
static double *anatomy_of(const clasp_def *c, size_t n, double *total, double *e, tr_arc_profile *p, tr_clasp_rope *r)
{
    double *x = build(c, n, total);
    *e = *total / (double)(n - 1);
    tr_error err;
    memset(r, 0, sizeof *r);
    if (tr_arc_profile_compute_open(x, n, p, &err) != 0) {
        /* r->found stays 0: the caller's check fails and says so */
        tr_test_report(__FILE__, __LINE__, "profile: %s", err.msg);
        memset(p, 0, sizeof *p);
        return x;
    }
    CHECK_OK(tr_clasp_rope_anatomy(p, r, &err));
    return x;
}

/* Everything resolved: 2 x 1525 vertices, edge 0.002; D1 15 edges wide, D2 6. */
static void test_resolved(void)
{
    clasp_def c = {{{1.0, 0, 0}, {0.8, 0.5, 0.5}, {0.03, 0, 0}, {1.2, 0.45, 0.65}, {0.012, 0, 0}, {0.15, 1, 1}}};
    size_t n = 3193;
    double total, e;
    tr_error err;
    tr_arc_profile p;
    tr_clasp_rope r;
    double *x = anatomy_of(&c, n, &total, &e, &p, &r);
    CHECK(r.found);
    if (!r.found) {
        tr_test_report(__FILE__, __LINE__, "not found: %s", r.why);
    } else {
        for (int h = 0; h < 2; h++) {
            check_half(&r.half[h], &c, e, h ? "resolved, half 1" : "resolved, half 0");
            CHECK(r.half[h].piece[TR_CLASP_D1].status == TR_PIECE_RESOLVED);
            CHECK(r.half[h].piece[TR_CLASP_D2].status == TR_PIECE_RESOLVED);
        }
        CHECK_NEAR(r.tip, 0.5 * total, e);
        CHECK_NEAR(r.kink_width, 2.0 * c.p[TR_CLASP_K].len, e);
        /* a polygon inscribed in a circle of radius R: 2 tan(theta/2)/e =
         * 1/R to (e/R)^2/12, 1e-6 here */
        CHECK_NEAR(r.shoulder_kappa, 0.5, 1e-5);
        CHECK_NEAR(r.kink_kappa, 1.0, 1e-5);
        tr_clasp_match sym;
        CHECK_OK(tr_clasp_symmetry(&p, &r, &sym, &err));
        /* mirrored by construction: equal to the curve's own integration error */
        CHECK(sym.boundary_diff < 1e-6 && sym.kappa_max_diff < 1e-6);
    }
    tr_arc_profile_free(&p);
    free(x);
}

/* As coarse as the engine's 2 x 2000 clasp, with Starostin's deeps: D1
 * (0.0078) about one edge, D2 (0.0004) a twentieth of one; four phases of
 * the sampling against the pieces. The other pieces are still within an
 * edge, D1 is a dip within an edge of 0.0078 and not resolved, D2 never
 * resolved; and the two differently sampled copies are congruent to the
 * stated uncertainties. */
static void test_coarse(void)
{
    size_t n = 2000;
    tr_clasp_rope first = {0};
    tr_arc_profile pfirst = {0};
    for (int phase = 0; phase < 4; phase++) {
        double le = 3.95 + 0.25 * phase * 0.00714;
        clasp_def c = {{{le, 0, 0},
                        {1.04, 0.5, 0.5},
                        {TR_CLASP_D1_STAROSTIN, 0, 0},
                        {2.0, 0.42, 0.66},
                        {TR_CLASP_D2_STAROSTIN, 0, 0},
                        {0.1335, 1, 1}}};
        double total, e;
        tr_error err;
        tr_arc_profile p;
        tr_clasp_rope r;
        free(anatomy_of(&c, n, &total, &e, &p, &r));
        CHECK(r.found);
        if (!r.found) {
            tr_test_report(__FILE__, __LINE__, "phase %d: not found: %s", phase, r.why);
            tr_arc_profile_free(&p);
            continue;
        }
        for (int h = 0; h < 2; h++) {
            const tr_clasp_half *hf = &r.half[h];
            const tr_clasp_piece *D1 = &hf->piece[TR_CLASP_D1], *D2 = &hf->piece[TR_CLASP_D2];
            printf("phase %d half %d: D1 %s %.5f +- %.5f (want %.5f), D2 %s\n", phase, h,
                   D1->status == TR_PIECE_RESOLVED ? "resolved" : D1->status == TR_PIECE_DIP ? "dip" : "unseen",
                   D1->width, D1->err, TR_CLASP_D1_STAROSTIN,
                   D2->status == TR_PIECE_RESOLVED ? "resolved" : D2->status == TR_PIECE_DIP ? "dip" : "unseen");
            CHECK(D1->status == TR_PIECE_DIP);
            /* the turning a dip lacks gives a straight piece's width up to
             * which side of it the straddled part of a cell is bent on:
             * e |kappa_S - kappa_G| / (kappa_S + kappa_G) = 0.09 e here */
            CHECK_NEAR(D1->width, TR_CLASP_D1_STAROSTIN, 0.1 * e);
            CHECK(fabs(D1->width - TR_CLASP_D1_STAROSTIN) <= D1->err);
            CHECK(D2->status != TR_PIECE_RESOLVED && D2->why[0] != '\0');
            for (int q = 0; q < TR_CLASP_NPIECES; q++) {
                const tr_clasp_piece *pc = &hf->piece[q];
                if (q == TR_CLASP_D1 || q == TR_CLASP_D2)
                    continue;
                /* G and K take D2's width between them when D2 is unseen */
                double want = c.p[q].len + (q == TR_CLASP_G || q == TR_CLASP_K ? 0.5 * c.p[TR_CLASP_D2].len : 0.0);
                CHECK_NEAR(pc->width, want, e);
            }
        }
        CHECK_NEAR(r.shoulder_kappa, 0.5, 1e-5);
        CHECK_NEAR(r.kink_kappa, 1.0, 1e-5);
        if (phase == 0) {
            first = r;
            pfirst = p;
            continue;
        }
        /* the same shape sampled at another phase, a longer end: congruent
         * from the tip to within the boundaries' uncertainties */
        tr_clasp_match cong;
        CHECK_OK(tr_clasp_congruence(&pfirst, &first, &p, &r, &cong, &err));
        CHECK(cong.boundary_diff <= 2.0 * e);
        CHECK(cong.boundary_diff <= cong.boundary_err);
        tr_arc_profile_free(&p);
    }
    tr_arc_profile_free(&pfirst);
}

/* Not a clasp: a circle arc of radius 3 (no kink), a straight line. */
static void test_not_clasp(void)
{
    size_t n = 200;
    double *x = calloc(3 * n, sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[3 * i] = 3.0 * cos(0.01 * (double)i), x[3 * i + 1] = 3.0 * sin(0.01 * (double)i);
    tr_error err;
    tr_arc_profile p;
    REQUIRE_OK(tr_arc_profile_compute_open(x, n, &p, &err));
    tr_clasp_rope r;
    CHECK_OK(tr_clasp_rope_anatomy(&p, &r, &err));
    CHECK(!r.found && r.why[0] != '\0');
    tr_arc_profile_free(&p);
    for (size_t i = 0; i < n; i++)
        x[3 * i] = 0.1 * (double)i, x[3 * i + 1] = 0.0;
    REQUIRE_OK(tr_arc_profile_compute_open(x, n, &p, &err));
    CHECK_OK(tr_clasp_rope_anatomy(&p, &r, &err));
    CHECK(!r.found);
    tr_arc_profile_free(&p);
    free(x);
}

int main(void)
{
    test_resolved();
    test_coarse();
    test_not_clasp();
    return tr_test_finish("test_analysis_clasp_anatomy");
}
