/* This file contains the all-or-nothing output folder: the staging folder,
 * the record of what the command wrote, the commit, its undo and the
 * removal of the earlier runs' files (out_folder.h). */
#include "util/out_folder.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/text_file.h"

#define STAGE_PREFIX ".tr-stage."

/* ---- the record -------------------------------------------------------- */

/* FNV-1a, 64 bits, of the bytes of a regular file: what tells the file the
 * command wrote from one put there under its name since (not a defence
 * against someone forging a file, which would need write access to the
 * folder anyway). 0 on success. */
static int hash_file(const char *path, uint64_t *size, uint64_t *hash)
{
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return -1;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return -1;
    }
    uint64_t h = 14695981039346656037ULL, n = 0;
    static unsigned char buf[1 << 16];
    for (;;) {
        ssize_t r = read(fd, buf, sizeof buf);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            close(fd);
            return -1;
        }
        if (r == 0)
            break;
        for (ssize_t i = 0; i < r; i++)
            h = (h ^ buf[i]) * 1099511628211ULL;
        n += (uint64_t)r;
    }
    close(fd);
    *size = n, *hash = h;
    return 0;
}

/* A relative name the record may hold: "name", "sub/" or "sub/name", with
 * no empty, "." or ".." part and not the stage. A record edited to name
 * anything else (../x, /etc/x) is not believed. */
static int sane_rel(const char *rel, int dir)
{
    size_t len = strlen(rel);
    if (!len || rel[0] == '/' || (dir && rel[len - 1] != '/') || (!dir && rel[len - 1] == '/'))
        return 0;
    int parts = 0;
    for (const char *p = rel; *p;) {
        const char *q = strchr(p, '/');
        size_t m = q ? (size_t)(q - p) : strlen(p);
        if (!m || (m == 1 && p[0] == '.') || (m == 2 && p[0] == '.' && p[1] == '.') ||
            !strncmp(p, STAGE_PREFIX, strlen(STAGE_PREFIX)))
            return 0;
        parts++;
        if (!q)
            break;
        p = q + 1;
    }
    return parts <= 2 && (!dir || parts == 1);
}

static int list_add(tr_out_list *l, const char *rel, int dir, uint64_t size, uint64_t hash)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        tr_out_entry *g = realloc(l->e, cap * sizeof *g);
        if (!g)
            return -1;
        l->e = g, l->cap = cap;
    }
    char *r = strdup(rel);
    if (!r)
        return -1;
    l->e[l->n++] = (tr_out_entry){r, dir, size, hash};
    return 0;
}

static void list_free(tr_out_list *l)
{
    for (size_t i = 0; i < l->n; i++)
        free(l->e[i].rel);
    free(l->e);
    memset(l, 0, sizeof *l);
}

static void header(char *buf, size_t n, const char *owner)
{
    snprintf(buf, n, "# written by %s: the files it wrote in this folder; it replaces or removes only these, "
                     "and only while unchanged\n", owner);
}

/* Reads the record of earlier runs into f->old. A missing record is an
 * empty one; anything but a regular file that starts with our header is
 * someone else's file under the record's name. */
static int read_record(tr_out_folder *f, tr_error *err)
{
    struct stat st;
    if (lstat(f->record, &st) != 0)
        return errno == ENOENT ? TR_OK : tr_fail(err, TR_EIO, "cannot read %s: %s", f->record, strerror(errno));
    char head[512];
    header(head, sizeof head, f->owner);
    char *text = NULL;
    if (!S_ISREG(st.st_mode) || tr_read_text_file(f->record, &text, NULL, NULL) != TR_OK ||
        strncmp(text, head, strlen(head)) != 0) {
        free(text);
        return tr_fail(err, TR_EIO,
                       "%s is not the record %s keeps of its files there; move it or choose another folder",
                       f->record, f->owner);
    }
    int rc = TR_OK;
    for (char *line = text + strlen(head), *next; *line && rc == TR_OK; line = next) {
        next = strchr(line, '\n');
        next = next ? (*next = '\0', next + 1) : line + strlen(line);
        char rel[4096];
        uint64_t size, hash;
        /* a line that does not parse lists nothing: fewer files are ours */
        if (sscanf(line, "file %" SCNx64 " %" SCNu64 " %4095[^\n]", &hash, &size, rel) == 3 && sane_rel(rel, 0))
            rc = list_add(&f->old, rel, 0, size, hash);
        else if (sscanf(line, "dir %4095[^\n]", rel) == 1 && sane_rel(rel, 1))
            rc = list_add(&f->old, rel, 1, 0, 0);
    }
    free(text);
    return rc == TR_OK ? TR_OK : tr_fail(err, TR_ENOMEM, "out of memory reading %s", f->record);
}

/* Whether the regular file at path is one the record lists under rel, with
 * the bytes it had then (any of the versions listed: a record written
 * before a commit lists the earlier run's and this run's). */
static int recorded(const tr_out_list *l, const char *rel, const char *path)
{
    uint64_t size = 0, hash = 0;
    int have = 0;
    for (size_t i = 0; i < l->n; i++) {
        if (l->e[i].dir || strcmp(l->e[i].rel, rel) != 0)
            continue;
        if (!have && hash_file(path, &size, &hash) != 0)
            return 0;
        have = 1;
        if (l->e[i].size == size && l->e[i].hash == hash)
            return 1;
    }
    return 0;
}

static int listed_dir(const tr_out_list *l, const char *rel)
{
    for (size_t i = 0; i < l->n; i++)
        if (l->e[i].dir && !strcmp(l->e[i].rel, rel))
            return 1;
    return 0;
}

static int listed_file(const tr_out_list *l, const char *rel)
{
    for (size_t i = 0; i < l->n; i++)
        if (!l->e[i].dir && !strcmp(l->e[i].rel, rel))
            return 1;
    return 0;
}

static void append_entries(tr_text *t, const tr_out_list *l)
{
    for (size_t i = 0; i < l->n; i++) {
        if (l->e[i].dir)
            tr_text_printf(t, "dir %s\n", l->e[i].rel);
        else
            tr_text_printf(t, "file %016" PRIx64 " %" PRIu64 " %s\n", l->e[i].hash, l->e[i].size, l->e[i].rel);
    }
}

/* ---- paths and signals ------------------------------------------------- */

static int join(char *buf, size_t n, const char *a, const char *b)
{
    int m = snprintf(buf, n, "%s/%s", a, b);
    return m >= 0 && (size_t)m < n ? 0 : -1;
}

/* base/rel, without the trailing '/' of a subfolder's rel. */
static int target_of(const char *base, const char *rel, char *buf, size_t n)
{
    if (join(buf, n, base, rel) != 0)
        return -1;
    size_t len = strlen(buf);
    if (len && buf[len - 1] == '/')
        buf[len - 1] = '\0';
    return 0;
}

/* The moves, the undo and the clean-up run with the interrupting signals
 * held back: a Ctrl-C between two renames would leave half a run. */
static void hold(sigset_t *old)
{
    sigset_t s;
    sigemptyset(&s);
    sigaddset(&s, SIGINT);
    sigaddset(&s, SIGTERM);
    sigaddset(&s, SIGHUP);
    sigaddset(&s, SIGQUIT);
    sigprocmask(SIG_BLOCK, &s, old);
}

/* Removes the stage and what is in it: a folder this run made with
 * mkdtemp, so everything in it is the run's own (its files, gnuplot's
 * temporaries, the backups of a commit), one level of subfolders deep. */
static void remove_stage(const char *dir, int depth)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char p[4400];
            struct stat st;
            if (join(p, sizeof p, dir, e->d_name) != 0 || lstat(p, &st) != 0)
                continue;
            if (S_ISDIR(st.st_mode) && depth == 0)
                remove_stage(p, 1);
            else
                unlink(p);
        }
        closedir(d);
    }
    rmdir(dir);
}

/* ---- the run ------------------------------------------------------------ */

int tr_out_folder_open(tr_out_folder *f, const char *out, const char *record, const char *owner, tr_error *err)
{
    memset(f, 0, sizeof *f);
    f->owner = owner;
    if (strlen(out) + 1 >= sizeof f->out || join(f->record, sizeof f->record, out, record) != 0 ||
        join(f->stage, sizeof f->stage, out, STAGE_PREFIX "XXXXXX") != 0)
        return tr_fail(err, TR_EINVAL, "%s: output path too long", out);
    strcpy(f->out, out);
    if (mkdir(out, 0777) == 0) {
        f->made_out = 1;
    } else {
        struct stat st;
        int e = errno;
        if (e != EEXIST || stat(out, &st) != 0 || !S_ISDIR(st.st_mode))
            return tr_fail(err, TR_EIO, "cannot create directory %s: %s", out, strerror(e == EEXIST ? ENOTDIR : e));
    }
    int rc = read_record(f, err);
    if (rc == TR_OK && !mkdtemp(f->stage))
        rc = tr_fail(err, TR_EIO, "cannot write in %s: %s", out, strerror(errno));
    if (rc != TR_OK) {
        list_free(&f->old);
        if (f->made_out)
            rmdir(out);
        f->stage[0] = '\0';
    }
    return rc;
}

const char *tr_out_folder_stage(const tr_out_folder *f) { return f->stage; }

const char *tr_out_folder_shown(const tr_out_folder *f, const char *msg, char *buf, size_t n)
{
    size_t k = 0, sl = strlen(f->stage), ol = strlen(f->out);
    if (!n)
        return buf;
    while (*msg && k + 1 < n) {
        if (sl && !strncmp(msg, f->stage, sl)) {
            size_t c = ol < n - 1 - k ? ol : n - 1 - k;
            memcpy(buf + k, f->out, c);
            k += c, msg += sl;
        } else {
            buf[k++] = *msg++;
        }
    }
    buf[k] = '\0';
    return buf;
}

static int by_rel(const void *a, const void *b)
{
    return strcmp(((const tr_out_entry *)a)->rel, ((const tr_out_entry *)b)->rel);
}

/* Lists the stage's files (and its subfolders, as "sub/") into f->now,
 * sorted, so that a subfolder comes before its files. */
static int scan_stage(tr_out_folder *f, const char *dir, const char *prefix, tr_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return tr_fail(err, TR_EIO, "cannot read %s: %s", dir, strerror(errno));
    int rc = TR_OK;
    struct dirent *e;
    while (rc == TR_OK && (e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        char p[4400], rel[512];
        struct stat st;
        if (join(p, sizeof p, dir, e->d_name) != 0 ||
            snprintf(rel, sizeof rel, "%s%s", prefix, e->d_name) >= (int)sizeof rel || lstat(p, &st) != 0) {
            rc = tr_fail(err, TR_EIO, "cannot read %s/%s", dir, e->d_name);
        } else if (S_ISDIR(st.st_mode) && !*prefix) {
            strcat(rel, "/");
            if (list_add(&f->now, rel, 1, 0, 0) != 0)
                rc = tr_fail(err, TR_ENOMEM, "out of memory");
            else
                rc = scan_stage(f, p, rel, err);
        } else if (S_ISREG(st.st_mode)) {
            uint64_t size, hash;
            if (hash_file(p, &size, &hash) != 0)
                rc = tr_fail(err, TR_EIO, "cannot read %s: %s", p, strerror(errno));
            else if (list_add(&f->now, rel, 0, size, hash) != 0)
                rc = tr_fail(err, TR_ENOMEM, "out of memory");
        } else {
            rc = tr_fail(err, TR_EIO, "%s: not a regular file", p);
        }
    }
    closedir(d);
    return rc;
}

/* Whether path is one of the n paths in keep (the run's inputs). */
static const char *kept(const char *path, const char *const *keep, size_t n)
{
    for (size_t j = 0; j < n; j++)
        if (keep[j] && tr_same_file(path, keep[j]))
            return keep[j];
    return NULL;
}

/* Nothing moves until every file in the way is known to be ours. */
static int check_targets(const tr_out_folder *f, const char *const *keep, size_t nkeep, tr_error *err)
{
    for (size_t i = 0; i < f->now.n; i++) {
        const tr_out_entry *e = &f->now.e[i];
        char t[4400];
        struct stat st;
        if (target_of(f->out, e->rel, t, sizeof t) != 0)
            return tr_fail(err, TR_EINVAL, "%s: output path too long", f->out);
        if (lstat(t, &st) != 0) {
            if (errno == ENOENT)
                continue;
            return tr_fail(err, TR_EIO, "cannot write %s: %s", t, strerror(errno));
        }
        const char *in = kept(t, keep, nkeep);
        if (in)
            return tr_fail(err, TR_EIO, "the output %s is the input %s; write elsewhere", t, in);
        if (e->dir && !S_ISDIR(st.st_mode))
            return tr_fail(err, TR_EIO, "%s is in the way: not a directory; move it or choose another folder", t);
        if (!e->dir && !S_ISREG(st.st_mode))
            return tr_fail(err, TR_EIO, "will not replace %s: not a regular file; move it or choose another folder", t);
        if (!e->dir && !recorded(&f->old, e->rel, t))
            return tr_fail(err, TR_EIO, "will not replace %s: not a file %s wrote (or it changed since); "
                           "move it or choose another folder", t, f->owner);
    }
    return TR_OK;
}

/* Puts the folder back as it was before the commit's moves. */
static void undo(tr_out_folder *f)
{
    int lossy = 0; /* an earlier file replaced with no copy kept */
    for (size_t i = f->now.n; i-- > 0;) {
        const tr_out_entry *e = &f->now.e[i];
        char t[4400], b[4400];
        if (e->dir || !(f->backed[i] & 2) || target_of(f->out, e->rel, t, sizeof t) != 0)
            continue;
        snprintf(b, sizeof b, "%s/.old.%zu", f->stage, i);
        if (f->backed[i] & 1)
            rename(b, t);
        else if (f->backed[i] & 4)
            lossy = 1; /* the new file stays: better than none */
        else
            unlink(t);
    }
    for (size_t i = f->now.n; i-- > 0;) {
        char t[4400];
        if (f->madedir[i] && target_of(f->out, f->now.e[i].rel, t, sizeof t) == 0)
            rmdir(t);
    }
    if (f->record_written && !lossy) {
        char b[4400];
        snprintf(b, sizeof b, "%s/.old.record", f->stage);
        if (f->record_backed_up)
            rename(b, f->record);
        else
            unlink(f->record);
    }
    f->committed = 0;
}

int tr_out_folder_commit(tr_out_folder *f, const char *const *keep, size_t nkeep, tr_error *err)
{
    sigset_t old;
    hold(&old);
    int rc = scan_stage(f, f->stage, "", err);
    if (rc == TR_OK)
        qsort(f->now.e, f->now.n, sizeof *f->now.e, by_rel);
    if (rc == TR_OK)
        rc = check_targets(f, keep, nkeep, err);
    /* per file: 1 a hard link to the earlier file kept in the stage, 2 moved
     * into place, 4 an earlier file was there */
    if (rc == TR_OK && (!(f->backed = calloc(f->now.n + 1, 1)) || !(f->madedir = calloc(f->now.n + 1, 1))))
        rc = tr_fail(err, TR_ENOMEM, "out of memory");
    for (size_t i = 0; rc == TR_OK && i < f->now.n; i++) {
        char t[4400], b[4400];
        struct stat st;
        if (f->now.e[i].dir || target_of(f->out, f->now.e[i].rel, t, sizeof t) != 0 || lstat(t, &st) != 0)
            continue;
        f->backed[i] = 4;
        snprintf(b, sizeof b, "%s/.old.%zu", f->stage, i);
        if (link(t, b) == 0) /* a file system without hard links: no undo for it */
            f->backed[i] |= 1;
    }
    if (rc == TR_OK) {
        struct stat st;
        char b[4400];
        snprintf(b, sizeof b, "%s/.old.record", f->stage);
        f->record_backed_up = lstat(f->record, &st) == 0 && link(f->record, b) == 0;
        /* Before anything moves, the record lists the earlier runs' files
         * and this run's: a crash between two moves leaves every file of
         * ours in the folder recognisable. */
        char head[512];
        header(head, sizeof head, f->owner);
        tr_text t = {0};
        tr_text_printf(&t, "%s", head);
        append_entries(&t, &f->old);
        append_entries(&t, &f->now);
        rc = tr_text_write_atomic(&t, f->record, err);
        f->record_written = rc == TR_OK;
    }
    for (size_t i = 0; rc == TR_OK && i < f->now.n; i++) {
        const tr_out_entry *e = &f->now.e[i];
        char t[4400], s[4400];
        if (target_of(f->out, e->rel, t, sizeof t) != 0 || target_of(f->stage, e->rel, s, sizeof s) != 0) {
            rc = tr_fail(err, TR_EINVAL, "%s: output path too long", f->out);
        } else if (e->dir) {
            if (mkdir(t, 0777) == 0)
                f->madedir[i] = 1;
            else if (errno != EEXIST)
                rc = tr_fail(err, TR_EIO, "cannot create directory %s: %s", t, strerror(errno));
        } else if (rename(s, t) != 0) {
            rc = tr_fail(err, TR_EIO, "cannot write %s: %s", t, strerror(errno));
        } else {
            f->backed[i] |= 2;
        }
    }
    if (rc == TR_OK) {
        f->committed = 1;
        int dfd = open(f->out, O_RDONLY | O_CLOEXEC); /* the renames made durable */
        if (dfd >= 0) {
            (void)fsync(dfd);
            close(dfd);
        }
    } else if (f->backed && f->madedir) {
        undo(f);
    }
    sigprocmask(SIG_SETMASK, &old, NULL);
    return rc;
}

int tr_out_folder_holds(const tr_out_folder *f, const char *path)
{
    if (!f->committed)
        return 0;
    if (tr_same_file(path, f->record))
        return 1;
    for (size_t i = 0; i < f->now.n; i++) {
        char t[4400];
        if (!f->now.e[i].dir && target_of(f->out, f->now.e[i].rel, t, sizeof t) == 0 && tr_same_file(path, t))
            return 1;
    }
    return 0;
}

static void release(tr_out_folder *f)
{
    list_free(&f->old);
    list_free(&f->now);
    free(f->backed);
    free(f->madedir);
    f->backed = f->madedir = NULL;
}

void tr_out_folder_finish(tr_out_folder *f, const char *const *keep, size_t nkeep)
{
    sigset_t old;
    hold(&old);
    /* The earlier runs' files this one did not write would read as this
     * run's: they go, if still as written and not an input. One that
     * cannot be removed (a read-only folder) stays ours: its entry goes
     * into the new record (stale), so a later run still knows it. */
    tr_out_list stale = {0};
    int oom = 0;
    for (size_t i = 0; i < f->old.n; i++) {
        const tr_out_entry *e = &f->old.e[i];
        char t[4400];
        if (e->dir || listed_file(&f->now, e->rel) || target_of(f->out, e->rel, t, sizeof t) != 0 ||
            kept(t, keep, nkeep))
            continue;
        if (recorded(&f->old, e->rel, t) && unlink(t) != 0 && errno != ENOENT)
            oom |= list_add(&stale, e->rel, 0, e->size, e->hash);
    }
    /* Subfolders ours and no longer used go if empty: a file of the
     * user's in one keeps it (and it stays ours). */
    tr_out_list dirs = {0};
    for (size_t i = 0; i < f->old.n; i++) {
        const tr_out_entry *e = &f->old.e[i];
        char t[4400];
        struct stat st;
        if (!e->dir || target_of(f->out, e->rel, t, sizeof t) != 0)
            continue;
        if (!listed_dir(&f->now, e->rel))
            rmdir(t);
        if (lstat(t, &st) == 0 && S_ISDIR(st.st_mode) && !listed_dir(&dirs, e->rel))
            oom |= list_add(&dirs, e->rel, 1, 0, 0);
    }
    for (size_t i = 0; i < f->now.n; i++)
        if (f->now.e[i].dir && f->madedir[i] && !listed_dir(&dirs, f->now.e[i].rel))
            oom |= list_add(&dirs, f->now.e[i].rel, 1, 0, 0);
    /* The record now lists this run's files; if it cannot be rewritten the
     * one written before the moves stays, a superset, still true. */
    char head[512];
    header(head, sizeof head, f->owner);
    tr_text t = {0};
    tr_text_printf(&t, "%s", head);
    append_entries(&t, &dirs);
    for (size_t i = 0; i < f->now.n; i++)
        if (!f->now.e[i].dir)
            tr_text_printf(&t, "file %016" PRIx64 " %" PRIu64 " %s\n", f->now.e[i].hash, f->now.e[i].size,
                           f->now.e[i].rel);
    append_entries(&t, &stale);
    if (!oom)
        (void)tr_text_write_atomic(&t, f->record, NULL);
    else
        free(tr_text_take(&t, NULL));
    list_free(&dirs);
    list_free(&stale);
    remove_stage(f->stage, 0);
    f->committed = 0;
    release(f);
    sigprocmask(SIG_SETMASK, &old, NULL);
}

void tr_out_folder_abort(tr_out_folder *f)
{
    sigset_t old;
    hold(&old);
    if (f->committed)
        undo(f);
    if (f->stage[0])
        remove_stage(f->stage, 0);
    if (f->made_out)
        rmdir(f->out);
    release(f);
    sigprocmask(SIG_SETMASK, &old, NULL);
}
