/* The C energy-conserving correction against the Rust one (tests/c_backend/conserve.rs): applies
 * noslip_conserve_fixed_dN and noslip_conserve_free_dN to every record of an input file and
 * writes the corrected states.
 *
 *   conserve_harness N IN OUT
 *
 * IN holds records of doubles, native byte order: ball1[3], ball2[3], before1[S+N],
 * before2[S+N], after1[S+N], after2[S+N], fixed2[S+N] (ball = inv_mass, radius, gamma2;
 * state = spin, velocity; after1, after2 the free kernel's outputs, fixed2 the fixed kernel's
 * output for body 2 against an immovable body 1). OUT receives per record fixed2 corrected
 * (ball2, before2), then after1 and after2 corrected (free). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noslip_kernels.h"

#define LOOP(N, S)                                                                   \
    do {                                                                             \
        const size_t st = (S) + (N), rec = 6 + 5 * st, out_rec = 3 * st;            \
        const double *x = (const double *)in;                                        \
        double *y = (double *)out;                                                   \
        for (size_t c = 0; c < count; c++, x += rec, y += out_rec) {                 \
            memcpy(y, x + 6 + 4 * st, st * sizeof(double));                          \
            noslip_conserve_fixed_d##N(x + 3, x + 6 + st, y);                         \
            memcpy(y + st, x + 6 + 2 * st, 2 * st * sizeof(double));                 \
            noslip_conserve_free_d##N(x, x + 3, x + 6, x + 6 + st, y + st, y + 2 * st); \
        }                                                                            \
        out_len = count * out_rec * sizeof(double);                                  \
    } while (0)

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: conserve_harness N IN OUT\n");
        return 2;
    }
    int n = atoi(argv[1]);
    FILE *f = fopen(argv[2], "rb");
    if (!f)
        return 3;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *in = malloc((size_t)len + 1);
    if (!in || fread(in, 1, (size_t)len, f) != (size_t)len)
        return 4;
    fclose(f);
    size_t s = (size_t)(n * (n - 1) / 2), st = s + (size_t)n;
    size_t count = (size_t)len / ((6 + 5 * st) * sizeof(double));
    char *out = malloc(count * 3 * st * sizeof(double) + 1);
    size_t out_len = 0;
    if (!out)
        return 5;
    switch (n) {
    case 2: LOOP(2, 1); break;
    case 3: LOOP(3, 3); break;
    case 4: LOOP(4, 6); break;
    case 5: LOOP(5, 10); break;
    case 6: LOOP(6, 15); break;
    default: return 6;
    }
    FILE *g = fopen(argv[3], "wb");
    if (!g || fwrite(out, 1, out_len, g) != out_len)
        return 7;
    fclose(g);
    free(in);
    free(out);
    return 0;
}
