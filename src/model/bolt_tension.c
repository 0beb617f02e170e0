/* The clamp force of the bolt, read from a displacement: the axial force its stud carries beyond
   the two preload layers. The layers take the applied force F; the element layer between them is
   squeezed and holds part of it back; the rest, T, stretches the stud and clamps the joint. Summed
   over the upper layer's nodes (its equilibrium, projected on the axis a):
   T = sum a . (K_L u - f), K_L the stiffness of the cells between the layers alone and f the
   applied preload. This does not use the contact forces, so it checks the calibration, which
   does. */
#include "private/model.h"

/* A matrix of K's layout holding only the cells whose eight vertices all lie in the two layers. */
static PetscErrorCode LayerStiffness(BoltLoadSet *l, const char lower[], const char upper[], Mat K, Mat *KL, PetscInt *ncells)
{
  BoltMesh *m = l->mesh;
  PetscInt  nlow, nup, *low, *up, local = 0;
  PetscBT   inLayer;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshGroupVertices(m, lower, PETSC_FALSE, &nlow, &low));
  PetscCall(BoltMeshGroupVertices(m, upper, PETSC_FALSE, &nup, &up));
  PetscCall(PetscBTCreate(m->vEnd - m->vStart, &inLayer));
  for (PetscInt k = 0; k < nlow; k++) PetscCall(PetscBTSet(inLayer, low[k] - m->vStart));
  for (PetscInt k = 0; k < nup; k++) PetscCall(PetscBTSet(inLayer, up[k] - m->vStart));
  { /* K's layout, storage only for the few rows of the layer (not a copy of K's pattern) */
    PetscInt mloc, nloc, M, N;
    PetscCall(MatGetLocalSize(K, &mloc, &nloc));
    PetscCall(MatGetSize(K, &M, &N));
    PetscCall(MatCreateAIJ(m->comm, mloc, nloc, M, N, 0, NULL, 0, NULL, KL));
    PetscCall(MatSetOption(*KL, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  }
  for (PetscInt c = m->cStart; c < m->cEnd; c++) {
    const BoltMaterial *mat = &m->materials->mat[m->partMaterial[m->cellPart[c - m->cStart]]];
    PetscInt            verts[8], idx[24];
    PetscReal           X[24], Ke[576];
    PetscScalar         Ks[576];
    PetscBool           all = PETSC_TRUE;

    PetscCall(BoltMeshCellVertices(m, c, verts));
    for (PetscInt a = 0; a < 8 && all; a++) all = PetscBTLookup(inLayer, verts[a] - m->vStart) ? PETSC_TRUE : PETSC_FALSE;
    if (!all) continue;
    PetscCall(BoltMeshCellCoordinates(m, c, X));
    PetscCall(BoltMeshCellDofs(m, c, idx));
    PetscCall(Hex8Stiffness(X, mat->E, mat->nu, m->formulation, Ke));
    for (PetscInt k = 0; k < 576; k++) Ks[k] = Ke[k];
    PetscCall(MatSetValues(*KL, 24, idx, 24, idx, Ks, ADD_VALUES));
    local++;
  }
  PetscCall(MatAssemblyBegin(*KL, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*KL, MAT_FINAL_ASSEMBLY));
  PetscCall(MPIU_Allreduce(&local, ncells, 1, MPIU_INT, MPI_SUM, m->comm));
  PetscCall(PetscBTDestroy(&inLayer));
  PetscCall(PetscFree(low));
  PetscCall(PetscFree(up));
  PetscFunctionReturn(0);
}

/* The tension T [N] of bolt b's stud (b: an index of -preload_bolts, or 0 for the one bolt)
   under the displacement u and the applied preload f (K: the structural stiffness, for its
   layout); *found is false, and T is 0, when no element layer lies between the two layers (a
   clamped face as the lower layer presses the upper one: there is no stud). Collective. */
PetscErrorCode BoltLoadSetStudTension(BoltLoadSet *l, PetscInt b, Mat K, Vec u, Vec f, PetscReal *T, PetscBool *found)
{
  BoltMesh          *m = l->mesh;
  Mat                KL;
  Vec                y;
  PetscInt           ncells, nup, *up, rstart;
  PetscReal          local = 0;
  const PetscScalar *ya, *fa;

  PetscFunctionBeginUser;
  const char        *lower = l->nbolts ? l->boltGroup[b][0] : l->preloadGroup[0], *upper = l->nbolts ? l->boltGroup[b][1] : l->preloadGroup[1];

  PetscCheck(l->hasPreload && b >= 0 && b < PetscMax(l->nbolts, 1), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "No bolt %" PetscInt_FMT " with preload layers", b);
  PetscCall(LayerStiffness(l, lower, upper, K, &KL, &ncells));
  *T     = 0;
  *found = (PetscBool)(ncells > 0);
  if (!*found) {
    PetscCall(MatDestroy(&KL));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(u, &y));
  PetscCall(MatMult(KL, u, y));
  PetscCall(VecGetOwnershipRange(y, &rstart, NULL));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(BoltMeshGroupVertices(m, upper, PETSC_TRUE, &nup, &up));
  for (PetscInt k = 0; k < nup; k++) {
    PetscInt idx[3];
    PetscCall(BoltMeshVertexDofs(m, up[k], idx));
    for (PetscInt d = 0; d < 3; d++)
      if (idx[d] >= 0) local += l->preloadAxis[d] * PetscRealPart(ya[idx[d] - rstart] - fa[idx[d] - rstart]);
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(MPIU_Allreduce(&local, T, 1, MPIU_REAL, MPI_SUM, m->comm));
  PetscCall(PetscFree(up));
  PetscCall(VecDestroy(&y));
  PetscCall(MatDestroy(&KL));
  PetscFunctionReturn(0);
}
