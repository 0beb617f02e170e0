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

/* y = M x (which 0) or K x (1): pointwise in modal coordinates (BoltOperatorSetDiagonalProducts). */
PetscErrorCode BoltOperatorMult(BoltOperator *op, PetscInt which, Vec x, Vec y)
{
  PetscFunctionBeginUser;
  if (op->Mdiag) PetscCall(VecPointwiseMult(y, which ? op->Kdiag : op->Mdiag, x));
  else PetscCall(MatMult(which ? op->K : op->M, x, y));
  PetscFunctionReturn(0);
}

/* The products with M and K (BoltOperatorMult) take their diagonals alone: the model's
   coordinates are its modes, where both are diagonal up to the rounding of their projection
   (a reduced model's; its factorisations keep the whole matrices, whose rounding the stiff
   contact penalty would otherwise lift to 1e-8 of the response). After BoltOperatorSetSystem. */
PetscErrorCode BoltOperatorSetDiagonalProducts(BoltOperator *op)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&op->Mdiag));
  PetscCall(VecDestroy(&op->Kdiag));
  PetscCall(MatCreateVecs(op->M, &op->Mdiag, NULL));
  PetscCall(MatCreateVecs(op->K, &op->Kdiag, NULL));
  PetscCall(MatGetDiagonal(op->M, op->Mdiag));
  PetscCall(MatGetDiagonal(op->K, op->Kdiag));
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

/* A stiffness added to K in the static solves only (referenced): a free ROM's rigid motions
   would leave K + K_c singular there, and a preload or contact force, self-balanced, does not
   move them, so the solution is the same (docs/reduction.md, "Free-free models"). */
PetscErrorCode BoltOperatorSetRigidStiffness(BoltOperator *op, Mat Krigid)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)Krigid));
  PetscCall(MatDestroy(&op->Krigid));
  op->Krigid = Krigid;
  PetscFunctionReturn(0);
}

/* The model's solver: its options prefix, its direct solver, whether every contact gap can be
   closed, whether the loop keeps K + a1 M + a4 C summed (small dense matrices). */
PetscErrorCode BoltOperatorSetSolver(BoltOperator *op, const char prefix[], MatSolverType type, PetscBool exactConstraints, PetscBool keepStructural)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(op->prefix, prefix, sizeof(op->prefix)));
  op->solverType       = type;
  op->exactConstraints = exactConstraints;
  op->keepStructural   = keepStructural;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltOperatorGetSolver(BoltOperator *op, const char *prefix[], MatSolverType *type)
{
  PetscFunctionBeginUser;
  if (prefix) *prefix = op->prefix;
  if (type) *type = op->solverType;
  PetscFunctionReturn(0);
}

/* One operation of the model's table (BOLT_OP_*), the way PETSc's shell matrices take theirs. */
PetscErrorCode BoltOperatorSetOperation(BoltOperator *op, BoltOperatorOp which, void (*fn)(void))
{
  PetscFunctionBeginUser;
  switch (which) {
  case BOLT_OP_CONTACT_DISPLACEMENTS: op->ops.contactDisplacements = (PetscErrorCode(*)(BoltOperator *, Vec))fn; break;
  case BOLT_OP_CONTACT_FORCES: op->ops.contactForces = (PetscErrorCode(*)(BoltOperator *, const PetscReal[], Vec))fn; break;
  case BOLT_OP_CONTACT_STIFFNESS: op->ops.contactStiffness = (PetscErrorCode(*)(BoltOperator *, Mat *))fn; break;
  case BOLT_OP_CONTACT_GAPS: op->ops.contactGaps = (PetscErrorCode(*)(BoltOperator *, Vec, PetscReal[]))fn; break;
  case BOLT_OP_OPEN_TRACTION: op->ops.openTraction = (PetscErrorCode(*)(BoltOperator *, PetscReal[]))fn; break;
  case BOLT_OP_CHECK_TRACTION: op->ops.checkTraction = (PetscErrorCode(*)(BoltOperator *, const PetscReal[], PetscReal[]))fn; break;
  case BOLT_OP_CHECK_GAPS: op->ops.checkGaps = (PetscErrorCode(*)(BoltOperator *, Vec, PetscReal[]))fn; break;
  case BOLT_OP_SET_KEPT: op->ops.setKept = (PetscErrorCode(*)(BoltOperator *, PetscBool *))fn; break;
  case BOLT_OP_PROBE: op->ops.probe = (PetscErrorCode(*)(BoltOperator *, Vec, PetscReal *))fn; break;
  case BOLT_OP_PAIR_FORCES: op->ops.pairForces = (PetscErrorCode(*)(BoltOperator *, Vec, PetscReal[]))fn; break;
  case BOLT_OP_VECTORS_SAVE: op->ops.vectorsSave = (PetscErrorCode(*)(BoltOperator *, PetscViewer, PetscInt, const char *const[], Vec[]))fn; break;
  case BOLT_OP_VECTORS_LOAD: op->ops.vectorsLoad = (PetscErrorCode(*)(BoltOperator *, PetscViewer, PetscInt, const char *const[], Vec[], PetscInt *))fn; break;
  case BOLT_OP_STATE_SAVE: op->ops.stateSave = (PetscErrorCode(*)(BoltOperator *, PetscViewer))fn; break;
  case BOLT_OP_STATE_LOAD: op->ops.stateLoad = (PetscErrorCode(*)(BoltOperator *, PetscViewer))fn; break;
  case BOLT_OP_VIEW: op->ops.view = (PetscErrorCode(*)(BoltOperator *, PetscViewer))fn; break;
  case BOLT_OP_DESTROY: op->ops.destroy = (PetscErrorCode(*)(BoltOperator *))fn; break;
  case BOLT_OP_FACTOR: op->ops.factor = (PetscErrorCode(*)(BoltOperator *, BoltDual *))fn; break;
  case BOLT_OP_HELD_TRACTIONS: op->ops.heldTractions = (PetscErrorCode(*)(BoltOperator *, Vec, Vec, Vec, PetscReal, const PetscBool **, const PetscReal **))fn; break;
  case BOLT_OP_SOLVE: op->ops.solve = (PetscErrorCode(*)(BoltOperator *, BoltDual *, Vec, Vec))fn; break;
  default: SETERRQ(op->comm, PETSC_ERR_ARG_OUTOFRANGE, "Unknown operator operation %d", (int)which);
  }
  PetscFunctionReturn(0);
}

/* The operations others call on a model. */
PetscErrorCode BoltOperatorContactDisplacements(BoltOperator *op, Vec q)
{
  return (*op->ops.contactDisplacements)(op, q);
}

PetscErrorCode BoltOperatorContactStiffness(BoltOperator *op, Mat *Kc)
{
  return (*op->ops.contactStiffness)(op, Kc);
}

PetscErrorCode BoltOperatorProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  return (*op->ops.probe)(op, q, value);
}

/* Each pair's resultant at q (BOLT_PAIR_FORCE values per pair, collective): the model's own, or
   the state's sum over its points. */
PetscErrorCode BoltOperatorPairForces(BoltOperator *op, Vec q, PetscReal force[])
{
  if (op->ops.pairForces) return (*op->ops.pairForces)(op, q, force);
  return BoltContactStatePairForces(op->state, force);
}

/* The model's context (its implementation's data) and what the others read of it. */
PetscErrorCode BoltOperatorSetContext(BoltOperator *op, void *ctx)
{
  PetscFunctionBeginUser;
  op->ctx = ctx;
  PetscFunctionReturn(0);
}

void *BoltOperatorContext(BoltOperator *op)
{
  return op->ctx;
}

BoltContactState *BoltOperatorState(BoltOperator *op)
{
  return op->state;
}

BoltContactSet *BoltOperatorContact(BoltOperator *op)
{
  return op->contact;
}

MPI_Comm BoltOperatorComm(BoltOperator *op)
{
  return op->comm;
}

Mat BoltOperatorMass(BoltOperator *op)
{
  return op->M;
}

Mat BoltOperatorStiffness(BoltOperator *op)
{
  return op->K;
}

/* Frees the damping matrix once the model has run (the Rayleigh coefficients stay). */
PetscErrorCode BoltOperatorReleaseDamping(BoltOperator *op)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&op->C));
  PetscFunctionReturn(0);
}

Vec BoltOperatorLoadVec(BoltOperator *op)
{
  return op->load;
}

Vec BoltOperatorPreloadVec(BoltOperator *op)
{
  return op->preload;
}

/* The load and preload become copies of the given vectors, the operator's own (a solve that
   scales them leaves the originals as they are). */
PetscErrorCode BoltOperatorCopyLoads(BoltOperator *op, Vec load, Vec preload)
{
  PetscFunctionBeginUser;
  if (load) {
    PetscCall(VecDestroy(&op->load));
    PetscCall(VecDuplicate(load, &op->load));
    PetscCall(VecCopy(load, op->load));
  }
  if (preload) {
    PetscCall(VecDestroy(&op->preload));
    PetscCall(VecDuplicate(preload, &op->preload));
    PetscCall(VecCopy(preload, op->preload));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltOperatorView(BoltOperator *op, PetscViewer viewer)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(op->K, &n, NULL));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s operator: %" PetscInt_FMT " unknowns, contact law %s (%s), direct solver %s\n", op->name, n, BoltContactStateLawType(op->state), BoltContactStateAugmented(op->state) ? "augmented Lagrangian" : "penalty", op->solverType));
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
  PetscCall(MatDestroy(&op->Krigid));
  PetscCall(VecDestroy(&op->Mdiag));
  PetscCall(VecDestroy(&op->Kdiag));
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
  const PetscInt    ne = BoltContactSetElementCount(op->contact);
  BoltPreloadState *st;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&st));
  PetscCall(VecDuplicate(q, &st->q));
  PetscCall(VecCopy(q, st->q));
  PetscCall(VecDuplicate(op->preload, &st->preload));
  PetscCall(VecCopy(op->preload, st->preload));
  PetscCall(PetscMalloc4(12 * ne + 1, &st->lambda, 4 * ne + 1, &st->active, 4 * ne + 1, &st->released, 12 * ne + 1, &st->anchor));
  PetscCall(PetscArraycpy(st->lambda, BoltContactStateLambda(s), 12 * ne));
  PetscCall(PetscArraycpy(st->anchor, BoltContactStateAnchor(s), 12 * ne));
  PetscCall(PetscArraycpy(st->active, BoltContactStateActive(s), 4 * ne));
  PetscCall(PetscArraycpy(st->released, BoltContactStateReleased(s), 4 * ne));
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
  PetscCall(PetscArraycpy(BoltContactStateLambda(s), st->lambda, 12 * BoltContactSetElementCount(op->contact)));
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
