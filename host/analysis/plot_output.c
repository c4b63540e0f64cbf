/* This file contains the plots' temporary names: reserved beside their final
 * names, renamed into place after gnuplot (plot_output.h). */
#include "analysis/plot_output.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Reserves a fresh temporary name beside dir/name: "name.tmpXXXXXX", created
 * empty with O_EXCL. */
static int reserve_temp(const char *dir, const char *name, unsigned *salt, char *tmp, size_t tmpn)
{
    for (int attempt = 0; attempt < 100; attempt++) {
        *salt = *salt * 1103515245u + 12345u;
        int m = snprintf(tmp, tmpn, "%s/%s.tmp%06x", dir, name, (*salt >> 8) & 0xffffffu);
        if (m < 0 || (size_t)m >= tmpn) {
            errno = ENAMETOOLONG;
            return -1;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            return 0;
        }
        if (errno != EEXIST)
            return -1;
    }
    return -1;
}

/* fsync, then rename over the final name. */
static int commit_temp(const char *tmp, const char *path)
{
    int fd = open(tmp, O_RDONLY);
    if (fd < 0)
        return -1;
    int bad = fsync(fd) != 0;
    bad |= close(fd) != 0;
    if (bad || rename(tmp, path) != 0)
        return -1;
    return 0;
}

int tr_plot_reserve(const char *dir, const char *const *names, size_t n, tr_plot_script *ps,
                    tr_error *err)
{
    ps->n = 0;
    if (n > TR_PLOTS_MAX)
        return tr_fail(err, TR_EINVAL, "%zu plots in one script, at most %d", n, TR_PLOTS_MAX);
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    unsigned salt = (unsigned)getpid() * 2654435761u ^ (unsigned)ts.tv_nsec;
    for (size_t i = 0; i < n; i++) {
        if (reserve_temp(dir, names[i], &salt, ps->tmp[i], sizeof ps->tmp[i])) {
            int rc = tr_fail(err, TR_EIO, "cannot create a temporary file beside %s/%s: %s", dir,
                             names[i], strerror(errno));
            tr_plot_discard(ps);
            return rc;
        }
        ps->name[i] = names[i];
        ps->n = i + 1;
    }
    return TR_OK;
}

const char *tr_plot_tmp_base(const tr_plot_script *ps, const char *dir, size_t i)
{
    return ps->tmp[i] + strlen(dir) + 1;
}

int tr_plot_commit(const char *dir, tr_plot_script *ps, tr_error *err)
{
    /* All drawn: now each takes its name. */
    for (size_t i = 0; i < ps->n; i++) {
        char fin[4096];
        int f = snprintf(fin, sizeof fin, "%s/%s", dir, ps->name[i]);
        if (f < 0 || (size_t)f >= sizeof fin || commit_temp(ps->tmp[i], fin) != 0) {
            int rc = tr_fail(err, TR_EIO, "cannot write %s/%s: %s", dir, ps->name[i], strerror(errno));
            tr_plot_discard(ps);
            return rc;
        }
    }
    ps->n = 0; /* renamed */
    return TR_OK;
}

void tr_plot_discard(tr_plot_script *ps)
{
    for (size_t i = 0; i < ps->n; i++)
        unlink(ps->tmp[i]);
    ps->n = 0;
}
