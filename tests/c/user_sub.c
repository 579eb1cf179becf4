/* A C user subroutine's use of the utility subroutines, printed for a
 * snapshot: every branch of BISTOP and IMPACT for IORD 0, 1, 2, STEP, and
 * the error cases. */
#include <math.h>
#include <stdio.h>

#include "mbexpr.h"

static void bistop(double x, double xd, double x1, double x2, int iord) {
    double vector[3] = {-1.0, -1.0, -1.0};
    int errflg = -1;
    c_bistop(x, xd, x1, x2, 1e5, 2.2, 100.0, 0.1, iord, vector, &errflg);
    printf("c_bistop(x=%g, xd=%g, x1=%g, x2=%g, iord=%d) = [%.12g, %.12g, %.12g] errflg=%d\n",
           x, xd, x1, x2, iord, vector[0], vector[1], vector[2], errflg);
}

int main(void) {
    const double points[][2] = {
        {0.0, 0.7},     /* in the gap */
        {10.0, 0.7},    /* at contact */
        {10.05, 0.7},   /* upper stop, inside the damping ramp */
        {10.1, 0.7},    /* at the end of the ramp */
        {10.5, 0.7},    /* beyond the ramp */
        {10.05, -100},  /* fast separation: clamped */
        {-10.05, -0.7}, /* lower stop */
    };
    for (unsigned i = 0; i < sizeof points / sizeof points[0]; i++) {
        for (int iord = 0; iord <= 2; iord++) {
            bistop(points[i][0], points[i][1], -10.0, 10.0, iord);
        }
    }
    bistop(0.0, 0.0, 10.0, -10.0, 0);  /* x1 >= x2 */
    bistop(0.0, 0.0, -10.0, 10.0, 3);  /* iord */
    bistop(NAN, 0.0, -10.0, 10.0, 0);  /* not finite */

    double vector[3];
    int errflg;
    c_impact(0.95, -1.0, 1.0, 1e4, 1.5, 10.0, 0.1, 1, vector, &errflg);
    printf("c_impact(x=0.95, xd=-1, iord=1) = [%.12g, %.12g, %.12g] errflg=%d\n",
           vector[0], vector[1], vector[2], errflg);
    c_impact(0.95, -1.0, 1.0, 1e4, 1.5, 10.0, -0.1, 0, vector, &errflg);
    printf("c_impact(d=-0.1) = [%.12g, %.12g, %.12g] errflg=%d\n",
           vector[0], vector[1], vector[2], errflg);

    for (int iord = 0; iord <= 2; iord++) {
        double value;
        c_step(0.25, 0.0, 0.0, 1.0, 10.0, iord, &value, &errflg);
        printf("c_step(0.25, 0, 0, 1, 10, iord=%d) = %.12g errflg=%d\n", iord, value, errflg);
    }
    double value;
    c_step(0.25, 1.0, 0.0, 1.0, 10.0, 0, &value, &errflg);
    printf("c_step(x0 = x1) = %.12g errflg=%d\n", value, errflg);

    /* Extreme but legal arguments (issues 17.6 and 18.2): the double where
     * the result is one, errflg where it is beyond the range, never NaN or
     * an infinity with errflg 0. */
    c_impact(-5e-161, 0.0, 0.0, 1.0, 2.0, 1.0, 1e-160, 2, vector, &errflg);
    printf("c_impact(x=-5e-161, d=1e-160, iord=2) = [%.12g, %.12g, %.12g] errflg=%d\n",
           vector[0], vector[1], vector[2], errflg);
    c_impact(-1e-300, 0.0, 0.0, 1.0, 0.5, 0.0, 1.0, 2, vector, &errflg);
    printf("c_impact(x=-1e-300, e=0.5, iord=2) = [%.12g, %.12g, %.12g] errflg=%d\n",
           vector[0], vector[1], vector[2], errflg);
    c_impact(-5e-201, 0.0, 0.0, 1.0, 2.0, 1.0, 1e-200, 1, vector, &errflg);
    printf("c_impact(x=-5e-201, d=1e-200, iord=1) = [%.12g, %.12g, %.12g] errflg=%d\n",
           vector[0], vector[1], vector[2], errflg);
    for (int iord = 0; iord <= 2; iord++) {
        c_step(5e-201, 0.0, 0.0, 1e-200, 1.0, iord, &value, &errflg);
        printf("c_step(5e-201, 0, 0, 1e-200, 1, iord=%d) = %.12g errflg=%d\n", iord, value, errflg);
    }
    for (int iord = 0; iord <= 1; iord++) {
        c_step(0.5, 0.0, -1e308, 1.0, 1e308, iord, &value, &errflg);
        printf("c_step(0.5, 0, -1e308, 1, 1e308, iord=%d) = %.12g errflg=%d\n", iord, value, errflg);
    }
    const double rates[] = {-1e307, -7e306, -1e306};
    for (unsigned i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        c_bistop(12.0, rates[i], -10.0, 10.0, 1e308, 3.0, 100.0, 0.1, 0, vector, &errflg);
        printf("c_bistop(x=12, xd=%g, k=1e308, e=3, iord=0) = [%.12g, %.12g, %.12g] errflg=%d\n",
               rates[i], vector[0], vector[1], vector[2], errflg);
    }

    c_bistop(10.05, 0.7, -10.0, 10.0, 1e5, 2.2, 100.0, 0.1, 0, 0, 0); /* null outputs: no crash */
    printf("null outputs: no crash\n");
    return 0;
}
