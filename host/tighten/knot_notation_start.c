/* Notation to a checked start (knot_notation_start.h). */
#include "tighten/knot_notation_start.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <threads.h>

#include "curve/generate.h"
#include "curve/pd_layout.h"
#include "tighten/knot_start.h"
#include "topology/knot_table.h"

/* The unknot's start: a circle of radius 3 (as make circle), 32 vertices
 * by default; below 19 its edges are longer than 1. */
#define UNKNOT_RADIUS 3.0
#define UNKNOT_N 32
#define UNKNOT_MIN_N 19
/* samples per crossing of a PD code's planar layout */
#define PD_LAYOUT_SAMPLES 2000

static const char *kind_word(int want_link)
{
    return want_link < 0 ? "knot or link" : want_link ? "link" : "knot";
}

/* the table's entry for nt->name, or a TR_EINVAL naming the nearest */
static int find_entry(const tr_knot_table *table, const tr_knot_notation *nt, tr_knot_made *made,
                      const tr_table_entry **entry, tr_error *err)
{
    *entry = tr_knot_table_find(table, nt->name, nt->want_link);
    if (*entry)
        return TR_OK;
    const tr_table_entry *other = nt->want_link < 0 ? NULL : tr_knot_table_find(table, nt->name, !nt->want_link);
    if (other) {
        made->other_kind = 1;
        snprintf(made->other_name, sizeof made->other_name, "%s", other->name);
        return tr_fail(err, TR_EINVAL, "%s is a %s, not a %s", other->name, nt->want_link ? "knot" : "link",
                       kind_word(nt->want_link));
    }
    char near[256];
    tr_knot_table_suggest(table, nt->name, nt->want_link, near, sizeof near);
    return tr_fail(err, TR_EINVAL, "no %s named '%s' in the table (%s); nearest: %s", kind_word(nt->want_link),
                   nt->name,
                   nt->want_link == 1 ? "LinkInfo's prime links to 9 crossings, L2a1 ... L9n27"
                   : nt->want_link == 0
                       ? "KnotInfo's prime knots to 12 crossings, 0_1, 3_1 ... 10_165, 11a_1 ... 12n_888"
                       : "KnotInfo's knots to 12 crossings, LinkInfo's links to 9",
                   near);
}

/* ", relaxed" after what was made, or why not */
static void say_relaxed(tr_knot_made *made, const tr_knot_notation *nt, int relaxed)
{
    size_t u = strlen(made->what);
    if (!nt->as_drawn)
        snprintf(made->what + u, sizeof made->what - u,
                 relaxed ? ", relaxed" : ", as drawn (too crowded a drawing to relax)");
}

/* A PD code's straight-line drawing relaxed (tr_knot_start_polygon_relaxed),
 * made a start of nt->n vertices */
static int from_pd_polygon(const tr_pd *pd, const tr_knot_notation *nt, tr_curve *out, tr_knot_made *made,
                           tr_error *err)
{
    tr_curve poly = {0}, moved = {0};
    int rc = tr_make_pd_polygon(&poly, (const int(*)[4])pd->x, pd->n, err);
    if (rc == TR_OK && (rc = tr_knot_start_polygon_relaxed(&poly, &moved, err)) == TR_OK)
        rc = tr_knot_start_from_curve(&moved, nt->n, out, &made->thickness, err);
    tr_curve_free(&moved);
    tr_curve_free(&poly);
    return rc;
}

/* a braid word's closure, refused when it is not the kind asked for */
static int from_braid(const tr_braid *b, const tr_knot_notation *nt, int named, tr_curve *out, tr_knot_made *made,
                      tr_error *err)
{
    int nc = tr_braid_components(b, NULL);
    if (!named && ((nt->want_link == 0 && nc != 1) || (nt->want_link == 1 && nc < 2))) {
        made->braid_components = nc;
        return nc > 1 ? tr_fail(err, TR_EINVAL, "braid word: its closure has %d components, not one", nc)
                      : tr_fail(err, TR_EINVAL, "braid word: its closure has one component");
    }
    if (named) {
        size_t u = strlen(made->what);
        snprintf(made->what + u, sizeof made->what - u, ", closure of its %d-strand braid", b->strands);
    } else {
        size_t u = (size_t)snprintf(made->what, sizeof made->what, "%s, closure of the braid ", nc > 1 ? "link" : "knot");
        for (int k = 0; k < b->len && u < sizeof made->what - 16; k++)
            u += (size_t)snprintf(made->what + u, sizeof made->what - u, "%s%d", k ? "," : "", b->word[k]);
        if (u >= sizeof made->what - 16)
            snprintf(made->what + sizeof made->what - 16, 16, "...");
    }
    int relaxed = 0;
    int rc = tr_knot_start_from_braid(b, nt->n, !nt->as_drawn, out, &made->thickness, &relaxed, err);
    say_relaxed(made, nt, relaxed);
    return rc;
}

static int check_type(const tr_curve *c, const tr_table_entry *entry, const tr_pd *pd, tr_knot_made *made,
                      tr_error *err);

/* A knot's start by name: its minimal diagram (KnotInfo's PD code) laid
 * out and relaxed, and its braid's closure relaxed; the shorter of the two
 * at thickness 1.25 is kept (the diagram's type checked here, so that one
 * that failed leaves the closure; the closure's by the caller). The
 * tightening's basin follows the start's conformation, and the more
 * compact start led to the lower basin: the plain command (T = 300) from
 * the diagrams ended at or below KnotInfo for 9_3, 9_8, 9_10, 9_12, where
 * from the braid closures (longer: 151.7 against 140.2 for 9_3, 183.5
 * against 129.1 for 9_8) it ended 1.2-1.4 % above; 9_1's closure is the
 * shorter (105.2 against 108.3), and from it 9_1 ended at 75.6262, from
 * its diagram at 75.9461 (bench/notes/2026-11-30-diagram-starts.md). */
/* the diagram's start, made on a thread of its own beside the closure */
typedef struct diagram_job {
    const tr_table_entry *entry;
    const tr_knot_notation *nt;
    tr_curve dia;
    tr_knot_made dm;
    tr_error err;
    int rc;
} diagram_job;

static int diagram_run(void *arg)
{
    diagram_job *j = arg;
    j->rc = from_pd_polygon(&j->entry->pd, j->nt, &j->dia, &j->dm, &j->err);
    if (j->rc == TR_OK && (j->rc = check_type(&j->dia, j->entry, NULL, &j->dm, &j->err)) != TR_OK)
        tr_curve_free(&j->dia);
    return 0;
}

static int shorter_start(const tr_table_entry *entry, const tr_knot_notation *nt, tr_curve *out,
                         tr_knot_made *made, tr_error *err)
{
    size_t u = strlen(made->what);
    diagram_job job = {.entry = entry, .nt = nt, .dm = *made};
    snprintf(job.dm.what + u, sizeof job.dm.what - u, ", its minimal diagram (KnotInfo's PD code), relaxed");
    /* the two relaxations are most of a make (10_3, two tightenings on
     * the 2 cores beside it: the closure 0.97 s, the diagram 0.29 s): the
     * diagram's runs on a thread beside the closure's; where no thread can
     * be started, after it */
    thrd_t th;
    int threaded = thrd_create(&th, diagram_run, &job) == thrd_success;
    int rc = from_braid(&entry->braid, nt, 1, out, made, err);
    if (threaded)
        thrd_join(th, NULL);
    else
        diagram_run(&job);
    if (job.rc != TR_OK) {
        if (job.rc == TR_ENOMEM && rc == TR_OK) {
            tr_curve_free(out);
            *err = job.err;
            return TR_ENOMEM;
        }
        return rc; /* the closure, or its error */
    }
    double ld = tr_curve_length(&job.dia);
    if (rc == TR_OK) {
        double lb = tr_curve_length(out);
        if (!(ld < lb)) {
            size_t w = strlen(made->what);
            snprintf(made->what + w, sizeof made->what - w, " (shorter than its minimal diagram relaxed: %.1f against "
                     "%.1f)", lb, ld);
            tr_curve_free(&job.dia);
            return TR_OK;
        }
        size_t w = strlen(job.dm.what);
        snprintf(job.dm.what + w, sizeof job.dm.what - w, " (shorter than its braid's closure relaxed: %.1f against "
                 "%.1f)", ld, lb);
        tr_curve_free(out);
    }
    *out = job.dia;
    *made = job.dm;
    return TR_OK;
}

/* The type is checked, never assumed: the invariants of the curve just
 * made, from its own vertices, against the name's or the PD code's. */
static int check_type(const tr_curve *c, const tr_table_entry *entry, const tr_pd *pd, tr_knot_made *made,
                      tr_error *err)
{
    tr_type_check tc;
    int rc = tr_type_check_of(c, &tc, err);
    if (rc && rc != TR_ENOMEM && !entry && !pd) {
        /* a braid word names no type: its invariants are words for the
         * file, and a closure beyond the exact arithmetic (more than
         * TR_TYPE_CHECK_MAX_COMPONENTS components, a crowded projection)
         * is made all the same */
        snprintf(made->check, sizeof made->check, "invariants not computed: %.900s", err->msg);
        return TR_OK;
    }
    /* a curve of our own making whose type cannot be checked is our
     * failure, not bad notation */
    if (rc)
        return tr_fail_wrap(err, rc == TR_ENOMEM ? rc : TR_EGEOMETRY, "%s: its type could not be checked", made->what);
    char got[600], why[1024];
    tr_type_describe(&tc, got, sizeof got);
    if (entry) {
        if (!tr_type_matches(&tc, entry, why, sizeof why))
            return tr_fail(err, TR_EGEOMETRY, "%s: the made curve is not %s: %s", made->what, entry->name, why);
        snprintf(made->check, sizeof made->check, "type checked: %s, as %s's%s", got, entry->name,
                 tr_type_is_mirror(&tc, entry) ? " mirror image's" : "");
    } else if (pd) {
        int m = tr_pd_type_matches(&tc, pd, err);
        if (m < 0)
            return TR_EINVAL;
        if (!m)
            return tr_fail(err, TR_EGEOMETRY, "%s: the laid-out curve's %s is not the PD code's: its layout went wrong",
                           made->what, got);
        snprintf(made->check, sizeof made->check, "type checked: %s, as the PD code's", got);
    } else {
        snprintf(made->check, sizeof made->check, "invariants: %s", got);
    }
    return TR_OK;
}

int tr_knot_start_make(const tr_knot_notation *nt, tr_curve *out, tr_knot_made *made, tr_error *err)
{
    memset(out, 0, sizeof *out);
    memset(made, 0, sizeof *made);
    made->thickness = NAN;
    if ((nt->name != NULL) + (nt->braid != NULL) + (nt->pd != NULL) != 1)
        return tr_fail(err, TR_EINVAL, "a start is made from one of a name, a braid word and a PD code");
    if (nt->pd && nt->want_link == 1)
        return tr_fail(err, TR_EINVAL, "a PD code makes knots only (a link: its name or a braid word)");
    tr_knot_table table = {0};
    const tr_table_entry *entry = NULL;
    tr_braid braid = {0};
    tr_pd pd = {0};
    int rc = TR_OK;
    if (nt->name) {
        if ((rc = tr_knot_table_load(&table, err)) || (rc = find_entry(&table, nt, made, &entry, err)))
            goto done;
        made->from_table = 1;
        snprintf(made->what, sizeof made->what, "%s %s (%s)", entry->is_link ? "link" : "knot", entry->name,
                 entry->is_link ? "LinkInfo" : "KnotInfo");
        if (entry->braid.len == 0) {
            /* the unknot, 0_1: a round circle */
            size_t nv = nt->n ? nt->n : UNKNOT_N;
            if (nv < UNKNOT_MIN_N) {
                rc = tr_fail(err, TR_EINVAL, "%zu vertices make the unknot's edges longer than 1 (at least %d)", nv,
                             UNKNOT_MIN_N);
                goto done;
            }
            rc = tr_make_circle(out, UNKNOT_RADIUS, nv, err);
            size_t u = strlen(made->what);
            snprintf(made->what + u, sizeof made->what - u, ": a circle of radius %g", UNKNOT_RADIUS);
        } else if (!entry->is_link && entry->pd.n >= 3 && !nt->as_drawn) {
            rc = shorter_start(entry, nt, out, made, err);
        } else {
            rc = from_braid(&entry->braid, nt, 1, out, made, err);
        }
    } else if (nt->braid) {
        if (!(rc = tr_braid_parse(nt->braid, &braid, err)))
            rc = from_braid(&braid, nt, 0, out, made, err);
    } else {
        if ((rc = tr_pd_parse(nt->pd, &pd, err)))
            goto done;
        snprintf(made->what, sizeof made->what, "knot from a %d-crossing PD code", pd.n);
        tr_curve dense = {0}, moved = {0};
        if (nt->as_drawn) {
            rc = tr_make_pd_layout(&dense, (const int(*)[4])pd.x, pd.n, (size_t)pd.n * PD_LAYOUT_SAMPLES, err);
            if (rc == TR_OK)
                rc = tr_knot_start_from_curve(&dense, nt->n, out, &made->thickness, err);
        } else {
            rc = tr_make_pd_polygon(&dense, (const int(*)[4])pd.x, pd.n, err);
            if (rc == TR_OK && (rc = tr_knot_start_polygon_relaxed(&dense, &moved, err)) == TR_OK)
                rc = tr_knot_start_from_curve(&moved, nt->n, out, &made->thickness, err);
        }
        say_relaxed(made, nt, 1); /* the polygon is always relaxed (an error says its own words) */
        tr_curve_free(&moved);
        tr_curve_free(&dense);
    }
    /* a construction's message says what it was making */
    if (rc && rc != TR_ENOMEM && made->what[0] && !made->other_kind)
        rc = tr_fail_wrap(err, rc, "%s", made->what);
    if (rc == TR_OK)
        rc = check_type(out, entry, nt->pd ? &pd : NULL, made, err);
done:
    if (rc)
        tr_curve_free(out);
    tr_braid_free(&braid);
    tr_pd_free(&pd);
    tr_knot_table_free(&table);
    return rc;
}
