/* This file contains whole-file reading, atomic writing (temporary in the
 * target's directory, renamed; in place for a device, a FIFO or a standard
 * stream) and the growing text buffer (text_file.h). */
#include "util/text_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Reads path whole. What is allocated is bounded by what the file holds:
 * a regular file's size up front (grown only if it grows meanwhile), and
 * for a device or a pipe, which has no size, chunks as they come; with
 * text_only the read stops at the first NUL byte (a text file has none),
 * so /dev/zero costs one chunk, not memory until it runs out. */
static int read_all(const char *path, int text_only, char **text, size_t *len, tr_error *err)
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
    int have_st = fstat(fileno(f), &st) == 0;
    if (have_st && S_ISDIR(st.st_mode)) {
        fclose(f);
        return tr_fail(err, TR_EIO, "cannot read %s: %s", path, strerror(EISDIR));
    }
    size_t want = 1 << 16;
    if (have_st && S_ISREG(st.st_mode) && st.st_size >= 0 && (uintmax_t)st.st_size < SIZE_MAX - 2)
        want = (size_t)st.st_size + 2; /* +1 for the NUL, +1 to see the end */
    char *buf = NULL;
    size_t n = 0, cap = 0, lines = 1;
    for (;;) {
        if (cap - n < 2) {
            size_t ncap = cap ? (cap > SIZE_MAX / 2 ? SIZE_MAX : 2 * cap) : want;
            char *g = ncap > cap ? realloc(buf, ncap) : NULL;
            if (!g) {
                free(buf);
                fclose(f);
                return tr_fail(err, TR_ENOMEM, "out of memory reading %s (%zu bytes read)", path, n);
            }
            buf = g;
            cap = ncap;
        }
        size_t r = fread(buf + n, 1, cap - n - 1, f);
        if (text_only) {
            const char *z = memchr(buf + n, '\0', r);
            for (const char *p = buf + n; p < (z ? z : buf + n + r); p++)
                lines += *p == '\n';
            if (z) {
                size_t at = n + (size_t)(z - (buf + n));
                free(buf);
                fclose(f);
                return tr_fail(err, TR_EPARSE, "%.200s:%zu: a NUL byte at offset %zu: not a text file", path,
                               lines, at);
            }
        }
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

int tr_read_file(const char *path, char **text, size_t *len, tr_error *err)
{
    return read_all(path, 0, text, len, err);
}

int tr_read_text_file(const char *path, char **text, size_t *len, tr_error *err)
{
    return read_all(path, 1, text, len, err);
}

int tr_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* The file a write to path lands in: path itself, or, if path is a symbolic
 * link, what it points to (followed as open() would, also when the final
 * target does not exist yet), so that the rename replaces the target and
 * leaves the link. Returns 0, or -1 with errno (ELOOP, ENAMETOOLONG). */
static int resolve_target(const char *path, char *out, size_t outn)
{
    char cur[PATH_MAX];
    if (strlen(path) >= sizeof cur) {
        errno = ENAMETOOLONG;
        return -1;
    }
    strcpy(cur, path);
    for (int hops = 0;; hops++) {
        struct stat st;
        if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode))
            break;
        if (hops >= 40) {
            errno = ELOOP;
            return -1;
        }
        char link[PATH_MAX];
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n < 0)
            return -1;
        link[n] = '\0';
        char next[PATH_MAX];
        const char *slash = strrchr(cur, '/');
        int m;
        if (link[0] == '/' || !slash)
            m = snprintf(next, sizeof next, "%s", link);
        else /* relative to the link's own directory */
            m = snprintf(next, sizeof next, "%.*s/%s", (int)(slash - cur), cur, link);
        if (m < 0 || (size_t)m >= sizeof next) {
            errno = ENAMETOOLONG;
            return -1;
        }
        strcpy(cur, next);
    }
    if (strlen(cur) >= outn) {
        errno = ENAMETOOLONG;
        return -1;
    }
    strcpy(out, cur);
    return 0;
}

/* The directory part of path ("." if none), into dir. */
static int dir_of(const char *path, char *dir, size_t dirn)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) : 1;
    if (slash && n == 0)
        n = 1; /* "/name": the root */
    if (n >= dirn) {
        errno = ENAMETOOLONG;
        return -1;
    }
    memcpy(dir, slash ? path : ".", n);
    dir[n] = '\0';
    return 0;
}

/* A new temporary file in directory dir, created with O_EXCL: a short
 * hidden name, ".tr.XXXXXX" (6 characters from the pid and the clock; a
 * clash tries the next), so that it fits wherever the target's name fits,
 * is on the same file system (rename is atomic) and is recognisable. */
static int open_temp(const char *dir, char *tmp, size_t tmpn)
{
    static const char digits[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t salt = ((uint64_t)getpid() << 32) ^ (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 20);
    for (int attempt = 0; attempt < 100; attempt++) {
        salt = salt * 6364136223846793005ULL + 1442695040888963407ULL;
        char suffix[7];
        uint64_t v = salt >> 16;
        for (int i = 0; i < 6; i++, v /= 62)
            suffix[i] = digits[v % 62];
        suffix[6] = '\0';
        int m = snprintf(tmp, tmpn, "%s/.tr.%s", dir, suffix);
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

/* The standard stream, 1 or 2, that the file st describes already is, or -1.
 * A path naming it (/dev/stdout, /dev/fd/2, or the file or pipe the shell
 * redirected the stream to) is written through that descriptor: it keeps
 * the shell's offset and O_APPEND (`>> log` appends), where a reopened file
 * would be written from its start and a file renamed over would take the
 * rest of the stream into a file no longer in the folder. */
static int std_stream_of(const struct stat *st)
{
    for (int fd = 1; fd <= 2; fd++) {
        struct stat s;
        if (fstat(fd, &s) == 0 && s.st_dev == st->st_dev && s.st_ino == st->st_ino)
            return fd;
    }
    return -1;
}

/* Whether a write to path, which stat describes, goes in place rather than
 * through a temporary renamed over it: a device, a FIFO or a socket is not
 * ours to replace (the rename would put a regular file where /dev/null was),
 * and one of our own standard streams is written through its descriptor. */
static int in_place(const struct stat *st)
{
    return std_stream_of(st) >= 0 || (!S_ISREG(st->st_mode) && !S_ISDIR(st->st_mode));
}

int tr_check_writable(const char *path, tr_error *err)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(EISDIR));
    /* Written in place: what counts is the file's own permission, not its
     * directory's (a user cannot create files in /dev, but writes /dev/null). */
    if (stat(path, &st) == 0 && in_place(&st)) {
        if (std_stream_of(&st) >= 0)
            return TR_OK;
        if (S_ISSOCK(st.st_mode))
            return tr_fail(err, TR_EIO, "cannot write %s: it is a socket, not a file", path);
        if (faccessat(AT_FDCWD, path, W_OK, AT_EACCESS) != 0)
            return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
        return TR_OK;
    }
    char target[PATH_MAX], dir[PATH_MAX], tmp[PATH_MAX + 16];
    int fd = -1;
    if (resolve_target(path, target, sizeof target) == 0 && dir_of(target, dir, sizeof dir) == 0)
        fd = open_temp(dir, tmp, sizeof tmp);
    if (fd < 0)
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
    close(fd);
    unlink(tmp);
    return TR_OK;
}

/* Writes all of text to fd, fsyncs and closes it (also on failure);
 * 0 or the errno, *what naming the step that failed. */
static int fill_temp(int fd, const char *text, size_t len, const char **what)
{
    int e = 0;
    *what = "write";
    for (size_t done = 0; done < len && !e;) {
        ssize_t w = write(fd, text + done, len - done);
        if (w >= 0)
            done += (size_t)w;
        else if (errno != EINTR)
            e = errno;
    }
    if (!e && fsync(fd) != 0)
        e = errno, *what = "sync";
    if (close(fd) != 0 && !e)
        e = errno, *what = "write";
    return e;
}

/* Signals that would end the process between creating the temporary and
 * renaming it are held back for that moment, so an interrupt or a kill(1)
 * never leaves a temporary behind: only SIGKILL or a crash can, and then
 * what remains is a hidden .tr.XXXXXX beside the target (the target itself
 * is the old file or the new one, never a part). */
static void hold_signals(sigset_t *old)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    sigaddset(&set, SIGQUIT);
    sigaddset(&set, SIGPIPE);
    sigprocmask(SIG_BLOCK, &set, old);
}

/* tr_write_file_atomic's answer when the file stopped being a device between
 * the stat and the open: the atomic way is taken after all. */
#define RACED 1

/* Writes text in place into what path names, a device or a FIFO (a socket
 * cannot be opened: refused), or into stream (1 or 2, when path is one of
 * ours, else -1): no temporary, no
 * rename, no O_CREAT or O_TRUNC, every byte written or an error naming path
 * (/dev/full: "No space left on device"). A FIFO's open waits for a reader,
 * as a shell's redirection does; a signal that interrupts it or a write
 * ends the write with an error rather than retrying, so Ctrl-C still stops
 * a program writing into a pipe nobody reads. SIGPIPE is ignored meanwhile:
 * a reader that went away is an EPIPE error, not the end of the process. */
static int write_in_place(const char *path, int stream, const char *text, size_t len, tr_error *err)
{
    int fd = stream;
    if (fd < 0) {
        fd = open(path, O_WRONLY | O_NOCTTY | O_CLOEXEC);
        if (fd < 0) {
            int e = errno;
            struct stat st;
            if (e == ENXIO && stat(path, &st) == 0 && S_ISSOCK(st.st_mode))
                return tr_fail(err, TR_EIO, "cannot write %s: it is a socket, not a file", path);
            return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(e));
        }
        struct stat st;
        if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
            close(fd);
            return RACED;
        }
    } else {
        /* what the program printed before comes first */
        fflush(stream == 1 ? stdout : stderr);
    }
    struct sigaction ign, old;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    sigemptyset(&ign.sa_mask);
    sigaction(SIGPIPE, &ign, &old);
    int e = 0;
    for (size_t done = 0; done < len && !e;) {
        ssize_t w = write(fd, text + done, len - done);
        if (w > 0)
            done += (size_t)w;
        else
            e = w < 0 ? errno : EIO; /* 0 bytes for a non-empty write: nothing more fits */
    }
    /* A disk's blocks are made durable; a pipe or a character device has
     * nothing to sync (EINVAL). */
    struct stat st;
    if (!e && fstat(fd, &st) == 0 && (S_ISBLK(st.st_mode) || S_ISREG(st.st_mode)) && fsync(fd) != 0 &&
        errno != EINVAL)
        e = errno;
    if (stream < 0 && close(fd) != 0 && !e && errno != EINTR)
        e = errno;
    sigaction(SIGPIPE, &old, NULL);
    if (e)
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(e));
    return TR_OK;
}

int tr_write_file_atomic(const char *path, const char *text, size_t len, tr_error *err)
{
    /* stat, not the link walk below: the kernel follows links the way a
     * write would, also /dev/stdout's through /proc */
    struct stat pst;
    if (stat(path, &pst) == 0 && in_place(&pst)) {
        int rc = write_in_place(path, std_stream_of(&pst), text, len, err);
        if (rc != RACED)
            return rc;
    }
    /* Through a symbolic link the link stays and its target is replaced. */
    char target[PATH_MAX], dir[PATH_MAX], tmp[PATH_MAX + 16];
    if (resolve_target(path, target, sizeof target) != 0 || dir_of(target, dir, sizeof dir) != 0)
        return tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
    sigset_t old;
    hold_signals(&old);
    int rc = TR_OK;
    int fd = open_temp(dir, tmp, sizeof tmp);
    if (fd < 0) {
        rc = tr_fail(err, TR_EIO, "cannot write %s: %s", path, strerror(errno));
        goto out;
    }
    /* An existing file keeps its permissions (a new one gets 0666 less
     * the umask, from open). */
    struct stat st;
    if (stat(target, &st) == 0 && S_ISREG(st.st_mode) && fchmod(fd, st.st_mode & 07777) != 0) {
        int e = errno;
        close(fd);
        unlink(tmp);
        rc = tr_fail(err, TR_EIO, "cannot keep the mode of %s: %s", path, strerror(e));
        goto out;
    }
    const char *what;
    int e = fill_temp(fd, text, len, &what);
    if (e) {
        unlink(tmp);
        rc = tr_fail(err, TR_EIO, "cannot %s %s: %s", what, path, strerror(e));
        goto out;
    }
    if (rename(tmp, target) != 0) {
        e = errno;
        unlink(tmp);
        rc = tr_fail(err, TR_EIO, "cannot replace %s: %s", path, strerror(e));
        goto out;
    }
    /* Make the rename itself durable; a failure here loses nothing that is
     * already visible, so it is not an error. */
    int dfd = open(dir, O_RDONLY);
    if (dfd >= 0) {
        (void)fsync(dfd);
        close(dfd);
    }
out:
    sigprocmask(SIG_SETMASK, &old, NULL);
    return rc;
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
