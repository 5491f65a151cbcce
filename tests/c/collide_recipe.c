/* What docs/backends.md ("Reproducing `noslip collide` from C") tells an outside user to do,
 * written out: from a case's numbers as `noslip collide` reads them to its f64 answer, bit for
 * bit, with the generated header (`noslip gen --lang c`). cli/tests/c_recipe.rs feeds it the
 * same cases as `noslip collide` and compares every output bit for bit.
 *
 *   collide_recipe MODE < CASES > RESULTS
 *
 * MODE is `recipe` (the documented steps), or a control that leaves one step out, which the
 * test requires to differ: `no-renormalise` (nu used as given), `fma` (the FMA kernels),
 * `still-wall` (the immovable body's state passed as zeros), `spin-sign` (the 2D and 3D
 * shorthands mapped with the opposite sign).
 *
 * A case is one line of whitespace-separated fields:
 *   n  nu[n]  BODY  BODY
 *   BODY = mass radius INERTIA value FORM spin... velocity[n]
 * mass: a decimal, or `inf` (immovable); INERTIA: `u` uniform, `s` shell, `g` gamma2 = value,
 * `l` lambda = value (value ignored for u and s); FORM: `c` a 2D scalar c (U = c J, one
 * value), `w` a 3D vector omega (U x = omega x x, three values), `m` the n x n matrix (n * n
 * values, row-major). Each decimal is read by strtod (correctly rounded, as noslip reads it).
 * A result is one line: per body its angular velocity in the form it was given (c: one value;
 * w: three; m: n * n), then its velocity, each value the 16 hex digits of the double's bits. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noslip_kernels.h"

typedef void (*free_fn)(const double *, const double *, const double *, const double *,
                        const double *, double *, double *);
typedef void (*fixed_fn)(const double *, double, const double *, const double *,
                         const double *, double *);

static const free_fn FREE[7] = {0, 0, noslip_d2_free_f64, noslip_d3_free_f64,
                                noslip_d4_free_f64, noslip_d5_free_f64, noslip_d6_free_f64};
static const fixed_fn FIXED[7] = {0, 0, noslip_d2_fixed_f64, noslip_d3_fixed_f64,
                                  noslip_d4_fixed_f64, noslip_d5_fixed_f64,
                                  noslip_d6_fixed_f64};
static const free_fn FREE_FMA[7] = {0, 0, noslip_d2_free_fma_f64, noslip_d3_free_fma_f64,
                                    noslip_d4_free_fma_f64, noslip_d5_free_fma_f64,
                                    noslip_d6_free_fma_f64};
static const fixed_fn FIXED_FMA[7] = {0, 0, noslip_d2_fixed_fma_f64, noslip_d3_fixed_fma_f64,
                                      noslip_d4_fixed_fma_f64, noslip_d5_fixed_fma_f64,
                                      noslip_d6_fixed_fma_f64};

enum mode { RECIPE, NO_RENORMALISE, FMA, STILL_WALL, SPIN_SIGN };

struct body {
    double mass, radius, value, spin[36], velocity[6];
    char inertia, form;
    double ball[3];  /* inv_mass, radius, gamma2 */
    double state[21]; /* U_01, U_02, .., U_(n-2)(n-1), then u */
};

static int read_double(double *x) { return scanf("%lf", x) == 1; }

static int read_body(struct body *b, int n) {
    char mass[64], inertia[4], form[4];
    if (scanf("%63s", mass) != 1 || !read_double(&b->radius) || scanf("%3s", inertia) != 1 ||
        !read_double(&b->value) || scanf("%3s", form) != 1)
        return 0;
    b->mass = strtod(mass, NULL); /* "inf" reads as infinity */
    b->inertia = inertia[0];
    b->form = form[0];
    int count = b->form == 'c' ? 1 : b->form == 'w' ? 3 : n * n;
    for (int k = 0; k < count; k++)
        if (!read_double(&b->spin[k])) return 0;
    for (int k = 0; k < n; k++)
        if (!read_double(&b->velocity[k])) return 0;
    return 1;
}

/* Steps 2 and 3 of the recipe: the kernel's ball and state of a body. */
static void kernel_inputs(struct body *b, int n, enum mode mode) {
    /* inv_mass = 1.0 / m, rounded in double; 0 for an immovable body. */
    b->ball[0] = isinf(b->mass) ? 0.0 : 1.0 / b->mass;
    b->ball[1] = b->radius;
    switch (b->inertia) {
    case 'u': b->ball[2] = 2.0 / (n + 2.0); break;
    case 's': b->ball[2] = 2.0 / n; break;
    case 'g': b->ball[2] = b->value; break;
    default: b->ball[2] = (2.0 * b->value) / (b->radius * b->radius); break; /* lambda */
    }
    const double sign = mode == SPIN_SIGN ? -1.0 : 1.0;
    if (b->form == 'c') {
        b->state[0] = -sign * b->spin[0]; /* U = c J, J = [[0, -1], [1, 0]]: U_01 = -c */
    } else if (b->form == 'w') {
        const double *w = b->spin; /* U x = w x x: U_01 = -w_2, U_02 = w_1, U_12 = -w_0 */
        b->state[0] = -sign * w[2];
        b->state[1] = sign * w[1];
        b->state[2] = -sign * w[0];
    } else {
        int s = 0; /* the strict upper triangle, row by row */
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) b->state[s++] = b->spin[i * n + j];
    }
    const int S = n * (n - 1) / 2;
    for (int k = 0; k < n; k++) b->state[S + k] = b->velocity[k];
}

static void put(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    printf(" %016llx", (unsigned long long)bits);
}

/* Step 5: the result in the form the angular velocity was given. */
static void print_body(const struct body *b, const double *out, int n) {
    const int S = n * (n - 1) / 2;
    if (b->form == 'c') {
        put(-out[0]);
    } else if (b->form == 'w') {
        put(-out[2]);
        put(out[1]);
        put(-out[0]);
    } else {
        double m[36] = {0};
        int s = 0;
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) {
                m[i * n + j] = out[s];
                m[j * n + i] = 0.0 - out[s]; /* printed as 0 - x: +0 for x = 0 */
                s++;
            }
        for (int k = 0; k < n * n; k++) put(m[k]);
    }
    for (int k = 0; k < n; k++) put(out[S + k]);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: collide_recipe MODE < CASES\n");
        return 2;
    }
    const char *names[] = {"recipe", "no-renormalise", "fma", "still-wall", "spin-sign"};
    int mode = -1;
    for (int m = 0; m < 5; m++)
        if (!strcmp(argv[1], names[m])) mode = m;
    if (mode < 0) {
        fprintf(stderr, "collide_recipe: unknown MODE %s\n", argv[1]);
        return 2;
    }
    int n;
    while (scanf("%d", &n) == 1) {
        if (n < 2 || n > 6) {
            fprintf(stderr, "collide_recipe: n = %d\n", n);
            return 2;
        }
        double nu[6];
        struct body b[2];
        for (int k = 0; k < n; k++)
            if (!read_double(&nu[k])) return 2;
        if (!read_body(&b[0], n) || !read_body(&b[1], n)) {
            fprintf(stderr, "collide_recipe: a malformed case\n");
            return 2;
        }
        /* Step 1: |nu|^2 summed in order; unless exactly 1, nu (3 - |nu|^2) / 2. */
        double norm2 = 0.0;
        for (int k = 0; k < n; k++) norm2 += nu[k] * nu[k];
        if (norm2 != 1.0 && mode != NO_RENORMALISE) {
            const double factor = (3.0 - norm2) / 2.0;
            for (int k = 0; k < n; k++) nu[k] *= factor;
        }
        for (int i = 0; i < 2; i++) kernel_inputs(&b[i], n, (enum mode)mode);
        /* Step 4: the plain kernel; fixed when a body is immovable, reading its state. */
        const int S = n * (n - 1) / 2;
        double zero[21] = {0}, out[2][21];
        const free_fn fr = (mode == FMA ? FREE_FMA : FREE)[n];
        const fixed_fn fx = (mode == FMA ? FIXED_FMA : FIXED)[n];
        const double *wall[2] = {b[0].state, b[1].state};
        if (mode == STILL_WALL) wall[0] = wall[1] = zero;
        if (b[0].ball[0] == 0.0) {
            fx(nu, b[0].radius, b[1].ball, wall[0], b[1].state, out[1]);
            memcpy(out[0], b[0].state, sizeof(double) * (S + n));
        } else if (b[1].ball[0] == 0.0) {
            double minus[6];
            for (int k = 0; k < n; k++) minus[k] = -nu[k];
            fx(minus, b[1].radius, b[0].ball, wall[1], b[0].state, out[0]);
            memcpy(out[1], b[1].state, sizeof(double) * (S + n));
        } else {
            fr(nu, b[0].ball, b[1].ball, b[0].state, b[1].state, out[0], out[1]);
        }
        for (int i = 0; i < 2; i++) print_body(&b[i], out[i], n);
        printf("\n");
    }
    return 0;
}
