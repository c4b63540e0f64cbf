/* This file contains the copy of a kept road's checkpoint files
 * (road_checkpoint.h). */
#include "tighten/road_checkpoint.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "solver/newton.h"
#include "util/text_file.h"

/* P.newton (engine/solver_state.c names it so) */
static int state_path(const char *path, char *out, size_t cap, tr_error *err)
{
    int n = snprintf(out, cap, "%s.newton", path);
    if (n < 0 || (size_t)n >= cap)
        return tr_fail(err, TR_EINVAL, "checkpoint path too long: %.200s", path);
    return TR_OK;
}

void tt_road_checkpoint_free(tt_road_checkpoint *c)
{
    free(c->ckpt);
    free(c->state);
    memset(c, 0, sizeof *c);
}

int tt_road_checkpoint_take(const char *path, tt_road_checkpoint *c, tr_error *err)
{
    tt_road_checkpoint_free(c);
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return TR_OK;
    char sp[4096];
    int rc = state_path(path, sp, sizeof sp, err);
    if (rc == TR_OK)
        rc = tr_read_file(path, &c->ckpt, &c->ckpt_len, err);
    if (rc == TR_OK && tr_newton_state_is_file(sp))
        rc = tr_read_file(sp, &c->state, &c->state_len, err);
    if (rc) {
        tt_road_checkpoint_free(c);
        return rc;
    }
    c->taken = 1;
    return TR_OK;
}

int tt_road_checkpoint_put(const char *path, const tt_road_checkpoint *c, tr_error *err)
{
    if (!c->taken)
        return TR_OK;
    char sp[4096];
    int rc = state_path(path, sp, sizeof sp, err);
    if (rc)
        return rc;
    if (c->state)
        rc = tr_write_file_atomic(sp, c->state, c->state_len, err);
    else if (tr_newton_state_is_file(sp) && remove(sp) != 0)
        rc = tr_fail(err, TR_EIO, "cannot remove %.200s, a later road's solver state", sp);
    if (rc == TR_OK)
        rc = tr_write_file_atomic(path, c->ckpt, c->ckpt_len, err);
    return rc;
}
