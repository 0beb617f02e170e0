/* Direct solvers: a KSP that only applies a factorisation (PREONLY with LU or Cholesky), the one
   set-up shared by the static and modal analyses, the Krylov basis, the interface reduction, the
   ROM's checks and the time integrators. Whatever is set here precedes KSPSetFromOptions, so that
   the command line (-<prefix>ksp_type, -<prefix>pc_type, ...) overrides it. */
#include "boltrom.h"

/* PREONLY with a Cholesky (symmetric) or LU factorisation by the given package (NULL: PETSc's
   default for the matrix type). Also for a KSP made by another object, e.g. an EPS's ST. */
PetscErrorCode BoltDirectSolverSetType(KSP ksp, PetscBool symmetric, MatSolverType type)
{
  PC pc;

  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU));
  if (type) PetscCall(PCFactorSetMatSolverType(pc, type));
  PetscFunctionReturn(0);
}

/* A direct solver of A (NULL: operators set later). With a prefix it takes the options of that
   prefix; without one it is fixed in code (checks that must not depend on the command line). */
PetscErrorCode BoltDirectSolverCreate(MPI_Comm comm, const char prefix[], Mat A, PetscBool symmetric, MatSolverType type, KSP *ksp)
{
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(comm, ksp));
  if (prefix) PetscCall(KSPSetOptionsPrefix(*ksp, prefix));
  if (A) PetscCall(KSPSetOperators(*ksp, A, A));
  PetscCall(BoltDirectSolverSetType(*ksp, symmetric, type));
  if (prefix) PetscCall(KSPSetFromOptions(*ksp));
  PetscFunctionReturn(0);
}

/* Reads (and so checks) the options of a direct solver made later from the model: the run's
   options are all read before anything is computed. */
PetscErrorCode BoltDirectSolverSetFromOptions(MPI_Comm comm, const char prefix[], PetscBool symmetric, MatSolverType type)
{
  KSP ksp;

  PetscFunctionBeginUser;
  PetscCall(BoltDirectSolverCreate(comm, prefix, NULL, symmetric, type, &ksp));
  PetscCall(KSPDestroy(&ksp));
  PetscFunctionReturn(0);
}

/* Bases in the Euclidean product, which is definite: a squared remainder norm that comes out
   negative is cancellation in orthogonalising a (nearly) dependent column, and counts as zero
   (the caller then drops the column) instead of SLEPc's "indefinite matrix" error, which a
   partition's rounding could otherwise raise at random. */
PetscErrorCode BoltBVTolerateCancellation(BV bv)
{
  PetscFunctionBeginUser;
  PetscCall(BVSetDefiniteTolerance(bv, PETSC_MAX_REAL));
  PetscFunctionReturn(0);
}
