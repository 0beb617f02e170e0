/* What the mesh tells the other modules about itself: its communicator and DMPlex, global sizes,
   parts, clamp and support groups, and its part of the run summary. Points (cells, vertices) are
   DMPlex points: other modules take their ranges from the DM's strata. */
#include "private/model.h"

MPI_Comm BoltMeshComm(const BoltMesh *m)
{
  return m->comm;
}

DM BoltMeshDM(const BoltMesh *m)
{
  return m->dm;
}

const char *BoltMeshFileName(const BoltMesh *m)
{
  return m->filename;
}

Hex8Formulation BoltMeshFormulation(const BoltMesh *m)
{
  return m->formulation;
}

PetscInt BoltMeshVertexCountGlobal(const BoltMesh *m)
{
  return m->nverticesGlobal;
}

PetscInt BoltMeshCellCountGlobal(const BoltMesh *m)
{
  return m->ncellsGlobal;
}

PetscInt BoltMeshPartCount(const BoltMesh *m)
{
  return m->nparts;
}

const char *BoltMeshPartName(const BoltMesh *m, PetscInt p)
{
  return m->partName[p];
}

/* The part of local cell c (a DMPlex height-0 point). */
PetscInt BoltMeshCellPart(const BoltMesh *m, PetscInt c)
{
  return m->cellPart[c - m->cStart];
}

/* The number of local point p in the mesh as it was read: a key that does not depend on the
   partition. */
PetscInt BoltMeshPointOriginal(const BoltMesh *m, PetscInt p)
{
  return m->pointOriginal[p - m->pStart];
}

/* The clamp group's name, or NULL when the clamp is not removed from the system. */
const char *BoltMeshClampGroup(const BoltMesh *m)
{
  return m->clamp ? m->clampGroup : NULL;
}

/* The support group's name ("" without one). */
const char *BoltMeshSupportGroup(const BoltMesh *m)
{
  return m->supportGroup;
}

/* The components held at the support group (ascending), and their count. */
PetscInt BoltMeshSupportComponents(const BoltMesh *m, const PetscInt **components)
{
  *components = m->supportComponents;
  return m->nsupportComponents;
}

/* A JSON object of one value per part, keyed by the part names: the integers vi, or else the
   reals vr. */
PetscErrorCode BoltMeshPartValuesWrite(const BoltMesh *m, BoltJSON *j, const char key[], const PetscInt vi[], const PetscReal vr[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONNamedValues(j, key, m->nparts, m->partName, vi, vr));
  PetscFunctionReturn(0);
}

/* The summary's mesh keys: file, element, partition and sizes. */
PetscErrorCode BoltMeshSummaryWrite(const BoltMesh *m, BoltJSON *j)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONString(j, "mesh", m->filename));
  PetscCall(BoltJSONString(j, "element", m->formulation == HEX8_FULL ? "full" : "incompatible"));
  PetscCall(BoltJSONString(j, "partitioner", m->partitioner));
  PetscCall(BoltJSONInt(j, "edge_cut", m->edgeCut));
  PetscCall(BoltJSONInt(j, "nodes", m->nverticesGlobal));
  PetscCall(BoltJSONInt(j, "elements", m->ncellsGlobal));
  PetscCall(BoltJSONInt(j, "dofs", 3 * m->nverticesGlobal));
  PetscCall(BoltJSONInt(j, "free_dofs", m->ndofsFree));
  PetscFunctionReturn(0);
}
