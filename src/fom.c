/* The full-order operator: the assembled M, C, K, the load vectors, and the contact DOFs
   reached through one scatter. */
#include "boltrom.h"

typedef struct {
  BoltLoadSet *loads;
} BoltFOMCtx;

static PetscErrorCode FOMContactDisplacements(BoltOperator *op, Vec q)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactSetScatter(op->contact, q));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F)
{
  BoltContactSet *c = op->contact;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetForcesOf(c, lambda));
  PetscCall(VecZeroEntries(F));
  PetscCall(VecScatterBegin(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(c->scatter, c->fc, F, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMContactStiffness(BoltOperator *op, Mat *Kc)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactSetStiffness(op->contact, Kc));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  BoltFOMCtx *ctx = (BoltFOMCtx *)op->ctx;

  PetscFunctionBeginUser;
  PetscCall(BoltLoadSetProbe(ctx->loads, q, value));
  PetscFunctionReturn(0);
}

/* transient: with the damping matrix; static solves need none (at 562k DOFs it is a 1.5 GB copy
   of the stiffness's pattern) */
PetscErrorCode BoltFOMCreate(BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, PetscBool transient, BoltOperator **opp)
{
  BoltOperator *op;
  BoltFOMCtx   *ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&op));
  PetscCall(PetscNew(&ctx));
  ctx->loads = loads;
  op->name       = "FOM";
  op->comm       = asmb->mesh->comm;
  op->solverType = MATSOLVERMUMPS;
  op->exactConstraints = PETSC_TRUE;
  op->augment          = contact->augmentOption;
  op->meshLayout       = PETSC_TRUE;
  PetscCall(PetscStrncpy(op->prefix, "fom_", sizeof(op->prefix)));
  op->M = asmb->M;
  op->K = asmb->K;
  PetscCall(PetscObjectReference((PetscObject)op->M));
  PetscCall(PetscObjectReference((PetscObject)op->K));
  if (transient) PetscCall(BoltAssemblerDamping(asmb, &op->C));
  op->load    = loads->load;
  op->preload = loads->preload;
  PetscCall(PetscObjectReference((PetscObject)op->load));
  PetscCall(PetscObjectReference((PetscObject)op->preload));
  op->contact              = contact;
  op->ctx                  = ctx;
  op->contactDisplacements = FOMContactDisplacements;
  op->contactForces        = FOMContactForces;
  op->contactStiffness     = FOMContactStiffness;
  op->probe                = FOMProbe;
  *opp                     = op;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltFOMDestroy(BoltOperator **opp)
{
  BoltOperator *op = *opp;

  PetscFunctionBeginUser;
  if (!op) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&op->M));
  PetscCall(MatDestroy(&op->K));
  PetscCall(MatDestroy(&op->C));
  PetscCall(VecDestroy(&op->load));
  PetscCall(VecDestroy(&op->preload));
  PetscCall(PetscFree(op->ctx));
  PetscCall(PetscFree(*opp));
  PetscFunctionReturn(0);
}
