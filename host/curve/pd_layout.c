/* A PD code drawn in the plane by Tutte's method and lifted at its crossings
 * (pd_layout.h). */
#include "curve/pd_layout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"

#define TR_PI 3.14159265358979323846
/* Pieces each edge is cut into: room for the spline to turn between
 * crossings, and a simple graph even where two edges join the same two
 * crossings (a bigon). */
#define LAYOUT_SUB 4

typedef struct end {
    int c, s; /* crossing, slot 0..3 (counterclockwise a, b, c, d) */
} end;

/* node ids: crossing c is c; edge e (0-based) has interior nodes
 * n + e (LAYOUT_SUB - 1) + 0 .. LAYOUT_SUB - 2, from its tail to its head */
static int sub_node(int n, int e, int k) { return n + e * (LAYOUT_SUB - 1) + k; }

int tr_make_pd_layout(tr_curve *out, const int (*pd)[4], int n, size_t dense, tr_error *err)
{
    memset(out, 0, sizeof *out);
    tr_curve coarse;
    int rc = tr_make_pd_polygon(&coarse, pd, n, err);
    if (rc)
        return rc;
    size_t want = dense < coarse.nv * 4 ? coarse.nv * 4 : dense;
    rc = tr_resample_smooth(&coarse, &want, out, err);
    tr_curve_free(&coarse);
    return rc;
}

int tr_make_pd_polygon(tr_curve *out, const int (*pd)[4], int n, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (n < 2)
        return tr_fail(err, TR_EINVAL, "a PD code of %d crossing%s is an unknot%s (make knot 0_1)", n,
                       n == 1 ? "" : "s", n == 1 ? " with a kink" : "");
    int ne = 2 * n, rc = 0;
    int nodes = n + ne * (LAYOUT_SUB - 1);
    end *tail = malloc((size_t)ne * sizeof *tail), *head = malloc((size_t)ne * sizeof *head);
    int *slot_edge = malloc((size_t)n * 4 * sizeof *slot_edge);
    int *dart_face = malloc((size_t)ne * 2 * sizeof *dart_face);
    int *mark = calloc((size_t)n, sizeof *mark);
    double *xy = calloc((size_t)nodes * 2, sizeof *xy);
    size_t npts = (size_t)ne * LAYOUT_SUB;
    /* Tutte's graph: edge list, face rings, adjacency (CSR), positions */
    int *eu = NULL, *ev = NULL, *ring = NULL, *deg = NULL, *adj = NULL, *fill = NULL, *fix = NULL;
    double *pos = NULL;
    if (!tail || !head || !slot_edge || !dart_face || !mark || !xy) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory laying out a PD code");
        goto done;
    }
    for (int e = 0; e < ne; e++)
        tail[e].c = head[e].c = -1;
    /* ends: the under strand enters at slot 0 and leaves at slot 2; the over
     * strand enters at d (slot 3) when b = d + 1, else at b */
    for (int c = 0; c < n; c++) {
        const int *x = pd[c];
        int b_out = x[1] == x[3] % ne + 1;
        int in_slot[2] = {0, b_out ? 3 : 1}, out_slot[2] = {2, b_out ? 1 : 3};
        for (int k = 0; k < 4; k++)
            slot_edge[4 * c + k] = x[k] - 1;
        for (int q = 0; q < 2; q++) {
            int ei = x[in_slot[q]] - 1, eo = x[out_slot[q]] - 1;
            if (head[ei].c >= 0 || tail[eo].c >= 0) {
                rc = tr_fail(err, TR_EINVAL, "PD code: crossing %d: an edge enters or leaves two crossings", c + 1);
                goto done;
            }
            head[ei] = (end){c, in_slot[q]};
            tail[eo] = (end){c, out_slot[q]};
        }
    }
    /* faces: a dart is edge e run forwards (2e) or backwards (2e+1); after
     * arriving at a crossing through slot s, the face goes on through slot
     * s + 1 (counterclockwise next) */
    for (int d = 0; d < 2 * ne; d++)
        dart_face[d] = -1;
    int nf = 0, best = -1, best_len = 0;
    for (int d0 = 0; d0 < 2 * ne; d0++) {
        if (dart_face[d0] >= 0)
            continue;
        int len = 0, simple = 1, d = d0;
        memset(mark, 0, (size_t)n * sizeof *mark);
        while (dart_face[d] < 0) {
            dart_face[d] = nf;
            len++;
            int e = d / 2;
            end at = d % 2 ? tail[e] : head[e];
            if (mark[at.c]++)
                simple = 0;
            int e2 = slot_edge[4 * at.c + (at.s + 1) % 4];
            /* leaving through that slot: forwards if it is e2's tail */
            end t2 = tail[e2];
            d = (t2.c == at.c && t2.s == (at.s + 1) % 4) ? 2 * e2 : 2 * e2 + 1;
        }
        if (d != d0) {
            rc = tr_fail(err, TR_EINVAL, "PD code: its crossings' orders do not close into faces (not a diagram)");
            goto done;
        }
        if (simple && len > best_len) {
            best_len = len;
            best = nf;
        }
        nf++;
    }
    if (nf != n + 2) {
        rc = tr_fail(err, TR_EINVAL, "PD code: %d faces for %d crossings, not %d: not a diagram in the plane", nf, n,
                     n + 2);
        goto done;
    }
    if (best < 0 || best_len < 3) {
        rc = tr_fail(err, TR_EINVAL, "PD code: no face to draw it around (a kink or a nugatory crossing; reduce the "
                     "diagram first)");
        goto done;
    }
    /* Tutte's graph: the edges' paths through their pieces, and a node in
     * every face but the outer one joined to all of the face's nodes (the
     * pieces of two edges that join the same two crossings would otherwise
     * lie on one straight line; the face nodes pull them apart, and the
     * graph is a near-triangulation, which Tutte draws without folds) */
    {
        int maxadj = ne * LAYOUT_SUB * 2 + 2 * ne * 2 * LAYOUT_SUB * 2;
        int tot = nodes + nf, m = 0;
        eu = malloc((size_t)maxadj * sizeof *eu);
        ev = malloc((size_t)maxadj * sizeof *ev);
        ring = malloc((size_t)2 * ne * LAYOUT_SUB * sizeof *ring);
        deg = calloc((size_t)tot + 1, sizeof *deg);
        pos = calloc((size_t)tot * 2, sizeof *pos);
        fix = calloc((size_t)tot, sizeof *fix);
        if (!eu || !ev || !ring || !deg || !pos || !fix) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory laying out a PD code");
            goto done;
        }
        for (int e = 0; e < ne; e++) {
            int prev = tail[e].c;
            for (int q = 0; q < LAYOUT_SUB; q++) {
                int v = q + 1 < LAYOUT_SUB ? sub_node(n, e, q) : head[e].c;
                eu[m] = prev;
                ev[m++] = v;
                prev = v;
            }
        }
        for (int f = 0; f < nf; f++) {
            int d0 = -1, k = 0, d;
            for (d = 0; d < 2 * ne; d++)
                if (dart_face[d] == f) {
                    d0 = d;
                    break;
                }
            d = d0;
            do { /* the face's nodes in its order */
                int e = d / 2, fwd = d % 2 == 0;
                end from = fwd ? tail[e] : head[e];
                ring[k++] = from.c;
                for (int q = 1; q < LAYOUT_SUB; q++)
                    ring[k++] = sub_node(n, e, fwd ? q - 1 : LAYOUT_SUB - 1 - q);
                end at = fwd ? head[e] : tail[e];
                int e2 = slot_edge[4 * at.c + (at.s + 1) % 4];
                end t2 = tail[e2];
                d = (t2.c == at.c && t2.s == (at.s + 1) % 4) ? 2 * e2 : 2 * e2 + 1;
            } while (d != d0);
            for (int q = 0; q < k; q++) {
                if (f == best) { /* the outer face on the unit circle */
                    double a = 2 * TR_PI * q / k; /* either way round: fixed below */
                    pos[2 * ring[q]] = cos(a);
                    pos[2 * ring[q] + 1] = sin(a);
                    fix[ring[q]] = 1;
                } else {
                    eu[m] = nodes + f;
                    ev[m++] = ring[q];
                }
            }
            if (f == best)
                fix[nodes + f] = 1; /* unused */
        }
        for (int q = 0; q < m; q++) {
            deg[eu[q] + 1]++;
            deg[ev[q] + 1]++;
        }
        for (int v = 0; v < tot; v++)
            deg[v + 1] += deg[v];
        adj = malloc((size_t)(2 * m > 0 ? 2 * m : 1) * sizeof *adj);
        fill = malloc((size_t)tot * sizeof *fill);
        if (!adj || !fill) {
            rc = tr_fail(err, TR_ENOMEM, "out of memory laying out a PD code");
            goto done;
        }
        memcpy(fill, deg, (size_t)tot * sizeof *fill);
        for (int q = 0; q < m; q++) {
            adj[fill[eu[q]]++] = ev[q];
            adj[fill[ev[q]]++] = eu[q];
        }
        /* barycentric: every free node at its neighbours' mean, by
         * successive over-relaxation until nothing moves */
        for (int it = 0; it < 100000; it++) {
            double change = 0;
            for (int v = 0; v < tot; v++) {
                if (fix[v] || deg[v + 1] == deg[v])
                    continue;
                double sx = 0, sy = 0;
                for (int q = deg[v]; q < deg[v + 1]; q++) {
                    sx += pos[2 * adj[q]];
                    sy += pos[2 * adj[q] + 1];
                }
                int dv = deg[v + 1] - deg[v];
                double nx = pos[2 * v] + 1.7 * (sx / dv - pos[2 * v]);
                double ny = pos[2 * v + 1] + 1.7 * (sy / dv - pos[2 * v + 1]);
                change = fmax(change, fmax(fabs(nx - pos[2 * v]), fabs(ny - pos[2 * v + 1])));
                pos[2 * v] = nx;
                pos[2 * v + 1] = ny;
            }
            if (change < 1e-13)
                break;
        }
        memcpy(xy, pos, (size_t)nodes * 2 * sizeof *xy);
    }
    /* Tutte's drawing of the faces is the diagram's or its mirror image in
     * the plane, as the outer face went round: the slots a, b, c, d of
     * crossing 0 must follow each other counterclockwise, as the code says.
     * The counterclockwise angles from each slot to the next sum to 2 pi
     * then, to 6 pi in the mirror image (one angle alone can exceed pi,
     * where the crossing sits on the outer face); else y -> -y */
    {
        double ang[4], turn = 0;
        for (int k = 0; k < 4; k++) {
            int e = slot_edge[k];
            int is_tail = tail[e].c == 0 && tail[e].s == k;
            int nb = sub_node(n, e, is_tail ? 0 : LAYOUT_SUB - 2);
            ang[k] = atan2(xy[2 * nb + 1] - xy[1], xy[2 * nb] - xy[0]);
        }
        for (int k = 0; k < 4; k++) {
            double d = ang[(k + 1) % 4] - ang[k];
            while (d < 0)
                d += 2 * TR_PI;
            turn += d;
        }
        if (turn > 4 * TR_PI)
            for (int v = 0; v < nodes; v++)
                xy[2 * v + 1] = -xy[2 * v + 1];
    }
    /* a drawing that collapsed two nodes onto each other is no drawing */
    double mind = INFINITY;
    for (int e = 0; e < ne; e++) {
        int prev = tail[e].c;
        for (int q = 0; q < LAYOUT_SUB; q++) {
            int v = q + 1 < LAYOUT_SUB ? sub_node(n, e, q) : head[e].c;
            mind = fmin(mind, hypot(xy[2 * v] - xy[2 * prev], xy[2 * v + 1] - xy[2 * prev + 1]));
            prev = v;
        }
    }
    if (!(mind > 1e-6)) {
        rc = tr_fail(err, TR_EINVAL, "PD code: its drawing collapses (the diagram is not 3-connected: a kink or a "
                     "nugatory crossing; reduce it first)");
        goto done;
    }
    /* the knot along its labels, lifted at the crossings */
    rc = tr_curve_alloc(out, 1, &npts, NULL, err);
    if (rc)
        goto done;
    double h = 0.35 * mind;
    for (int e = 0; e < ne; e++) {
        int c = tail[e].c;
        double *p = out->x + 3 * (size_t)e * LAYOUT_SUB;
        /* the passage that leaves by edge e: under when e is the crossing's
         * slot c (the under strand's way out), else over */
        int is_over = slot_edge[4 * c + 2] != e;
        p[0] = xy[2 * c];
        p[1] = xy[2 * c + 1];
        p[2] = is_over ? h : -h;
        for (int q = 1; q < LAYOUT_SUB; q++) {
            int v = sub_node(n, e, q - 1);
            p[3 * q] = xy[2 * v];
            p[3 * q + 1] = xy[2 * v + 1];
            p[3 * q + 2] = 0;
        }
    }
done:
    free(eu);
    free(ev);
    free(ring);
    free(deg);
    free(adj);
    free(fill);
    free(fix);
    free(pos);
    free(tail);
    free(head);
    free(slot_edge);
    free(dart_face);
    free(mark);
    free(xy);
    return rc;
}
