/* The Alexander polynomial from a PD code, exactly.
 *
 * The Wirtinger presentation has one generator x_k per arc (a maximal over
 * strand: arcs end at under passages) and one relation per crossing,
 * x_out = x_over^e x_in x_over^-e with e the crossing's sign. Fox calculus
 * and the abelianisation x_k -> t give the row of the Alexander matrix
 *     over arc: 1 - t,   incoming under arc: t,   outgoing under arc: -1
 * for a right-handed crossing, and t and -1 swapped for a left-handed one
 * (the same row with t -> 1/t, times a unit). Delta is any (n-1)-minor.
 *
 * The minor is a polynomial of degree <= n-1 in t with integer
 * coefficients. It is computed exactly without big numbers: evaluated at
 * t = 2 .. n+1 modulo two primes near 2^61 (Gaussian elimination in the
 * field), interpolated there (Newton's divided differences), and its
 * coefficients rebuilt by the Chinese remainder theorem in 128 bits, the
 * symmetric residue being the integer while |coefficient| < p1 p2 / 2
 * (alexander.h: guaranteed up to TR_ALEXANDER_MAX_CROSSINGS). */
#include "topology/alexander.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "topology/knot_diagram.h"
#include "topology/signature.h"

typedef unsigned __int128 u128;
typedef __int128 i128;

static const uint64_t PRIME[2] = {0x1fffffffffffffffULL /* 2^61 - 1 */, 0x3fffffffffffffc7ULL /* 2^62 - 57 */};

static uint64_t mulmod(uint64_t a, uint64_t b, uint64_t p) { return (uint64_t)((u128)a * b % p); }
static uint64_t addmod(uint64_t a, uint64_t b, uint64_t p) { return (uint64_t)(((u128)a + b) % p); }
static uint64_t submod(uint64_t a, uint64_t b, uint64_t p) { return a >= b ? a - b : (uint64_t)((u128)a + p - b); }

static uint64_t powmod(uint64_t a, uint64_t e, uint64_t p)
{
    uint64_t r = 1;
    for (; e; e >>= 1, a = mulmod(a, a, p))
        if (e & 1)
            r = mulmod(r, a, p);
    return r;
}

/* a^-1 mod p (p prime, a != 0): Fermat */
static uint64_t invmod(uint64_t a, uint64_t p) { return powmod(a, p - 2, p); }

static uint64_t mod_of(long long v, uint64_t p)
{
    long long r = v % (long long)p;
    return r < 0 ? (uint64_t)(r + (long long)p) : (uint64_t)r;
}

/* det of the m x m matrix a (row major, destroyed) mod p */
static uint64_t det_mod(uint64_t *a, int m, uint64_t p)
{
    uint64_t det = 1;
    for (int c = 0; c < m; c++) {
        int piv = -1;
        for (int r = c; r < m; r++)
            if (a[r * m + c]) {
                piv = r;
                break;
            }
        if (piv < 0)
            return 0;
        if (piv != c) {
            for (int k = 0; k < m; k++) {
                uint64_t tmp = a[c * m + k];
                a[c * m + k] = a[piv * m + k];
                a[piv * m + k] = tmp;
            }
            det = submod(0, det, p);
        }
        det = mulmod(det, a[c * m + c], p);
        uint64_t inv = invmod(a[c * m + c], p);
        for (int r = c + 1; r < m; r++) {
            uint64_t f = mulmod(a[r * m + c], inv, p);
            if (!f)
                continue;
            for (int k = c; k < m; k++)
                a[r * m + k] = submod(a[r * m + k], mulmod(f, a[c * m + k], p), p);
        }
    }
    return det;
}

/* Coefficients poly[0..m] (of t^0..t^m) of the minor mod p, the minor's
 * entries being e0 + e1 t (m x m each). */
static void minor_poly_mod(const long long *e0, const long long *e1, int m, uint64_t p, uint64_t *work,
                           uint64_t *xs, uint64_t *ys, uint64_t *poly)
{
    for (int i = 0; i <= m; i++) {
        uint64_t t = (uint64_t)i + 2;
        for (int k = 0; k < m * m; k++)
            work[k] = addmod(mod_of(e0[k], p), mulmod(mod_of(e1[k], p), t, p), p);
        xs[i] = t;
        ys[i] = det_mod(work, m, p);
    }
    /* divided differences in place: ys[i] becomes f[x0..xi] */
    for (int j = 1; j <= m; j++)
        for (int i = m; i >= j; i--)
            ys[i] = mulmod(submod(ys[i], ys[i - 1], p), invmod(submod(xs[i], xs[i - j], p), p), p);
    /* Horner on the Newton form: poly = ys[m]; poly = poly (t - x_i) + ys[i] */
    memset(poly, 0, (size_t)(m + 1) * sizeof *poly);
    poly[0] = ys[m];
    for (int i = m - 1; i >= 0; i--) {
        for (int k = m; k >= 1; k--)
            poly[k] = submod(poly[k - 1], mulmod(poly[k], xs[i], p), p);
        poly[0] = submod(ys[i], mulmod(poly[0], xs[i], p), p);
    }
}

static int find_root(int *parent, int x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

int tr_alexander_from_pd(const int (*pd)[4], int n, tr_alexander *a, tr_error *err)
{
    memset(a, 0, sizeof *a);
    if (n < 0)
        return tr_fail(err, TR_EINVAL, "a PD code cannot have %d crossings", n);
    if (n > TR_ALEXANDER_MAX_CROSSINGS)
        return tr_fail(err, TR_EUNSUPPORTED, "a diagram of %d crossings is more than the %d the exact Alexander "
                       "polynomial here handles", n, TR_ALEXANDER_MAX_CROSSINGS);
    if (n <= 1) {
        /* no crossing, or one (a kink): the unknot; its 0 x 0 minor is 1 */
        a->span = 0;
        a->coef[0] = 1;
        a->determinant = 1;
        for (int k = 0; n == 1 && k < 4; k++)
            if (pd[0][k] < 1 || pd[0][k] > 2)
                return tr_fail(err, TR_EINVAL, "PD crossing 1: edge label %d is outside 1..2", pd[0][k]);
        return 0;
    }
    int ne = 2 * n, rc = 0;
    int *use = calloc((size_t)ne + 1, sizeof *use), *parent = malloc(((size_t)ne + 1) * sizeof *parent);
    int *arc = malloc(((size_t)ne + 1) * sizeof *arc);
    long long *e0 = calloc((size_t)n * (size_t)n, sizeof *e0), *e1 = calloc((size_t)n * (size_t)n, sizeof *e1);
    uint64_t *work = malloc((size_t)n * (size_t)n * sizeof *work), *xs = malloc((size_t)n * sizeof *xs);
    uint64_t *ys = malloc((size_t)n * sizeof *ys), *poly[2] = {malloc((size_t)n * sizeof(uint64_t)),
                                                                malloc((size_t)n * sizeof(uint64_t))};
    if (!use || !parent || !arc || !e0 || !e1 || !work || !xs || !ys || !poly[0] || !poly[1]) {
        rc = tr_fail(err, TR_ENOMEM, "out of memory for a %d-crossing Alexander matrix", n);
        goto done;
    }
    /* the code must be one knot's: labels 1..2n, each twice, under strands
     * a -> a+1, over strands over consecutive edges */
    for (int c = 0; c < n && rc == 0; c++)
        for (int k = 0; k < 4; k++) {
            if (pd[c][k] < 1 || pd[c][k] > ne) {
                rc = tr_fail(err, TR_EINVAL, "PD crossing %d: edge label %d is outside 1..%d", c + 1, pd[c][k], ne);
                break;
            }
            use[pd[c][k]]++;
        }
    for (int e = 1; e <= ne && rc == 0; e++)
        if (use[e] != 2)
            rc = tr_fail(err, TR_EINVAL, "PD code: edge %d appears %d times, not twice (not one knot's diagram)", e,
                         use[e]);
    for (int e = 0; e <= ne; e++)
        parent[e] = e;
    for (int c = 0; c < n && rc == 0; c++) {
        int ia = pd[c][0], ib = pd[c][1], ic = pd[c][2], id = pd[c][3];
        if (ic != ia % ne + 1)
            rc = tr_fail(err, TR_EINVAL, "PD crossing %d: the under strand runs %d -> %d, not to %d (not one knot's "
                         "diagram, or not oriented along its labels)", c + 1, ia, ic, ia % ne + 1);
        else if (ib != id % ne + 1 && id != ib % ne + 1)
            rc = tr_fail(err, TR_EINVAL, "PD crossing %d: over strand edges %d and %d are not consecutive", c + 1, ib,
                         id);
        else
            parent[find_root(parent, ib)] = find_root(parent, id);
    }
    if (rc)
        goto done;
    /* arcs: the classes of edges joined through over passages */
    int narc = 0;
    for (int e = 1; e <= ne; e++)
        arc[e] = -1;
    for (int e = 1; e <= ne; e++) {
        int r = find_root(parent, e);
        if (arc[r] < 0)
            arc[r] = narc++;
        arc[e] = arc[r];
    }
    if (narc != n) {
        rc = tr_fail(err, TR_EINVAL, "PD code: %d arcs for %d crossings (not one knot's diagram)", narc, n);
        goto done;
    }
    /* the Alexander matrix, one row per crossing; the last row and column
     * are struck out by keeping the leading (n-1) x (n-1) block */
    int m = n - 1;
    for (int c = 0; c < m; c++) {
        int ia = pd[c][0], ib = pd[c][1], ic = pd[c][2], id = pd[c][3];
        int right = ib == id % ne + 1; /* X[i, j+1, i+1, j] */
        int ko = arc[ib], ki = arc[ia], kx = arc[ic];
        if (ko < m) {
            e0[c * m + ko] += 1;
            e1[c * m + ko] -= 1;
        }
        if (ki < m) {
            if (right)
                e1[c * m + ki] += 1;
            else
                e0[c * m + ki] -= 1;
        }
        if (kx < m) {
            if (right)
                e0[c * m + kx] -= 1;
            else
                e1[c * m + kx] += 1;
        }
    }
    for (int q = 0; q < 2; q++)
        minor_poly_mod(e0, e1, m, PRIME[q], work, xs, ys, poly[q]);
    /* Chinese remainder: x = r1 + p1 ((r2 - r1) p1^-1 mod p2), symmetric */
    const u128 P = (u128)PRIME[0] * PRIME[1];
    uint64_t p1inv = invmod(PRIME[0] % PRIME[1], PRIME[1]);
    long long coef[TR_ALEXANDER_MAX_CROSSINGS + 1];
    int lo = -1, hi = -1;
    for (int k = 0; k <= m; k++) {
        uint64_t r1 = poly[0][k], r2 = poly[1][k];
        uint64_t h = mulmod(submod(r2, r1 % PRIME[1], PRIME[1]), p1inv, PRIME[1]);
        u128 x = (u128)r1 + (u128)PRIME[0] * h;
        i128 v = x > P / 2 ? -(i128)(P - x) : (i128)x;
        if (v > (i128)INT64_MAX || v < -(i128)INT64_MAX) {
            rc = tr_fail(err, TR_EUNSUPPORTED, "an Alexander polynomial coefficient does not fit 64 bits");
            goto done;
        }
        coef[k] = (long long)v;
        if (coef[k]) {
            if (lo < 0)
                lo = k;
            hi = k;
        }
    }
    /* For a knot Delta(1) = +-1 and Delta is symmetric up to a unit: both
     * are checked, as the proof that the code was one knot's diagram and
     * the arithmetic right. */
    /* summed in 128 bits: coefficients near the 64-bit bound must not
     * overflow into a false +-1 */
    i128 sum = 0;
    for (int k = lo; lo >= 0 && k <= hi; k++)
        sum += coef[k];
    if (lo < 0 || (sum != 1 && sum != -1)) {
        rc = tr_fail(err, TR_EINVAL, "the Alexander matrix gives Delta(1) = %s, not +-1: not one knot's diagram",
                     lo < 0 || sum == 0 ? "0" : sum > 1 ? "more than 1" : "less than -1");
        goto done;
    }
    int span = hi - lo;
    for (int k = 0; k <= span; k++)
        if (coef[lo + k] != coef[hi - k]) {
            rc = tr_fail(err, TR_EINVAL, "the Alexander polynomial is not symmetric: not one knot's diagram");
            goto done;
        }
    a->span = span;
    i128 at_minus_one = 0;
    for (int k = 0; k <= span; k++) {
        a->coef[k] = sum * coef[lo + k];
        at_minus_one += ((k - span / 2) % 2 ? -1 : 1) * (i128)a->coef[k];
    }
    if (at_minus_one < 0)
        at_minus_one = -at_minus_one;
    if (at_minus_one > (i128)INT64_MAX) {
        rc = tr_fail(err, TR_EUNSUPPORTED, "the determinant does not fit 64 bits");
        goto done;
    }
    a->determinant = (long long)at_minus_one;
done:
    free(use);
    free(parent);
    free(arc);
    free(e0);
    free(e1);
    free(work);
    free(xs);
    free(ys);
    free(poly[0]);
    free(poly[1]);
    if (rc)
        memset(a, 0, sizeof *a);
    return rc;
}

int tr_alexander_equal(const tr_alexander *a, const tr_alexander *b)
{
    if (a->span != b->span)
        return 0;
    int same = 1, opposite = 1;
    for (int k = 0; k <= a->span; k++) {
        same &= a->coef[k] == b->coef[k];
        opposite &= a->coef[k] == -b->coef[k];
    }
    return same || opposite;
}

int tr_knot_invariants_of(const tr_curve *c, tr_knot_invariants *inv, tr_error *err)
{
    memset(inv, 0, sizeof *inv);
    tr_knot_diagram d;
    int rc = tr_knot_diagram_of(c, &d, err);
    if (rc == 0 && d.ncross > TR_ALEXANDER_MAX_CROSSINGS)
        rc = tr_fail(err, TR_EUNSUPPORTED,
                     "the best projection has %d crossings after removing kinks, more than the %d the exact "
                     "Alexander polynomial here handles",
                     d.ncross, TR_ALEXANDER_MAX_CROSSINGS);
    if (rc == 0)
        rc = tr_alexander_from_pd((const int(*)[4])d.pd, d.ncross, &inv->alexander, err);
    if (rc == 0)
        rc = tr_signature_from_pd((const int(*)[4])d.pd, d.ncross, &inv->signature, err);
    if (rc == 0) {
        inv->crossings = d.ncross;
        inv->projected_crossings = d.projected_crossings;
        for (int k = 0; k < 3; k++)
            inv->direction[k] = d.direction[k];
    }
    tr_knot_diagram_free(&d);
    return rc;
}
