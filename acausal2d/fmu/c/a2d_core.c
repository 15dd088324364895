/* acausal2d FMU core (see a2d_core.h): Newton solves of the index-reduced
 * equations with linear side conditions, consistent initialization and the
 * event iteration with Modelica semantics (acausal2d/runtime/events.py). */
#include <math.h>
#include <string.h>
#include <stdio.h>

#include "a2d_core.h"
#include "a2d_casadi.h"

#define NEAR_ZERO 1e-6
#define MAX_EVENT_ITERATIONS 20

typedef int (*a2d_fn)(const casadi_real**, casadi_real**, casadi_int*, casadi_real*, int);

static void call(a2d_core* c, a2d_fn f, double t, const double* z, const double* d, double* out)
{
    double tt = t;
    c->arg[0] = &tt;
    c->arg[1] = z;
    c->arg[2] = c->p;
    c->arg[3] = d;
    c->res[0] = out;
    f(c->arg, c->res, c->iw, c->w, 0);
}

void a2d_residual(a2d_core* c, double t, const double* z, double* out)
{
    call(c, a2d_fE, t, z, c->d, out);
}

void a2d_crossings(a2d_core* c, double t, const double* z, double* out)
{
#if A2D_NREL > 0
    call(c, a2d_fG, t, z, c->d, out);
#else
    (void)c; (void)t; (void)z; (void)out;
#endif
}

void a2d_update_offsets(a2d_core* c)
{
#if A2D_NALIAS > 0
    c->arg[0] = c->p;
    c->res[0] = c->offsets;
    a2d_fO(c->arg, c->res, c->iw, c->w, 0);
#endif
}

static void iteration_matrix(a2d_core* c, double t, const double* z, const a2d_rows* rows,
                             double* M);

/* Dense LU with partial pivoting of the n x n row-major M, in place.
 * Returns -1 if M is singular. */
static int lu_factor(double* M, int n, int* piv)
{
    int i, j, k;
    for (k = 0; k < n; k++) {
        int p = k;
        double big = fabs(M[k * n + k]);
        for (i = k + 1; i < n; i++)
            if (fabs(M[i * n + k]) > big) { big = fabs(M[i * n + k]); p = i; }
        if (!(big > 1e-300)) return -1;
        piv[k] = p;
        if (p != k)
            for (j = 0; j < n; j++) { double s = M[k * n + j]; M[k * n + j] = M[p * n + j]; M[p * n + j] = s; }
        for (i = k + 1; i < n; i++) {
            double f = M[i * n + k] / M[k * n + k];
            M[i * n + k] = f;
            if (f == 0.0) continue;
            for (j = k + 1; j < n; j++) M[i * n + j] -= f * M[k * n + j];
        }
    }
    return 0;
}

/* Solve with the factors of lu_factor, in place of b. */
static void lu_back(const double* M, int n, const int* piv, double* b)
{
    int i, k;
    for (k = 0; k < n; k++)
        if (piv[k] != k) { double s = b[k]; b[k] = b[piv[k]]; b[piv[k]] = s; }
    for (k = 0; k < n; k++) {
        double s = b[k];
        if (s != 0.0) for (i = k + 1; i < n; i++) b[i] -= M[i * n + k] * s;
    }
    for (k = n - 1; k >= 0; k--) {
        double s = b[k];
        for (i = k + 1; i < n; i++) s -= M[k * n + i] * b[i];
        b[k] = s / M[k * n + k];
    }
}

/* The slot holding factors for ``rows`` (its kind, s within 20 %), or -1.
 * Factors for a nearby s only precondition the simplified Newton iteration,
 * whose fixed point is the exact solution; it must contract (reused_newton). */
static int kept_slot(const a2d_core* c, const a2d_rows* rows)
{
    int k;
    if (!rows->reuse) return -1;
    for (k = 0; k < 2; k++)
        if (c->lu_valid[k] == rows->reuse && fabs(c->lu_s[k] - rows->s) <= 0.2 * fabs(rows->s))
            return k;
    return -1;
}

/* dz = -M^-1 r with the factors kept in slot k. */
static void kept_step(a2d_core* c, int k)
{
    int j;
    for (j = 0; j < A2D_N; j++) c->dz[j] = -c->r[j];
    lu_back(c->M[k], A2D_N, c->piv[k], c->dz);
    c->cur = k;
}

/* Newton step dz = -M^-1 r with a fresh iteration matrix at z, factored
 * into the slot of ``rows`` (or the one not used last) and kept there. */
static int fresh_step(a2d_core* c, double t, const double* z, const a2d_rows* rows)
{
    int k = kept_slot(c, rows);
    if (k < 0) k = 1 - c->cur;
    iteration_matrix(c, t, z, rows, c->M[k]);
    c->lu_valid[k] = 0;
    if (lu_factor(c->M[k], A2D_N, c->piv[k])) return -1;
    c->lu_valid[k] = rows->reuse;
    c->lu_s[k] = rows->s;
    kept_step(c, k);
    return 0;
}

/* Residuals of E(t, z) = 0 and the side conditions z[a] - s z[b] = rhs. */
static double full_residual(a2d_core* c, double t, const double* z, const a2d_rows* rows,
                            double* r)
{
    int i;
    double norm = 0.0;
    a2d_residual(c, t, z, r);
    for (i = 0; i < rows->n; i++) {
        double v = z[rows->a[i]] - rows->rhs[i];
        if (rows->b && rows->b[i] >= 0) v -= rows->s * z[rows->b[i]];
        r[A2D_NEQ + i] = v;
    }
    for (i = 0; i < A2D_NEQ + rows->n; i++) {
        double v = fabs(r[i]);
        if (!(v <= norm)) norm = v;     /* NaN propagates as a large norm */
    }
    return norm;
}

static void iteration_matrix(a2d_core* c, double t, const double* z, const a2d_rows* rows,
                             double* M)
{
    int k, n = A2D_N;
    memset(M, 0, sizeof(double) * n * n);
    call(c, a2d_fJ, t, z, c->d, c->jnz);
    for (k = 0; k < A2D_NNZ; k++) M[a2d_jrow[k] * n + a2d_jcol[k]] += c->jnz[k];
    for (k = 0; k < rows->n; k++) {
        M[(A2D_NEQ + k) * n + rows->a[k]] += 1.0;
        if (rows->b && rows->b[k] >= 0) M[(A2D_NEQ + k) * n + rows->b[k]] -= rows->s;
    }
}

/* Simplified Newton with the kept factors of an earlier iteration matrix
 * (SDIRK stages share it): 0 when converged; otherwise z is left where the
 * iteration stopped contracting, for the full Newton iteration to go on. */
static int reused_newton(a2d_core* c, double t, const a2d_rows* rows, double* z, double* norm)
{
    int it, j, n = A2D_N, slot = kept_slot(c, rows);
    if (slot < 0) return -1;
    for (it = 0; it < 8; it++) {
        double nn;
        if (*norm < 1e-10) return 0;
        kept_step(c, slot);
        for (j = 0; j < n; j++) c->ztry[j] = z[j] + c->dz[j];
        nn = full_residual(c, t, c->ztry, rows, c->rtry);
        if (!(nn < 0.5 * *norm)) return -1;
        memcpy(z, c->ztry, sizeof(double) * n);
        memcpy(c->r, c->rtry, sizeof(double) * n);
        *norm = nn;
    }
    return *norm < 1e-10 ? 0 : -1;
}

/* Newton steps from a converged point until the steps reach rounding (the
 * solution then hardly depends on the warm start, so that derivatives handed
 * to an importer's integrator are smooth in the states).  Kept factors of an
 * earlier iteration matrix serve while they contract fast; fresh ones else. */
static int polish(a2d_core* c, double t, const a2d_rows* rows, double* z, double norm)
{
    int it, j, n = A2D_N;
    int slot = kept_slot(c, rows), fresh = slot < 0;
    double last = 1e300;
    for (it = 0; it < 8; it++) {
        double size = 0.0, nn;
        int was_fresh = fresh;
        if (fresh) {
            if (fresh_step(c, t, z, rows)) break;
            slot = c->cur;
            fresh = 0;
        } else {
            kept_step(c, slot);
        }
        for (j = 0; j < n; j++) {
            double v = fabs(c->dz[j]) / (1.0 + fabs(z[j]));
            if (v > size) size = v;
            c->ztry[j] = z[j] + c->dz[j];
        }
        nn = full_residual(c, t, c->ztry, rows, c->rtry);
        if (!(nn <= 2.0 * norm + 1e-300)) {
            if (was_fresh) break;
            fresh = 1;
            continue;
        }
        memcpy(z, c->ztry, sizeof(double) * n);
        memcpy(c->r, c->rtry, sizeof(double) * n);
        norm = nn;
        if (size < 1e-14) break;
        if (size > 0.1 * last) fresh = 1;     /* slow contraction: refresh */
        last = size;
    }
    return 0;
}

int a2d_newton(a2d_core* c, double t, const a2d_rows* rows, double* z)
{
    int it, j, n = A2D_N;
    double norm;
    if (A2D_NEQ + rows->n != n) return -2;
    norm = full_residual(c, t, z, rows, c->r);
    if (kept_slot(c, rows) >= 0 && !reused_newton(c, t, rows, z, &norm))
        return rows->polish ? polish(c, t, rows, z, norm) : 0;
    for (it = 0; it < 60; it++) {
        double step = 1.0;
        int accepted = 0;
        if (norm < 1e-10) return rows->polish ? polish(c, t, rows, z, norm) : 0;
        if (fresh_step(c, t, z, rows)) break;
        while (step > 1e-8) {
            double nn;
            for (j = 0; j < n; j++) c->ztry[j] = z[j] + step * c->dz[j];
            nn = full_residual(c, t, c->ztry, rows, c->rtry);
            if ((nn == nn && nn < (1 - 1e-4 * step) * norm)
                || (step == 1.0 && it < 3 && nn == nn && nn < 1e6 * (norm > 1 ? norm : 1))) {
                memcpy(z, c->ztry, sizeof(double) * n);
                memcpy(c->r, c->rtry, sizeof(double) * n);
                norm = nn;
                accepted = 1;
                break;
            }
            step *= 0.5;
        }
        if (!accepted) break;
    }
    if (norm >= 1e-9) return -1;
    return rows->polish ? polish(c, t, rows, z, norm) : 0;
}

/* Text of the equation with the largest residual of E at (t, z). */
static const char* worst_equation(a2d_core* c, double t, const double* z)
{
    int i, worst = 0;
    double big = -1.0;
    a2d_residual(c, t, z, c->r);
    for (i = 0; i < A2D_NEQ; i++) {
        double v = c->r[i] == c->r[i] ? fabs(c->r[i]) : 1e300;
        if (v > big) { big = v; worst = i; }
    }
    return A2D_NEQ > 0 ? a2d_equation_text[worst] : "";
}

int a2d_solve_held(a2d_core* c, double t, const int* held, int n_held, const double* values,
                   double* z)
{
    a2d_rows rows;
    rows.n = n_held;
    rows.a = held;
    rows.b = 0;
    rows.s = 0.0;
    rows.rhs = values;
    rows.reuse = held == a2d_states ? 1 : 0;   /* kept factors for the states held */
    rows.polish = 1;
    return a2d_newton(c, t, &rows, z);
}

int a2d_solve_states(a2d_core* c)
{
    int rc;
    if (!c->dirty) return 0;
    rc = a2d_solve_held(c, c->t, a2d_states, A2D_NX, c->x, c->z);
    if (rc) {
        snprintf(c->message, sizeof(c->message),
                 "no consistent algebraic values for the states at t = %.9g (Newton did not "
                 "converge; largest residual: %s): the mechanism may be at a singular position",
                 c->t, worst_equation(c, c->t, c->z));
        return rc;
    }
    c->dirty = 0;
    return 0;
}

static double relation_value(int k, double g)
{
    return (a2d_strict[k] ? g > 0 : g >= 0) ? 1.0 : 0.0;
}

/* Crossing functions g and their rates at the consistent point z, with the
 * nodes ``held`` moving with their derivative nodes (a re-solve at t + h). */
static void crossing_rates(a2d_core* c, const int* held, int n_held, double* g, double* gdot)
{
    double hv[A2D_NZ], zh[A2D_NZ], g2[A2D_NR], vmax = 1.0, h;
    int k, near = 0;
    a2d_crossings(c, c->t, c->z, g);
    for (k = 0; k < A2D_NREL; k++) { gdot[k] = 0.0; if (fabs(g[k]) <= NEAR_ZERO) near = 1; }
    if (!near) return;
    for (k = 0; k < n_held; k++) {
        int dn = a2d_diff[held[k]];
        double v = dn >= 0 ? c->z[dn] : 0.0;
        if (fabs(v) > vmax) vmax = fabs(v);
    }
    h = 1e-7 * (fabs(c->t) > 1 ? fabs(c->t) : 1.0) / vmax;
    for (k = 0; k < n_held; k++) {
        int dn = a2d_diff[held[k]];
        hv[k] = c->z[held[k]] + h * (dn >= 0 ? c->z[dn] : 0.0);
    }
    memcpy(zh, c->z, sizeof(double) * A2D_N);
    if (a2d_solve_held(c, c->t + h, held, n_held, hv, zh)) return;
    a2d_crossings(c, c->t + h, zh, g2);
    for (k = 0; k < A2D_NREL; k++) gdot[k] = (g2[k] - g[k]) / h;
}

/* Event iteration: relation values from the crossing functions (near zero:
 * from their rates) until they agree with the point they give. */
int a2d_settle(a2d_core* c, const int* held, int n_held, const double* values, int* changed)
{
    double g[A2D_NR], gdot[A2D_NR];
    int it, k;
    for (it = 0; it < MAX_EVENT_ITERATIONS; it++) {
        int differ = 0;
        crossing_rates(c, held, n_held, g, gdot);
        for (k = 0; k < A2D_NREL; k++) {
            double v = relation_value(k, g[k]);
            if (fabs(g[k]) <= NEAR_ZERO && gdot[k] != 0.0) v = gdot[k] > 0 ? 1.0 : 0.0;
            if (v != c->d[k]) { c->d[k] = v; differ = 1; }
        }
        if (!differ) return 0;
        *changed = 1;
        if (a2d_solve_held(c, c->t, held, n_held, values, c->z)) {
            snprintf(c->message, sizeof(c->message), "no consistent values after an event at "
                     "t = %.9g", c->t);
            return -1;
        }
    }
    for (k = 0; k < A2D_NREL; k++)
        if (relation_value(k, g[k]) != c->d[k] || fabs(g[k]) <= NEAR_ZERO) break;
    snprintf(c->message, sizeof(c->message), "the event iteration at t = %.9g found no relation "
             "values that agree with the motion (a sliding mode or chattering) at %s: model "
             "sticking in the element or smooth the relation", c->t,
             k < A2D_NREL ? a2d_relation_text[k] : "a relation");
    return -3;
}

/* Sign (+-1) of det of the iteration matrix with the states held at the
 * consistent point of c, log|det| in *logdet and the pivot of the smallest
 * scaled pivot in *weak; 0 where it is singular within rounding: the
 * smallest pivot of its LU, rows and columns scaled to largest entries 1
 * (the scaling changes no sign and is undone in *logdet), is below
 * PASSAGE_PIVOT of the largest - there Newton's 1e-10 residuals no longer
 * fix the unknowns.  Its own LU buffer: the factors kept for Newton stay. */
#define PASSAGE_PIVOT 1e-10
static int det_sign(a2d_core* c, double* logdet, int* weak)
{
    int i, k, n = A2D_N, sign = 1, small = 0;
    double* M = c->Mdet;
    double big = 0.0;
    a2d_rows rows = {A2D_NX, a2d_states, 0, 0.0, c->x, 0, 0};
    iteration_matrix(c, c->t, c->z, &rows, M);
    *logdet = 0.0;
    for (k = 0; k < 2 * n; k++) {          /* rows (k < n), then columns */
        double m = 0.0;
        double* e = k < n ? M + k * n : M + (k - n);  /* the row or column */
        int step = k < n ? 1 : n;
        for (i = 0; i < n; i++)
            if (fabs(e[i * step]) > m) m = fabs(e[i * step]);
        if (!(m > 0.0)) return 0;
        for (i = 0; i < n; i++) e[i * step] /= m;
        *logdet += log(m);
    }
    if (lu_factor(M, n, c->pivdet)) return 0;
    for (k = 0; k < n; k++) {
        double u = M[k * n + k];
        if (c->pivdet[k] != k) sign = -sign;
        if (u < 0) sign = -sign;
        if (fabs(u) > big) big = fabs(u);
        if (fabs(u) < fabs(M[small * n + small])) small = k;
        *logdet += log(fabs(u));
    }
    *weak = small;
    return fabs(M[small * n + small]) < PASSAGE_PIVOT * big ? 0 : sign;
}

#define PASSAGE_DIP 6.907755278982137     /* log(1e3) */

/* The elements of the equations in the nearly dependent combination of the
 * rows of det_sign's LU (P M = L U; y^T M ~ 0 for y = P^T L^-T U^-T e_weak),
 * the largest weights first, at most three, into buf. */
static void dependent_elements(a2d_core* c, int weak, char* buf, size_t size)
{
    int n = A2D_N, i, k, named = 0;
    double* y = c->ztry;
    const double* M = c->Mdet;
    double big = 0.0;
    for (i = 0; i < n; i++) {                         /* U^T a = e_weak */
        double v = i == weak ? 1.0 : 0.0;
        for (k = 0; k < i; k++) v -= M[k * n + i] * y[k];
        y[i] = v / M[i * n + i];
    }
    for (i = n - 1; i >= 0; i--)                      /* L^T c = a (unit diagonal) */
        for (k = i + 1; k < n; k++) y[i] -= M[k * n + i] * y[k];
    for (k = n - 1; k >= 0; k--)                      /* y = P^T c */
        if (c->pivdet[k] != k) { double t = y[k]; y[k] = y[c->pivdet[k]]; y[c->pivdet[k]] = t; }
    for (i = 0; i < A2D_NEQ; i++) if (fabs(y[i]) > big) big = fabs(y[i]);
    buf[0] = 0;
    while (named < 3 && big > 0.0) {
        int best = -1;
        for (i = 0; i < A2D_NEQ; i++)
            if (fabs(y[i]) >= 0.1 * big && (best < 0 || fabs(y[i]) > fabs(y[best]))) best = i;
        if (best < 0) break;
        y[best] = 0.0;
        {
            char element[80];
            const char* text = a2d_equation_text[best];
            const char* end = strstr(text, " equation ");
            snprintf(element, sizeof(element), "%.*s", end ? (int)(end - text) : 79, text);
            if (strstr(buf, element) == 0) {
                size_t used = strlen(buf);
                snprintf(buf + used, size - used, "%s%s", named ? ", " : "", element);
                named++;
            }
        }
    }
}

static int passage(a2d_core* c, double at, double t0, double t1, int weak, const char* how)
{
    char elements[200];
    dependent_elements(c, weak, elements, sizeof(elements));
    snprintf(c->message, sizeof(c->message), "the mechanism reached a singular position at "
             "t = %.9g in %s (between the steps at %.9g and %.9g the determinant of its "
             "equations %s): the states chosen at the export cannot follow it; acausal2d "
             "simulate passes it and reports it", at, elements[0] ? elements : "its equations",
             t0, t1, how);
    return -1;
}

/* After an accepted step: -1 (with the message) where det dE/dz with the
 * states held changed sign since the last accepted step of the same
 * relation values, or where its size at the last step was a local minimum
 * below 1e-3 of its largest since then (the runtime's criteria,
 * acausal2d/runtime/singularities.py): the mechanism passed or touched a
 * singular position, which the states chosen at the export cannot follow. */
int a2d_check_passage(a2d_core* c)
{
    double logdet = 0.0;
    int weak = 0, sign;
    if (A2D_NX == 0) return 0;
    if (a2d_solve_states(c)) return -1;
    sign = det_sign(c, &logdet, &weak);
    if (sign == 0)
        return passage(c, c->t, c->det_known ? c->det_t[1] : c->t, c->t, weak,
                       "is zero within rounding");
    if (c->det_known && sign != c->det_sign) {
        double w = 1.0 / (1.0 + exp(logdet - c->det_log[1]));   /* |det0| / (|det0| + |det1|) */
        return passage(c, c->det_t[1] + w * (c->t - c->det_t[1]), c->det_t[1], c->t, weak,
                       "changed sign");
    }
    if (c->det_known >= 2 && c->det_log[1] < c->det_log[0] && c->det_log[1] < logdet
        && c->det_log[1] < c->det_max - PASSAGE_DIP)
        return passage(c, c->det_t[1], c->det_t[0], c->t, weak, "had a deep minimum");
    if (!c->det_known || logdet > c->det_max) c->det_max = logdet;
    c->det_sign = sign;
    c->det_t[0] = c->det_t[1];
    c->det_log[0] = c->det_log[1];
    c->det_t[1] = c->t;
    c->det_log[1] = logdet;
    c->det_known += c->det_known < 2;
    return 0;
}

int a2d_event_iteration(a2d_core* c, int* changed)
{
    *changed = 0;
    c->det_known = 0;             /* the relations may change the equations */
    if (a2d_solve_states(c)) return -1;
    return a2d_settle(c, a2d_states, A2D_NX, c->x, changed);
}

int a2d_initialize(a2d_core* c)
{
    double start[A2D_NL0 > 0 ? A2D_NL0 : 1], z0[A2D_NZ], held[A2D_NZ], g[A2D_NR];
    int k, tries, changed = 0;
    memset(c->z, 0, sizeof(c->z));
    memset(c->d, 0, sizeof(c->d));
    a2d_update_offsets(c);
#if A2D_NL0 > 0
    c->arg[0] = c->p;
    c->res[0] = start;
    a2d_fS(c->arg, c->res, c->iw, c->w, 0);
    for (k = 0; k < A2D_NL0; k++) c->z[a2d_level0[k]] = start[k];
#endif
    memcpy(z0, c->z, sizeof(z0));
    for (k = 0; k < A2D_NHELD0; k++) held[k] = z0[a2d_held0[k]];
    a2d_crossings(c, c->t, c->z, g);
    for (k = 0; k < A2D_NREL; k++) c->d[k] = relation_value(k, g[k]);
    for (tries = 0; tries < 10; tries++) {
        int differ = 0;
        memcpy(c->z, z0, sizeof(z0));
        if (!a2d_solve_held(c, c->t, a2d_held0, A2D_NHELD0, held, c->z)) break;
        a2d_crossings(c, c->t, c->z, g);
        for (k = 0; k < A2D_NREL; k++)
            if (relation_value(k, g[k]) != c->d[k]) { c->d[k] = relation_value(k, g[k]); differ = 1; }
        if (!differ) tries = 10;
    }
    if (tries >= 10) {
        snprintf(c->message, sizeof(c->message), "no consistent initial values at t = %.9g "
                 "(Newton did not converge; largest residual: %s): check the geometry and "
                 "the parameter values set", c->t, worst_equation(c, c->t, c->z));
        return -1;
    }
    if (a2d_settle(c, a2d_held0, A2D_NHELD0, held, &changed)) return -1;
    for (k = 0; k < A2D_NX; k++) c->x[k] = c->z[a2d_states[k]];
    c->dirty = 0;
    c->det_known = 0;
    return 0;
}

double a2d_value(a2d_core* c, unsigned int vr)
{
    if (vr < A2D_NP) return c->p[vr];
    vr -= A2D_NP;
    if (vr < A2D_N) return c->z[vr];
    vr -= A2D_N;
#if A2D_NALIAS > 0
    if (vr < A2D_NALIAS) {
        int j = a2d_alias_node[vr];
        return (j >= 0 ? a2d_alias_sign[vr] * c->z[j] : 0.0) + c->offsets[vr];
    }
    vr -= A2D_NALIAS;
#endif
#if A2D_NADER > 0
    if (vr < A2D_NADER) return a2d_alias_der_sign[vr] * c->z[a2d_alias_der_node[vr]];
#endif
    return 0.0;
}

/* The next time event after t (relations of time alone whose crossing
 * function is affine in time), or -1 if there is none. */
double a2d_next_time_event(a2d_core* c, double t)
{
    double next = -1.0;
#if A2D_NTIME > 0
    double gr[2 * A2D_NTIME];
    int k;
    double tt = t;
    c->arg[0] = &tt;
    c->arg[1] = c->p;
    c->res[0] = gr;
    a2d_fT(c->arg, c->res, c->iw, c->w, 0);
    for (k = 0; k < A2D_NTIME; k++) {
        double rate = gr[A2D_NTIME + k], te;
        if (rate == 0.0) continue;
        te = t - gr[k] / rate;
        if (te > t + 1e-13 * (fabs(t) > 1 ? fabs(t) : 1.0) && (next < 0 || te < next)) next = te;
    }
#else
    (void)c; (void)t;
#endif
    return next;
}
