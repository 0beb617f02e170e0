/* What the other modules ask of the mesh: groups as points or vertices, a face's or a cell's
   vertices and coordinates, the DOFs of a vertex or a cell (-1 where held), keys that name DOFs
   on any partition, and vertex fields. */
#include "private/model.h"
#include <metis.h>
#include <stdio.h>
#include <stdlib.h>
#include <scotch/scotch.h> /* for SCOTCH_randomSeed: the one PT-Scotch that PETSc links */

/* Closure vertex order of a DMPlex hexahedron -> gmsh/VTK order used by the element kernels. */
static const PetscInt plexToGmshHex[8] = {0, 3, 2, 1, 4, 5, 6, 7};

PetscErrorCode BoltMeshHasGroup(BoltMesh *m, const char name[], PetscBool *has)
{
  PetscInt local = 0, global;
  DMLabel  label;

  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(m->dm, name, &label));
  if (label) {
    IS ids;
    PetscCall(DMLabelGetValueIS(label, &ids));
    PetscCall(ISGetLocalSize(ids, &local));
    PetscCall(ISDestroy(&ids));
  }
  PetscCall(MPIU_Allreduce(&local, &global, 1, MPIU_INT, MPI_MAX, m->comm));
  *has = global > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Every point of a group (all values of its label): unique, sorted; owned ones only if asked. */
PetscErrorCode BoltMeshGroupPoints(BoltMesh *m, const char name[], PetscBool ownedOnly, PetscInt *npoints, PetscInt **points)
{
  DMLabel  label;
  PetscInt n = 0, cap = 64, *pts;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(cap, &pts));
  PetscCall(DMGetLabel(m->dm, name, &label));
  if (label) {
    IS              ids;
    const PetscInt *id;
    PetscInt        nids;

    PetscCall(DMLabelGetValueIS(label, &ids));
    PetscCall(ISGetLocalSize(ids, &nids));
    PetscCall(ISGetIndices(ids, &id));
    for (PetscInt i = 0; i < nids; i++) {
      IS              stratum;
      const PetscInt *p;
      PetscInt        np;

      PetscCall(DMLabelGetStratumIS(label, id[i], &stratum));
      if (!stratum) continue;
      PetscCall(ISGetLocalSize(stratum, &np));
      PetscCall(ISGetIndices(stratum, &p));
      for (PetscInt j = 0; j < np; j++) {
        if (ownedOnly && PetscBTLookup(m->pointGhost, p[j] - m->pStart)) continue;
        if (n == cap) {
          cap *= 2;
          PetscCall(PetscRealloc(sizeof(PetscInt) * cap, &pts));
        }
        pts[n++] = p[j];
      }
      PetscCall(ISRestoreIndices(stratum, &p));
      PetscCall(ISDestroy(&stratum));
    }
    PetscCall(ISRestoreIndices(ids, &id));
    PetscCall(ISDestroy(&ids));
  }
  PetscCall(PetscSortRemoveDupsInt(&n, pts));
  *npoints = n;
  *points  = pts;
  PetscFunctionReturn(0);
}

/* Vertices in the closure of every point of a group; unique, sorted; owned ones only if asked. */
PetscErrorCode BoltMeshGroupVertices(BoltMesh *m, const char name[], PetscBool ownedOnly, PetscInt *nv, PetscInt **verts)
{
  PetscInt  np, *pts, n = 0, npt = m->pEnd - m->pStart, *v;
  PetscInt *mark, *markRoot;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshGroupPoints(m, name, PETSC_FALSE, &np, &pts));
  PetscCall(PetscCalloc2(npt + 1, &mark, npt + 1, &markRoot));
  for (PetscInt j = 0; j < np; j++) {
    PetscInt *cl = NULL, ncl;

    PetscCall(DMPlexGetTransitiveClosure(m->dm, pts[j], PETSC_TRUE, &ncl, &cl));
    for (PetscInt k = 0; k < ncl; k++) {
      PetscInt q = cl[2 * k];
      if (q >= m->vStart && q < m->vEnd) mark[q - m->pStart] = 1;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(m->dm, pts[j], PETSC_TRUE, &ncl, &cl));
  }
  PetscCall(PetscFree(pts));
  if (ownedOnly) {
    /* A vertex on the rim of the group can be owned by a rank that holds none of the group's
       faces (only a neighbouring cell): send the marks of ghost copies to the owners, or the
       vertex would be counted by no rank (the result would then depend on the partition). */
    PetscSF sf;
    PetscCall(DMGetPointSF(m->dm, &sf));
    PetscCall(PetscArraycpy(markRoot, mark, npt));
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, mark, markRoot, MPI_MAX));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, mark, markRoot, MPI_MAX));
    PetscCall(PetscArraycpy(mark, markRoot, npt));
  }
  PetscCall(PetscMalloc1(m->vEnd - m->vStart + 1, &v));
  for (PetscInt q = m->vStart; q < m->vEnd; q++)
    if (mark[q - m->pStart] && !(ownedOnly && PetscBTLookup(m->pointGhost, q - m->pStart))) v[n++] = q;
  PetscCall(PetscFree2(mark, markRoot));
  *nv    = n;
  *verts = v;
  PetscFunctionReturn(0);
}

/* The vertices of a face in closure order (cyclic for a quadrilateral) and their coordinates. */
PetscErrorCode BoltMeshFaceVertices(BoltMesh *m, PetscInt face, PetscInt *nv, PetscInt verts[4], PetscReal X[12])
{
  PetscInt          *cl = NULL, ncl;
  Vec                coords;
  PetscSection       cs;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  *nv = 0;
  PetscCall(DMPlexGetTransitiveClosure(m->dm, face, PETSC_TRUE, &ncl, &cl));
  for (PetscInt q = 0; q < ncl; q++)
    if (cl[2 * q] >= m->vStart && cl[2 * q] < m->vEnd && *nv < 4) verts[(*nv)++] = cl[2 * q];
  PetscCall(DMPlexRestoreTransitiveClosure(m->dm, face, PETSC_TRUE, &ncl, &cl));
  PetscCall(DMGetCoordinatesLocal(m->dm, &coords));
  PetscCall(DMGetCoordinateSection(m->dm, &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt a = 0; a < *nv; a++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, verts[a], &off));
    for (PetscInt d = 0; d < 3; d++) X[3 * a + d] = PetscRealPart(x[off + d]);
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshCellVertices(BoltMesh *m, PetscInt c, PetscInt verts[8])
{
  PetscInt *cl = NULL, ncl, n = 0, tmp[8];

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(m->dm, c, PETSC_TRUE, &ncl, &cl));
  for (PetscInt k = 0; k < ncl; k++)
    if (cl[2 * k] >= m->vStart && cl[2 * k] < m->vEnd) tmp[n++] = cl[2 * k];
  PetscCall(DMPlexRestoreTransitiveClosure(m->dm, c, PETSC_TRUE, &ncl, &cl));
  PetscCheck(n == 8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cell %" PetscInt_FMT " has %" PetscInt_FMT " vertices", c, n);
  for (PetscInt a = 0; a < 8; a++) verts[a] = tmp[plexToGmshHex[a]];
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshCellCoordinates(BoltMesh *m, PetscInt c, PetscReal X[24])
{
  PetscInt           verts[8];
  Vec                coords;
  PetscSection       cs;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshCellVertices(m, c, verts));
  PetscCall(DMGetCoordinatesLocal(m->dm, &coords));
  PetscCall(DMGetCoordinateSection(m->dm, &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt a = 0; a < 8; a++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, verts[a], &off));
    for (PetscInt d = 0; d < 3; d++) X[3 * a + d] = PetscRealPart(x[off + d]);
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshVertexDofs(BoltMesh *m, PetscInt v, PetscInt idx[3])
{
  PetscSection    gs, ls;
  PetscInt        off, cdof, k = 0;
  const PetscInt *held = NULL;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalSection(m->dm, &gs));
  PetscCall(DMGetLocalSection(m->dm, &ls));
  PetscCall(PetscSectionGetOffset(gs, v, &off));
  PetscCall(PetscSectionGetConstraintDof(ls, v, &cdof));
  if (cdof) PetscCall(PetscSectionGetConstraintIndices(ls, v, &held));
  if (off < 0) off = -(off + 1);
  /* the global vector keeps a node's free components, in order, from its offset on */
  for (PetscInt d = 0; d < 3; d++) {
    PetscBool isHeld = PETSC_FALSE;
    for (PetscInt j = 0; j < cdof; j++)
      if (held[j] == d) isHeld = PETSC_TRUE;
    idx[d] = isHeld ? -1 : off + k++;
  }
  PetscFunctionReturn(0);
}

/* Sets or adds a node's three values at its free components (idx from BoltMeshVertexDofs, -1
   where clamped or supported: VecSetValues would write before the array, unchecked in an
   optimised PETSc). */
PetscErrorCode BoltMeshSetNodeValues(Vec f, const PetscInt idx[3], const PetscScalar v[3], InsertMode mode)
{
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; d++)
    if (idx[d] >= 0) PetscCall(VecSetValue(f, idx[d], v[d], mode));
  PetscFunctionReturn(0);
}

/* A key for every owned DOF that does not depend on the partition or the number of ranks:
   3 x (the vertex's point number in the mesh as read) + component. Files that hold rows at
   chosen DOFs (the ROM file) are indexed by it, so that any rank count can read them. */
PetscErrorCode BoltMeshDofKeys(BoltMesh *m, Vec layout, Vec *keys)
{
  PetscInt idx[3];

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(layout, keys));
  PetscCall(VecSet(*keys, -1.0));
  for (PetscInt v = m->vStart; v < m->vEnd; v++) {
    PetscBool owned;
    PetscCall(BoltMeshVertexOwned(m, v, &owned));
    if (!owned) continue;
    PetscCall(BoltMeshVertexDofs(m, v, idx));
    for (PetscInt d = 0; d < 3; d++)
      if (idx[d] >= 0) PetscCall(VecSetValue(*keys, idx[d], (PetscScalar)(3 * m->pointOriginal[v - m->pStart] + d), INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(*keys));
  PetscCall(VecAssemblyEnd(*keys));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshCellDofs(BoltMesh *m, PetscInt c, PetscInt idx[24])
{
  PetscInt verts[8];

  PetscFunctionBeginUser;
  PetscCall(BoltMeshCellVertices(m, c, verts));
  for (PetscInt a = 0; a < 8; a++) PetscCall(BoltMeshVertexDofs(m, verts[a], &idx[3 * a]));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshVertexOwned(BoltMesh *m, PetscInt v, PetscBool *owned)
{
  PetscFunctionBeginUser;
  *owned = PetscBTLookup(m->pointGhost, v - m->pStart) ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Sets a global vector from f(x, vertex part) at every owned, unclamped vertex. */
PetscErrorCode BoltMeshFillVertexField(BoltMesh *m, PetscErrorCode (*f)(const PetscReal[3], PetscInt, PetscReal[3], void *), void *ctx, Vec u)
{
  Vec                coords;
  PetscSection       cs;
  const PetscScalar *x;
  PetscInt          *vpart;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m->vEnd - m->vStart + 1, &vpart));
  for (PetscInt v = 0; v < m->vEnd - m->vStart; v++) vpart[v] = PETSC_MAX_INT;
  for (PetscInt c = m->cStart; c < m->cEnd; c++) {
    PetscInt verts[8];
    PetscCall(BoltMeshCellVertices(m, c, verts));
    for (PetscInt a = 0; a < 8; a++) vpart[verts[a] - m->vStart] = PetscMin(vpart[verts[a] - m->vStart], m->cellPart[c - m->cStart]);
  }
  PetscCall(DMGetCoordinatesLocal(m->dm, &coords));
  PetscCall(DMGetCoordinateSection(m->dm, &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt v = m->vStart; v < m->vEnd; v++) {
    PetscInt    off, idx[3];
    PetscReal   X[3], val[3];
    PetscScalar sv[3];

    if (PetscBTLookup(m->pointGhost, v - m->pStart)) continue;
    PetscCall(BoltMeshVertexDofs(m, v, idx));
    if (idx[0] < 0 && idx[1] < 0 && idx[2] < 0) continue;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < 3; d++) X[d] = PetscRealPart(x[off + d]);
    PetscCall(f(X, vpart[v - m->vStart], val, ctx));
    for (PetscInt d = 0; d < 3; d++) sv[d] = val[d];
    PetscCall(BoltMeshSetNodeValues(u, idx, sv, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscCall(VecAssemblyBegin(u));
  PetscCall(VecAssemblyEnd(u));
  PetscCall(PetscFree(vpart));
  PetscFunctionReturn(0);
}
