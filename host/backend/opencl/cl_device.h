/* OpenCL platforms and devices: enumeration with FP64 status, selection by
 * "reference | auto | P:D | name-substring" (or TIGHTROPE_DEVICE), a context
 * with one in-order queue, and program builds from the embedded kernels. */
#ifndef TR_CL_DEVICE_H
#define TR_CL_DEVICE_H

#include <CL/cl.h>
#include <CL/cl_ext.h> /* CL_PLATFORM_NOT_FOUND_KHR */
#include <stddef.h>

#include "layout.h" /* TR_LOCAL_SIZE, the work-group size of every launch */
#include "util/error.h"

typedef struct tr_cl_device_info {
    int platform, device; /* indices, as "P:D" */
    cl_platform_id pid;
    cl_device_id did;
    char platform_name[128];
    char platform_vendor[128]; /* CL_PLATFORM_VENDOR ("The pocl project", "NVIDIA Corporation") */
    char name[256];
    char vendor[128];
    char version[128];        /* CL_DEVICE_VERSION */
    char driver[64];          /* CL_DRIVER_VERSION */
    cl_device_type type;
    cl_uint compute_units;
    cl_uint clock_mhz;
    cl_ulong global_mem;
    size_t max_work_group;
    int fp64;                 /* cl_khr_fp64 (or cl_amd_fp64) with a double FP config */
    int usable;
    char reason[512];         /* why unusable; empty when usable (a build log's first errors) */
    double score;             /* ranking used by "auto" (higher is faster, see cl_device.c) */
} tr_cl_device_info;

typedef struct tr_cl_device_list {
    tr_cl_device_info *dev;
    int n;
    /* When enumeration found no OpenCL at all, why (e.g. "clGetPlatformIDs:
     * CL_PLATFORM_NOT_FOUND_KHR (-1001) [...]: no opencl driver (icd) installed"). */
    char none_reason[256];
} tr_cl_device_list;

/* Lists every device of every platform. Finding no platform is not an error:
 * the list is empty and none_reason says why. */
int tr_cl_enumerate(tr_cl_device_list *out, tr_error *err);
void tr_cl_device_list_free(tr_cl_device_list *l);

typedef enum tr_device_kind { TR_DEVICE_REFERENCE = 0, TR_DEVICE_OPENCL = 1 } tr_device_kind;

typedef struct tr_device_choice {
    tr_device_kind kind;
    tr_cl_device_info cl;   /* valid when kind == TR_DEVICE_OPENCL */
    char spec[128];         /* the specification it came from */
    char warning[512];      /* non-empty when "auto" fell back to the reference */
} tr_device_choice;

/* The specification to use when the user gave none: TIGHTROPE_DEVICE if set, else "auto". */
const char *tr_device_spec_default(void);

/* Resolves spec (NULL: tr_device_spec_default()). "reference" (or "serial",
 * "cpu-reference") -> the serial reference; "auto" -> the highest-scoring usable
 * GPU/accelerator, or the reference with a warning when there is none; "P:D" -> that
 * device; anything else -> the single usable device whose platform or device
 * name contains it (case-insensitive). "auto" skips OpenCL drivers that run
 * on the host CPU (slower than the reference,
 * bench/notes/2026-11-23-opencl-targets-issue-4.md), and falls
 * back to the reference when OpenCL itself is missing; "opencl" is the best
 * usable device of any type. Any other choice, "opencl" included, of an
 * unusable or missing device is an error, never a silent fallback. */
int tr_device_select(const char *spec, tr_device_choice *out, tr_error *err);

/* Device time per kernel function, summed over the launches of a profiled
 * context (tr_cl_launch), whichever module launched them. */
#define TR_CL_PROF_MAX 128
typedef struct tr_cl_prof {
    int count;
    char name[TR_CL_PROF_MAX][48];
    long launches[TR_CL_PROF_MAX];
    double seconds[TR_CL_PROF_MAX];
} tr_cl_prof;

/* A context and an in-order queue on one device; prof is allocated only
 * when profiling is on. */
typedef struct tr_cl_ctx {
    tr_cl_device_info info;
    cl_context context;
    cl_command_queue queue;
    int profiling;
    tr_cl_prof *prof;
    /* Work-items of a launch over indices (tr_cl_launch_items) on a device
     * that wants blocks of them; 0: one index per work-item. */
    size_t block_items;
} tr_cl_ctx;

int tr_cl_ctx_open(tr_cl_ctx *ctx, const tr_cl_device_info *dev, int profiling, tr_error *err);
void tr_cl_ctx_close(tr_cl_ctx *ctx);

/* Enqueues k (arguments set) over global items in work-groups of local. In
 * a profiling context it waits for the launch and adds its device time to
 * ctx->prof under the kernel's function name. */
int tr_cl_launch(const tr_cl_ctx *ctx, cl_kernel k, size_t global, size_t local, tr_error *err);

/* Launches a kernel that loops over the indices [0, n) (kernels/common.clh
 * TR_ITEMS). On a GPU, one index per work-item in groups of TR_LOCAL_SIZE; on a
 * CPU device, ctx->block_items work-items of one each, every one walking a
 * contiguous block of indices: PoCL runs the CG's axpy over 2 x 10^5
 * entries 5x faster so, over 2 x 10^6 3x (bench/launch_shapes). TIGHTROPE_CL_ITEMS=one|blocks
 * overrides the choice (tr_cl_ctx_open). */
int tr_cl_launch_items(const tr_cl_ctx *ctx, cl_kernel k, size_t n, tr_error *err);

/* The work-items tr_cl_launch_items launches for n indices (a kernel that
 * folds its indices writes one partial result per work-item). */
size_t tr_cl_items_global(const tr_cl_ctx *ctx, size_t n);

/* The sources every program starts with, in order (kernels/): the layout the
 * host shares, the helpers, the segment distance the host shares. */
#define TR_CL_PREAMBLE {"layout.h", "common.clh", "segment_distance.h"}
#define TR_CL_PREAMBLE_COUNT 3

/* Builds one program from the preamble followed by the named kernel files
 * (embedded, or from TIGHTROPE_KERNEL_DIR). On failure err holds the call,
 * the options and the build log folded onto one line. */
int tr_cl_build(const tr_cl_ctx *ctx, const char *const *files, int nfiles, const char *options,
                cl_program *out, tr_error *err);

/* Blocks of indices per compute unit of a CPU device (tr_cl_launch_items). */
#define TR_CL_BLOCKS_PER_UNIT 8

/* Global size padded up to a multiple of TR_LOCAL_SIZE (at least one group). */
static inline size_t tr_cl_global(size_t n)
{
    size_t g = (n + TR_LOCAL_SIZE - 1) / TR_LOCAL_SIZE * TR_LOCAL_SIZE;
    return g ? g : TR_LOCAL_SIZE;
}

#endif
