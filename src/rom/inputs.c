/* The ROM's input matrix B: unit relative forces at contact node pairs, the load and the
   preload (one column per bolt with several), as columns of a BV. */
#include "private/rom.h"

/* The preload's inputs: one column, or with several bolts (-preload_bolts) one per bolt, its 1 N
   layer pattern: the bolts' forces are calibrated apart (by the FOM), so the basis must hold
   each bolt's response, not one fixed mix of them. */
PetscInt ROMPreloadInputs(BoltLoadSet *loads)
{
  return PetscMax(1, BoltLoadSetBoltCount(loads));
}

PetscErrorCode ROMInsertPreloadInputs(BV B, PetscInt col, BoltLoadSet *loads)
{
  PetscFunctionBeginUser;
  if (!BoltLoadSetBoltCount(loads)) PetscCall(BVInsertVec(B, col, BoltLoadSetPreload(loads)));
  for (PetscInt b = 0; b < BoltLoadSetBoltCount(loads); b++) PetscCall(BVInsertVec(B, col + b, BoltLoadSetBoltUnit(loads, b)));
  PetscFunctionReturn(0);
}

/* Columns e_a - e_b for every matched node pair and direction (select: the pairs of the points
   it marks; NULL: all), then the load and the preload. *npairsOut (may be NULL): the pairs. */
PetscErrorCode ROMInputMatrix(BoltContactSet *c, BoltLoadSet *loads, Vec layout, const PetscBool select[], BV *B, PetscInt *ncols, PetscInt *npairsOut)
{
  PetscInt npairs, *pairs, col = 0;

  PetscFunctionBeginUser;
  PetscCall(BoltNodePairs(c, select, &npairs, &pairs));
  if (npairsOut) *npairsOut = npairs;
  *ncols = 3 * npairs + 1 + ROMPreloadInputs(loads);
  PetscCall(BVCreate(BoltMeshComm(BoltContactSetMesh(c)), B));
  PetscCall(BVSetSizesFromVec(*B, layout, *ncols));
  PetscCall(BVSetFromOptions(*B));
  PetscCall(BoltBVTolerateCancellation(*B));
  for (PetscInt i = 0; i < npairs; i++)
    for (PetscInt d = 0; d < 3; d++) {
      Vec v;
      PetscCall(BVGetColumn(*B, col, &v));
      PetscCall(BoltNodePairVector(pairs[2 * i], pairs[2 * i + 1], d, v));
      PetscCall(BVRestoreColumn(*B, col, &v));
      col++;
    }
  PetscCall(BVInsertVec(*B, col++, BoltLoadSetLoadUnit(loads)));
  PetscCall(ROMInsertPreloadInputs(*B, col, loads));
  PetscCall(PetscFree(pairs));
  PetscFunctionReturn(0);
}
