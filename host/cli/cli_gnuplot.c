/* This file contains running gnuplot from the command line: finding it on
 * PATH, and fork/exec in the plots' directory with its output to a log
 * (cli_gnuplot.h). */
#include "cli/cli_gnuplot.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int tr_gnuplot_available(void)
{
    const char *path = getenv("PATH");
    if (!path)
        return 0;
    char buf[4096];
    const char *p = path;
    while (*p) {
        const char *q = strchr(p, ':');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        if (len && len + 9 < sizeof buf) {
            memcpy(buf, p, len);
            memcpy(buf + len, "/gnuplot", 9);
            if (access(buf, X_OK) == 0)
                return 1;
        }
        if (!q)
            break;
        p = q + 1;
    }
    return 0;
}

int tr_gnuplot_run(const char *dir, const char *script, const char *log, tr_error *err)
{
    char logp[4096];
    int ml = snprintf(logp, sizeof logp, "%s/%s", dir, log);
    if (ml < 0 || (size_t)ml >= sizeof logp)
        return tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
    pid_t pid = fork();
    if (pid < 0)
        return tr_fail(err, TR_EIO, "cannot start gnuplot: fork failed");
    if (pid == 0) {
        int fd = open(logp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        if (chdir(dir) != 0)
            _exit(126);
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) < 0)
        return tr_fail(err, TR_EIO, "waiting for gnuplot failed");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return tr_fail(err, TR_EIO, "gnuplot failed (status %d); see %s",
                       WIFEXITED(status) ? WEXITSTATUS(status) : -1, logp);
    return TR_OK;
}

int tr_gnuplot_draw(const char *dir, const char *script, const char *log, tr_plot_script *ps, tr_error *err)
{
    int rc = tr_gnuplot_run(dir, script, log, err);
    if (rc != TR_OK) {
        tr_plot_discard(ps);
        return rc;
    }
    return tr_plot_commit(dir, ps, err);
}
