/* Co-Simulation integrator of an acausal2d FMU: Alexander's 3-stage
 * L-stable, stiffly accurate SDIRK method of order 3 applied to the
 * semi-explicit index-1 DAE (every stage solves all equations E together
 * with z[x] - h gamma z[der(x)] = rhs, so each stage is consistent), step
 * size control by step doubling, relation crossings located by bisection
 * of the step and handled by the event iteration, time events hit exactly. */
#include <math.h>
#include <string.h>
#include <stdio.h>

#include "a2d_cs.h"

#define GAMMA 0.43586652150845899942
#define MAX_STEPS_PER_CALL 1000000

static const double C2 = (1.0 + GAMMA) / 2.0;

void a2d_cs_setup(a2d_cs* s, double tol)
{
    s->rtol = tol > 0 ? tol : 1e-8;
    if (s->rtol > 1e-6) s->rtol = 1e-6;
    s->atol = 1e-3 * s->rtol;
    s->h = 0.0;
    s->steps = 0;
}

/* One SDIRK step of size h from (c->t, z0): z1 (consistent at t + h). */
static int sdirk_step(a2d_core* c, const double* z0, double h, double* z1)
{
    static const double b1 = -(6 * GAMMA * GAMMA - 16 * GAMMA + 1) / 4.0;
    static const double b2 = (6 * GAMMA * GAMMA - 20 * GAMMA + 5) / 4.0;
    double K[3][A2D_NXX], rhs[A2D_NXX];
    const double ci[3] = {GAMMA, C2, 1.0};
    int i, k, der[A2D_NXX];
    a2d_rows rows;
    for (k = 0; k < A2D_NX; k++) der[k] = a2d_diff[a2d_states[k]];
    rows.n = A2D_NX;
    rows.a = a2d_states;
    rows.b = der;
    rows.s = h * GAMMA;
    rows.rhs = rhs;
    rows.reuse = 2;       /* all stages share the iteration matrix */
    rows.polish = 0;
    memcpy(z1, z0, sizeof(double) * A2D_N);
    for (i = 0; i < 3; i++) {
        for (k = 0; k < A2D_NX; k++) {
            double x0 = z0[a2d_states[k]];
            if (i == 1) x0 += h * (C2 - GAMMA) * K[0][k];
            if (i == 2) x0 += h * (b1 * K[0][k] + b2 * K[1][k]);
            rhs[k] = x0;
        }
        if (a2d_newton(c, c->t + ci[i] * h, &rows, z1)) return -1;
        for (k = 0; k < A2D_NX; k++) K[i][k] = z1[der[k]];
    }
    return 0;
}

/* Accepted step with error control: two half steps against one full step. */
static int controlled_step(a2d_cs* s, a2d_core* c, double h_max, double* z1, double* h_used)
{
    double full[A2D_NZ], half[A2D_NZ];
    double h = s->h > 0 && s->h < h_max ? s->h : h_max, t0 = c->t;
    int k, tries;
    for (tries = 0; tries < 60; tries++) {
        double err = 0.0, fac;
        int ok = !sdirk_step(c, c->z, h, full);
        if (ok) ok = !sdirk_step(c, c->z, 0.5 * h, half);
        if (ok) { c->t = t0 + 0.5 * h; ok = !sdirk_step(c, half, 0.5 * h, z1); c->t = t0; }
        if (ok) {
            for (k = 0; k < A2D_NX; k++) {
                double a = z1[a2d_states[k]], e = fabs(a - full[a2d_states[k]]) / 7.0;
                e /= s->atol * a2d_nominal_x[k] + s->rtol * fabs(a);
                if (e > err) err = e;
            }
            if (err <= 1.0) {
                *h_used = h;
                fac = err > 0 ? 0.9 * pow(err, -0.25) : 4.0;
                s->h = h * (fac > 4.0 ? 4.0 : (fac < 0.2 ? 0.2 : fac));
                return 0;
            }
            fac = 0.9 * pow(err, -0.25);
            h *= fac < 0.1 ? 0.1 : (fac > 0.5 ? 0.5 : fac);
        } else {
            h *= 0.25;
        }
        if (h < 1e-14 * (fabs(t0) > 1 ? fabs(t0) : 1.0)) break;
    }
    snprintf(c->message, sizeof(c->message), "the integrator could not step on from t = %.9g",
             t0);
    return -1;
}

/* Does a relation disagree with the point z (a crossing inside the step)? */
static int crossed(a2d_core* c, double t, const double* z)
{
    double g[A2D_NR];
    int k;
    a2d_crossings(c, t, z, g);
    for (k = 0; k < A2D_NREL; k++) {
        double v = (a2d_strict[k] ? g[k] > 0 : g[k] >= 0) ? 1.0 : 0.0;
        if (v != c->d[k] && fabs(g[k]) > 1e-12) return 1;
    }
    return 0;
}

/* The step [t, t + h] crossed a relation: the first crossing time by
 * bisection (to 1e-12 relative); z1 becomes the point just after it. */
static int locate(a2d_core* c, double h, double* z1, double* h_event)
{
    double lo = 0.0, hi = h, zt[A2D_NZ];
    int it;
    for (it = 0; it < 200 && hi - lo > 1e-12 * (fabs(c->t) > 1 ? fabs(c->t) : 1.0); it++) {
        double mid = 0.5 * (lo + hi);
        if (sdirk_step(c, c->z, mid, zt)) return -1;
        if (crossed(c, c->t + mid, zt)) { hi = mid; memcpy(z1, zt, sizeof(zt)); }
        else lo = mid;
    }
    if (hi == h) return 0;
    *h_event = hi;
    return 0;
}

int a2d_cs_advance(a2d_cs* s, a2d_core* c, double t_end)
{
    double z1[A2D_NZ];
    long n;
    int changed;
    if (a2d_solve_states(c)) return -1;
    for (n = 0; n < MAX_STEPS_PER_CALL && c->t < t_end - 1e-13 * (fabs(t_end) > 1 ? fabs(t_end) : 1); n++) {
        double h_max = t_end - c->t, h = 0.0, te = a2d_next_time_event(c, c->t);
        int k, timed = 0;
        if (te > 0 && te - c->t <= h_max) h_max = te - c->t;
        if (controlled_step(s, c, h_max, z1, &h)) return -1;
        if (A2D_NREL > 0 && crossed(c, c->t + h, z1)) {
            double he = h;
            if (locate(c, h, z1, &he)) return -1;
            h = he;
            timed = 1;
        }
        c->t = (h == h_max) ? c->t + h_max : c->t + h;
        memcpy(c->z, z1, sizeof(z1));
        for (k = 0; k < A2D_NX; k++) c->x[k] = c->z[a2d_states[k]];
        c->dirty = 0;
        s->steps++;
        if (a2d_check_passage(c)) return -1;
        if (timed || (te > 0 && fabs(c->t - te) <= 1e-13 * (fabs(te) > 1 ? fabs(te) : 1))) {
            if (a2d_event_iteration(c, &changed)) return -1;
        }
    }
    c->t = t_end;
    return 0;
}
