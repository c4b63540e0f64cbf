/* tightrope make knot|link NAME | --braid WORD | --pd CODE (cli_make_knot.h). */
#include "cli/cli_make_knot.h"

#include <math.h>
#include <stdio.h>

#include "curve/curve_io.h"
#include "tighten/knot_notation_start.h"

int tr_make_knot_command(int is_link, const char *name, const char *braid_text, const char *pd_text, size_t n,
                         int as_drawn, const char *outpath, const char *version)
{
    tr_error err = {{0}};
    tr_curve c = {0};
    tr_knot_made made;
    tr_knot_notation nt = {.name = name, .braid = braid_text, .pd = pd_text, .want_link = is_link, .n = n,
                          .as_drawn = as_drawn};
    int rc = tr_knot_start_make(&nt, &c, &made, &err);
    if (rc) {
        if (made.other_kind)
            fprintf(stderr, "tightrope make: %s (tightrope make %s %s)\n", err.msg, is_link ? "knot" : "link",
                    made.other_name);
        else if (made.braid_components)
            fprintf(stderr, "tightrope make: %s (a %s: tightrope make %s --braid)\n", err.msg,
                    made.braid_components > 1 ? "link" : "knot", made.braid_components > 1 ? "link" : "knot");
        else
            fprintf(stderr, "tightrope make: %s%s\n", err.msg, rc == TR_EGEOMETRY ? " (nothing written)" : "");
        /* bad notation and unknown names are the user's to mend (2); a made
         * curve not of its type, or no memory, is ours (1) */
        return rc == TR_EINVAL ? 2 : 1;
    }
    int status = 0;
    if ((rc = tr_make_start_check(&c, &err))) {
        fprintf(stderr, "tightrope make: %s: tighten would refuse it: %s\n", made.what, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto done;
    }
    char comments[2600];
    double length = tr_curve_length(&c);
    snprintf(comments, sizeof comments, "%s, %zu vertices, equilateral per component\n%s\nlength %.17g\n"
             "made by tightrope %s%s", made.what, c.nv, made.check, length, version,
             made.from_table ? "\nnotation: KnotInfo/LinkInfo (database_knotinfo, GPL-3.0)" : "");
    if ((rc = tr_curve_write(outpath, TR_FORMAT_AUTO, &c, comments, &err))) {
        fprintf(stderr, "tightrope make: %s\n", err.msg);
        status = 2;
        goto done;
    }
    printf("%s: %s; %zu vertices, length %.10g", outpath, made.what, c.nv, length);
    if (isfinite(made.thickness))
        printf(", thickness %.4g", made.thickness);
    printf("; %s\n", made.check);
done:
    tr_curve_free(&c);
    return status;
}
