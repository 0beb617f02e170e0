/* The ROM file (HDF5): everything the online phase needs, and the fingerprint of what the basis
   depends on (fingerprint.c; which load is the input, group and direction, not its amplitude).
   A scene with a matching file skips the offline phase; a file that does not match is refused,
   or with -rom_rebuild another is built, never used silently. Rows of the basis are kept only at
   the contact DOFs and at the point groups (loads, probes). */
#include "private/rom.h"
#include <petscviewerhdf5.h>

/* Owned contact DOFs (every DOF of a contact element, whichever rank keeps the element). */
static PetscErrorCode BoltOwnedContactDofs(BoltContactSet *c, Vec layout, PetscInt *n, PetscInt **dofs)
{
  Vec                mark;
  const PetscScalar *a;
  PetscInt           rstart, rend;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(layout, &mark));
  PetscCall(VecZeroEntries(mark));
  for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++)
    for (PetscInt k = 0; k < 24; k++)
      if (BoltContactSetElementDofs(c, e)[k] >= 0) PetscCall(VecSetValue(mark, BoltContactSetElementDofs(c, e)[k], 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(mark));
  PetscCall(VecAssemblyEnd(mark));
  PetscCall(VecGetOwnershipRange(mark, &rstart, &rend));
  PetscCall(PetscMalloc1(rend - rstart + 1, dofs));
  *n = 0;
  PetscCall(VecGetArrayRead(mark, &a));
  for (PetscInt i = 0; i < rend - rstart; i++)
    if (PetscRealPart(a[i]) != 0) (*dofs)[(*n)++] = rstart + i;
  PetscCall(VecRestoreArrayRead(mark, &a));
  PetscCall(VecDestroy(&mark));
  PetscFunctionReturn(0);
}

/* A dense array (rows x cols, row-major) known on rank 0, written as an (rows, cols) dataset. */
static PetscErrorCode BoltReadArray(PetscViewer v, const char name[], PetscInt rows, PetscInt cols, PetscScalar *a)
{
  Vec          w;
  PetscInt     n;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(PETSC_COMM_SELF, &w));
  if (cols > 1) PetscCall(VecSetBlockSize(w, cols));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  PetscCall(VecLoad(w, v));
  PetscCall(VecGetSize(w, &n));
  PetscCheck(n == rows * cols, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "ROM file: dataset %s has %" PetscInt_FMT " entries, expected %" PetscInt_FMT, name, n, rows * cols);
  PetscCall(VecGetArray(w, &x));
  PetscCall(PetscArraycpy(a, x, n));
  PetscCall(VecRestoreArray(w, &x));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* Rows of V at the three DOFs of a point group's vertex, rows[d n + j], on every rank. */
static PetscErrorCode BoltPointRows(BoltMesh *m, BV V, const char group[], PetscInt n, PetscScalar rows[], PetscBool *found)
{
  PetscInt nv, *verts, total, rstart;
  Vec      col;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(rows, 3 * n));
  PetscCall(BoltMeshGroupVertices(m, group, PETSC_TRUE, &nv, &verts));
  PetscCall(MPIU_Allreduce(&nv, &total, 1, MPIU_INT, MPI_SUM, BoltMeshComm(m)));
  *found = total == 1 ? PETSC_TRUE : PETSC_FALSE;
  if (nv == 1) {
    PetscInt idx[3];
    PetscCall(BoltMeshVertexDofs(m, verts[0], idx));
    for (PetscInt j = 0; j < n; j++) {
      const PetscScalar *x;
      PetscCall(BVGetColumn(V, j, &col));
      PetscCall(VecGetOwnershipRange(col, &rstart, NULL));
      PetscCall(VecGetArrayRead(col, &x));
      for (PetscInt d = 0; d < 3; d++) rows[d * n + j] = idx[d] >= 0 ? x[idx[d] - rstart] : 0.0;
      PetscCall(VecRestoreArrayRead(col, &x));
      PetscCall(BVRestoreColumn(V, j, &col));
    }
  } else
    for (PetscInt j = 0; j < n; j++) { /* collective column access on every rank */
      PetscCall(BVGetColumn(V, j, &col));
      PetscCall(BVRestoreColumn(V, j, &col));
    }
  PetscCall(PetscFree(verts));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rows, (PetscMPIInt)(3 * n), MPIU_SCALAR, MPIU_SUM, BoltMeshComm(m)));
  PetscFunctionReturn(0);
}

/* The preloaded contact state, per contact element keyed by its face a in the mesh as read
   (as in checkpoints): 12 multipliers and 12 gap components per newton of preload, then 4 active
   flags (plus 4 where the opening shapes' static solves changed the point). */
#define BOLT_ROM_STATE 28

static PetscErrorCode BoltROMSavePreloadState(BoltROM *rom, PetscViewer v)
{
  BoltContactSet *c = rom->contact;
  const PetscInt  ne = BoltContactSetElementCount(c);
  PetscScalar    *buf;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(BOLT_ROM_STATE * ne + 1, &buf));
  for (PetscInt e = 0; e < ne; e++) buf[e] = BoltContactSetElementKey(c, e);
  PetscCall(BoltHDF5WriteValues(v, rom->comm, "state_keys", ne, 1, buf, PETSC_FALSE));
  for (PetscInt e = 0; e < ne; e++) {
    for (PetscInt i = 0; i < 12; i++) buf[BOLT_ROM_STATE * e + i] = rom->lambda0[12 * e + i];
    for (PetscInt i = 0; i < 12; i++) buf[BOLT_ROM_STATE * e + 12 + i] = rom->gap0[12 * e + i];
    /* 1 closed, 2 closed and sliding (strict law), 0 open; plus 4 where the opening shapes' solves changed it */
    for (PetscInt i = 0; i < 4; i++) buf[BOLT_ROM_STATE * e + 24 + i] = (rom->active0[4 * e + i] ? (rom->released0[4 * e + i] ? 2.0 : 1.0) : 0.0) + (rom->marked && rom->marked[4 * e + i] ? 4.0 : 0.0);
  }
  PetscCall(BoltHDF5WriteValues(v, rom->comm, "state", BOLT_ROM_STATE * ne, 1, buf, PETSC_FALSE));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltROMLoadPreloadState(BoltROM *rom, BoltContactSet *c, PetscViewer v, const char file[])
{
  PetscInt     n;
  PetscReal   *keys, *x;
  BoltKeyIndex *ix;

  PetscFunctionBeginUser;
  PetscCall(BoltReadAll(v, rom->comm, "state_keys", &n, &keys));
  PetscCall(BoltKeyIndexCreate(n, keys, &ix));
  PetscCall(PetscFree(keys));
  PetscCall(BoltReadAll(v, rom->comm, "state", &n, &x));
  PetscCheck(n == BOLT_ROM_STATE * BoltKeyIndexSize(ix), rom->comm, PETSC_ERR_FILE_UNEXPECTED, "ROM file %s is damaged (preloaded state of %" PetscInt_FMT " values for %" PetscInt_FMT " elements): build a new one with -rom_rebuild FILE", file, n, BoltKeyIndexSize(ix));
  PetscCall(PetscMalloc4(12 * BoltContactSetElementCount(c) + 1, &rom->lambda0, 12 * BoltContactSetElementCount(c) + 1, &rom->gap0, 4 * BoltContactSetElementCount(c) + 1, &rom->active0, 4 * BoltContactSetElementCount(c) + 1, &rom->released0));
  PetscCall(PetscFree(rom->marked));
  PetscCall(PetscMalloc1(4 * BoltContactSetElementCount(c) + 1, &rom->marked));
  for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++) {
    PetscInt row;
    PetscCall(BoltKeyIndexFind(ix, BoltContactSetElementKey(c, e), &row));
    PetscCheck(row >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "ROM file %s has no preloaded state for contact element %" PetscInt_FMT ": build a new one with -rom_rebuild FILE", file, BoltContactSetElementKey(c, e));
    for (PetscInt i = 0; i < 12; i++) rom->lambda0[12 * e + i] = x[BOLT_ROM_STATE * row + i];
    for (PetscInt i = 0; i < 12; i++) rom->gap0[12 * e + i] = x[BOLT_ROM_STATE * row + 12 + i];
    for (PetscInt i = 0; i < 4; i++) {
      const PetscInt code = (PetscInt)x[BOLT_ROM_STATE * row + 24 + i];
      rom->active0[4 * e + i]   = code % 4 != 0 ? PETSC_TRUE : PETSC_FALSE;
      rom->released0[4 * e + i] = code % 4 == 2 ? PETSC_TRUE : PETSC_FALSE;
      rom->marked[4 * e + i]    = code >= 4 ? PETSC_TRUE : PETSC_FALSE;
    }
  }
  rom->preloadState = PETSC_TRUE;
  PetscCall(BoltKeyIndexDestroy(&ix));
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMSave(BoltROM *rom, BV V, BoltAssembler *asmb, BoltLoadSet *loads, const char file[])
{
  MPI_Comm     comm = rom->comm;
  BoltMesh    *m;
  PetscViewer  v;
  PetscMPIInt  rank;
  char         tmp[PETSC_MAX_PATH_LEN], groups[256] = "";
  PetscInt     ncd, *cd, npts = 0, n = rom->n;
  PetscScalar *a;
  const char  *candidates[] = {"load_point", "corner_point", BoltLoadSetLoadGroup(loads), BoltLoadSetProbeGroup(loads)};

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMesh(asmb, &m));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", file));
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/rom"));
  {
    const PetscScalar *x;
    PetscCall(MatDenseGetArrayRead(rom->Mr, &x));
    PetscCall(BoltHDF5WriteValues(v, comm, "Mr", n * n, n, x, PETSC_TRUE));
    PetscCall(MatDenseRestoreArrayRead(rom->Mr, &x));
    PetscCall(MatDenseGetArrayRead(rom->Cr, &x));
    PetscCall(BoltHDF5WriteValues(v, comm, "Cr", n * n, n, x, PETSC_TRUE));
    PetscCall(MatDenseRestoreArrayRead(rom->Cr, &x));
    PetscCall(MatDenseGetArrayRead(rom->Kr, &x));
    PetscCall(BoltHDF5WriteValues(v, comm, "Kr", n * n, n, x, PETSC_TRUE));
    PetscCall(MatDenseRestoreArrayRead(rom->Kr, &x));
  }
  /* loads per unit amplitude: the file serves any amplitude */
  PetscCall(PetscMalloc1(2 * n + 1, &a));
  {
    const PetscScalar *x, *y;
    PetscCheck(BoltLoadSetPreloadForce(loads) != 0 || !BoltLoadSetHasPreload(loads), comm, PETSC_ERR_USER_INPUT, "A ROM file needs a nonzero -preload_force to store the preload pattern");
    PetscCall(VecGetArrayRead(rom->loadUnitr, &x));
    PetscCall(VecGetArrayRead(rom->preloadr, &y));
    for (PetscInt j = 0; j < n; j++) {
      a[j]     = x[j];
      a[n + j] = BoltLoadSetPreloadForce(loads) != 0 ? y[j] / BoltLoadSetPreloadForce(loads) : 0;
    }
    PetscCall(VecRestoreArrayRead(rom->loadUnitr, &x));
    PetscCall(VecRestoreArrayRead(rom->preloadr, &y));
  }
  PetscCall(BoltHDF5WriteValues(v, comm, "load_unit", n, 1, a, PETSC_TRUE));
  PetscCall(BoltHDF5WriteValues(v, comm, "preload_unit", n, 1, &a[n], PETSC_TRUE));
  PetscCall(PetscFree(a));
  if (rom->rigidr) PetscCall(BoltHDF5WriteValues(v, comm, "rigid", 6 * n, n, rom->rigidr, PETSC_TRUE)); /* a free model's rigid motions, V' R */
  /* rows at the contact DOFs, each rank its owned ones, in global order */
  PetscCall(BoltOwnedContactDofs(rom->contact, BoltLoadSetLoad(loads), &ncd, &cd));
  {
    Vec          w, d;
    PetscScalar *x, *y;
    PetscInt     rstart;
    PetscCall(VecCreateMPI(comm, ncd * n, PETSC_DETERMINE, &w));
    PetscCall(VecSetBlockSize(w, n));
    PetscCall(PetscObjectSetName((PetscObject)w, "Vc"));
    PetscCall(VecCreateMPI(comm, ncd, PETSC_DETERMINE, &d));
    PetscCall(PetscObjectSetName((PetscObject)d, "contact_dof_keys"));
    PetscCall(VecGetArray(w, &x));
    PetscCall(VecGetArray(d, &y));
    {
      Vec                keys;
      const PetscScalar *k;
      PetscInt           kstart;
      PetscCall(BoltMeshDofKeys(BoltContactSetMesh(rom->contact), BoltLoadSetLoad(loads), &keys));
      PetscCall(VecGetOwnershipRange(keys, &kstart, NULL));
      PetscCall(VecGetArrayRead(keys, &k));
      for (PetscInt i = 0; i < ncd; i++) y[i] = k[cd[i] - kstart];
      PetscCall(VecRestoreArrayRead(keys, &k));
      PetscCall(VecDestroy(&keys));
    }
    for (PetscInt j = 0; j < n; j++) {
      Vec                col;
      const PetscScalar *c;
      PetscCall(BVGetColumn(V, j, &col));
      PetscCall(VecGetOwnershipRange(col, &rstart, NULL));
      PetscCall(VecGetArrayRead(col, &c));
      for (PetscInt i = 0; i < ncd; i++) x[i * n + j] = c[cd[i] - rstart];
      PetscCall(VecRestoreArrayRead(col, &c));
      PetscCall(BVRestoreColumn(V, j, &col));
    }
    PetscCall(VecRestoreArray(w, &x));
    PetscCall(VecRestoreArray(d, &y));
    PetscCall(VecView(w, v));
    PetscCall(VecView(d, v));
    PetscCall(VecDestroy(&w));
    PetscCall(VecDestroy(&d));
  }
  PetscCall(PetscFree(cd));
  /* rows at the point groups (loads and probes a later scene may use) */
  {
    PetscScalar *rows;
    PetscCall(PetscMalloc1(4 * 3 * n + 1, &rows));
    for (PetscInt g = 0; g < 4; g++) {
      PetscBool found = PETSC_FALSE, dup = PETSC_FALSE;
      for (PetscInt h = 0; h < g; h++) {
        PetscBool same;
        PetscCall(PetscStrcmp(candidates[g], candidates[h], &same));
        dup = (PetscBool)(dup || same);
      }
      if (dup) continue;
      PetscCall(BoltPointRows(m, V, candidates[g], n, &rows[3 * n * npts], &found));
      if (!found) continue;
      if (npts) PetscCall(PetscStrlcat(groups, ",", sizeof(groups)));
      PetscCall(PetscStrlcat(groups, candidates[g], sizeof(groups)));
      npts++;
    }
    PetscCall(BoltHDF5WriteValues(v, comm, "Vpoints", 3 * npts * n, n, rows, PETSC_TRUE));
    PetscCall(PetscFree(rows));
  }
  PetscCall(BoltROMBasisSave(rom, V, m, v)); /* the whole basis, for the fields of a run that reads the file (rom_field.c) */
  if (rom->preloadState) PetscCall(BoltROMSavePreloadState(rom, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(BoltROMFingerprintWrite(&rom->fingerprint, v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "point_groups", PETSC_STRING, groups));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "input_load", PETSC_STRING, BoltLoadSetLoadGroup(loads)));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "input_direction_x", PETSC_REAL, &BoltLoadSetLoadDirection(loads)[0]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "input_direction_y", PETSC_REAL, &BoltLoadSetLoadDirection(loads)[1]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "input_direction_z", PETSC_REAL, &BoltLoadSetLoadDirection(loads)[2]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "dimension", PETSC_INT, &n));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "order", PETSC_INT, &rom->order));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "inputs", PETSC_INT, &rom->ninputs));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "n_ccm", PETSC_INT, &rom->nCCM));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "n_jim", PETSC_INT, &rom->nJIM));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "opening_pairs", PETSC_INT, &rom->nOpeningPairs));
  {
    PetscInt tied = rom->autoTied ? 1 : 0; /* -rom_train auto made it the tied ROM */
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "auto_tied", PETSC_INT, &tied));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "snapshot_modes", PETSC_INT, &rom->nSnapshotModes));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "cone_pairs", PETSC_INT, &rom->nConePairs));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "cone_modes", PETSC_INT, &rom->nConeModes));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "s0", PETSC_REAL, &rom->s0));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/Mr", "offline_s", PETSC_REAL, &rom->tOffline));
  PetscCall(PetscViewerDestroy(&v));
  if (rank == 0) PetscCall(BoltHDF5Seal(tmp)); /* complete: sealed, then given its name */
  if (rank == 0) PetscCheck(rename(tmp, file) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", tmp, file);
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscPrintf(comm, "ROM written to %s (dimension %" PetscInt_FMT ", rows at %" PetscInt_FMT " contact DOFs per rank and at %s)\n", file, n, ncd, groups));
  PetscFunctionReturn(0);
}

/* The file's rows of the basis at this rank's contact DOFs (keyed by DOF keys that name a DOF
   on any partition) into rom->Vc. */
static PetscErrorCode ROMLoadContactRows(BoltROM *rom, BoltContactSet *c, BoltLoadSet *loads, PetscViewer v, const char file[])
{
  Vec          w;
  PetscInt     ncd, n = rom->n;
  PetscScalar *a, *Vc, *cdofs;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(PETSC_COMM_SELF, &w));
  PetscCall(PetscObjectSetName((PetscObject)w, "contact_dof_keys"));
  PetscCall(VecLoad(w, v));
  PetscCall(VecGetSize(w, &ncd));
  PetscCall(PetscMalloc2(ncd + 1, &cdofs, ncd * n + 1, &Vc));
  PetscCall(VecGetArray(w, &a));
  PetscCall(PetscArraycpy(cdofs, a, ncd));
  PetscCall(VecRestoreArray(w, &a));
  PetscCall(VecDestroy(&w));
  PetscCall(BoltReadArray(v, "Vc", ncd, n, Vc));
  {
    /* the file's rows are keyed by partition-independent DOF keys: find ours among them */
    Vec                keys, ckeys;
    const PetscScalar *k;
    PetscInt          *fileKey, *perm;
    PetscCall(PetscMalloc2(ncd + 1, &fileKey, ncd + 1, &perm));
    for (PetscInt i = 0; i < ncd; i++) {
      fileKey[i] = (PetscInt)PetscRealPart(cdofs[i]);
      perm[i]    = i;
    }
    PetscCall(PetscSortIntWithArray(ncd, fileKey, perm));
    PetscCall(BoltMeshDofKeys(BoltContactSetMesh(c), BoltLoadSetLoad(loads), &keys));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, BoltContactSetLocalSize(c), &ckeys));
    PetscCall(VecScatterBegin(BoltContactSetScatterContext(c), keys, ckeys, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(BoltContactSetScatterContext(c), keys, ckeys, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(PetscCalloc1(BoltContactSetLocalSize(c) * n + 1, &rom->Vc));
    PetscCall(VecGetArrayRead(ckeys, &k));
    for (PetscInt i = 0; i < BoltContactSetLocalSize(c); i++) {
      PetscInt key = (PetscInt)PetscRealPart(k[i]), loc;
      PetscCall(PetscFindInt(key, ncd, fileKey, &loc));
      PetscCheck(loc >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "ROM file %s lacks the row of contact DOF %" PetscInt_FMT " (key %" PetscInt_FMT "): build a new one with -rom_rebuild FILE", file, BoltContactSetLocalGlobal(c)[i], key);
      for (PetscInt j = 0; j < n; j++) rom->Vc[i + BoltContactSetLocalSize(c) * j] = Vc[perm[loc] * n + j];
    }
    PetscCall(VecRestoreArrayRead(ckeys, &k));
    PetscCall(VecDestroy(&ckeys));
    PetscCall(VecDestroy(&keys));
    PetscCall(PetscFree2(fileKey, perm));
  }
  PetscCall(PetscFree2(cdofs, Vc));
  PetscFunctionReturn(0);
}

/* Reads a matching ROM file into rom (its settings resolved). *matched is false (and nothing is
   read) when the fingerprint differs or the file does not serve the scene's load or probe; *why
   then says what differs first. */
PetscErrorCode BoltROMLoad(const char file[], BoltROM *rom, BoltContactSet *c, BoltLoadSet *loads, PetscBool *matched, char why[], size_t whylen)
{
  BoltReductionOptions *o    = &rom->opt;
  MPI_Comm     comm = o->comm;
  PetscViewer  v;
  char        *groups = NULL, *input = NULL;
  PetscInt     n, npts = 0;
  PetscScalar *a, *Vpoints;
  PetscBool    same;

  PetscFunctionBeginUser;
  *matched = PETSC_FALSE;
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, file, FILE_MODE_READ, &v));
  PetscCall(BoltROMFingerprintMatch(&rom->fingerprint, v, matched, why, whylen));
  if (*matched) PetscCall(BoltROMFingerprintMatchLoad(v, loads, o->extraInputs, matched, &same, why, whylen));
  if (!*matched) {
    PetscCall(PetscViewerDestroy(&v));
    PetscFunctionReturn(0);
  }
  *matched = PETSC_FALSE;
  rom->contact  = c;
  rom->fromFile = PETSC_TRUE;
  rom->orthogonality = -1;
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "dimension", PETSC_INT, NULL, &n));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "order", PETSC_INT, NULL, &rom->order));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "inputs", PETSC_INT, NULL, &rom->ninputs));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "n_ccm", PETSC_INT, NULL, &rom->nCCM));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "n_jim", PETSC_INT, NULL, &rom->nJIM));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "opening_pairs", PETSC_INT, NULL, &rom->nOpeningPairs));
  {
    PetscInt none = 0, tied = 0; /* files written before the modes existed have none */
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "snapshot_modes", PETSC_INT, &none, &rom->nSnapshotModes));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "cone_pairs", PETSC_INT, &none, &rom->nConePairs));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "cone_modes", PETSC_INT, &none, &rom->nConeModes));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "auto_tied", PETSC_INT, &none, &tied));
    rom->autoTied = (PetscBool)(tied != 0);
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "s0", PETSC_REAL, NULL, &rom->s0));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "point_groups", PETSC_STRING, NULL, &groups));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "input_load", PETSC_STRING, NULL, &input));
  rom->n = n;
  PetscCall(PetscViewerHDF5PushGroup(v, "/rom"));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Mr));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Cr));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Kr));
  {
    PetscScalar *x;
    PetscCall(MatDenseGetArray(rom->Mr, &x));
    PetscCall(BoltReadArray(v, "Mr", n, n, x));
    PetscCall(MatDenseRestoreArray(rom->Mr, &x));
    PetscCall(MatDenseGetArray(rom->Cr, &x));
    PetscCall(BoltReadArray(v, "Cr", n, n, x));
    PetscCall(MatDenseRestoreArray(rom->Cr, &x));
    PetscCall(MatDenseGetArray(rom->Kr, &x));
    PetscCall(BoltReadArray(v, "Kr", n, n, x));
    PetscCall(MatDenseRestoreArray(rom->Kr, &x));
  }
  /* point rows: which groups, 3 rows each */
  {
    char **names;
    int    nn;
    PetscCall(PetscStrToArray(groups, ',', &nn, &names));
    npts = nn;
    PetscCall(PetscMalloc1(3 * npts * n + 1, &Vpoints));
    PetscCall(BoltReadArray(v, "Vpoints", 3 * npts, n, Vpoints));
    /* the load: an input of this ROM, or a point group whose rows are here (if allowed) */
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &rom->loadr));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &rom->preloadr));
    PetscCall(PetscMalloc1(n + 1, &a));
    if (same) { /* the file's input load (BoltROMFingerprintMatchLoad) */
      PetscCall(BoltReadArray(v, "load_unit", n, 1, a));
      for (PetscInt j = 0; j < n; j++) a[j] *= BoltLoadSetLoadForce(loads);
    } else {
      PetscInt g = -1;
      for (PetscInt k = 0; k < npts; k++) {
        PetscBool s;
        PetscCall(PetscStrcmp(names[k], BoltLoadSetLoadGroup(loads), &s));
        if (s) g = k;
      }
      PetscCheck(g >= 0, comm, PETSC_ERR_PLIB, "ROM file %s: no rows at '%s'", file, BoltLoadSetLoadGroup(loads));
      for (PetscInt j = 0; j < n; j++) {
        a[j] = 0;
        for (PetscInt d = 0; d < 3; d++) a[j] += BoltLoadSetLoadForce(loads) * BoltLoadSetLoadDirection(loads)[d] * Vpoints[(3 * g + d) * n + j];
      }
      PetscCall(PetscPrintf(comm, "ROM: the load at '%s' along %.17g,%.17g,%.17g is not the input of %s (built for '%s'): projected with the stored rows, as asked\n", BoltLoadSetLoadGroup(loads), (double)BoltLoadSetLoadDirection(loads)[0], (double)BoltLoadSetLoadDirection(loads)[1], (double)BoltLoadSetLoadDirection(loads)[2], file, input));
    }
    {
      PetscScalar *x;
      PetscCall(VecGetArray(rom->loadr, &x));
      PetscCall(PetscArraycpy(x, a, n));
      PetscCall(VecRestoreArray(rom->loadr, &x));
      PetscCall(BoltReadArray(v, "preload_unit", n, 1, a));
      PetscCall(VecGetArray(rom->preloadr, &x));
      for (PetscInt j = 0; j < n; j++) x[j] = a[j] * BoltLoadSetPreloadForce(loads);
      PetscCall(VecRestoreArray(rom->preloadr, &x));
    }
    /* the probe row */
    {
      PetscInt g = -1;
      for (PetscInt k = 0; k < npts; k++) {
        PetscBool s;
        PetscCall(PetscStrcmp(names[k], BoltLoadSetProbeGroup(loads), &s));
        if (s) g = k;
      }
      PetscCheck(g >= 0, comm, PETSC_ERR_PLIB, "ROM file %s: no rows at the probe '%s'", file, BoltLoadSetProbeGroup(loads));
      PetscCall(PetscMalloc1(n + 1, &rom->Vprobe));
      for (PetscInt j = 0; j < n; j++) rom->Vprobe[j] = PetscRealPart(Vpoints[(3 * g + BoltLoadSetProbeComponent(loads)) * n + j]);
    }
    PetscCall(PetscStrToArrayDestroy(nn, names));
    PetscCall(PetscFree(a));
    PetscCall(PetscFree(Vpoints));
  }
  PetscCall(ROMLoadContactRows(rom, c, loads, v, file));
  if (BoltMeshIsFree(BoltContactSetMesh(c))) { /* the fingerprint's mesh hash and clamp make it a free model's file */
    PetscCall(PetscMalloc1(6 * n, &rom->rigidr));
    PetscCall(BoltReadArray(v, "rigid", 6, n, rom->rigidr));
  }
  if (rom->preloadState) PetscCall(BoltROMLoadPreloadState(rom, c, v, file));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscFree(groups));
  PetscCall(PetscFree(input));
  PetscCall(PetscViewerDestroy(&v));
  *matched = PETSC_TRUE;
  PetscFunctionReturn(0);
}
