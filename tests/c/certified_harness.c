/* The faithfulness harness of the certified companions in C (tests/c_certified.rs): runs one
 * companion on every record of an input file and writes its outputs and bounds.
 *
 *   certified_harness N KERNEL PRECISION IN OUT [RHO_NU RHO_GAMMA2]
 *
 * KERNEL free, fixed, free_fast, fixed_fast, or the FMA kernels' free_fma, fixed_fma,
 * free_fma_fast, fixed_fma_fast; or the rounded-input companions free_rounded, fixed_rounded,
 * free_fma_rounded, fixed_fma_rounded, which take RHO_NU and RHO_GAMMA2 (decimals of values
 * exact in float); PRECISION f64, f32, or f32_wide (the float kernels' companions with the
 * bound in double; KERNEL free, fixed, free_fma or fixed_fma); or the rough-family companions
 * rough_free, rough_fixed_fma, walton_free, ..., which take the law (E BETA, or E MU BETA0;
 * decimals of values exact in float) for every record. IN holds records as for
 * harness.c: nu[N], ball1[3], ball2[3], state1[S+N], state2[S+N]. OUT receives per record
 * out1, out2 (free) or out2 (fixed, radius1 = ball1[1]), each S+N values, then after all
 * records' outputs, their bounds in the same layout (double for f32_wide). Compiled with
 * -DNOSLIP_ONLY_N=3 it calls the n = 3 companions only (a header of n = 3 alone). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noslip_kernels.h"

#define LOOP(T, B, N, S, FREE, FIXED, ...)                                              \
    do {                                                                                \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), len = (S) + (N);                  \
        count = in_len / (rec * sizeof(T));                                             \
        const T *x = (const T *)in;                                                     \
        T *y = (T *)out;                                                                \
        B *yb = (B *)bounds;                                                            \
        for (size_t c = 0; c < count; c++, x += rec) {                                  \
            const T *nu = x, *b1 = x + (N), *b2 = x + (N) + 3, *s1 = x + (N) + 6,       \
                    *s2 = x + (N) + 6 + len;                                            \
            if (free_) {                                                                \
                FREE(nu, b1, b2, s1, s2, __VA_ARGS__ y, y + len, yb, yb + len);         \
                y += 2 * len;                                                           \
                yb += 2 * len;                                                          \
            } else {                                                                    \
                FIXED(nu, b1[1], b2, s1, s2, __VA_ARGS__ y, yb);                        \
                y += len;                                                               \
                yb += len;                                                              \
            }                                                                           \
        }                                                                               \
        out_len = (size_t)((char *)y - (char *)out);                                    \
        bounds_len = (size_t)((char *)yb - (char *)bounds);                             \
    } while (0)

/* The rough-family companions: `law` (LAW[0..3)) after ball2. */
#define LOOP_LAW(T, N, S, FREE, FIXED)                                                  \
    do {                                                                                \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), len = (S) + (N);                  \
        const T law_t[3] = {(T)law[0], (T)law[1], (T)law[2]};                           \
        count = in_len / (rec * sizeof(T));                                             \
        const T *x = (const T *)in;                                                     \
        T *y = (T *)out;                                                                \
        T *yb = (T *)bounds;                                                            \
        for (size_t c = 0; c < count; c++, x += rec) {                                  \
            const T *nu = x, *b1 = x + (N), *b2 = x + (N) + 3, *s1 = x + (N) + 6,       \
                    *s2 = x + (N) + 6 + len;                                            \
            if (free_) {                                                                \
                FREE(nu, b1, b2, law_t, s1, s2, y, y + len, yb, yb + len);              \
                y += 2 * len;                                                           \
                yb += 2 * len;                                                          \
            } else {                                                                    \
                FIXED(nu, b1[1], b2, law_t, s1, s2, y, yb);                             \
                y += len;                                                               \
                yb += len;                                                              \
            }                                                                           \
        }                                                                               \
        out_len = (size_t)((char *)y - (char *)out);                                    \
        bounds_len = (size_t)((char *)yb - (char *)bounds);                             \
    } while (0)

#define FAMILY(N, S, LAW, FMA)                                                                     \
    if (f64) LOOP_LAW(double, N, S, noslip_d##N##_##LAW##_free##FMA##_certified_f64, noslip_d##N##_##LAW##_fixed##FMA##_certified_f64); \
    else LOOP_LAW(float, N, S, noslip_d##N##_##LAW##_free##FMA##_certified_f32, noslip_d##N##_##LAW##_fixed##FMA##_certified_f32);

#define KIND(N, S, FMA, FAST)                                                                      \
    if (f64) LOOP(double, double, N, S, noslip_d##N##_free##FMA##_certified_##FAST##f64, noslip_d##N##_fixed##FMA##_certified_##FAST##f64, ); \
    else LOOP(float, float, N, S, noslip_d##N##_free##FMA##_certified_##FAST##f32, noslip_d##N##_fixed##FMA##_certified_##FAST##f32, );

#define ROUNDED(N, S, FMA)                                                                         \
    if (f64) LOOP(double, double, N, S, noslip_d##N##_free##FMA##_certified_rounded_f64, noslip_d##N##_fixed##FMA##_certified_rounded_f64, rho_nu, rho_gamma2,); \
    else LOOP(float, float, N, S, noslip_d##N##_free##FMA##_certified_rounded_f32, noslip_d##N##_fixed##FMA##_certified_rounded_f32, (float)rho_nu, (float)rho_gamma2,);

#define WIDE(N, S, FMA)                                                                            \
    LOOP(float, double, N, S, noslip_d##N##_free##FMA##_certified_f32_wide, noslip_d##N##_fixed##FMA##_certified_f32_wide, );

#define DIM(N, S)                                                                                  \
    if (n == (N) && rough && !fma) { FAMILY(N, S, rough, ) }                                       \
    else if (n == (N) && rough && fma) { FAMILY(N, S, rough, _fma) }                               \
    else if (n == (N) && walton && !fma) { FAMILY(N, S, walton, ) }                                \
    else if (n == (N) && walton && fma) { FAMILY(N, S, walton, _fma) }                             \
    else if (n == (N) && wide && !fma) { WIDE(N, S, ) }                                            \
    else if (n == (N) && wide && fma) { WIDE(N, S, _fma) }                                         \
    else if (n == (N) && rounded && !fma) { ROUNDED(N, S, ) }                                      \
    else if (n == (N) && rounded && fma) { ROUNDED(N, S, _fma) }                                   \
    else if (n == (N) && !fma && !fast) { KIND(N, S, , ) }                                         \
    else if (n == (N) && !fma && fast) { KIND(N, S, , fast_) }                                     \
    else if (n == (N) && fma && !fast) { KIND(N, S, _fma, ) }                                      \
    else if (n == (N) && fma && fast) { KIND(N, S, _fma, fast_) }

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
    if (argc < 6 || argc > 9) {
        fprintf(stderr, "usage: certified_harness N KERNEL PRECISION IN OUT [RHO_NU RHO_GAMMA2 | E BETA | E MU BETA0]\n");
        return 2;
    }
    const int n = atoi(argv[1]);
    const int rough = !strncmp(argv[2], "rough_", 6), walton = !strncmp(argv[2], "walton_", 7);
    const char *kernel = argv[2] + (rough ? 6 : walton ? 7 : 0);
    const int free_ = !strncmp(kernel, "free", 4);
    const int fast = strstr(argv[2], "_fast") != NULL;
    const int fma = strstr(argv[2], "_fma") != NULL;
    const int rounded = strstr(argv[2], "_rounded") != NULL;
    const int wide = !strcmp(argv[3], "f32_wide");
    const int f64 = !strcmp(argv[3], "f64");
    if (argc != 6 + (rounded || rough ? 2 : walton ? 3 : 0)) {
        fprintf(stderr, "certified_harness: the _rounded kernels take RHO_NU RHO_GAMMA2, rough_ E BETA, walton_ E MU BETA0, others nothing\n");
        return 2;
    }
    double law[3] = {0.0, 0.0, 0.0};
    for (int k = 6; k < argc && (rough || walton); k++) law[k - 6] = strtod(argv[k], NULL);
    (void)law;
    /* Exact: the test passes values representable in float, as shortest decimals. */
    const double rho_nu = rounded ? strtod(argv[6], NULL) : 0.0;
    const double rho_gamma2 = rounded ? strtod(argv[7], NULL) : 0.0;
    (void)rho_nu;
    (void)rho_gamma2;
    size_t in_len = 0, count = 0, out_len = 0, bounds_len = 0;
    void *in = read_all(argv[4], &in_len);
    if (!in) {
        fprintf(stderr, "certified_harness: cannot read %s\n", argv[4]);
        return 2;
    }
    /* Outputs and bounds, each at most the inputs' size (per record 2 (S+N) values of at most
     * 8 bytes against N + 6 + 2 (S+N) values of at least 4). */
    void *out = malloc(2 * in_len + 64), *bounds = malloc(2 * in_len + 64);
#if !defined(NOSLIP_ONLY_N) || NOSLIP_ONLY_N == 2
    DIM(2, 1)
#endif
#if !defined(NOSLIP_ONLY_N) || NOSLIP_ONLY_N == 3
    DIM(3, 3)
#endif
#if !defined(NOSLIP_ONLY_N) || NOSLIP_ONLY_N == 4
    DIM(4, 6)
#endif
#if !defined(NOSLIP_ONLY_N) || NOSLIP_ONLY_N == 5
    DIM(5, 10)
#endif
#if !defined(NOSLIP_ONLY_N) || NOSLIP_ONLY_N == 6
    DIM(6, 15)
#endif
    (void)count;
    if (out_len == 0) {
        fprintf(stderr, "certified_harness: no kernel %s for n = %d in %s, or no records\n", argv[2], n, argv[3]);
        return 2;
    }
    FILE *f = fopen(argv[5], "wb");
    if (!f || fwrite(out, 1, out_len, f) != out_len || fwrite(bounds, 1, bounds_len, f) != bounds_len ||
        fclose(f) != 0) {
        fprintf(stderr, "certified_harness: cannot write %s\n", argv[5]);
        return 1;
    }
    free(in);
    free(out);
    free(bounds);
    return 0;
}
