/* The faithfulness harness of the C back end (tests/c_backend.rs): runs one generated kernel
 * on every record of an input file and writes its outputs.
 *
 *   harness N KERNEL PRECISION IN OUT [E BETA | E MU BETA0]
 *
 * KERNEL is free, fixed, free_fma or fixed_fma, or one of them prefixed rough_ (the
 * rough-ball kernels, which then take law = {E, BETA}) or walton_ (the Walton kernels, law =
 * {E, MU, BETA0}); the law is read with strtod or strtof, so that a shortest round-trip
 * decimal gives the exact value. PRECISION f64 or f32. IN holds records of
 * the precision's type, native byte order: nu[N], ball1[3], ball2[3], state1[S+N],
 * state2[S+N] (ball = inv_mass, radius, gamma2; state = spin, velocity). OUT receives per
 * record out1[S+N] and out2[S+N] (free) or out2[S+N] (fixed; its radius1 is ball1[1]).
 * Each kernel is called directly in the loop, so the compiler may inline and vectorise it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noslip_kernels.h"

#define LOOP_FREE(T, FN, N, S)                                                    \
    do {                                                                          \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), out_rec = 2 * ((S) + (N)); \
        const T *x = (const T *)in;                                               \
        T *y = (T *)out;                                                          \
        for (size_t c = 0; c < count; c++, x += rec, y += out_rec)                \
            FN(x, x + (N), x + (N) + 3, x + (N) + 6, x + (N) + 6 + (S) + (N), y,  \
               y + (S) + (N));                                                    \
        out_len = count * out_rec * sizeof(T);                                    \
    } while (0)

#define LOOP_FIXED(T, FN, N, S)                                                   \
    do {                                                                          \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), out_rec = (S) + (N);       \
        const T *x = (const T *)in;                                               \
        T *y = (T *)out;                                                          \
        for (size_t c = 0; c < count; c++, x += rec, y += out_rec)                \
            FN(x, x[(N) + 1], x + (N) + 3, x + (N) + 6, x + (N) + 6 + (S) + (N), \
               y);                                                                \
        out_len = count * out_rec * sizeof(T);                                    \
    } while (0)

#define LOOP_ROUGH_FREE(T, FN, N, S, LAW)                                        \
    do {                                                                          \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), out_rec = 2 * ((S) + (N)); \
        const T *x = (const T *)in;                                               \
        T *y = (T *)out;                                                          \
        for (size_t c = 0; c < count; c++, x += rec, y += out_rec)                \
            FN(x, x + (N), x + (N) + 3, LAW, x + (N) + 6, x + (N) + 6 + (S) + (N), \
               y, y + (S) + (N));                                                 \
        out_len = count * out_rec * sizeof(T);                                    \
    } while (0)

#define LOOP_ROUGH_FIXED(T, FN, N, S, LAW)                                       \
    do {                                                                          \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), out_rec = (S) + (N);       \
        const T *x = (const T *)in;                                               \
        T *y = (T *)out;                                                          \
        for (size_t c = 0; c < count; c++, x += rec, y += out_rec)                \
            FN(x, x[(N) + 1], x + (N) + 3, LAW, x + (N) + 6,                      \
               x + (N) + 6 + (S) + (N), y);                                       \
        out_len = count * out_rec * sizeof(T);                                    \
    } while (0)

#define ROUGH(N, S)                                                                                            \
    if (n == (N)) {                                                                                            \
        if (f64 && !strcmp(kernel, "rough_free")) LOOP_ROUGH_FREE(double, noslip_d##N##_rough_free_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "rough_fixed")) LOOP_ROUGH_FIXED(double, noslip_d##N##_rough_fixed_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "rough_free_fma")) LOOP_ROUGH_FREE(double, noslip_d##N##_rough_free_fma_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "rough_fixed_fma")) LOOP_ROUGH_FIXED(double, noslip_d##N##_rough_fixed_fma_f64, N, S, law64); \
        if (!f64 && !strcmp(kernel, "rough_free")) LOOP_ROUGH_FREE(float, noslip_d##N##_rough_free_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "rough_fixed")) LOOP_ROUGH_FIXED(float, noslip_d##N##_rough_fixed_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "rough_free_fma")) LOOP_ROUGH_FREE(float, noslip_d##N##_rough_free_fma_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "rough_fixed_fma")) LOOP_ROUGH_FIXED(float, noslip_d##N##_rough_fixed_fma_f32, N, S, law32); \
    }

#define WALTON(N, S)                                                                                           \
    if (n == (N)) {                                                                                            \
        if (f64 && !strcmp(kernel, "walton_free")) LOOP_ROUGH_FREE(double, noslip_d##N##_walton_free_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "walton_fixed")) LOOP_ROUGH_FIXED(double, noslip_d##N##_walton_fixed_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "walton_free_fma")) LOOP_ROUGH_FREE(double, noslip_d##N##_walton_free_fma_f64, N, S, law64); \
        if (f64 && !strcmp(kernel, "walton_fixed_fma")) LOOP_ROUGH_FIXED(double, noslip_d##N##_walton_fixed_fma_f64, N, S, law64); \
        if (!f64 && !strcmp(kernel, "walton_free")) LOOP_ROUGH_FREE(float, noslip_d##N##_walton_free_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "walton_fixed")) LOOP_ROUGH_FIXED(float, noslip_d##N##_walton_fixed_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "walton_free_fma")) LOOP_ROUGH_FREE(float, noslip_d##N##_walton_free_fma_f32, N, S, law32); \
        if (!f64 && !strcmp(kernel, "walton_fixed_fma")) LOOP_ROUGH_FIXED(float, noslip_d##N##_walton_fixed_fma_f32, N, S, law32); \
    }

#define DIM(N, S)                                                                        \
    if (n == (N)) {                                                                      \
        const size_t rec = (N) + 6 + 2 * ((S) + (N));                                   \
        count = in_len / (rec * size);                                                  \
        if (f64 && !strcmp(kernel, "free")) LOOP_FREE(double, noslip_d##N##_free_f64, N, S);         \
        if (f64 && !strcmp(kernel, "fixed")) LOOP_FIXED(double, noslip_d##N##_fixed_f64, N, S);      \
        if (f64 && !strcmp(kernel, "free_fma")) LOOP_FREE(double, noslip_d##N##_free_fma_f64, N, S); \
        if (f64 && !strcmp(kernel, "fixed_fma")) LOOP_FIXED(double, noslip_d##N##_fixed_fma_f64, N, S); \
        if (!f64 && !strcmp(kernel, "free")) LOOP_FREE(float, noslip_d##N##_free_f32, N, S);         \
        if (!f64 && !strcmp(kernel, "fixed")) LOOP_FIXED(float, noslip_d##N##_fixed_f32, N, S);      \
        if (!f64 && !strcmp(kernel, "free_fma")) LOOP_FREE(float, noslip_d##N##_free_fma_f32, N, S); \
        if (!f64 && !strcmp(kernel, "fixed_fma")) LOOP_FIXED(float, noslip_d##N##_fixed_fma_f32, N, S); \
    }

static void *read_all(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    void *buf = malloc(size > 0 ? (size_t)size : 1);
    *len = fread(buf, 1, (size_t)size, f);
    fclose(f);
    return buf;
}

int main(int argc, char **argv) {
    if (argc != 6 && argc != 8 && argc != 9) {
        fprintf(stderr, "usage: harness N KERNEL PRECISION IN OUT [E BETA | E MU BETA0]\n");
        return 2;
    }
    /* The law's parameters in order (rough: e, beta; Walton: e, mu, beta0). */
    double law64[3] = {1.0, 1.0, 1.0};
    float law32[3] = {1.0f, 1.0f, 1.0f};
    for (int k = 6; k < argc; k++) {
        law64[k - 6] = strtod(argv[k], NULL);
        law32[k - 6] = strtof(argv[k], NULL);
    }
    const int n = atoi(argv[1]);
    const char *kernel = argv[2];
    const int f64 = !strcmp(argv[3], "f64");
    const size_t size = f64 ? sizeof(double) : sizeof(float);
    size_t in_len = 0, count = 0, out_len = 0;
    void *in = read_all(argv[4], &in_len);
    if (!in) {
        fprintf(stderr, "harness: cannot read %s\n", argv[4]);
        return 2;
    }
    void *out = malloc(in_len);
    DIM(2, 1)
    DIM(3, 3)
    DIM(4, 6)
    DIM(5, 10)
    DIM(6, 15)
    {
        /* count from the same record layout; the rough kernels read law after the balls. */
        const size_t s_of[7] = {0, 0, 1, 3, 6, 10, 15};
        if (n >= 2 && n <= 6) count = in_len / (((size_t)n + 6 + 2 * (s_of[n] + (size_t)n)) * size);
    }
    ROUGH(2, 1)
    ROUGH(3, 3)
    ROUGH(4, 6)
    ROUGH(5, 10)
    ROUGH(6, 15)
    WALTON(2, 1)
    WALTON(3, 3)
    WALTON(4, 6)
    WALTON(5, 10)
    WALTON(6, 15)
    if (out_len == 0) {
        fprintf(stderr, "harness: no kernel %s for n = %d in %s, or no records\n", kernel, n, argv[3]);
        return 2;
    }
    FILE *f = fopen(argv[5], "wb");
    if (!f || fwrite(out, 1, out_len, f) != out_len || fclose(f) != 0) {
        fprintf(stderr, "harness: cannot write %s\n", argv[5]);
        return 1;
    }
    free(in);
    free(out);
    return 0;
}
