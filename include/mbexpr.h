/*
 * mbexpr: the solver's utility subroutines for C and C++ user subroutines.
 *
 * Link with target/release/libmbexpr.a (and -lpthread -ldl -lm) or
 * libmbexpr.so. VECTOR has three entries:
 *
 *   VECTOR | iord = 0 | iord = 1   | iord = 2
 *   [0]    | F        | dF/dx      | d2F/dx2
 *   [1]    | 0        | dF/dx'     | d2F/dx dx'
 *   [2]    | 0        | 0          | d2F/dx'2 (always 0)
 *
 * On a broken argument rule (x1 >= x2, k < 0, e <= 0, cmax < 0, d <= 0),
 * an iord other than 0, 1, 2, an input that is not finite, or an entry
 * asked for that is beyond the range of a double (about 1.8e308), *errflg
 * is set to 1 and VECTOR (or *value) to zeros; otherwise *errflg is 0 and
 * every entry is a finite number: no NaN and no infinity is ever returned.
 * See docs/contact.md.
 */
#ifndef MBEXPR_H
#define MBEXPR_H

#ifdef __cplusplus
extern "C" {
#endif

/* BISTOP: free in [x1, x2], pushed back up below x1 and down above x2. */
void c_bistop(double x, double xd, double x1, double x2, double k, double e,
              double cmax, double d, int iord, double *vector, int *errflg);

/* IMPACT: pushed back up when x is below x1. */
void c_impact(double x, double xd, double x1, double k, double e,
              double cmax, double d, int iord, double *vector, int *errflg);

/* STEP: h0 up to x0, h1 from x1, a cubic between; *value is the value or
 * its first or second derivative in x for iord 0, 1, 2. */
void c_step(double x, double x0, double h0, double x1, double h1, int iord,
            double *value, int *errflg);

#ifdef __cplusplus
}
#endif

#endif /* MBEXPR_H */
