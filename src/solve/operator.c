/* BoltOperator: what the dual loop and the time integrator see of a model (fom.c, rom.c fill in
   the ops table), with its own contact state; and the preloaded state one model hands another. */
#include "private/solve.h"

/* An operator with a fresh contact state over the shared geometry; the model fills in the rest. */
PetscErrorCode BoltOperatorCreate(MPI_Comm comm, const char name[], BoltContactSet *contact, BoltOperator **opp)
{
  BoltOperator *op;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&op));
  op->comm    = comm;
  op->name    = name;
  op->contact = contact;
  PetscCall(BoltContactStateCreate(contact, &op->state));
  *opp = op;
  PetscFunctionReturn(0);
}

/* The model's matrices and load vectors (referenced; C may be NULL for static solves). */
PetscErrorCode BoltOperatorSetSystem(BoltOperator *op, Mat M, Mat C, Mat K, Vec load, Vec preload)
{
  PetscFunctionBeginUser;
  op->M       = M;
  op->C       = C;
  op->K       = K;
  op->load    = load;
  op->preload = preload;
  if (C) PetscCall(PetscObjectReference((PetscObject)C));
  PetscCall(PetscObjectReference((PetscObject)M));
  PetscCall(PetscObjectReference((PetscObject)K));
  PetscCall(PetscObjectReference((PetscObject)load));
  PetscCall(PetscObjectReference((PetscObject)preload));
  PetscFunctionReturn(0);
}

/* Rayleigh damping C = alpha M + beta K: the matrix for the effective matrix's factorisations
   (referenced), the coefficients for Newmark's right-hand sides and energy accounting, which then
   need M and K times the displacement alone. */
PetscErrorCode BoltOperatorSetDamping(BoltOperator *op, Mat C, PetscReal alpha, PetscReal beta)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)C));
  PetscCall(MatDestroy(&op->C));
  op->C           = C;
  op->rayleigh[0] = alpha;
  op->rayleigh[1] = beta;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltOperatorView(BoltOperator *op, PetscViewer viewer)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(op->K, &n, NULL));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s operator: %" PetscInt_FMT " unknowns, contact law %s (%s), direct solver %s\n", op->name, n, op->state->lawType, op->state->augment ? "augmented Lagrangian" : "penalty", op->solverType));
  if (op->ops.view) PetscCall((*op->ops.view)(op, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltOperatorDestroy(BoltOperator **opp)
{
  BoltOperator *op = *opp;

  PetscFunctionBeginUser;
  if (!op) PetscFunctionReturn(0);
  if (op->ops.destroy) PetscCall((*op->ops.destroy)(op));
  PetscCall(MatDestroy(&op->M));
  PetscCall(MatDestroy(&op->C));
  PetscCall(MatDestroy(&op->K));
  PetscCall(VecDestroy(&op->load));
  PetscCall(VecDestroy(&op->preload));
  PetscCall(BoltContactStateDestroy(&op->state));
  PetscCall(PetscFree(*opp));
  PetscFunctionReturn(0);
}

/* The static preloaded state of op just solved into q: the displacement, the calibrated preload,
   the multipliers, the active set and the sliding points, and the iterations it took. */
PetscErrorCode BoltPreloadStateCreate(BoltOperator *op, Vec q, PetscReal outer, PetscReal inner, BoltPreloadState **stp)
{
  BoltContactState *s  = op->state;
  const PetscInt    ne = op->contact->nelem;
  BoltPreloadState *st;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&st));
  PetscCall(VecDuplicate(q, &st->q));
  PetscCall(VecCopy(q, st->q));
  PetscCall(VecDuplicate(op->preload, &st->preload));
  PetscCall(VecCopy(op->preload, st->preload));
  PetscCall(PetscMalloc4(12 * ne + 1, &st->lambda, 4 * ne + 1, &st->active, 4 * ne + 1, &st->released, 12 * ne + 1, &st->anchor));
  PetscCall(PetscArraycpy(st->lambda, s->lambda, 12 * ne));
  PetscCall(PetscArraycpy(st->anchor, s->anchor, 12 * ne));
  PetscCall(PetscArraycpy(st->active, s->active, 4 * ne));
  PetscCall(PetscArraycpy(st->released, s->released, 4 * ne));
  st->outer = outer;
  st->inner = inner;
  *stp      = st;
  PetscFunctionReturn(0);
}

/* Puts a preloaded state in place of a solve, on an operator of the same scene and layout: q,
   the calibrated preload, the multipliers and the active set, every element due for a stiffness
   update. */
PetscErrorCode BoltPreloadStateApply(const BoltPreloadState *st, BoltOperator *op, Vec q)
{
  BoltContactState *s = op->state;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(st->q, q));
  PetscCall(VecCopy(st->preload, op->preload));
  PetscCall(PetscArraycpy(s->lambda, st->lambda, 12 * op->contact->nelem));
  PetscCall(BoltContactStateSetActive(s, st->active, st->released));
  BoltContactStateSetAnchors(s, st->anchor);
  PetscFunctionReturn(0);
}

/* The outer and inner iterations of the solve that found the state. */
PetscErrorCode BoltPreloadStateGetIterations(const BoltPreloadState *st, PetscReal *outer, PetscReal *inner)
{
  PetscFunctionBeginUser;
  *outer = st->outer;
  *inner = st->inner;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltPreloadStateDestroy(BoltPreloadState **stp)
{
  BoltPreloadState *st = *stp;

  PetscFunctionBeginUser;
  if (!st) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&st->q));
  PetscCall(VecDestroy(&st->preload));
  PetscCall(PetscFree4(st->lambda, st->active, st->released, st->anchor));
  PetscCall(PetscFree(*stp));
  PetscFunctionReturn(0);
}
