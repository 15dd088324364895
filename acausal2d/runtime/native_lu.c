/* Sparse LU of IDA's iteration matrix for acausal2d's native driver (the
 * "sparse-lu" solver of native.py; placed before native_driver.c in the
 * generated source, or built alone for tests/test_native_lu.py).
 *
 * Left-looking (Gilbert-Peierls, as CSparse's cs_lu): column k of P A Q is
 * x = L \ A(:, q[k]), its pattern the reach of A(:, q[k])'s rows in the graph
 * of L (depth-first search), so each column costs its flops, not n.  The
 * pivot is the column's preferred row (the row matched to the column, so the
 * "diagonal" of the symmetric fill-reducing order q computed in Python,
 * ordering.py) when its magnitude is at least A2D_LU_TOL times the largest
 * candidate, else the largest (threshold partial pivoting as KLU's; 0.1, not
 * KLU's 1e-3: on random 300 x 300 matrices with shuffled rows 1e-3 gave
 * solutions off by up to 3.7e-9 relative, 0.1 by 3.4e-14, for 5 % more
 * fill).  A refactorization reuses the pivot sequence and the patterns of L
 * and U of the last full factorization (KLU's refactor) and gives up (the
 * caller factors afresh) where a pivot falls below A2D_LU_RETOL times its
 * column, so a stale pivot order never costs accuracy.  Measured on the
 * compressor (217 unknowns, 664 nonzeros, L + U 1230; perf of five
 * simulates in one process): solves 8.4 % of the samples, full
 * factorizations 3.1 %, refactorizations 2.0 % (78 % of the setups
 * refactor) - SuperLU_MT took 29 %.  Refactor pays a little: warm simulate
 * 0.90-0.95 s with it, 0.94-0.96 s without.  Matrices are compressed sparse
 * columns, 0-based int.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The generated code around it is compiled at -O1 (native.py); this file at
 * -O2 where gcc builds it: the chain of 20 links' IDA alone took 0.0433 s
 * instead of 0.0549 s (median of 7, benchmarks/bench_floor.py's run). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("O2")
#endif

#ifndef A2D_LU_TOL
#define A2D_LU_TOL 0.1
#endif
#ifndef A2D_LU_RETOL
#define A2D_LU_RETOL 0.1
#endif

typedef struct {
  int n, lmax, umax, nnz;
  int *q, *prefer;            /* column order; preferred pivot row of each column (or -1) */
  int *lp, *li, *up, *ui;     /* L: unit diagonal first in each column; U: diagonal last */
  double *lx, *ux;            /* rows of L and U are pivot indices (after a factorization) */
  int *pinv, *prow;           /* row -> pivot index, pivot index -> row */
  int *ap, *ai;               /* the pattern of the last full factorization */
  double *x;                  /* dense work, zero between columns */
  int *xi, *mark, stamp;      /* reach (2n: stack and pattern), visit marks */
  int valid;                  /* a factorization to refactor and solve with */
  long full, refactored;      /* counts */
} a2d_splu;

void a2d_splu_free(a2d_splu *f) {
  if (!f) return;
  free(f->q); free(f->prefer); free(f->lp); free(f->li); free(f->up); free(f->ui);
  free(f->lx); free(f->ux); free(f->pinv); free(f->prow); free(f->ap); free(f->ai);
  free(f->x); free(f->xi); free(f->mark);
  free(f);
}

/* A factorization object for n x n matrices of nnz nonzeros, factored in
 * the column order q with the preferred pivot rows prefer (copied). */
a2d_splu *a2d_splu_new(int n, int nnz, const int *q, const int *prefer) {
  a2d_splu *f = (a2d_splu *)calloc(1, sizeof(a2d_splu));
  if (!f) return 0;
  f->n = n; f->nnz = nnz;
  f->lmax = f->umax = 4 * nnz + n;
  f->q = (int *)malloc(sizeof(int) * n); f->prefer = (int *)malloc(sizeof(int) * n);
  f->lp = (int *)malloc(sizeof(int) * (n + 1)); f->up = (int *)malloc(sizeof(int) * (n + 1));
  f->li = (int *)malloc(sizeof(int) * f->lmax); f->ui = (int *)malloc(sizeof(int) * f->umax);
  f->lx = (double *)malloc(sizeof(double) * f->lmax);
  f->ux = (double *)malloc(sizeof(double) * f->umax);
  f->pinv = (int *)malloc(sizeof(int) * n); f->prow = (int *)malloc(sizeof(int) * n);
  f->ap = (int *)malloc(sizeof(int) * (n + 1)); f->ai = (int *)malloc(sizeof(int) * (nnz + 1));
  f->x = (double *)calloc(n, sizeof(double)); f->xi = (int *)malloc(sizeof(int) * 2 * n);
  f->mark = (int *)calloc(n, sizeof(int));
  if (!f->q || !f->prefer || !f->lp || !f->up || !f->li || !f->ui || !f->lx || !f->ux ||
      !f->pinv || !f->prow || !f->ap || !f->ai || !f->x || !f->xi || !f->mark) {
    a2d_splu_free(f);
    return 0;
  }
  memcpy(f->q, q, sizeof(int) * n);
  memcpy(f->prefer, prefer, sizeof(int) * n);
  return f;
}

/* Room for `need` more entries of L (which 0) or U (1); 0 on success. */
static int lu_grow(a2d_splu *f, int which, int need) {
  int *cap = which ? &f->umax : &f->lmax, size = *cap;
  int **idx = which ? &f->ui : &f->li;
  double **val = which ? &f->ux : &f->lx, *v;
  int *i;
  if (need <= size) return 0;
  while (size < need) size *= 2;
  i = (int *)realloc(*idx, sizeof(int) * size);
  if (!i) return -1;
  *idx = i;
  v = (double *)realloc(*val, sizeof(double) * size);
  if (!v) return -1;
  *val = v;
  *cap = size;
  return 0;
}

/* Depth-first search from row j in the graph of L (row -> the column it
 * pivots, that column's rows): the rows reached are pushed below `top` in
 * xi in topological order; returns the new top (cs_dfs without recursion). */
static int lu_dfs(a2d_splu *f, int j, int top) {
  int *xi = f->xi, *stack = f->xi + f->n, head = 0, p, col, end, done;
  xi[0] = j;
  while (head >= 0) {
    j = xi[head];
    col = f->pinv[j];
    if (f->mark[j] != f->stamp) {
      f->mark[j] = f->stamp;
      stack[head] = col < 0 ? 0 : f->lp[col] + 1;
    }
    done = 1;
    end = col < 0 ? 0 : f->lp[col + 1];
    for (p = stack[head]; p < end; ++p) {
      if (f->mark[f->li[p]] == f->stamp) continue;
      stack[head] = p + 1;
      xi[++head] = f->li[p];
      done = 0;
      break;
    }
    if (done) { head--; xi[--top] = j; }
  }
  return top;
}

/* x = L \ A(:, c) on the reach of column c; returns top (the reach is xi[top..n)). */
static int lu_column(a2d_splu *f, const int *ap, const int *ai, const double *ax, int c) {
  int p, px, top = f->n, j, col;
  if (++f->stamp == 0x7fffffff) { memset(f->mark, 0, sizeof(int) * f->n); f->stamp = 1; }
  for (p = ap[c]; p < ap[c + 1]; ++p)
    if (f->mark[ai[p]] != f->stamp) top = lu_dfs(f, ai[p], top);
  for (p = ap[c]; p < ap[c + 1]; ++p) f->x[ai[p]] += ax[p];
  for (px = top; px < f->n; ++px) {
    j = f->xi[px];
    col = f->pinv[j];
    if (col < 0) continue;
    for (p = f->lp[col] + 1; p < f->lp[col + 1]; ++p) f->x[f->li[p]] -= f->lx[p] * f->x[j];
  }
  return top;
}

/* The pivot row of the reach xi[top..n): the preferred row if it is within
 * the threshold of the largest candidate, else the largest; -1 if none is
 * nonzero and finite (a singular column). */
static int lu_pivot(a2d_splu *f, int top, int preferred) {
  int px, i, best = -1;
  double big = 0.0, t;
  for (px = top; px < f->n; ++px) {
    i = f->xi[px];
    if (f->pinv[i] >= 0) continue;
    t = fabs(f->x[i]);
    if (t > big) { big = t; best = i; }
  }
  if (best < 0 || !isfinite(big)) return -1;
  if (preferred >= 0 && f->pinv[preferred] < 0 && fabs(f->x[preferred]) >= A2D_LU_TOL * big)
    return preferred;
  return best;
}

/* Column k of L and U from the reach and the pivot row ipiv; clears x. */
static void lu_store(a2d_splu *f, int k, int top, int ipiv) {
  int px, i, lnz = f->lp[k], unz = f->up[k];
  double pivot = f->x[ipiv];
  f->li[lnz] = ipiv; f->lx[lnz++] = 1.0;
  for (px = top; px < f->n; ++px) {
    i = f->xi[px];
    if (f->pinv[i] < 0) {
      if (i != ipiv) { f->li[lnz] = i; f->lx[lnz++] = f->x[i] / pivot; }
    } else {
      f->ui[unz] = f->pinv[i]; f->ux[unz++] = f->x[i];
    }
    f->x[i] = 0.0;
  }
  f->ui[unz] = k; f->ux[unz++] = pivot;
  f->pinv[ipiv] = k; f->prow[k] = ipiv;
  f->lp[k + 1] = lnz; f->up[k + 1] = unz;
}

static void lu_clear(a2d_splu *f, int top) {
  for (; top < f->n; ++top) f->x[f->xi[top]] = 0.0;
}

/* Full factorization with pivoting of the matrix (ap, ai, ax): 0, or k + 1
 * for a singular column k, or -1 out of memory. */
int a2d_splu_factor(a2d_splu *f, const int *ap, const int *ai, const double *ax) {
  int k, p, top, ipiv, n = f->n;
  f->valid = 0;
  if (ap[n] > f->nnz) return -1;
  for (k = 0; k < n; ++k) f->pinv[k] = -1;
  f->lp[0] = f->up[0] = 0;
  for (k = 0; k < n; ++k) {
    if (lu_grow(f, 0, f->lp[k] + n) || lu_grow(f, 1, f->up[k] + n)) return -1;
    top = lu_column(f, ap, ai, ax, f->q[k]);
    ipiv = lu_pivot(f, top, f->prefer[f->q[k]]);
    if (ipiv < 0) { lu_clear(f, top); return k + 1; }
    lu_store(f, k, top, ipiv);
  }
  for (p = 0; p < f->lp[n]; ++p) f->li[p] = f->pinv[f->li[p]];
  memcpy(f->ap, ap, sizeof(int) * (n + 1));
  memcpy(f->ai, ai, sizeof(int) * ap[n]);
  f->valid = 1;
  f->full++;
  return 0;
}

/* Column k of a refactorization (x indexed by pivot): 0, or 1 where the
 * pivot is below the threshold of its column (x is cleared either way). */
static int lu_recolumn(a2d_splu *f, int k) {
  int p, pp, j, end = f->up[k + 1] - 1;
  double xj, pivot, big = 0.0;
  for (p = f->up[k]; p < end; ++p) {
    j = f->ui[p];
    xj = f->x[j];
    f->ux[p] = xj;
    f->x[j] = 0.0;
    for (pp = f->lp[j] + 1; pp < f->lp[j + 1]; ++pp) f->x[f->li[pp]] -= f->lx[pp] * xj;
  }
  pivot = f->x[k];
  f->x[k] = 0.0;
  f->ux[end] = pivot;
  for (pp = f->lp[k] + 1; pp < f->lp[k + 1]; ++pp)
    if (fabs(f->x[f->li[pp]]) > big) big = fabs(f->x[f->li[pp]]);
  if (!(fabs(pivot) > 0.0 && fabs(pivot) >= A2D_LU_RETOL * big && isfinite(big))) {
    for (pp = f->lp[k] + 1; pp < f->lp[k + 1]; ++pp) f->x[f->li[pp]] = 0.0;
    return 1;
  }
  for (pp = f->lp[k] + 1; pp < f->lp[k + 1]; ++pp) {
    f->lx[pp] = f->x[f->li[pp]] / pivot;
    f->x[f->li[pp]] = 0.0;
  }
  return 0;
}

/* New values on the pattern of the last full factorization with its pivot
 * order: 0, or 1 (no factorization to reuse, another pattern, or a pivot
 * too small: the caller factors afresh with a2d_splu_factor). */
int a2d_splu_refactor(a2d_splu *f, const int *ap, const int *ai, const double *ax) {
  int k, p, c, n = f->n;
  if (!f->valid || memcmp(ap, f->ap, sizeof(int) * (n + 1)) ||
      memcmp(ai, f->ai, sizeof(int) * ap[n]))
    return 1;
  for (k = 0; k < n; ++k) {
    c = f->q[k];
    for (p = ap[c]; p < ap[c + 1]; ++p) f->x[f->pinv[ai[p]]] += ax[p];
    if (lu_recolumn(f, k)) { f->valid = 0; return 1; }
  }
  f->refactored++;
  return 0;
}

/* x := A^-1 b with the factorization (x may be b; work w: n doubles); -1
 * without one. */
int a2d_splu_solve(const a2d_splu *f, const double *b, double *x, double *w) {
  int k, p, n = f->n;
  double t;
  if (!f->valid) return -1;
  for (k = 0; k < n; ++k) w[k] = b[f->prow[k]];
  for (k = 0; k < n; ++k) {
    t = w[k];
    for (p = f->lp[k] + 1; p < f->lp[k + 1]; ++p) w[f->li[p]] -= f->lx[p] * t;
  }
  for (k = n - 1; k >= 0; --k) {
    t = w[k] /= f->ux[f->up[k + 1] - 1];
    for (p = f->up[k]; p < f->up[k + 1] - 1; ++p) w[f->ui[p]] -= f->ux[p] * t;
  }
  for (k = 0; k < n; ++k) x[f->q[k]] = w[k];
  return 0;
}

/* Nonzeros of L and U (for the space report and the tests). */
long a2d_splu_nnz(const a2d_splu *f) {
  return f->valid ? (long)f->lp[f->n] + f->up[f->n] : 0;
}

/* For tests: number of full factorizations (which 0) or refactorizations (1). */
long a2d_splu_count(const a2d_splu *f, int which) { return which ? f->refactored : f->full; }

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
