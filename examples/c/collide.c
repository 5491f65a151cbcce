/* The generated C kernels in use (docs/backends.md): the collision of examples/case.json, a
 * ball (m = 2, R = 1, lambda = 1/5) hitting an immovable ball (R = 3/2), then two free balls.
 *
 *   cargo run --release -- gen --lang c --dims 3 --out target/c
 *   cc -std=c99 -O2 -ffp-contract=off -I target/c examples/c/collide.c -o target/c/collide -lm
 *   target/c/collide
 *
 * Prints each body's state after contact (spin U_01 U_02 U_12, then velocity), one body a
 * line, with 17 significant digits. */
#include <stdio.h>

#include "noslip_kernels.h"

static void print_state(const char *label, const double s[6]) {
    printf("%s", label);
    for (int k = 0; k < 6; k++) printf(" %.17g", s[k]);
    printf("\n");
}

int main(void) {
    /* examples/case.json: nu from body 1 to body 2; body 2 immovable. */
    const double nu[3] = {0.0, 0.6, 0.8};
    const double ball1[3] = {0.5, 1.0, 0.4};   /* inv_mass = 1/2, radius, gamma2 = 2 lambda / R^2 */
    const double state1[6] = {1.0, -2.0, 3.0, 1.0, 0.0, 0.5}; /* U_01, U_02, U_12, u */
    const double radius2 = 1.5;
    const double state2[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

    /* Body 2 immovable: `fixed` takes the immovable body first, so the roles swap and the
     * normal is negated (docs/kernels.md, "How collide dispatches"). */
    const double minus_nu[3] = {-nu[0], -nu[1], -nu[2]};
    double body1[6];
    noslip_d3_fixed_f64(minus_nu, radius2, ball1, state2, state1, body1);
    print_state("wall: body 1+", body1);

    /* Two free balls: body 2 now movable (m = 1, R = 3/2, uniform: gamma2 = 2/(n+2) = 2/5). */
    const double ball2[3] = {1.0, 1.5, 0.4};
    double out1[6], out2[6];
    noslip_d3_free_f64(nu, ball1, ball2, state1, state2, out1, out2);
    print_state("free: body 1+", out1);
    print_state("free: body 2+", out2);
    return 0;
}
