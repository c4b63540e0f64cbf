/* This file contains running gnuplot from the command line: finding it on
 * PATH, and fork/exec in the plots' directory with its output to a log,
 * stopped on an interrupt (cli_gnuplot.h). */
#include "cli/cli_gnuplot.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli_interrupt.h"
#include "util/text_file.h"

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

/* The last non-empty line of the log (gnuplot puts its error there), for a
 * message: the log itself may not outlive a failed run. */
static void last_line(const char *logp, char *buf, size_t n)
{
    buf[0] = '\0';
    char *text = NULL;
    size_t len = 0;
    if (tr_read_text_file(logp, &text, &len, NULL) != TR_OK)
        return;
    while (len && (text[len - 1] == '\n' || text[len - 1] == ' ' || text[len - 1] == '\r'))
        text[--len] = '\0';
    const char *start = strrchr(text, '\n');
    snprintf(buf, n, "%s", start ? start + 1 : text);
    free(text);
}

/* Stops gnuplot: SIGTERM, and SIGKILL if it is still there after 2 s. */
static void stop_child(pid_t pid)
{
    kill(pid, SIGTERM);
    for (int i = 0; i < 100; i++) {
        if (waitpid(pid, NULL, WNOHANG) == pid)
            return;
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    kill(pid, SIGKILL);
    while (waitpid(pid, NULL, 0) < 0 && errno == EINTR)
        ;
}

int tr_gnuplot_run(const char *dir, const char *script, const char *log, tr_error *err)
{
    char logp[4096];
    int ml = snprintf(logp, sizeof logp, "%s/%s", dir, log);
    if (ml < 0 || (size_t)ml >= sizeof logp)
        return tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
    if (tr_cli_interrupted())
        return tr_fail(err, TR_EINTERRUPTED, "interrupted");
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
    /* Polled, not a blocking waitpid: an interrupt that lands just before
     * the wait would otherwise go unseen until gnuplot ends by itself. On
     * an interrupt gnuplot is stopped and reaped, so none is left running
     * and its half-drawn temporaries can be removed. */
    int status = 0;
    for (;;) {
        if (tr_cli_interrupted()) {
            stop_child(pid);
            return tr_fail(err, TR_EINTERRUPTED, "interrupted while gnuplot was drawing");
        }
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid)
            break;
        if (w < 0 && errno != EINTR)
            return tr_fail(err, TR_EIO, "waiting for gnuplot failed: %s", strerror(errno));
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        char last[512];
        last_line(logp, last, sizeof last);
        return tr_fail(err, TR_EIO, "gnuplot failed (status %d)%s%s",
                       WIFEXITED(status) ? WEXITSTATUS(status) : -1, last[0] ? ": " : "", last);
    }
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
