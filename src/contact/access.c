/* What the contact set and a contact state tell the other modules. The per-point arrays are the
   state's own (3 values per point for the multipliers, gaps and anchors; one flag per point):
   the dual loop and the ROM read and write them in place, and call BoltContactStateChanged after
   a write, as a Vec's array is restored. */
#include "private/contact.h"

/* ------------------------------------------------------------------ the set */
BoltMesh *BoltContactSetMesh(const BoltContactSet *c)
{
  return c->mesh;
}

PetscInt BoltContactSetElementCount(const BoltContactSet *c)
{
  return c->nelem;
}

PetscInt BoltContactSetPairCount(const BoltContactSet *c)
{
  return c->npairs;
}

const char *BoltContactSetPairName(const BoltContactSet *c, PetscInt p)
{
  return c->pairName[p];
}

PetscReal BoltContactSetPairArea(const BoltContactSet *c, PetscInt p)
{
  return c->areaPerPair[p];
}

PetscReal BoltContactSetFriction(const BoltContactSet *c, PetscInt p)
{
  return c->friction[p];
}

/* The default normal penalty of pair p [Pa/m]. */
PetscReal BoltContactSetPairPenalty(const BoltContactSet *c, PetscInt p)
{
  return c->epsN[p];
}

PetscReal BoltContactSetPairStickStiffness(const BoltContactSet *c, PetscInt p)
{
  return c->stickStiffness[p];
}

/* Length of the local contact vector, and the global number of contact points. */
PetscInt BoltContactSetLocalSize(const BoltContactSet *c)
{
  return c->nlocal;
}

PetscInt BoltContactSetPointCountGlobal(const BoltContactSet *c)
{
  return c->ngpGlobal;
}

PetscInt BoltContactSetDofCount(const BoltContactSet *c)
{
  return c->contactDofs;
}

PetscInt BoltContactSetQuadrature(const BoltContactSet *c)
{
  return c->quadrature;
}

const char *BoltContactSetLawType(const BoltContactSet *c)
{
  return c->lawType;
}

PetscBool BoltContactSetReanchor(const BoltContactSet *c)
{
  return c->reanchor;
}

PetscBool BoltContactSetAugmented(const BoltContactSet *c)
{
  return c->augment;
}

PetscReal BoltContactSetGapTolerance(const BoltContactSet *c)
{
  return c->gapTolerance;
}

PetscReal BoltContactSetPenaltyFactor(const BoltContactSet *c)
{
  return c->penaltyFactor;
}

/* The law's settings that decide the contact state besides the pairs' own: the penetration at
   which an open point closes [m], the node matching tolerance (relative), the stick law's opening
   test (the strict laws judge at the nodes), and friction's slip tolerances. */
PetscReal BoltContactSetActivationGap(const BoltContactSet *c)
{
  return c->activationGap;
}

PetscReal BoltContactSetMatchTolerance(const BoltContactSet *c)
{
  return c->matchTolerance;
}

const char *BoltContactSetOpenTest(const BoltContactSet *c)
{
  return BoltContactSetIsComplementarity(c) || c->openTest == BOLT_OPEN_NODAL ? "nodal" : "gauss";
}

void BoltContactSetSlipTolerances(const BoltContactSet *c, PetscReal *angle, PetscReal *stiffnessRatio)
{
  *angle          = c->slipAngleTolerance;
  *stiffnessRatio = c->slipStiffnessRatio;
}

/* The shortest edge of a contact face (global) [m]. */
PetscReal BoltContactSetMinEdge(const BoltContactSet *c)
{
  return c->hMin;
}

/* Per element: 16 shape values (4 per point), 4 area weights, and 12 normal components. */
const PetscReal *BoltContactSetShapeValues(const BoltContactSet *c)
{
  return c->gpN;
}

const PetscReal *BoltContactSetWeights(const BoltContactSet *c)
{
  return c->gpW;
}

const PetscReal *BoltContactSetNormals(const BoltContactSet *c)
{
  return c->gpNormal;
}

/* 24 per element: the index of each DOF in the local contact vector, -1 where clamped. */
const PetscInt *BoltContactSetElementLocal(const BoltContactSet *c)
{
  return c->elemLocal;
}

/* The global DOF of each entry of the local contact vector, and each entry's vector area. */
const PetscInt *BoltContactSetLocalGlobal(const BoltContactSet *c)
{
  return c->localGlobal;
}

const PetscReal *BoltContactSetNodalArea(const BoltContactSet *c)
{
  return c->nodalArea;
}

/* The scatter from the global layout to the local contact vector, and a vector of that layout
   (a template: never written). */
VecScatter BoltContactSetScatterContext(const BoltContactSet *c)
{
  return c->scatter;
}

Vec BoltContactSetLayout(const BoltContactSet *c)
{
  return c->layout;
}

/* The summary's contact keys: DOFs, law, gap tolerance, and figures per pair. */
PetscErrorCode BoltContactSetSummaryWrite(const BoltContactSet *c, BoltJSON *j)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONInt(j, "contact_dofs", c->contactDofs));
  PetscCall(BoltJSONString(j, "contact_law", c->lawType));
  if (BoltContactSetIsComplementarity(c)) PetscCall(BoltJSONString(j, "contact_reclose", c->reanchor ? "stick" : "slide"));
  PetscCall(BoltJSONReal(j, "contact_gap_tolerance", c->gapTolerance));
  PetscCall(BoltContactSetPairValuesWrite(c, j, "contact_dofs_per_pair", c->contactDofsPerPair, NULL));
  PetscCall(BoltContactSetPairValuesWrite(c, j, "contact_elements_per_pair", c->elementsPerPair, NULL));
  PetscCall(BoltContactSetPairValuesWrite(c, j, "contact_area_per_pair", NULL, c->areaPerPair));
  PetscFunctionReturn(0);
}

/* A JSON object of one value per pair, keyed by the pair names: the integers vi, or else the
   reals vr. */
PetscErrorCode BoltContactSetPairValuesWrite(const BoltContactSet *c, BoltJSON *j, const char key[], const PetscInt vi[], const PetscReal vr[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONNamedValues(j, key, c->npairs, c->pairName, vi, vr));
  PetscFunctionReturn(0);
}
