/* Output rows made consistent in C (see projection.py): for each row, the
 * non-state unknowns are solved from E(t, z) = 0 by Newton with a dense LU
 * of dE/dz_free, reused from row to row while it converges fast, so that
 * every equation holds to tol times its scale (|dE_i/dz| times the
 * unknowns' sizes, at the row).  Prepended: CasADi-generated "E" and "dEdz"
 * of the system.  A row that does not converge is left as given (ok = 0). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* SUNDIALS 7.x declarations (the wheel ships no headers): SuperLU_MT through
 * the generic linear-solver interface, for the sparse rows */
typedef struct _generic_N_Vector *N_Vector;
typedef struct _generic_SUNMatrix *SUNMatrix;
typedef struct _generic_SUNLinearSolver *SUNLinearSolver;
typedef struct SUNContext_ *SUNContext;
int SUNContext_Create(int comm, SUNContext *ctx);
int SUNContext_Free(SUNContext *ctx);
int SUNContext_ClearErrHandlers(SUNContext ctx);
N_Vector N_VNew_Serial(int n, SUNContext ctx);
double *N_VGetArrayPointer(N_Vector v);
void N_VDestroy(N_Vector v);
SUNMatrix SUNSparseMatrix(int m, int n, int nnz, int type, SUNContext ctx);
double *SUNSparseMatrix_Data(SUNMatrix a);
int *SUNSparseMatrix_IndexValues(SUNMatrix a);
int *SUNSparseMatrix_IndexPointers(SUNMatrix a);
void SUNMatDestroy(SUNMatrix a);
SUNLinearSolver SUNLinSol_SuperLUMT(N_Vector y, SUNMatrix a, int threads, SUNContext ctx);
int SUNLinSolInitialize(SUNLinearSolver s);
int SUNLinSolSetup(SUNLinearSolver s, SUNMatrix a);
int SUNLinSolSolve(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b, double tol);
int SUNLinSolFree(SUNLinearSolver s);

typedef struct {
  int n_var, n_eq, nnz;
  const int *col_of;            /* free index of each unknown, -1 for states */
  const int *colind, *row;      /* CCS pattern of dE/dz (given: generated code compresses dense ones) */
  const double *nominal;        /* nominal of each unknown */
  double *jnz, *M, *e, *scale, *z0, tbuf[1];
  int *piv, *lp, *li, *up, *ui;   /* pivots; nonzero pattern of L and U */
  int sparse, set_up;           /* SuperLU_MT instead of the dense LU; factored once */
  SUNContext ctx;
  N_Vector x, b;
  SUNMatrix A;
  SUNLinearSolver LS;
  const casadi_real **arg;
  casadi_real **res;
  casadi_int *iw;
  casadi_real *w;
} a2d_proj;

static int a2d_lu(double *M, int n, int *piv) {   /* column-major, in place */
  int i, j, k, p;
  for (k = 0; k < n; ++k) {
    double best = 0.0;
    p = k;
    for (i = k; i < n; ++i) if (fabs(M[k * n + i]) > best) { best = fabs(M[k * n + i]); p = i; }
    if (!(best > 0.0) || !isfinite(best)) return -1;
    piv[k] = p;
    if (p != k) for (j = 0; j < n; ++j) { double t = M[j * n + k]; M[j * n + k] = M[j * n + p]; M[j * n + p] = t; }
    for (i = k + 1; i < n; ++i) M[k * n + i] /= M[k * n + k];
    for (j = k + 1; j < n; ++j) {
      double f = M[j * n + k];
      if (f != 0.0) for (i = k + 1; i < n; ++i) M[j * n + i] -= M[k * n + i] * f;
    }
  }
  return 0;
}

/* Nonzeros of each column of L (below the diagonal) and U (above it), in
 * ascending row order: the solves skip the exact zeros of the factors (the
 * rows of a mechanism's Jacobian are sparse), same operations otherwise. */
static void a2d_lu_pattern(const double *M, int n, int *lp, int *li, int *up, int *ui) {
  int i, k, ql = 0, qu = 0;
  for (k = 0; k < n; ++k) {
    lp[k] = ql; up[k] = qu;
    for (i = k + 1; i < n; ++i) if (M[k * n + i] != 0.0) li[ql++] = i;
    for (i = 0; i < k; ++i) if (M[k * n + i] != 0.0) ui[qu++] = i;
  }
  lp[n] = ql; up[n] = qu;
}

static void a2d_lu_solve(const double *M, int n, const int *piv, const int *lp,
                         const int *li, const int *up, const int *ui, double *b) {
  int q, k;
  for (k = 0; k < n; ++k) { if (piv[k] != k) { double t = b[k]; b[k] = b[piv[k]]; b[piv[k]] = t; } }
  for (k = 0; k < n; ++k) for (q = lp[k]; q < lp[k + 1]; ++q) b[li[q]] -= M[k * n + li[q]] * b[k];
  for (k = n - 1; k >= 0; --k) {
    b[k] /= M[k * n + k];
    for (q = up[k]; q < up[k + 1]; ++q) b[ui[q]] -= M[k * n + ui[q]] * b[k];
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

/* dE/dz at z: the row's equation scales, and (if factor) the LU of dE/dz_free */
static int a2d_jacobian(a2d_proj *h, double t, const double *z, const double *p,
                        const double *d, int factor) {
  const int *colind = h->colind, *row = h->row;
  int c, k, n = h->n_eq;
  if (a2d_eval(h, 1, t, z, p, d, h->jnz)) return -1;
  int q = 0;
  double *sdata = h->sparse ? SUNSparseMatrix_Data(h->A) : 0;
  int *sptr = h->sparse ? SUNSparseMatrix_IndexPointers(h->A) : 0;
  int *sidx = h->sparse ? SUNSparseMatrix_IndexValues(h->A) : 0;
  memset(h->scale, 0, sizeof(double) * n);
  if (factor && !h->sparse) memset(h->M, 0, sizeof(double) * n * n);
  for (c = 0; c < h->n_var; ++c) {
    int f = h->col_of[c];
    double size = h->nominal[c] + fabs(z[c]);
    if (f < 0) continue;
    if (factor && h->sparse) sptr[f] = q;
    for (k = (int)colind[c]; k < (int)colind[c + 1]; ++k) {
      h->scale[row[k]] += fabs(h->jnz[k]) * size;
      if (factor && h->sparse) { sdata[q] = h->jnz[k]; sidx[q++] = (int)row[k]; }
      else if (factor) h->M[f * n + row[k]] = h->jnz[k];
    }
  }
  if (factor && h->sparse) sptr[n] = q;
  for (k = 0; k < n; ++k) if (!(h->scale[k] > 1e-300)) h->scale[k] = 1e-300;
  if (!factor) return 0;
  if (!h->sparse) {
    if (a2d_lu(h->M, n, h->piv)) return -1;
    a2d_lu_pattern(h->M, n, h->lp, h->li, h->up, h->ui);
    return 0;
  }
  for (k = 0; k < q; ++k) if (!isfinite(sdata[k])) return -1;
  h->set_up = 1;
  return SUNLinSolSetup(h->LS, h->A) ? -1 : 0;
}

/* Newton on one row with the current LU, from the z at which a2d_jacobian
 * left E(z) in h->e: iterations used, or -1 */
static int a2d_newton(a2d_proj *h, double t, double *z, const double *p, const double *d,
                      double tol, int max_iter) {
  int it, i, c, n = h->n_eq;
  for (it = 0; it <= max_iter; ++it) {
    int done = 1;
    if (it > 0 && a2d_eval(h, 0, t, z, p, d, h->e)) return -1;
    for (i = 0; i < n; ++i) {
      if (!isfinite(h->e[i])) return -1;
      if (fabs(h->e[i]) > tol * h->scale[i]) done = 0;
    }
    if (done) return it;
    if (it == max_iter) break;
    if (h->sparse) {
      memcpy(N_VGetArrayPointer(h->b), h->e, sizeof(double) * n);
      if (SUNLinSolSolve(h->LS, h->A, h->x, h->b, 0.0)) return -1;
      memcpy(h->e, N_VGetArrayPointer(h->x), sizeof(double) * n);
    } else {
      a2d_lu_solve(h->M, n, h->piv, h->lp, h->li, h->up, h->ui, h->e);
    }
    for (c = 0; c < h->n_var; ++c) if (h->col_of[c] >= 0) z[c] -= h->e[h->col_of[c]];
  }
  return -1;
}

static int a2d_sparse_setup(a2d_proj *h) {
  if (SUNContext_Create(0, &h->ctx)) return -1;
  SUNContext_ClearErrHandlers(h->ctx);
  h->x = N_VNew_Serial(h->n_eq, h->ctx);
  h->b = N_VNew_Serial(h->n_eq, h->ctx);
  h->A = SUNSparseMatrix(h->n_eq, h->n_eq, h->nnz > 0 ? h->nnz : 1, 0, h->ctx);
  if (!h->x || !h->b || !h->A) return -1;
  h->LS = SUNLinSol_SuperLUMT(h->x, h->A, 1, h->ctx);
  return (!h->LS || SUNLinSolInitialize(h->LS)) ? -1 : 0;
}

static void a2d_sparse_free(a2d_proj *h) {
  if (h->LS && h->set_up) SUNLinSolFree(h->LS);   /* SuperLU_MT crashes when freed unused */
  if (h->A) SUNMatDestroy(h->A);
  if (h->x) N_VDestroy(h->x);
  if (h->b) N_VDestroy(h->b);
  if (h->ctx) SUNContext_Free(&h->ctx);
}

int a2d_project(int m, const double *T, double *Z, const double *p, const double *d, int n_var,
                int n_eq, const int *col_of, const double *nominal, double tol, int max_iter,
                int sparse, const int *colind, const int *row, int *ok) {
  a2d_proj h;
  casadi_int sz_arg, sz_res, sz_iw, sz_w, a1, r1, i1, w1;
  int r, c, fresh = 0, have = 0, pred = 0, m_all = m;
  double *delta = (double *)calloc(n_var + 1, sizeof(double));
  E_work(&sz_arg, &sz_res, &sz_iw, &sz_w);
  EJ_work(&a1, &r1, &i1, &w1);
  if (a1 > sz_arg) sz_arg = a1;
  if (r1 > sz_res) sz_res = r1;
  if (i1 > sz_iw) sz_iw = i1;
  if (w1 > sz_w) sz_w = w1;
  memset(&h, 0, sizeof h);
  h.n_var = n_var; h.n_eq = n_eq; h.col_of = col_of; h.nominal = nominal;
  h.colind = colind; h.row = row;
  h.nnz = colind[n_var];
  h.sparse = sparse;
  h.jnz = (double *)malloc(sizeof(double) * (h.nnz + 1));
  h.M = (double *)malloc(sizeof(double) * ((sparse ? 0 : n_eq * n_eq) + 1));
  h.e = (double *)malloc(sizeof(double) * (n_eq + 1));
  h.scale = (double *)malloc(sizeof(double) * (n_eq + 1));
  h.z0 = (double *)malloc(sizeof(double) * (n_var + 1));
  h.piv = (int *)malloc(sizeof(int) * (n_eq + 1));
  h.lp = (int *)malloc(sizeof(int) * (n_eq + 1));
  h.up = (int *)malloc(sizeof(int) * (n_eq + 1));
  h.li = (int *)malloc(sizeof(int) * ((sparse ? 0 : n_eq * n_eq) + 1));
  h.ui = (int *)malloc(sizeof(int) * ((sparse ? 0 : n_eq * n_eq) + 1));
  h.arg = (const casadi_real **)calloc(sz_arg + 1, sizeof(casadi_real *));
  h.res = (casadi_real **)calloc(sz_res + 1, sizeof(casadi_real *));
  h.iw = (casadi_int *)calloc(sz_iw + 1, sizeof(casadi_int));
  h.w = (casadi_real *)calloc(sz_w + 1, sizeof(casadi_real));
  if (sparse && a2d_sparse_setup(&h)) m = 0;      /* every row left to the caller */
  for (r = 0; r < m; ++r) {
    double *z = Z + (size_t)r * n_var;
    int its = -1;
    memcpy(h.z0, z, sizeof(double) * n_var);
    ok[r] = 0;
    fresh = !have;
    if (pred) for (c = 0; c < n_var; ++c) z[c] += delta[c];   /* the last row's correction */
    if (a2d_jacobian(&h, T[r], z, p, d, fresh)) { have = 0; continue; }
    have = 1;
    its = a2d_newton(&h, T[r], z, p, d, tol, max_iter);
    if (its < 0 && !fresh) {      /* an LU of an earlier row: once more with this row's */
      memcpy(z, h.z0, sizeof(double) * n_var);
      if (a2d_jacobian(&h, T[r], z, p, d, 1)) { have = 0; memcpy(z, h.z0, sizeof(double) * n_var); continue; }
      fresh = 1;
      its = a2d_newton(&h, T[r], z, p, d, tol, max_iter);
    }
    if (its < 0) { memcpy(z, h.z0, sizeof(double) * n_var); have = 0; pred = 0; continue; }
    ok[r] = 1;
    for (c = 0; c < n_var; ++c) delta[c] = z[c] - h.z0[c];
    pred = 1;
    if (its > max_iter / 2) have = 0;   /* slow: a new LU at the next row (max_iter 6: after 3) */
  }
  if (sparse) a2d_sparse_free(&h);
  for (r = m; r < m_all; ++r) ok[r] = 0;
  free(delta);
  free(h.jnz); free(h.M); free(h.e); free(h.scale); free(h.z0); free(h.piv);
  free(h.lp); free(h.up); free(h.li); free(h.ui);
  free(h.arg); free(h.res); free(h.iw); free(h.w);
  return 0;
}
