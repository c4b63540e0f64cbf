/* This file contains the tube mesh of the rope: rotation-minimising rings
 * around every vertex, triangulated, written as ASCII PLY (tube_mesh.h). */
#include "analysis/tube_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/text_file.h"
#include "util/vec3.h"

#define TUBE_PI 3.14159265358979323846

void tr_tube_mesh_free(tr_tube_mesh *m)
{
    if (!m)
        return;
    free(m->v), free(m->f);
    memset(m, 0, sizeof *m);
}

/* Grows m to hold nv more vertices and nf more faces. */
static int reserve(tr_tube_mesh *m, size_t nv, size_t nf)
{
    if (m->nv + nv > m->vcap) {
        size_t cap = 2 * (m->nv + nv);
        double *v = realloc(m->v, 3 * cap * sizeof *v);
        if (!v)
            return -1;
        m->v = v, m->vcap = cap;
    }
    if (m->nf + nf > m->fcap) {
        size_t cap = 2 * (m->nf + nf);
        size_t *f = realloc(m->f, 3 * cap * sizeof *f);
        if (!f)
            return -1;
        m->f = f, m->fcap = cap;
    }
    return 0;
}

/* u rotated by the smallest rotation that takes unit a to unit b (c = a.b > -1). */
static void transport(double *out, const double *u, const double *a, const double *b)
{
    double ax[3], axu[3];
    v3_cross(ax, a, b);
    double c = v3_dot(a, b);
    v3_cross(axu, ax, u);
    for (int i = 0; i < 3; i++)
        out[i] = c * u[i] + axu[i] + v3_dot(ax, u) / (1.0 + c) * ax[i];
}

/* u (normal to unit t) rotated by angle phi about t. */
static void spin(double *u, const double *t, double phi)
{
    double w[3], r[3];
    v3_cross(w, t, u);
    for (int i = 0; i < 3; i++)
        r[i] = cos(phi) * u[i] + sin(phi) * w[i];
    memcpy(u, r, sizeof r);
}

/* u made unit and normal to unit t. */
static void orthonormalise(double *u, const double *t)
{
    v3_axpy(u, -v3_dot(u, t), t);
    v3_scale(u, 1.0 / v3_norm(u), u);
}

static void tri(tr_tube_mesh *m, size_t a, size_t b, size_t c)
{
    size_t *f = m->f + 3 * m->nf++;
    f[0] = a, f[1] = b, f[2] = c;
}

int tr_tube_mesh_add(tr_tube_mesh *m, const double *x, size_t n, int closed, double radius, size_t K,
                     tr_error *err)
{
    if (n < (closed ? 3u : 2u))
        return tr_fail(err, TR_EINVAL, "a tube needs %s of at least %d vertices, got %zu",
                       closed ? "a closed polygon" : "an open rope", closed ? 3 : 2, n);
    if (K < 3 || K > TR_TUBE_SIDES_MAX)
        return tr_fail(err, TR_EINVAL, "a tube needs 3 to %d vertices per ring, got %zu", TR_TUBE_SIDES_MAX, K);
    if (!(radius > 0) || !isfinite(radius))
        return tr_fail(err, TR_EINVAL, "a tube needs a positive radius");
    size_t ne = closed ? n : n - 1, nseg = ne;
    double *te = malloc(3 * ne * sizeof *te), *T = malloc(3 * n * sizeof *T), *U = malloc(3 * n * sizeof *U);
    double *s = malloc((n + 1) * sizeof *s);
    if (!te || !T || !U || !s) {
        free(te), free(T), free(U), free(s);
        return tr_fail(err, TR_ENOMEM, "out of memory for the tube of %zu vertices", n);
    }
    int rc = TR_OK;
    s[0] = 0.0;
    for (size_t e = 0; e < ne && rc == TR_OK; e++) {
        v3_sub(te + 3 * e, x + 3 * ((e + 1) % n), x + 3 * e);
        double l = v3_norm(te + 3 * e);
        if (!(l > 0) || !isfinite(l))
            rc = tr_fail(err, TR_EGEOMETRY, "edge %zu of the tube's core has zero length", e);
        else
            v3_scale(te + 3 * e, 1.0 / l, te + 3 * e), s[e + 1] = s[e] + l;
    }
    /* Ring tangents: the bisector of the two edges at a vertex, the edge at an open end. */
    for (size_t v = 0; v < n && rc == TR_OK; v++) {
        const double *a = closed || v > 0 ? te + 3 * ((v + n - 1) % n) : te;
        const double *b = closed || v + 1 < n ? te + 3 * (v % ne) : te + 3 * (ne - 1);
        double *t = T + 3 * v;
        v3_add(t, a, b);
        double l = v3_norm(t);
        if (!(l > 1e-8))
            rc = tr_fail(err, TR_EGEOMETRY, "the tube's core doubles back at vertex %zu", v);
        else
            v3_scale(t, 1.0 / l, t);
    }
    if (rc == TR_OK && reserve(m, K * n + (closed ? 0 : 2), 2 * K * nseg + (closed ? 0 : 2 * K)))
        rc = tr_fail(err, TR_ENOMEM, "out of memory for the tube of %zu vertices", n);
    if (rc != TR_OK) {
        free(te), free(T), free(U), free(s);
        return rc;
    }
    /* The first frame vector: normal to T_0, from the axis T_0 is least along. */
    double e0[3] = {0, 0, 0};
    int ax = fabs(T[0]) <= fabs(T[1]) && fabs(T[0]) <= fabs(T[2]) ? 0 : fabs(T[1]) <= fabs(T[2]) ? 1 : 2;
    e0[ax] = 1.0;
    v3_cross(U, T, e0);
    orthonormalise(U, T);
    for (size_t v = 1; v < n; v++) {
        transport(U + 3 * v, U + 3 * (v - 1), T + 3 * (v - 1), T + 3 * v);
        orthonormalise(U + 3 * v, T + 3 * v);
    }
    if (closed) { /* holonomy: the frame carried once round, against the first; spread over the length */
        double u[3], c[3];
        transport(u, U + 3 * (n - 1), T + 3 * (n - 1), T);
        orthonormalise(u, T);
        v3_cross(c, U, u);
        double hol = atan2(v3_dot(c, T), v3_dot(U, u));
        for (size_t v = 1; v < n; v++)
            spin(U + 3 * v, T + 3 * v, -hol * s[v] / s[n]);
    }
    size_t base = m->nv;
    for (size_t v = 0; v < n; v++) {
        double V[3];
        v3_cross(V, T + 3 * v, U + 3 * v);
        for (size_t j = 0; j < K; j++) {
            double phi = 2.0 * TUBE_PI * (double)j / (double)K, *p = m->v + 3 * m->nv++;
            for (int i = 0; i < 3; i++)
                p[i] = x[3 * v + i] + radius * (cos(phi) * U[3 * v + i] + sin(phi) * V[i]);
        }
    }
    for (size_t v = 0; v < nseg; v++) {
        size_t r0 = base + K * v, r1 = base + K * ((v + 1) % n);
        for (size_t j = 0; j < K; j++) {
            size_t j1 = (j + 1) % K;
            tri(m, r0 + j, r0 + j1, r1 + j1);
            tri(m, r0 + j, r1 + j1, r1 + j);
        }
    }
    if (!closed) { /* fan caps, facing away from the rope */
        size_t c0 = m->nv, c1 = m->nv + 1, rl = base + K * (n - 1);
        memcpy(m->v + 3 * c0, x, 3 * sizeof *x);
        memcpy(m->v + 3 * c1, x + 3 * (n - 1), 3 * sizeof *x);
        m->nv += 2;
        for (size_t j = 0; j < K; j++) {
            size_t j1 = (j + 1) % K;
            tri(m, c0, base + j1, base + j);
            tri(m, c1, rl + j, rl + j1);
        }
    }
    free(te), free(T), free(U), free(s);
    return TR_OK;
}

int tr_tube_mesh_ply(const tr_tube_mesh *m, const char *comment, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "ply\nformat ascii 1.0\n");
    if (comment && *comment) {
        tr_text_printf(&b, "comment ");
        for (const char *c = comment; *c; c++) /* one header line */
            tr_text_printf(&b, "%c", *c == '\n' || *c == '\r' ? ' ' : *c);
        tr_text_printf(&b, "\n");
    }
    tr_text_printf(&b, "element vertex %zu\nproperty double x\nproperty double y\nproperty double z\n"
                       "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
                   m->nv, m->nf);
    for (size_t i = 0; i < m->nv; i++)
        tr_text_printf(&b, "%.12g %.12g %.12g\n", m->v[3 * i], m->v[3 * i + 1], m->v[3 * i + 2]);
    for (size_t i = 0; i < m->nf; i++)
        tr_text_printf(&b, "3 %zu %zu %zu\n", m->f[3 * i], m->f[3 * i + 1], m->f[3 * i + 2]);
    *out = tr_text_take(&b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}
