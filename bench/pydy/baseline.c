/* The bicycle's eval_abcd of this branch and of a baseline checkout, with PyDy's bicycle6,
 * called in turn in one process (see baseline.sh): the same loop as driver.c (1024 distinct
 * parameter vectors, nominal ±5 %, 31 batches, ns per call, median and min), and first the
 * largest relative difference between the two eom kernels' entries over the 1024 vectors.
 *
 * usage: ./build/baseline [rounds]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

void bicycle6_pydy(double *in, double *a, double *b, double *c, double *d);
int bicycle_rs(const double *p, double *a, double *b, double *c, double *d);
int bicycle_base_rs(const double *p, double *a, double *b, double *c, double *d);

#define NV 1024
#define NB 31
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec * 1e9 + t.tv_nsec; }
static int cmp(const void *x, const void *y) { double a = *(const double *)x, b = *(const double *)y; return a < b ? -1 : a > b; }
static const double nom[27] = {1.02, 0.08, 0.3141592653589793, 9.81, 5.0, 0.3, 2.0, 0.0603, 0.12,
    0.3, -0.9, 85.0, 9.2, 11.0, 2.8, 2.4, 0.9, -0.7, 4.0, 0.05892, 0.06, 0.00708, -0.00756, 0.35, 3.0,
    0.1405, 0.28};
static double bp[NV][27];
static double A[36], B[12], C[12], D[4];
static volatile double sink;

#define RUN(name, CALL) do { \
    double r[NB]; long fails = 0; \
    for (int s = 0; s < NB; s++) { \
        double t = now(); \
        for (int i = 0; i < NV; i++) { const double *p = bp[i]; fails += CALL; } \
        r[s] = (now() - t) / NV; \
        sink += A[0] + A[5]; \
    } \
    qsort(r, NB, sizeof(double), cmp); \
    printf("%-15s median %7.2f ns  min %7.2f ns  max %7.2f ns  (fails %ld)\n", name, r[NB / 2], r[0], r[NB - 1], fails); \
    fflush(stdout); } while (0)

static double rel(const double *x, const double *y, int n) {
    double m = 0;
    for (int k = 0; k < n; k++)
        if (x[k] != y[k]) m = fmax(m, fabs(x[k] - y[k]) / fmax(fabs(x[k]), fabs(y[k])));
    return m;
}

int main(int argc, char **argv) {
    int rounds = argc > 1 ? atoi(argv[1]) : 3;
    srand(12345);
    for (int i = 0; i < NV; i++)
        for (int k = 0; k < 27; k++) bp[i][k] = nom[k] * (0.95 + 0.1 * rand() / (double)RAND_MAX);
    double md = 0;
    for (int i = 0; i < NV; i++) {
        double a0[36] = {0}, b0[12] = {0}, c0[12] = {0}, d0[4] = {0};
        double a1[36] = {0}, b1[12] = {0}, c1[12] = {0}, d1[4] = {0};
        if (bicycle_base_rs(bp[i], a0, b0, c0, d0) | bicycle_rs(bp[i], a1, b1, c1, d1)) md = INFINITY;
        md = fmax(md, fmax(fmax(rel(a0, a1, 36), rel(b0, b1, 12)), fmax(rel(c0, c1, 12), rel(d0, d1, 4))));
    }
    printf("largest relative difference of an entry, base against this branch: %.3g\n", md);
    for (int k = 0; k < rounds; k++) {
        printf("round %d\n", k);
        RUN("bicycle6_pydy", (bicycle6_pydy((double *)p, A, B, C, D), 0));
        RUN("bicycle_base_rs", bicycle_base_rs(p, A, B, C, D));
        RUN("bicycle_rs", bicycle_rs(p, A, B, C, D));
    }
    return (int)(sink * 0);
}
