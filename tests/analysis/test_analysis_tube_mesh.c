/* Tube meshes (issue 23) against closed forms: around a regular n-gon of
 * radius R every ring vertex lies at distance 1 from the polygon, up to the
 * corner's 1 - cos(pi/n); the surface is closed (every edge in exactly two
 * triangles, once each way) and encloses the K-gon prism volume
 * (K/2) sin(2 pi/K) r^2 L; a non-planar closed curve joins its last ring to
 * its first without a twist beyond the others; open ropes are capped; the
 * PLY header counts what follows. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/tube_mesh.h"
#include "testlib.h"

#define M_PI 3.14159265358979323846

static double seg_dist(const double *p, const double *a, const double *b)
{
    double ab[3], ap[3], q[3];
    for (int i = 0; i < 3; i++)
        ab[i] = b[i] - a[i], ap[i] = p[i] - a[i];
    double t = (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int i = 0; i < 3; i++)
        q[i] = ap[i] - t * ab[i];
    return sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
}

typedef struct { size_t a, b; } dedge;

static int cmp_edge(const void *x, const void *y)
{
    const dedge *p = x, *q = y;
    return p->a != q->a ? (p->a < q->a ? -1 : 1) : p->b != q->b ? (p->b < q->b ? -1 : 1) : 0;
}

/* Closed and consistently oriented: each directed edge once, and its reverse once. */
static int watertight(const tr_tube_mesh *m)
{
    size_t ne = 3 * m->nf;
    dedge *d = malloc(ne * sizeof *d);
    for (size_t i = 0; i < m->nf; i++)
        for (int k = 0; k < 3; k++)
            d[3 * i + k] = (dedge){m->f[3 * i + k], m->f[3 * i + (k + 1) % 3]};
    qsort(d, ne, sizeof *d, cmp_edge);
    int ok = 1;
    for (size_t i = 0; i < ne && ok; i++) {
        if (i + 1 < ne && !cmp_edge(d + i, d + i + 1))
            ok = 0; /* a directed edge twice: more than two faces or flipped ones */
        dedge r = {d[i].b, d[i].a};
        if (!bsearch(&r, d, ne, sizeof *d, cmp_edge))
            ok = 0; /* a border edge */
    }
    free(d);
    return ok;
}

static double volume(const tr_tube_mesh *m)
{
    double V = 0.0;
    for (size_t i = 0; i < m->nf; i++) {
        const double *a = m->v + 3 * m->f[3 * i], *b = m->v + 3 * m->f[3 * i + 1], *c = m->v + 3 * m->f[3 * i + 2];
        V += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    return V;
}

static void test_circle(void)
{
    tr_error err;
    size_t n = 120, K = 16;
    double R = 4.0;
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        x[3 * i] = R * cos(t), x[3 * i + 1] = R * sin(t), x[3 * i + 2] = 0.0;
    }
    tr_tube_mesh m = {0};
    CHECK_OK(tr_tube_mesh_add(&m, x, n, 1, 1.0, K, &err));
    CHECK(m.nv == n * K && m.nf == 2 * n * K);
    double tol = 1.0 - cos(M_PI / (double)n), worst = 0.0;
    for (size_t i = 0; i < m.nv; i++) {
        double d = INFINITY;
        for (size_t e = 0; e < n; e++)
            d = fmin(d, seg_dist(m.v + 3 * i, x + 3 * e, x + 3 * ((e + 1) % n)));
        worst = fmax(worst, fabs(d - 1.0));
    }
    if (!(worst <= tol + 1e-12))
        tr_test_report(__FILE__, __LINE__, "distance off by %g > %g", worst, tol);
    CHECK(worst <= tol + 1e-12);
    CHECK(watertight(&m));
    /* the polygon's length 2 n R sin(pi/n), the K-gon's area */
    double L = 2.0 * (double)n * R * sin(M_PI / (double)n), A = 0.5 * (double)K * sin(2.0 * M_PI / (double)K);
    CHECK_NEAR(volume(&m), A * L, 0.01 * A * L);
    /* PLY: the header's counts match the lines that follow */
    char *ply = NULL;
    CHECK_OK(tr_tube_mesh_ply(&m, "circle\nof radius 4", &ply));
    size_t nv = 0, nf = 0, lines = 0, hdr = 0;
    CHECK(!strncmp(ply, "ply\nformat ascii 1.0\n", 21));
    const char *p = strstr(ply, "element vertex ");
    CHECK(p && sscanf(p, "element vertex %zu", &nv) == 1 && nv == m.nv);
    p = strstr(ply, "element face ");
    CHECK(p && sscanf(p, "element face %zu", &nf) == 1 && nf == m.nf);
    p = strstr(ply, "end_header\n");
    CHECK(p != NULL);
    for (const char *c = ply; *c; c++)
        if (*c == '\n') {
            lines++;
            if (p && c <= p + 10) /* through end_header's newline */
                hdr++;
        }
    CHECK(lines == hdr + nv + nf);
    size_t a, b, c;
    const char *last = ply + strlen(ply) - 2;
    while (last > ply && last[-1] != '\n')
        last--;
    CHECK(sscanf(last, "3 %zu %zu %zu", &a, &b, &c) == 3 && a < nv && b < nv && c < nv);
    free(ply);
    tr_tube_mesh_free(&m);
    free(x);
}

/* A trefoil on a torus: not planar, so the transported frame comes back
 * turned; spread over the length, the closing segment twists no more than
 * any other. Measured on the longitudinal mesh edges (ring j to ring j). */
static void test_closed_joint(void)
{
    tr_error err;
    size_t n = 300, K = 12;
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 2.0 * M_PI * (double)i / (double)n;
        double rr = 6.0 + 2.0 * cos(3.0 * t);
        x[3 * i] = rr * cos(2.0 * t), x[3 * i + 1] = rr * sin(2.0 * t), x[3 * i + 2] = 2.0 * sin(3.0 * t);
    }
    tr_tube_mesh m = {0};
    CHECK_OK(tr_tube_mesh_add(&m, x, n, 1, 1.0, K, &err));
    CHECK(watertight(&m));
    double worst = 0.0, closing = 0.0;
    for (size_t v = 0; v < n; v++) {
        size_t w = (v + 1) % n;
        double core = sqrt(pow(x[3 * w] - x[3 * v], 2) + pow(x[3 * w + 1] - x[3 * v + 1], 2) +
                           pow(x[3 * w + 2] - x[3 * v + 2], 2));
        for (size_t j = 0; j < K; j++) {
            const double *p = m.v + 3 * (K * v + j), *q = m.v + 3 * (K * w + j);
            double d = sqrt(pow(q[0] - p[0], 2) + pow(q[1] - p[1], 2) + pow(q[2] - p[2], 2)) / core;
            if (w == 0)
                closing = fmax(closing, d);
            else
                worst = fmax(worst, d);
        }
    }
    if (!(closing <= 1.05 * worst))
        tr_test_report(__FILE__, __LINE__, "closing segment stretched %g x, others at most %g x", closing, worst);
    CHECK(closing <= 1.05 * worst);
    CHECK(volume(&m) > 0);
    tr_tube_mesh_free(&m);
    free(x);
}

/* An open helix and a straight rope in one mesh: capped, closed, outward;
 * the straight rope's ring vertices are exactly at distance 1 from its axis. */
static void test_open(void)
{
    tr_error err;
    size_t n = 400, K = 16;
    double *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < n; i++) {
        double t = 6.0 * M_PI * (double)i / (double)(n - 1);
        x[3 * i] = 2.0 * cos(t), x[3 * i + 1] = 2.0 * sin(t), x[3 * i + 2] = 1.5 * t;
    }
    double y[9] = {10, 0, 0, 10, 0, 3, 10, 0, 7};
    tr_tube_mesh m = {0};
    CHECK_OK(tr_tube_mesh_add(&m, x, n, 0, 1.0, K, &err));
    size_t nv1 = m.nv;
    CHECK(nv1 == n * K + 2 && m.nf == 2 * K * (n - 1) + 2 * K);
    CHECK_OK(tr_tube_mesh_add(&m, y, 3, 0, 1.0, K, &err));
    CHECK(watertight(&m));
    for (size_t i = nv1; i < nv1 + 3 * K; i++)
        CHECK_NEAR(hypot(m.v[3 * i] - 10.0, m.v[3 * i + 1]), 1.0, 1e-12);
    double A = 0.5 * (double)K * sin(2.0 * M_PI / (double)K);
    CHECK(volume(&m) > 0);
    /* the caps' centres are the ends */
    CHECK(m.v[3 * (m.nv - 2) + 2] == 0.0 && m.v[3 * (m.nv - 1) + 2] == 7.0);
    tr_tube_mesh m2 = {0};
    CHECK_OK(tr_tube_mesh_add(&m2, y, 3, 0, 1.0, K, &err));
    CHECK_NEAR(volume(&m2), 7.0 * A, 1e-9);
    tr_tube_mesh_free(&m2);
    /* refused: too few sides, a zero edge, a reversal; the mesh is kept */
    size_t nf = m.nf;
    CHECK(tr_tube_mesh_add(&m, y, 3, 0, 1.0, 2, &err) == TR_EINVAL);
    double z[9] = {0, 0, 0, 0, 0, 0, 1, 0, 0}, r[9] = {0, 0, 0, 1, 0, 0, 0, 0, 0};
    CHECK(tr_tube_mesh_add(&m, z, 3, 0, 1.0, K, &err) == TR_EGEOMETRY);
    CHECK(tr_tube_mesh_add(&m, r, 3, 0, 1.0, K, &err) == TR_EGEOMETRY);
    CHECK(m.nf == nf && watertight(&m));
    tr_tube_mesh_free(&m);
    free(x);
}

int main(void)
{
    test_circle();
    test_closed_joint();
    test_open();
    return tr_test_finish("test_analysis_tube_mesh");
}
