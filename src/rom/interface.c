/* Interface reduction of the contact surfaces (CCM + JIM) and the bordered solve of the
   interface-reduced model.

   Interface I = every contact DOF, interior G = the other free DOFs. The constraint modes are
   taken at the expansion point, Psi = [-Kt_GG^-1 Kt_GI; I] with Kt = K + s0 C + s0^2 M, so that
   the condensed Kt^ = Psi' Kt Psi is the Schur complement S_t and Kt^-1 Psi' y = (Kt^-1 y)_I:
   one solve with the full factorisation. On the condensed operators a single-input
   second-order Krylov space is built twice (Arnoldi on the linearisation): CCM with input ones
   on all interface DOFs, JIM with +1 on side a and -1 on side b (forces in equilibrium).
   V_IR = orth([V_CCM V_JIM]); T = blockdiag(I, V_IR). The block Krylov basis of the T-projected
   model is then built with the bordered solve y -> T (T' Kt T)^-1 T' y (interior solves and the
   small Schur complement V_IR' S_t V_IR), so T' Kt T is never formed. */
#include "private/rom.h"
#include "private/boltrom_interface.h"

static PetscErrorCode IRFullSolve(BoltInterface *ir, Vec b, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(ir->kspFull, b, x));
  ir->nFullSolves++;
  PetscFunctionReturn(0);
}

static PetscErrorCode IRInteriorSolve(BoltInterface *ir, Vec b, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(ir->kspGG, b, x));
  ir->nInteriorSolves++;
  PetscFunctionReturn(0);
}

/* u = Psi x = [-Kt_GG^-1 Kt_GI x; x] */
static PetscErrorCode IRLift(BoltInterface *ir, Vec xI, Vec u)
{
  PetscFunctionBeginUser;
  PetscCall(MatMult(ir->KtGI, xI, ir->gA));
  PetscCall(IRInteriorSolve(ir, ir->gA, ir->gB));
  PetscCall(VecScale(ir->gB, -1.0));
  PetscCall(VecISCopy(u, ir->isG, SCATTER_FORWARD, ir->gB));
  PetscCall(VecISCopy(u, ir->isI, SCATTER_FORWARD, xI));
  PetscFunctionReturn(0);
}

static PetscErrorCode IRFactor(BoltInterface *ir, Mat A, const char prefix[], KSP *ksp)
{
  PCFailedReason reason;

  PetscFunctionBeginUser;
  /* Kt = K + s0 C + s0^2 M is symmetric positive definite for s0 > 0: Cholesky keeps half the
     factor of LU, which is what lets the interface reduction run on meshes of 500k DOFs */
  PetscCall(MatSetOption(A, MAT_SPD, PETSC_TRUE));
  PetscCall(BoltDirectSolverCreate(ir->comm, prefix, A, PETSC_TRUE, MATSOLVERMUMPS, ksp));
  PetscCall(BoltDirectSolverFactor(*ksp, &reason));
  PetscCheck(reason == PC_NOERROR, ir->comm, PETSC_ERR_NOT_CONVERGED, "Interface reduction: factorisation of %s failed (%s): check that the model is held, or raise -%smat_mumps_icntl_14 if MUMPS ran short of workspace", prefix && !strcmp(prefix, "ir_") ? "Kt = K + s0 C + s0^2 M" : "its interior block", PCFailedReasons[reason], prefix ? prefix : "");
  PetscFunctionReturn(0);
}

/* Single-input second-order Krylov space of the condensed operators, n vectors, by Arnoldi on
   L = [tau P, tau^2 Q; I, 0] (P = -Kt^-1 Ct, Q = -Kt^-1 M in condensed form); the top halves,
   orthonormalised, are appended to VIR. Returns the number of directions kept. */
static PetscErrorCode IRSecondOrderKrylov(BoltInterface *ir, Vec b, PetscInt n, PetscInt *kept)
{
  BV        Z;
  Vec       z, zt, zb, xI, yI, u, v, w;
  PetscInt  nIloc, k;
  PetscReal nrm, tau = 1.0;
  PetscBool lindep;

  PetscFunctionBeginUser;
  *kept = 0;
  if (n <= 0) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(b, &nIloc));
  PetscCall(VecCreateMPI(ir->comm, 2 * nIloc, 2 * ir->nI, &z));
  PetscCall(BVCreate(ir->comm, &Z));
  PetscCall(BVSetSizesFromVec(Z, z, n));
  PetscCall(BVSetType(Z, BVSVEC));
  PetscCall(BVSetOrthogonalization(Z, BV_ORTHOG_CGS, BV_ORTHOG_REFINE_ALWAYS, PETSC_DEFAULT, BV_ORTHOG_BLOCK_GS));
  PetscCall(BoltBVTolerateCancellation(Z));
  PetscCall(VecDestroy(&z));
  PetscCall(VecDuplicate(b, &xI));
  PetscCall(VecDuplicate(b, &yI));
  PetscCall(VecDuplicate(ir->full, &u));
  PetscCall(VecDuplicate(ir->full, &v));
  PetscCall(VecDuplicate(ir->full, &w));
  /* r0 = -(Kt^-1 E_I b)_I; z0 = [r0; 0] */
  PetscCall(VecZeroEntries(u));
  PetscCall(VecISCopy(u, ir->isI, SCATTER_FORWARD, b));
  PetscCall(IRFullSolve(ir, u, v));
  PetscCall(VecISCopy(v, ir->isI, SCATTER_REVERSE, xI));
  PetscCall(VecScale(xI, -1.0));
  /* balance the halves of L with tau ~ ||Q||^-1/2 on r0 */
  PetscCall(IRLift(ir, xI, u));
  PetscCall(MatMult(ir->M, u, w));
  PetscCall(IRFullSolve(ir, w, v));
  PetscCall(VecISCopy(v, ir->isI, SCATTER_REVERSE, yI));
  {
    PetscReal a, q;
    PetscCall(VecNorm(xI, NORM_2, &a));
    PetscCall(VecNorm(yI, NORM_2, &q));
    if (a > 0 && q > 0) tau = PetscSqrtReal(a / q);
  }
  PetscCall(BVGetColumn(Z, 0, &z));
  PetscCall(VecGetSubVector(z, ir->isTop, &zt));
  PetscCall(VecCopy(xI, zt));
  PetscCall(VecRestoreSubVector(z, ir->isTop, &zt));
  PetscCall(VecGetSubVector(z, ir->isBottom, &zb));
  PetscCall(VecZeroEntries(zb));
  PetscCall(VecRestoreSubVector(z, ir->isBottom, &zb));
  PetscCall(BVRestoreColumn(Z, 0, &z));
  PetscCall(BVOrthonormalizeColumn(Z, 0, PETSC_TRUE, &nrm, &lindep));
  PetscCheck(!lindep && nrm > 0, ir->comm, PETSC_ERR_USER_INPUT, "Interface reduction: the input vector gives no response (zero interface?)");
  for (k = 1; k < n; k++) {
    /* z_k = L z_{k-1}: top = -tau (Kt^-1 (Ct lift(x) + tau M lift(y)))_I, bottom = x */
    PetscCall(BVGetColumn(Z, k - 1, &z));
    PetscCall(VecGetSubVector(z, ir->isTop, &zt));
    PetscCall(VecCopy(zt, xI));
    PetscCall(VecRestoreSubVector(z, ir->isTop, &zt));
    PetscCall(VecGetSubVector(z, ir->isBottom, &zb));
    PetscCall(VecCopy(zb, yI));
    PetscCall(VecRestoreSubVector(z, ir->isBottom, &zb));
    PetscCall(BVRestoreColumn(Z, k - 1, &z));
    PetscCall(IRLift(ir, xI, u));
    PetscCall(MatMult(ir->Ct, u, w));
    PetscCall(IRLift(ir, yI, u));
    PetscCall(MatMult(ir->M, u, v));
    PetscCall(VecAXPY(w, tau, v));
    PetscCall(IRFullSolve(ir, w, v));
    PetscCall(BVGetColumn(Z, k, &z));
    PetscCall(VecGetSubVector(z, ir->isTop, &zt));
    PetscCall(VecISCopy(v, ir->isI, SCATTER_REVERSE, zt));
    PetscCall(VecScale(zt, -tau));
    PetscCall(VecRestoreSubVector(z, ir->isTop, &zt));
    PetscCall(VecGetSubVector(z, ir->isBottom, &zb));
    PetscCall(VecCopy(xI, zb));
    PetscCall(VecRestoreSubVector(z, ir->isBottom, &zb));
    PetscCall(BVRestoreColumn(Z, k, &z));
    PetscCall(BVOrthonormalizeColumn(Z, k, PETSC_TRUE, &nrm, &lindep));
    if (lindep || nrm < ir->deflationTol) break; /* the Krylov space is exhausted */
  }
  /* top halves, orthonormalised against V_IR with deflation */
  for (PetscInt j = 0; j < k; j++) {
    PetscInt col = ir->nIR;
    PetscCall(BVGetColumn(Z, j, &z));
    PetscCall(VecGetSubVector(z, ir->isTop, &zt));
    PetscCall(BVInsertVec(ir->VIR, col, zt));
    PetscCall(VecRestoreSubVector(z, ir->isTop, &zt));
    PetscCall(BVRestoreColumn(Z, j, &z));
    PetscCall(BVSetActiveColumns(ir->VIR, 0, col + 1));
    PetscCall(BVOrthonormalizeColumn(ir->VIR, col, PETSC_TRUE, &nrm, &lindep));
    if (!lindep && nrm > ir->deflationTol) {
      ir->nIR++;
      (*kept)++;
    }
  }
  PetscCall(BVDestroy(&Z));
  PetscCall(VecDestroy(&xI));
  PetscCall(VecDestroy(&yI));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&v));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltInterfaceBuild(BoltContactSet *c, Mat M, Mat C, Mat K, PetscReal s0, PetscInt nCCM, PetscInt nJIM, PetscReal deflationTol, BoltInterface **irp)
{
  BoltInterface *ir;
  Vec            mark, bI;
  PetscInt       rstart, rend, nloc = 0, *idx;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscNew(&ir));
  ir->comm         = BoltMeshComm(BoltContactSetMesh(c));
  ir->s0           = s0;
  ir->deflationTol = deflationTol;
  ir->M            = M;
  PetscCall(PetscObjectReference((PetscObject)M));
  /* +1 on side-a DOFs, -1 on side-b DOFs: the JIM input, and the interface itself */
  PetscCall(MatCreateVecs(K, &mark, NULL));
  PetscCall(VecDuplicate(mark, &ir->full));
  PetscCall(VecZeroEntries(mark));
  for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++)
    for (PetscInt k = 0; k < 24; k++)
      if (BoltContactSetElementDofs(c, e)[k] >= 0) PetscCall(VecSetValue(mark, BoltContactSetElementDofs(c, e)[k], k < 12 ? 1.0 : -1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(mark));
  PetscCall(VecAssemblyEnd(mark));
  PetscCall(VecGetOwnershipRange(mark, &rstart, &rend));
  PetscCall(PetscMalloc1(rend - rstart + 1, &idx));
  {
    const PetscScalar *m;
    PetscCall(VecGetArrayRead(mark, &m));
    for (PetscInt i = 0; i < rend - rstart; i++)
      if (PetscRealPart(m[i]) != 0) idx[nloc++] = rstart + i;
    PetscCall(VecRestoreArrayRead(mark, &m));
  }
  PetscCall(ISCreateGeneral(ir->comm, nloc, idx, PETSC_COPY_VALUES, &ir->isI));
  PetscCall(PetscFree(idx));
  PetscCall(ISComplement(ir->isI, rstart, rend, &ir->isG));
  PetscCall(ISGetSize(ir->isI, &ir->nI));
  PetscCheck(nCCM + nJIM <= ir->nI, ir->comm, PETSC_ERR_USER_INPUT, "-rom_n_ccm (%" PetscInt_FMT ") + -rom_n_jim (%" PetscInt_FMT ") exceed the %" PetscInt_FMT " DOFs of the contact interface: choose at most %" PetscInt_FMT " in total", nCCM, nJIM, ir->nI, ir->nI);
  /* the top and bottom halves of a 2 n_I Arnoldi vector, locally [top | bottom] */
  {
    PetscInt s;
    PetscCall(VecCreateMPI(ir->comm, 2 * nloc, 2 * ir->nI, &bI));
    PetscCall(VecGetOwnershipRange(bI, &s, NULL));
    PetscCall(ISCreateStride(ir->comm, nloc, s, 1, &ir->isTop));
    PetscCall(ISCreateStride(ir->comm, nloc, s + nloc, 1, &ir->isBottom));
    PetscCall(VecDestroy(&bI));
  }
  /* Kt, Ct, the blocks, and two factorisations: full (condensed solves) and interior (lifts) */
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &ir->Kt));
  PetscCall(MatAXPY(ir->Kt, s0, C, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(ir->Kt, s0 * s0, M, SAME_NONZERO_PATTERN));
  PetscCall(MatDuplicate(C, MAT_COPY_VALUES, &ir->Ct));
  PetscCall(MatAXPY(ir->Ct, 2 * s0, M, SAME_NONZERO_PATTERN));
  PetscCall(MatCreateSubMatrix(ir->Kt, ir->isG, ir->isG, MAT_INITIAL_MATRIX, &ir->KtGG));
  PetscCall(MatCreateSubMatrix(ir->Kt, ir->isG, ir->isI, MAT_INITIAL_MATRIX, &ir->KtGI));
  PetscCall(MatCreateSubMatrix(ir->Kt, ir->isI, ir->isG, MAT_INITIAL_MATRIX, &ir->KtIG));
  PetscCall(MatCreateVecs(ir->KtGG, &ir->gA, &ir->gB));
  PetscCall(VecDuplicate(ir->gA, &ir->gC));
  PetscCall(MatCreateVecs(ir->KtIG, NULL, &ir->iA));
  PetscCall(VecDuplicate(ir->iA, &ir->iB));
  PetscCall(IRFactor(ir, ir->Kt, "ir_", &ir->kspFull));
  PetscCall(IRFactor(ir, ir->KtGG, "ir_interior_", &ir->kspGG));
  PetscCall(PetscTime(&t1));
  ir->tFactor = t1 - t0;
  /* CCM and JIM */
  PetscCall(BVCreate(ir->comm, &ir->VIR));
  PetscCall(BVSetSizesFromVec(ir->VIR, ir->iA, PetscMax(nCCM + nJIM, 1)));
  PetscCall(BVSetType(ir->VIR, BVSVEC));
  PetscCall(BVSetOrthogonalization(ir->VIR, BV_ORTHOG_CGS, BV_ORTHOG_REFINE_ALWAYS, PETSC_DEFAULT, BV_ORTHOG_BLOCK_GS));
  PetscCall(BoltBVTolerateCancellation(ir->VIR));
  ir->nIR = 0;
  PetscCall(VecSet(ir->iA, 1.0));
  PetscCall(IRSecondOrderKrylov(ir, ir->iA, nCCM, &ir->rankCCM));
  PetscCall(VecISCopy(mark, ir->isI, SCATTER_REVERSE, ir->iA));
  PetscCall(IRSecondOrderKrylov(ir, ir->iA, nJIM, &ir->rankJIM));
  PetscCheck(ir->nIR > 0, ir->comm, PETSC_ERR_USER_INPUT, "Interface reduction kept no direction: set -rom_n_ccm or -rom_n_jim > 0");
  PetscCall(BVSetActiveColumns(ir->VIR, 0, ir->nIR));
  PetscCall(VecDestroy(&mark));
  /* S_IR = V' S_t V, S_t v = (Kt Psi v)_I */
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, ir->nIR, ir->nIR, NULL, &ir->SIR));
  {
    PetscScalar *S;
    Vec          vI, u, w;
    PetscCall(VecDuplicate(ir->iA, &vI));
    PetscCall(VecDuplicate(ir->full, &u));
    PetscCall(VecDuplicate(ir->full, &w));
    PetscCall(MatDenseGetArray(ir->SIR, &S));
    for (PetscInt j = 0; j < ir->nIR; j++) {
      PetscCall(BVCopyVec(ir->VIR, j, vI));
      PetscCall(IRLift(ir, vI, u));
      PetscCall(MatMult(ir->Kt, u, w));
      PetscCall(VecISCopy(w, ir->isI, SCATTER_REVERSE, vI));
      PetscCall(BVDotVec(ir->VIR, vI, &S[j * ir->nIR]));
    }
    PetscCall(MatDenseRestoreArray(ir->SIR, &S));
    PetscCall(VecDestroy(&vI));
    PetscCall(VecDestroy(&u));
    PetscCall(VecDestroy(&w));
  }
  PetscCall(MatLUFactor(ir->SIR, NULL, NULL, NULL));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, ir->nIR, &ir->eta));
  PetscCall(VecDuplicate(ir->eta, &ir->etaRhs));
  PetscCall(PetscTime(&t2));
  ir->tKrylov = t2 - t1;
  PetscCall(PetscPrintf(ir->comm, "Interface reduction: %" PetscInt_FMT " interface DOFs -> %" PetscInt_FMT " (CCM %" PetscInt_FMT " of %" PetscInt_FMT ", JIM %" PetscInt_FMT " of %" PetscInt_FMT "), %.2f s factorisations, %.2f s Krylov and Schur complement\n", ir->nI, ir->nIR, ir->rankCCM, nCCM, ir->rankJIM, nJIM, (double)ir->tFactor, (double)ir->tKrylov));
  PetscCall(BoltMemoryPrint(ir->comm, "the interface reduction"));
  *irp = ir;
  PetscFunctionReturn(0);
}

/* The input block of the interface-reduced model, in full coordinates: E_I V_IR. */
PetscErrorCode BoltInterfaceInputs(BoltInterface *ir, BV B, PetscInt first)
{
  Vec v;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < ir->nIR; j++) {
    PetscCall(BVGetColumn(B, first + j, &v));
    PetscCall(VecZeroEntries(v));
    PetscCall(BVCopyVec(ir->VIR, j, ir->iA));
    PetscCall(VecISCopy(v, ir->isI, SCATTER_FORWARD, ir->iA));
    PetscCall(BVRestoreColumn(B, first + j, &v));
  }
  PetscFunctionReturn(0);
}

/* Sol = T (T' Kt T)^-1 T' Rhs, column by column, by the bordered (Schur complement) solve:
   a = Kt_GG^-1 y_G;  S_IR eta = V'(y_I - Kt_IG a);  x_I = V eta;  x_G = a - Kt_GG^-1 Kt_GI x_I. */
PetscErrorCode BoltInterfaceSolve(void *ctx, BV Rhs, BV Sol, PetscInt nc)
{
  BoltInterface *ir = (BoltInterface *)ctx;
  Vec            y, x;
  PetscScalar   *e;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < nc; j++) {
    PetscCall(BVGetColumn(Rhs, j, &y));
    PetscCall(VecISCopy(y, ir->isG, SCATTER_REVERSE, ir->gA));
    PetscCall(VecISCopy(y, ir->isI, SCATTER_REVERSE, ir->iB));
    PetscCall(BVRestoreColumn(Rhs, j, &y));
    PetscCall(IRInteriorSolve(ir, ir->gA, ir->gB)); /* a */
    PetscCall(MatMult(ir->KtIG, ir->gB, ir->iA));
    PetscCall(VecAYPX(ir->iA, -1.0, ir->iB));
    PetscCall(VecGetArray(ir->etaRhs, &e));
    PetscCall(BVDotVec(ir->VIR, ir->iA, e));
    PetscCall(VecRestoreArray(ir->etaRhs, &e));
    PetscCall(MatSolve(ir->SIR, ir->etaRhs, ir->eta));
    PetscCall(VecGetArray(ir->eta, &e));
    PetscCall(BVMultVec(ir->VIR, 1.0, 0.0, ir->iB, e));
    PetscCall(VecRestoreArray(ir->eta, &e));
    PetscCall(MatMult(ir->KtGI, ir->iB, ir->gA));
    PetscCall(IRInteriorSolve(ir, ir->gA, ir->gC));
    PetscCall(VecAXPY(ir->gB, -1.0, ir->gC));
    PetscCall(BVGetColumn(Sol, j, &x));
    PetscCall(VecISCopy(x, ir->isG, SCATTER_FORWARD, ir->gB));
    PetscCall(VecISCopy(x, ir->isI, SCATTER_FORWARD, ir->iB));
    PetscCall(BVRestoreColumn(Sol, j, &x));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltInterfaceDestroy(BoltInterface **irp)
{
  BoltInterface *ir = *irp;

  PetscFunctionBeginUser;
  if (!ir) PetscFunctionReturn(0);
  PetscCall(ISDestroy(&ir->isI));
  PetscCall(ISDestroy(&ir->isG));
  PetscCall(ISDestroy(&ir->isTop));
  PetscCall(ISDestroy(&ir->isBottom));
  PetscCall(MatDestroy(&ir->Kt));
  PetscCall(MatDestroy(&ir->Ct));
  PetscCall(MatDestroy(&ir->M));
  PetscCall(MatDestroy(&ir->KtGG));
  PetscCall(MatDestroy(&ir->KtGI));
  PetscCall(MatDestroy(&ir->KtIG));
  PetscCall(MatDestroy(&ir->SIR));
  PetscCall(KSPDestroy(&ir->kspFull));
  PetscCall(KSPDestroy(&ir->kspGG));
  PetscCall(BVDestroy(&ir->VIR));
  PetscCall(VecDestroy(&ir->full));
  PetscCall(VecDestroy(&ir->gA));
  PetscCall(VecDestroy(&ir->gB));
  PetscCall(VecDestroy(&ir->gC));
  PetscCall(VecDestroy(&ir->iA));
  PetscCall(VecDestroy(&ir->iB));
  PetscCall(VecDestroy(&ir->eta));
  PetscCall(VecDestroy(&ir->etaRhs));
  PetscCall(PetscFree(*irp));
  PetscFunctionReturn(0);
}
