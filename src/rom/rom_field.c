/* The ROM's displacement in the full model's coordinates, u = V q, for the output (ParaView).
   The online ROM keeps only V's rows at the contact DOFs and the point groups; the whole basis is
   handed over by the offline build (BoltROMKeepBasis) and kept with the reduced mass matrix, so
   that it lives and dies with the ROM, until the app releases it (BoltROMReleaseBasis). */
#include "boltrom.h"
#include <slepcbv.h>

static const char boltROMBasisKey[] = "BoltROMBasis";

static PetscErrorCode BoltROMGetBasis(BoltROM *rom, BV *V)
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
  PetscCall(BoltROMGetBasis(rom, &V));
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
  PetscCall(BoltROMGetBasis(rom, &V));
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
