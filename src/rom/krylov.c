/* Block second-order Krylov subspace G_m(P, Q; r_0) (Bai & Su's SOAR, Lin & Bao's block form),
   built by a compact block Arnoldi (TOAR) on the linearisation

     L = [tau P, tau^2 Q; I, 0],   z = [x; y] -> [tau (P x + tau Q y); x],   z_0 = [r_0; 0].

   The tops of K_m(L, z_0) span G_m (tau only balances the two halves: it rescales r_l by tau^l).
   Every Arnoldi vector is kept as z = [U a; U b] with U the orthonormal N x r basis of G being built
   (the output V), so that <z_i, z_j> = a_i'a_j + b_i'b_j: the 2N-long basis is never stored, only
   the small coefficient vectors [a; b], orthonormalized redundantly on every rank.

   Orthogonalization is block classical Gram-Schmidt, twice (BCGS2): a block projection against U
   with BLAS3, column-wise CGS with refinement inside the block (where the deflation is decided),
   then both again unless no column lost more than 1/sqrt(2) of its norm. A column is dropped when
   its norm after orthogonalization is below deflationTol times its norm before. The same routine
   orthonormalizes the coefficient vectors. Only the last block needs no coefficients. */
#include "private/krylov.h"
#include "private/boltrom_krylov.h"
#include <petscksp.h>

PetscErrorCode BoltKrylovCreate(MPI_Comm comm, BoltKrylov **kr)
{
  BoltKrylov *k;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&k));
  k->comm         = comm;
  k->order        = 1;
  k->s0           = 2 * PETSC_PI * 100;
  k->blockSize    = 64;
  k->deflationTol = 1e-10;
  *kr             = k;
  PetscFunctionReturn(0);
}

static PetscErrorCode KrylovCheck(BoltKrylov *kr)
{
  PetscFunctionBeginUser;
  PetscCheck(kr->order >= 1 && kr->order <= BOLTKRYLOV_MAX_ORDER, kr->comm, PETSC_ERR_USER_INPUT, "-krylov_order must be between 1 and %d (got %" PetscInt_FMT "): it is the number of moments matched at s0", BOLTKRYLOV_MAX_ORDER, kr->order);
  PetscCheck(kr->s0 >= 0 && !PetscIsInfOrNanReal(kr->s0), kr->comm, PETSC_ERR_USER_INPUT, "-krylov_s0 must be a finite angular frequency >= 0 [rad/s] (got %g)", (double)kr->s0);
  PetscCheck(kr->blockSize >= 1, kr->comm, PETSC_ERR_USER_INPUT, "-krylov_block_size must be >= 1 (got %" PetscInt_FMT "); 32-128 right-hand sides per solve is efficient", kr->blockSize);
  PetscCheck(kr->deflationTol > 0 && kr->deflationTol < 1, kr->comm, PETSC_ERR_USER_INPUT, "-krylov_deflation_tol must be in (0, 1) (got %g); around 1e-10 keeps every direction above round-off", (double)kr->deflationTol);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltKrylovSetFromOptions(BoltKrylov *kr)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(kr->comm, NULL, "Block second-order Krylov reduction (SOAR)", "boltrom");
  PetscCall(PetscOptionsInt("-krylov_order", "Number of Krylov blocks r_0..r_{m-1}, i.e. moments matched at s0 (1..8)", NULL, kr->order, &kr->order, NULL));             /* default 1 */
  PetscCall(PetscOptionsReal("-krylov_s0", "Real expansion point [rad/s]", NULL, kr->s0, &kr->s0, NULL));                                                                /* default 2 pi 100 */
  PetscCall(PetscOptionsInt("-krylov_block_size", "Right-hand sides per MatMatSolve (and per orthogonalization block)", NULL, kr->blockSize, &kr->blockSize, NULL)); /* default 64 */
  PetscCall(PetscOptionsReal("-krylov_deflation_tol", "Relative norm after orthogonalization below which a new column is dropped", NULL, kr->deflationTol, &kr->deflationTol, NULL)); /* default 1e-10 */
  PetscOptionsEnd();
  PetscCall(KrylovCheck(kr));
  PetscFunctionReturn(0);
}

/* W <- (I - U U') W with U = columns 0..r-1, one block classical Gram-Schmidt pass (BLAS3) */
static PetscErrorCode KrylovProject(BV U, PetscInt r, BV W, Mat H)
{
  PetscFunctionBeginUser;
  PetscCall(BVSetActiveColumns(U, 0, r));
  PetscCall(BVDot(W, U, H));
  PetscCall(BVMult(W, -1.0, 1.0, U, H));
  PetscFunctionReturn(0);
}

/* Orthonormalize the nw columns of W against U(:, 0:r) and among themselves, dropping (deflating)
   those whose norm falls below tol times their norm on entry; append the kept ones to U.
   H: seq dense, at least r x nw; nrm0: work array of nw */
static PetscErrorCode KrylovAppend(BV U, PetscInt *r, BV W, PetscInt nw, PetscReal tol, Mat H, PetscReal *nrm0, PetscInt *nkept)
{
  PetscInt  j, k = 0;
  PetscReal nrm, minRatio = 1.0;
  Vec       w;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_KRYLOV_ORTH, 0, 0, 0, 0));
  PetscCall(BVSetActiveColumns(W, 0, nw));
  for (j = 0; j < nw; j++) {
    PetscCall(BVNormColumn(W, j, NORM_2, &nrm0[j]));
    PetscCheck(!PetscIsInfOrNanReal(nrm0[j]), PetscObjectComm((PetscObject)W), PETSC_ERR_FP, "Krylov column %" PetscInt_FMT " is Inf or NaN: Kt = K + s0 C + s0^2 M is (nearly) singular; change -krylov_s0 or check that the model is held", j);
  }
  if (*r > 0) PetscCall(KrylovProject(U, *r, W, H));
  for (j = 0; j < nw; j++) {
    if (j > k) PetscCall(BVCopyColumn(W, j, k));
    PetscCall(BVOrthogonalizeColumn(W, k, NULL, &nrm, NULL));
    if (nrm0[j] > 0 && nrm > tol * nrm0[j]) {
      PetscCall(BVScaleColumn(W, k, 1.0 / nrm));
      minRatio = PetscMin(minRatio, nrm / nrm0[j]);
      k++;
    }
  }
  /* Second pass: after a cancellation (nrm << nrm0) the kept columns still carry components along U
     of relative size eps nrm0/nrm, which one more projection removes; not needed if every kept
     column kept at least 1/sqrt(2) of its norm (the criterion of Daniel, Gragg, Kaufman, Stewart) */
  if (*r > 0 && k > 0 && minRatio < PETSC_SQRT2 / 2) {
    PetscCall(BVSetActiveColumns(W, 0, k));
    PetscCall(KrylovProject(U, *r, W, H));
    for (j = 0; j < k; j++) PetscCall(BVOrthonormalizeColumn(W, j, PETSC_FALSE, NULL, NULL));
  }
  for (j = 0; j < k; j++) {
    PetscCall(BVGetColumn(W, j, &w));
    PetscCall(BVInsertVec(U, *r + j, w));
    PetscCall(BVRestoreColumn(W, j, &w));
  }
  PetscCall(PetscInfo(W, "Krylov append: %" PetscInt_FMT " of %" PetscInt_FMT " columns kept, smallest kept norm ratio %g\n", k, nw, (double)minRatio));
  *r += k;
  if (nkept) *nkept = k;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_KRYLOV_ORTH, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Q (rows x nc) = rows [off, off + nrows) of the coefficient columns c..c+nc-1 of S (ld = ldS), zero below */
static PetscErrorCode KrylovCoefficientBlock(const PetscScalar *S, PetscInt ldS, PetscInt off, PetscInt nrows, PetscInt c, PetscInt nc, PetscInt rows, Mat *Q)
{
  PetscScalar *q;
  PetscInt     i, j, lda;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, rows, nc, NULL, Q));
  PetscCall(MatDenseGetLDA(*Q, &lda));
  PetscCall(MatDenseGetArrayWrite(*Q, &q));
  for (j = 0; j < nc; j++)
    for (i = 0; i < rows; i++) q[i + j * lda] = i < nrows ? S[off + i + (c + j) * ldS] : 0.0;
  PetscCall(MatDenseRestoreArrayWrite(*Q, &q));
  PetscFunctionReturn(0);
}

/* The local and global rows of M, C, K and B (which must agree) and B's columns. */
static PetscErrorCode KrylovSizes(Mat M, Mat C, Mat K, BV B, PetscInt *n, PetscInt *N, PetscInt *p)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)K);
  PetscInt nC, NC, nK, NK, nB, NB;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(M, N, NULL));
  PetscCall(MatGetLocalSize(M, n, NULL));
  PetscCall(MatGetSize(C, &NC, NULL));
  PetscCall(MatGetLocalSize(C, &nC, NULL));
  PetscCall(MatGetSize(K, &NK, NULL));
  PetscCall(MatGetLocalSize(K, &nK, NULL));
  PetscCheck(NC == *N && NK == *N && nC == *n && nK == *n, comm, PETSC_ERR_ARG_SIZ, "M, C and K must have the same size and row layout (global %" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ")", *N, NC, NK);
  PetscCall(BVGetSizes(B, &nB, &NB, p));
  PetscCheck(NB == *N && nB == *n, comm, PETSC_ERR_ARG_SIZ, "The input BV B must have the row layout of M, C, K (global %" PetscInt_FMT " rows, expected %" PetscInt_FMT ")", NB, *N);
  PetscCheck(*p >= 1, comm, PETSC_ERR_USER_INPUT, "The input BV B has no column: give at least one input vector");
  PetscFunctionReturn(0);
}

/* Balances the halves of L: tau ~ ||Q||^{-1/2} ~ the lowest |s0 + i omega| that r_0 excites,
   from the first basis vector. */
static PetscErrorCode KrylovScaling(BoltKrylov *kr, Mat F, Mat M, BV U, BV X, BV W1, BV W2, PetscReal *tau)
{
  PetscReal      qn;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(BVSetActiveColumns(U, 0, 1));
  PetscCall(BVSetActiveColumns(X, 0, 1));
  PetscCall(BVSetActiveColumns(W1, 0, 1));
  PetscCall(BVCopy(U, X));
  PetscCall(BVMatMult(X, M, W1));
  PetscCall(KrylovSolve(kr, F, W1, W2, 1));
  PetscCall(BVNormColumn(W2, 0, NORM_2, &qn));
  if (qn > 0 && !PetscIsInfOrNanReal(qn)) *tau = 1.0 / PetscSqrtReal(qn);
  PetscCall(PetscInfo(NULL, "Krylov: Arnoldi scaling tau = %g rad/s\n", (double)*tau));
  PetscCall(PetscTime(&t1));
  kr->tSolve += t1 - t0;
  PetscFunctionReturn(0);
}

/* The coefficient vectors' basis S (rowsS x colsS, sequential) with block 0's z_j = [u_j; 0],
   its work block Sc and projection matrix Hs. */
static PetscErrorCode KrylovCoefficientBasis(PetscInt r0, PetscInt rowsS, PetscInt colsS, PetscInt nbw, BV *S, BV *Sc, Mat *Hs)
{
  PetscScalar *sa;

  PetscFunctionBeginUser;
  PetscCall(BVCreate(PETSC_COMM_SELF, S));
  PetscCall(BVSetSizes(*S, rowsS, rowsS, colsS));
  PetscCall(BVSetType(*S, BVSVEC));
  PetscCall(BVSetOrthogonalization(*S, BV_ORTHOG_CGS, BV_ORTHOG_REFINE_IFNEEDED, PETSC_DEFAULT, BV_ORTHOG_BLOCK_GS));
  PetscCall(BoltBVTolerateCancellation(*S));
  PetscCall(BVDuplicateResize(*S, nbw, Sc));
  PetscCall(BoltBVTolerateCancellation(*Sc));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, colsS, nbw, NULL, Hs));
  PetscCall(BVGetArray(*S, &sa));
  PetscCall(PetscArrayzero(sa, rowsS * colsS));
  for (PetscInt j = 0; j < r0; j++) sa[j + j * rowsS] = 1.0;
  PetscCall(BVRestoreArray(*S, &sa));
  PetscFunctionReturn(0);
}

/* The new Arnoldi vectors [w; x] (tops w in X, x the previous block's c..c+nc) as coefficients
   [U' w; a] in S, orthonormalized among the previous ones (na counts them). */
static PetscErrorCode KrylovNewCoefficients(BoltKrylov *kr, BV U, PetscInt r, BV X, Mat H, BV S, BV Sc, Mat Hs, PetscInt rowsS, PetscInt capTop, PetscInt capBot, PetscInt k, PetscInt c, PetscInt nc, PetscReal nrm0[], PetscInt *na)
{
  PetscInt           ldH;
  PetscScalar       *sc;
  const PetscScalar *h, *sr;

  PetscFunctionBeginUser;
  PetscCall(BVSetActiveColumns(U, 0, r));
  PetscCall(BVDot(X, U, H));
  PetscCall(MatDenseGetLDA(H, &ldH));
  PetscCall(MatDenseGetArrayRead(H, &h));
  PetscCall(BVGetArrayRead(S, &sr));
  PetscCall(BVGetArray(Sc, &sc));
  PetscCall(PetscArrayzero(sc, rowsS * nc));
  for (PetscInt j = 0; j < nc; j++) {
    for (PetscInt i = 0; i < r; i++) sc[i + j * rowsS] = h[i + j * ldH];
    if (k == 1) sc[capTop + c + j + j * rowsS] = 1.0;
    else
      for (PetscInt i = 0; i < capBot; i++) sc[capTop + i + j * rowsS] = sr[i + (c + j) * rowsS];
  }
  PetscCall(BVRestoreArray(Sc, &sc));
  PetscCall(BVRestoreArrayRead(S, &sr));
  PetscCall(MatDenseRestoreArrayRead(H, &h));
  PetscCall(KrylovAppend(S, na, Sc, nc, kr->deflationTol, Hs, nrm0, NULL));
  PetscFunctionReturn(0);
}

/* Block 0: r_0 = -Kt^{-1} B (the sign does not change the span), nbw columns at a time, appended
   to U (r counts its columns). */
static PetscErrorCode KrylovBlockZero(BoltKrylov *kr, Mat F, BV B, PetscInt p, PetscInt nbw, BV U, BV W1, BV W2, Mat H, PetscReal nrm0[], PetscInt *r)
{
  Vec       v;
  PetscReal t0, t1;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < p; c += nbw) {
    const PetscInt nc = PetscMin(nbw, p - c);
    PetscCall(PetscTime(&t0));
    for (PetscInt j = 0; j < nc; j++) {
      PetscCall(BVGetColumn(W1, j, &v));
      PetscCall(BVCopyVec(B, c + j, v));
      PetscCall(BVRestoreColumn(W1, j, &v));
    }
    PetscCall(KrylovSolve(kr, F, W1, W2, nc));
    PetscCall(PetscTime(&t1));
    kr->tSolve += t1 - t0;
    PetscCall(KrylovAppend(U, r, W2, nc, kr->deflationTol, H, nrm0, NULL));
    PetscCall(PetscTime(&t0));
    kr->tOrth += t0 - t1;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltKrylovBuild(BoltKrylov *kr, Mat M, Mat C, Mat K, BV B, BV *V)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)K);
  Mat                Kt, F, H = NULL, Hs = NULL, Qt, Qb;
  KSP                ksp;
  BV                 U, X, Y, W1, W2, S = NULL, Sc = NULL;
  PetscBool          last;
  PetscInt           m = kr->order, n, N, p, nbw, r = 0, r0, capU, c, nc, k;
  PetscInt           capTop = 0, capBot = 0, rowsS = 0, na = 0, naBefore, rBefore, blkStart, blkEnd;
  PetscReal         *nrm0, tau = 1.0, s0 = kr->s0, t0, t1;
  const PetscScalar *sr;

  PetscFunctionBeginUser;
  PetscCall(KrylovCheck(kr));
  PetscCall(KrylovSizes(M, C, K, B, &n, &N, &p));
  PetscCall(PetscArrayzero(kr->rankPerOrder, BOLTKRYLOV_MAX_ORDER));
  kr->rank = 0;
  kr->nsolves = 0;
  kr->tFactor = kr->tSolve = kr->tOrth = 0;

  Kt = F = NULL;
  ksp = NULL;
  if (!kr->solve) PetscCall(KrylovFactor(kr, M, C, K, &Kt, &ksp, &F));

  /* U holds p columns for block 0, then r0 per block; work blocks of nbw columns */
  nbw = PetscMin(kr->blockSize, p);
  PetscCall(BVCreate(comm, &U));
  PetscCall(BVSetSizes(U, n, N, p));
  PetscCall(BVSetType(U, BVSVEC));
  PetscCall(BVSetOrthogonalization(U, BV_ORTHOG_CGS, BV_ORTHOG_REFINE_IFNEEDED, PETSC_DEFAULT, BV_ORTHOG_BLOCK_GS));
  PetscCall(BoltBVTolerateCancellation(U));
  PetscCall(BVDuplicateResize(U, nbw, &X));
  PetscCall(BVDuplicateResize(U, nbw, &Y));
  PetscCall(BVDuplicateResize(U, nbw, &W1));
  PetscCall(BVDuplicateResize(U, nbw, &W2));
  PetscCall(BoltBVTolerateCancellation(X));
  PetscCall(BoltBVTolerateCancellation(Y));
  PetscCall(BoltBVTolerateCancellation(W1));
  PetscCall(BoltBVTolerateCancellation(W2));
  PetscCall(PetscMalloc1(nbw, &nrm0));
  capU = p;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, capU, nbw, NULL, &H));

  PetscCall(KrylovBlockZero(kr, F, B, p, nbw, U, W1, W2, H, nrm0, &r));
  r0                  = r;
  kr->rankPerOrder[0] = r0;
  PetscCheck(r0 > 0, comm, PETSC_ERR_USER_INPUT, "Every column of the input B is zero (or below -krylov_deflation_tol): there is no input to reduce");

  if (m >= 2) {
    /* G_m has at most r0 new directions per block */
    if (r0 * m != capU) {
      capU = r0 * m;
      PetscCall(BVResize(U, capU, PETSC_TRUE));
      PetscCall(MatDestroy(&H));
      PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, capU, nbw, NULL, &H));
    }
    nbw = PetscMin(nbw, r0);
  }
  if (m >= 3) {
    PetscCall(KrylovScaling(kr, F, M, U, X, W1, W2, &tau));

    /* Arnoldi vectors of blocks 0..m-2 as coefficients: tops in U(:, 0:capTop), bottoms in U(:, 0:capBot) */
    capTop = r0 * (m - 1);
    capBot = r0 * (m - 2);
    rowsS  = capTop + capBot;
    PetscCall(KrylovCoefficientBasis(r0, rowsS, r0 * (m - 1), nbw, &S, &Sc, &Hs));
    na = r0;
  }

  /* Blocks 1..m-1: tops of L z for the Arnoldi vectors z of the previous block */
  blkStart = 0;
  blkEnd   = r0;
  for (k = 1; k < m; k++) {
    last     = (PetscBool)(k == m - 1);
    rBefore  = r;
    naBefore = na;
    for (c = blkStart; c < blkEnd; c += nbw) {
      nc = PetscMin(nbw, blkEnd - c);
      PetscCall(PetscTime(&t0));
      PetscCall(BVSetActiveColumns(X, 0, nc));
      PetscCall(BVSetActiveColumns(Y, 0, nc));
      PetscCall(BVSetActiveColumns(W1, 0, nc));
      PetscCall(BVSetActiveColumns(W2, 0, nc));
      if (k == 1) { /* z = [u_c; 0] */
        PetscCall(BVSetActiveColumns(U, c, c + nc));
        PetscCall(BVCopy(U, X));
        PetscCall(BVCopy(X, Y));
        PetscCall(BVScale(Y, 2 * s0));
      } else { /* z = [U a; U b] */
        PetscCall(BVGetArrayRead(S, &sr));
        PetscCall(KrylovCoefficientBlock(sr, rowsS, 0, PetscMin(rBefore, capTop), c, nc, rBefore, &Qt));
        PetscCall(KrylovCoefficientBlock(sr, rowsS, capTop, PetscMin(rBefore, capBot), c, nc, rBefore, &Qb));
        PetscCall(BVRestoreArrayRead(S, &sr));
        PetscCall(BVSetActiveColumns(U, 0, rBefore));
        PetscCall(BVMult(X, 1.0, 0.0, U, Qt));
        PetscCall(BVMult(Y, 1.0, 0.0, U, Qb));
        PetscCall(MatDestroy(&Qt));
        PetscCall(MatDestroy(&Qb));
        PetscCall(BVScale(Y, tau));
        PetscCall(BVMult(Y, 2 * s0, 1.0, X, NULL));
      }
      /* top of L z = -tau Kt^{-1} (C x + M (2 s0 x + tau y)) = tau (P x + tau Q y) */
      PetscCall(BVMatMult(X, C, W1));
      PetscCall(BVMatMult(Y, M, W2));
      PetscCall(BVMult(W1, -tau, -tau, W2, NULL));
      PetscCall(KrylovSolve(kr, F, W1, W2, nc));
      PetscCall(PetscTime(&t1));
      kr->tSolve += t1 - t0;
      if (!last) PetscCall(BVCopy(W2, X)); /* keep the tops w for their coefficients */
      PetscCall(KrylovAppend(U, &r, W2, nc, kr->deflationTol, H, nrm0, NULL));
      if (!last) {
        PetscCall(KrylovNewCoefficients(kr, U, r, X, H, S, Sc, Hs, rowsS, capTop, capBot, k, c, nc, nrm0, &na));
      }
      PetscCall(PetscTime(&t0));
      kr->tOrth += t0 - t1;
    }
    kr->rankPerOrder[k] = r - rBefore;
    blkStart            = naBefore;
    blkEnd              = na;
    if (!last && blkEnd == blkStart) break; /* the Krylov space is invariant: no further directions */
  }

  if (r < capU) PetscCall(BVResize(U, r, PETSC_TRUE));
  PetscCall(BVSetActiveColumns(U, 0, r));
  PetscCall(PetscObjectSetName((PetscObject)U, "V"));
  kr->rank = r;
  *V       = U;

  PetscCall(PetscFree(nrm0));
  PetscCall(MatDestroy(&H));
  PetscCall(MatDestroy(&Hs));
  PetscCall(BVDestroy(&S));
  PetscCall(BVDestroy(&Sc));
  PetscCall(BVDestroy(&X));
  PetscCall(BVDestroy(&Y));
  PetscCall(BVDestroy(&W1));
  PetscCall(BVDestroy(&W2));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&Kt));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltKrylovView(BoltKrylov *kr, PetscViewer viewer)
{
  PetscBool iascii;
  PetscInt  k;

  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(kr->comm);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "Krylov (block SOAR): order %" PetscInt_FMT ", s0 %g rad/s (%g Hz), block size %" PetscInt_FMT ", deflation tol %g\n", kr->order, (double)kr->s0, (double)(kr->s0 / (2 * PETSC_PI)), kr->blockSize, (double)kr->deflationTol));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  rank %" PetscInt_FMT " =", kr->rank));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE));
  for (k = 0; k < kr->order; k++) PetscCall(PetscViewerASCIIPrintf(viewer, "%s %" PetscInt_FMT, k ? " +" : "", kr->rankPerOrder[k]));
  PetscCall(PetscViewerASCIIPrintf(viewer, " (columns kept per block)\n"));
  PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " solves; time: factor %.3f s, solve %.3f s, orthogonalization %.3f s\n", kr->nsolves, (double)kr->tFactor, (double)kr->tSolve, (double)kr->tOrth));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltKrylovDestroy(BoltKrylov **kr)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*kr));
  PetscFunctionReturn(0);
}
