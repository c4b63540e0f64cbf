/* Whole text files in and out, and the growing text buffer the writers
 * format into. One place for the three things every command needs:
 * read a file whole (with the reason when it cannot be read), write one
 * so that a reader never sees it half-written, and printf into memory. */
#ifndef TIGHTROPE_TEXT_FILE_H
#define TIGHTROPE_TEXT_FILE_H

#include <stddef.h>

#include "util/error.h"

/* Reads all of `path` into a NUL-terminated buffer (*text, caller frees);
 * *len (may be NULL) gets the byte count without the NUL. A directory,
 * a missing file or a read error is TR_EIO with the system's reason. */
int tr_read_file(const char *path, char **text, size_t *len, tr_error *err);

/* As tr_read_file, for a text file: a NUL byte ends the read at once with
 * TR_EPARSE "FILE:LINE: a NUL byte ...", so reading /dev/zero or a binary
 * file allocates no more than one chunk. Either reader allocates what the
 * file holds (a regular file's size), not more; out of memory is TR_ENOMEM. */
int tr_read_text_file(const char *path, char **text, size_t *len, tr_error *err);

/* Writes `len` bytes to a temporary file beside `path` (same directory,
 * a short hidden name ".tr.XXXXXX", so any legal name of path works),
 * fsyncs it and renames it over `path`: readers see the old file or the
 * whole new one, never a part. An existing file keeps its mode; a symbolic
 * link stays a link and its target is replaced. Interrupting signals are
 * held back while the temporary exists, so only SIGKILL or a crash leaves
 * one behind.
 * A `path` that exists and is not a regular file (a character or block
 * device, a FIFO: /dev/null, a pipe) is written in place, never replaced:
 * opened without O_CREAT or O_TRUNC, every byte written (a FIFO's open
 * waits for a reader), the write's or the close's error reported
 * ("cannot write full: No space left on device"); a socket is refused.
 * A path that is the process's own stdout or stderr (/dev/stdout, or the
 * file the shell redirected it to) is written in place too, through
 * descriptor 1 or 2, after the stream's buffered output, keeping the
 * shell's O_APPEND. */
int tr_write_file_atomic(const char *path, const char *text, size_t len, tr_error *err);

/* What tr_write_file_atomic needs, checked before a long computation whose
 * result it will write: the temporary beside `path` can be created (and is
 * removed again) and `path` is not a directory; for a path written in place,
 * that the file itself is writable. TR_EIO with the reason. */
int tr_check_writable(const char *path, tr_error *err);

/* Whether a and b are one file (same device and inode: ./k.vect, a hard
 * link and a symbolic link to k.vect are all k.vect). 0 when either does
 * not exist. Commands use it to refuse an output that is one of their
 * inputs. */
int tr_same_file(const char *a, const char *b);

/* A growing string. Zero-initialise; tr_text_printf appends; an
 * allocation or format failure sets `oom` and later calls do nothing, so
 * callers check once at the end. */
typedef struct tr_text {
    char *s;
    size_t n, cap;
    int oom;
} tr_text;

void tr_text_printf(tr_text *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Hands the string to the caller (NULL after a failure, also freed). */
char *tr_text_take(tr_text *t, size_t *len);

/* Writes the string to path atomically (tr_write_file_atomic) and frees
 * it; a formatting failure is TR_ENOMEM naming path, and writes nothing. */
int tr_text_write_atomic(tr_text *t, const char *path, tr_error *err);

#endif
