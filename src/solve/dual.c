/* The dual contact loop (the paper's Algorithm 1), written once against BoltOperator so that the
   full and the reduced model, in time steps and in the offline static solves, run the same code.
   Outer loop: the active set, until it stops changing; inner loop: the multipliers of that set,
   by a registered inner solver, until they stop changing and the penetration is small. */
#include "boltrom.h"

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

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactStiffness, 0, 0, 0, 0));
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
  PetscCall(PetscLogEventEnd(boltLog.contactStiffness, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  d->tContactStiffness += t1 - t0;
  PetscCall(PetscLogEventBegin(boltLog.factorization, 0, 0, 0, 0));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetUp(ksp));
  PetscCall(PetscLogEventEnd(boltLog.factorization, 0, 0, 0, 0));
  {
    PC             pc;
    PCFailedReason reason;
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCGetFailedReason(pc, &reason));
    PetscCheck(reason == PC_NOERROR, op->comm, PETSC_ERR_NOT_CONVERGED, "%s: factorisation of the effective stiffness failed (%s) at step %" PetscInt_FMT ", t = %g s: the system is singular (a part held by contact alone lost all contact?)", op->name, PCFailedReasons[reason], d->step, (double)d->time);
  }
  PetscCall(PetscTime(&t0));
  d->tDisplacements += t0 - t1;
  d->factorizations++;
  PetscFunctionReturn(0);
}

/* After a change of the active set: the operator's own update of its factorisation if it has
   one (the ROM's low-rank updates), else a new one. */
static PetscErrorCode BoltDualFactor(BoltDual *d)
{
  PetscFunctionBeginUser;
  if (d->op->ops.factor) PetscCall(d->op->ops.factor(d->op, d));
  else PetscCall(BoltDualFactorInto(d, d->Keff, d->ksp));
  PetscFunctionReturn(0);
}

/* Timed pieces of the inner loops: q = K_eff^-1 (rhs0 - B' lambda), and the gaps of q. */
static PetscErrorCode BoltDualSolveWithForces(BoltDual *d, Vec rhs0, const PetscReal lambda[], Vec q)
{
  BoltOperator  *op = d->op;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(op->ops.contactForces(op, lambda, d->Fc));
  if (rhs0) PetscCall(VecWAXPY(d->work, -1.0, d->Fc, rhs0));
  else PetscCall(VecCopy(d->Fc, d->work));
  PetscCall(PetscLogEventEnd(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogEventBegin(boltLog.displacements, 0, 0, 0, 0));
  if (op->ops.solve) PetscCall(op->ops.solve(op, d, d->work, q));
  else PetscCall(KSPSolve(d->ksp, d->work, q));
  PetscCall(PetscLogEventEnd(boltLog.displacements, 0, 0, 0, 0));
  PetscCall(PetscTime(&t2));
  d->solves++;
  d->tContactForces += t1 - t0;
  d->tDisplacements += t2 - t1;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltDualGapsOf(BoltDual *d, Vec q, PetscReal gap[])
{
  BoltOperator  *op = d->op;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactForces, 0, 0, 0, 0));
  if (op->ops.contactGaps) PetscCall(op->ops.contactGaps(op, q, gap));
  else {
    PetscCall(op->ops.contactDisplacements(op, q));
    PetscCall(BoltContactSetGapsOf(op->contact, gap));
  }
  PetscCall(PetscLogEventEnd(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  d->tContactForces += t1 - t0;
  PetscFunctionReturn(0);
}

/* The active set judged on the last solve: the opening test's tractions (the model's own way, if
   it has one), then the state's decisions. */
static PetscErrorCode BoltDualUpdateActive(BoltDual *d, PetscInt *nchanged, PetscBool *cycling)
{
  BoltOperator *op = d->op;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(boltLog.contactUpdate, 0, 0, 0, 0));
  if (op->ops.openTraction) PetscCall(op->ops.openTraction(op, d->tnOpen));
  else PetscCall(BoltContactStateOpenTraction(op->state, d->tnOpen));
  PetscCall(BoltContactStateUpdateActive(op->state, d->tnOpen, nchanged, cycling));
  PetscCall(PetscLogEventEnd(boltLog.contactUpdate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltDualInnerFailure(BoltDual *d, PetscInt inner, PetscReal rel, PetscReal pen)
{
  MPI_Comm comm = d->op->comm;

  PetscFunctionBeginUser;
  d->failures++;
  PetscCheck(d->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: contact augmentations did not converge at step %" PetscInt_FMT ", t = %g s: after %" PetscInt_FMT " iterations the multipliers change by %.3e (tolerance %.1e) and the penetration is %.3e m (tolerance %.1e); raise -contact_max_inner or loosen -contact_tol_lambda / -contact_tol_penetration, or add -contact_continue to go on with a warning", d->op->name, d->step, (double)d->time, inner, (double)rel, (double)d->tolLambda, (double)pen, (double)d->tolPenetration);
  PetscCall(PetscPrintf(comm, "WARNING %s: augmentations not converged at step %" PetscInt_FMT ", t = %g s (change %.3e, penetration %.3e m)\n", d->op->name, d->step, (double)d->time, (double)rel, (double)pen));
  PetscFunctionReturn(0);
}

/* Inner loop, the paper's way: lambda <- lambda + P g at the active points until the
   multipliers stop changing and the penetration is small. */
static PetscErrorCode BoltDualInnerUzawa(BoltDual *d, Vec rhs0, Vec q, PetscInt *ninner)
{
  BoltContactState *s = d->op->state;
  PetscReal         rel = 0, pen = 0;
  PetscInt          inner;

  PetscFunctionBeginUser;
  for (inner = 1;; inner++) {
    PetscCall(BoltDualSolveWithForces(d, rhs0, BoltContactStateForceMultipliers(s), q));
    PetscCall(BoltDualGapsOf(d, q, s->gap));
    BoltContactStateAnchorGaps(s, s->gap);
    PetscCall(PetscLogEventBegin(boltLog.contactUpdate, 0, 0, 0, 0));
    PetscCall(BoltContactStateAugment(s, &rel, &pen));
    PetscCall(PetscLogEventEnd(boltLog.contactUpdate, 0, 0, 0, 0));
    d->lastChange      = rel;
    d->lastPenetration = pen;
    PetscCheck(!PetscIsInfOrNanReal(rel) && !PetscIsInfOrNanReal(pen), d->op->comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", d->op->name, d->step, (double)d->time);
    if (!s->augment) break;
    if (rel <= d->tolLambda && (pen <= d->tolPenetration || !d->op->exactConstraints)) break;
    if (inner >= d->maxInner) {
      PetscCall(BoltDualInnerFailure(d, inner, rel, pen));
      break;
    }
  }
  *ninner = inner;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltDualMonitorCG(BoltDual *, Vec, Vec, PetscInt, PetscReal, PetscReal, PetscReal, const PetscReal[], PetscReal, PetscReal[]);

/* Inner loop by conjugate gradients on the multipliers. For a fixed active set the gaps are
   affine in the multipliers, g(lambda) = g(0) - A lambda with A = B K_eff^-1 B' W symmetric
   in the area-weighted product, and the augmentations are Richardson iterations towards
   g = 0; CG reaches the same multipliers in far fewer solves (one solve per iteration). Under
   the penalty law there are no multiplier unknowns: one solve, as Uzawa. */
static PetscErrorCode BoltDualInnerCG(BoltDual *d, Vec rhs0, Vec q, PetscInt *ninner)
{
  BoltContactState *s  = d->op->state;
  BoltContactSet   *c  = s->set;
  PetscInt          ng = 12 * c->nelem, inner;
  PetscReal        *r = d->cgR, *p = d->cgP, *Ap = d->cgAp, rr, rr0, pAp, alpha, rel = 0, pen = 0, lnorm, pnorm;

  PetscFunctionBeginUser;
  if (!s->augment) {
    PetscCall(BoltDualInnerUzawa(d, rhs0, q, ninner));
    PetscFunctionReturn(0);
  }
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++)
    if (!s->active[gp]) s->lambda[3 * gp] = s->lambda[3 * gp + 1] = s->lambda[3 * gp + 2] = 0;
  BoltContactStateChanged(s);
  PetscCall(BoltDualSolveWithForces(d, rhs0, s->lambda, q));
  PetscCall(VecCopy(d->Fc, d->FcLambda)); /* the contact forces of lambda, kept up to date */
  PetscCall(BoltDualGapsOf(d, q, r));
  PetscCall(BoltContactStatePenetration(s, r, &pen));
  PetscCall(PetscArraycpy(p, r, ng));
  PetscCall(BoltContactStateDot(s, r, r, &rr));
  rr0 = rr;
  for (inner = 1;; inner++) {
    PetscReal rrNew;

    d->lastPenetration = pen;
    if (rr == 0) { /* nothing active, or exactly closed */
      rel = 0;
      break;
    }
    /* A p: the gaps that the multipliers p alone produce (with a minus sign) */
    PetscCall(BoltDualSolveWithForces(d, NULL, p, d->qp));
    PetscCall(BoltDualGapsOf(d, d->qp, Ap));
    PetscCall(BoltContactStatePenetration(s, Ap, &pnorm)); /* zeroes inactive points */
    PetscCall(BoltContactStateDot(s, p, Ap, &pAp));
    PetscCheck(!PetscIsInfOrNanReal(pAp) && !PetscIsInfOrNanReal(rr), d->op->comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", d->op->name, d->step, (double)d->time);
    if (pAp <= 0) break; /* the remaining gaps are invisible to the multipliers */
    alpha = rr / pAp;
    for (PetscInt k = 0; k < ng; k++) {
      s->lambda[k] += alpha * p[k];
      r[k] -= alpha * Ap[k];
    }
    BoltContactStateChanged(s);
    PetscCall(VecAXPY(q, -alpha, d->qp));
    /* change of the multipliers, measured by the nodal forces they exert: components of lambda
       that exert no force (there are more Gauss points than nodes) change nothing */
    PetscCall(VecAXPY(d->FcLambda, alpha, d->Fc));
    PetscCall(VecNorm(d->Fc, NORM_2, &pnorm));
    PetscCall(VecNorm(d->FcLambda, NORM_2, &lnorm));
    rel = lnorm > 0 ? PetscAbsReal(alpha) * pnorm / lnorm : 0;
    PetscCall(BoltContactStatePenetration(s, r, &pen));
    d->lastChange      = rel;
    d->lastPenetration = pen;
    if (d->monitor > 1) PetscCall(BoltDualMonitorCG(d, rhs0, q, inner, rel, pen, alpha, r, rr0, Ap));
    /* a reduced model may have fewer DOFs than contact constraints: there the penetration
       cannot vanish everywhere, and the loop ends when the gaps (the dual residual) have dropped
       by the tolerance, or the reduced forces stop changing */
    if (rel <= d->tolLambda && pen <= d->tolPenetration) break;
    PetscCall(BoltContactStateDot(s, r, r, &rrNew));
    if (!d->op->exactConstraints && (PetscSqrtReal(rrNew / rr0) <= d->tolLambda || rel <= 1e-2 * d->tolLambda)) break;
    if (inner >= d->maxInner) {
      PetscCall(BoltDualInnerFailure(d, inner, rel, pen));
      break;
    }
    for (PetscInt k = 0; k < ng; k++) p[k] = r[k] + (rrNew / rr) * p[k];
    rr = rrNew;
  }
  /* the true gaps of the final displacement at every point: r holds them only at active points
     (zeroed elsewhere), and an inactive point must be able to close again */
  PetscCall(BoltDualGapsOf(d, q, s->gap));
  *ninner = inner;
  PetscFunctionReturn(0);
}

/* The true residual of the CG iteration for -contact_monitor 2: the gaps of q and of a fresh
   solve with the current multipliers (their difference is the drift of the recurrence). */
static PetscErrorCode BoltDualMonitorCG(BoltDual *d, Vec rhs0, Vec q, PetscInt inner, PetscReal rel, PetscReal pen, PetscReal alpha, const PetscReal r[], PetscReal rr0, PetscReal work[])
{
  BoltContactState *s  = d->op->state;
  PetscInt          ng = 12 * s->set->nelem;
  PetscReal         rrN, trueRes = 0, drift = 0;

  PetscFunctionBeginUser;
  PetscCall(BoltContactStateDot(s, r, r, &rrN));
  if (inner % 10 == 0) {
    PetscReal *tg, dd, tt;
    Vec        qt;
    PetscCall(PetscMalloc1(ng + 1, &tg));
    PetscCall(VecDuplicate(q, &qt));
    PetscCall(BoltDualSolveWithForces(d, rhs0, s->lambda, qt));
    PetscCall(BoltDualGapsOf(d, qt, tg));
    PetscCall(VecDestroy(&qt));
    PetscCall(BoltContactStatePenetration(s, tg, &tt));
    for (PetscInt k = 0; k < ng; k++) work[k] = tg[k] - r[k];
    PetscCall(BoltContactStateDot(s, work, work, &dd));
    PetscCall(BoltContactStateDot(s, tg, tg, &tt));
    trueRes = PetscSqrtReal(tt / rr0);
    drift   = PetscSqrtReal(dd / rr0);
    PetscCall(PetscFree(tg));
  }
  PetscCall(PetscPrintf(d->op->comm, "    CG %4" PetscInt_FMT " rel %.3e |r|/|r0| %.3e true %.3e drift %.3e pen %.3e alpha %.3e\n", inner, (double)rel, (double)PetscSqrtReal(rrN / rr0), (double)trueRes, (double)drift, (double)pen, (double)alpha));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltDualInnerFinalize(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&BoltDualInnerList));
  PetscFunctionReturn(0);
}

/* The inner solvers that come with boltrom; others register beside them with BoltDualInnerRegister. */
static PetscErrorCode BoltDualInnerRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (BoltDualInnerList) PetscFunctionReturn(0);
  PetscCall(BoltDualInnerRegister("uzawa", BoltDualInnerUzawa));
  PetscCall(BoltDualInnerRegister("cg", BoltDualInnerCG));
  PetscCall(PetscRegisterFinalize(BoltDualInnerFinalize));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualCreate(BoltOperator *op, BoltDual **dp)
{
  BoltDual *d;

  PetscFunctionBeginUser;
  PetscCall(BoltDualInnerRegisterAll());
  PetscCall(PetscNew(&d));
  d->op             = op;
  d->maxOuter       = 20;
  d->maxInner       = 5000;
  d->tolLambda      = 1e-4;
  d->tolPenetration = 1e-9;
  d->tolFriction    = 1e-7;
  d->warmStart      = PETSC_TRUE;
  d->extrapolate    = PETSC_TRUE;
  d->closeCycles    = PETSC_TRUE;
  d->preloadScale   = 1.0;
  PetscCall(PetscStrncpy(d->innerType, "cg", sizeof(d->innerType)));
  *dp = d;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualSetFromOptions(BoltDual *d)
{
  MPI_Comm comm = d->op->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Contact loop", "boltrom");
  PetscCall(PetscOptionsFList("-contact_inner", "Inner loop: uzawa (augmentations, as the paper) or cg (conjugate gradients on the multipliers, same fixed point, fewer solves)", "BoltDual", BoltDualInnerList, d->innerType, d->innerType, sizeof(d->innerType), NULL));
  PetscCall(PetscOptionsInt("-contact_max_outer", "Outer (active set) iterations per step (strict law: active sets per step)", NULL, d->maxOuter, &d->maxOuter, NULL));
  PetscCall(PetscOptionsInt("-contact_max_inner", "Inner (augmentation) iterations per outer iteration (strict law: solves per step)", NULL, d->maxInner, &d->maxInner, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_lambda", "Tolerance on the relative change of the multipliers", NULL, d->tolLambda, &d->tolLambda, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_penetration", "Tolerance on the largest penetration of an active point [m] (strict law: on the largest gap of a closed pair; default 1e-9 x the shortest contact-face edge; stick law: 1e-9 m)", NULL, d->tolPenetration, &d->tolPenetration, &d->tolPenetrationSet));
  PetscCall(PetscOptionsReal("-contact_tol_friction", "Coulomb friction: tolerance on the largest change of a slipping pair's tangential traction after a solve, relative to the largest contact pressure", NULL, d->tolFriction, &d->tolFriction, NULL));
  PetscCall(PetscOptionsBool("-contact_warm_start", "Start each outer iteration from the last multipliers (false: from zero, as the paper)", NULL, d->warmStart, &d->warmStart, NULL));
  PetscCall(PetscOptionsBool("-contact_cycle_close", "Anti-cycling: when the active set cycles between two sets (its toggling points are then closed) or has not settled in half of -contact_max_outer, points may only close for the rest of the step; false: a cycle stops the run (or warns, with -contact_continue)", NULL, d->closeCycles, &d->closeCycles, NULL));
  PetscCall(PetscOptionsBool("-contact_extrapolate", "Strict law, time steps: start each step's loop from the multipliers of the points closed over the last two steps extrapolated linearly in time (false: from the last step's)", NULL, d->extrapolate, &d->extrapolate, NULL));
  PetscCall(PetscOptionsBool("-contact_continue", "On non-convergence, warn and go on instead of stopping", NULL, d->continueOnFailure, &d->continueOnFailure, NULL));
  PetscCall(PetscOptionsInt("-contact_monitor", "Print the contact loop: 1 a line per outer iteration, 2 also per inner CG iteration", NULL, d->monitor, &d->monitor, NULL));
  PetscOptionsEnd();
  PetscCheck(d->maxOuter >= 1 && d->maxInner >= 1, comm, PETSC_ERR_USER_INPUT, "-contact_max_outer and -contact_max_inner must be >= 1");
  PetscCall(PetscFunctionListFind(BoltDualInnerList, d->innerType, &d->inner));
  PetscCheck(d->inner, comm, PETSC_ERR_USER_INPUT, "Unknown -contact_inner %s: use uzawa or cg", d->innerType);
  PetscFunctionReturn(0);
}

/* The effective matrix's pattern, its direct solver (prefix fom_ or rom_), the work space. */
PetscErrorCode BoltDualSetUp(BoltDual *d)
{
  BoltOperator *op = d->op;
  PetscInt      ng = 12 * op->contact->nelem + 1;
  Mat           Kc, Z;

  PetscFunctionBeginUser;
  if (op->state->law.strict && !d->tolPenetrationSet) d->tolPenetration = op->contact->gapTolerance;
  PetscCall(MatCreateVecs(op->K, &d->Fc, NULL));
  PetscCall(VecDuplicate(d->Fc, &d->work));
  PetscCall(VecDuplicate(d->Fc, &d->qp));
  PetscCall(VecDuplicate(d->Fc, &d->FcLambda));
  PetscCall(PetscMalloc4(ng, &d->cgR, ng, &d->cgP, ng, &d->cgAp, 4 * op->contact->nelem + 1, &d->tnOpen));
  /* K_eff gets the union of the structural and the contact pattern once, so that it keeps one
     pattern and MUMPS repeats only the numeric factorisation */
  PetscCall(op->ops.contactStiffness(op, &Kc));
  PetscCall(MatDuplicate(Kc, MAT_DO_NOT_COPY_VALUES, &Z));
  PetscCall(MatDuplicate(op->K, MAT_COPY_VALUES, &d->Keff));
  PetscCall(MatAXPY(d->Keff, 1.0, Z, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&Z));
  {
    /* K_eff is symmetric (the stick penalty is): Cholesky (LDL' in MUMPS) halves the factor */
    PetscBool set, sym;
    PetscCall(MatIsSymmetricKnown(op->K, &set, &sym));
    if (set && sym) PetscCall(MatSetOption(d->Keff, MAT_SYMMETRIC, PETSC_TRUE));
    PetscCall(BoltDirectSolverCreate(PetscObjectComm((PetscObject)op->K), op->prefix, NULL, (PetscBool)(set && sym), op->solverType, &d->ksp));
  }
  PetscFunctionReturn(0);
}

/* The next factorisations: K + K_c (static), or a1 M + a4 C + K + K_c (a Newmark step). */
PetscErrorCode BoltDualSetEffective(BoltDual *d, PetscBool dynamic, PetscReal massCoef, PetscReal dampingCoef)
{
  PetscFunctionBeginUser;
  d->dynamic     = dynamic;
  d->massCoef    = massCoef;
  d->dampingCoef = dampingCoef;
  PetscFunctionReturn(0);
}

/* The preload layers bound an elastic element layer of the stud, which takes part of the
   applied force; the clamping force is what a preload means. With zero initial gaps and a fixed
   active set the static contact problem is linear in the load, so scaling the solution, the
   multipliers, the gaps and the preload vector by target / transmitted is exact. It is done
   after every inner solve of the preload, before the active set is updated: the activation band
   is absolute (metres, pascals), so the set must be judged on the tractions of the calibrated
   preload, not on those of the applied layer forces (about 15 times smaller for the joint). */
static PetscErrorCode BoltDualCalibrate(BoltDual *d, Vec rhs0, Vec q)
{
  BoltContactState *s = d->op->state;
  BoltContactSet   *c = s->set;
  PetscReal         force[BOLTROM_MAX_PAIRS], fmax = 0, scale;

  PetscFunctionBeginUser;
  PetscCall(BoltContactStateNormalForcePerPair(s, force));
  for (PetscInt p = 0; p < c->npairs; p++) fmax = PetscMax(fmax, PetscAbsReal(force[p]));
  PetscCheck(fmax > 0, d->op->comm, PETSC_ERR_USER_INPUT, "The preload transmits no contact force: check the preload groups and the bolt axis (-preload_axis)");
  scale = d->preloadTarget / fmax;
  d->preloadScale *= scale;
  PetscCall(VecScale(q, scale));
  PetscCall(VecScale(d->op->preload, scale));
  if (rhs0 != d->op->preload) PetscCall(VecScale(rhs0, scale));
  for (PetscInt k = 0; k < 12 * c->nelem; k++) {
    s->lambda[k] *= scale;
    s->gap[k] *= scale;
    s->anchor[k] *= scale; /* the preload's problem is linear in its scale, positions included */
  }
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* One solve's outer and inner iterations, returned and added to the loop's counters. */
static PetscErrorCode BoltDualCount(BoltDual *d, PetscInt outer, PetscInt inner, PetscInt *nouter, PetscInt *ninner)
{
  PetscFunctionBeginUser;
  *nouter = outer;
  *ninner = inner;
  d->outerTotal += outer;
  d->innerTotal += inner;
  d->outerMax = PetscMax(d->outerMax, outer);
  d->innerMax = PetscMax(d->innerMax, inner);
  PetscFunctionReturn(0);
}

/* Anti-cycling (-contact_cycle_close): after a two-set cycle the toggling points are closed, and
   for the rest of the step points may only close, so the set can only grow and the loop ends. */
static PetscErrorCode BoltDualCloseOnly(BoltDual *d, PetscBool cycling, PetscInt sets)
{
  BoltContactState *s       = d->op->state;
  PetscInt          nclosed = 0;

  PetscFunctionBeginUser;
  if (cycling) PetscCall(BoltContactStateCloseCycle(s, &nclosed));
  s->closeOnly = PETSC_TRUE;
  d->cycles++;
  if (d->monitor > 0 || d->cycles <= 10) PetscCall(PetscPrintf(d->op->comm, "%s step %" PetscInt_FMT ", t = %g s: the active set %s after %" PetscInt_FMT " outer iterations; from now on in this step points only close (%" PetscInt_FMT " points re-closed, %" PetscInt_FMT " active)%s\n", d->op->name, d->step, (double)d->time, cycling ? "cycles between two sets" : "has not settled", sets, nclosed, s->nactive, d->cycles == 10 ? "; further cycles are counted, not printed" : ""));
  PetscFunctionReturn(0);
}

/* The strict law's loop: the active set and the multipliers are updated together after every
   solve (a primal-dual active-set iteration on the augmented Lagrangian). Each iteration solves
   with the current multipliers and the stiff penalty of the closed pairs, takes the trial
   tractions lambda + P g as the new multipliers (they balance the solved displacement exactly),
   and re-decides every node pair from them: a closed pair opens under tension, an open one
   closes when it penetrates. The loop ends when the set holds and no closed pair is off its
   contact by more than the tolerance; the multipliers' error is then that tolerance times the
   structure's stiffness, not times the penalty. Warm-started from the last step, a step in
   which the set does not change costs one solve; a set change costs a factorisation. */
static PetscErrorCode BoltDualSolveActiveSet(BoltDual *d, Vec rhs0, Vec q, PetscBool refactor, PetscInt *nouter, PetscInt *ninner)
{
  BoltOperator     *op   = d->op;
  BoltContactState *s    = op->state;
  MPI_Comm          comm = op->comm;
  PetscInt          sets = 1, solves = 0, frictionStall = 0;
  PetscReal         frictionBest = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  s->closeOnly = PETSC_FALSE;
  if (d->extrapolate && d->dynamic) BoltContactStateExtrapolate(s);
  for (;;) {
    PetscInt  nchanged;
    PetscBool cycling;
    PetscReal rel, viol;

    if (refactor) PetscCall(BoltDualFactor(d));
    refactor = PETSC_FALSE;
    PetscCall(BoltDualSolveWithForces(d, rhs0, BoltContactStateForceMultipliers(s), q));
    PetscCall(BoltDualGapsOf(d, q, s->gap));
    BoltContactStateAnchorGaps(s, s->gap);
    solves++;
    PetscCall(PetscLogEventBegin(boltLog.contactUpdate, 0, 0, 0, 0));
    PetscCall(BoltContactStateAugment(s, &rel, &viol));
    PetscCall(PetscLogEventEnd(boltLog.contactUpdate, 0, 0, 0, 0));
    PetscCheck(!PetscIsInfOrNanReal(rel) && !PetscIsInfOrNanReal(viol), comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", op->name, d->step, (double)d->time);
    d->lastChange      = rel;
    d->lastPenetration = viol;
    if (d->calibrating) PetscCall(BoltDualCalibrate(d, rhs0, q));
    if (d->keepActiveSet && !d->dynamic) {
      cycling = PETSC_FALSE;
      nchanged = 0;
      if (s->law.friction && !s->stickOnly) { /* the set kept; its closed pairs still stick or slip (a ROM's preload, as the FOM's) */
        s->holdContact = PETSC_TRUE;
        PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
        s->holdContact = PETSC_FALSE;
      }
    } else PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
    if (d->monitor > 0) PetscCall(BoltContactMonitorOuter(d, sets, solves, nchanged, cycling));
    if (!nchanged && viol <= d->tolPenetration && (!s->law.friction || s->frictionChange <= d->tolFriction)) break;
    /* friction at its rounding floor: the set holds, and the slipping tractions' residual, within
       ten times the tolerance, has not halved in five solves (a reduced model's gaps, differences
       of basis rows, are that much less precise than the full model's) */
    if (s->law.friction && !nchanged && viol <= d->tolPenetration) {
      if (s->frictionChange < 0.5 * frictionBest) {
        frictionBest = s->frictionChange;
        frictionStall = 0;
      } else if (++frictionStall >= 5 && s->frictionChange <= 10 * d->tolFriction) break;
    } else frictionBest = PETSC_MAX_REAL, frictionStall = 0;
    if (nchanged) {
      sets++;
      refactor = PETSC_TRUE;
      if (d->closeCycles && !s->closeOnly && (cycling || 2 * sets >= d->maxOuter)) PetscCall(BoltDualCloseOnly(d, cycling, sets));
    }
    if ((nchanged && (sets > d->maxOuter || (cycling && !d->closeCycles))) || solves >= d->maxInner) {
      d->failures++;
      char friction[160] = "";

      if (s->law.friction) PetscCall(PetscSNPrintf(friction, sizeof(friction), ", and the slipping pairs' tractions move by %.3e of the largest pressure (tolerance %.1e: -contact_tol_friction)", (double)s->frictionChange, (double)d->tolFriction));
      PetscCheck(d->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: the contact loop did not converge at step %" PetscInt_FMT ", t = %g s: after %" PetscInt_FMT " solves and %" PetscInt_FMT " active sets, %" PetscInt_FMT " pairs changed and a closed pair is off its contact by %.3e m (tolerance %.1e)%s; raise -contact_max_outer / -contact_max_inner or add -contact_continue to go on with a warning", op->name, d->step, (double)d->time, solves, sets, nchanged, (double)viol, (double)d->tolPenetration, friction);
      PetscCall(PetscPrintf(comm, "WARNING %s: contact loop not converged at step %" PetscInt_FMT ", t = %g s; going on\n", op->name, d->step, (double)d->time));
      if (refactor) PetscCall(BoltDualFactor(d)); /* the next step starts consistent */
      break;
    }
  }
  {
    PetscReal pen, ten, comp, prod;
    PetscCall(BoltContactStateComplementarity(s, &pen, &ten, &comp, &prod));
    d->worstPenetration = PetscMax(d->worstPenetration, pen);
    d->worstTension     = PetscMax(d->worstTension, ten);
    d->worstCompression = PetscMax(d->worstCompression, comp);
    d->worstProduct     = PetscMax(d->worstProduct, prod);
  }
  if (d->dynamic) BoltContactStateEndStep(s);
  BoltContactStateEndSolve(s, d->dynamic);
  PetscCall(BoltDualCount(d, sets, solves, nouter, ninner));
  PetscFunctionReturn(0);
}

/* The dual loop for one solve: K_eff q = rhs0 - B' lambda with contact. */
PetscErrorCode BoltDualSolve(BoltDual *d, Vec rhs0, Vec q, PetscBool refactor, PetscInt *nouter, PetscInt *ninner)
{
  BoltOperator     *op   = d->op;
  BoltContactState *s    = op->state;
  MPI_Comm          comm = op->comm;
  PetscInt          outer, inner = 0, innerTotal = 0;

  PetscFunctionBeginUser;
  if (BoltContactStateLambdaIsTraction(s)) {
    PetscCall(BoltDualSolveActiveSet(d, rhs0, q, refactor, nouter, ninner));
    PetscFunctionReturn(0);
  }
  s->closeOnly = PETSC_FALSE;
  for (outer = 1;; outer++) {
    PetscInt  nchanged;
    PetscBool cycling;

    if (refactor) PetscCall(BoltDualFactor(d));
    /* under the penalty law the multipliers are not unknowns (zero, or a ROM's frozen preload) */
    if (!d->warmStart && s->augment) {
      PetscCall(PetscArrayzero(s->lambda, 12 * op->contact->nelem));
      BoltContactStateChanged(s);
    }
    PetscCall((*d->inner)(d, rhs0, q, &inner));
    innerTotal += inner;
    if (d->calibrating) PetscCall(BoltDualCalibrate(d, rhs0, q));
    if (d->monitor > 0 && s->augment) PetscCall(BoltContactMonitorTension(d));
    if (d->keepActiveSet && !d->dynamic) break;
    PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
    if (d->monitor > 0) PetscCall(BoltContactMonitorOuter(d, outer, inner, nchanged, cycling));
    if (!nchanged) break;
    refactor = PETSC_TRUE;
    /* Anti-cycling: once the set returns to the one of two iterations before, or has not settled
       in half the allowed iterations, points may only close for the rest of the step (after a
       two-set cycle its toggling points are closed first). The set can then only grow, so the
       loop ends; closed is the side that lets nothing penetrate. */
    if (d->closeCycles && !s->closeOnly && (cycling || 2 * outer >= d->maxOuter)) {
      PetscCall(BoltDualCloseOnly(d, cycling, outer));
      continue;
    }
    if (cycling || outer >= d->maxOuter) {
      if (cycling) d->cycles++;
      d->failures++;
      PetscCheck(d->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: the active set did not settle at step %" PetscInt_FMT ", t = %g s: %s after %" PetscInt_FMT " outer iterations (%" PetscInt_FMT " points changed, %" PetscInt_FMT " active); raise -contact_max_outer or add -contact_continue to go on with a warning", op->name, d->step, (double)d->time, cycling ? "it cycles between two sets" : "limit reached", outer, nchanged, s->nactive);
      PetscCall(PetscPrintf(comm, "WARNING %s: active set %s at step %" PetscInt_FMT ", t = %g s; going on\n", op->name, cycling ? "cycles between two sets" : "not settled", d->step, (double)d->time));
      /* the last solve used the previous set: refactor so the next step starts consistent */
      PetscCall(BoltDualFactor(d));
      break;
    }
  }
  PetscCall(BoltDualCount(d, outer, innerTotal, nouter, ninner));
  PetscFunctionReturn(0);
}

/* A static contact solve (K + K_c) q = rhs - B' lambda from the current contact state. With
   target > 0 the preload is calibrated on the way to that clamping force [N]: q, the operator's
   preload, rhs and the multipliers are scaled, and preloadScale says by how much. */
PetscErrorCode BoltDualSolveStatic(BoltDual *d, Vec rhs, Vec q, PetscReal target, PetscInt *nouter, PetscInt *ninner)
{
  PetscFunctionBeginUser;
  PetscCall(BoltDualSetEffective(d, PETSC_FALSE, 0, 0));
  d->step          = 0;
  d->time          = 0;
  d->preloadScale  = 1.0;
  d->preloadTarget = target;
  d->calibrating   = target > 0 ? PETSC_TRUE : PETSC_FALSE;
  BoltContactStateStaticStart(d->op->state);
  PetscCall(BoltDualSolve(d, rhs, q, PETSC_TRUE, nouter, ninner));
  d->calibrating = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualResetCounters(BoltDual *d)
{
  PetscFunctionBeginUser;
  d->factorizations = d->updates = d->solves = d->outerTotal = d->innerTotal = d->outerMax = d->innerMax = 0;
  d->worstPenetration = d->worstTension = d->worstCompression = d->worstProduct = 0;
  d->tContactStiffness = d->tDisplacements = d->tContactForces = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualView(BoltDual *d, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact loop (%s inner): %" PetscInt_FMT " factorisations, %" PetscInt_FMT " low-rank updates, %" PetscInt_FMT " solves, outer %" PetscInt_FMT " (max %" PetscInt_FMT "), inner %" PetscInt_FMT " (max %" PetscInt_FMT "/solve)\n", d->innerType, d->factorizations, d->updates, d->solves, d->outerTotal, d->outerMax, d->innerTotal, d->innerMax));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  phases: contact stiffness %.3f s, displacements %.3f s, contact forces %.3f s\n", (double)d->tContactStiffness, (double)d->tDisplacements, (double)d->tContactForces));
  PetscFunctionReturn(0);
}

/* Frees the factorisation and the effective matrix (the largest part of a finished run). */
PetscErrorCode BoltDualReleaseSolver(BoltDual *d)
{
  PetscFunctionBeginUser;
  if (d->ksp) PetscCall(KSPReset(d->ksp));
  PetscCall(MatDestroy(&d->Keff));
  PetscCall(MatDestroy(&d->Kstruct));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualDestroy(BoltDual **dp)
{
  BoltDual *d = *dp;

  PetscFunctionBeginUser;
  if (!d) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&d->Fc));
  PetscCall(VecDestroy(&d->work));
  PetscCall(VecDestroy(&d->qp));
  PetscCall(VecDestroy(&d->FcLambda));
  PetscCall(PetscFree4(d->cgR, d->cgP, d->cgAp, d->tnOpen));
  PetscCall(MatDestroy(&d->Keff));
  PetscCall(MatDestroy(&d->Kstruct));
  PetscCall(KSPDestroy(&d->ksp));
  PetscCall(PetscFree(*dp));
  PetscFunctionReturn(0);
}
