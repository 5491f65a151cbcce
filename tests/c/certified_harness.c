/* The faithfulness harness of the certified companions in C (tests/c_certified.rs): runs one
 * companion on every record of an input file and writes its outputs and bounds.
 *
 *   certified_harness N KERNEL PRECISION IN OUT
 *
 * KERNEL free, fixed, free_fast, fixed_fast, or the FMA kernels' free_fma, fixed_fma,
 * free_fma_fast, fixed_fma_fast; PRECISION f64 or f32. IN holds records as for harness.c: nu[N],
 * ball1[3], ball2[3], state1[S+N], state2[S+N]. OUT receives per record out1, out2, bound1,
 * bound2 (free) or out2, bound2 (fixed, radius1 = ball1[1]), each S+N values. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noslip_kernels.h"

#define LOOP(T, N, S, FREE, FIXED)                                                      \
    do {                                                                                \
        const size_t rec = (N) + 6 + 2 * ((S) + (N)), len = (S) + (N);                  \
        count = in_len / (rec * sizeof(T));                                             \
        const T *x = (const T *)in;                                                     \
        T *y = (T *)out;                                                                \
        for (size_t c = 0; c < count; c++, x += rec) {                                  \
            const T *nu = x, *b1 = x + (N), *b2 = x + (N) + 3, *s1 = x + (N) + 6,       \
                    *s2 = x + (N) + 6 + len;                                            \
            if (free_) {                                                                \
                FREE(nu, b1, b2, s1, s2, y, y + len, y + 2 * len, y + 3 * len);         \
                y += 4 * len;                                                           \
            } else {                                                                    \
                FIXED(nu, b1[1], b2, s1, s2, y, y + len);                               \
                y += 2 * len;                                                           \
            }                                                                           \
        }                                                                               \
        out_len = (size_t)((char *)y - (char *)out);                                    \
    } while (0)

#define KIND(N, S, FMA, FAST)                                                                      \
    if (f64) LOOP(double, N, S, noslip_d##N##_free##FMA##_certified_##FAST##f64, noslip_d##N##_fixed##FMA##_certified_##FAST##f64); \
    else LOOP(float, N, S, noslip_d##N##_free##FMA##_certified_##FAST##f32, noslip_d##N##_fixed##FMA##_certified_##FAST##f32);

#define DIM(N, S)                                                                                  \
    if (n == (N) && !fma && !fast) { KIND(N, S, , ) }                                              \
    if (n == (N) && !fma && fast) { KIND(N, S, , fast_) }                                          \
    if (n == (N) && fma && !fast) { KIND(N, S, _fma, ) }                                           \
    if (n == (N) && fma && fast) { KIND(N, S, _fma, fast_) }

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
    if (argc != 6) {
        fprintf(stderr, "usage: certified_harness N KERNEL PRECISION IN OUT\n");
        return 2;
    }
    const int n = atoi(argv[1]);
    const int free_ = !strncmp(argv[2], "free", 4);
    const int fast = strstr(argv[2], "_fast") != NULL;
    const int fma = strstr(argv[2], "_fma") != NULL;
    const int f64 = !strcmp(argv[3], "f64");
    size_t in_len = 0, count = 0, out_len = 0;
    void *in = read_all(argv[4], &in_len);
    if (!in) {
        fprintf(stderr, "certified_harness: cannot read %s\n", argv[4]);
        return 2;
    }
    void *out = malloc(2 * in_len + 64);
    DIM(2, 1)
    DIM(3, 3)
    DIM(4, 6)
    DIM(5, 10)
    DIM(6, 15)
    (void)count;
    if (out_len == 0) {
        fprintf(stderr, "certified_harness: no kernel %s for n = %d in %s, or no records\n", argv[2], n, argv[3]);
        return 2;
    }
    FILE *f = fopen(argv[5], "wb");
    if (!f || fwrite(out, 1, out_len, f) != out_len || fclose(f) != 0) {
        fprintf(stderr, "certified_harness: cannot write %s\n", argv[5]);
        return 1;
    }
    free(in);
    free(out);
    return 0;
}
