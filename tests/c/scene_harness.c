/* The faithfulness harness of the scene-specialised C kernels (tests/scene_backends.rs): runs
 * one kernel of a shipped scene on every record of an input file and writes its outputs.
 *
 *   scene_harness KERNEL PRECISION IN OUT
 *
 * KERNEL is a scene kernel's name without the precision suffix (noslip_gas2d_ball_ball_0_0),
 * PRECISION f64 or f32. The test writes scene_headers.inc (an #include of each scene's
 * header) and scene_kernels.inc (one BALL_BALL, BALL_WALL or BALL_OBSTACLE line per kernel,
 * with its N and S). Records, in the precision's type and native byte order:
 *   ball-ball:     nu[N], state1[S+N], state2[S+N]  ->  out1[S+N], out2[S+N]
 *   ball-wall:     state[S+N]                       ->  out[S+N]
 *   ball-obstacle: nu[N], state[S+N]                ->  out[S+N]
 * Each kernel is called directly in its loop, so the compiler may inline and vectorise it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_headers.inc"

#define LOOP(T, CALL, IN_REC, OUT_REC)                              \
    do {                                                            \
        const size_t in_rec = (IN_REC), out_rec = (OUT_REC);        \
        const T *x = (const T *)in;                                 \
        T *y = (T *)out;                                            \
        count = in_len / (in_rec * sizeof(T));                      \
        for (size_t c = 0; c < count; c++, x += in_rec, y += out_rec) \
            CALL;                                                   \
        out_len = count * out_rec * sizeof(T);                      \
        found = 1;                                                  \
    } while (0)

#define BALL_BALL(FN, N, S)                                                                  \
    if (!strcmp(kernel, #FN)) {                                                              \
        if (f64) LOOP(double, FN##_f64(x, x + (N), x + (N) + (S) + (N), y, y + (S) + (N)),  \
                      (N) + 2 * ((S) + (N)), 2 * ((S) + (N)));                               \
        else LOOP(float, FN##_f32(x, x + (N), x + (N) + (S) + (N), y, y + (S) + (N)),       \
                  (N) + 2 * ((S) + (N)), 2 * ((S) + (N)));                                   \
    }
#define BALL_WALL(FN, N, S)                                                          \
    if (!strcmp(kernel, #FN)) {                                                      \
        if (f64) LOOP(double, FN##_f64(x, y), (S) + (N), (S) + (N));                 \
        else LOOP(float, FN##_f32(x, y), (S) + (N), (S) + (N));                      \
    }
#define BALL_OBSTACLE(FN, N, S)                                                      \
    if (!strcmp(kernel, #FN)) {                                                      \
        if (f64) LOOP(double, FN##_f64(x, x + (N), y), (N) + (S) + (N), (S) + (N));  \
        else LOOP(float, FN##_f32(x, x + (N), y), (N) + (S) + (N), (S) + (N));       \
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
    if (argc != 5) {
        fprintf(stderr, "usage: scene_harness KERNEL PRECISION IN OUT\n");
        return 2;
    }
    const char *kernel = argv[1];
    const int f64 = !strcmp(argv[2], "f64");
    size_t in_len = 0, count = 0, out_len = 0;
    int found = 0;
    void *in = read_all(argv[3], &in_len);
    if (!in) {
        fprintf(stderr, "scene_harness: cannot read %s\n", argv[3]);
        return 2;
    }
    void *out = malloc(2 * in_len + 1); /* every output record is at most twice its input's */
#include "scene_kernels.inc"
    if (!found || out_len == 0) {
        fprintf(stderr, "scene_harness: no kernel %s, or no records\n", kernel);
        return 2;
    }
    FILE *f = fopen(argv[4], "wb");
    if (!f || fwrite(out, 1, out_len, f) != out_len || fclose(f) != 0) {
        fprintf(stderr, "scene_harness: cannot write %s\n", argv[4]);
        return 1;
    }
    free(in);
    free(out);
    return 0;
}
