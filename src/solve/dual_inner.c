/* The dual loop's inner solvers, registered by name (-contact_inner): Uzawa's augmentations
   and the conjugate gradients on the multipliers of the active set, with their monitor. */
#include "private/solve.h"

static PetscErrorCode BoltDualMonitorCG(BoltDual *, Vec, Vec, PetscInt, PetscReal, PetscReal, PetscReal, const PetscReal[], PetscReal, PetscReal[]);

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
    PetscCall(BoltDualGapsOf(d, q, BoltContactStateGap(s)));
    BoltContactStateAnchorGaps(s, BoltContactStateGap(s));
    PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
    PetscCall(BoltContactStateAugment(s, &rel, &pen));
    PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
    d->lastChange      = rel;
    d->lastPenetration = pen;
    PetscCheck(!PetscIsInfOrNanReal(rel) && !PetscIsInfOrNanReal(pen), d->op->comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", d->op->name, d->step, (double)d->time);
    if (!BoltContactStateAugmented(s)) break;
    if (rel <= d->tolLambda && (pen <= d->tolPenetration || !d->op->exactConstraints)) break;
    if (inner >= d->maxInner) {
      PetscCall(BoltDualInnerFailure(d, inner, rel, pen));
      break;
    }
  }
  *ninner = inner;
  PetscFunctionReturn(0);
}

/* Inner loop by conjugate gradients on the multipliers. For a fixed active set the gaps are
   affine in the multipliers, g(lambda) = g(0) - A lambda with A = B K_eff^-1 B' W symmetric
   in the area-weighted product, and the augmentations are Richardson iterations towards
   g = 0; CG reaches the same multipliers in far fewer solves (one solve per iteration). Under
   the penalty law there are no multiplier unknowns: one solve, as Uzawa. */
static PetscErrorCode BoltDualInnerCG(BoltDual *d, Vec rhs0, Vec q, PetscInt *ninner)
{
  BoltContactState *s  = d->op->state;
  BoltContactSet   *c  = BoltContactStateSet(s);
  PetscInt          ng = 12 * BoltContactSetElementCount(c), inner;
  PetscReal        *lambda = BoltContactStateLambda(s);
  const PetscBool  *active = BoltContactStateActive(s);
  PetscReal        *r = d->cgR, *p = d->cgP, *Ap = d->cgAp, rr, rr0, pAp, alpha, rel = 0, pen = 0, lnorm, pnorm;

  PetscFunctionBeginUser;
  if (!BoltContactStateAugmented(s)) {
    PetscCall(BoltDualInnerUzawa(d, rhs0, q, ninner));
    PetscFunctionReturn(0);
  }
  for (PetscInt gp = 0; gp < ng / 3; gp++)
    if (!active[gp]) lambda[3 * gp] = lambda[3 * gp + 1] = lambda[3 * gp + 2] = 0;
  BoltContactStateChanged(s);
  PetscCall(BoltDualSolveWithForces(d, rhs0, lambda, q));
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
      lambda[k] += alpha * p[k];
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
  PetscCall(BoltDualGapsOf(d, q, BoltContactStateGap(s)));
  *ninner = inner;
  PetscFunctionReturn(0);
}

/* The true residual of the CG iteration for -contact_monitor 2: the gaps of q and of a fresh
   solve with the current multipliers (their difference is the drift of the recurrence). */
static PetscErrorCode BoltDualMonitorCG(BoltDual *d, Vec rhs0, Vec q, PetscInt inner, PetscReal rel, PetscReal pen, PetscReal alpha, const PetscReal r[], PetscReal rr0, PetscReal work[])
{
  BoltContactState *s  = d->op->state;
  PetscInt          ng = 12 * BoltContactSetElementCount(BoltContactStateSet(s));
  PetscReal         rrN, trueRes = 0, drift = 0;

  PetscFunctionBeginUser;
  PetscCall(BoltContactStateDot(s, r, r, &rrN));
  if (inner % 10 == 0) {
    PetscReal *tg, dd, tt;
    Vec        qt;
    PetscCall(PetscMalloc1(ng + 1, &tg));
    PetscCall(VecDuplicate(q, &qt));
    PetscCall(BoltDualSolveWithForces(d, rhs0, BoltContactStateLambda(s), qt));
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
PetscErrorCode BoltDualInnerRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (BoltDualInnerList) PetscFunctionReturn(0);
  PetscCall(BoltDualInnerRegister("uzawa", BoltDualInnerUzawa));
  PetscCall(BoltDualInnerRegister("cg", BoltDualInnerCG));
  PetscCall(PetscRegisterFinalize(BoltDualInnerFinalize));
  PetscFunctionReturn(0);
}
