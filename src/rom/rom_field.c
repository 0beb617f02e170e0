/* The ROM's displacement in the full model's coordinates, u = V q, for the output (ParaView).
   The online ROM keeps only V's rows at the contact DOFs and the point groups; the whole basis is
   handed over by the offline build (BoltROMKeepBasis) and kept with the reduced mass matrix, so
   that it lives and dies with the ROM, until the app releases it (BoltROMReleaseBasis). The ROM
   file keeps it too (/rom/basis: V by rows, keyed by DOF keys that name a DOF on any partition),
   read back only when a ROM from a file writes its fields (BoltROMBasisEnsure). */
#include "private/rom.h"
#include <petscviewerhdf5.h>

static const char boltROMBasisKey[] = "BoltROMBasis";

/* The whole basis, if the ROM keeps it (else NULL). */
PetscErrorCode ROMGetBasis(BoltROM *rom, BV *V)
{
  PetscFunctionBeginUser;
  *V = NULL;
  if (rom && rom->Mr) PetscCall(PetscObjectQuery((PetscObject)rom->Mr, boltROMBasisKey, (PetscObject *)V));
  PetscFunctionReturn(0);
}

/* Keeps the whole basis V (a reference: the caller still destroys its own). */
PetscErrorCode BoltROMKeepBasis(BoltROM *rom, BV V)
{
  PetscFunctionBeginUser;
  PetscCheck(rom->Mr, rom->comm, PETSC_ERR_ORDER, "The ROM keeps its basis once projected");
  PetscCall(PetscObjectCompose((PetscObject)rom->Mr, boltROMBasisKey, (PetscObject)V));
  PetscFunctionReturn(0);
}

/* Whether the ROM can give its displacement in full (a ROM read from a file has no whole basis). */
PetscErrorCode BoltROMHasBasis(BoltROM *rom, PetscBool *has)
{
  BV V;

  PetscFunctionBeginUser;
  PetscCall(ROMGetBasis(rom, &V));
  *has = V ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* u = V q: q the ROM's coordinates (the same on every rank), u of the full model's layout. */
PetscErrorCode BoltROMExpand(BoltROM *rom, Vec q, Vec u)
{
  BV                 V;
  const PetscScalar *a;
  PetscInt           nq;

  PetscFunctionBeginUser;
  PetscCall(ROMGetBasis(rom, &V));
  PetscCheck(V, rom->comm, PETSC_ERR_ORDER, "The ROM has no whole basis to expand its coordinates with");
  PetscCall(VecGetLocalSize(q, &nq));
  PetscCheck(nq == rom->n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "ROM coordinates of size %" PetscInt_FMT ", the ROM has %" PetscInt_FMT, nq, rom->n);
  PetscCall(BVSetActiveColumns(V, 0, rom->n));
  PetscCall(VecGetArrayRead(q, &a));
  PetscCall(BVMultVec(V, 1.0, 0.0, u, (PetscScalar *)a));
  PetscCall(VecRestoreArrayRead(q, &a));
  PetscFunctionReturn(0);
}

/* Frees the whole basis (nothing if it was not kept). */
PetscErrorCode BoltROMReleaseBasis(BoltROM *rom)
{
  PetscFunctionBeginUser;
  if (rom && rom->Mr) PetscCall(PetscObjectCompose((PetscObject)rom->Mr, boltROMBasisKey, NULL));
  PetscFunctionReturn(0);
}

/* The whole basis into the ROM file being written (v, group /rom/basis): "V", (N, n) by rows of
   this partition's global order, and "dof_keys", the key of each row's DOF. */
PetscErrorCode BoltROMBasisSave(BoltROM *rom, BV V, BoltMesh *mesh, PetscViewer v)
{
  const PetscInt n = rom->n;
  Vec            w, keys, col;
  PetscInt       nloc, N;
  PetscScalar   *x;

  PetscFunctionBeginUser;
  PetscCall(BVCreateVec(V, &col));
  PetscCall(VecGetLocalSize(col, &nloc));
  PetscCall(VecGetSize(col, &N));
  PetscCall(BoltMeshDofKeys(mesh, col, &keys));
  PetscCall(PetscObjectSetName((PetscObject)keys, "dof_keys"));
  PetscCall(VecCreateMPI(rom->comm, nloc * n, N * n, &w));
  PetscCall(VecSetBlockSize(w, n));
  PetscCall(PetscObjectSetName((PetscObject)w, "V"));
  PetscCall(VecGetArray(w, &x));
  for (PetscInt j = 0; j < n; j++) {
    const PetscScalar *c;
    PetscCall(BVCopyVec(V, j, col));
    PetscCall(VecGetArrayRead(col, &c));
    for (PetscInt i = 0; i < nloc; i++) x[i * n + j] = c[i];
    PetscCall(VecRestoreArrayRead(col, &c));
  }
  PetscCall(VecRestoreArray(w, &x));
  PetscCall(PetscViewerHDF5PushGroup(v, "/rom/basis"));
  PetscCall(VecView(w, v));
  PetscCall(VecView(keys, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&keys));
  PetscCall(VecDestroy(&col));
  PetscFunctionReturn(0);
}

/* For each of the file's local rows (keys fk), its row in this partition's global order. */
static PetscErrorCode BoltROMBasisRows(BoltMesh *mesh, Vec layout, Vec fk, const char file[], PetscInt **rows)
{
  Vec                ck, all;
  VecScatter         sc;
  BoltKeyIndex      *ix;
  const PetscScalar *a;
  PetscReal         *keys;
  PetscInt           N, nl;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshDofKeys(mesh, layout, &ck));
  PetscCall(VecScatterCreateToAll(ck, &sc, &all));
  PetscCall(VecScatterBegin(sc, ck, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, ck, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetSize(all, &N));
  PetscCall(PetscMalloc1(N + 1, &keys));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt i = 0; i < N; i++) keys[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(BoltKeyIndexCreate(N, keys, &ix));
  PetscCall(VecGetLocalSize(fk, &nl));
  PetscCall(PetscMalloc1(nl + 1, rows));
  PetscCall(VecGetArrayRead(fk, &a));
  for (PetscInt i = 0; i < nl; i++) {
    PetscCall(BoltKeyIndexFind(ix, (PetscInt)PetscRealPart(a[i]), &(*rows)[i]));
    PetscCheck((*rows)[i] >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "ROM file %s: its basis has a DOF this mesh has not: rebuild the ROM", file);
  }
  PetscCall(VecRestoreArrayRead(fk, &a));
  PetscCall(BoltKeyIndexDestroy(&ix));
  PetscCall(PetscFree(keys));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&ck));
  PetscFunctionReturn(0);
}

/* Reads the file's whole basis into this partition (layout: a vector of the full model). */
static PetscErrorCode BoltROMBasisLoad(BoltROM *rom, PetscViewer v, const char file[], BoltMesh *mesh, Vec layout)
{
  const PetscInt n = rom->n;
  Vec            fk, fv, cv, col;
  IS             from, to;
  VecScatter     sc;
  BV             V;
  PetscInt       N, nl = PETSC_DECIDE, fstart = 0, nloc, *rows;
  PetscScalar   *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(layout, &N));
  PetscCall(VecGetLocalSize(layout, &nloc));
  PetscCall(PetscSplitOwnership(rom->comm, &nl, &N));
  PetscCallMPI(MPI_Exscan(&nl, &fstart, 1, MPIU_INT, MPI_SUM, rom->comm));
  PetscCall(VecCreateMPI(rom->comm, nl, N, &fk));
  PetscCall(VecCreateMPI(rom->comm, nl * n, N * n, &fv));
  PetscCall(VecSetBlockSize(fv, n));
  PetscCall(PetscObjectSetName((PetscObject)fk, "dof_keys"));
  PetscCall(PetscObjectSetName((PetscObject)fv, "V"));
  PetscCall(PetscViewerHDF5PushGroup(v, "/rom/basis"));
  PetscCall(VecLoad(fk, v));
  PetscCall(VecLoad(fv, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(BoltROMBasisRows(mesh, layout, fk, file, &rows));
  PetscCall(VecCreateMPI(rom->comm, nloc * n, N * n, &cv));
  PetscCall(ISCreateStride(rom->comm, nl * n, fstart * n, 1, &from));
  PetscCall(ISCreateBlock(rom->comm, n, nl, rows, PETSC_OWN_POINTER, &to));
  PetscCall(VecScatterCreate(fv, from, cv, to, &sc));
  PetscCall(VecScatterBegin(sc, fv, cv, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, fv, cv, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(BVCreate(rom->comm, &V));
  PetscCall(BVSetSizesFromVec(V, layout, n));
  PetscCall(BVSetFromOptions(V));
  PetscCall(VecGetArray(cv, &x));
  for (PetscInt j = 0; j < n; j++) {
    PetscScalar *c;
    PetscCall(BVGetColumn(V, j, &col));
    PetscCall(VecGetArray(col, &c));
    for (PetscInt i = 0; i < nloc; i++) c[i] = x[i * n + j];
    PetscCall(VecRestoreArray(col, &c));
    PetscCall(BVRestoreColumn(V, j, &col));
  }
  PetscCall(VecRestoreArray(cv, &x));
  PetscCall(BoltROMKeepBasis(rom, V));
  PetscCall(BVDestroy(&V));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(ISDestroy(&from));
  PetscCall(ISDestroy(&to));
  PetscCall(VecDestroy(&cv));
  PetscCall(VecDestroy(&fv));
  PetscCall(VecDestroy(&fk));
  PetscFunctionReturn(0);
}

/* Whether the ROM can give its displacement in full: with the basis it built, or one its file
   keeps (read here); a file written before the files kept it has none (said in the log). */
PetscErrorCode BoltROMBasisEnsure(BoltROM *rom, BoltMesh *mesh, Vec layout, PetscBool *has)
{
  const char *file = rom->opt.file;
  PetscViewer v;

  PetscFunctionBeginUser;
  PetscCall(BoltROMHasBasis(rom, has));
  if (*has || !rom->fromFile || !file[0]) PetscFunctionReturn(0);
  PetscCall(PetscViewerHDF5Open(rom->comm, file, FILE_MODE_READ, &v));
  PetscCall(PetscViewerHDF5HasDataset(v, "/rom/basis/V", has));
  if (*has) PetscCall(BoltROMBasisLoad(rom, v, file, mesh, layout));
  else PetscCall(PetscPrintf(rom->comm, "ROM file %s keeps no whole basis (written before files kept it): no rom_ displacement fields; rebuild it for them\n", file));
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(0);
}
