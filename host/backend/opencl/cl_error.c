/* This file contains the names of OpenCL error codes and the checked-call helpers (cl_error.h). */
#include "backend/opencl/cl_error.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *tr_cl_strerror(cl_int code)
{
    /* Literal values so that codes newer than the CL_TARGET_OPENCL_VERSION
     * headers (a 3.0 driver answering a 1.2 program) are still named. */
    switch (code) {
    case 0: return "CL_SUCCESS";
    case -1: return "CL_DEVICE_NOT_FOUND";
    case -2: return "CL_DEVICE_NOT_AVAILABLE";
    case -3: return "CL_COMPILER_NOT_AVAILABLE";
    case -4: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case -5: return "CL_OUT_OF_RESOURCES";
    case -6: return "CL_OUT_OF_HOST_MEMORY";
    case -7: return "CL_PROFILING_INFO_NOT_AVAILABLE";
    case -8: return "CL_MEM_COPY_OVERLAP";
    case -9: return "CL_IMAGE_FORMAT_MISMATCH";
    case -10: return "CL_IMAGE_FORMAT_NOT_SUPPORTED";
    case -11: return "CL_BUILD_PROGRAM_FAILURE";
    case -12: return "CL_MAP_FAILURE";
    case -13: return "CL_MISALIGNED_SUB_BUFFER_OFFSET";
    case -14: return "CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST";
    case -15: return "CL_COMPILE_PROGRAM_FAILURE";
    case -16: return "CL_LINKER_NOT_AVAILABLE";
    case -17: return "CL_LINK_PROGRAM_FAILURE";
    case -18: return "CL_DEVICE_PARTITION_FAILED";
    case -19: return "CL_KERNEL_ARG_INFO_NOT_AVAILABLE";
    case -30: return "CL_INVALID_VALUE";
    case -31: return "CL_INVALID_DEVICE_TYPE";
    case -32: return "CL_INVALID_PLATFORM";
    case -33: return "CL_INVALID_DEVICE";
    case -34: return "CL_INVALID_CONTEXT";
    case -35: return "CL_INVALID_QUEUE_PROPERTIES";
    case -36: return "CL_INVALID_COMMAND_QUEUE";
    case -37: return "CL_INVALID_HOST_PTR";
    case -38: return "CL_INVALID_MEM_OBJECT";
    case -39: return "CL_INVALID_IMAGE_FORMAT_DESCRIPTOR";
    case -40: return "CL_INVALID_IMAGE_SIZE";
    case -41: return "CL_INVALID_SAMPLER";
    case -42: return "CL_INVALID_BINARY";
    case -43: return "CL_INVALID_BUILD_OPTIONS";
    case -44: return "CL_INVALID_PROGRAM";
    case -45: return "CL_INVALID_PROGRAM_EXECUTABLE";
    case -46: return "CL_INVALID_KERNEL_NAME";
    case -47: return "CL_INVALID_KERNEL_DEFINITION";
    case -48: return "CL_INVALID_KERNEL";
    case -49: return "CL_INVALID_ARG_INDEX";
    case -50: return "CL_INVALID_ARG_VALUE";
    case -51: return "CL_INVALID_ARG_SIZE";
    case -52: return "CL_INVALID_KERNEL_ARGS";
    case -53: return "CL_INVALID_WORK_DIMENSION";
    case -54: return "CL_INVALID_WORK_GROUP_SIZE";
    case -55: return "CL_INVALID_WORK_ITEM_SIZE";
    case -56: return "CL_INVALID_GLOBAL_OFFSET";
    case -57: return "CL_INVALID_EVENT_WAIT_LIST";
    case -58: return "CL_INVALID_EVENT";
    case -59: return "CL_INVALID_OPERATION";
    case -60: return "CL_INVALID_GL_OBJECT";
    case -61: return "CL_INVALID_BUFFER_SIZE";
    case -62: return "CL_INVALID_MIP_LEVEL";
    case -63: return "CL_INVALID_GLOBAL_WORK_SIZE";
    case -64: return "CL_INVALID_PROPERTY";
    case -65: return "CL_INVALID_IMAGE_DESCRIPTOR";
    case -66: return "CL_INVALID_COMPILER_OPTIONS";
    case -67: return "CL_INVALID_LINKER_OPTIONS";
    case -68: return "CL_INVALID_DEVICE_PARTITION_COUNT";
    case -69: return "CL_INVALID_PIPE_SIZE";
    case -70: return "CL_INVALID_DEVICE_QUEUE";
    case -71: return "CL_INVALID_SPEC_ID";
    case -72: return "CL_MAX_SIZE_RESTRICTION_EXCEEDED";
    /* Extensions the ICD loader and common drivers return. */
    case -1000: return "CL_INVALID_GL_SHAREGROUP_REFERENCE_KHR";
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    case -1002: return "CL_INVALID_D3D10_DEVICE_KHR";
    case -1003: return "CL_INVALID_D3D10_RESOURCE_KHR";
    case -1004: return "CL_D3D10_RESOURCE_ALREADY_ACQUIRED_KHR";
    case -1005: return "CL_D3D10_RESOURCE_NOT_ACQUIRED_KHR";
    case -1006: return "CL_INVALID_D3D11_DEVICE_KHR";
    case -1007: return "CL_INVALID_D3D11_RESOURCE_KHR";
    case -1008: return "CL_D3D11_RESOURCE_ALREADY_ACQUIRED_KHR";
    case -1009: return "CL_D3D11_RESOURCE_NOT_ACQUIRED_KHR";
    case -1010: return "CL_INVALID_DX9_MEDIA_ADAPTER_KHR";
    case -1011: return "CL_INVALID_DX9_MEDIA_SURFACE_KHR";
    case -1012: return "CL_DX9_MEDIA_SURFACE_ALREADY_ACQUIRED_KHR";
    case -1013: return "CL_DX9_MEDIA_SURFACE_NOT_ACQUIRED_KHR";
    case -1057: return "CL_DEVICE_PARTITION_FAILED_EXT";
    case -1058: return "CL_INVALID_PARTITION_COUNT_EXT";
    case -1059: return "CL_INVALID_PARTITION_NAME_EXT";
    case -1092: return "CL_EGL_RESOURCE_NOT_ACQUIRED_KHR";
    case -1093: return "CL_INVALID_EGL_OBJECT_KHR";
    case -1094: return "CL_INVALID_ACCELERATOR_INTEL";
    case -1095: return "CL_INVALID_ACCELERATOR_TYPE_INTEL";
    case -1096: return "CL_INVALID_ACCELERATOR_DESCRIPTOR_INTEL";
    case -1097: return "CL_ACCELERATOR_TYPE_NOT_SUPPORTED_INTEL";
    case -1098: return "CL_INVALID_VA_API_MEDIA_ADAPTER_INTEL";
    case -1099: return "CL_INVALID_VA_API_MEDIA_SURFACE_INTEL";
    case -1100: return "CL_VA_API_MEDIA_SURFACE_ALREADY_ACQUIRED_INTEL";
    case -1101: return "CL_VA_API_MEDIA_SURFACE_NOT_ACQUIRED_INTEL";
    case -1143: return "CL_COMMAND_TERMINATED_ITSELF_WITH_FAILURE_ARM";
    case -9999: return "CL_NV_ILLEGAL_MEMORY_ACCESS";
    default: return "CL_UNKNOWN_ERROR";
    }
}

/* The entry point is the first identifier "cl" + upper-case letter, so both
 * "clFinish(q)" and "(buf = clCreateBuffer(...), e)" name the right call. */
static void entry_point_name(const char *text, char *out, size_t n)
{
    const char *p = text;
    for (; *p; p++) {
        int starts_word = p == text || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
        if (starts_word && p[0] == 'c' && p[1] == 'l' && isupper((unsigned char)p[2]))
            break;
    }
    if (!*p)
        p = text;
    size_t k = 0;
    while (k + 1 < n && (isalnum((unsigned char)p[k]) || p[k] == '_'))
        k++;
    memcpy(out, p, k);
    out[k] = '\0';
}

int tr_cl_fail(tr_error *err, cl_int code, const char *call_text, const char *file, int line)
{
    char name[64];
    entry_point_name(call_text, name, sizeof name);
    const char *base = strrchr(file, '/');
    return tr_fail(err, TR_EOPENCL, "%s: %s (%d) [%s:%d]", name[0] ? name : "opencl call",
                   tr_cl_strerror(code), (int)code, base ? base + 1 : file, line);
}

void tr_cl_kernel_name(cl_kernel k, char *name, size_t n)
{
    if (n == 0)
        return;
    if (clGetKernelInfo(k, CL_KERNEL_FUNCTION_NAME, n, name, NULL) != CL_SUCCESS)
        snprintf(name, n, "?");
    name[n - 1] = '\0';
}

int tr_cl_vargs(tr_error *err, const char *file, int line, cl_kernel k, cl_uint first, va_list ap)
{
    for (cl_uint i = first;; i++) {
        size_t size = va_arg(ap, size_t);
        if (size == TR_CL_END)
            return TR_OK;
        const void *value = va_arg(ap, const void *);
        cl_int code = clSetKernelArg(k, i, size, value);
        if (code != CL_SUCCESS) {
            char name[64];
            tr_cl_kernel_name(k, name, sizeof name);
            tr_cl_fail(err, code, "clSetKernelArg", file, line);
            return tr_fail_wrap(err, TR_EOPENCL, "kernel %s, argument %u", name, (unsigned)i);
        }
    }
}

int tr_cl_args_at(tr_error *err, const char *file, int line, cl_kernel k, cl_uint first, ...)
{
    va_list ap;
    va_start(ap, first);
    int rc = tr_cl_vargs(err, file, line, k, first, ap);
    va_end(ap);
    return rc;
}
