/* Output rows made consistent in C (see projection.py): for each row, the
 * non-state unknowns are solved from E(t, z) = 0 by Newton with an LU of
 * dE/dz_free in block lower-triangular form, reused from row to row while it
 * converges fast, so that every equation holds to tol times its scale
 * (|dE_i/dz| times the unknowns' sizes, at the row).  The BLT form (row and
 * column permutations, diagonal blocks) is computed once per system in
 * Python (acausal2d/runtime/blt_layout.py) and handed in as index arrays:
 * each Jacobian nonzero's slot among a diagonal block's entries (compressed
 * by column) or among the below-block entries (also by column).  Each
 * diagonal block of more than one unknown is factored by native_lu.c (the
 * sparse LU of IDA's matrix, placed before this file: Gilbert-Peierls with
 * threshold partial pivoting preferring the block's diagonal - its matched
 * entries - and refactored with its last pivots while they hold); a solve
 * is forward block substitution.  Prepended: CasADi-generated "E" and "EJ"
 * (E and dE/dz) of the system.  A row that does not converge is left as
 * given (ok = 0). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("O2")   /* the functions below; the generated code above keeps -O1 (native.py).
                                Rows alone, CPU s per run: chain 0.0450 -> 0.0394, belt drive 0.0200
                                -> 0.0192, piston 0.0035 -> 0.0033, compressor 0.023 either way */
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {             /* the BLT form (see a2d_project) */
  int nb;                    /* number of diagonal blocks */
  const int *start;          /* block b: positions start[b] .. start[b + 1] - 1 */
  const int *rperm;          /* position -> equation */
  const int *pvar;           /* position -> unknown (index into z) */
  const int *slot;           /* nonzero -> block entry (>= 0), -2 - below entry, -1 (a state) */
  const int *aptr, *ai;      /* block entries by column position, their rows in the block */
  const int *bptr, *brow;    /* below-block entries by column position, their row positions */
} a2d_blt;

typedef struct {
  int n_var, n_eq, nnz;
  const int *col_of;            /* free index of each unknown, -1 for states */
  const int *colind, *row;      /* CCS pattern of dE/dz */
  const double *nominal;        /* nominal of each unknown */
  a2d_blt b;
  double *jnz, *ax, *below, *dinv, *w, *e, *x, *scale, *z0, tbuf[1];
  a2d_splu **lu;                /* per block of more than one unknown its LU (native_lu.c) */
  int *ap;                      /* per block its column starts from 0 (block b: at start[b] + b) */
  const casadi_real **arg;
  casadi_real **res;
  casadi_int *iw;
  casadi_real *w_ca;
  const int *ids;               /* A2D_CAPI: the ids of E and EJ in CasADi's C API */
  int mem[2];                   /* their memories */
} a2d_proj;

/* The functions E and EJ: generated (prepended), or (A2D_CAPI, native_driver.c before
 * this file) evaluated through CasADi's C API */
#ifdef A2D_CAPI
#define A2D_CALL(h, k, fn) casadi_c_eval_id((h)->ids[k], (h)->arg, (h)->res, (h)->iw, \
                                            (h)->w_ca, (h)->mem[k])
#define A2D_WORK(h, k, fn, a, r, i, w) casadi_c_work_id((h)->ids[k], a, r, i, w)
#else
#define A2D_CALL(h, k, fn) fn((h)->arg, (h)->res, (h)->iw, (h)->w_ca, 0)
#define A2D_WORK(h, k, fn, a, r, i, w) fn##_work(a, r, i, w)
#endif

/* Factor the diagonal blocks; all entries must be finite.  A block with
 * an LU from an earlier row is refactored with its pivots first. */
static int a2d_blt_factor(a2d_proj *h) {
  const a2d_blt *b = &h->b;
  int k, n = h->n_eq;
  for (k = 0; k < b->bptr[n]; ++k) if (!isfinite(h->below[k])) return -1;
  for (k = 0; k < b->aptr[n]; ++k) if (!isfinite(h->ax[k])) return -1;
  for (k = 0; k < b->nb; ++k) {
    int s0 = b->start[k], q = b->aptr[s0];
    const int *ap = h->ap + s0 + k;
    if (!h->lu[k]) {
      if (!(fabs(h->ax[q]) > 0.0)) return -1;
      h->dinv[s0] = 1.0 / h->ax[q];
    } else if (a2d_splu_refactor(h->lu[k], ap, b->ai + q, h->ax + q) &&
               a2d_splu_factor(h->lu[k], ap, b->ai + q, h->ax + q)) return -1;
  }
  return 0;
}

/* x = (dE/dz_free)^-1 e in positions: forward block substitution */
static void a2d_blt_solve(const a2d_proj *h, const double *e, double *x) {
  const int *start = h->b.start, *rperm = h->b.rperm, *bptr = h->b.bptr, *brow = h->b.brow;
  const double *below = h->below, *dinv = h->dinv;
  int k, j, q, s0, s1, nb = h->b.nb;
  for (k = 0; k < h->n_eq; ++k) x[k] = e[rperm[k]];
  for (k = 0; k < nb; ++k) {
    s0 = start[k]; s1 = start[k + 1];
    if (!h->lu[k]) x[s0] *= dinv[s0];
    else a2d_splu_solve(h->lu[k], x + s0, x + s0, h->w);
    for (j = s0; j < s1; ++j) {
      double xj = x[j];
      for (q = bptr[j]; q < bptr[j + 1]; ++q) x[brow[q]] -= below[q] * xj;
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
    return A2D_CALL(h, 1, EJ);
  }
  return A2D_CALL(h, 0, E);
}

/* dE/dz at z: the row's equation scales, and (if factor) the BLT LU of dE/dz_free */
static int a2d_jacobian(a2d_proj *h, double t, const double *z, const double *p,
                        const double *d, int factor) {
  const int *colind = h->colind, *row = h->row, *slot = h->b.slot, *col_of = h->col_of;
  const double *jnz = h->jnz, *nominal = h->nominal;
  double *scale = h->scale, *ax = h->ax, *below = h->below;
  int c, k, n = h->n_eq;
  if (a2d_eval(h, 1, t, z, p, d, h->jnz)) return -1;
  memset(scale, 0, sizeof(double) * n);
  for (c = 0; c < h->n_var; ++c) {
    double size = nominal[c] + fabs(z[c]);
    if (col_of[c] < 0) continue;
    for (k = colind[c]; k < colind[c + 1]; ++k) scale[row[k]] += fabs(jnz[k]) * size;
    if (factor) for (k = colind[c]; k < colind[c + 1]; ++k) {
      if (slot[k] >= 0) ax[slot[k]] = jnz[k];
      else below[-2 - slot[k]] = jnz[k];
    }
  }
  for (k = 0; k < n; ++k) if (!(scale[k] > 1e-300)) scale[k] = 1e-300;
  return factor ? a2d_blt_factor(h) : 0;
}

/* Newton on one row with the current LU, from the z at which a2d_jacobian
 * left E(z) in h->e: iterations used, or -1 */
static int a2d_newton(a2d_proj *h, double t, double *z, const double *p, const double *d,
                      double tol, int max_iter) {
  const int *pvar = h->b.pvar;
  const double *e = h->e, *x = h->x, *scale = h->scale;
  int it, i, n = h->n_eq;
  for (it = 0; it <= max_iter; ++it) {
    int done = 1;
    if (it > 0 && a2d_eval(h, 0, t, z, p, d, h->e)) return -1;
    for (i = 0; i < n; ++i) {
      if (!isfinite(e[i])) return -1;
      if (fabs(e[i]) > tol * scale[i]) done = 0;
    }
    if (done) return it;
    if (it == max_iter) break;
    a2d_blt_solve(h, h->e, h->x);
    for (i = 0; i < n; ++i) z[pvar[i]] -= x[i];
  }
  return -1;
}

/* The LU objects of the blocks of more than one unknown, each in its own
 * order (the rows of a block come in minimum-degree order from Python) with
 * its diagonal as the preferred pivots: 0, or -1 out of memory. */
static int a2d_blocks(a2d_proj *h) {
  const a2d_blt *b = &h->b;
  int k, j, n = h->n_eq;
  int *ident = (int *)malloc(sizeof(int) * (n + 1));
  if (!ident) return -1;
  for (j = 0; j < n; ++j) ident[j] = j;
  for (k = 0; k < b->nb; ++k) {
    int s0 = b->start[k], s = b->start[k + 1] - s0;
    for (j = 0; j <= s; ++j) h->ap[s0 + k + j] = b->aptr[s0 + j] - b->aptr[s0];
    if (s > 1 && !(h->lu[k] = a2d_splu_new(s, h->ap[s0 + k + s], ident, ident))) break;
  }
  free(ident);
  return k < b->nb ? -1 : 0;
}

static int a2d_alloc(a2d_proj *h) {
  casadi_int sz_arg, sz_res, sz_iw, sz_w, a1, r1, i1, w1;
  int n = h->n_eq;
  A2D_WORK(h, 0, E, &sz_arg, &sz_res, &sz_iw, &sz_w);
  A2D_WORK(h, 1, EJ, &a1, &r1, &i1, &w1);
#ifdef A2D_CAPI
  h->mem[0] = casadi_c_checkout_id(h->ids[0]);
  h->mem[1] = casadi_c_checkout_id(h->ids[1]);
#endif
  if (a1 > sz_arg) sz_arg = a1;
  if (r1 > sz_res) sz_res = r1;
  if (i1 > sz_iw) sz_iw = i1;
  if (w1 > sz_w) sz_w = w1;
  h->jnz = (double *)malloc(sizeof(double) * (h->nnz + 1));
  h->ax = (double *)malloc(sizeof(double) * (h->b.aptr[n] + 1));
  h->below = (double *)malloc(sizeof(double) * (h->b.bptr[n] + 1));
  h->dinv = (double *)malloc(sizeof(double) * (n + 1));
  h->w = (double *)malloc(sizeof(double) * (n + 1));
  h->e = (double *)malloc(sizeof(double) * (n + 1));
  h->x = (double *)malloc(sizeof(double) * (n + 1));
  h->scale = (double *)malloc(sizeof(double) * (n + 1));
  h->z0 = (double *)malloc(sizeof(double) * (h->n_var + 1));
  h->lu = (a2d_splu **)calloc(h->b.nb + 1, sizeof(a2d_splu *));
  h->ap = (int *)malloc(sizeof(int) * (n + h->b.nb + 1));
  h->arg = (const casadi_real **)calloc(sz_arg + 1, sizeof(casadi_real *));
  h->res = (casadi_real **)calloc(sz_res + 1, sizeof(casadi_real *));
  h->iw = (casadi_int *)calloc(sz_iw + 1, sizeof(casadi_int));
  h->w_ca = (casadi_real *)calloc(sz_w + 1, sizeof(casadi_real));
  if (!h->jnz || !h->ax || !h->below || !h->dinv || !h->w || !h->e || !h->x || !h->scale ||
      !h->z0 || !h->lu || !h->ap || !h->arg || !h->res || !h->iw || !h->w_ca) return -1;
  return a2d_blocks(h);
}

static void a2d_release(a2d_proj *h) {
  int k;
  for (k = 0; h->lu && k < h->b.nb; ++k) a2d_splu_free(h->lu[k]);
  free(h->lu); free(h->ap); free(h->jnz); free(h->ax); free(h->below); free(h->dinv);
  free(h->w); free(h->e); free(h->x); free(h->scale); free(h->z0);
  free(h->arg); free(h->res); free(h->iw); free(h->w_ca);
#ifdef A2D_CAPI
  if (h->ids) {
    casadi_c_release_id(h->ids[0], h->mem[0]);
    casadi_c_release_id(h->ids[1], h->mem[1]);
  }
#endif
}

/* One row from z (its predicted start applied): iterations used, or -1 with
 * z restored; *have: whether the LU stays usable for the next row. */
static int a2d_row(a2d_proj *h, double t, double *z, const double *p, const double *d,
                   double tol, int max_iter, int slow, int *have) {
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
  else if (its > slow) *have = 0;      /* slow: a new LU at the next row */
  return its;
}

int a2d_project(int m, const double *T, double *Z, const double *p, const double *d, int n_var,
                int n_eq, const int *col_of, const double *nominal, double tol, int max_iter,
                int slow, const int *colind, const int *row, const int *blt_ints, int *ok,
                const int *ids) {
  a2d_proj h;
  int r, c, have = 0, pred = 0;
  double *delta = (double *)calloc(n_var + 1, sizeof(double));
  const int *q = blt_ints;       /* nb, start, rperm, pvar, slot, aptr, ai, bptr, brow in one array */
  memset(&h, 0, sizeof h);
  h.n_var = n_var; h.n_eq = n_eq; h.col_of = col_of; h.nominal = nominal;
  h.colind = colind; h.row = row; h.ids = ids;
  h.nnz = colind[n_var];
  h.b.nb = q[0]; q += 1;
  h.b.start = q; q += h.b.nb + 1;
  h.b.rperm = q; q += n_eq;
  h.b.pvar = q; q += n_eq;
  h.b.slot = q; q += h.nnz;
  h.b.aptr = q; q += n_eq + 1;
  h.b.ai = q; q += h.b.aptr[n_eq];
  h.b.bptr = q; q += n_eq + 1;
  h.b.brow = q;
  if (a2d_alloc(&h)) m = 0;         /* out of memory: every row left to the caller */
  for (r = 0; r < m; ++r) {
    double *z = Z + (size_t)r * n_var;
    memcpy(h.z0, z, sizeof(double) * n_var);
    if (pred) for (c = 0; c < n_var; ++c) z[c] += delta[c];   /* the last row's correction */
    ok[r] = a2d_row(&h, T[r], z, p, d, tol, max_iter, slow, &have) >= 0;
    if (!ok[r]) { memcpy(z, h.z0, sizeof(double) * n_var); pred = 0; continue; }
    for (c = 0; c < n_var; ++c) delta[c] = z[c] - h.z0[c];
    pred = 1;
  }
  free(delta);
  a2d_release(&h);
  return 0;
}
