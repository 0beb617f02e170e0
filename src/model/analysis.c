/* Linear analyses of an assembled model: static solve and undamped eigenfrequencies, both
   with a MUMPS LU factorisation (defaults set here, overridable through the prefix). */
#include "private/model.h"

PetscErrorCode BoltStaticSolve(Mat K, Vec f, Vec u, const char prefix[])
{
  KSP                ksp;
  KSPConvergedReason reason;
  PetscReal          norm;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_STATIC_SOLVE, 0, 0, 0, 0));
  /* a failed solve does not raise an error (KSP's default): the check below names its cause */
  PetscCall(BoltDirectSolverCreate(PetscObjectComm((PetscObject)K), prefix, K, PETSC_FALSE, MATSOLVERMUMPS, &ksp));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCall(BoltDirectSolverFactor(ksp, NULL));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCall(KSPSolve(ksp, f, u));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(VecNorm(u, NORM_2, &norm));
  PetscCheck(reason >= 0 && !PetscIsInfOrNanReal(norm), PetscObjectComm((PetscObject)K), PETSC_ERR_NOT_CONVERGED, "Static solve failed (%s, |u| = %g): the stiffness matrix is singular, i.e. some part is not held; check the clamp group and the contact pairs", KSPConvergedReasons[reason], (double)norm);
  PetscCall(KSPDestroy(&ksp));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_STATIC_SOLVE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The eigensolver of the nev lowest eigenpairs, by shift-and-invert about target (0, or a free
   model's small negative shift), then its options. Operators (K, M) are set before, if at all. */
static PetscErrorCode ModalSetUp(EPS eps, PetscInt nev, PetscReal target)
{
  ST  st;
  KSP ksp;

  PetscFunctionBeginUser;
  PetscCall(EPSSetProblemType(eps, EPS_GHEP));
  PetscCall(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PetscCall(EPSSetTarget(eps, target));
  PetscCall(EPSSetTolerances(eps, 1e-10, PETSC_DEFAULT));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(BoltDirectSolverSetType(ksp, PETSC_FALSE, MATSOLVERMUMPS));
  PetscCall(EPSSetFromOptions(eps));
  PetscFunctionReturn(0);
}

/* Reads (and so checks) the options of the modal solve before the model exists. */
PetscErrorCode BoltModalSetFromOptions(MPI_Comm comm, PetscInt nev, const char prefix[])
{
  EPS eps;

  PetscFunctionBeginUser;
  PetscCall(EPSCreate(comm, &eps));
  PetscCall(EPSSetOptionsPrefix(eps, prefix));
  PetscCall(ModalSetUp(eps, PetscMax(nev, 1), 0.0));
  PetscCall(EPSDestroy(&eps));
  PetscFunctionReturn(0);
}

/* The nev lowest eigenfrequencies [Hz] of K x = w^2 M x, by shift-and-invert about 0; for a free
   model (R: its rigid motions, else NULL) the nev lowest elastic ones, R deflated and the shift
   -BoltRigidShift() keeping the factorisation regular. shift: that shift even for a held model,
   whose K may be singular all the same (a part held by frictionless contact slides freely). */
PetscErrorCode BoltModalSolve(Mat K, Mat M, BV R, PetscBool shift, PetscInt nev, const char prefix[], PetscInt *nconv, PetscReal freq[])
{
  EPS eps;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_MODAL_SOLVE, 0, 0, 0, 0));
  PetscCall(EPSCreate(PetscObjectComm((PetscObject)K), &eps));
  PetscCall(EPSSetOptionsPrefix(eps, prefix));
  PetscCall(EPSSetOperators(eps, K, M));
  if (R) {
    Vec rigid[6];
    for (PetscInt k = 0; k < 6; k++) {
      PetscCall(MatCreateVecs(M, &rigid[k], NULL));
      PetscCall(BVCopyVec(R, k, rigid[k]));
    }
    PetscCall(EPSSetDeflationSpace(eps, 6, rigid));
    for (PetscInt k = 0; k < 6; k++) PetscCall(VecDestroy(&rigid[k]));
  }
  PetscCall(ModalSetUp(eps, nev, (R || shift) ? -BoltRigidShift() : 0.0));
  PetscCall(EPSSolve(eps));
  PetscCall(EPSGetConverged(eps, nconv));
  PetscCheck(*nconv >= nev, PetscObjectComm((PetscObject)K), PETSC_ERR_NOT_CONVERGED, "Eigensolver found %" PetscInt_FMT " of %" PetscInt_FMT " eigenpairs: raise -%seps_max_it or check the model", *nconv, nev, prefix ? prefix : "");
  *nconv = PetscMin(*nconv, nev);
  for (PetscInt i = 0; i < *nconv; i++) {
    PetscScalar kr;
    PetscCall(EPSGetEigenvalue(eps, i, &kr, NULL));
    freq[i] = PetscSqrtReal(PetscMax(PetscRealPart(kr), 0.0)) / (2 * PETSC_PI);
  }
  PetscCall(EPSDestroy(&eps));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_MODAL_SOLVE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
