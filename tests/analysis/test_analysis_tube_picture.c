/* The tube pictures' data and script (tube_picture.h, tube_views.h,
 * tube_script.h): around a circle of radius 4 every surface point lies at
 * distance 1 from the circle, the grid data gnuplot reads has rings + 1
 * blocks of sides + 1 rows (rings x sides quads) and closes on itself, and
 * the cameras are orthonormal and right-handed with the front one along the
 * circle's axis; on the tight N = 2400 trefoil (bench/data) the surface is
 * at distance 1 from the full polygon, the kappa = 1 stretches and the
 * contacts are marked, the struts drawn are struts (length 2), the front
 * camera looks along the threefold axis, and the script's view vectors are
 * unit vectors. Drawing the PNGs needs gnuplot: tests/scripts/analyze_cli.sh,
 * case tube. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/contact_functions.h"
#include "analysis/portrait.h"
#include "analysis/tube_picture.h"
#include "analysis/tube_script.h"
#include "analysis/tube_views.h"
#include "curve/curve_io.h"
#include "oracle/thickness.h"
#include "testlib.h"
#include "util/vec3.h"

#define PI 3.14159265358979323846

/* Distance from p to the closed polygon x of n vertices. */
static double polygon_dist(const double *p, const double *x, size_t n)
{
    double best = INFINITY;
    for (size_t i = 0; i < n; i++) {
        const double *a = x + 3 * i, *b = x + 3 * ((i + 1) % n);
        double ab[3], ap[3];
        v3_sub(ab, b, a), v3_sub(ap, p, a);
        double t = v3_dot(ap, ab) / v3_dot(ab, ab);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        v3_axpy(ap, -t, ab);
        best = fmin(best, v3_norm(ap));
    }
    return best;
}

/* The grid data as gnuplot reads it: rows and blank-line-separated blocks
 * (several blank lines in a row end one block, as for gnuplot); each
 * block's row count must be `per` (0: not checked); the first row of the
 * first and of the last block returned in first, last (3 coordinates). */
static void count_grid(const char *text, size_t *rows, size_t *blocks, size_t per, int *uneven, double *first,
                       double *last)
{
    *rows = *blocks = 0, *uneven = 0;
    size_t in_block = 0;
    for (const char *l = text; *l;) {
        const char *e = strchr(l, '\n');
        size_t len = e ? (size_t)(e - l) : strlen(l);
        if (len && l[0] != '#') {
            double q[3];
            if (sscanf(l, "%lf %lf %lf", q, q + 1, q + 2) == 3 && in_block == 0) {
                if (*blocks == 0)
                    memcpy(first, q, sizeof q);
                memcpy(last, q, sizeof q);
            }
            (*rows)++, in_block++;
        } else if (!len && in_block) {
            (*blocks)++;
            *uneven |= per && in_block != per;
            in_block = 0;
        }
        l = e ? e + 1 : l + len;
    }
    if (in_block)
        (*blocks)++, *uneven |= per && in_block != per;
}

static void check_views(const tr_tube_views *v)
{
    for (int i = 0; i < TR_NVIEWS; i++) {
        const tr_view *w = &v->v[i];
        double c[3];
        CHECK_NEAR(v3_norm(w->right), 1.0, 1e-12);
        CHECK_NEAR(v3_norm(w->up), 1.0, 1e-12);
        CHECK_NEAR(v3_norm(w->toward), 1.0, 1e-12);
        CHECK_NEAR(v3_dot(w->right, w->up), 0.0, 1e-12);
        CHECK_NEAR(v3_dot(w->up, w->toward), 0.0, 1e-12);
        v3_cross(c, w->right, w->up); /* right-handed: the picture is not mirrored */
        CHECK_NEAR(v3_dot(c, w->toward), 1.0, 1e-12);
    }
    /* the three cameras at right angles */
    CHECK_NEAR(v3_dot(v->v[0].toward, v->v[1].toward), 0.0, 1e-12);
    CHECK_NEAR(v3_dot(v->v[0].toward, v->v[2].toward), 0.0, 1e-12);
    CHECK_NEAR(v3_dot(v->v[1].toward, v->v[2].toward), 0.0, 1e-12);
}

/* Every "rx = ..; ry = ..; rz = .." (and u, t) line of the script is a unit
 * vector; returns how many were read. */
static int script_vectors_unit(const char *s)
{
    int n = 0;
    for (const char *l = s; (l = strchr(l, '\n')) != NULL; l++) {
        double a, b, c;
        char p0, p1, p2;
        if (sscanf(l + 1, "%cx = %lf; %cy = %lf; %cz = %lf", &p0, &a, &p1, &b, &p2, &c) == 6 && p0 == p1 &&
            p1 == p2 && strchr("rut", p0)) {
            CHECK_NEAR(sqrt(a * a + b * b + c * c), 1.0, 1e-9);
            n++;
        }
    }
    return n;
}

static void test_circle(void)
{
    tr_error err;
    size_t n = 2000, K = 24;
    double R = 4.0, *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * PI * (double)i / (double)n;
        x[3 * i] = R * cos(t), x[3 * i + 1] = R * sin(t), x[3 * i + 2] = 0.0;
    }
    tr_analysis a;
    tr_analysis_opts o = {.m = 10};
    REQUIRE_OK(tr_analyze_component(x, n, NULL, 0, &o, &a, &err));
    tr_tube_picture tp;
    REQUIRE_OK(tr_tube_picture_build(x, n, &a, 0, K, &tp, &err));
    /* decimated: one ring per 0.05 of length */
    CHECK(tp.rings == tr_tube_picture_default_rings(n, 2.0 * PI * R));
    CHECK(tp.rings == (size_t)ceil(2.0 * PI * R / 0.05) && tp.rings < n);
    double worst = 0.0;
    for (size_t i = 0; i < tp.rings * K; i++) {
        const double *q = tp.p + 3 * i;
        double rho = hypot(q[0], q[1]);
        worst = fmax(worst, fabs(hypot(rho - R, q[2]) - 1.0));
    }
    CHECK(worst < 1e-4);
    CHECK(tp.minrad_rings == 0 && tp.contact_marks == 0 && tp.nstruts == 0);
    for (size_t r = 0; r < tp.rings; r++)
        CHECK_NEAR(tp.kappa[r], 1.0 / R, 1e-3);

    char *text = NULL;
    REQUIRE_OK(tr_tube_data_text(&tp, &text));
    size_t rows, blocks;
    int uneven;
    double first[3], last[3];
    count_grid(text, &rows, &blocks, K + 1, &uneven, first, last);
    CHECK(blocks == tp.rings + 1);
    CHECK(rows == (tp.rings + 1) * (K + 1));
    CHECK(!uneven);
    CHECK((blocks - 1) * (rows / blocks - 1) == tp.rings * K); /* the quads pm3d fills */
    for (int i = 0; i < 3; i++) /* the tube closes: the last block is the first ring again */
        CHECK_NEAR(last[i], first[i], 1e-6);
    free(text);

    tr_tube_views v;
    tr_tube_views_choose(x, n, &a.sym, &v);
    check_views(&v);
    CHECK(fabs(v.v[TR_VIEW_FRONT].toward[2]) > 1.0 - 1e-9); /* along the circle's axis */
    CHECK_NEAR(v3_norm(v.centre), 0.0, 1e-9);
    tr_tube_picture_free(&tp);
    tr_analysis_free(&a);
    free(x);
}

static void test_trefoil(void)
{
    char path[4096];
    tr_error err;
    tr_curve c;
    REQUIRE_OK(tr_curve_read(tr_source_path(path, sizeof path, "bench/data/trefoil_2400.vect"), TR_FORMAT_AUTO,
                             &c, &err));
    size_t n = c.nv;
    /* the contacts as analyze finds them: struts within 1e-4 of the shortest */
    tr_thickness th;
    tr_strut_list sl = {0};
    tr_thickness_opts to = {.strut_rel_tol = 1e-4};
    REQUIRE_OK(tr_thickness_measure(&c, &to, &th, &sl, &err));
    tr_contact_pair *pairs = NULL;
    size_t np = 0;
    REQUIRE_OK(tr_contact_pairs_from_struts(c.x, n, 0, sl.s, sl.n, (1.0 + 1e-4) * th.dcsd, &pairs, &np, &err));
    tr_analysis a;
    tr_analysis_opts o = {.m = 1, .plateau_eps = 3e-3};
    REQUIRE_OK(tr_analyze_component(c.x, n, pairs, np, &o, &a, &err));
    CHECK(a.sym.verdict == TR_SYM_D3);
    /* bench/notes/2026-11-24-tube-pictures.md: l1 ~ 0.164, l2 ~ 0.309 at every image */
    CHECK(a.nplateaus == 6);

    size_t K = 16;
    tr_tube_picture tp;
    REQUIRE_OK(tr_tube_picture_build(c.x, n, &a, 0, K, &tp, &err));
    CHECK(tp.rings < n);
    /* the rings are at distance 1 from the full polygon: a ring's vertex
     * sits on the decimated core's bisecting plane, whose chords cut the
     * polygon's bends by h^2 kappa / 8 ~ 3e-4 at most */
    double lo = INFINITY, hi = 0.0;
    for (size_t i = 0; i < tp.rings * K; i += 7) {
        double d = polygon_dist(tp.p + 3 * i, c.x, n);
        lo = fmin(lo, d), hi = fmax(hi, d);
    }
    CHECK(lo > 1.0 - 2e-3);
    CHECK(hi < 1.0 + 1e-6);
    /* six kappa = 1 stretches of ~0.15 (three rings each at 0.05) and contacts */
    CHECK(tp.minrad_rings >= 6 * 2);
    CHECK(tp.minrad_rings < tp.rings / 4);
    CHECK(tp.contact_marks > tp.rings); /* two contact lines run along the tight trefoil */
    CHECK(tp.nstruts > 0 && tp.nstruts <= TR_TUBE_STRUTS_MAX);
    CHECK(tp.nstruts == (np < TR_TUBE_STRUTS_MAX ? np : TR_TUBE_STRUTS_MAX) || np > TR_TUBE_STRUTS_MAX);
    for (size_t i = 0; i < tp.nstruts; i++)
        CHECK_NEAR(sqrt(v3_dist2(tp.strut + 6 * i, tp.strut + 6 * i + 3)), 2.0, 1e-3);

    tr_tube_views v;
    tr_tube_views_choose(c.x, n, &a.sym, &v);
    check_views(&v);
    CHECK(fabs(v3_dot(v.v[TR_VIEW_FRONT].toward, a.sym.c3.axis)) > 1.0 - 1e-12);
    CHECK(!strcmp(v.front_axis, "the threefold axis"));

    /* the struts' data: the core's rings + 1 blocks, then two per strut */
    char *text = NULL;
    REQUIRE_OK(tr_tube_struts_text(&tp, &text));
    size_t rows, blocks;
    int uneven;
    double first[3], last[3];
    count_grid(text, &rows, &blocks, 0, &uneven, first, last);
    CHECK(blocks == tp.rings + 1 + 2 * tp.nstruts);
    free(text);

    /* the script: four pictures, each to its own output, shaded and
     * depth-sorted, and every view vector a unit vector */
    const char *outs[TR_TUBE_PNGS] = {"f.png.tmp1", "t.png.tmp2", "s.png.tmp3", "st.png.tmp4"};
    REQUIRE_OK(tr_tube_script_text(&tp, &v, "tube.dat", "struts.dat", outs, "it's a test", 300, &text));
    for (int i = 0; i < TR_TUBE_PNGS; i++) {
        char want[64];
        snprintf(want, sizeof want, "\nset output '%s'\n", outs[i]);
        CHECK(strstr(text, want) != NULL);
    }
    CHECK(strstr(text, "set pm3d depthorder lighting") != NULL);
    CHECK(strstr(text, "size 300,300") != NULL);
    CHECK(strstr(text, "it's") == NULL); /* a quote would end gnuplot's string */
    CHECK(script_vectors_unit(text) == 3 * TR_TUBE_PNGS);
    free(text);

    tr_tube_picture_free(&tp);
    tr_analysis_free(&a);
    free(pairs);
    tr_strut_list_free(&sl);
    tr_curve_free(&c);
}

static void test_refused(void)
{
    tr_error err;
    double x[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    tr_analysis a;
    memset(&a, 0, sizeof a);
    tr_tube_picture tp;
    CHECK(tr_tube_picture_build(x, 3, &a, 4, 16, &tp, &err) == TR_EINVAL); /* more rings than vertices */
    CHECK(tr_tube_picture_build(x, 3, &a, 3, 2, &tp, &err) == TR_EINVAL);  /* two sides */
    CHECK(tr_tube_picture_build(x, 2, &a, 0, 16, &tp, &err) == TR_EINVAL);
}

int main(void)
{
    test_circle();
    test_trefoil();
    test_refused();
    return tr_test_failures ? 1 : 0;
}
