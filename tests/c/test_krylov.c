static char help[] = "Verification of the block second-order Krylov basis (boltrom_krylov.h) on small SPD\n"
                     "M, C, K (a 3D grid, 3 DOFs per node, varying coefficients, non-proportional damping):\n"
                     "orthonormality, moment matching at s0 (and mismatch of the next moment), deflation of\n"
                     "duplicated and zero inputs, same subspace on 1 rank and on all ranks.\n"
                     "Prints PASS/FAIL name value per check; exits non-zero if any check fails.\n"
                     "With -bench: only times BoltKrylovBuild on a larger grid (-bench_nodes per side, -bench_columns\n"
                     "unit inputs on the middle plane, -krylov_* options).\n";

#include "private/boltrom_krylov.h" /* petscsys.h must precede petscblaslapack.h */
#include <petscksp.h>
#include <petscblaslapack.h>

typedef struct {
  PetscInt  nx, ny, nz, dof; /* grid nodes per side, DOFs per node (1 or 3) */
  PetscBool lumped;          /* diagonal M: a pattern different from K's */
} Grid;

/* The reduced model V'MV, V'CV, V'KV, V'B, V'l (column-major, replicated on every rank) */
typedef struct {
  PetscInt     r, p;
  PetscScalar *M, *C, *K, *B, *l;
} Reduced;

static PetscInt npass = 0;

static PetscErrorCode Report(const char *name, PetscReal value, PetscBool ok, PetscInt *nfail)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s %.6e\n", ok ? "PASS" : "FAIL", name, (double)value));
  if (ok) npass++;
  else (*nfail)++;
  PetscFunctionReturn(0);
}

/* value < tol, written so that NaN fails */
static PetscErrorCode CheckBelow(const char *name, PetscReal value, PetscReal tol, PetscInt *nfail)
{
  PetscFunctionBeginUser;
  PetscCall(Report(name, value, (PetscBool)(value < tol), nfail));
  PetscFunctionReturn(0);
}

/* Deterministic value in [0, 1) from three integers (splitmix64), the same on any number of ranks */
static PetscErrorCode Hash(PetscInt a, PetscInt b, PetscInt c, PetscReal *h)
{
  unsigned long long x = (unsigned long long)a * 0x9E3779B97F4A7C15ULL + (unsigned long long)b * 0xBF58476D1CE4E5B9ULL + (unsigned long long)c * 0x94D049BB133111EBULL + 0x2545F4914F6CDD1DULL;

  PetscFunctionBeginUser;
  x  = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x  = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  x  = x ^ (x >> 31);
  *h = (PetscReal)(x >> 11) * (1.0 / 9007199254740992.0);
  PetscFunctionReturn(0);
}

/* K = kscale (L + D) (x) A: weighted 27-point graph Laplacian with a positive shift, A 3x3 SPD;
   M = node mass matrix (x) I3 (explicit zeros keep K's pattern), diagonally dominant, or lumped;
   C = alpha M + beta K + a random positive diagonal (non-proportional damping). All SPD. */
static PetscErrorCode CreateProblem(MPI_Comm comm, const Grid *g, Mat *M, Mat *C, Mat *K)
{
  const PetscReal A[3][3] = {
    {2.0, 0.5, 0.2},
    {0.5, 2.0, 0.3},
    {0.2, 0.3, 2.0}
  };
  const PetscReal kscale = 1e5, alpha = 5.0, beta = 1e-5, damp = 20.0;
  PetscInt        nn = g->nx * g->ny * g->nz, dof = g->dof, nloc = PETSC_DECIDE, nend, nstart, a, b, i, j, k, di, dj, dk, al, be, nc, row;
  PetscInt        cols[81];
  PetscScalar     kv[81], mv[81], cv[81];
  PetscReal       w, mw, sumw, summ, shift, mdiag, h, kd, md;
  Mat             mats[3];

  PetscFunctionBeginUser;
  PetscCall(PetscSplitOwnership(comm, &nloc, &nn));
  PetscCallMPI(MPI_Scan(&nloc, &nend, 1, MPIU_INT, MPI_SUM, comm));
  nstart = nend - nloc;
  for (i = 0; i < 3; i++) {
    PetscCall(MatCreate(comm, &mats[i]));
    PetscCall(MatSetSizes(mats[i], nloc * dof, nloc * dof, nn * dof, nn * dof));
    PetscCall(MatSetType(mats[i], MATAIJ));
    PetscCall(MatSeqAIJSetPreallocation(mats[i], 27 * dof, NULL));
    PetscCall(MatMPIAIJSetPreallocation(mats[i], 27 * dof, NULL, 27 * dof, NULL));
  }
  for (a = nstart; a < nend; a++) {
    i = a % g->nx;
    j = (a / g->nx) % g->ny;
    k = a / (g->nx * g->ny);
    for (al = 0; al < dof; al++) {
      row  = a * dof + al;
      nc   = 0;
      sumw = 0;
      summ = 0;
      for (dk = -1; dk <= 1; dk++)
        for (dj = -1; dj <= 1; dj++)
          for (di = -1; di <= 1; di++) {
            if (!di && !dj && !dk) continue;
            if (i + di < 0 || i + di >= g->nx || j + dj < 0 || j + dj >= g->ny || k + dk < 0 || k + dk >= g->nz) continue;
            b = a + di + g->nx * (dj + g->ny * dk);
            PetscCall(Hash(PetscMin(a, b), PetscMax(a, b), 1, &h));
            w = 0.5 + h;
            PetscCall(Hash(PetscMin(a, b), PetscMax(a, b), 2, &h));
            mw = 0.01 + 0.02 * h;
            sumw += w;
            summ += mw;
            for (be = 0; be < dof; be++) {
              cols[nc] = b * dof + be;
              kv[nc]   = -kscale * w * (dof == 3 ? A[al][be] : 1.0);
              mv[nc]   = (g->lumped || al != be) ? 0.0 : mw;
              cv[nc]   = alpha * mv[nc] + beta * kv[nc];
              nc++;
            }
          }
      PetscCall(Hash(a, 0, 3, &h));
      shift = 0.05 * (1 + h);
      PetscCall(Hash(a, 0, 4, &h));
      mdiag = 1.0 + 0.3 * h + (g->lumped ? summ : 0.0);
      for (be = 0; be < dof; be++) {
        cols[nc] = a * dof + be;
        kd       = kscale * (sumw + shift) * (dof == 3 ? A[al][be] : 1.0);
        md       = al == be ? mdiag : 0.0;
        PetscCall(Hash(row, 0, 5, &h));
        kv[nc] = kd;
        mv[nc] = md;
        cv[nc] = alpha * md + beta * kd + (al == be ? damp * h : 0.0);
        nc++;
      }
      PetscCall(MatSetValues(mats[2], 1, &row, nc, cols, kv, INSERT_VALUES));
      PetscCall(MatSetValues(mats[1], 1, &row, nc, cols, cv, INSERT_VALUES));
      if (g->lumped) PetscCall(MatSetValues(mats[0], 1, &row, 1, &row, &mdiag, INSERT_VALUES));
      else PetscCall(MatSetValues(mats[0], 1, &row, nc, cols, mv, INSERT_VALUES));
    }
  }
  for (i = 0; i < 3; i++) {
    PetscCall(MatAssemblyBegin(mats[i], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(mats[i], MAT_FINAL_ASSEMBLY));
    PetscCall(MatSetOption(mats[i], MAT_SYMMETRIC, PETSC_TRUE));
  }
  *M = mats[0];
  *C = mats[1];
  *K = mats[2];
  PetscFunctionReturn(0);
}

/* A random column: hash of the seed and the global row, the same on any number of ranks */
static PetscErrorCode FillColumn(Vec v, PetscInt seed)
{
  PetscInt     lo, hi, i;
  PetscScalar *x;
  PetscReal    h;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(v, &lo, &hi));
  PetscCall(VecGetArrayWrite(v, &x));
  for (i = lo; i < hi; i++) {
    PetscCall(Hash(seed, i, 7, &h));
    x[i - lo] = h - 0.5;
  }
  PetscCall(VecRestoreArrayWrite(v, &x));
  PetscFunctionReturn(0);
}

/* B with p columns; coef (p x nbase, row-major) combines nbase random base columns */
static PetscErrorCode CreateInputs(Mat K, PetscInt p, PetscInt nbase, const PetscReal *coef, BV *B, Vec *l)
{
  Vec      v, *base;
  PetscInt j, q;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(K, l, NULL));
  PetscCall(FillColumn(*l, 1000));
  PetscCall(BVCreate(PetscObjectComm((PetscObject)K), B));
  PetscCall(BVSetSizesFromVec(*B, *l, p));
  PetscCall(BVSetFromOptions(*B));
  PetscCall(VecDuplicateVecs(*l, nbase, &base));
  for (q = 0; q < nbase; q++) PetscCall(FillColumn(base[q], q));
  for (j = 0; j < p; j++) {
    PetscCall(BVGetColumn(*B, j, &v));
    PetscCall(VecZeroEntries(v));
    for (q = 0; q < nbase; q++)
      if (coef[j * nbase + q] != 0.0) PetscCall(VecAXPY(v, coef[j * nbase + q], base[q]));
    PetscCall(BVRestoreColumn(*B, j, &v));
  }
  PetscCall(VecDestroyVecs(nbase, &base));
  PetscFunctionReturn(0);
}

/* p independent random columns */
static PetscErrorCode CreateRandomInputs(Mat K, PetscInt p, BV *B, Vec *l)
{
  PetscReal *coef;
  PetscInt   j;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(p * p, &coef));
  for (j = 0; j < p; j++) coef[j * p + j] = 1.0;
  PetscCall(CreateInputs(K, p, p, coef, B, l));
  PetscCall(PetscFree(coef));
  PetscFunctionReturn(0);
}

static PetscErrorCode BuildBasis(MPI_Comm comm, PetscInt order, PetscInt blockSize, Mat M, Mat C, Mat K, BV B, BoltKrylov **kr, BV *V)
{
  PetscFunctionBeginUser;
  PetscCall(BoltKrylovCreate(comm, kr));
  PetscCall(BoltKrylovSetFromOptions(*kr));
  (*kr)->order     = order;
  (*kr)->blockSize = blockSize;
  PetscCall(BoltKrylovBuild(*kr, M, C, K, B, V));
  PetscFunctionReturn(0);
}

/* max |V'V - I| */
static PetscErrorCode OrthogonalityError(BV V, PetscReal *err)
{
  Mat                G;
  PetscInt           r, i, j, ld;
  const PetscScalar *g;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &r));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, r, r, NULL, &G));
  PetscCall(BVDot(V, V, G));
  PetscCall(MatDenseGetLDA(G, &ld));
  PetscCall(MatDenseGetArrayRead(G, &g));
  *err = 0;
  for (j = 0; j < r; j++)
    for (i = 0; i < r; i++) {
      PetscReal e = PetscAbsScalar(g[i + j * ld] - (i == j ? 1.0 : 0.0));
      if (!(e <= *err)) *err = e; /* NaN propagates */
    }
  PetscCall(MatDenseRestoreArrayRead(G, &g));
  PetscCall(MatDestroy(&G));
  PetscFunctionReturn(0);
}

static PetscErrorCode CopyDense(Mat A, PetscInt m, PetscInt n, PetscScalar **out)
{
  const PetscScalar *a;
  PetscInt           i, j, ld;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m * n, out));
  PetscCall(MatDenseGetLDA(A, &ld));
  PetscCall(MatDenseGetArrayRead(A, &a));
  for (j = 0; j < n; j++)
    for (i = 0; i < m; i++) (*out)[i + j * m] = a[i + j * ld];
  PetscCall(MatDenseRestoreArrayRead(A, &a));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReducedCreate(BV V, Mat M, Mat C, Mat K, BV B, Vec l, Reduced *rm)
{
  Mat      A;
  Mat      ops[3] = {M, C, K};
  PetscInt i;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &rm->r));
  PetscCall(BVGetSizes(B, NULL, NULL, &rm->p));
  for (i = 0; i < 3; i++) {
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, rm->r, rm->r, NULL, &A));
    PetscCall(BVMatProject(V, ops[i], V, A));
    PetscCall(CopyDense(A, rm->r, rm->r, i == 0 ? &rm->M : (i == 1 ? &rm->C : &rm->K)));
    PetscCall(MatDestroy(&A));
  }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, rm->r, rm->p, NULL, &A));
  PetscCall(BVDot(B, V, A));
  PetscCall(CopyDense(A, rm->r, rm->p, &rm->B));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscMalloc1(rm->r, &rm->l));
  PetscCall(BVDotVec(V, l, rm->l));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReducedDestroy(Reduced *rm)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(rm->M));
  PetscCall(PetscFree(rm->C));
  PetscCall(PetscFree(rm->K));
  PetscCall(PetscFree(rm->B));
  PetscCall(PetscFree(rm->l));
  PetscFunctionReturn(0);
}

/* y = a A x + y, A r x r column-major */
static PetscErrorCode DenseMultAdd(PetscInt r, PetscScalar a, const PetscScalar *A, const PetscScalar *x, PetscScalar *y)
{
  PetscInt i, j;

  PetscFunctionBeginUser;
  for (j = 0; j < r; j++)
    for (i = 0; i < r; i++) y[i] += a * A[i + j * r] * x[j];
  PetscFunctionReturn(0);
}

/* Derivatives d^k/ds^k of H(s) = l' G(s)^{-1} B at s, k = 0..nd-1, G = s^2 M + s C + K (reduced, dense):
   G X0 = B, G X1 = -G' X0, G X2 = -(2 G' X1 + G'' X0), G X3 = -(3 G' X2 + 3 G'' X1), G' = 2 s M + C, G'' = 2 M */
static PetscErrorCode ReducedDerivatives(const Reduced *rm, PetscReal s, PetscInt nd, PetscScalar *d)
{
  PetscInt      r = rm->r, i, j, k;
  PetscBLASInt  br, one = 1, info, *piv;
  PetscScalar  *G, *Gp, *X, *t;

  PetscFunctionBeginUser;
  PetscCheck(nd <= 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Up to the third derivative");
  PetscCall(PetscBLASIntCast(r, &br));
  PetscCall(PetscMalloc5(r * r, &G, r * r, &Gp, r * 4, &X, r, &t, r, &piv));
  for (i = 0; i < r * r; i++) {
    G[i]  = s * s * rm->M[i] + s * rm->C[i] + rm->K[i];
    Gp[i] = 2 * s * rm->M[i] + rm->C[i];
  }
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&br, &br, G, &br, piv, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "Reduced G(s) is singular (info %d)", (int)info);
  for (j = 0; j < rm->p; j++) {
    for (k = 0; k < nd; k++) {
      PetscCall(PetscArrayzero(t, r));
      if (k == 0) PetscCall(PetscArraycpy(t, rm->B + j * r, r));
      if (k >= 1) PetscCall(DenseMultAdd(r, -(PetscReal)k, Gp, X + (k - 1) * r, t));
      if (k >= 2) PetscCall(DenseMultAdd(r, -(PetscReal)(k * (k - 1)), rm->M, X + (k - 2) * r, t)); /* binomial(k,2) G'' = k(k-1) M */
      PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &br, &one, G, &br, piv, t, &br, &info));
      PetscCall(PetscArraycpy(X + k * r, t, r));
      d[k * rm->p + j] = 0;
      for (i = 0; i < r; i++) d[k * rm->p + j] += rm->l[i] * t[i];
    }
  }
  PetscCall(PetscFree5(G, Gp, X, t, piv));
  PetscFunctionReturn(0);
}

/* The same derivatives of the full model, with a MUMPS factorization of G(s) */
static PetscErrorCode FullDerivatives(Mat M, Mat C, Mat K, BV B, Vec l, PetscReal s, PetscInt nd, PetscScalar *d)
{
  Mat      G;
  KSP      ksp;
  PC       pc;
  Vec     *X, t, u;
  PetscInt p, j, k;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(B, NULL, NULL, &p));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &G));
  PetscCall(MatAXPY(G, s, C, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatAXPY(G, s * s, M, DIFFERENT_NONZERO_PATTERN));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)K), &ksp));
  PetscCall(KSPSetOperators(ksp, G, G));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(VecDuplicateVecs(l, 4, &X));
  PetscCall(VecDuplicate(l, &t));
  PetscCall(VecDuplicate(l, &u));
  for (j = 0; j < p; j++) {
    for (k = 0; k < nd; k++) {
      PetscCall(VecZeroEntries(t));
      if (k == 0) PetscCall(BVCopyVec(B, j, t));
      if (k >= 1) { /* t -= k G' X_{k-1} */
        PetscCall(MatMult(M, X[k - 1], u));
        PetscCall(VecScale(u, 2 * s));
        PetscCall(MatMultAdd(C, X[k - 1], u, u));
        PetscCall(VecAXPY(t, -(PetscReal)k, u));
      }
      if (k >= 2) { /* t -= k(k-1) M X_{k-2} */
        PetscCall(MatMult(M, X[k - 2], u));
        PetscCall(VecAXPY(t, -(PetscReal)(k * (k - 1)), u));
      }
      PetscCall(KSPSolve(ksp, t, X[k]));
      PetscCall(VecDot(X[k], l, &d[k * p + j]));
    }
  }
  PetscCall(VecDestroyVecs(4, &X));
  PetscCall(VecDestroy(&t));
  PetscCall(VecDestroy(&u));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&G));
  PetscFunctionReturn(0);
}

/* || a - b || / || b || over p values */
static PetscErrorCode RelativeDifference(PetscInt p, const PetscScalar *a, const PetscScalar *b, PetscReal *e)
{
  PetscReal num = 0, den = 0;
  PetscInt  j;

  PetscFunctionBeginUser;
  for (j = 0; j < p; j++) {
    num += PetscSqr(PetscAbsScalar(a[j] - b[j]));
    den += PetscSqr(PetscAbsScalar(b[j]));
  }
  *e = PetscSqrtReal(num / den);
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckOrthonormality(const Grid *g, PetscInt *nfail)
{
  const PetscInt orders[] = {1, 2, 3, 4, 8};
  Mat            M, C, K;
  BV             B, V;
  Vec            l;
  BoltKrylov    *kr;
  PetscReal      err;
  PetscInt       i, p = 10;
  char           name[64];

  PetscFunctionBeginUser;
  PetscCall(CreateProblem(PETSC_COMM_WORLD, g, &M, &C, &K));
  PetscCall(CreateRandomInputs(K, p, &B, &l));
  for (i = 0; i < 5; i++) {
    PetscCall(BuildBasis(PETSC_COMM_WORLD, orders[i], 4, M, C, K, B, &kr, &V)); /* block size 4: several blocks per order */
    PetscCall(OrthogonalityError(V, &err));
    PetscCall(PetscSNPrintf(name, sizeof(name), "orthonormality_order%" PetscInt_FMT, orders[i]));
    PetscCall(CheckBelow(name, err, 1e-12, nfail));
    PetscCall(PetscSNPrintf(name, sizeof(name), "rank_order%" PetscInt_FMT, orders[i]));
    PetscCall(Report(name, (PetscReal)kr->rank, (PetscBool)(kr->rank == p * orders[i]), nfail));
    PetscCall(BVDestroy(&V));
    PetscCall(BoltKrylovDestroy(&kr));
  }
  PetscCall(BVDestroy(&B));
  PetscCall(VecDestroy(&l));
  PetscCall(MatDestroy(&M));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

/* Derivatives 0..m-1 of l'G(s)^{-1}B at s0 match, derivative m does not (generic l, B) */
static PetscErrorCode CheckMoments(const Grid *g, const char *tag, PetscInt maxOrder, PetscInt *nfail)
{
  Mat          M, C, K;
  BV           B, V;
  Vec          l;
  BoltKrylov  *kr;
  Reduced      rm;
  PetscScalar  full[4 * 3], red[4 * 3];
  PetscReal    err;
  PetscInt     m, k, p = 3;
  char         name[64];

  PetscFunctionBeginUser;
  PetscCall(CreateProblem(PETSC_COMM_WORLD, g, &M, &C, &K));
  PetscCall(CreateRandomInputs(K, p, &B, &l));
  for (m = 1; m <= maxOrder; m++) {
    PetscCall(BuildBasis(PETSC_COMM_WORLD, m, 64, M, C, K, B, &kr, &V));
    PetscCall(FullDerivatives(M, C, K, B, l, kr->s0, m + 1, full));
    PetscCall(ReducedCreate(V, M, C, K, B, l, &rm));
    PetscCall(ReducedDerivatives(&rm, kr->s0, m + 1, red));
    for (k = 0; k <= m; k++) {
      PetscCall(RelativeDifference(p, red + k * p, full + k * p, &err));
      PetscCall(PetscSNPrintf(name, sizeof(name), "moments%s_order%" PetscInt_FMT "_deriv%" PetscInt_FMT "%s", tag, m, k, k < m ? "_match" : "_mismatch"));
      if (k < m) PetscCall(CheckBelow(name, err, 1e-8, nfail));
      else PetscCall(Report(name, err, (PetscBool)(err > 1e-6), nfail)); /* the test can fail */
    }
    PetscCall(ReducedDestroy(&rm));
    PetscCall(BVDestroy(&V));
    PetscCall(BoltKrylovDestroy(&kr));
  }
  PetscCall(BVDestroy(&B));
  PetscCall(VecDestroy(&l));
  PetscCall(MatDestroy(&M));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

/* Inputs with p columns combining nbase random ones (coef, p x nbase row-major), nindep of them
   numerically independent: rank nindep per block, orthonormal, no NaN */
static PetscErrorCode CheckDeflation(const Grid *g, const char *tag, PetscInt p, PetscInt nbase, const PetscReal *coef, PetscInt nindep, PetscInt *nfail)
{
  Mat         M, C, K;
  BV          B, V;
  Vec         l;
  BoltKrylov *kr;
  PetscReal   err;
  PetscInt    m, k;
  PetscBool   ok;
  char        name[64];

  PetscFunctionBeginUser;
  PetscCall(CreateProblem(PETSC_COMM_WORLD, g, &M, &C, &K));
  PetscCall(CreateInputs(K, p, nbase, coef, &B, &l));
  for (m = 1; m <= 4; m++) {
    PetscCall(BuildBasis(PETSC_COMM_WORLD, m, 2, M, C, K, B, &kr, &V)); /* block size 2: dependent columns in different blocks */
    ok = (PetscBool)(kr->rank == nindep * m);
    for (k = 0; k < m; k++) ok = (PetscBool)(ok && kr->rankPerOrder[k] == nindep);
    PetscCall(PetscSNPrintf(name, sizeof(name), "deflation%s_rank_order%" PetscInt_FMT, tag, m));
    PetscCall(Report(name, (PetscReal)kr->rank, ok, nfail));
    PetscCall(OrthogonalityError(V, &err));
    PetscCall(PetscSNPrintf(name, sizeof(name), "deflation%s_orthonormality_order%" PetscInt_FMT, tag, m));
    PetscCall(CheckBelow(name, err, 1e-12, nfail));
    PetscCall(BVDestroy(&V));
    PetscCall(BoltKrylovDestroy(&kr));
  }
  PetscCall(BVDestroy(&B));
  PetscCall(VecDestroy(&l));
  PetscCall(MatDestroy(&M));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

/* The basis built on all ranks and on one rank (redundantly on each) span the same subspace */
static PetscErrorCode CheckParallel(const Grid *g, PetscInt *nfail)
{
  const PetscReal freq[] = {0.3, 1.0, 2.0, 5.0};
  Mat             M[2], C[2], K[2], D;
  BV              B[2], V[2], Vg;
  Vec             l[2], vd, vs;
  VecScatter      sct;
  BoltKrylov     *kr[2];
  Reduced         rm[2];
  MPI_Comm        comms[2] = {PETSC_COMM_WORLD, PETSC_COMM_SELF};
  PetscScalar     h[2][3];
  PetscReal       err, maxerr = 0, dist;
  PetscInt        i, j, f, p = 3, order = 3;

  PetscFunctionBeginUser;
  for (i = 0; i < 2; i++) {
    PetscCall(CreateProblem(comms[i], g, &M[i], &C[i], &K[i]));
    PetscCall(CreateRandomInputs(K[i], p, &B[i], &l[i]));
    PetscCall(BuildBasis(comms[i], order, 2, M[i], C[i], K[i], B[i], &kr[i], &V[i]));
    PetscCall(ReducedCreate(V[i], M[i], C[i], K[i], B[i], l[i], &rm[i]));
  }
  PetscCall(Report("parallel_rank", (PetscReal)kr[0]->rank, (PetscBool)(kr[0]->rank == kr[1]->rank), nfail));
  /* reduced transfer function at real frequencies around s0 */
  for (f = 0; f < 4; f++) {
    for (i = 0; i < 2; i++) PetscCall(ReducedDerivatives(&rm[i], freq[f] * kr[i]->s0, 1, h[i]));
    PetscCall(RelativeDifference(p, h[0], h[1], &err));
    maxerr = PetscMax(maxerr, err);
    if (PetscIsInfOrNanReal(err)) maxerr = err;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &maxerr, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(CheckBelow("parallel_transfer_function", maxerr, 1e-10, nfail));
  /* || V_all - V_one V_one' V_all ||_F, V_all gathered on every rank */
  if (kr[0]->rank == kr[1]->rank) {
    PetscCall(BVDuplicate(V[1], &Vg));
    PetscCall(BVGetColumn(V[0], 0, &vd));
    PetscCall(VecScatterCreateToAll(vd, &sct, &vs));
    PetscCall(BVRestoreColumn(V[0], 0, &vd));
    for (j = 0; j < kr[0]->rank; j++) {
      PetscCall(BVGetColumn(V[0], j, &vd));
      PetscCall(VecScatterBegin(sct, vd, vs, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(sct, vd, vs, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(BVRestoreColumn(V[0], j, &vd));
      PetscCall(BVInsertVec(Vg, j, vs));
    }
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, kr[1]->rank, kr[1]->rank, NULL, &D));
    PetscCall(BVDot(Vg, V[1], D));
    PetscCall(BVMult(Vg, -1.0, 1.0, V[1], D));
    PetscCall(BVNorm(Vg, NORM_FROBENIUS, &dist));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dist, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(CheckBelow("parallel_subspace", dist, 1e-10, nfail));
    PetscCall(MatDestroy(&D));
    PetscCall(VecScatterDestroy(&sct));
    PetscCall(VecDestroy(&vs));
    PetscCall(BVDestroy(&Vg));
  }
  for (i = 0; i < 2; i++) {
    PetscCall(ReducedDestroy(&rm[i]));
    PetscCall(BVDestroy(&V[i]));
    PetscCall(BoltKrylovDestroy(&kr[i]));
    PetscCall(BVDestroy(&B[i]));
    PetscCall(VecDestroy(&l[i]));
    PetscCall(MatDestroy(&M[i]));
    PetscCall(MatDestroy(&C[i]));
    PetscCall(MatDestroy(&K[i]));
  }
  PetscFunctionReturn(0);
}

/* Options checked with a clear error */
static PetscErrorCode CheckOptions(PetscInt *nfail)
{
  BoltKrylov    *kr;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(BoltKrylovCreate(PETSC_COMM_WORLD, &kr));
  PetscCall(PetscOptionsSetValue(NULL, "-krylov_order", "9"));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = BoltKrylovSetFromOptions(kr);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClearValue(NULL, "-krylov_order"));
  PetscCall(Report("options_order_out_of_range_rejected", (PetscReal)ierr, (PetscBool)(ierr == PETSC_ERR_USER_INPUT), nfail));
  PetscCall(BoltKrylovDestroy(&kr));
  PetscFunctionReturn(0);
}

/* Timing: unit inputs on the DOFs of the middle plane, like contact DOFs */
static PetscErrorCode Bench(void)
{
  Grid        g = {20, 20, 20, 3, PETSC_FALSE};
  Mat         M, C, K;
  BV          B, V;
  Vec         v;
  BoltKrylov *kr;
  PetscInt    p = 1000, j, N, lo, hi, plane, row;
  PetscReal   err, t0, t1;

  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Krylov benchmark", "test_krylov");
  PetscCall(PetscOptionsInt("-bench_nodes", "Grid nodes per side (3 DOFs per node)", NULL, g.nx, &g.nx, NULL)); /* default 20 */
  PetscCall(PetscOptionsInt("-bench_columns", "Number of unit input columns", NULL, p, &p, NULL));               /* default 1000 */
  PetscOptionsEnd();
  g.ny = g.nz = g.nx;
  plane = g.nx * g.ny * g.dof;
  PetscCheck(p >= 1 && p <= plane, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-bench_columns must be in [1, %" PetscInt_FMT "] (the DOFs of one grid plane)", plane);
  PetscCall(CreateProblem(PETSC_COMM_WORLD, &g, &M, &C, &K));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(BVCreate(PETSC_COMM_WORLD, &B));
  PetscCall(MatCreateVecs(K, &v, NULL));
  PetscCall(BVSetSizesFromVec(B, v, p));
  PetscCall(BVSetFromOptions(B));
  PetscCall(VecDestroy(&v));
  for (j = 0; j < p; j++) {
    row = (g.nz / 2) * plane + j * (plane / p); /* spread over the plane */
    PetscCall(BVGetColumn(B, j, &v));
    PetscCall(VecZeroEntries(v));
    PetscCall(VecGetOwnershipRange(v, &lo, &hi));
    if (row >= lo && row < hi) PetscCall(VecSetValue(v, row, 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
    PetscCall(BVRestoreColumn(B, j, &v));
  }
  PetscCall(BoltKrylovCreate(PETSC_COMM_WORLD, &kr));
  PetscCall(BoltKrylovSetFromOptions(kr));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bench: N = %" PetscInt_FMT " DOFs, %" PetscInt_FMT " input columns\n", N, p));
  PetscCall(PetscTime(&t0));
  PetscCall(BoltKrylovBuild(kr, M, C, K, B, &V));
  PetscCall(PetscTime(&t1));
  PetscCall(BoltKrylovView(kr, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(OrthogonalityError(V, &err));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bench: BoltKrylovBuild %.3f s, max|V'V - I| = %.3e\n", (double)(t1 - t0), (double)err));
  PetscCall(BVDestroy(&V));
  PetscCall(BoltKrylovDestroy(&kr));
  PetscCall(BVDestroy(&B));
  PetscCall(MatDestroy(&M));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Grid      g = {6, 5, 7, 3, PETSC_FALSE}; /* 630 DOFs */
  Grid      lumped = {6, 5, 7, 3, PETSC_TRUE};
  /* [b1, b2, b1, 0, b3, b1 + b2, 2 b3]: duplicated, zero and dependent columns, 3 independent */
  PetscReal dupZero[7 * 3] = {1, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 2};
  /* [b1, b1 + 1e-7 b2, b1 + 1e-13 b3]: a strong cancellation kept, one below the tolerance dropped */
  PetscReal nearDup[3 * 3] = {1, 0, 0, 1, 1e-7, 0, 1, 0, 1e-13};
  PetscInt  nfail = 0;
  PetscBool bench = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(SlepcInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench", &bench, NULL));
  if (bench) PetscCall(Bench());
  else {
    PetscCall(CheckOrthonormality(&g, &nfail));
    PetscCall(CheckMoments(&g, "", 3, &nfail));
    PetscCall(CheckMoments(&lumped, "_lumped", 2, &nfail)); /* M's pattern differs from K's */
    PetscCall(CheckDeflation(&g, "", 7, 3, dupZero, 3, &nfail));
    PetscCall(CheckDeflation(&g, "_near", 3, 3, nearDup, 2, &nfail));
    PetscCall(CheckParallel(&g, &nfail));
    PetscCall(CheckOptions(&nfail));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_krylov: %" PetscInt_FMT " passed, %" PetscInt_FMT " failed\n", npass, nfail));
  }
  PetscCall(SlepcFinalize());
  return nfail > 0 ? 1 : 0;
}
