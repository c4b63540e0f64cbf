/* The engine on small curves: a trefoil gets strictly shorter while no
 * strand passes another (the shortest non-local distance, measured by the
 * independent thickness oracle, never drops below 2 - tol), edges stay equal
 * and MinRad >= 1; a Hopf link keeps its Gauss linking number; clasp ends
 * stay on their planes; a run resumed from a checkpoint is bitwise the
 * uninterrupted run; impossible starts are refused. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "engine/engine.h"
#include "curve/generate.h"
#include "testlib.h"
#include "testlib_oracle.h"
#include "oracle/thickness.h"
#include "util/vec3.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* the two components' linking number (testlib.h) */
static double linking_number(const tr_curve *c)
{
    return tr_test_linking_number(c->x + 3 * c->start[0], tr_comp_nv(c, 0), c->x + 3 * c->start[1], tr_comp_nv(c, 1));
}

static void oracle(const tr_curve *c, tr_thickness *t)
{
    tr_error err;
    CHECK_OK(tr_thickness_measure(c, NULL, t, NULL, &err));
}

static void trefoil_run(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 72, &err));
    tr_thickness t0;
    oracle(&c, &t0);
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", NULL, &err));
    tr_engine_progress p0, p;
    tr_engine_get_progress(e, &p0);
    double last = p0.length, worst = INFINITY;
    int accepted_any = 0;
    for (int k = 0; k < 120; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
        tr_engine_get_progress(e, &p);
        if (acc) {
            CHECK(p.length < last);
            last = p.length;
            accepted_any = 1;
        }
        /* the shortest non-local distance after every step (engine), and
         * the independent oracle's dcsd every few steps */
        CHECK(p.min_strut >= 2.0 - 1e-7);
        if (k % 5 == 4) {
            tr_curve s;
            tr_thickness t;
            CHECK_OK(tr_engine_get_curve(e, &s, &err));
            oracle(&s, &t);
            if (t.dcsd < worst)
                worst = t.dcsd;
            tr_curve_free(&s);
        }
    }
    CHECK(accepted_any);
    printf("trefoil: length %.6f -> %.6f, worst dcsd %.12f\n", p0.length, p.length, worst);
    CHECK(p.length < p0.length - 1.0);
    CHECK(worst >= 2.0 - 1e-7);
    CHECK(p.edge_dev < 1e-9);
    tr_curve f;
    tr_thickness t;
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    oracle(&f, &t);
    CHECK(t.minrad >= 1.0 - 1e-6);
    CHECK(t.dcsd >= 2.0 - 1e-7);
    CHECK(t.ropelength < t0.ropelength - 1.0);
    tr_curve_free(&f);
    /* refinement: low-pass resample to twice the vertices, still a valid rope */
    if (tr_engine_refine(e, 144, &err) != TR_OK) {
        tr_test_failures++;
        printf("refine failed: %s\n", err.msg);
    }
    tr_engine_get_progress(e, &p);
    CHECK(p.n == 144);
    CHECK(p.edge_dev < 1e-9);
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    oracle(&f, &t);
    printf("refined: N %zu ropelength %.6f MinRad %.9f dcsd %.9f\n", t.vertices, t.ropelength, t.minrad, t.dcsd);
    CHECK(t.minrad >= 1.0 - 1e-6);
    CHECK(t.dcsd >= 2.0 - 1e-7);
    tr_curve_free(&f);
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

/* With a contact list starved to almost nothing (tilt and skin ~0) the
 * correction cannot hold the struts; what keeps the rope from passing
 * through itself is the check after each step on the rebuilt list, so the
 * oracle's dcsd must still stay >= 2 while steps are being rejected. */
static void starved_list_run(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 72, &err));
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    prm.tilt_edges = 1e-9;
    prm.tilt_motion = 0.0;
    prm.skin = prm.skin_min = 1e-9;
    prm.polish = 0;
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", &prm, &err));
    double worst = INFINITY;
    tr_engine_progress p;
    for (int k = 0; k < 600; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
        if (k % 20 == 19) {
            tr_curve f;
            tr_thickness t;
            CHECK_OK(tr_engine_get_curve(e, &f, &err));
            oracle(&f, &t);
            worst = fmin(worst, t.dcsd);
            tr_curve_free(&f);
        }
    }
    tr_engine_get_progress(e, &p);
    printf("starved list: %ld steps, %ld rejected, length %.6f, worst dcsd %.12f\n", p.steps, p.rejected,
           p.length, worst);
    CHECK(p.rejected > 0);
    CHECK(worst >= 2.0 - 1e-7);
    CHECK(worst < 2.0 + 1e-3); /* the run did reach contact */
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

static void hopf_run(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_hopf(&c, 40, &err));
    double lk0 = linking_number(&c);
    CHECK_NEAR(fabs(lk0), 1.0, 1e-9);
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", NULL, &err));
    tr_engine_progress p0, p;
    tr_engine_get_progress(e, &p0);
    for (int k = 0; k < 30; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
    }
    tr_engine_get_progress(e, &p);
    tr_curve f;
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    double lk = linking_number(&f);
    printf("hopf: length %.6f -> %.6f, Lk %.12f -> %.12f\n", p0.length, p.length, lk0, lk);
    CHECK(p.length < p0.length);
    CHECK_NEAR(lk, lk0, 1e-9);
    tr_curve_free(&f);
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

static void clasp_run(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_clasp(&c, 40, 5.0, &err));
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", NULL, &err));
    tr_engine_progress p0, p;
    tr_engine_get_progress(e, &p0);
    for (int k = 0; k < 30; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
    }
    tr_engine_get_progress(e, &p);
    tr_curve f;
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    double worst = 0.0;
    int constrained = 0;
    for (size_t i = 0; i < f.nv; i++) {
        if (!f.vcst || f.vcst[i] < 0)
            continue;
        constrained++;
        double v = tr_constraint_violation(&f.cst[f.vcst[i]], f.x + 3 * i);
        if (v > worst)
            worst = v;
    }
    printf("clasp: length %.6f -> %.6f, %d constrained ends, worst plane distance %.3g\n", p0.length,
           p.length, constrained, worst);
    CHECK(constrained == 4);
    CHECK(worst <= 1e-12);
    CHECK(p.length < p0.length);
    tr_curve_free(&f);
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

/* A refined clasp goes to the second-order solver unsettled (its planes
 * forbid the settle's rescaling): should the run stop before the solver has
 * it, or the solver not take it, the engine goes back to the coarse level
 * the refinement came from, which is the run's result. It once failed the
 * run with nothing kept (2 x 48 000 with short ends, after two hours).
 * Here the stop flag is raised once the 2 x 40 level is done: the
 * refinement to 2 x 80 follows, and the run must stop at 2 x 40 with that
 * level's curve, at thickness 1 (to the solver's 1e-6), its ends on their
 * planes. */
typedef struct {
    volatile sig_atomic_t *flag;
    double solved_length;
} clasp_stop;

static void clasp_stop_progress(const tr_engine_progress *p, void *user)
{
    clasp_stop *s = user;
    /* the coarse level done (polished, or the solver's): the refinement
     * comes next */
    if (p->n == 80 && (p->polished != 0 || p->newton_ran != 0) && !*s->flag) {
        *s->flag = 1;
        s->solved_length = p->length;
    }
}

static void clasp_refine_stopped(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_clasp(&c, 40, 5.0, &err));
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    prm.newton = 1;
    prm.polish = 1;
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", &prm, &err));
    volatile sig_atomic_t flag = 0;
    clasp_stop cs = {.flag = &flag, .solved_length = NAN};
    tr_engine_limits lim = {.refine_to = 80, .stop = &flag, .progress = clasp_stop_progress, .user = &cs};
    tr_stop_reason why = TR_STOP_NONE;
    int rc = tr_engine_run(e, &lim, &why, &err);
    CHECK_OK(rc);
    tr_engine_progress p;
    tr_engine_get_progress(e, &p);
    tr_curve f = {0};
    CHECK_OK(tr_engine_get_curve(e, &f, &err));
    double worst = 0.0, th = tr_test_thickness(&f);
    for (size_t i = 0; i < f.nv; i++)
        if (f.vcst && f.vcst[i] >= 0)
            worst = fmax(worst, tr_constraint_violation(&f.cst[f.vcst[i]], f.x + 3 * i));
    printf("clasp stopped at its refinement: %s, stop %s at N %zu, length %.9f (the solved 2 x 40: %.9f), "
           "thickness %.9f, worst plane distance %.3g\n", rc ? err.msg : "ok", tr_stop_reason_name(why), p.n,
           p.length, cs.solved_length, th, worst);
    CHECK(why == TR_STOP_SIGNAL);
    CHECK(p.n == 80);
    CHECK(fabs(p.length - cs.solved_length) < 1e-9 * p.length);
    CHECK(th > 1.0 - 1e-6);
    CHECK(worst <= 1e-12);
    tr_curve_free(&f);
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

static void run_steps(tr_engine *e, int n)
{
    tr_error err;
    for (int k = 0; k < n; k++) {
        int acc;
        CHECK_OK(tr_engine_step(e, &acc, &err));
    }
}

/* Rewrites the checkpoint at `path` with its 'comp' line replaced by
 * `comp_line` and expects resume to fail with `want`. */
static void resume_with_comp_line(const char *path, const char *comp_line, int want)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f)
        return;
    static char text[1 << 20];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    char *c = strstr(text, "\ncomp ");
    CHECK(c != NULL);
    if (!c)
        return;
    char *eol = strchr(c + 1, '\n');
    char bad[512];
    snprintf(bad, sizeof bad, "%s/engine_corrupt.ckpt", TR_BINARY_DIR);
    FILE *g = fopen(bad, "wb");
    CHECK(g != NULL);
    if (!g)
        return;
    fwrite(text, 1, (size_t)(c + 1 - text), g);
    fputs(comp_line, g);
    fputs(eol, g);
    fclose(g);
    tr_engine *r = NULL;
    tr_error err;
    int rc = tr_engine_resume(&r, bad, "reference", NULL, &err);
    CHECK(rc == want);
    if (rc == TR_OK)
        tr_engine_destroy(r);
    else
        printf("'%s': %s\n", comp_line, err.msg);
    remove(bad);
}

static void corrupt_checkpoints(const char *path)
{
    /* the torus start has 72 vertices, closed, gap >= 2 */
    resume_with_comp_line(path, "comp 72 1 zzz 3", TR_EPARSE);          /* edge length not a number */
    resume_with_comp_line(path, "comp 72 1 nan 3", TR_EPARSE);          /* not finite */
    resume_with_comp_line(path, "comp 72 1 -1 3", TR_EPARSE);           /* not positive */
    resume_with_comp_line(path, "comp 4000000000000 1 1 3", TR_EPARSE); /* more vertices than the file */
    resume_with_comp_line(path, "comp 72 7 1 3", TR_EPARSE);            /* closure flag */
    resume_with_comp_line(path, "comp 72 1 1 0", TR_EPARSE);            /* exclusion gap */
    /* parses, but the stored edges are far from the stated edge length: not a
     * valid rope state, so the run must not go on from it */
    resume_with_comp_line(path, "comp 72 1 0.5 3", TR_EGEOMETRY);
}

static void checkpoint_resume(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 72, &err));
    char path[512];
    snprintf(path, sizeof path, "%s/engine_resume.ckpt", TR_BINARY_DIR);
    /* uninterrupted */
    tr_engine *a;
    CHECK_OK(tr_engine_create(&a, &c, "reference", NULL, &err));
    run_steps(a, 24);
    tr_curve xa;
    CHECK_OK(tr_engine_get_curve(a, &xa, &err));
    /* interrupted at 12, resumed in a new engine */
    tr_engine *b;
    CHECK_OK(tr_engine_create(&b, &c, "reference", NULL, &err));
    run_steps(b, 12);
    CHECK_OK(tr_engine_checkpoint_write(b, path, &err));
    tr_engine_destroy(b);
    tr_engine *r;
    int rc = tr_engine_resume(&r, path, "reference", NULL, &err);
    CHECK_OK(rc);
    if (rc == TR_OK) {
        run_steps(r, 12);
        tr_curve xr;
        CHECK_OK(tr_engine_get_curve(r, &xr, &err));
        tr_engine_progress pa, pr;
        tr_engine_get_progress(a, &pa);
        tr_engine_get_progress(r, &pr);
        CHECK(pa.steps == pr.steps && pa.rejected == pr.rejected);
        CHECK(xa.nv == xr.nv && memcmp(xa.x, xr.x, 3 * xa.nv * sizeof *xa.x) == 0);
        CHECK(pa.h == pr.h);
        tr_curve_free(&xr);
        tr_engine_destroy(r);
    }
    /* a checkpoint is input: broken content is refused, never continued */
    corrupt_checkpoints(path);
    /* a truncated checkpoint is refused with its line */
    FILE *f = fopen(path, "r+");
    if (f) {
        fseek(f, 0, SEEK_END);
        long len = ftell(f);
        fclose(f);
        CHECK(truncate(path, len / 2) == 0);
        CHECK(tr_engine_resume(&r, path, "reference", NULL, &err) == TR_EPARSE);
        printf("truncated checkpoint: %s\n", err.msg);
    }
    remove(path);
    tr_curve_free(&xa);
    tr_engine_destroy(a);
    tr_curve_free(&c);
}

/* The run loop: a raised stop flag (what SIGINT/SIGTERM set) ends the run
 * at once with a checkpoint; a step limit ends a multi-level run at the
 * level reached; refinement levels double N up to refine_to. */
static void run_loop(void)
{
    tr_error err;
    tr_curve c;
    CHECK_OK(tr_make_torus(&c, 2, 3, 72, &err));
    char path[512];
    snprintf(path, sizeof path, "%s/engine_signal.ckpt", TR_BINARY_DIR);
    remove(path);
    tr_engine *e;
    CHECK_OK(tr_engine_create(&e, &c, "reference", NULL, &err));
    volatile sig_atomic_t flag = 1;
    tr_engine_limits lim = {.stop = &flag, .checkpoint_path = path};
    tr_stop_reason why;
    CHECK_OK(tr_engine_run(e, &lim, &why, &err));
    CHECK(why == TR_STOP_SIGNAL);
    tr_engine *r = NULL;
    CHECK_OK(tr_engine_resume(&r, path, "reference", NULL, &err));
    tr_engine_destroy(r);
    remove(path);
    /* levels: 72 -> 144, the coarse level until jammed or its
     * residual falls below coarse_residual, then the step limit */
    tr_engine_limits lv = {.refine_to = 144, .max_steps = 60, .coarse_residual = 0.95};
    CHECK_OK(tr_engine_run(e, &lv, &why, &err));
    tr_engine_progress p;
    tr_engine_get_progress(e, &p);
    printf("levels: stop %s at N %zu after %ld steps, length %.6f\n", tr_stop_reason_name(why), p.n, p.steps,
           p.length);
    CHECK(p.n == 144);
    CHECK(why == TR_STOP_STEPS || why == TR_STOP_JAMMED || why == TR_STOP_RESIDUAL);
    CHECK(p.edge_dev < 1e-9);
    tr_engine_destroy(e);
    tr_curve_free(&c);
}

static void refused(void)
{
    tr_error err;
    tr_curve c;
    tr_engine *e;
    /* too coarse: 12 vertices on a circle of radius 3 (edges 1.55) */
    CHECK_OK(tr_make_circle(&c, 3.0, 12, &err));
    CHECK(tr_engine_create(&e, &c, "reference", NULL, &err) == TR_EGEOMETRY);
    CHECK(strstr(err.msg, "too coarse") != NULL);
    printf("refused: %s\n", err.msg);
    tr_curve_free(&c);
    /* overlapping: a trefoil shrunk to 0.4 of its size */
    CHECK_OK(tr_make_torus(&c, 2, 3, 240, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        c.x[i] *= 0.4;
    CHECK(tr_engine_create(&e, &c, "reference", NULL, &err) == TR_EGEOMETRY);
    CHECK(strstr(err.msg, "overlaps") != NULL);
    printf("refused: %s\n", err.msg);
    tr_curve_free(&c);
    /* unknown device */
    CHECK_OK(tr_make_torus(&c, 2, 3, 72, &err));
    CHECK(tr_engine_create(&e, &c, "no-such-device-xyz", NULL, &err) != TR_OK);
    printf("refused: %s\n", err.msg);
    tr_curve_free(&c);
}

int main(void)
{
    trefoil_run();
    hopf_run();
    starved_list_run();
    clasp_run();
    clasp_refine_stopped();
    checkpoint_resume();
    run_loop();
    refused();
    return tr_test_finish("test_engine_tighten");
}
