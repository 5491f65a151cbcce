/* The OpenCL host of the faithfulness test (tests/opencl_backend.rs): builds the generated
 * OpenCL C once and runs every batch kernel on the case files of a directory.
 *
 *   cl_host SOURCE.cl DIR
 *
 * For each n in 2..6 and format f64/f32 whose DIR/cases_{n}_{format}.bin exists (records as
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

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: cl_host SOURCE.cl DIR\n");
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
            /* Split the records into one array per parameter: nu, ball1, ball2, state1, state2. */
            const size_t widths[5] = {n, 3, 3, len, len};
            char *arrays[5];
            size_t offset = 0;
            for (int a = 0; a < 5; a++) {
                arrays[a] = malloc(count * widths[a] * size);
                for (size_t c = 0; c < count; c++)
                    memcpy(arrays[a] + c * widths[a] * size, in + (c * rec + offset) * size, widths[a] * size);
                offset += widths[a];
            }
            char *radius1 = malloc(count * size); /* fixed: ball1[1] */
            for (size_t c = 0; c < count; c++)
                memcpy(radius1 + c * size, arrays[1] + (c * 3 + 1) * size, size);
            cl_mem bufs[5], radius_buf, out1, out2;
            for (int a = 0; a < 5; a++) {
                bufs[a] = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * widths[a] * size, arrays[a], &err);
                CHECK(err);
            }
            radius_buf = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, count * size, radius1, &err);
            CHECK(err);
            out1 = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, count * len * size, NULL, &err);
            CHECK(err);
            out2 = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, count * len * size, NULL, &err);
            CHECK(err);
            char *result = malloc(2 * count * len * size);
            for (int k = 0; k < 4; k++) {
                const int fixed = strstr(kernels[k], "fixed") != NULL;
                char kname[128];
                snprintf(kname, sizeof kname, "noslip_d%zu_%s_%s_batch", n, kernels[k], formats[f]);
                cl_kernel kernel = clCreateKernel(program, kname, &err);
                CHECK(err);
                cl_uint cnt = (cl_uint)count, arg = 0;
                CHECK(clSetKernelArg(kernel, arg++, sizeof cnt, &cnt));
                CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &bufs[0]));
                CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), fixed ? &radius_buf : &bufs[1]));
                for (int a = 2; a < 5; a++) CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &bufs[a]));
                if (!fixed) CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &out1));
                CHECK(clSetKernelArg(kernel, arg++, sizeof(cl_mem), &out2));
                size_t global = count;
                CHECK(clEnqueueNDRangeKernel(queue, kernel, 1, NULL, &global, NULL, 0, NULL, NULL));
                const size_t out_bytes = count * len * size;
                if (!fixed) CHECK(clEnqueueReadBuffer(queue, out1, CL_TRUE, 0, out_bytes, result, 0, NULL, NULL));
                CHECK(clEnqueueReadBuffer(queue, out2, CL_TRUE, 0, out_bytes, result + (fixed ? 0 : out_bytes), 0, NULL, NULL));
                clReleaseKernel(kernel);
                /* Interleave per record: out1[len], out2[len] (free) or out2[len] (fixed). */
                snprintf(path, sizeof path, "%s/%zu_%s_%s.out", argv[2], n, kernels[k], formats[f]);
                FILE *o = fopen(path, "wb");
                if (!o) {
                    fprintf(stderr, "cl_host: cannot write %s\n", path);
                    return 1;
                }
                for (size_t c = 0; c < count; c++) {
                    if (!fixed) fwrite(result + c * len * size, size, len, o);
                    fwrite(result + (fixed ? 0 : out_bytes) + c * len * size, size, len, o);
                }
                if (fclose(o) != 0) return 1;
            }
            for (int a = 0; a < 5; a++) {
                clReleaseMemObject(bufs[a]);
                free(arrays[a]);
            }
            clReleaseMemObject(radius_buf);
            clReleaseMemObject(out1);
            clReleaseMemObject(out2);
            free(radius1);
            free(result);
            free(in);
        }
    }
    return 0;
}
