/* tightrope make knot|link NAME | --braid WORD | --pd CODE (cli_make_knot.h). */
#include "cli/cli_make_knot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tighten/knot_start.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "curve/pd_layout.h"
#include "topology/knot_table.h"
#include "topology/signature.h"

/* The unknot's start: a circle of radius 3 (as make circle), 32 vertices. */
#define UNKNOT_RADIUS 3.0
#define UNKNOT_N 32

int tr_make_knot_command(int is_link, const char *name, const char *braid_text, const char *pd_text, size_t n,
                         const char *outpath, const char *version)
{
    const char *kind = is_link ? "link" : "knot";
    tr_error err = {{0}};
    tr_knot_table table = {0};
    const tr_table_entry *entry = NULL;
    tr_braid braid = {0};
    tr_pd pd = {0};
    tr_curve c = {0};
    char what[512], check[1024] = "", why[1024];
    int status = 0;
    double thickness = NAN;

    if (name) {
        if (tr_knot_table_load(&table, &err)) {
            fprintf(stderr, "tightrope make: the embedded knot table: %s\n", err.msg);
            return 1;
        }
        entry = tr_knot_table_find(&table, name, is_link);
        if (!entry) {
            const tr_table_entry *other = tr_knot_table_find(&table, name, !is_link);
            if (other) {
                fprintf(stderr, "tightrope make: %s is a %s, not a %s (tightrope make %s %s)\n", other->name,
                        is_link ? "knot" : "link", kind, is_link ? "knot" : "link", other->name);
                status = 2;
            } else {
                char near[256];
                tr_knot_table_suggest(&table, name, is_link, near, sizeof near);
                fprintf(stderr, "tightrope make: no %s named '%s' in the table (%s); nearest: %s\n", kind, name,
                        is_link ? "LinkInfo's prime links to 9 crossings, L2a1 ... L9n27"
                                : "KnotInfo's prime knots to 12 crossings, 0_1, 3_1 ... 10_165, 11a_1 ... 12n_888",
                        near);
                status = 2;
            }
            tr_knot_table_free(&table);
            return status;
        }
        snprintf(what, sizeof what, "%s %s (%s)", kind, entry->name, is_link ? "LinkInfo" : "KnotInfo");
    }
    int rc = 0;
    if (entry && entry->braid.len == 0) {
        /* the unknot, 0_1: a round circle */
        size_t nv = n ? n : UNKNOT_N;
        if (2 * 3.14159265358979 * UNKNOT_RADIUS / (double)nv > 1.0) {
            tr_knot_table_free(&table);
            fprintf(stderr, "tightrope make: %zu vertices make the unknot's edges longer than 1 (at least 19)\n", nv);
            return 2;
        }
        rc = tr_make_circle(&c, UNKNOT_RADIUS, nv, &err);
        snprintf(what + strlen(what), sizeof what - strlen(what), ": a circle of radius %g", UNKNOT_RADIUS);
    } else if (entry || braid_text) {
        const tr_braid *b = entry ? &entry->braid : &braid;
        if (braid_text && (rc = tr_braid_parse(braid_text, &braid, &err))) {
            fprintf(stderr, "tightrope make: --braid: %s\n", err.msg);
            return 2;
        }
        int nc = tr_braid_components(b, NULL);
        if (!entry && !is_link && nc != 1) {
            fprintf(stderr, "tightrope make: --braid: its closure has %d components, not one (a link: tightrope make "
                            "link --braid)\n", nc);
            tr_braid_free(&braid);
            return 2;
        }
        if (!entry && is_link && nc < 2) {
            fprintf(stderr, "tightrope make: --braid: its closure has one component (a knot: tightrope make knot "
                            "--braid)\n");
            tr_braid_free(&braid);
            return 2;
        }
        if (!entry) {
            size_t u = (size_t)snprintf(what, sizeof what, "%s, closure of the braid ", kind);
            for (int k = 0; k < b->len && u < sizeof what - 16; k++)
                u += (size_t)snprintf(what + u, sizeof what - u, "%s%d", k ? "," : "", b->word[k]);
            if (u >= sizeof what - 16)
                snprintf(what + sizeof what - 16, 16, "...");
        } else {
            snprintf(what + strlen(what), sizeof what - strlen(what), ", closure of its %d-strand braid",
                     b->strands);
        }
        rc = tr_knot_start_from_braid(b, n, &c, &thickness, &err);
    } else {
        if ((rc = tr_pd_parse(pd_text, &pd, &err))) {
            fprintf(stderr, "tightrope make: --pd: %s\n", err.msg);
            return 2;
        }
        snprintf(what, sizeof what, "knot from a %d-crossing PD code", pd.n);
        tr_curve dense;
        rc = tr_make_pd_layout(&dense, (const int(*)[4])pd.x, pd.n, (size_t)pd.n * 2000, &err);
        if (rc == 0) {
            rc = tr_knot_start_from_curve(&dense, n, &c, &thickness, &err);
            tr_curve_free(&dense);
        }
    }
    if (rc) {
        fprintf(stderr, "tightrope make: %s: %s\n", what, err.msg);
        status = rc == TR_ENOMEM || rc == TR_EGEOMETRY ? 1 : 2;
        goto done;
    }

    /* The type is checked, never assumed: the invariants of the curve just
     * made, from its own vertices, against the name's or the PD code's. */
    tr_type_check tc;
    if ((rc = tr_type_check_of(&c, &tc, &err))) {
        fprintf(stderr, "tightrope make: %s: its type could not be checked: %s\n", what, err.msg);
        status = 1;
        goto done;
    }
    char got[600];
    tr_type_describe(&tc, got, sizeof got);
    if (entry) {
        if (!tr_type_matches(&tc, entry, why, sizeof why)) {
            fprintf(stderr, "tightrope make: %s: the made curve is not %s: %s (nothing written)\n", what, entry->name,
                    why);
            status = 1;
            goto done;
        }
        snprintf(check, sizeof check, "type checked: %s, as %s's%s", got, entry->name,
                 tr_type_is_mirror(&tc, entry) ? " mirror image's" : "");
    } else if (pd_text) {
        int m = tr_pd_type_matches(&tc, &pd, &err);
        if (m < 0) {
            fprintf(stderr, "tightrope make: --pd: %s\n", err.msg);
            status = 2;
            goto done;
        }
        if (!m) {
            fprintf(stderr, "tightrope make: %s: the laid-out curve's %s is not the PD code's (its layout went "
                            "wrong; nothing written)\n", what, got);
            status = 1;
            goto done;
        }
        snprintf(check, sizeof check, "type checked: %s, as the PD code's", got);
    } else {
        snprintf(check, sizeof check, "invariants: %s", got);
    }

    if ((rc = tr_make_start_check(&c, &err))) {
        fprintf(stderr, "tightrope make: %s: tighten would refuse it: %s\n", what, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto done;
    }
    char comments[2600];
    double length = tr_curve_length(&c);
    snprintf(comments, sizeof comments, "%s, %zu vertices, equilateral per component\n%s\nlength %.17g\n"
             "made by tightrope %s%s", what, c.nv, check, length, version,
             name ? "\nnotation: KnotInfo/LinkInfo (database_knotinfo, GPL-3.0)" : "");
    if ((rc = tr_curve_write(outpath, TR_FORMAT_AUTO, &c, comments, &err))) {
        fprintf(stderr, "tightrope make: %s\n", err.msg);
        status = 2;
        goto done;
    }
    printf("%s: %s; %zu vertices, length %.10g", outpath, what, c.nv, length);
    if (isfinite(thickness))
        printf(", thickness %.4g", thickness);
    printf("; %s\n", check);
done:
    tr_curve_free(&c);
    tr_braid_free(&braid);
    tr_pd_free(&pd);
    tr_knot_table_free(&table);
    return status;
}
