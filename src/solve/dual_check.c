/* The contact conditions at every node pair after every -contact_check_every-th converged step of
   the transient (25 by default: docs/decisions.md), from the
   model's own displacements: a reduced model holds part of its pairs in their state and computes
   their gaps only now and then; this check recomputes them all and says whether a held pair
   would have changed state (a warning at the first, and a flag in the summary). */
#include "private/solve.h"

PetscErrorCode BoltDualCheckStep(BoltDual *d, Vec q, Vec v, Vec a, PetscReal amp)
{
  BoltOperator     *op = d->op;
  BoltContactState *s  = op->state;
  const PetscBool  *tied  = NULL;
  const PetscReal  *tTied = NULL;
  PetscReal         worst[3];
  PetscInt          leaving;
  PetscBool         given;
  PetscLogDouble    t0, t1;

  PetscFunctionBeginUser;
  if (!d->dynamic || !d->checkEvery || d->step % d->checkEvery || !BoltContactSetPointCountGlobal(op->contact)) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_CHECK, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  if (!d->checkGaps) PetscCall(PetscMalloc1(12 * BoltContactSetElementCount(op->contact) + 1, &d->checkGaps));
  if (op->ops.checkGaps) PetscCall(op->ops.checkGaps(op, q, d->checkGaps));
  else {
    PetscCall(BoltOperatorContactDisplacements(op, q));
    PetscCall(BoltContactSetGapsOf(op->contact, BoltContactStateWork(s), d->checkGaps));
  }
  /* a pair its basis ties has no gap to tell: its force comes from the model's residual there */
  if (op->ops.heldTractions) PetscCall(op->ops.heldTractions(op, q, v, a, amp, &tied, &tTied));
  given = (PetscBool)(op->ops.checkTraction && !tied);
  if (given) { /* the model's own form of the opening test's traction */
    const PetscInt ngp = 4 * BoltContactSetElementCount(op->contact);
    if (!d->checkTn) PetscCall(PetscMalloc2(3 * ngp + 1, &d->checkAnchored, ngp + 1, &d->checkTn));
    PetscCall(PetscArraycpy(d->checkAnchored, d->checkGaps, 3 * ngp));
    BoltContactStateAnchorGaps(s, d->checkAnchored);
    PetscCall(op->ops.checkTraction(op, d->checkAnchored, d->checkTn));
  }
  PetscCall(BoltContactStateCheck(s, d->checkGaps, tied, tTied, given ? d->checkTn : NULL, worst, &leaving));
  for (PetscInt k = 0; k < 3; k++) d->checkWorst[k] = PetscMax(d->checkWorst[k], worst[k]);
  if (leaving && !d->checkLeaving) {
    d->checkFirstStep = d->step;
    d->checkFirstTime = d->time;
    PetscCall(PetscPrintf(op->comm, "WARNING %s: at step %" PetscInt_FMT ", t = %g s, %" PetscInt_FMT " held contact points would leave their state; the model keeps them, so results near them are suspect\n", op->name, d->step, (double)d->time, leaving));
  }
  d->checkLeaving += leaving;
  d->checkSteps++;
  PetscCall(PetscTime(&t1));
  d->tCheck += t1 - t0;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_CHECK, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The check's summary keys: what it found over the checked steps, and what it cost. */
PetscErrorCode BoltDualCheckSummaryWrite(BoltDual *d, BoltJSON *j)
{
  PetscFunctionBeginUser;
  if (!d->checkSteps) PetscFunctionReturn(0);
  PetscCall(BoltJSONBeginObject(j, "contact_check"));
  PetscCall(BoltJSONInt(j, "steps_checked", d->checkSteps));
  PetscCall(BoltJSONReal(j, "penetration_max_m", d->checkWorst[0]));
  PetscCall(BoltJSONReal(j, "tension_max_pa", d->checkWorst[1]));
  PetscCall(BoltJSONReal(j, "cone_excess_max", d->checkWorst[2]));
  PetscCall(BoltJSONInt(j, "held_points_leaving", d->checkLeaving));
  PetscCall(BoltJSONInt(j, "held_first_step", d->checkLeaving ? d->checkFirstStep : -1));
  PetscCall(BoltJSONReal(j, "held_first_time", d->checkLeaving ? d->checkFirstTime : -1));
  PetscCall(BoltJSONReal(j, "seconds", d->tCheck));
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}
