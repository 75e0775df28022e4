/* Timing driver: PyDy-generated C (each compiled alone with gcc -O2 -c) vs
 * our generated Rust (staticlib, separate crate) called alternately in the
 * same process.  Each measurement: 31 batches, each batch = BREPS/SREPS passes over
 * 1024 distinct parameter vectors (nominal +-5%, uniform), ns per call; the
 * median and min of the 31 batches are printed.  No LTO: every call is a real
 * call into a separately compiled object.
 *
 * usage: ./driver [rounds]   (default 3 rounds of all functions)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <math.h>

void shimmy_pydy(double *in, double *a, double *b, double *c, double *d);
void bicycle4_pydy(double *in, double *a, double *b);
void bicycle6_pydy(double *in, double *a, double *b, double *c, double *d);
int shimmy_rs(const double *p, double *a, double *b, double *c, double *d);
int bicycle_simplified_rs(const double *p, double *a, double *b, double *c, double *d);
int shimmy_simplified_rs(const double *p, double *a, double *b, double *c, double *d);
int anatomy_no_tests(const double *p, double *a, double *b, double *c, double *d);
int anatomy_pivot(const double *p, double *a, double *b, double *c, double *d);
int anatomy_magnitude(const double *p, double *a, double *b, double *c, double *d);
int anatomy_sinks(const double *p, double *a, double *b, double *c, double *d);
int anatomy_varying_no_tests(const double *p, double *a, double *b, double *c, double *d);
int anatomy_best(const double *p, double *a, double *b, double *c, double *d);
int bicycle_rs(const double *p, double *a, double *b, double *c, double *d);
int bicycle_varying_rs(const double *p, double *a, double *b, double *c, double *d);
int shimmy_varying_rs(const double *p, double *a, double *b, double *c, double *d);

#define NV 1024
#define NB 31
/* passes over the 1024 vectors per batch: batches are kept short (~125-200 us)
 * because the machine is shared (load 3-5 on 2 vCPUs) and the scheduler steals
 * ~4 ms slices every few ms; longer batches get hit in most samples. */
#ifndef BREPS
#define BREPS 1
#endif
#ifndef SREPS
#define SREPS 30
#endif
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec * 1e9 + t.tv_nsec; }
static int cmp(const void *x, const void *y) { double a = *(const double *)x, b = *(const double *)y; return a < b ? -1 : a > b; }

static const double shimmy_nom[6] = {5.0, 1.05, 1.5, 1.0, 0.5, 10.0};
static const double bicycle_nom[27] = {1.02, 0.08, 0.3141592653589793, 9.81, 5.0, 0.3, 2.0, 0.0603, 0.12,
    0.3, -0.9, 85.0, 9.2, 11.0, 2.8, 2.4, 0.9, -0.7, 4.0, 0.05892, 0.06, 0.00708, -0.00756, 0.35, 3.0,
    0.1405, 0.28};
static double sp[NV][6], bp[NV][27];
static double A[36], B[12], C[12], D[4];
static volatile double sink;

/* direct calls in the timed loop (macro, no function pointers) */
#define RUN(name, CALL, ps, np, reps) do { \
    double r[NB]; long fails = 0; \
    for (int s = 0; s < NB; s++) { \
        double t = now(); \
        for (int rep = 0; rep < (reps); rep++) \
            for (int i = 0; i < NV; i++) { const double *p = (ps) + (size_t)i * (np); fails += CALL; } \
        r[s] = (now() - t) / ((double)(reps) * NV); \
        sink += A[0] + A[5]; \
    } \
    qsort(r, NB, sizeof(double), cmp); \
    printf("%-15s median %7.2f ns  min %7.2f ns  max %7.2f ns  (fails %ld)\n", name, r[NB / 2], r[0], r[NB - 1], fails); \
    fflush(stdout); } while (0)

int main(int argc, char **argv) {
    int rounds = argc > 1 ? atoi(argv[1]) : 3;
    srand(12345);
    for (int i = 0; i < NV; i++) {
        for (int k = 0; k < 6; k++) sp[i][k] = shimmy_nom[k] * (0.95 + 0.1 * rand() / (double)RAND_MAX);
        for (int k = 0; k < 27; k++) bp[i][k] = bicycle_nom[k] * (0.95 + 0.1 * rand() / (double)RAND_MAX);
    }
    /* value check at the nominal point (printed once) */
    memset(A, 0, sizeof A); memset(B, 0, sizeof B); memset(C, 0, sizeof C); memset(D, 0, sizeof D);
    bicycle4_pydy((double *)bicycle_nom, A, B);
    printf("PyDy bicycle4 A (row-major) at nominal:");
    for (int i = 0; i < 16; i++) printf("%s%.6f", i % 4 ? " " : "\n  ", A[i]);
    printf("\n");
    memset(A, 0, sizeof A); memset(B, 0, sizeof B); memset(C, 0, sizeof C); memset(D, 0, sizeof D);
    int e = bicycle_rs(bicycle_nom, A, B, C, D);
    printf("Rust bicycle (err %d) A (col-major 6x6) at nominal:", e);
    for (int i = 0; i < 36; i++) printf("%s%.9g", i % 6 ? " " : "\n  ", A[i]);
    printf("\n  B:"); for (int i = 0; i < 12; i++) printf(" %.9g", B[i]);
    printf("\n  C:"); for (int i = 0; i < 12; i++) printf(" %.9g", C[i]);
    printf("\n");
    typedef int (*shimmy_fn)(const double *, double *, double *, double *, double *);
    const shimmy_fn rs[9] = {shimmy_rs, shimmy_simplified_rs, shimmy_varying_rs, anatomy_no_tests, anatomy_pivot, anatomy_sinks, anatomy_magnitude, anatomy_varying_no_tests, anatomy_best};
    const char *rs_name[9] = {"shimmy_rs", "shimmy_simplified_rs", "shimmy_varying_rs", "anatomy_no_tests", "anatomy_pivot", "anatomy_sinks", "anatomy_magnitude", "anatomy_varying_no_tests", "anatomy_best"};
    for (int f = 0; f < 9; f++) {
        double As[9], Bs[3], Cs[6], Ds[2], Ar[9] = {0}, Br[3] = {0}, Cr[6] = {0}, Dr[2] = {0}, md = 0;
        /* the varying kernel writes no constant entry: they come from one full call */
        if (rs[f] == shimmy_varying_rs || rs[f] == anatomy_varying_no_tests || rs[f] == anatomy_best) shimmy_simplified_rs(sp[0], Ar, Br, Cr, Dr);
        for (int i = 0; i < NV; i++) {
            shimmy_pydy(sp[i], As, Bs, Cs, Ds);
            rs[f](sp[i], Ar, Br, Cr, Dr);
            for (int r = 0; r < 3; r++) for (int c = 0; c < 3; c++) md = fmax(md, fabs(As[r * 3 + c] - Ar[r + 3 * c]));
            for (int r = 0; r < 2; r++) for (int c = 0; c < 3; c++) md = fmax(md, fabs(Cs[r * 3 + c] - Cr[r + 2 * c]));
            for (int r = 0; r < 3; r++) md = fmax(md, fabs(Bs[r] - Br[r]));
        }
        printf("shimmy: max |PyDy - %s| over the 1024 vectors (A,B,C): %.3g\n", rs_name[f], md);
    }
    printf("\n");

    for (int k = 0; k < rounds; k++) {
        printf("round %d\n", k);
        RUN("bicycle6_pydy", (bicycle6_pydy((double *)p, A, B, C, D), 0), &bp[0][0], 27, BREPS);
        RUN("bicycle_rs", bicycle_rs(p, A, B, C, D), &bp[0][0], 27, BREPS);
        RUN("bicycle_varying_rs", bicycle_varying_rs(p, A, B, C, D), &bp[0][0], 27, BREPS);
        RUN("bicycle_simplified_rs", bicycle_simplified_rs(p, A, B, C, D), &bp[0][0], 27, BREPS);
        RUN("bicycle4_pydy", (bicycle4_pydy((double *)p, A, B), 0), &bp[0][0], 27, BREPS);
        RUN("shimmy_pydy", (shimmy_pydy((double *)p, A, B, C, D), 0), &sp[0][0], 6, SREPS);
        RUN("shimmy_rs", shimmy_rs(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("shimmy_simplified_rs", shimmy_simplified_rs(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("shimmy_varying_rs", shimmy_varying_rs(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_no_tests", anatomy_no_tests(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_pivot", anatomy_pivot(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_sinks", anatomy_sinks(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_magnitude", anatomy_magnitude(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_varying_no_tests", anatomy_varying_no_tests(p, A, B, C, D), &sp[0][0], 6, SREPS);
        RUN("anatomy_best", anatomy_best(p, A, B, C, D), &sp[0][0], 6, SREPS);
    }
    return (int)(sink * 0);
}
