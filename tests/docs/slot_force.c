/* Runs the C example of docs/contact.md (slot_force) at a few points. */
#include <stdio.h>

void slot_force(double gap, double rate, double *force, double *dfdx, double *dfdv);

int main(void) {
    const double gaps[] = {0.0, 5.05, -5.2};
    for (unsigned i = 0; i < sizeof gaps / sizeof gaps[0]; i++) {
        double force, dfdx, dfdv;
        slot_force(gaps[i], 0.7, &force, &dfdx, &dfdv);
        printf("gap %g: force %.12e, dF/dx %.12e, dF/dx' %.12e\n", gaps[i], force, dfdx, dfdv);
    }
    return 0;
}
