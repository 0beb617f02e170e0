/* Load set: the external load pattern (a force at a point group or spread over a face group),
   the bolt preload (equal and opposite axial forces on two node layers of the stud), and the
   probe where the response is read. */
#include "private/model.h"

PetscErrorCode BoltLoadSetCreate(BoltMesh *mesh, BoltLoadSet **ls)
{
  BoltLoadSet *l;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&l));
  l->mesh = mesh;
  PetscCall(PetscStrncpy(l->loadGroup, "load_point", sizeof(l->loadGroup)));
  PetscCall(PetscStrncpy(l->probeGroup, "load_point", sizeof(l->probeGroup)));
  PetscCall(PetscStrncpy(l->preloadGroup[0], "preload_lower", sizeof(l->preloadGroup[0])));
  PetscCall(PetscStrncpy(l->preloadGroup[1], "preload_upper", sizeof(l->preloadGroup[1])));
  l->loadDirection[2] = -1.0;
  l->loadForce        = 10.0;
  l->preloadAxis[2]   = 1.0;
  l->preloadForce     = 20e3;
  l->probeComponent   = 2;
  l->probeDof         = -1;
  *ls                 = l;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltLoadSetSetFromOptions(BoltLoadSet *l)
{
  PetscReal nrm;
  PetscBool set[4];

  PetscFunctionBeginUser;
  PetscOptionsBegin(l->mesh->comm, NULL, "Loads", "boltrom");
  PetscCall(PetscOptionsString("-load_group", "Physical group (point or surface) that carries the external load", NULL, l->loadGroup, l->loadGroup, sizeof(l->loadGroup), NULL));
  PetscCall(BoltOptionsRealVector(PetscOptionsObject, "-load_direction", "Direction of the external load, x,y,z (normalised)", 3, l->loadDirection, NULL));
  PetscCall(PetscOptionsReal("-load_force", "Total external force [N]", NULL, l->loadForce, &l->loadForce, NULL));
  PetscCall(PetscOptionsReal("-preload_force", "Bolt preload [N]", NULL, l->preloadForce, &l->preloadForce, &set[0]));
  PetscCall(PetscOptionsString("-preload_lower_group", "Group of the lower preload layer (its nodes pulled along -preload_axis; clamped nodes take nothing)", NULL, l->preloadGroup[0], l->preloadGroup[0], sizeof(l->preloadGroup[0]), &set[1]));
  PetscCall(PetscOptionsString("-preload_upper_group", "Group of the upper preload layer (its nodes pushed against -preload_axis)", NULL, l->preloadGroup[1], l->preloadGroup[1], sizeof(l->preloadGroup[1]), &set[2]));
  PetscCall(BoltOptionsRealVector(PetscOptionsObject, "-preload_axis", "Bolt axis, x,y,z, from the lower to the upper preload layer", 3, l->preloadAxis, NULL));
  {
    char    *names[BOLTROM_MAX_BOLTS];
    PetscInt n = BOLTROM_MAX_BOLTS;
    PetscCall(PetscOptionsStringArray("-preload_bolts", "Several bolts: names, comma-separated; bolt B: layer groups preload_B_lower and _upper, clamp force -preload_B_force (default -preload_force)", NULL, names, &n, &set[3]));
    l->nbolts = set[3] ? n : 0;
    for (PetscInt b = 0; b < l->nbolts; b++) {
      char opt[BOLTROM_NAME_LEN + 32];
      PetscCall(PetscStrncpy(l->boltName[b], names[b], sizeof(l->boltName[b])));
      PetscCall(PetscFree(names[b]));
      PetscCall(PetscSNPrintf(l->boltGroup[b][0], sizeof(l->boltGroup[b][0]), "preload_%s_lower", l->boltName[b]));
      PetscCall(PetscSNPrintf(l->boltGroup[b][1], sizeof(l->boltGroup[b][1]), "preload_%s_upper", l->boltName[b]));
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-preload_%s_force", l->boltName[b]));
      l->boltForce[b] = l->preloadForce;
      PetscCall(PetscOptionsReal(opt, "Clamp force of this bolt [N] (default -preload_force)", NULL, l->boltForce[b], &l->boltForce[b], NULL));
    }
  }
  PetscCall(PetscOptionsString("-probe_group", "Point group where the response is probed", NULL, l->probeGroup, l->probeGroup, sizeof(l->probeGroup), NULL));
  PetscCall(PetscOptionsInt("-probe_component", "Displacement component of the probe: 0 x, 1 y, 2 z", NULL, l->probeComponent, &l->probeComponent, NULL));
  PetscOptionsEnd();
  PetscCheck(!set[3] || l->nbolts > 0, l->mesh->comm, PETSC_ERR_USER_INPUT, "-preload_bolts needs the bolts' names, e.g. -preload_bolts 1,2");
  PetscCheck(!l->nbolts || !(set[1] || set[2]), l->mesh->comm, PETSC_ERR_USER_INPUT, "-preload_bolts names each bolt's layers (preload_<name>_lower/_upper): drop -preload_lower_group and -preload_upper_group");
  l->preloadAsked = (PetscBool)((set[0] || set[1] || set[2] || l->nbolts) && l->preloadForce != 0);
  nrm = PetscSqrtReal(PetscSqr(l->loadDirection[0]) + PetscSqr(l->loadDirection[1]) + PetscSqr(l->loadDirection[2]));
  PetscCheck(nrm > 0, l->mesh->comm, PETSC_ERR_USER_INPUT, "-load_direction must be a nonzero vector");
  for (PetscInt d = 0; d < 3; d++) l->loadDirection[d] /= nrm;
  nrm = PetscSqrtReal(PetscSqr(l->preloadAxis[0]) + PetscSqr(l->preloadAxis[1]) + PetscSqr(l->preloadAxis[2]));
  PetscCheck(nrm > 0, l->mesh->comm, PETSC_ERR_USER_INPUT, "-preload_axis must be a nonzero vector");
  for (PetscInt d = 0; d < 3; d++) l->preloadAxis[d] /= nrm;
  PetscCheck(l->probeComponent >= 0 && l->probeComponent < 3, l->mesh->comm, PETSC_ERR_USER_INPUT, "-probe_component must be 0, 1 or 2");
  PetscFunctionReturn(0);
}

/* Equal shares of `force` along `dir` on the owned vertices of a group (a point load when the
   group is one node). Returns the global node count. */
static PetscErrorCode BoltLoadSpread(BoltMesh *m, const char group[], const PetscReal dir[3], PetscReal force, Vec f, PetscInt *nglobal)
{
  PetscInt nv, *verts, n;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshGroupVertices(m, group, PETSC_TRUE, &nv, &verts));
  PetscCall(MPIU_Allreduce(&nv, &n, 1, MPIU_INT, MPI_SUM, m->comm));
  PetscCheck(n > 0, m->comm, PETSC_ERR_USER_INPUT, "Load group '%s' is not in mesh %s (or has no nodes): add the physical group or choose another with -load_group / -preload_*", group, m->filename);
  for (PetscInt i = 0; i < nv; i++) {
    PetscInt    idx[3];
    PetscScalar v[3];
    PetscCall(BoltMeshVertexDofs(m, verts[i], idx));
    for (PetscInt d = 0; d < 3; d++) v[d] = force * dir[d] / n;
    PetscCall(BoltMeshSetNodeValues(f, idx, v, ADD_VALUES));
  }
  PetscCall(PetscFree(verts));
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  *nglobal = n;
  PetscFunctionReturn(0);
}

/* Consistent share of a total force over a face group: each face's area in quarters. */
static PetscErrorCode BoltLoadFaces(BoltMesh *m, PetscInt nfaces, const PetscInt faces[], const PetscReal dir[3], PetscReal force, Vec f)
{
  PetscReal *area, atot = 0, aglob;
  PetscInt  *fv;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(4 * nfaces + 1, &fv, nfaces + 1, &area));
  for (PetscInt i = 0; i < nfaces; i++) {
    PetscInt  nv;
    PetscReal X[12];
    PetscCall(BoltMeshFaceVertices(m, faces[i], &nv, &fv[4 * i], X));
    PetscCheck(nv == 4, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Load surface: a face with %" PetscInt_FMT " vertices; surfaces must be quadrilateral faces of hexahedra", nv);
    PetscCall(QuadArea(X, &area[i]));
    atot += area[i];
  }
  PetscCall(MPIU_Allreduce(&atot, &aglob, 1, MPIU_REAL, MPI_SUM, m->comm));
  for (PetscInt i = 0; i < nfaces; i++)
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt    idx[3];
      PetscScalar v[3];
      PetscCall(BoltMeshVertexDofs(m, fv[4 * i + a], idx));
      for (PetscInt d = 0; d < 3; d++) v[d] = force * dir[d] * area[i] / (4 * aglob);
      PetscCall(BoltMeshSetNodeValues(f, idx, v, ADD_VALUES));
    }
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscCall(PetscFree2(fv, area));
  PetscFunctionReturn(0);
}

/* The preload: each bolt's two layers pulled together along the axis, so the stud between them
   is shortened. One bolt (its layers -preload_lower_group / -preload_upper_group), or the bolts of
   -preload_bolts, each with its own layers and force and a 1 N pattern of its own. */
static PetscErrorCode BoltLoadSetSetUpPreload(BoltLoadSet *l, Vec layout)
{
  BoltMesh *m = l->mesh;
  PetscInt  n;
  PetscReal down[3];

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; d++) down[d] = -l->preloadAxis[d];
  if (l->nbolts) {
    for (PetscInt b = 0; b < l->nbolts; b++) {
      for (PetscInt side = 0; side < 2; side++) {
        PetscBool has;
        PetscCall(BoltMeshHasGroup(m, l->boltGroup[b][side], &has));
        PetscCheck(has, m->comm, PETSC_ERR_USER_INPUT, "Bolt %s of -preload_bolts needs the preload layer '%s', which mesh %s does not have: add the physical group, or correct the bolt's name", l->boltName[b], l->boltGroup[b][side], m->filename);
      }
      PetscCall(VecDuplicate(layout, &l->boltUnit[b]));
      PetscCall(VecZeroEntries(l->boltUnit[b]));
      PetscCall(BoltLoadSpread(m, l->boltGroup[b][0], l->preloadAxis, 1.0, l->boltUnit[b], &n));
      PetscCall(BoltLoadSpread(m, l->boltGroup[b][1], down, 1.0, l->boltUnit[b], &n));
      PetscCall(VecAXPY(l->preload, l->boltForce[b], l->boltUnit[b]));
    }
    l->hasPreload = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  {
    PetscBool hasLow, hasUp;
    PetscCall(BoltMeshHasGroup(m, l->preloadGroup[0], &hasLow));
    PetscCall(BoltMeshHasGroup(m, l->preloadGroup[1], &hasUp));
    /* a mesh without the layers runs without a preload (the beam, the blocks), unless one is
       asked for; one layer alone is a mesh fault */
    PetscCheck(hasLow == hasUp, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s has the preload layer '%s' but not '%s': add the missing physical group, or name the layers with -preload_lower_group and -preload_upper_group", m->filename, l->preloadGroup[hasLow ? 0 : 1], l->preloadGroup[hasLow ? 1 : 0]);
    PetscCheck(hasLow || !l->preloadAsked, m->comm, PETSC_ERR_USER_INPUT, "-preload_force %g needs the preload layers '%s' and '%s', which mesh %s does not have: add the two physical groups, name yours with -preload_lower_group and -preload_upper_group, or give -preload_force 0", (double)l->preloadForce, l->preloadGroup[0], l->preloadGroup[1], m->filename);
    l->hasPreload = (hasLow && hasUp) ? PETSC_TRUE : PETSC_FALSE;
    if (l->hasPreload) {
      PetscCall(BoltLoadSpread(m, l->preloadGroup[0], l->preloadAxis, l->preloadForce, l->preload, &n));
      PetscCall(BoltLoadSpread(m, l->preloadGroup[1], down, l->preloadForce, l->preload, &n));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltLoadSetSetUp(BoltLoadSet *l, Vec layout)
{
  BoltMesh *m = l->mesh;
  PetscInt  n, hasFaces = 0, nv, *verts, nfaces, *faces;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_LOADS, 0, 0, 0, 0));
  PetscCall(VecDuplicate(layout, &l->load));
  PetscCall(VecDuplicate(layout, &l->preload));
  PetscCall(VecZeroEntries(l->load));
  PetscCall(VecZeroEntries(l->preload));
  PetscCall(PetscObjectSetName((PetscObject)l->load, "load"));
  PetscCall(PetscObjectSetName((PetscObject)l->preload, "preload"));
  /* a surface group spreads the force by area; a point group takes it whole */
  PetscCall(BoltMeshGroupPoints(m, l->loadGroup, PETSC_TRUE, &nfaces, &faces));
  {
    PetscInt fStart, fEnd, n2 = 0;
    PetscCall(DMPlexGetHeightStratum(m->dm, 1, &fStart, &fEnd));
    for (PetscInt k = 0; k < nfaces; k++)
      if (faces[k] >= fStart && faces[k] < fEnd) faces[n2++] = faces[k];
    nfaces   = n2;
    hasFaces = nfaces > 0;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &hasFaces, 1, MPIU_INT, MPI_MAX, m->comm));
  /* the pattern of a 1 N load, then scaled: a reduced model keeps the pattern */
  PetscCall(VecDuplicate(layout, &l->loadUnit));
  PetscCall(VecZeroEntries(l->loadUnit));
  if (hasFaces) PetscCall(BoltLoadFaces(m, nfaces, faces, l->loadDirection, 1.0, l->loadUnit));
  else PetscCall(BoltLoadSpread(m, l->loadGroup, l->loadDirection, 1.0, l->loadUnit, &n));
  {
    PetscReal nrm;
    PetscCall(VecNorm(l->loadUnit, NORM_INFINITY, &nrm));
    PetscCheck(nrm > 0, m->comm, PETSC_ERR_USER_INPUT, "Load group '%s' lies entirely on clamped nodes (group '%s'%s%s%s), or along held components: its force would act on nothing; choose a group on a free part with -load_group", l->loadGroup, m->clamp ? m->clampGroup : "none", m->supportGroup[0] ? ", support group '" : "", m->supportGroup, m->supportGroup[0] ? "'" : "");
  }
  PetscCall(VecAXPY(l->load, l->loadForce, l->loadUnit));
  PetscCall(PetscFree(faces));
  PetscCall(BoltLoadSetSetUpPreload(l, layout));
  /* probe */
  PetscCall(BoltMeshGroupVertices(m, l->probeGroup, PETSC_TRUE, &nv, &verts));
  PetscCall(MPIU_Allreduce(&nv, &n, 1, MPIU_INT, MPI_SUM, m->comm));
  PetscCheck(n >= 1, m->comm, PETSC_ERR_USER_INPUT, "Probe group '%s' is not in mesh %s: add the point group or set -probe_group", l->probeGroup, m->filename);
  l->probeDof = -1;
  for (PetscInt d = 0; d < 3; d++) l->probeCoord[d] = 0;
  {
    PetscInt clamped = 0, any;
    if (nv > 0) {
      PetscInt idx[3];
      PetscCall(BoltMeshVertexDofs(m, verts[0], idx));
      clamped = idx[l->probeComponent] < 0;
    }
    PetscCall(MPIU_Allreduce(&clamped, &any, 1, MPIU_INT, MPI_MAX, m->comm));
    PetscCheck(!any, m->comm, PETSC_ERR_USER_INPUT, "Probe group '%s' is a clamped node (group '%s'%s%s%s) in component %" PetscInt_FMT ": its displacement is zero; choose a free node with -probe_group or another -probe_component", l->probeGroup, m->clampGroup, m->supportGroup[0] ? ", or support group '" : "", m->supportGroup, m->supportGroup[0] ? "'" : "", l->probeComponent);
  }
  if (nv > 0) {
    PetscInt           idx[3], off;
    Vec                coords;
    PetscSection       cs;
    const PetscScalar *x;
    PetscCall(BoltMeshVertexDofs(m, verts[0], idx));
    l->probeDof = idx[l->probeComponent];
    PetscCall(DMGetCoordinatesLocal(m->dm, &coords));
    PetscCall(DMGetCoordinateSection(m->dm, &cs));
    PetscCall(VecGetArrayRead(coords, &x));
    PetscCall(PetscSectionGetOffset(cs, verts[0], &off));
    for (PetscInt d = 0; d < 3; d++) l->probeCoord[d] = PetscRealPart(x[off + d]);
    PetscCall(VecRestoreArrayRead(coords, &x));
  }
  PetscCall(PetscFree(verts));
  /* a point group's vertex is owned by one rank: the others contribute zeros */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, l->probeCoord, 3, MPIU_REAL, MPI_SUM, m->comm));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_LOADS, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The probe value, known on every rank. */
PetscErrorCode BoltLoadSetProbe(BoltLoadSet *l, Vec u, PetscReal *value)
{
  PetscReal          v = 0;
  PetscInt           rstart;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(VecGetArrayRead(u, &a));
  if (l->probeDof >= 0) v = PetscRealPart(a[l->probeDof - rstart]);
  PetscCall(VecRestoreArrayRead(u, &a));
  PetscCall(MPIU_Allreduce(&v, value, 1, MPIU_REAL, MPI_SUM, l->mesh->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltLoadSetView(BoltLoadSet *l, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Loads: %g N along (%g, %g, %g) at '%s'; preload %s%g N; probe u_%c at '%s' (%g, %g, %g)\n", (double)l->loadForce, (double)l->loadDirection[0], (double)l->loadDirection[1], (double)l->loadDirection[2], l->loadGroup, l->hasPreload ? "" : "(no preload layers in mesh) ", (double)l->preloadForce, "xyz"[l->probeComponent], l->probeGroup, (double)l->probeCoord[0], (double)l->probeCoord[1], (double)l->probeCoord[2]));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltLoadSetDestroy(BoltLoadSet **ls)
{
  PetscFunctionBeginUser;
  if (!*ls) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*ls)->load));
  PetscCall(VecDestroy(&(*ls)->loadUnit));
  PetscCall(VecDestroy(&(*ls)->preload));
  for (PetscInt b = 0; b < (*ls)->nbolts; b++) PetscCall(VecDestroy(&(*ls)->boltUnit[b]));
  PetscCall(PetscFree(*ls));
  PetscFunctionReturn(0);
}
