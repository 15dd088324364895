/* Output rows made consistent in C (see projection.py): for each row, the
 * non-state unknowns are solved from E(t, z) = 0 by Newton with an LU of
 * dE/dz_free in block lower-triangular form, reused from row to row while it
 * converges fast, so that every equation holds to tol times its scale
 * (|dE_i/dz| times the unknowns' sizes, at the row).  The BLT form (row and
 * column permutations, diagonal blocks) is computed once per system in
 * Python (acausal2d/compiler/blt.py) and handed in as index arrays: each
 * Jacobian nonzero's slot in a dense diagonal block (column-major, factored
 * with partial pivoting inside the block) or in the below-block entries
 * (compressed by permuted column); a solve is forward block substitution.
 * Prepended: CasADi-generated "E" and "EJ" (E and dE/dz) of the system.
 * A row that does not converge is left as given (ok = 0). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {             /* the BLT form (see a2d_project) */
  int nb;                    /* number of diagonal blocks */
  const int *start;          /* block b: positions start[b] .. start[b + 1] - 1 */
  const int *off;            /* block b's dense storage at off[b] (size s * s) */
  const int *rperm;          /* position -> equation */
  const int *pvar;           /* position -> unknown (index into z) */
  const int *slot;           /* nonzero -> block slot (>= 0), -2 - below slot, -1 (a state) */
  const int *bptr, *brow;    /* below-block entries: by column position, their row positions */
} a2d_blt;

typedef struct {
  int n_var, n_eq, nnz;
  const int *col_of;            /* free index of each unknown, -1 for states */
  const int *colind, *row;      /* CCS pattern of dE/dz */
  const double *nominal;        /* nominal of each unknown */
  a2d_blt b;
  double *jnz, *M, *lx, *ux, *dinv, *below, *e, *x, *scale, *z0, tbuf[1];
  int *piv, *lp, *li, *up, *ui;   /* pivots; nonzero pattern of L (columns) and U (rows) per block */
  const casadi_real **arg;
  casadi_real **res;
  casadi_int *iw;
  casadi_real *w;
} a2d_proj;

/* LU of one dense block (column-major, in place) with partial pivoting,
 * LINPACK's order (dgefa): step k swaps rows k and piv[k] in the columns
 * from k on only, so column k of L is final after step k.  The nonzero
 * rows of each column of L and the nonzero columns of each row of U are
 * listed as they are found (lp/li, up/ui): the updates and the solves run
 * over those only (a mechanism's Jacobian blocks are sparse). */
static int a2d_lu(double *M, int n, int *piv, int *lp, int *li, int *up, int *ui) {
  int i, j, k, p, q, ql = 0, qu = 0;
  for (k = 0; k < n; ++k) {
    double best = 0.0, *Mk = M + (size_t)k * n;
    p = k;
    for (i = k; i < n; ++i) if (fabs(Mk[i]) > best) { best = fabs(Mk[i]); p = i; }
    if (!(best > 0.0) || !isfinite(best)) return -1;
    piv[k] = p;
    if (p != k) for (j = k; j < n; ++j) { double t = M[j * n + k]; M[j * n + k] = M[j * n + p]; M[j * n + p] = t; }
    lp[k] = ql;
    for (i = k + 1; i < n; ++i) if (Mk[i] != 0.0) { Mk[i] /= Mk[k]; li[ql++] = i; }
    up[k] = qu;
    for (j = k + 1; j < n; ++j) {
      double f = M[j * n + k], *Mj = M + (size_t)j * n;
      if (f == 0.0) continue;
      ui[qu++] = j;
      for (q = lp[k]; q < ql; ++q) Mj[li[q]] -= Mk[li[q]] * f;
    }
  }
  lp[n] = ql; up[n] = qu;
  return 0;
}

/* The factors of a2d_lu packed along their pattern lists (lx, ux) with
 * the inverse of U's diagonal (dinv): the solves stream through them
 * instead of gathering from the dense block (which need not fit the cache). */
static void a2d_lu_pack(const double *M, int n, const int *lp, const int *li, const int *up,
                        const int *ui, double *lx, double *ux, double *dinv) {
  int k, q;
  for (k = 0; k < n; ++k) {
    for (q = lp[k]; q < lp[k + 1]; ++q) lx[q] = M[(size_t)k * n + li[q]];
    for (q = up[k]; q < up[k + 1]; ++q) ux[q] = M[(size_t)ui[q] * n + k];
    dinv[k] = 1.0 / M[(size_t)k * n + k];
  }
}

/* Solve with the packed factors: pivots interleaved with the columns of L
 * (LINPACK's dgesl), then U by rows. */
static void a2d_lu_solve(int n, const int *piv, const int *lp, const int *li, const double *lx,
                         const int *up, const int *ui, const double *ux, const double *dinv,
                         double *b) {
  int q, k;
  for (k = 0; k < n; ++k) {
    double bk = b[piv[k]];
    if (piv[k] != k) { b[piv[k]] = b[k]; b[k] = bk; }
    if (bk != 0.0) for (q = lp[k]; q < lp[k + 1]; ++q) b[li[q]] -= lx[q] * bk;
  }
  for (k = n - 1; k >= 0; --k) {
    double s = b[k];
    for (q = up[k]; q < up[k + 1]; ++q) s -= ux[q] * b[ui[q]];
    b[k] = s * dinv[k];
  }
}

/* Factor the diagonal blocks (block b's pivots and pattern lists at
 * start[b], start[b] + b and off[b]); the below-block values are checked. */
static int a2d_blt_factor(a2d_proj *h) {
  const a2d_blt *b = &h->b;
  int k, s0, s;
  for (k = 0; k < b->bptr[h->n_eq]; ++k) if (!isfinite(h->below[k])) return -1;
  for (k = 0; k < b->nb; ++k) {
    double *M = h->M + b->off[k];
    s0 = b->start[k]; s = b->start[k + 1] - s0;
    int *lp = h->lp + s0 + k, *li = h->li + b->off[k], *up = h->up + s0 + k, *ui = h->ui + b->off[k];
    if (s == 1) {
      if (!(fabs(M[0]) > 0.0) || !isfinite(M[0])) return -1;
      h->dinv[s0] = 1.0 / M[0];
      continue;
    }
    if (a2d_lu(M, s, h->piv + s0, lp, li, up, ui)) return -1;
    a2d_lu_pack(M, s, lp, li, up, ui, h->lx + b->off[k], h->ux + b->off[k], h->dinv + s0);
  }
  return 0;
}

/* x = (dE/dz_free)^-1 e in positions: forward block substitution */
static void a2d_blt_solve(const a2d_proj *h, const double *e, double *x) {
  const a2d_blt *b = &h->b;
  int k, j, q, s0, s;
  for (k = 0; k < h->n_eq; ++k) x[k] = e[b->rperm[k]];
  for (k = 0; k < b->nb; ++k) {
    s0 = b->start[k]; s = b->start[k + 1] - s0;
    if (s == 1) x[s0] *= h->dinv[s0];
    else a2d_lu_solve(s, h->piv + s0, h->lp + s0 + k, h->li + b->off[k], h->lx + b->off[k],
                      h->up + s0 + k, h->ui + b->off[k], h->ux + b->off[k], h->dinv + s0, x + s0);
    for (j = s0; j < s0 + s; ++j) {
      double xj = x[j];
      if (xj != 0.0) for (q = b->bptr[j]; q < b->bptr[j + 1]; ++q) x[b->brow[q]] -= h->below[q] * xj;
    }
  }
}

static int a2d_eval(a2d_proj *h, int jac, double t, const double *z, const double *p,
                    const double *d, double *out) {
  h->tbuf[0] = t;
  h->arg[0] = h->tbuf; h->arg[1] = z; h->arg[2] = p; h->arg[3] = d;
  h->res[0] = out;
  if (jac) {            /* E and dE/dz in one pass (shared subexpressions): E into h->e */
    h->res[0] = h->e; h->res[1] = out;
    return EJ(h->arg, h->res, h->iw, h->w, 0);
  }
  return E(h->arg, h->res, h->iw, h->w, 0);
}

/* dE/dz at z: the row's equation scales, and (if factor) the BLT LU of dE/dz_free */
static int a2d_jacobian(a2d_proj *h, double t, const double *z, const double *p,
                        const double *d, int factor) {
  const int *colind = h->colind, *row = h->row, *slot = h->b.slot;
  int c, k, n = h->n_eq;
  if (a2d_eval(h, 1, t, z, p, d, h->jnz)) return -1;
  memset(h->scale, 0, sizeof(double) * n);
  if (factor) memset(h->M, 0, sizeof(double) * h->b.off[h->b.nb]);
  for (c = 0; c < h->n_var; ++c) {
    double size = h->nominal[c] + fabs(z[c]);
    if (h->col_of[c] < 0) continue;
    for (k = colind[c]; k < colind[c + 1]; ++k) {
      h->scale[row[k]] += fabs(h->jnz[k]) * size;
      if (!factor) continue;
      if (slot[k] >= 0) h->M[slot[k]] = h->jnz[k];
      else h->below[-2 - slot[k]] = h->jnz[k];
    }
  }
  for (k = 0; k < n; ++k) if (!(h->scale[k] > 1e-300)) h->scale[k] = 1e-300;
  return factor ? a2d_blt_factor(h) : 0;
}

/* Newton on one row with the current LU, from the z at which a2d_jacobian
 * left E(z) in h->e: iterations used, or -1 */
static int a2d_newton(a2d_proj *h, double t, double *z, const double *p, const double *d,
                      double tol, int max_iter) {
  int it, i, n = h->n_eq;
  for (it = 0; it <= max_iter; ++it) {
    int done = 1;
    if (it > 0 && a2d_eval(h, 0, t, z, p, d, h->e)) return -1;
    for (i = 0; i < n; ++i) {
      if (!isfinite(h->e[i])) return -1;
      if (fabs(h->e[i]) > tol * h->scale[i]) done = 0;
    }
    if (done) return it;
    if (it == max_iter) break;
    a2d_blt_solve(h, h->e, h->x);
    for (i = 0; i < n; ++i) z[h->b.pvar[i]] -= h->x[i];
  }
  return -1;
}

static void a2d_alloc(a2d_proj *h) {
  casadi_int sz_arg, sz_res, sz_iw, sz_w, a1, r1, i1, w1;
  int n = h->n_eq, nd = h->b.off[h->b.nb];
  E_work(&sz_arg, &sz_res, &sz_iw, &sz_w);
  EJ_work(&a1, &r1, &i1, &w1);
  if (a1 > sz_arg) sz_arg = a1;
  if (r1 > sz_res) sz_res = r1;
  if (i1 > sz_iw) sz_iw = i1;
  if (w1 > sz_w) sz_w = w1;
  h->jnz = (double *)malloc(sizeof(double) * (h->nnz + 1));
  h->M = (double *)malloc(sizeof(double) * (nd + 1));
  h->lx = (double *)malloc(sizeof(double) * (nd + 1));
  h->ux = (double *)malloc(sizeof(double) * (nd + 1));
  h->dinv = (double *)malloc(sizeof(double) * (n + 1));
  h->below = (double *)malloc(sizeof(double) * (h->b.bptr[n] + 1));
  h->e = (double *)malloc(sizeof(double) * (n + 1));
  h->x = (double *)malloc(sizeof(double) * (n + 1));
  h->scale = (double *)malloc(sizeof(double) * (n + 1));
  h->z0 = (double *)malloc(sizeof(double) * (h->n_var + 1));
  h->piv = (int *)malloc(sizeof(int) * (n + 1));
  h->lp = (int *)malloc(sizeof(int) * (n + h->b.nb + 1));
  h->up = (int *)malloc(sizeof(int) * (n + h->b.nb + 1));
  h->li = (int *)malloc(sizeof(int) * (nd + 1));
  h->ui = (int *)malloc(sizeof(int) * (nd + 1));
  h->arg = (const casadi_real **)calloc(sz_arg + 1, sizeof(casadi_real *));
  h->res = (casadi_real **)calloc(sz_res + 1, sizeof(casadi_real *));
  h->iw = (casadi_int *)calloc(sz_iw + 1, sizeof(casadi_int));
  h->w = (casadi_real *)calloc(sz_w + 1, sizeof(casadi_real));
}

static void a2d_release(a2d_proj *h) {
  free(h->jnz); free(h->M); free(h->lx); free(h->ux); free(h->dinv); free(h->below); free(h->e); free(h->x); free(h->scale);
  free(h->z0); free(h->piv); free(h->lp); free(h->up); free(h->li); free(h->ui);
  free(h->arg); free(h->res); free(h->iw); free(h->w);
}

/* One row from z (its predicted start applied): iterations used, or -1 with
 * z restored; *have: whether the LU stays usable for the next row. */
static int a2d_row(a2d_proj *h, double t, double *z, const double *p, const double *d,
                   double tol, int max_iter, int *have) {
  int its, fresh = !*have;
  if (a2d_jacobian(h, t, z, p, d, fresh)) { *have = 0; return -1; }
  *have = 1;
  its = a2d_newton(h, t, z, p, d, tol, max_iter);
  if (its < 0 && !fresh) {      /* an LU of an earlier row: once more with this row's */
    memcpy(z, h->z0, sizeof(double) * h->n_var);
    if (a2d_jacobian(h, t, z, p, d, 1)) { *have = 0; return -1; }
    its = a2d_newton(h, t, z, p, d, tol, max_iter);
  }
  if (its < 0) *have = 0;
  else if (its > max_iter / 2) *have = 0;   /* slow: a new LU at the next row (max_iter 6: after 3) */
  return its;
}

int a2d_project(int m, const double *T, double *Z, const double *p, const double *d, int n_var,
                int n_eq, const int *col_of, const double *nominal, double tol, int max_iter,
                const int *colind, const int *row, const int *blt_ints, int *ok) {
  a2d_proj h;
  int r, c, have = 0, pred = 0;
  double *delta = (double *)calloc(n_var + 1, sizeof(double));
  const int *q = blt_ints;       /* nb, start, off, rperm, pvar, slot, bptr, brow, in one array */
  memset(&h, 0, sizeof h);
  h.n_var = n_var; h.n_eq = n_eq; h.col_of = col_of; h.nominal = nominal;
  h.colind = colind; h.row = row;
  h.nnz = colind[n_var];
  h.b.nb = q[0]; q += 1;
  h.b.start = q; q += h.b.nb + 1;
  h.b.off = q; q += h.b.nb + 1;
  h.b.rperm = q; q += n_eq;
  h.b.pvar = q; q += n_eq;
  h.b.slot = q; q += h.nnz;
  h.b.bptr = q; q += n_eq + 1;
  h.b.brow = q;
  a2d_alloc(&h);
  for (r = 0; r < m; ++r) {
    double *z = Z + (size_t)r * n_var;
    memcpy(h.z0, z, sizeof(double) * n_var);
    if (pred) for (c = 0; c < n_var; ++c) z[c] += delta[c];   /* the last row's correction */
    ok[r] = a2d_row(&h, T[r], z, p, d, tol, max_iter, &have) >= 0;
    if (!ok[r]) { memcpy(z, h.z0, sizeof(double) * n_var); pred = 0; continue; }
    for (c = 0; c < n_var; ++c) delta[c] = z[c] - h.z0[c];
    pred = 1;
  }
  free(delta);
  a2d_release(&h);
  return 0;
}
