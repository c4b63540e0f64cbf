#include "util/text_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int tr_read_file(const char *path, char **text, size_t *len, tr_error *err)
{
    *text = NULL;
    if (len)
        *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return tr_fail(err, TR_EIO, "cannot open %s: %s", path, strerror(errno));
    /* fopen succeeds on a directory; the read would fail with EISDIR, but
     * say so plainly before that */
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        return tr_fail(err, TR_EIO, "cannot read %s: %s", path, strerror(EISDIR));
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (cap - n < 65536) {
            size_t ncap = cap ? 2 * cap : 1 << 16;
            char *g = realloc(buf, ncap);
            if (!g) {
                free(buf);
                fclose(f);
                return tr_fail(err, TR_ENOMEM, "out of memory reading %s", path);
            }
            buf = g;
            cap = ncap;
        }
        size_t r = fread(buf + n, 1, cap - n - 1, f);
        n += r;
        if (r == 0)
            break;
    }
    int bad = ferror(f), e = errno;
    fclose(f);
    if (bad) {
        free(buf);
        return tr_fail(err, TR_EIO, "cannot read %s: %s", path, strerror(e));
    }
    buf[n] = '\0';
    *text = buf;
    if (len)
        *len = n;
    return TR_OK;
}

/* Temporary name beside the target (same file system, so rename is atomic),
 * created with O_EXCL; the suffix mixes the pid and the clock, and a clash
 * just tries the next one. */
static int open_temp(const char *path, char *tmp, size_t tmpn)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t salt = ((uint64_t)getpid() << 32) ^ (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 20);
    for (int attempt = 0; attempt < 100; attempt++) {
        salt = salt * 6364136223846793005ULL + 1442695040888963407ULL;
        int m = snprintf(tmp, tmpn, "%s.tmp%06x", path, (unsigned)(salt >> 40));
        if (m < 0 || (size_t)m >= tmpn) {
            errno = ENAMETOOLONG;
            return -1;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    return -1;
}

int tr_check_writable(const char *path, tr_error *err)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(EISDIR));
    char tmp[4096];
    int fd = open_temp(path, tmp, sizeof tmp);
    if (fd < 0)
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
    close(fd);
    unlink(tmp);
    return TR_OK;
}

int tr_write_file_atomic(const char *path, const char *text, size_t len, tr_error *err)
{
    char tmp[4096];
    int fd = open_temp(path, tmp, sizeof tmp);
    if (fd < 0)
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
    size_t done = 0;
    while (done < len) {
        ssize_t w = write(fd, text + done, len - done);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            int e = errno;
            close(fd);
            unlink(tmp);
            return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(e));
        }
        done += (size_t)w;
    }
    if (fsync(fd) != 0) {
        int e = errno;
        close(fd);
        unlink(tmp);
        return tr_fail(err, TR_EIO, "cannot sync %s: %s", path, strerror(e));
    }
    if (close(fd) != 0) {
        int e = errno;
        unlink(tmp);
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(e));
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        return tr_fail(err, TR_EIO, "cannot replace %s: %s", path, strerror(e));
    }
    /* Make the rename itself durable; a failure here loses nothing that is
     * already visible, so it is not an error. */
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (slash) {
        size_t n = (size_t)(slash - path);
        if (n == 0)
            n = 1;
        if (n < sizeof dir) {
            memcpy(dir, path, n);
            dir[n] = '\0';
        } else {
            dir[0] = '\0';
        }
    } else {
        strcpy(dir, ".");
    }
    if (dir[0]) {
        int dfd = open(dir, O_RDONLY);
        if (dfd >= 0) {
            (void)fsync(dfd);
            close(dfd);
        }
    }
    return TR_OK;
}

void tr_text_printf(tr_text *t, const char *fmt, ...)
{
    if (t->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = t->cap - t->n;
        int k = vsnprintf(t->s ? t->s + t->n : NULL, room, fmt, ap);
        va_end(ap);
        if (k < 0) {
            t->oom = 1;
            return;
        }
        if ((size_t)k < room) {
            t->n += (size_t)k;
            return;
        }
        size_t cap = t->cap ? 2 * t->cap : 4096;
        while (cap - t->n <= (size_t)k)
            cap *= 2;
        char *g = realloc(t->s, cap);
        if (!g) {
            t->oom = 1;
            return;
        }
        t->s = g;
        t->cap = cap;
    }
}

int tr_text_write_atomic(tr_text *t, const char *path, tr_error *err)
{
    size_t n;
    char *s = tr_text_take(t, &n);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory formatting %s", path);
    int rc = tr_write_file_atomic(path, s, n, err);
    free(s);
    return rc;
}

char *tr_text_take(tr_text *t, size_t *len)
{
    char *s = t->s;
    if (t->oom || !s) {
        free(s);
        s = t->oom ? NULL : calloc(1, 1);
    }
    if (len)
        *len = s ? t->n : 0;
    t->s = NULL;
    t->n = t->cap = 0;
    t->oom = 0;
    return s;
}
