/* The mesh: a gmsh file read into DMPlex, checked, partitioned and distributed, with the
   parts (volume groups), their materials and the DOF layout (3 per vertex, clamp removed). */
#include "private/model.h"
#include <metis.h>
#include <stdio.h>
#include <stdlib.h>
#include <scotch/scotch.h> /* for SCOTCH_randomSeed: the one PT-Scotch that PETSc links */

static const char *defaultPartMaterials = "plate1:aluminium,plate2:aluminium,plate:aluminium,bolt:steel,washer_head:steel,washer_nut:steel,nut:steel,block:steel,upper:steel,lower:steel";

PetscErrorCode BoltMeshCreate(MPI_Comm comm, BoltMesh **mesh)
{
  BoltMesh *m;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&m));
  PetscCall(PetscNew(&m->materials));
  m->comm  = comm;
  m->clamp = PETSC_TRUE;
  PetscCall(PetscStrncpy(m->clampGroup, "clamp", sizeof(m->clampGroup)));
  PetscCall(PetscStrncpy(m->partitioner, "ptscotch", sizeof(m->partitioner))); /* smaller edge cut than METIS on fine meshes (docs/model.md) */
  PetscCall(PetscStrncpy(m->partMaterialMap, defaultPartMaterials, sizeof(m->partMaterialMap)));
  m->formulation = HEX8_INCOMPATIBLE;
  *mesh          = m;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshSetFromOptions(BoltMesh *m)
{
  const char *forms[] = {"full", "incompatible", "Hex8Formulation", "HEX8_", NULL};
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscOptionsBegin(m->comm, NULL, "Mesh and model", "boltrom");
  PetscCall(PetscOptionsString("-mesh", "gmsh mesh file (.msh) with the physical groups of docs/model.md", NULL, m->filename, m->filename, sizeof(m->filename), &set));
  PetscCall(PetscOptionsString("-clamp_group", "Physical group whose nodes are fully clamped", NULL, m->clampGroup, m->clampGroup, sizeof(m->clampGroup), NULL));
  PetscCall(PetscOptionsBool("-clamp", "Remove the clamp group's DOFs (false: free-free model)", NULL, m->clamp, &m->clamp, NULL));
  PetscCall(PetscOptionsString("-support_group", "Physical group whose nodes are held in the components -support_components only (a guide, e.g. a test machine's grip at the loaded end); none by default", NULL, m->supportGroup, m->supportGroup, sizeof(m->supportGroup), NULL));
  {
    PetscInt  comp[3] = {1, 2, 0}, ncomp = 3;
    PetscBool cset;
    PetscCall(PetscOptionsIntArray("-support_components", "Components held at -support_group, 0 x, 1 y, 2 z, comma separated (default 1,2: y and z)", NULL, comp, &ncomp, &cset));
    if (!cset) ncomp = 2;
    PetscCheck(ncomp >= 1, m->comm, PETSC_ERR_USER_INPUT, "-support_components needs at least one of 0, 1, 2 (x, y, z)");
    PetscCall(PetscSortRemoveDupsInt(&ncomp, comp));
    for (PetscInt i = 0; i < ncomp; i++) PetscCheck(comp[i] >= 0 && comp[i] <= 2, m->comm, PETSC_ERR_USER_INPUT, "-support_components: %" PetscInt_FMT " is not a component; use 0, 1, 2 (x, y, z)", comp[i]);
    for (PetscInt i = 0; i < ncomp; i++) m->supportComponents[i] = comp[i];
    m->nsupportComponents = ncomp;
  }
  PetscCall(PetscOptionsString("-partitioner", "Mesh partitioner: metis (boltrom's, through a shell partitioner) or a PETSc partitioner type (ptscotch, simple, ...)", NULL, m->partitioner, m->partitioner, sizeof(m->partitioner), NULL));
  PetscCall(PetscOptionsString("-part_material", "Material of each part, as part:material pairs separated by commas", NULL, m->partMaterialMap, m->partMaterialMap, sizeof(m->partMaterialMap), NULL));
  PetscCall(PetscOptionsEnum("-element", "Hexahedron formulation: full (2x2x2 Gauss) or incompatible (Wilson-Taylor modes, no bending locking)", "Hex8Formulation", forms, (PetscEnum)m->formulation, (PetscEnum *)&m->formulation, NULL));
  PetscOptionsEnd();
  PetscCall(BoltMaterialTableSetFromOptions(m->comm, m->materials));
  PetscFunctionReturn(0);
}

/* Part names and tags are read on rank 0 (which holds the whole serial mesh) and broadcast. */
static PetscErrorCode BoltMeshFindParts(BoltMesh *m, DM dm)
{
  PetscMPIInt rank;
  PetscInt    nlabels, cStart, cEnd;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(m->comm, &rank));
  m->nparts = 0;
  if (rank == 0) {
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    PetscCall(DMGetNumLabels(dm, &nlabels));
    for (PetscInt l = 0; l < nlabels; l++) {
      const char     *name;
      DMLabel         label;
      IS              ids;
      const PetscInt *id;
      PetscInt        nids, pStart, pEnd, ncells = 0, tag = -1;

      PetscCall(DMGetLabelName(dm, l, &name));
      PetscCall(DMGetLabelByNum(dm, l, &label));
      PetscCall(DMLabelGetValueIS(label, &ids));
      PetscCall(ISGetLocalSize(ids, &nids));
      PetscCall(ISGetIndices(ids, &id));
      for (PetscInt i = 0; i < nids; i++) {
        IS              pts;
        const PetscInt *p;
        PetscInt        np;

        PetscCall(DMLabelGetStratumIS(label, id[i], &pts));
        if (!pts) continue;
        PetscCall(ISGetLocalSize(pts, &np));
        PetscCall(ISGetIndices(pts, &p));
        for (PetscInt j = 0; j < np; j++)
          if (p[j] >= cStart && p[j] < cEnd) {
            ncells++;
            tag = id[i];
          }
        PetscCall(ISRestoreIndices(pts, &p));
        PetscCall(ISDestroy(&pts));
      }
      PetscCall(ISRestoreIndices(ids, &id));
      PetscCall(ISDestroy(&ids));
      (void)pStart;
      (void)pEnd;
      if (!ncells) continue;
      {
        PetscBool skip;
        PetscCall(PetscStrcmp(name, "celltype", &skip));
        if (!skip) PetscCall(PetscStrcmp(name, "depth", &skip));
        if (skip) continue;
      }
      PetscCheck(m->nparts < BOLTROM_MAX_PARTS, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Mesh %s has more than %d volume groups", m->filename, BOLTROM_MAX_PARTS);
      PetscCall(PetscStrncpy(m->partName[m->nparts], name, BOLTROM_NAME_LEN));
      m->partTag[m->nparts] = tag;
      m->nparts++;
    }
  }
  PetscCallMPI(MPI_Bcast(&m->nparts, 1, MPIU_INT, 0, m->comm));
  PetscCallMPI(MPI_Bcast(m->partName, BOLTROM_MAX_PARTS * BOLTROM_NAME_LEN, MPI_CHAR, 0, m->comm));
  PetscCallMPI(MPI_Bcast(m->partTag, BOLTROM_MAX_PARTS, MPIU_INT, 0, m->comm));
  PetscCheck(m->nparts > 0, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s has no volume physical group: name one group per part (e.g. plate1, bolt)", m->filename);
  PetscFunctionReturn(0);
}

/* part:material pairs -> material index of each part */
static PetscErrorCode BoltMeshAssignMaterials(BoltMesh *m)
{
  char    **pairs;
  PetscInt  npairs;

  PetscFunctionBeginUser;
  PetscCall(PetscStrToArray(m->partMaterialMap, ',', (int *)&npairs, &pairs));
  for (PetscInt p = 0; p < m->nparts; p++) {
    PetscBool found = PETSC_FALSE;

    for (PetscInt i = 0; i < npairs && !found; i++) {
      char  *colon;
      size_t len;
      PetscBool same;

      PetscCall(PetscStrchr(pairs[i], ':', &colon));
      PetscCheck(colon, m->comm, PETSC_ERR_USER_INPUT, "-part_material entry '%s' is not of the form part:material", pairs[i]);
      len = (size_t)(colon - pairs[i]);
      PetscCall(PetscStrncmp(pairs[i], m->partName[p], len, &same));
      if (same && m->partName[p][len] == '\0') {
        PetscCall(BoltMaterialTableFind(m->comm, m->materials, colon + 1, &m->partMaterial[p]));
        found = PETSC_TRUE;
      }
    }
    PetscCheck(found, m->comm, PETSC_ERR_USER_INPUT, "Part '%s' has no material: add it to -part_material, e.g. -part_material %s:steel", m->partName[p], m->partName[p]);
  }
  PetscCall(PetscStrToArrayDestroy((int)npairs, pairs));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltMeshCheckHexahedra(BoltMesh *m, DM dm)
{
  PetscInt cStart, cEnd, bad = -1;
  DMPolytopeType badType = DM_POLYTOPE_HEXAHEDRON;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd && bad < 0; c++) {
    DMPolytopeType ct;

    PetscCall(DMPlexGetCellType(dm, c, &ct));
    if (ct != DM_POLYTOPE_HEXAHEDRON) {
      bad     = c;
      badType = ct;
    }
  }
  PetscCheck(bad < 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Mesh %s: cell %" PetscInt_FMT " is a %s, but boltrom needs hexahedra only: recombine the mesh into hexahedra in gmsh", m->filename, bad, DMPolytopeTypes[badType]);
  PetscFunctionReturn(0);
}

/* Partition on rank 0 (METIS on the cell dual graph, or a PETSc partitioner), measure the edge
   cut there, and hand the result to DMPlexDistribute through a shell partitioner. */
static PetscErrorCode BoltMeshDistribute(BoltMesh *m, DM *dm)
{
  PetscMPIInt      size, rank;
  PetscPartitioner part;
  PetscInt         nv = 0, *xadj = NULL, *adj = NULL, *owner = NULL, *sizes, *points;
  IS               globalNumbering;
  PetscBool        metis;
  DM               dmDist = NULL;
  PetscSF          sfMigration = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(m->comm, &size));
  PetscCallMPI(MPI_Comm_rank(m->comm, &rank));
  m->edgeCut = 0;
  if (size == 1) {
    PetscInt pStart, pEnd;
    PetscCall(DMPlexGetChart(*dm, &pStart, &pEnd));
    PetscCall(PetscMalloc1(pEnd - pStart + 1, &m->pointOriginal));
    for (PetscInt p = pStart; p < pEnd; p++) m->pointOriginal[p - pStart] = p;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(BOLT_EVENT_MESH_DISTRIBUTE, 0, 0, 0, 0));
  PetscCall(PetscStrcmp(m->partitioner, "metis", &metis));
  PetscCall(DMPlexCreatePartitionerGraph(*dm, 0, &nv, &xadj, &adj, &globalNumbering));
  PetscCall(PetscMalloc1(nv + 1, &owner));
  if (metis) {
    if (nv > 0) {
      idx_t n = (idx_t)nv, ncon = 1, nparts = size, objval, options[METIS_NOPTIONS];
      idx_t *mx, *ma, *mp;
      int    status;

      PetscCall(PetscMalloc3(nv + 1, &mx, xadj[nv], &ma, nv, &mp));
      for (PetscInt i = 0; i <= nv; i++) mx[i] = (idx_t)xadj[i];
      for (PetscInt i = 0; i < xadj[nv]; i++) ma[i] = (idx_t)adj[i];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_SEED] = 17; /* same partition every run */
      status = METIS_PartGraphKway(&n, &ncon, mx, ma, NULL, NULL, NULL, &nparts, NULL, NULL, options, &objval, mp);
      PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway failed with status %d", status);
      for (PetscInt i = 0; i < nv; i++) owner[i] = (PetscInt)mp[i];
      PetscCall(PetscFree3(mx, ma, mp));
    }
  } else {
    PetscPartitioner ptmp;
    PetscSection     partSection;
    IS               partition;
    const PetscInt  *pts;

    /* Debian's Scotch seeds its generator from the clock and splits its work over threads:
       with either, the partition, and with it the rounding of every parallel sum, changed from
       run to run. One thread (unless the user set SCOTCH_PTHREAD_NUMBER) and a fixed seed. */
    PetscCheck(setenv("SCOTCH_PTHREAD_NUMBER", "1", 0) == 0, PETSC_COMM_SELF, PETSC_ERR_SYS, "setenv failed");
    SCOTCH_randomSeed(17);
    SCOTCH_randomReset();
    PetscCall(PetscPartitionerCreate(m->comm, &ptmp));
    PetscCall(PetscPartitionerSetType(ptmp, m->partitioner));
    PetscCall(PetscPartitionerSetUp(ptmp));
    PetscCall(PetscSectionCreate(m->comm, &partSection));
    PetscCall(PetscPartitionerDMPlexPartition(ptmp, *dm, NULL, partSection, &partition));
    PetscCall(ISGetIndices(partition, &pts));
    for (PetscMPIInt r = 0; r < size; r++) {
      PetscInt off, dof;
      PetscCall(PetscSectionGetOffset(partSection, r, &off));
      PetscCall(PetscSectionGetDof(partSection, r, &dof));
      for (PetscInt k = 0; k < dof; k++) owner[pts[off + k]] = r;
    }
    PetscCall(ISRestoreIndices(partition, &pts));
    PetscCall(ISDestroy(&partition));
    PetscCall(PetscSectionDestroy(&partSection));
    PetscCall(PetscPartitionerDestroy(&ptmp));
  }
  for (PetscInt i = 0; i < nv; i++)
    for (PetscInt k = xadj[i]; k < xadj[i + 1]; k++)
      if (owner[i] != owner[adj[k]]) m->edgeCut++;
  m->edgeCut /= 2;
  PetscCallMPI(MPI_Bcast(&m->edgeCut, 1, MPIU_INT, 0, m->comm));
  /* shell partition: the cells of each rank, in rank order */
  PetscCall(PetscCalloc1(size, &sizes));
  PetscCall(PetscMalloc1(nv + 1, &points));
  for (PetscInt i = 0; i < nv; i++) sizes[owner[i]]++;
  {
    PetscInt *start;
    PetscCall(PetscCalloc1(size + 1, &start));
    for (PetscMPIInt r = 0; r < size; r++) start[r + 1] = start[r] + sizes[r];
    for (PetscInt i = 0; i < nv; i++) points[start[owner[i]]++] = i;
    PetscCall(PetscFree(start));
  }
  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes, points));
  PetscCall(DMPlexDistribute(*dm, 0, &sfMigration, &dmDist));
  {
    /* the mesh was read on rank 0, so the root of every point is its number in the file's mesh */
    PetscInt           pStart, pEnd, nleaves;
    const PetscInt    *ilocal;
    const PetscSFNode *iremote;
    DM                 d = dmDist ? dmDist : *dm;
    PetscCall(DMPlexGetChart(d, &pStart, &pEnd));
    PetscCall(PetscMalloc1(pEnd - pStart + 1, &m->pointOriginal));
    for (PetscInt p = pStart; p < pEnd; p++) m->pointOriginal[p - pStart] = p;
    if (sfMigration) {
      PetscCall(PetscSFGetGraph(sfMigration, NULL, &nleaves, &ilocal, &iremote));
      for (PetscInt i = 0; i < nleaves; i++) m->pointOriginal[(ilocal ? ilocal[i] : i) - pStart] = iremote[i].index;
    }
    PetscCall(PetscSFDestroy(&sfMigration));
  }
  if (dmDist) {
    PetscCall(DMDestroy(dm));
    *dm = dmDist;
  }
  PetscCall(PetscFree(sizes));
  PetscCall(PetscFree(points));
  PetscCall(PetscFree(owner));
  PetscCall(PetscFree(xadj));
  PetscCall(PetscFree(adj));
  PetscCall(ISDestroy(&globalNumbering));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_MESH_DISTRIBUTE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltMeshCreateSection(BoltMesh *m)
{
  PetscSection s;
  PetscInt     pStart, pEnd, nclamp = 0, *clampVerts = NULL, nsupport = 0, *supportVerts = NULL;
  const PetscInt all[3] = {0, 1, 2};

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(m->dm, &pStart, &pEnd));
  PetscCall(PetscSectionCreate(m->comm, &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldComponents(s, 0, 3));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = m->vStart; v < m->vEnd; v++) {
    PetscCall(PetscSectionSetDof(s, v, 3));
    PetscCall(PetscSectionSetFieldDof(s, v, 0, 3));
  }
  /* a node of both groups is clamped: the support goes first, the clamp overrides it */
  if (m->supportGroup[0]) {
    PetscCall(BoltMeshGroupVertices(m, m->supportGroup, PETSC_FALSE, &nsupport, &supportVerts));
    for (PetscInt i = 0; i < nsupport; i++) {
      PetscCall(PetscSectionSetConstraintDof(s, supportVerts[i], m->nsupportComponents));
      PetscCall(PetscSectionSetFieldConstraintDof(s, supportVerts[i], 0, m->nsupportComponents));
    }
  }
  if (m->clamp) {
    PetscCall(BoltMeshGroupVertices(m, m->clampGroup, PETSC_FALSE, &nclamp, &clampVerts));
    for (PetscInt i = 0; i < nclamp; i++) {
      PetscCall(PetscSectionSetConstraintDof(s, clampVerts[i], 3));
      PetscCall(PetscSectionSetFieldConstraintDof(s, clampVerts[i], 0, 3));
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt i = 0; i < nsupport; i++) {
    PetscInt cdof;
    PetscCall(PetscSectionGetConstraintDof(s, supportVerts[i], &cdof));
    if (cdof == 3) continue; /* clamped as well */
    PetscCall(PetscSectionSetConstraintIndices(s, supportVerts[i], m->supportComponents));
    PetscCall(PetscSectionSetFieldConstraintIndices(s, supportVerts[i], 0, m->supportComponents));
  }
  for (PetscInt i = 0; i < nclamp; i++) {
    PetscCall(PetscSectionSetConstraintIndices(s, clampVerts[i], all));
    PetscCall(PetscSectionSetFieldConstraintIndices(s, clampVerts[i], 0, all));
  }
  PetscCall(PetscFree(clampVerts));
  PetscCall(PetscFree(supportVerts));
  PetscCall(DMSetLocalSection(m->dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshSetUp(BoltMesh *m)
{
  PetscBool   exists, has;
  DM          dm;
  PetscSF     sf;
  PetscInt    nleaves;
  const PetscInt *leaves;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(m->comm, &rank));
  PetscCheck(m->filename[0], m->comm, PETSC_ERR_USER_INPUT, "No mesh given: set -mesh FILE.msh (make one with scripts/mesh-joint)");
  PetscCall(PetscTestFile(m->filename, 'r', &exists));
  PetscCheck(exists, m->comm, PETSC_ERR_USER_INPUT, "Mesh file %s does not exist or is not readable: check -mesh, or make it with scripts/mesh-joint", m->filename);
  /* labels named after the physical groups, point groups included */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &has));
  if (!has) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "1"));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_mark_vertices", &has));
  if (!has) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_mark_vertices", "1"));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_MESH_READ, 0, 0, 0, 0));
  {
    /* a file that exists but cannot be read (truncated, not MSH): say which, not just where */
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = DMPlexCreateFromFile(m->comm, m->filename, "boltrom", PETSC_TRUE, &dm);
    PetscCall(PetscPopErrorHandler());
    if (ierr) {
      const char *text;
      char       *specific = NULL;
      PetscErrorMessage(ierr, &text, &specific);
      SETERRQ(m->comm, PETSC_ERR_FILE_UNEXPECTED, "Cannot read the mesh %s (%s): is it a complete gmsh MSH 4.1 file? Regenerate it (scripts/mesh-joint) or export it again from gmsh", m->filename, specific && specific[0] ? specific : text);
    }
  }
  PetscCall(PetscLogEventEnd(BOLT_EVENT_MESH_READ, 0, 0, 0, 0));
  PetscCall(PetscObjectSetName((PetscObject)dm, "boltrom"));
  {
    PetscInt dim;
    PetscCall(DMGetDimension(dm, &dim));
    PetscCheck(dim == 3, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s is %" PetscInt_FMT "-dimensional: boltrom needs a 3D hexahedral mesh", m->filename, dim);
  }
  {
    PetscErrorCode ierr = 0;
    PetscInt       ok, allok;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = BoltMeshCheckHexahedra(m, dm);
    PetscCall(PetscPopErrorHandler());
    ok = ierr ? 0 : 1;
    PetscCall(MPIU_Allreduce(&ok, &allok, 1, MPIU_INT, MPI_MIN, m->comm));
    if (!allok) PetscCall(BoltMeshCheckHexahedra(m, dm)); /* repeat to raise the error with its message */
    PetscCheck(allok, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s has non-hexahedral cells: recombine it into hexahedra", m->filename);
  }
  PetscCall(BoltMeshFindParts(m, dm));
  PetscCall(BoltMeshAssignMaterials(m));
  PetscCall(BoltMeshDistribute(m, &dm));
  m->dm = dm;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &m->cStart, &m->cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &m->vStart, &m->vEnd));
  PetscCall(DMPlexGetChart(dm, &m->pStart, &m->pEnd));
  PetscCall(PetscBTCreate(m->pEnd - m->pStart, &m->pointGhost));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  for (PetscInt i = 0; i < nleaves; i++) PetscCall(PetscBTSet(m->pointGhost, (leaves ? leaves[i] : i) - m->pStart));
  if (m->clamp) {
    PetscCall(BoltMeshHasGroup(m, m->clampGroup, &has));
    PetscCheck(has, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s has no physical group '%s' to clamp: add it, set -clamp_group NAME, or run free-free with -clamp false", m->filename, m->clampGroup);
  }
  if (m->supportGroup[0]) {
    PetscCall(BoltMeshHasGroup(m, m->supportGroup, &has));
    PetscCheck(has, m->comm, PETSC_ERR_USER_INPUT, "Mesh %s has no physical group '%s' to support: check -support_group (the mesh's groups are in docs/model.md)", m->filename, m->supportGroup);
  }
  /* part of every local cell */
  PetscCall(PetscMalloc1(m->cEnd - m->cStart + 1, &m->cellPart));
  for (PetscInt c = m->cStart; c < m->cEnd; c++) m->cellPart[c - m->cStart] = -1;
  for (PetscInt p = 0; p < m->nparts; p++) {
    IS              pts;
    const PetscInt *pt;
    PetscInt        np;

    PetscCall(DMGetStratumIS(dm, m->partName[p], m->partTag[p], &pts));
    if (!pts) continue;
    PetscCall(ISGetLocalSize(pts, &np));
    PetscCall(ISGetIndices(pts, &pt));
    for (PetscInt j = 0; j < np; j++)
      if (pt[j] >= m->cStart && pt[j] < m->cEnd) m->cellPart[pt[j] - m->cStart] = p;
    PetscCall(ISRestoreIndices(pts, &pt));
    PetscCall(ISDestroy(&pts));
  }
  for (PetscInt c = m->cStart; c < m->cEnd; c++) PetscCheck(m->cellPart[c - m->cStart] >= 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Mesh %s: a cell belongs to no volume physical group: put every hexahedron in one part", m->filename);
  PetscCall(BoltMeshCreateSection(m));
  {
    PetscInt nown = 0, ncell = m->cEnd - m->cStart, N;
    Vec      x;
    for (PetscInt v = m->vStart; v < m->vEnd; v++)
      if (!PetscBTLookup(m->pointGhost, v - m->pStart)) nown++;
    PetscCall(MPIU_Allreduce(&nown, &m->nverticesGlobal, 1, MPIU_INT, MPI_SUM, m->comm));
    PetscCall(MPIU_Allreduce(&ncell, &m->ncellsGlobal, 1, MPIU_INT, MPI_SUM, m->comm));
    PetscCall(DMCreateGlobalVector(dm, &x));
    PetscCall(VecGetSize(x, &N));
    m->ndofsFree = N;
    PetscCall(VecDestroy(&x));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshView(BoltMesh *m, PetscViewer viewer)
{
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(m->comm, &size));
  PetscCall(PetscViewerASCIIPrintf(viewer, "Mesh %s: %" PetscInt_FMT " hexahedra, %" PetscInt_FMT " nodes, %" PetscInt_FMT " DOFs (%" PetscInt_FMT " free after clamping '%s'), element %s\n", m->filename, m->ncellsGlobal, m->nverticesGlobal, 3 * m->nverticesGlobal, m->ndofsFree, m->clamp ? m->clampGroup : "none", m->formulation == HEX8_FULL ? "full" : "incompatible"));
  if (m->supportGroup[0]) {
    const char *xyz = "xyz";
    char        held[4] = {0};
    for (PetscInt i = 0; i < m->nsupportComponents; i++) held[i] = xyz[m->supportComponents[i]];
    PetscCall(PetscViewerASCIIPrintf(viewer, "  support: the nodes of '%s' held in %s\n", m->supportGroup, held));
  }
  if (size > 1) PetscCall(PetscViewerASCIIPrintf(viewer, "  partitioner %s on %d ranks: edge cut %" PetscInt_FMT " faces\n", m->partitioner, size, m->edgeCut));
  for (PetscInt p = 0; p < m->nparts; p++) {
    const BoltMaterial *mat = &m->materials->mat[m->partMaterial[p]];
    PetscCall(PetscViewerASCIIPrintf(viewer, "  part %-12s %-10s E %.4g Pa, nu %.3g, rho %.5g kg/m^3\n", m->partName[p], mat->name, (double)mat->E, (double)mat->nu, (double)mat->rho));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshDestroy(BoltMesh **mesh)
{
  PetscFunctionBeginUser;
  if (!*mesh) PetscFunctionReturn(0);
  PetscCall(DMDestroy(&(*mesh)->dm));
  PetscCall(PetscFree((*mesh)->cellPart));
  PetscCall(PetscFree((*mesh)->pointOriginal));
  PetscCall(PetscBTDestroy(&(*mesh)->pointGhost));
  PetscCall(BoltMaterialTableDestroy(&(*mesh)->materials));
  PetscCall(PetscFree(*mesh));
  PetscFunctionReturn(0);
}
