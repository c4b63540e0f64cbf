/* Starts by name of a batch (batch_start.h). */
#include "cli/batch_start.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "curve/curve_io.h"
#include "tighten/knot_notation_start.h"

int tr_batch_make_start(const tr_batch_knot *k, tr_error *err)
{
    if (k->from == TR_BATCH_FROM_FILE)
        return TR_OK;
    /* OUT/starts: made on the first start by name (the table's name is
     * what follows "knot:" or "link:") */
    const char *slash = strrchr(k->file, '/');
    size_t dl = slash ? (size_t)(slash - k->file) : 0;
    char *dir = slash ? strndup(k->file, dl) : NULL;
    if (slash && !dir)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    if (dir && mkdir(dir, 0777) && errno != EEXIST) {
        int rc = tr_fail(err, TR_EIO, "cannot make the folder %s for the starts by name: %s", dir, strerror(errno));
        free(dir);
        return rc;
    }
    free(dir);
    const char *name = strchr(k->source, ':') + 1;
    int is_link = k->from == TR_BATCH_FROM_LINK;
    tr_curve c;
    tr_knot_made made;
    /* n 0: as many vertices as make knot gives it; the manifest's N is
     * tighten's (--refine-to or --n), as for a file */
    tr_knot_notation nt = {.name = name, .want_link = is_link};
    int rc = tr_knot_start_make(&nt, &c, &made, err);
    if (rc)
        return rc;
    char comments[2048];
    snprintf(comments, sizeof comments,
             "%s, %zu vertices, equilateral per component\n%s\n"
             "made by tightrope batch as tightrope make %s %s makes it; %s\n"
             "notation: KnotInfo/LinkInfo (database_knotinfo, GPL-3.0)",
             made.what, c.nv, made.check, is_link ? "link" : "knot", name, k->notation);
    rc = tr_curve_write(k->file, TR_FORMAT_AUTO, &c, comments, err);
    tr_curve_free(&c);
    return rc;
}
