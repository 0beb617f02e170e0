/* The small dense system of a Woodbury correction. A factorised A_ref and a change U S U' give

     (A_ref + U S U')^-1 b = y - Z w,   w = (I + S G)^-1 S U' y,   y = A_ref^-1 b,

   with Z = A_ref^-1 U and G = U' Z (m x m for m columns of U). Factorising I + S G costs
   2 m^3 / 3 at every change of S (two or three a step under friction). Where S is
   block-diagonal in symmetric 3 x 3 blocks (a node pair's penalty difference: nodal contact
   points), each block is S_i = Q_i L_i Q_i' with only its non-zero eigenvalues kept, and

     (I + S G)^-1 S = Q (L^-1 + Q' G Q)^-1 Q',

   a symmetric system of the blocks' rank r (about two thirds of m under friction: a pair that
   starts or stops slipping changes two tangential directions), factorised by Bunch-Kaufman
   (r^3 / 3), about a seventh of the general LU's flops. Other S (Gauss points couple the pairs of
   a face) keep the general form. Every rank factorises the same data alike, so the correction has
   the same bits on every rank. */
#include "private/sys.h"
#include <petscblaslapack.h>

/* An eigenvalue counts if it is above this fraction of its block's largest: the rest is the
   rounding of blocks that cancel (a tangential stiffness removed and put back). */
#define CAP_RANK_TOL 1e-13

struct _n_BoltCapacitance {
  PetscBool     blocks;  /* the symmetric block form is in force */
  PetscInt      m, r;    /* columns of U; rank kept (blocks) */
  PetscInt      mAlloc, lwork;
  PetscReal    *C;       /* m x m: I + S G (general), or r x r: L^-1 + Q' G Q, factorised */
  PetscReal    *Q;       /* blocks: 3 x 3 per block, column-major, its kept eigenvectors first */
  PetscInt     *rankOf;  /* blocks: the kept eigenvalues per block */
  PetscReal    *S;       /* general: m x m copy of S */
  PetscReal    *t, *work;
  PetscBLASInt *piv;
};

PetscErrorCode BoltCapacitanceCreate(BoltCapacitance **cap)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(cap));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltCapacitanceDestroy(BoltCapacitance **cap)
{
  PetscFunctionBeginUser;
  if (!*cap) PetscFunctionReturn(0);
  PetscCall(PetscFree4((*cap)->C, (*cap)->Q, (*cap)->rankOf, (*cap)->S));
  PetscCall(PetscFree3((*cap)->t, (*cap)->work, (*cap)->piv));
  PetscCall(PetscFree(*cap));
  PetscFunctionReturn(0);
}

static PetscErrorCode CapReserve(BoltCapacitance *cap, PetscInt m)
{
  PetscFunctionBeginUser;
  if (m <= cap->mAlloc) PetscFunctionReturn(0);
  cap->mAlloc = PetscMax(m, 2 * cap->mAlloc);
  PetscCall(PetscFree4(cap->C, cap->Q, cap->rankOf, cap->S));
  PetscCall(PetscFree3(cap->t, cap->work, cap->piv));
  cap->lwork = 64 * cap->mAlloc; /* Bunch-Kaufman's blocked work space: n times a block size */
  PetscCall(PetscMalloc4((size_t)cap->mAlloc * cap->mAlloc, &cap->C, 3 * cap->mAlloc, &cap->Q, cap->mAlloc / 3 + 1, &cap->rankOf, (size_t)cap->mAlloc * cap->mAlloc, &cap->S));
  PetscCall(PetscMalloc3(cap->mAlloc, &cap->t, cap->lwork, &cap->work, cap->mAlloc, &cap->piv));
  PetscFunctionReturn(0);
}

/* Whether S (m x m, leading dimension m) is block-diagonal in symmetric 3 x 3 blocks. */
static PetscBool CapIsSymmetricBlocks(PetscInt m, const PetscReal S[])
{
  if (m % 3) return PETSC_FALSE;
  for (PetscInt j = 0; j < m; j++)
    for (PetscInt i = 0; i < m; i++) {
      const PetscReal v = S[i + m * j];
      if (i / 3 != j / 3 ? v != 0 : v != S[j + m * i]) return PETSC_FALSE;
    }
  return PETSC_TRUE;
}

/* The eigenpairs of the blocks that Q holds on entry (the kept eigenvectors first in each
   block's columns), and L^-1 + Q' G Q. */
static PetscErrorCode CapFactorBlocks(BoltCapacitance *cap, const PetscReal G[], PetscInt ldG, const PetscInt idx[], PetscBool *ok)
{
  const PetscInt m = cap->m, k = m / 3;
  PetscReal     *inv;
  PetscBLASInt   three = 3, lw = 16, info, br;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m + 1, &inv));
  cap->r = 0;
  for (PetscInt b = 0; b < k; b++) {
    PetscReal *Qb = &cap->Q[9 * b], ev[3], w16[16], mx = 0;
    PetscInt   kept = 0;
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &three, Qb, &three, ev, w16, &lw, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev of a 3 x 3 block failed (%d)", (int)info);
    for (PetscInt l = 0; l < 3; l++) mx = PetscMax(mx, PetscAbsReal(ev[l]));
    for (PetscInt l = 0; l < 3; l++) { /* the kept eigenvectors to the front, in their order */
      if (!(PetscAbsReal(ev[l]) > CAP_RANK_TOL * mx)) continue;
      if (kept != l)
        for (PetscInt q = 0; q < 3; q++) Qb[q + 3 * kept] = Qb[q + 3 * l];
      inv[cap->r++] = 1.0 / ev[l];
      kept++;
    }
    cap->rankOf[b] = kept;
  }
  /* C = L^-1 + Q' G Q: first W = G Q (m x r, each block column of G times its Q_b), from G's
     rows and columns gathered in the columns' order, then Q_a' W row block by row block */
  for (PetscInt b = 0, cb = 0; b < k; cb += cap->rankOf[b++]) {
    const PetscReal *Qb = &cap->Q[9 * b];
    const PetscReal *g0 = &G[ldG * idx[3 * b]], *g1 = &G[ldG * idx[3 * b + 1]], *g2 = &G[ldG * idx[3 * b + 2]];
    for (PetscInt i = 0; i < m; i++) {
      const PetscInt  gi = idx[i];
      const PetscReal x0 = g0[gi], x1 = g1[gi], x2 = g2[gi];
      for (PetscInt j = 0; j < cap->rankOf[b]; j++) cap->S[i + m * (cb + j)] = x0 * Qb[3 * j] + x1 * Qb[3 * j + 1] + x2 * Qb[3 * j + 2];
    }
  }
  for (PetscInt j = 0; j < cap->r; j++) {
    const PetscReal *w = &cap->S[m * j];
    for (PetscInt a = 0, ca = 0; a < k; ca += cap->rankOf[a++])
      for (PetscInt i = 0; i < cap->rankOf[a]; i++) {
        const PetscReal *q = &cap->Q[9 * a + 3 * i];
        cap->C[ca + i + cap->r * j] = q[0] * w[3 * a] + q[1] * w[3 * a + 1] + q[2] * w[3 * a + 2];
      }
  }
  for (PetscInt i = 0; i < cap->r; i++) cap->C[i + cap->r * i] += inv[i];
  PetscCall(PetscFree(inv));
  *ok = PETSC_TRUE;
  if (!cap->r) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(cap->r, &br));
  PetscCall(PetscBLASIntCast(cap->lwork, &lw));
  PetscCallBLAS("LAPACKsytrf", LAPACKsytrf_("L", &br, cap->C, &br, cap->piv, cap->work, &lw, &info));
  if (info != 0) *ok = PETSC_FALSE; /* singular: A_ref + U S U' is */
  PetscFunctionReturn(0);
}

/* I + S G, S applied entry by entry (it is sparse: a pair couples with its faces' other pairs). */
static PetscErrorCode CapFactorGeneral(BoltCapacitance *cap, const PetscReal S[], const PetscReal G[], PetscInt ldG, const PetscInt idx[], PetscBool *ok)
{
  const PetscInt m = cap->m;
  PetscInt       nnz = 0, *start, *row;
  PetscReal     *val;
  PetscBLASInt   bm, info;

  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(cap->S, S, m * m));
  for (PetscInt i = 0; i < m * m; i++) nnz += S[i] != 0 ? 1 : 0;
  PetscCall(PetscMalloc3(m + 1, &start, nnz + 1, &row, nnz + 1, &val));
  nnz = 0;
  for (PetscInt l = 0; l < m; l++) { /* S's columns, their non-zeros */
    start[l] = nnz;
    for (PetscInt i = 0; i < m; i++)
      if (S[i + m * l] != 0) {
        row[nnz]   = i;
        val[nnz++] = S[i + m * l];
      }
  }
  start[m] = nnz;
  PetscCall(PetscArrayzero(cap->C, m * m));
  for (PetscInt j = 0; j < m; j++) {
    PetscReal *Cc = &cap->C[m * j];
    for (PetscInt l = 0; l < m; l++) {
      const PetscReal g = G[idx[l] + ldG * idx[j]];
      for (PetscInt z = start[l]; z < start[l + 1]; z++) Cc[row[z]] += val[z] * g;
    }
    Cc[j] += 1.0;
  }
  PetscCall(PetscFree3(start, row, val));
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bm, &bm, cap->C, &bm, cap->piv, &info));
  *ok = (PetscBool)(info == 0);
  PetscFunctionReturn(0);
}

/* The system of S (m x m, leading dimension m) and of G's rows and columns idx (G(i, j) =
   G[idx[i] + ldG idx[j]]); *ok is false where it is singular. */
PetscErrorCode BoltCapacitanceFactor(BoltCapacitance *cap, PetscInt m, const PetscReal S[], const PetscReal G[], PetscInt ldG, const PetscInt idx[], PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(CapReserve(cap, m));
  cap->m      = m;
  cap->blocks = CapIsSymmetricBlocks(m, S);
  if (cap->blocks) {
    for (PetscInt b = 0; b < m / 3; b++)
      for (PetscInt l = 0; l < 3; l++)
        for (PetscInt q = 0; q < 3; q++) cap->Q[9 * b + l + 3 * q] = S[3 * b + l + m * (3 * b + q)];
    PetscCall(CapFactorBlocks(cap, G, ldG, idx, ok));
  } else PetscCall(CapFactorGeneral(cap, S, G, ldG, idx, ok));
  PetscFunctionReturn(0);
}

/* The same, for an S known to be block-diagonal with symmetric 3 x 3 blocks B (k of them, 9
   values each, column-major). */
PetscErrorCode BoltCapacitanceFactorBlocks(BoltCapacitance *cap, PetscInt k, const PetscReal B[], const PetscReal G[], PetscInt ldG, const PetscInt idx[], PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(CapReserve(cap, 3 * k));
  cap->m      = 3 * k;
  cap->blocks = PETSC_TRUE;
  PetscCall(PetscArraycpy(cap->Q, B, 9 * k));
  PetscCall(CapFactorBlocks(cap, G, ldG, idx, ok));
  PetscFunctionReturn(0);
}

/* w = (I + S G)^-1 S t (m values each). */
PetscErrorCode BoltCapacitanceSolve(BoltCapacitance *cap, const PetscReal t[], PetscReal w[])
{
  const PetscInt m = cap->m;
  PetscBLASInt   bn, one = 1, info;

  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  if (!cap->blocks) {
    PetscReal    pone = 1, zero = 0;
    PetscBLASInt bm;
    PetscCall(PetscBLASIntCast(m, &bm));
    PetscCallBLAS("BLASgemv", BLASgemv_("N", &bm, &bm, &pone, cap->S, &bm, t, &one, &zero, w, &one));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bm, &one, cap->C, &bm, cap->piv, w, &bm, &info));
    PetscFunctionReturn(0);
  }
  for (PetscInt b = 0, c = 0; b < m / 3; c += cap->rankOf[b++]) /* Q' t */
    for (PetscInt j = 0; j < cap->rankOf[b]; j++) {
      const PetscReal *q = &cap->Q[9 * b + 3 * j];
      cap->t[c + j]      = q[0] * t[3 * b] + q[1] * t[3 * b + 1] + q[2] * t[3 * b + 2];
    }
  if (cap->r) {
    PetscCall(PetscBLASIntCast(cap->r, &bn));
    PetscCallBLAS("LAPACKsytrs", LAPACKsytrs_("L", &bn, &one, cap->C, &bn, cap->piv, cap->t, &bn, &info));
  }
  for (PetscInt b = 0, c = 0; b < m / 3; c += cap->rankOf[b++]) /* Q (...) */
    for (PetscInt l = 0; l < 3; l++) {
      PetscReal v = 0;
      for (PetscInt j = 0; j < cap->rankOf[b]; j++) v += cap->Q[9 * b + 3 * j + l] * cap->t[c + j];
      w[3 * b + l] = v;
    }
  PetscFunctionReturn(0);
}
