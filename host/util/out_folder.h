/* A folder that a command writes a set of files into, all of them or none,
 * and in which it replaces or removes only files it wrote itself.
 *
 * The run writes everything into a private staging folder inside the
 * output folder (same file system, so moving a file into place is one
 * atomic rename). Only when every file is written are they moved into
 * place; a failure or an interrupt before that leaves the folder as it
 * was. What the command wrote is kept in a record in the folder (each
 * file's name, size and a hash of its bytes): a later run replaces or
 * removes a file only while the record says this command wrote it and the
 * bytes are still the ones it wrote. Anything else in the folder, a file of
 * the user's under one of the command's names, a changed output, the
 * command's own input, a subfolder it did not make, is never replaced or
 * removed: a file in the way is an error before anything moves. */
#ifndef TIGHTROPE_OUT_FOLDER_H
#define TIGHTROPE_OUT_FOLDER_H

#include <stddef.h>
#include <stdint.h>

#include "util/error.h"

/* One line of the record: a file (with its size and hash) or a subfolder
 * the command made. */
typedef struct tr_out_entry {
    char *rel;  /* relative to the folder: "report.txt", "comp0/", "comp0/report.txt" */
    int dir;
    uint64_t size, hash;
} tr_out_entry;

typedef struct tr_out_list {
    tr_out_entry *e;
    size_t n, cap;
} tr_out_list;

typedef struct tr_out_folder {
    char out[4096];    /* the folder */
    char stage[4160];  /* where the run writes: out/.tr-stage.XXXXXX */
    char record[4160]; /* out/RECORD */
    const char *owner; /* the command, named in the record's first line */
    int made_out;      /* out did not exist: this run made it */
    tr_out_list old;   /* the record of the runs before */
    tr_out_list now;   /* this run's files, found in the stage at commit */
    /* the commit, for an undo: */
    int committed, record_written, record_backed_up;
    size_t moved;           /* files of now moved into place, in order */
    unsigned char *backed;  /* per file of now: the earlier file kept in the stage */
    unsigned char *madedir; /* per entry of now: a subfolder this commit made */
} tr_out_folder;

/* Begins a run into folder `out` (made if missing; its parent must exist),
 * whose record is out/`record` and names `owner` ("tightrope analyze"). The
 * record of earlier runs is read; one that is not a regular file with the
 * owner's first line is an error (it is not ours to replace). TR_EIO with
 * the reason; then nothing is left behind. */
int tr_out_folder_open(tr_out_folder *f, const char *out, const char *record, const char *owner, tr_error *err);

/* The staging folder the run writes its files into (subfolders allowed,
 * one level deep). */
const char *tr_out_folder_stage(const tr_out_folder *f);

/* msg with every mention of the staging folder replaced by the folder, so
 * that a message names the file the user will look for. Returns buf. */
const char *tr_out_folder_shown(const tr_out_folder *f, const char *msg, char *buf, size_t n);

/* Moves every file of the stage into place. Refused first, with nothing
 * moved, when a file in the way is not one the record says the owner
 * wrote (or it changed since), is not a regular file, or is the same file
 * as one of the n paths in `keep` (the run's inputs); or when a subfolder
 * in the way is not a directory. TR_EIO with a message naming the file; a
 * failure half-way undoes what moved. */
int tr_out_folder_commit(tr_out_folder *f, const char *const *keep, size_t n, tr_error *err);

/* Whether path is the same file as one this run moved into place, or the
 * record (after a commit). */
int tr_out_folder_holds(const tr_out_folder *f, const char *path);

/* Ends a committed run: the earlier runs' files that this one did not
 * write are removed, if unchanged and not one of `keep`; subfolders the
 * record lists that are left empty go; the record is rewritten to list
 * this run's files; the stage goes. Nothing here can lose this run's
 * output, so a failure only leaves a superset in the record. Frees f. */
void tr_out_folder_finish(tr_out_folder *f, const char *const *keep, size_t n);

/* Abandons the run: a commit is undone (the earlier files back in place,
 * this run's removed), the stage goes, and the folder too if this run made
 * it and it is empty. Frees f. */
void tr_out_folder_abort(tr_out_folder *f);

#endif
