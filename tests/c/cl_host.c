/* The OpenCL host of the faithfulness tests (tests/opencl_backend.rs, tests/scene_backends.rs):
 * builds the generated OpenCL C once and runs batch kernels on the case files of a directory.
 *
 *   cl_host SOURCE.cl DIR            the generic kernels (below)
 *   cl_host SOURCE.cl DIR LIST       the kernels listed in LIST (the scene kernels)
 *
 * LIST: one line per kernel, "FORMAT NAME IN_WIDTHS OUT_WIDTHS", e.g.
 * "f64 noslip_gas2d_ball_ball_0_0_f64 2,3,3 3,3": runs NAME_batch on DIR/NAME.bin, records of
 * the input widths' sum of FORMAT values split into one array per input parameter (in order),
 * and writes DIR/NAME.out, per record the output parameters' values in order. An output width
 * suffixed `d` ("21d") is of double whatever FORMAT (the bounds of the _f32_wide companions).
 *
 * Without LIST: for each n in 2..6 and format f64/f32 whose DIR/cases_{n}_{format}.bin exists (records as
 * in tests/c/harness.c), runs noslip_d{n}_{kernel}_{format}_batch for kernel = free, fixed,
 * free_fma, fixed_fma and writes DIR/{n}_{kernel}_{format}.out (out1, out2 or out2 per
 * record). Exit 3 when there is no OpenCL device, or the device cannot give IEEE results
 * (no correctly rounded float divide, float subnormals flushed, no fp64): the test then says
 * so. Prints the platform and device on stderr. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The most parameters of a kernel (free: nu, ball1, ball2, state1, state2, out1, out2). */
#define MAX_PARAMS 8

static void *read_all(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)size + 1);
    *len = fread(buf, 1, (size_t)size, f);
    buf[*len] = 0;
    fclose(f);
    return buf;
}

#define CHECK(call)                                                          \
    do {                                                                     \
        cl_int err_ = (call);                                                \
        if (err_ != CL_SUCCESS) {                                            \
            fprintf(stderr, "cl_host: %s failed: %d\n", #call, (int)err_);   \
            exit(1);                                                         \
        }                                                                    \
    } while (0)

/* Run kernel KNAME over COUNT work items with the input buffers INS (N_IN of them), then write
 * PATH: per work item, the N_OUT outputs of OUT_WIDTHS values of OUT_SIZES bytes each, in order. */
static int run_batch(cl_context ctx, cl_command_queue queue, cl_program program, const char *kname,
                     size_t count, int n_in, const cl_mem *ins, int n_out,
                     const size_t *out_widths, const size_t *out_sizes, const char *path) {
    cl_int err;
    cl_kernel kernel = clCreateKernel(program, kname, &err);
    CHECK(err);
    cl_uint cnt = (cl_uint)count, arg = 0;
    CHECK(clSetKernelArg(kernel, arg++, sizeof cnt, &cnt));
    for (int a = 0; a < n_in; a++) CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &ins[a]));
    cl_mem outs[MAX_PARAMS];
    char *results[MAX_PARAMS];
    for (int o = 0; o < n_out; o++) {
        outs[o] = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, count * out_widths[o] * out_sizes[o] + 1, NULL, &err);
        CHECK(err);
        CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &outs[o]));
        results[o] = malloc(count * out_widths[o] * out_sizes[o] + 1);
    }
    size_t global = count;
    CHECK(clEnqueueNDRangeKernel(queue, kernel, 1, NULL, &global, NULL, 0, NULL, NULL));
    for (int o = 0; o < n_out; o++)
        CHECK(clEnqueueReadBuffer(queue, outs[o], CL_TRUE, 0, count * out_widths[o] * out_sizes[o], results[o], 0, NULL, NULL));
    clReleaseKernel(kernel);
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cl_host: cannot write %s\n", path);
        return 1;
    }
    for (size_t c = 0; c < count; c++)
        for (int o = 0; o < n_out; o++)
            fwrite(results[o] + c * out_widths[o] * out_sizes[o], out_sizes[o], out_widths[o], f);
    for (int o = 0; o < n_out; o++) {
        clReleaseMemObject(outs[o]);
        free(results[o]);
    }
    return fclose(f) != 0;
}

/* Split COUNT records of the widths WIDTHS (N of them, values of SIZE bytes) into one
 * read-only buffer per width. */
static void split(cl_context ctx, const char *in, size_t count, size_t size, int n,
                  const size_t *widths, cl_mem *bufs) {
    size_t rec = 0, offset = 0;
    for (int a = 0; a < n; a++) rec += widths[a];
    for (int a = 0; a < n; a++) {
        char *array = malloc(count * widths[a] * size + 1);
        for (size_t c = 0; c < count; c++)
            memcpy(array + c * widths[a] * size, in + (c * rec + offset) * size, widths[a] * size);
        offset += widths[a];
        cl_int err;
        bufs[a] = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * widths[a] * size + 1, array, &err);
        CHECK(err);
        free(array);
    }
}

/* Parse "a,b,c" into WIDTHS and SIZES (SIZE, or sizeof(double) for a width suffixed `d`);
 * the count, or -1. */
static int widths_of(const char *text, size_t size, size_t *widths, size_t *sizes) {
    int n = 0;
    while (*text) {
        char *end;
        unsigned long w = strtoul(text, &end, 10);
        if (end == text || w == 0 || n == MAX_PARAMS) return -1;
        sizes[n] = size;
        if (*end == 'd') {
            sizes[n] = sizeof(double);
            end++;
        }
        widths[n++] = (size_t)w;
        text = *end == ',' ? end + 1 : end;
        if (*end && *end != ',') return -1;
    }
    return n;
}

/* The kernels of LIST (the usage above). */
static int run_list(cl_context ctx, cl_command_queue queue, cl_program program, const char *dir,
                    const char *list) {
    FILE *f = fopen(list, "r");
    if (!f) {
        fprintf(stderr, "cl_host: cannot read %s\n", list);
        return 2;
    }
    char format[8], name[256], ins[256], outs[256], path[4096], kname[300];
    while (fscanf(f, "%7s %255s %255s %255s", format, name, ins, outs) == 4) {
        size_t in_w[MAX_PARAMS], out_w[MAX_PARAMS], in_s[MAX_PARAMS], out_s[MAX_PARAMS];
        const size_t size = !strcmp(format, "f64") ? sizeof(double) : sizeof(float);
        const int n_in = widths_of(ins, size, in_w, in_s), n_out = widths_of(outs, size, out_w, out_s);
        int mixed = 0;
        for (int a = 0; a < n_in; a++) mixed |= in_s[a] != size;
        if (n_in < 0 || n_out < 0 || mixed || (strcmp(format, "f64") && strcmp(format, "f32"))) {
            fprintf(stderr, "cl_host: bad line for %s in %s\n", name, list);
            return 2;
        }
        snprintf(path, sizeof path, "%s/%s.bin", dir, name);
        size_t in_len, rec = 0;
        char *in = read_all(path, &in_len);
        if (!in) {
            fprintf(stderr, "cl_host: cannot read %s\n", path);
            return 2;
        }
        for (int a = 0; a < n_in; a++) rec += in_w[a];
        const size_t count = in_len / (rec * size);
        cl_mem bufs[MAX_PARAMS];
        split(ctx, in, count, size, n_in, in_w, bufs);
        snprintf(kname, sizeof kname, "%s_batch", name);
        snprintf(path, sizeof path, "%s/%s.out", dir, name);
        if (run_batch(ctx, queue, program, kname, count, n_in, bufs, n_out, out_w, out_s, path)) return 1;
        for (int a = 0; a < n_in; a++) clReleaseMemObject(bufs[a]);
        free(in);
    }
    return fclose(f) != 0;
}

int main(int argc, char **argv) {
    if (argc != 3 && argc != 4) {
        fprintf(stderr, "usage: cl_host SOURCE.cl DIR [LIST]\n");
        return 2;
    }
    cl_platform_id platform;
    cl_uint platforms = 0;
    if (clGetPlatformIDs(1, &platform, &platforms) != CL_SUCCESS || platforms == 0) {
        fprintf(stderr, "cl_host: no OpenCL platform\n");
        return 3;
    }
    cl_device_id device;
    cl_uint devices = 0;
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device, &devices) != CL_SUCCESS || devices == 0) {
        fprintf(stderr, "cl_host: no OpenCL device\n");
        return 3;
    }
    char name[256] = "", version[256] = "", pname[256] = "";
    clGetPlatformInfo(platform, CL_PLATFORM_NAME, sizeof pname, pname, NULL);
    clGetDeviceInfo(device, CL_DEVICE_NAME, sizeof name, name, NULL);
    clGetDeviceInfo(device, CL_DEVICE_VERSION, sizeof version, version, NULL);
    fprintf(stderr, "cl_host: platform %s, device %s, %s\n", pname, name, version);
    cl_device_fp_config single = 0, dbl = 0;
    clGetDeviceInfo(device, CL_DEVICE_SINGLE_FP_CONFIG, sizeof single, &single, NULL);
    clGetDeviceInfo(device, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof dbl, &dbl, NULL);
    if (!(single & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) || !(single & CL_FP_DENORM) ||
        !(single & CL_FP_FMA) || !(single & CL_FP_ROUND_TO_NEAREST) || dbl == 0) {
        fprintf(stderr, "cl_host: device lacks IEEE float divide/subnormals/fma or fp64 (config %#lx, %#lx)\n",
                (unsigned long)single, (unsigned long)dbl);
        return 3;
    }
    cl_int err;
    cl_context ctx = clCreateContext(NULL, 1, &device, NULL, NULL, &err);
    CHECK(err);
    cl_command_queue queue = clCreateCommandQueue(ctx, device, 0, &err);
    CHECK(err);
    size_t src_len;
    const char *src = read_all(argv[1], &src_len);
    if (!src) {
        fprintf(stderr, "cl_host: cannot read %s\n", argv[1]);
        return 2;
    }
    cl_program program = clCreateProgramWithSource(ctx, 1, &src, &src_len, &err);
    CHECK(err);
    if (clBuildProgram(program, 1, &device, "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt", NULL, NULL) != CL_SUCCESS) {
        static char log[1 << 16];
        clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
        fprintf(stderr, "cl_host: build failed:\n%s\n", log);
        return 1;
    }
    if (argc == 4) return run_list(ctx, queue, program, argv[2], argv[3]);
    static const int dims[5][2] = {{2, 1}, {3, 3}, {4, 6}, {5, 10}, {6, 15}};
    static const char *kernels[4] = {"free", "fixed", "free_fma", "fixed_fma"};
    static const char *formats[2] = {"f64", "f32"};
    char path[4096];
    for (int d = 0; d < 5; d++) {
        const size_t n = (size_t)dims[d][0], len = (size_t)dims[d][1] + n;
        const size_t rec = n + 6 + 2 * len;
        for (int f = 0; f < 2; f++) {
            const size_t size = f == 0 ? sizeof(double) : sizeof(float);
            snprintf(path, sizeof path, "%s/cases_%zu_%s.bin", argv[2], n, formats[f]);
            size_t in_len;
            char *in = read_all(path, &in_len);
            if (!in) continue;
            const size_t count = in_len / (rec * size);
            /* One array per parameter: nu, ball1, ball2, state1, state2; fixed: radius1 = ball1[1]. */
            const size_t widths[5] = {n, 3, 3, len, len};
            cl_mem bufs[5];
            split(ctx, in, count, size, 5, widths, bufs);
            char *radius1 = malloc(count * size + 1);
            for (size_t c = 0; c < count; c++) memcpy(radius1 + c * size, in + (c * rec + n + 1) * size, size);
            cl_mem radius_buf = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * size + 1, radius1, &err);
            CHECK(err);
            for (int k = 0; k < 4; k++) {
                const int fixed = strstr(kernels[k], "fixed") != NULL;
                const cl_mem args[5] = {bufs[0], fixed ? radius_buf : bufs[1], bufs[2], bufs[3], bufs[4]};
                const size_t out_widths[2] = {len, len}, out_sizes[2] = {size, size};
                char kname[128];
                snprintf(kname, sizeof kname, "noslip_d%zu_%s_%s_batch", n, kernels[k], formats[f]);
                snprintf(path, sizeof path, "%s/%zu_%s_%s.out", argv[2], n, kernels[k], formats[f]);
                if (run_batch(ctx, queue, program, kname, count, 5, args, fixed ? 1 : 2, out_widths, out_sizes, path))
                    return 1;
            }
            for (int a = 0; a < 5; a++) clReleaseMemObject(bufs[a]);
            clReleaseMemObject(radius_buf);
            free(radius1);
            free(in);
        }
    }
    return 0;
}
