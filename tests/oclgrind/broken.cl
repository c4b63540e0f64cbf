/* Kernels with one bug each that no conformant implementation has to
 * report, and Oclgrind does: tests/oclgrind.cmake runs each under
 * scripts/oclgrind_run.sh (the Oclgrind CI leg) and requires it to fail
 * there, naming the bug and this file's line. Built only by that test
 * (oclgrind_broken.c), never part of Tightrope's program. The test names
 * the lines below: keep them where they are or change it too. */

/* The control: the same shape, without a bug. */
__kernel void fine(__global const int *in, __global int *out, const int n)
{
    int i = get_global_id(0);
    if (i < n)
        out[i] = 2 * in[i];
}

/* Writes one past the end of out (line 21). */
__kernel void out_of_bounds(__global const int *in, __global int *out, const int n)
{
    int i = get_global_id(0);
    if (i < n)
        out[i + 1] = 2 * in[i];
}

/* Reads a neighbour's slot of local memory with no barrier after the
 * writes (line 31): a race between work-items of a group. */
__kernel void race(__global const int *in, __global int *out, const int n)
{
    __local int s[64];
    int l = get_local_id(0), i = get_global_id(0);
    s[l] = i < n ? in[i] : 0;
    int v = s[(l + 1) % 64];
    if (i < n)
        out[i] = v;
}

/* Writes into `in`, a buffer created CL_MEM_READ_ONLY (line 42). */
__kernel void write_read_only(__global int *in, __global int *out, const int n)
{
    int i = get_global_id(0);
    if (i < n) {
        out[i] = in[i];
        in[i] = 0;
    }
}
