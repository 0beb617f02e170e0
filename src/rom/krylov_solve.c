/* The Krylov basis's shifted operator Kt = K + s0 C + s0^2 M: its assembly on the union of the
   three patterns, its direct factorisation, and block solves with it (or with the caller's
   solver, such as the interface reduction's bordered solve). */
#include "private/krylov.h"
#include "private/boltrom_krylov.h"
#include <petscksp.h>

/* Exact comparison of two SeqAIJ patterns */
static PetscErrorCode KrylovSameSeqPattern(Mat A, Mat B, PetscBool *same)
{
  const PetscInt *ia, *ja, *ib, *jb;
  PetscInt        na, nb;
  PetscBool       doneA, doneB;

  PetscFunctionBeginUser;
  PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &doneA));
  PetscCall(MatGetRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &doneB));
  *same = (PetscBool)(doneA && doneB && na == nb);
  if (*same) PetscCall(PetscArraycmp(ia, ib, na + 1, same));
  if (*same) PetscCall(PetscArraycmp(ja, jb, ia[na], same));
  PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &doneA));
  PetscCall(MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &doneB));
  PetscFunctionReturn(0);
}

/* MatAXPY with SAME_NONZERO_PATTERN silently gives a wrong sum if the patterns differ: check them
   (O(nnz)) and fall back to DIFFERENT_NONZERO_PATTERN (slower, always right) */
static PetscErrorCode KrylovPattern(Mat A, Mat B, MatStructure *str)
{
  Mat             Ad, Ao, Bd, Bo;
  const PetscInt *ga, *gb;
  PetscInt        nga, ngb;
  PetscBool       mpiA, mpiB, seqA, seqB, same = PETSC_FALSE;
  PetscMPIInt     flag;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATMPIAIJ, &mpiA));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)B, MATMPIAIJ, &mpiB));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATSEQAIJ, &seqA));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)B, MATSEQAIJ, &seqB));
  if (mpiA && mpiB) {
    PetscCall(MatMPIAIJGetSeqAIJ(A, &Ad, &Ao, &ga));
    PetscCall(MatMPIAIJGetSeqAIJ(B, &Bd, &Bo, &gb));
    PetscCall(KrylovSameSeqPattern(Ad, Bd, &same));
    if (same) PetscCall(KrylovSameSeqPattern(Ao, Bo, &same));
    if (same) {
      PetscCall(MatGetSize(Ao, NULL, &nga));
      PetscCall(MatGetSize(Bo, NULL, &ngb));
      same = (PetscBool)(nga == ngb);
      if (same) PetscCall(PetscArraycmp(ga, gb, nga, &same));
    }
  } else if (seqA && seqB) PetscCall(KrylovSameSeqPattern(A, B, &same));
  flag = (PetscMPIInt)same;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_LAND, PetscObjectComm((PetscObject)A)));
  *str = flag ? SAME_NONZERO_PATTERN : DIFFERENT_NONZERO_PATTERN;
  PetscFunctionReturn(0);
}

/* Sol(:, 0:nc) = Kt^{-1} Rhs(:, 0:nc), all right-hand sides in one MatMatSolve */
PetscErrorCode KrylovSolve(BoltKrylov *kr, Mat F, BV Rhs, BV Sol, PetscInt nc)
{
  Mat A, X;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_KRYLOV_SOLVE, 0, 0, 0, 0));
  if (kr->solve) PetscCall(kr->solve(kr->solveCtx, Rhs, Sol, nc));
  else {
    PetscCall(BVSetActiveColumns(Rhs, 0, nc));
    PetscCall(BVSetActiveColumns(Sol, 0, nc));
    PetscCall(BVGetMat(Rhs, &A));
    PetscCall(BVGetMat(Sol, &X));
    PetscCall(MatMatSolve(F, A, X));
    PetscCall(BVRestoreMat(Sol, &X));
    PetscCall(BVRestoreMat(Rhs, &A));
  }
  kr->nsolves += nc;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_KRYLOV_SOLVE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Kt = K + s0 C + s0^2 M, formed and factored once (KSP prefix krylov_: MUMPS LU by default) */
PetscErrorCode KrylovFactor(BoltKrylov *kr, Mat M, Mat C, Mat K, Mat *Kt, KSP *ksp, Mat *F)
{
  MPI_Comm       comm = PetscObjectComm((PetscObject)K);
  PC             pc;
  MatStructure   strC, strM;
  PCFailedReason reason;
  PetscBool      isfactor, set, symK, symC, symM;
  PetscReal      s0 = kr->s0, t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_KRYLOV_FACTOR, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, Kt));
  PetscCall(KrylovPattern(K, C, &strC));
  PetscCall(KrylovPattern(K, M, &strM));
  PetscCall(MatAXPY(*Kt, s0, C, strC));
  PetscCall(MatAXPY(*Kt, s0 * s0, M, strM));
  PetscCall(MatIsSymmetricKnown(K, &set, &symK));
  symK = (PetscBool)(set && symK);
  PetscCall(MatIsSymmetricKnown(C, &set, &symC));
  symC = (PetscBool)(set && symC);
  PetscCall(MatIsSymmetricKnown(M, &set, &symM));
  symM = (PetscBool)(set && symM);
  if (symK && symC && symM) PetscCall(MatSetOption(*Kt, MAT_SYMMETRIC, PETSC_TRUE));
  /* Cholesky when Kt is symmetric: half the factor of LU */
  PetscCall(BoltDirectSolverCreate(comm, "krylov_", *Kt, (PetscBool)(symK && symC && symM), MATSOLVERMUMPS, ksp));
  PetscCall(KSPGetPC(*ksp, &pc));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &isfactor, PCLU, PCCHOLESKY, ""));
  PetscCheck(isfactor, comm, PETSC_ERR_USER_INPUT, "-krylov_pc_type must be lu or cholesky: the Krylov blocks are solved with MatMatSolve on a direct factorization");
  PetscCall(BoltDirectSolverFactor(*ksp, &reason));
  PetscCall(PCFactorGetMatrix(pc, F));
  PetscCheck(reason != PC_FACTOR_OUTMEMORY, comm, PETSC_ERR_MEM, "Factorization of Kt = K + s0 C + s0^2 M ran out of workspace even after four larger tries: raise -krylov_mat_mumps_icntl_14 or run on more memory");
  PetscCheck(reason == PC_NOERROR, comm, PETSC_ERR_USER_INPUT, "Factorization of Kt = K + s0 C + s0^2 M failed (s0 = %g rad/s): Kt is singular, i.e. s0 = 0 on an unheld model; change -krylov_s0 or check the clamp", (double)s0);
  PetscCall(PetscTime(&t1));
  kr->tFactor = t1 - t0;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_KRYLOV_FACTOR, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
