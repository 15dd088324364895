/* Co-Simulation integrator of an acausal2d FMU (a2d_cs.c). */
#ifndef A2D_CS_H
#define A2D_CS_H

#include "a2d_core.h"

typedef struct {
    double rtol, atol;
    double h;          /* internal step size carried from step to step */
    long steps;
} a2d_cs;

void a2d_cs_setup(a2d_cs* s, double tol);
int a2d_cs_advance(a2d_cs* s, a2d_core* c, double t_end);

#endif
