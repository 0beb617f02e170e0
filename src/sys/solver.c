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

/* MUMPS's errors of a workspace smaller than the factorisation needs (its users' guide: -8, -9,
   -11, -14, -15 and -17; increase ICNTL(14)). */
static PetscBool BoltMumpsShortOfSpace(PetscInt infog1)
{
  return (PetscBool)(infog1 == -8 || infog1 == -9 || infog1 == -11 || infog1 == -14 || infog1 == -15 || infog1 == -17);
}

/* Factorises the operator of a direct solver (KSPSetUp). MUMPS allocates the workspace its
   analysis estimates, plus ICNTL(14) percent; the estimate follows the ordering, and on several
   ranks the ordering differs from run to run, so now and then it falls short: the joint at level
   0.5 on 3 ranks failed with -9 in about 1 run of 25 (the interface reduction's factorisation),
   which the PC records but does not raise, and every solve then returned Inf. MUMPS factorises
   only after a fresh analysis once a factorisation failed, so the PC is reset and set up again,
   with the margin doubled plus 20 (at least MUMPS's default, 20) for this solver's prefix, up to
   four times; the later factorisations of that prefix keep the margin. reason (or NULL): how
   the last factorisation failed, the same on every rank (PC_NOERROR if it did not), for the
   caller to report in its own terms. */
PetscErrorCode BoltDirectSolverFactor(KSP ksp, PCFailedReason *reason)
{
  PC            pc;
  Mat           A, P, F;
  MatSolverType type = NULL;
  PetscBool     isfactor, mumps;
  const char   *prefix;

  PetscFunctionBeginUser;
  PetscCall(KSPSetUp(ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &isfactor, PCLU, PCCHOLESKY, ""));
  if (isfactor) PetscCall(PCFactorGetMatSolverType(pc, &type));
  mumps = (PetscBool)(isfactor && type && !strcmp(type, MATSOLVERMUMPS));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  for (PetscInt attempt = 0; mumps && attempt < 4; attempt++) {
    PetscInt infog1, margin;
    char     name[256], value[32];
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatMumpsGetInfog(F, 1, &infog1)); /* the same on every rank */
    if (!BoltMumpsShortOfSpace(infog1)) break;
    PetscCall(MatMumpsGetIcntl(F, 14, &margin));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%smat_mumps_icntl_14", prefix ? prefix : ""));
    PetscCall(PetscSNPrintf(value, sizeof(value), "%" PetscInt_FMT, PetscMax(20, 2 * margin + 20)));
    PetscCall(PetscOptionsSetValue(NULL, name, value));
    PetscCall(PetscPrintf(PetscObjectComm((PetscObject)ksp), "MUMPS: the factorisation needed more workspace than its analysis estimated (INFOG(1) = %" PetscInt_FMT "): made again with %s %s\n", infog1, name, value));
    PetscCall(KSPGetOperators(ksp, &A, &P));
    PetscCall(PetscObjectReference((PetscObject)A));
    PetscCall(PetscObjectReference((PetscObject)P));
    PetscCall(PCReset(pc));
    PetscCall(KSPSetOperators(ksp, A, P));
    PetscCall(MatDestroy(&A));
    PetscCall(MatDestroy(&P));
    PetscCall(KSPSetUp(ksp));
  }
  if (reason) {
    PetscInt r; /* a factor's error is recorded where it was met */
    PetscCall(PCGetFailedReason(pc, reason));
    r = (PetscInt)*reason;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &r, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)ksp)));
    *reason = (PCFailedReason)r;
  }
  PetscFunctionReturn(0);
}
