/* The dual loop's linear algebra: the effective matrix with the contact stiffness of the active
   set, its factorisation, a solve under given multipliers and the gaps of a displacement; and
   the registry of inner solvers. */
#include "private/solve.h"

PetscFunctionList BoltDualInnerList = NULL;

PetscErrorCode BoltDualInnerRegister(const char name[], BoltDualInnerFn fn)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&BoltDualInnerList, name, fn));
  PetscFunctionReturn(0);
}

/* S = K (static) or K + a1 M + a4 C, summed in the pattern fixed at set-up. */
static PetscErrorCode BoltDualSumStructural(BoltDual *d, Mat S)
{
  BoltOperator *op = d->op;

  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(S));
  PetscCall(MatAXPY(S, 1.0, op->K, SUBSET_NONZERO_PATTERN));
  if (!d->dynamic && op->Krigid) PetscCall(MatAXPY(S, 1.0, op->Krigid, SUBSET_NONZERO_PATTERN));
  if (d->dynamic) {
    PetscCall(MatAXPY(S, d->massCoef, op->M, SUBSET_NONZERO_PATTERN));
    PetscCall(MatAXPY(S, d->dampingCoef, op->C, SUBSET_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

/* A = K + K_c (static) or a1 M + a4 C + K + K_c of the current contact state, factorised by ksp;
   timed and counted as the loop's factorisation. A and ksp are the loop's own, or a model's that
   keeps several (the ROM's references). */
PetscErrorCode BoltDualFactorInto(BoltDual *d, Mat A, KSP ksp)
{
  BoltOperator  *op = d->op;
  Mat            Kc;
  PetscLogDouble t0, t1;
  PCFailedReason reason;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
  PetscCall(op->ops.contactStiffness(op, &Kc));
  if (op->keepStructural) {
    /* the structural part summed once per set of Newmark coefficients, by the same calls in the
       same order as below (the same bits): then each factorisation copies it and adds K_c */
    const PetscReal stamp[3] = {(PetscReal)d->dynamic, d->massCoef, d->dampingCoef};
    if (!d->Kstruct || stamp[0] != d->structStamp[0] || stamp[1] != d->structStamp[1] || stamp[2] != d->structStamp[2]) {
      if (!d->Kstruct) PetscCall(MatDuplicate(A, MAT_DO_NOT_COPY_VALUES, &d->Kstruct));
      PetscCall(BoltDualSumStructural(d, d->Kstruct));
      PetscCall(PetscArraycpy(d->structStamp, stamp, 3));
    }
    PetscCall(MatCopy(d->Kstruct, A, SAME_NONZERO_PATTERN));
  } else PetscCall(BoltDualSumStructural(d, A)); /* (a FOM-sized copy is not kept: at 562k DOFs memory is the limit) */
  PetscCall(MatAXPY(A, 1.0, Kc, SUBSET_NONZERO_PATTERN));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  d->tContactStiffness += t1 - t0;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(BoltDirectSolverFactor(ksp, &reason));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCheck(reason != PC_FACTOR_OUTMEMORY, op->comm, PETSC_ERR_MEM, "%s: factorisation of the effective stiffness ran out of workspace at step %" PetscInt_FMT ", t = %g s, even after four larger tries: raise -%smat_mumps_icntl_14 or run on more memory", op->name, d->step, (double)d->time, op->prefix);
  PetscCheck(reason == PC_NOERROR, op->comm, PETSC_ERR_NOT_CONVERGED, "%s: factorisation of the effective stiffness failed (%s) at step %" PetscInt_FMT ", t = %g s: the system is singular (a part held by contact alone lost all contact?)", op->name, PCFailedReasons[reason], d->step, (double)d->time);
  PetscCall(PetscTime(&t0));
  d->tDisplacements += t0 - t1;
  d->factorizations++;
  PetscFunctionReturn(0);
}

/* After a change of the active set: the operator's own update of its factorisation if it has
   one (the ROM's low-rank updates), else a new one. */
PetscErrorCode BoltDualFactor(BoltDual *d)
{
  PetscFunctionBeginUser;
  if (d->op->ops.factor) PetscCall(d->op->ops.factor(d->op, d));
  else PetscCall(BoltDualFactorInto(d, d->Keff, d->ksp));
  PetscFunctionReturn(0);
}

/* Timed pieces of the inner loops: q = K_eff^-1 (rhs0 - B' lambda), and the gaps of q. */
PetscErrorCode BoltDualSolveWithForces(BoltDual *d, Vec rhs0, const PetscReal lambda[], Vec q)
{
  BoltOperator  *op = d->op;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_FORCES, 0, 0, 0, 0));
  PetscCall(op->ops.contactForces(op, lambda, d->Fc));
  if (rhs0) PetscCall(VecWAXPY(d->work, -1.0, d->Fc, rhs0));
  else PetscCall(VecCopy(d->Fc, d->work));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_FORCES, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_DISPLACEMENTS, 0, 0, 0, 0));
  if (op->ops.solve) PetscCall(op->ops.solve(op, d, d->work, q));
  else PetscCall(KSPSolve(d->ksp, d->work, q));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_DISPLACEMENTS, 0, 0, 0, 0));
  PetscCall(PetscTime(&t2));
  d->solves++;
  d->tContactForces += t1 - t0;
  d->tDisplacements += t2 - t1;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualGapsOf(BoltDual *d, Vec q, PetscReal gap[])
{
  BoltOperator  *op = d->op;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_FORCES, 0, 0, 0, 0));
  if (op->ops.contactGaps) PetscCall(op->ops.contactGaps(op, q, gap));
  else {
    PetscCall(op->ops.contactDisplacements(op, q));
    PetscCall(BoltContactSetGapsOf(op->contact, BoltContactStateWork(op->state), gap));
  }
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_FORCES, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  d->tContactForces += t1 - t0;
  PetscFunctionReturn(0);
}
