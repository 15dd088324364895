/* acausal2d FMU core: the index-1 system of an exported model solved in C.
 *
 * Nodes z (all variable nodes of the index-reduced system), equations
 * E(t, z, p, d) = 0 (n_eq of them, CasADi-generated with their sparse
 * Jacobian), relation values d (0/1, held between events) and their
 * crossing functions g(t, z, p, d).  Holding n - n_eq nodes (the states,
 * or the initial conditions) makes E square in the remaining nodes, which
 * a damped Newton iteration with a dense LU solves. */
#ifndef A2D_CORE_H
#define A2D_CORE_H

#include "a2d_model_data.h"

#define A2D_NZ (A2D_N > 0 ? A2D_N : 1)
#define A2D_NE (A2D_NEQ > 0 ? A2D_NEQ : 1)
#define A2D_NR (A2D_NREL > 0 ? A2D_NREL : 1)
#define A2D_NPP (A2D_NP > 0 ? A2D_NP : 1)
#define A2D_NA (A2D_NALIAS > 0 ? A2D_NALIAS : 1)
#define A2D_NXX (A2D_NX > 0 ? A2D_NX : 1)

/* Side conditions z[a[i]] - s z[b[i]] = rhs[i] (b NULL or b[i] < 0: none). */
typedef struct {
    int n;
    const int* a;
    const int* b;
    double s;
    const double* rhs;
    int reuse;     /* kind of system (0: none) whose factored matrix is kept and reused */
    int polish;    /* Newton steps down to rounding after convergence */
} a2d_rows;

typedef struct {
    double t;
    double z[A2D_NZ];
    double p[A2D_NPP];
    double d[A2D_NR];
    double x[A2D_NXX];
    double offsets[A2D_NA];
    int dirty;                /* z must be solved again for (t, x) */
    /* two slots of LU factors of iteration matrices, each for the kind of
     * system lu_valid[k] (0: none) and side-condition coefficient lu_s[k]
     * (the step-doubling integrator alternates two step sizes) */
    int lu_valid[2];
    double lu_s[2];
    int cur;                  /* the slot used last */
    /* det dE/dz (states held) at the last two accepted steps of the same
     * relation values (a2d_check_passage): its sign (0: none known yet),
     * log|det| and time, and the largest log|det| since the relations changed */
    int det_sign, det_known;
    double det_t[2], det_log[2], det_max;
    /* work */
    const double* arg[A2D_SZ_ARG + 1];
    double* res[A2D_SZ_RES + 1];
    long long iw[A2D_SZ_IW + 1];
    double w[A2D_SZ_W + 1];
    double jnz[A2D_NNZ + 1];
    double M[2][A2D_NZ * A2D_NZ];
    double r[A2D_NZ], rtry[A2D_NZ], dz[A2D_NZ], ztry[A2D_NZ];
    int piv[2][A2D_NZ];
    double Mdet[A2D_NZ * A2D_NZ];     /* the determinant's LU (a2d_check_passage) */
    int pivdet[A2D_NZ];
    char message[512];
} a2d_core;

void a2d_residual(a2d_core* c, double t, const double* z, double* out);
void a2d_crossings(a2d_core* c, double t, const double* z, double* out);
void a2d_update_offsets(a2d_core* c);
int a2d_newton(a2d_core* c, double t, const a2d_rows* rows, double* z);
int a2d_solve_held(a2d_core* c, double t, const int* held, int n_held, const double* values,
                   double* z);
int a2d_settle(a2d_core* c, const int* held, int n_held, const double* values, int* changed);
int a2d_solve_states(a2d_core* c);
int a2d_initialize(a2d_core* c);
int a2d_event_iteration(a2d_core* c, int* changed);
double a2d_value(a2d_core* c, unsigned int vr);
double a2d_next_time_event(a2d_core* c, double t);
int a2d_check_passage(a2d_core* c);

#endif
