/* Time the generated C kernels (f64, free and fixed) on a file of case records, as
 * noslip_accuracy::timing times the Rust kernels: one warm-up pass, passes grouped into
 * samples of at least 200 us, the median nanoseconds per collision over SAMPLES samples.
 * Driven by `cargo run --release -p noslip-tests --example c_vs_rust` (docs/backends.md),
 * which writes the cases and times the Rust kernels on the same ones in the same run.
 *
 *   bench N CASES.bin SAMPLES      prints "free <ns>" and "fixed <ns>"
 *
 * Records as in tests/c/harness.c: nu[N], ball1[3], ball2[3], state1[S+N], state2[S+N]. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "noslip_kernels.h"

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static int cmp(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One pass over the cases; the outputs are summed into a volatile so none is optimised away. */
#define PASS_FREE(FN, N, S)                                                             \
    for (size_t c = 0; c < count; c++) {                                                \
        const double *x = cases + c * rec;                                              \
        FN(x, x + (N), x + (N) + 3, x + (N) + 6, x + (N) + 6 + (S) + (N), out1, out2); \
        sink += out1[0] + out2[0];                                                      \
    }
#define PASS_FIXED(FN, N, S)                                                            \
    for (size_t c = 0; c < count; c++) {                                                \
        const double *x = cases + c * rec;                                              \
        FN(x, x[(N) + 1], x + (N) + 3, x + (N) + 6, x + (N) + 6 + (S) + (N), out2);    \
        sink += out2[0];                                                                \
    }

/* Median ns per collision of PASS over SAMPLES samples. */
#define TIME(PASS)                                                       \
    do {                                                                 \
        double t0 = now_ns();                                            \
        PASS;                                                            \
        double once = now_ns() - t0;                                     \
        size_t passes = once > 0 ? (size_t)(200e3 / once) : 1;          \
        if (passes < 1) passes = 1;                                      \
        for (int s = 0; s < samples; s++) {                              \
            t0 = now_ns();                                               \
            for (size_t p = 0; p < passes; p++) { PASS; }                \
            per_case[s] = (now_ns() - t0) / (double)(passes * count);    \
        }                                                                \
        qsort(per_case, (size_t)samples, sizeof(double), cmp);           \
        median = per_case[samples / 2];                                  \
    } while (0)

#define DIM(N, S)                                                          \
    if (n == (N)) {                                                        \
        double median;                                                     \
        TIME(PASS_FREE(noslip_d##N##_free_f64, N, S));                     \
        printf("free %.3f\n", median);                                     \
        TIME(PASS_FIXED(noslip_d##N##_fixed_f64, N, S));                   \
        printf("fixed %.3f\n", median);                                    \
    }

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: bench N CASES.bin SAMPLES\n");
        return 2;
    }
    const int n = atoi(argv[1]);
    const int samples = atoi(argv[3]);
    FILE *f = fopen(argv[2], "rb");
    if (!f || samples < 1) {
        fprintf(stderr, "bench: cannot read %s\n", argv[2]);
        return 2;
    }
    fseek(f, 0, SEEK_END);
    const size_t bytes = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    double *cases = malloc(bytes);
    if (fread(cases, 1, bytes, f) != bytes) return 2;
    fclose(f);
    const size_t s_ = (size_t)(n * (n - 1) / 2), rec = (size_t)n + 6 + 2 * (s_ + (size_t)n);
    const size_t count = bytes / (rec * sizeof(double));
    double out1[21], out2[21], *per_case = malloc((size_t)samples * sizeof(double));
    volatile double sink = 0.0;
    DIM(2, 1)
    DIM(3, 3)
    DIM(4, 6)
    DIM(5, 10)
    DIM(6, 15)
    free(cases);
    free(per_case);
    return sink != sink; /* NaN results would show here */
}
