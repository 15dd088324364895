/* Output rows made consistent in C (see projection.py): for each row, the
 * non-state unknowns are solved from E(t, z) = 0 by Newton with an LU of
 * dE/dz_free in block lower-triangular form, reused from row to row while it
 * converges fast, so that every equation holds to tol times its scale
 * (|dE_i/dz| times the unknowns' sizes, at the row).  The BLT form (row and
 * column permutations, diagonal blocks) is computed once per system in
 * Python (acausal2d/runtime/blt_layout.py) and handed in as index arrays:
 * each Jacobian nonzero's slot among a diagonal block's entries (compressed
 * by column) or among the below-block entries (also by column).  Each
 * diagonal block is factored by a left-looking sparse LU with partial
 * pivoting (Gilbert and Peierls; the steps of Davis' CSparse cs_lu) and
 * later refactored with the same pivots and pattern while they hold (KLU's
 * refactor); a solve is forward block substitution.  Prepended: CasADi-generated "E"
 * and "EJ" (E and dE/dz) of the system.  A row that does not converge is
 * left as given (ok = 0). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("O2")   /* the functions below; the generated code above keeps -O1 (native.py).
                                Rows alone, CPU s per run: chain 0.0450 -> 0.0394, belt drive 0.0200
                                -> 0.0192, piston 0.0035 -> 0.0033, compressor 0.023 either way */
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define REFACTOR_PIVOT 0.1   /* see a2d_block_refactor */


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
  double *jnz, *ax, *below, *lx, *ux, *dinv, *y, *e, *x, *scale, *z0, tbuf[1];
  int *lp, *li, *up, *ui, *pinv, *xi, *mark;    /* L and U of each block, compressed by column */
  int *pivoted;                 /* per block: its pivots and pattern are set (a2d_block_refactor) */
  size_t *cap;                  /* block b's L and U entries from cap[b] (room for s(s+1)/2 each) */
  const casadi_real **arg;
  casadi_real **res;
  casadi_int *iw;
  casadi_real *w;
} a2d_proj;

typedef struct {              /* one diagonal block of size s and its factors */
  int s;
  const int *ap, *ai;         /* its entries (ap: s + 1 offsets into ax, ai) */
  const double *ax;
  int *lp, *li, *up, *ui, *pinv;
  double *lx, *ux, *dinv;
} a2d_block;

/* Depth-first search from row j in the graph of L: the rows found are put
 * below top in xi, in reverse topological order (CSparse's cs_dfs). */
static int a2d_dfs(int j, const a2d_block *B, int top, int *xi, int *pstack, int *mark, int stamp) {
  const int *lp = B->lp, *li = B->li, *pinv = B->pinv;
  int head = 0;
  xi[0] = j;
  while (head >= 0) {
    int p, p2, done = 1, jn;
    j = xi[head];
    jn = pinv[j];
    if (mark[j] != stamp) { mark[j] = stamp; pstack[head] = jn < 0 ? 0 : lp[jn] + 1; }
    p2 = jn < 0 ? 0 : lp[jn + 1];
    for (p = pstack[head]; p < p2; ++p) {
      int i = li[p];
      if (mark[i] == stamp) continue;
      pstack[head] = p;
      xi[++head] = i;
      done = 0;
      break;
    }
    if (done) { --head; xi[--top] = j; }
  }
  return top;
}

/* x = L \ A(:, k) on the rows reachable from A(:, k) (xi[top..s-1], in
 * topological order); x is zero on entry outside them */
static int a2d_lsolve_column(const a2d_block *B, int k, double *x, int *xi, int *mark, int stamp) {
  const int *ap = B->ap, *ai = B->ai, *lp = B->lp, *li = B->li, *pinv = B->pinv;
  const double *lx = B->lx;
  int p, q, s = B->s, top = s;
  for (p = ap[k]; p < ap[k + 1]; ++p)
    if (mark[ai[p]] != stamp) top = a2d_dfs(ai[p], B, top, xi, xi + s, mark, stamp);
  for (p = ap[k]; p < ap[k + 1]; ++p) x[ai[p]] = B->ax[p];
  for (p = top; p < s; ++p) {
    int j = xi[p], J = pinv[j];
    double xj = x[j];
    if (J < 0 || xj == 0.0) continue;
    for (q = lp[J] + 1; q < lp[J + 1]; ++q) x[li[q]] -= lx[q] * xj;
  }
  return top;
}

/* Column k of L and U from x on xi[top..s-1] (partial pivoting: the row
 * of the largest entry not yet a pivot); x is left zero there */
static int a2d_lu_column(a2d_block *B, int k, double *x, const int *xi, int top, int *lnz, int *unz) {
  int *pinv = B->pinv, *li = B->li, *ui = B->ui;
  double *lx = B->lx, *ux = B->ux;
  int p, ipiv = -1, s = B->s, ql = *lnz, qu = *unz;
  double a = 0.0, pivot, inv;
  for (p = top; p < s; ++p) {
    int i = xi[p];
    if (pinv[i] < 0) { if (fabs(x[i]) > a) { a = fabs(x[i]); ipiv = i; } }
    else { ui[qu] = pinv[i]; ux[qu++] = x[i]; }
  }
  if (ipiv < 0 || !isfinite(a)) return -1;
  if (pinv[k] < 0 && fabs(x[k]) >= a) ipiv = k;     /* a tie: the matched row */
  pivot = x[ipiv];
  inv = B->dinv[k] = 1.0 / pivot;
  ui[qu] = k; ux[qu++] = pivot;       /* U's diagonal last in its column */
  pinv[ipiv] = k;
  li[ql] = ipiv; lx[ql++] = 1.0;      /* L's unit diagonal first */
  for (p = top; p < s; ++p) {
    int i = xi[p];
    if (pinv[i] < 0) { li[ql] = i; lx[ql++] = x[i] * inv; }
    x[i] = 0.0;
  }
  *lnz = ql; *unz = qu;
  return 0;
}

/* LU of one diagonal block: P A = L U (partial pivoting), left-looking */
static int a2d_block_lu(a2d_block *B, double *x, int *xi, int *mark) {
  int k, p, lnz = 0, unz = 0;
  for (k = 0; k < B->s; ++k) { B->pinv[k] = -1; mark[k] = -1; }
  for (k = 0; k < B->s; ++k) {
    int top;
    B->lp[k] = lnz; B->up[k] = unz;
    top = a2d_lsolve_column(B, k, x, xi, mark, k);
    if (a2d_lu_column(B, k, x, xi, top, &lnz, &unz)) {
      for (p = 0; p < B->s; ++p) x[p] = 0.0;
      return -1;
    }
  }
  B->lp[B->s] = lnz; B->up[B->s] = unz;
  for (p = 0; p < lnz; ++p) B->li[p] = B->pinv[B->li[p]];    /* rows of L in pivot order */
  return 0;
}

/* LU of one diagonal block with the pivots and the pattern of its last LU
 * (no search of the reach, no pivot search; KLU's refactor): -1 where a
 * pivot is below REFACTOR_PIVOT times the largest entry of its column of L
 * (then a2d_block_lu chooses new pivots).  x is indexed in pivot order. */
static int a2d_block_refactor(a2d_block *B, double *x) {
  const int *ap = B->ap, *ai = B->ai, *lp = B->lp, *li = B->li, *up = B->up, *ui = B->ui;
  const int *pinv = B->pinv;
  const double *ax = B->ax;
  double *lx = B->lx, *ux = B->ux;
  int k, p, q, s = B->s;
  for (k = 0; k < s; ++k) {
    double pivot, big = 0.0, inv;
    for (p = ap[k]; p < ap[k + 1]; ++p) x[pinv[ai[p]]] = ax[p];
    for (q = up[k]; q < up[k + 1] - 1; ++q) {     /* U's column in topological order */
      int J = ui[q];
      double xj = x[J];
      x[J] = 0.0;
      ux[q] = xj;
      for (p = lp[J] + 1; p < lp[J + 1]; ++p) x[li[p]] -= lx[p] * xj;
    }
    pivot = x[k];
    x[k] = 0.0;
    for (p = lp[k] + 1; p < lp[k + 1]; ++p) if (fabs(x[li[p]]) > big) big = fabs(x[li[p]]);
    if (!(fabs(pivot) >= REFACTOR_PIVOT * big) || !(fabs(pivot) > 0.0)) {
      for (p = lp[k] + 1; p < lp[k + 1]; ++p) x[li[p]] = 0.0;
      return -1;
    }
    ux[up[k + 1] - 1] = pivot;
    inv = B->dinv[k] = 1.0 / pivot;
    for (p = lp[k] + 1; p < lp[k + 1]; ++p) { lx[p] = x[li[p]] * inv; x[li[p]] = 0.0; }
  }
  return 0;
}

/* b = A^-1 b for a factored block (y: workspace of s) */
static void a2d_block_solve(const a2d_block *B, double *b, double *y) {
  const int *pinv = B->pinv, *lp = B->lp, *li = B->li, *up = B->up, *ui = B->ui;
  const double *lx = B->lx, *ux = B->ux, *dinv = B->dinv;
  int j, q, s = B->s;
  for (j = 0; j < s; ++j) y[pinv[j]] = b[j];
  for (j = 0; j < s; ++j) {
    double yj = y[j];
    for (q = lp[j] + 1; q < lp[j + 1]; ++q) y[li[q]] -= lx[q] * yj;
  }
  for (j = s - 1; j >= 0; --j) {
    double yj = y[j] * dinv[j];
    y[j] = yj;
    for (q = up[j]; q < up[j + 1] - 1; ++q) y[ui[q]] -= ux[q] * yj;
  }
  memcpy(b, y, sizeof(double) * s);
}

static a2d_block a2d_block_of(const a2d_proj *h, int k) {
  const a2d_blt *b = &h->b;
  int s0 = b->start[k];
  size_t c = h->cap[k];
  a2d_block B = {b->start[k + 1] - s0, b->aptr + s0, b->ai, h->ax, h->lp + s0 + k, h->li + c,
                 h->up + s0 + k, h->ui + c, h->pinv + s0, h->lx + c, h->ux + c, h->dinv + s0};
  return B;
}

/* Factor the diagonal blocks; all entries must be finite.  A block with
 * an LU from an earlier row is refactored with its pivots first. */
static int a2d_blt_factor(a2d_proj *h) {
  const a2d_blt *b = &h->b;
  int k, n = h->n_eq;
  for (k = 0; k < b->bptr[n]; ++k) if (!isfinite(h->below[k])) return -1;
  for (k = 0; k < b->aptr[n]; ++k) if (!isfinite(h->ax[k])) return -1;
  for (k = 0; k < b->nb; ++k) {
    int s0 = b->start[k];
    a2d_block B;
    if (b->start[k + 1] == s0 + 1) {
      double a = h->ax[b->aptr[s0]];
      if (!(fabs(a) > 0.0)) return -1;
      h->dinv[s0] = 1.0 / a;
      continue;
    }
    B = a2d_block_of(h, k);
    if (h->pivoted[k] && !a2d_block_refactor(&B, h->y)) continue;
    h->pivoted[k] = !a2d_block_lu(&B, h->y, h->xi, h->mark);
    if (!h->pivoted[k]) return -1;
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
    if (s1 == s0 + 1) x[s0] *= dinv[s0];
    else {
      a2d_block B = a2d_block_of(h, k);
      a2d_block_solve(&B, x + s0, h->y);
    }
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
    return EJ(h->arg, h->res, h->iw, h->w, 0);
  }
  return E(h->arg, h->res, h->iw, h->w, 0);
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

static void a2d_alloc(a2d_proj *h) {
  casadi_int sz_arg, sz_res, sz_iw, sz_w, a1, r1, i1, w1;
  int k, n = h->n_eq;
  size_t nd;
  E_work(&sz_arg, &sz_res, &sz_iw, &sz_w);
  EJ_work(&a1, &r1, &i1, &w1);
  if (a1 > sz_arg) sz_arg = a1;
  if (r1 > sz_res) sz_res = r1;
  if (i1 > sz_iw) sz_iw = i1;
  if (w1 > sz_w) sz_w = w1;
  h->cap = (size_t *)malloc(sizeof(size_t) * (h->b.nb + 1));
  for (h->cap[0] = 0, k = 0; k < h->b.nb; ++k) {
    size_t s = (size_t)(h->b.start[k + 1] - h->b.start[k]);
    h->cap[k + 1] = h->cap[k] + (s > 1 ? s * (s + 1) / 2 : 0);
  }
  nd = h->cap[h->b.nb] + 1;
  h->jnz = (double *)malloc(sizeof(double) * (h->nnz + 1));
  h->ax = (double *)malloc(sizeof(double) * (h->b.aptr[n] + 1));
  h->below = (double *)malloc(sizeof(double) * (h->b.bptr[n] + 1));
  h->lx = (double *)malloc(sizeof(double) * nd);
  h->ux = (double *)malloc(sizeof(double) * nd);
  h->li = (int *)malloc(sizeof(int) * nd);
  h->ui = (int *)malloc(sizeof(int) * nd);
  h->lp = (int *)malloc(sizeof(int) * (n + h->b.nb + 1));
  h->up = (int *)malloc(sizeof(int) * (n + h->b.nb + 1));
  h->pinv = (int *)malloc(sizeof(int) * (n + 1));
  h->xi = (int *)malloc(sizeof(int) * (2 * n + 1));
  h->mark = (int *)malloc(sizeof(int) * (n + 1));
  h->pivoted = (int *)calloc(h->b.nb + 1, sizeof(int));
  h->dinv = (double *)malloc(sizeof(double) * (n + 1));
  h->y = (double *)calloc(n + 1, sizeof(double));     /* zero: the LU's column workspace */
  h->e = (double *)malloc(sizeof(double) * (n + 1));
  h->x = (double *)malloc(sizeof(double) * (n + 1));
  h->scale = (double *)malloc(sizeof(double) * (n + 1));
  h->z0 = (double *)malloc(sizeof(double) * (h->n_var + 1));
  h->arg = (const casadi_real **)calloc(sz_arg + 1, sizeof(casadi_real *));
  h->res = (casadi_real **)calloc(sz_res + 1, sizeof(casadi_real *));
  h->iw = (casadi_int *)calloc(sz_iw + 1, sizeof(casadi_int));
  h->w = (casadi_real *)calloc(sz_w + 1, sizeof(casadi_real));
}

static void a2d_release(a2d_proj *h) {
  free(h->cap); free(h->jnz); free(h->ax); free(h->below); free(h->lx); free(h->ux);
  free(h->li); free(h->ui); free(h->lp); free(h->up); free(h->pinv); free(h->xi); free(h->mark); free(h->pivoted);
  free(h->dinv); free(h->y); free(h->e); free(h->x); free(h->scale); free(h->z0);
  free(h->arg); free(h->res); free(h->iw); free(h->w);
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
                int slow, const int *colind, const int *row, const int *blt_ints, int *ok) {
  a2d_proj h;
  int r, c, have = 0, pred = 0;
  double *delta = (double *)calloc(n_var + 1, sizeof(double));
  const int *q = blt_ints;       /* nb, start, rperm, pvar, slot, aptr, ai, bptr, brow in one array */
  memset(&h, 0, sizeof h);
  h.n_var = n_var; h.n_eq = n_eq; h.col_of = col_of; h.nominal = nominal;
  h.colind = colind; h.row = row;
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
  a2d_alloc(&h);
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
