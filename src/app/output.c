/* Output: an HDF5 file (PetscViewerHDF5) with the mesh, part ids and vertex fields, and an XDMF
   file beside it so that ParaView opens it. Every file is written under a temporary name and
   renamed when complete, so a failed run leaves no half-written file. */
#include "private/app.h"
#include <petscviewerhdf5.h>

/* Global vertex number of a local vertex (ghosts are encoded -(g+1) by DMPlex). */
static inline PetscInt BoltGlobalNumber(const PetscInt *num, PetscInt i)
{
  return num[i] < 0 ? -(num[i] + 1) : num[i];
}

PetscErrorCode BoltOutputOpen(BoltMesh *m, const char dir[], const char name[], BoltOutput *out)
{
  const PetscInt nvg = BoltMeshVertexCountGlobal(m), ncg = BoltMeshCellCountGlobal(m);
  IS              vnumIS, cnumIS, topo;
  const PetscInt *vnum, *cnum;
  PetscInt        nown = 0, ncell, *cells, vStart, vEnd, cStart, cEnd;
  Vec             geom, part, vpart;
  Vec             coords;
  PetscSection    cs;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(BoltMeshDM(m), 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(BoltMeshDM(m), 0, &vStart, &vEnd));
  ncell = cEnd - cStart;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscCall(PetscMemzero(out, sizeof(*out)));
  out->comm = BoltMeshComm(m);
  PetscCall(PetscStrncpy(out->dir, dir, sizeof(out->dir)));
  PetscCall(PetscStrncpy(out->name, name, sizeof(out->name)));
  PetscCall(BoltMakeDir(BoltMeshComm(m), dir));
  PetscCall(PetscSNPrintf(out->h5final, sizeof(out->h5final), "%s/%s.h5", dir, name));
  PetscCall(PetscSNPrintf(out->h5tmp, sizeof(out->h5tmp), "%s/.%s.h5.tmp", dir, name));
  PetscCall(PetscViewerHDF5Open(BoltMeshComm(m), out->h5tmp, FILE_MODE_WRITE, &out->viewer));

  PetscCall(DMPlexGetVertexNumbering(BoltMeshDM(m), &vnumIS));
  PetscCall(DMPlexGetCellNumbering(BoltMeshDM(m), &cnumIS));
  PetscCall(ISGetIndices(vnumIS, &vnum));
  PetscCall(ISGetIndices(cnumIS, &cnum));
  for (PetscInt v = vStart; v < vEnd; v++)
    if (vnum[v - vStart] >= 0) nown++;
  /* geometry: (N, 3) */
  PetscCall(VecCreateMPI(BoltMeshComm(m), 3 * nown, 3 * nvg, &geom));
  PetscCall(VecSetBlockSize(geom, 3));
  PetscCall(VecCreateMPI(BoltMeshComm(m), nown, nvg, &vpart));
  PetscCall(PetscObjectSetName((PetscObject)geom, "vertices"));
  PetscCall(PetscObjectSetName((PetscObject)vpart, "part"));
  PetscCall(DMGetCoordinatesLocal(BoltMeshDM(m), &coords));
  PetscCall(DMGetCoordinateSection(BoltMeshDM(m), &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, g = vnum[v - vStart], rows[3];
    if (g < 0) continue;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < 3; d++) rows[d] = 3 * g + d;
    PetscCall(VecSetValues(geom, 3, rows, &x[off], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  /* topology (NC, 8) in VTK order, part of each cell, and the lowest part at each vertex
     (a key, with the coordinates, to compare runs on different rank counts) */
  PetscCall(VecCreateMPI(BoltMeshComm(m), ncell, ncg, &part));
  PetscCall(PetscObjectSetName((PetscObject)part, "part"));
  PetscCall(PetscMalloc1(8 * ncell + 1, &cells));
  {
    PetscInt *vp;
    PetscCall(PetscMalloc1(vEnd - vStart + 1, &vp));
    for (PetscInt v = 0; v < vEnd - vStart; v++) vp[v] = PETSC_MAX_INT;
    for (PetscInt c = cStart; c < cEnd; c++) {
      PetscInt verts[8];
      PetscCall(BoltMeshCellVertices(m, c, verts));
      for (PetscInt a = 0; a < 8; a++) vp[verts[a] - vStart] = PetscMin(vp[verts[a] - vStart], BoltMeshCellPart(m, c));
    }
    for (PetscInt v = vStart; v < vEnd; v++)
      if (vnum[v - vStart] >= 0) PetscCall(VecSetValue(vpart, vnum[v - vStart], (PetscScalar)vp[v - vStart], INSERT_VALUES));
    PetscCall(PetscFree(vp));
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt verts[8], g = cnum[c - cStart];
    PetscCheck(g >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Unexpected ghost cell");
    PetscCall(BoltMeshCellVertices(m, c, verts));
    for (PetscInt a = 0; a < 8; a++) {
      PetscInt gv = BoltGlobalNumber(vnum, verts[a] - vStart);
      cells[8 * (c - cStart) + a] = gv;
    }
    PetscCall(VecSetValue(part, g, (PetscScalar)BoltMeshCellPart(m, c), INSERT_VALUES));
  }
  PetscCall(ISRestoreIndices(vnumIS, &vnum));
  PetscCall(ISRestoreIndices(cnumIS, &cnum));
  PetscCall(VecAssemblyBegin(geom));
  PetscCall(VecAssemblyEnd(geom));
  PetscCall(VecAssemblyBegin(part));
  PetscCall(VecAssemblyEnd(part));
  PetscCall(VecAssemblyBegin(vpart));
  PetscCall(VecAssemblyEnd(vpart));
  PetscCall(ISCreateGeneral(BoltMeshComm(m), 8 * ncell, cells, PETSC_OWN_POINTER, &topo));
  PetscCall(ISSetBlockSize(topo, 8));
  PetscCall(PetscObjectSetName((PetscObject)topo, "cells"));
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, "/geometry"));
  PetscCall(VecView(geom, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, "/topology"));
  PetscCall(ISView(topo, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, "/cell_fields"));
  PetscCall(VecView(part, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, "/vertex_fields"));
  PetscCall(VecView(vpart, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  out->nfields = 0;
  PetscCall(PetscStrncpy(out->field[out->nfields], "part", BOLTROM_NAME_LEN));
  out->fieldComponents[out->nfields] = 1;
  out->fieldOnCells[out->nfields++]  = PETSC_TRUE;
  PetscCall(ISDestroy(&topo));
  PetscCall(VecDestroy(&geom));
  PetscCall(VecDestroy(&part));
  PetscCall(VecDestroy(&vpart));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A node's contact state from the weights of its open, sticking and slipping points: 0 where it
   has none, else 1 + the state of most of them (1 open, 2 stick, 3 slip; on a tie open, then
   slip: a node at the edge of a zone shows the zone). */
static PetscScalar BoltNodeContactState(const PetscReal wk[3])
{
  const PetscInt tieOrder[3] = {BOLT_POINT_OPEN, BOLT_POINT_SLIP, BOLT_POINT_STICK};
  PetscReal      best = 0, tol = 1e-12 * (wk[0] + wk[1] + wk[2]);
  PetscScalar    code = 0;

  for (PetscInt j = 0; j < 3; j++)
    if (wk[tieOrder[j]] > best + tol) {
      best = wk[tieOrder[j]];
      code = tieOrder[j] + 1;
    }
  return code;
}

/* A vector of the global layout (3 DOFs per node, clamped ones absent) as a vertex field: (N, 3),
   clamped DOFs at zero, or with state (N), each node's contact state from its three values, the
   weights of BoltContactSetNodalStates. */
static PetscErrorCode BoltOutputVertexValues(BoltOutput *out, BoltMesh *m, Vec u, const char name[], PetscBool state)
{
  const PetscInt     nvg = BoltMeshVertexCountGlobal(m);
  const PetscInt     bs = state ? 1 : 3;
  PetscInt           vStart, vEnd;
  IS                 vnumIS;
  const PetscInt    *vnum;
  PetscInt           nown = 0, rstart;
  Vec                w;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(BoltMeshDM(m), 0, &vStart, &vEnd));
  PetscCheck(out->nfields < 16, BoltMeshComm(m), PETSC_ERR_SUP, "Too many output fields");
  PetscCall(PetscLogEventBegin(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscCall(DMPlexGetVertexNumbering(BoltMeshDM(m), &vnumIS));
  PetscCall(ISGetIndices(vnumIS, &vnum));
  for (PetscInt v = vStart; v < vEnd; v++)
    if (vnum[v - vStart] >= 0) nown++;
  PetscCall(VecCreateMPI(BoltMeshComm(m), bs * nown, bs * nvg, &w));
  PetscCall(VecSetBlockSize(w, bs));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  PetscCall(VecGetOwnershipRange(u, &rstart, NULL));
  PetscCall(VecGetArrayRead(u, &a));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt    g = vnum[v - vStart], idx[3], rows[3];
    PetscScalar val[3];
    if (g < 0) continue;
    PetscCall(BoltMeshVertexDofs(m, v, idx));
    for (PetscInt d = 0; d < 3; d++) {
      rows[d] = 3 * g + d;
      val[d]  = idx[d] >= 0 ? a[idx[d] - rstart] : 0.0;
    }
    if (state) {
      const PetscReal wk[3] = {PetscRealPart(val[0]), PetscRealPart(val[1]), PetscRealPart(val[2])};
      PetscCall(VecSetValue(w, g, BoltNodeContactState(wk), INSERT_VALUES));
    } else PetscCall(VecSetValues(w, 3, rows, val, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(u, &a));
  PetscCall(ISRestoreIndices(vnumIS, &vnum));
  PetscCall(VecAssemblyBegin(w));
  PetscCall(VecAssemblyEnd(w));
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, "/vertex_fields"));
  PetscCall(VecView(w, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  PetscCall(VecDestroy(&w));
  PetscCall(PetscStrncpy(out->field[out->nfields], name, BOLTROM_NAME_LEN));
  out->fieldComponents[out->nfields] = bs;
  out->fieldOnCells[out->nfields++]  = PETSC_FALSE;
  PetscCall(PetscLogEventEnd(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A displacement-like field (free DOFs of the global system) as an (N, 3) vertex field,
   clamped nodes at zero. */
PetscErrorCode BoltOutputVertexField(BoltOutput *out, BoltMesh *m, Vec u, const char name[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltOutputVertexValues(out, m, u, name, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* The contact state at the nodes as a scalar vertex field (BoltNodeContactState), from the codes
   of the local points of contact set c (BoltContactStatePointCodes). */
PetscErrorCode BoltOutputContactState(BoltOutput *out, BoltMesh *m, BoltContactSet *c, const unsigned char codes[], const char name[])
{
  Vec              W;
  BoltContactWork *w;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(BoltContactSetLayout(c), &W));
  PetscCall(BoltContactWorkCreate(c, &w));
  PetscCall(BoltContactSetNodalStates(c, w, codes, W));
  PetscCall(BoltContactWorkDestroy(&w));
  PetscCall(BoltOutputVertexValues(out, m, W, name, PETSC_TRUE));
  PetscCall(VecDestroy(&W));
  PetscFunctionReturn(0);
}

/* A table of n rows of bs values known on every rank, row i column k at values[stride i + k],
   written once from rank 0: an (n) dataset if bs is 1, else (n, bs). */
static PetscErrorCode BoltOutputTable(BoltOutput *out, const char group[], const char name[], PetscInt n, PetscInt bs, PetscInt stride, const PetscReal values[])
{
  Vec         w;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(out->comm, &rank));
  PetscCall(VecCreate(out->comm, &w));
  PetscCall(VecSetSizes(w, rank == 0 ? bs * n : 0, bs * n));
  PetscCall(VecSetBlockSize(w, bs));
  PetscCall(VecSetType(w, VECMPI));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  if (rank == 0) {
    PetscScalar *a;
    PetscCall(VecGetArray(w, &a));
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt k = 0; k < bs; k++) a[bs * i + k] = values[stride * i + k];
    PetscCall(VecRestoreArray(w, &a));
  }
  PetscCall(PetscViewerHDF5PushGroup(out->viewer, group));
  PetscCall(VecView(w, out->viewer));
  PetscCall(PetscViewerHDF5PopGroup(out->viewer));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* A time series known on every rank (e.g. a probe history), written once from rank 0. */
PetscErrorCode BoltOutputSeries(BoltOutput *out, const char group[], const char name[], PetscInt n, const PetscReal values[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltOutputTable(out, group, name, n, 1, 1, values));
  PetscFunctionReturn(0);
}

/* The pair-force history of a run (n steps of BoltContactStatePairForces) as <group>/pair_force/
   <pair name>, an (n, 4) dataset per pair: the force on side b (x, y, z) and the normal force [N]. */
PetscErrorCode BoltOutputPairForces(BoltOutput *out, const char group[], BoltContactSet *c, PetscInt n, const PetscReal values[])
{
  char sub[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(sub, sizeof(sub), "%s/pair_force", group));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) PetscCall(BoltOutputTable(out, sub, BoltContactSetPairName(c, p), n, BOLT_PAIR_FORCE, BOLT_PAIR_FORCE * BoltContactSetPairCount(c), &values[BOLT_PAIR_FORCE * p]));
  PetscFunctionReturn(0);
}

/* The contact state at each snapshot (codes: per snapshot, each local point's), as vertex fields
   <prefix>contact_state_<i> that the model's temporal series shows beside the displacement. */
PetscErrorCode BoltOutputSnapshotStates(BoltOutput *out, BoltMesh *m, const char prefix[], BoltContactSet *c, PetscInt n, const unsigned char codes[])
{
  PetscInt nf = out->nfields;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    char name[BOLTROM_NAME_LEN];
    PetscCall(PetscSNPrintf(name, sizeof(name), "%scontact_state_%06" PetscInt_FMT, prefix, i));
    PetscCall(BoltOutputContactState(out, m, c, &codes[4 * BoltContactSetElementCount(c) * i], name));
    out->nfields = nf;
  }
  PetscFunctionReturn(0);
}

/* Displacement snapshot i of a model as the vertex field <prefix>snapshot_<i> (its temporal
   series, not the main grid, shows it: BoltOutputSnapshotSeries). */
PetscErrorCode BoltOutputSnapshot(BoltOutput *out, BoltMesh *m, const char prefix[], PetscInt i, Vec u)
{
  PetscInt nf = out->nfields;
  char     name[BOLTROM_NAME_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(name, sizeof(name), "%ssnapshot_%06" PetscInt_FMT, prefix, i));
  PetscCall(BoltOutputVertexField(out, m, u, name));
  out->nfields = nf;
  PetscFunctionReturn(0);
}

/* A model's n snapshots at times time[] (and its contact states, if written) become a temporal
   XDMF series at close: <name>-series.xmf for prefix "", else <name>-<prefix without _>-series.xmf. */
PetscErrorCode BoltOutputSnapshotSeries(BoltOutput *out, const char prefix[], PetscInt n, const PetscReal time[], PetscBool states)
{
  PetscInt k = out->nseries;

  PetscFunctionBeginUser;
  PetscCheck(k < 2, out->comm, PETSC_ERR_SUP, "At most two snapshot series (the FOM's and the ROM's)");
  PetscCall(PetscStrncpy(out->series[k].prefix, prefix, sizeof(out->series[k].prefix)));
  PetscCall(PetscMalloc1(n + 1, &out->series[k].time));
  PetscCall(PetscArraycpy(out->series[k].time, time, n));
  out->series[k].n      = n;
  out->series[k].states = states;
  out->nseries++;
  PetscFunctionReturn(0);
}

static void BoltWriteXdmfMesh(FILE *fp, BoltOutput *out, BoltMesh *m)
{
  const PetscInt nvg = BoltMeshVertexCountGlobal(m), ncg = BoltMeshCellCountGlobal(m);
  fprintf(fp, "   <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n", ncg);
  fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s.h5:/topology/cells</DataItem>\n   </Topology>\n", ncg, (int)sizeof(PetscInt), out->name);
  fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/geometry/vertices</DataItem>\n   </Geometry>\n", nvg, out->name);
  fprintf(fp, "   <Attribute Name=\"part\" AttributeType=\"Scalar\" Center=\"Cell\">\n    <DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/cell_fields/part</DataItem>\n   </Attribute>\n", ncg, out->name);
}

static const char boltXdmfHead[] = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";

/* The main grid: the mesh and the fields written on it. */
static void BoltWriteXdmfGrid(FILE *fp, BoltOutput *out, BoltMesh *m)
{
  const PetscInt nvg = BoltMeshVertexCountGlobal(m), ncg = BoltMeshCellCountGlobal(m);
  fprintf(fp, "%s", boltXdmfHead);
  fprintf(fp, "  <Grid Name=\"%s\" GridType=\"Uniform\">\n", out->name);
  fprintf(fp, "   <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n", ncg);
  fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s.h5:/topology/cells</DataItem>\n   </Topology>\n", ncg, (int)sizeof(PetscInt), out->name);
  fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/geometry/vertices</DataItem>\n   </Geometry>\n", nvg, out->name);
  for (PetscInt f = 0; f < out->nfields; f++) {
    PetscInt n = out->fieldOnCells[f] ? ncg : nvg;
    fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", out->field[f], out->fieldComponents[f] == 3 ? "Vector" : "Scalar", out->fieldOnCells[f] ? "Cell" : "Node");
    if (out->fieldComponents[f] == 3) fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/%s/%s</DataItem>\n", n, out->name, "vertex_fields", out->field[f]);
    else fprintf(fp, "    <DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/%s/%s</DataItem>\n", n, out->name, out->fieldOnCells[f] ? "cell_fields" : "vertex_fields", out->field[f]);
    fprintf(fp, "   </Attribute>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
}

/* Series k: a grid per snapshot with its displacement (and contact state). */
static void BoltWriteXdmfSeries(FILE *fp, BoltOutput *out, BoltMesh *m, PetscInt k)
{
  const PetscInt nvg = BoltMeshVertexCountGlobal(m);
  const char *pre = out->series[k].prefix;

  fprintf(fp, "%s", boltXdmfHead);
  fprintf(fp, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", out->name);
  for (PetscInt i = 0; i < out->series[k].n; i++) {
    fprintf(fp, "  <Grid Name=\"step\" GridType=\"Uniform\">\n   <Time Value=\"%.10g\"/>\n", (double)out->series[k].time[i]);
    BoltWriteXdmfMesh(fp, out, m);
    fprintf(fp, "   <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/vertex_fields/%ssnapshot_%06" PetscInt_FMT "</DataItem>\n   </Attribute>\n", nvg, out->name, pre, i);
    if (out->series[k].states) fprintf(fp, "   <Attribute Name=\"contact_state\" AttributeType=\"Scalar\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s.h5:/vertex_fields/%scontact_state_%06" PetscInt_FMT "</DataItem>\n   </Attribute>\n", nvg, out->name, pre, i);
    fprintf(fp, "  </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
}

/* An XDMF file <dir>/<name><suffix>.xmf (rank 0), written under a temporary name: the main grid
   (k < 0) or series k. */
static PetscErrorCode BoltWriteXdmf(BoltOutput *out, BoltMesh *m, const char suffix[], PetscInt k)
{
  char  xtmp[PETSC_MAX_PATH_LEN], xfinal[PETSC_MAX_PATH_LEN];
  FILE *fp;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(xfinal, sizeof(xfinal), "%s/%s%s.xmf", out->dir, out->name, suffix));
  PetscCall(PetscSNPrintf(xtmp, sizeof(xtmp), "%s/.%s%s.xmf.tmp", out->dir, out->name, suffix));
  fp = fopen(xtmp, "w");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write %s: check -output_dir", xtmp);
  if (k < 0) BoltWriteXdmfGrid(fp, out, m);
  else BoltWriteXdmfSeries(fp, out, m, k);
  PetscCheck(fclose(fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write %s", xtmp);
  PetscCheck(rename(xtmp, xfinal) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", xtmp, xfinal);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltOutputClose(BoltOutput *out, BoltMesh *m)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscCall(PetscViewerDestroy(&out->viewer));
  PetscCallMPI(MPI_Comm_rank(BoltMeshComm(m), &rank));
  if (rank == 0) {
    PetscCheck(rename(out->h5tmp, out->h5final) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", out->h5tmp, out->h5final);
    PetscCall(BoltWriteXdmf(out, m, "", -1));
    for (PetscInt k = 0; k < out->nseries; k++) {
      char   suffix[BOLTROM_NAME_LEN];
      size_t len;
      PetscCall(PetscStrncpy(suffix, "-", sizeof(suffix)));
      PetscCall(PetscStrlcat(suffix, out->series[k].prefix, sizeof(suffix)));
      PetscCall(PetscStrlen(suffix, &len));
      if (suffix[len - 1] == '_') suffix[len - 1] = '-';
      PetscCall(PetscStrlcat(suffix, "series", sizeof(suffix)));
      PetscCall(BoltWriteXdmf(out, m, suffix, k));
    }
  }
  for (PetscInt k = 0; k < out->nseries; k++) PetscCall(PetscFree(out->series[k].time));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_OUTPUT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
