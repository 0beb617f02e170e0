/* The full-order operator: the assembled M, C, K, the load vectors, and the contact DOFs
   reached through one scatter. Its contact law is the scene's (-contact_law, -contact_augment). */
#include "private/solve.h"

static PetscErrorCode FOMContactDisplacements(BoltOperator *op, Vec q)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactSetScatter(op->contact, BoltContactStateWork(op->state), q));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F)
{
  BoltContactSet *c = op->contact;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetForcesOf(c, BoltContactStateWork(op->state), lambda, F));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMContactStiffness(BoltOperator *op, Mat *Kc)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactStateStiffness(op->state, Kc));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  BoltFOMCtx *ctx = (BoltFOMCtx *)op->ctx;

  PetscFunctionBeginUser;
  PetscCall(BoltLoadSetProbe(ctx->loads, q, value));
  PetscFunctionReturn(0);
}

/* Checkpoints: each vector with dof_keys, the key of each DOF in the mesh as read
   (3 x vertex + component), so that a checkpoint does not depend on the partition. */
static PetscErrorCode FOMVectorsSave(BoltOperator *op, PetscViewer v, PetscInt n, const char *const names[], Vec x[])
{
  Vec keys;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshDofKeys(BoltContactSetMesh(op->contact), x[0], &keys));
  PetscCall(PetscObjectSetName((PetscObject)keys, "dof_keys"));
  PetscCall(VecView(keys, v));
  PetscCall(VecDestroy(&keys));
  PetscCall(BoltHDF5WriteVecs(v, op->comm, n, names, x, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* Every rank reads the keyed data and picks its own rows; missing counts the DOFs not found. */
static PetscErrorCode FOMVectorsLoad(BoltOperator *op, PetscViewer v, PetscInt nvec, const char *const names[], Vec y[], PetscInt *missing)
{
  BoltKeyIndex      *ix = NULL;
  Vec                keys;
  const PetscScalar *kmine;
  PetscReal         *kall, *x;
  PetscInt           n, nloc;

  PetscFunctionBeginUser;
  PetscCall(BoltReadAll(v, op->comm, "dof_keys", &n, &kall));
  PetscCall(BoltKeyIndexCreate(n, kall, &ix));
  PetscCall(PetscFree(kall));
  PetscCall(BoltMeshDofKeys(BoltContactSetMesh(op->contact), y[0], &keys));
  PetscCall(VecGetLocalSize(y[0], &nloc));
  PetscCall(VecGetArrayRead(keys, &kmine));
  for (PetscInt f = 0; f < nvec; f++) {
    PetscScalar *a;
    PetscCall(BoltReadAll(v, op->comm, names[f], &n, &x));
    PetscCall(VecGetArray(y[f], &a));
    for (PetscInt i = 0; i < nloc; i++) {
      PetscInt row;
      PetscCall(BoltKeyIndexFind(ix, (PetscInt)PetscRealPart(kmine[i]), &row));
      if (row < 0) (*missing)++;
      else a[i] = x[row];
    }
    PetscCall(VecRestoreArray(y[f], &a));
    PetscCall(PetscFree(x));
  }
  PetscCall(VecRestoreArrayRead(keys, &kmine));
  PetscCall(VecDestroy(&keys));
  PetscCall(BoltKeyIndexDestroy(&ix));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMDestroy(BoltOperator *op)
{
  PetscFunctionBeginUser;
  PetscCall(BoltFOMUpdateDestroy(&((BoltFOMCtx *)op->ctx)->update));
  PetscCall(PetscFree(op->ctx));
  PetscFunctionReturn(0);
}

/* transient: with the damping matrix; static solves need none (on the finest meshes it is a copy
   of the stiffness's pattern) */
PetscErrorCode BoltFOMCreate(BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, PetscBool transient, BoltOperator **opp)
{
  BoltOperator *op;
  BoltFOMCtx   *ctx;
  BoltMesh     *mesh;
  Mat           K, M;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMesh(asmb, &mesh));
  PetscCall(BoltAssemblerGetMatrices(asmb, &K, &M));
  PetscCall(BoltOperatorCreate(BoltMeshComm(mesh), "FOM", contact, &op));
  PetscCall(PetscNew(&ctx));
  ctx->loads           = loads;
  op->solverType       = MATSOLVERMUMPS;
  op->exactConstraints = PETSC_TRUE;
  /* the frictional law factorises about twice a step as pairs stick and slip: K + a1 M + a4 C is
     then summed once per set of Newmark coefficients and copied, not summed from K, M and C before
     every factorisation (the same bits; one more matrix of K's pattern in memory) */
  op->keepStructural = BoltContactSetHasFriction(contact);
  PetscCall(PetscStrncpy(op->prefix, "fom_", sizeof(op->prefix)));
  PetscCall(BoltOperatorSetSystem(op, M, NULL, K, BoltLoadSetLoad(loads), BoltLoadSetPreload(loads)));
  if (transient) {
    Mat       C;
    PetscReal alpha, beta;
    PetscCall(BoltAssemblerDamping(asmb, &C));
    PetscCall(BoltAssemblerGetRayleigh(asmb, &alpha, &beta));
    PetscCall(BoltOperatorSetDamping(op, C, alpha, beta));
    PetscCall(MatDestroy(&C));
  }
  op->ctx                      = ctx;
  op->ops.contactDisplacements = FOMContactDisplacements;
  op->ops.contactForces        = FOMContactForces;
  op->ops.contactStiffness     = FOMContactStiffness;
  op->ops.probe                = FOMProbe;
  op->ops.vectorsSave          = FOMVectorsSave;
  op->ops.vectorsLoad          = FOMVectorsLoad;
  op->ops.destroy              = FOMDestroy;
  *opp                         = op;
  PetscFunctionReturn(0);
}
