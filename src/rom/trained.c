/* The trained ROM (-rom_train): exact where the contact can change, held everywhere else. A FOM
   run of the scene records the contact points whose state (open, sticking, slipping) left the
   preloaded one after some step: their node pairs are the changing pairs. They, and the pairs of
   the points that share a contact element with a changed one, get three unit-force inputs each,
   beside the load and the preload; the Krylov basis is taken about the preloaded joint (K plus
   the FOM's contact stiffness of its preloaded state), so the first block holds the response to
   a force at each changing pair. Every closed node pair but the changing ones is then tied in the
   basis (no column opens, shears or presses it; under friction only its normal, so that a held
   stick keeps its spring): held by a penalty instead, the stiff springs lock the reduced model;
   a pair that slips anywhere in the training run changes. The ROM takes the FOM's penalty and
   band as they are, with no scale of its own; online only the points the FOM changed may change,
   and the check of every node pair (-contact_check_every) says when a held one would leave its
   state (docs/reduction.md, "The trained ROM"). */
#include "private/rom.h"

PetscBool BoltROMIsTrained(const BoltROM *rom)
{
  return rom->opt.trained;
}

/* The trained ROM's settings, none of them the user's: the penalty law at the FOM's penalty,
   started from the FOM's preloaded state (its multipliers frozen at the held points); the caller
   adds the static shapes of that state and no opening shapes (the changing pairs' inputs take
   their place), and no cone shapes under friction (the changing pairs include the slipping
   ones). */
PetscErrorCode ROMTrainedSettings(BoltROM *rom, BoltLoadSet *loads)
{
  PetscFunctionBeginUser;
  PetscCheck(BoltLoadSetHasPreload(loads) && BoltLoadSetPreloadForce(loads) != 0, rom->comm, PETSC_ERR_USER_INPUT, "-rom_train starts from the FOM's preloaded joint: give a nonzero -preload_force");
  rom->augment      = PETSC_FALSE;
  rom->preloadState = PETSC_TRUE;
  rom->penaltyScale = 1;
  PetscFunctionReturn(0);
}

/* K + K_c of the FOM's preloaded state (the FOM's penalties and sticks), a new matrix. */
static PetscErrorCode ROMPreloadedStiffness(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, Mat *Kheld)
{
  BoltOperator *fom;
  Mat           K, M, Kc;
  Vec           q;
  PetscBool     set, sym;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMatrices(asmb, &K, &M));
  PetscCall(BoltFOMCreate(asmb, contact, loads, PETSC_FALSE, &fom));
  PetscCall(MatCreateVecs(K, &q, NULL));
  PetscCall(BoltPreloadStateApply(rom->opt.fomPreload, fom, q));
  PetscCall(BoltContactStateStiffness(BoltOperatorState(fom), &Kc));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, Kheld));
  PetscCall(MatAXPY(*Kheld, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatIsSymmetricKnown(K, &set, &sym));
  if (set && sym) PetscCall(MatSetOption(*Kheld, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(VecDestroy(&q));
  PetscCall(BoltOperatorDestroy(&fom));
  PetscFunctionReturn(0);
}

/* The inputs B (three per input node pair, the load, the preload's) and the stiffness the Krylov
   basis is taken with; marks the points the FOM changed in rom (held online: the others). */
PetscErrorCode ROMTrainedInputs(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, BV *B, Mat *Kheld)
{
  BoltReductionOptions *o  = &rom->opt;
  const PetscInt        np = 4 * BoltContactSetElementCount(contact);
  PetscInt              npairs;
  PetscBool            *free_;

  PetscFunctionBeginUser;
  PetscCheck(o->fomChanged && o->fomPreload, o->comm, PETSC_ERR_USER_INPUT, "-rom_train learns where the contact changes from the FOM's run of the scene: add -fom true, or give a -rom_file built with -rom_train for this scene");
  PetscCall(PetscFree(rom->marked));
  PetscCall(PetscMalloc1(np + 1, &rom->marked));
  PetscCall(PetscMalloc1(np + 1, &free_));
  PetscCall(PetscArraycpy(rom->marked, o->fomChanged, np));
  /* inputs at the pairs of the changed points and of the points sharing a contact element with
     one: the neighbours stay tied, but their responses give the basis the deformation next to a
     pair that opens (paper-step at level 0.5, order 4: e_L2 3.3e-3 without, 9.2e-5 with them;
     docs/decisions.md) */
  PetscCall(PetscArraycpy(free_, rom->marked, np));
  for (PetscInt e = 0; e < np / 4; e++) {
    PetscBool any = PETSC_FALSE;
    for (PetscInt q = 0; q < 4; q++) any = (PetscBool)(any || rom->marked[4 * e + q]);
    if (any)
      for (PetscInt q = 0; q < 4; q++) free_[4 * e + q] = PETSC_TRUE;
  }
  PetscCall(ROMInputMatrix(contact, loads, BoltLoadSetLoad(loads), free_, B, &rom->ninputs, &npairs));
  PetscCall(PetscFree(free_));
  rom->nOpeningPairs = npairs;
  PetscCall(PetscPrintf(o->comm, "ROM: trained on %s: %" PetscInt_FMT " node pairs changed their contact state there or neighbour one that did: they are its inputs; the closed pairs that did not change are tied\n", o->trainStatic ? "static solves" : "the FOM's run", npairs));
  PetscCall(ROMPreloadedStiffness(rom, asmb, contact, loads, Kheld));
  PetscFunctionReturn(0);
}

/* The tied node pairs, the same list on every rank: the closed pairs of the preloaded state with
   no point the FOM changed, side b not clamped; as (a dof, b dof) of their x component (a -1
   where clamped), with their normals (3 each) if asked. */
PetscErrorCode ROMTiedPairs(BoltROM *rom, BoltContactSet *contact, PetscInt *ntie, PetscInt **pairs, PetscReal **normals)
{
  const PetscInt np = 4 * BoltContactSetElementCount(contact);
  PetscBool     *held;
  PetscInt       nheld, *hp, nm, *mp, k = 0;
  PetscReal     *hn;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(np + 1, &held));
  for (PetscInt i = 0; i < np; i++) held[i] = (PetscBool)(rom->active0[i] && !rom->marked[i]);
  PetscCall(BoltNodePairsDirected(contact, held, 1, BoltContactSetNormals(contact), &nheld, &hp, &hn));
  PetscCall(BoltNodePairs(contact, rom->marked, &nm, &mp));
  PetscCall(PetscFree(held));
  for (PetscInt i = 0; i < nheld; i++) { /* pairs with a changing point stay free */
    PetscBool free_ = PETSC_FALSE;
    for (PetscInt j = 0; j < nm && !free_; j++) free_ = (PetscBool)(mp[2 * j] == hp[2 * i] && mp[2 * j + 1] == hp[2 * i + 1]);
    if (free_ || hp[2 * i + 1] < 0) continue;
    hp[2 * k]     = hp[2 * i];
    hp[2 * k + 1] = hp[2 * i + 1];
    for (PetscInt d = 0; d < 3; d++) hn[3 * k + d] = hn[3 * i + d];
    k++;
  }
  PetscCall(PetscFree(mp));
  *ntie  = k;
  *pairs = hp;
  if (normals) *normals = hn;
  else PetscCall(PetscFree(hn));
  PetscFunctionReturn(0);
}

/* Ties the held closed node pairs in every column of V: side b takes side a's displacement (zero
   where a is clamped), so that no combination of columns opens, shears or presses a held pair;
   under friction b loses only its normal motion relative to a (a held stick keeps its spring).
   Held by a penalty instead, the stiff springs lock the reduced model. */
PetscErrorCode ROMTieHeld(BoltROM *rom, BoltContactSet *contact, BV V)
{
  const PetscBool normalOnly = BoltContactSetHasFriction(contact);
  PetscInt   ntie, *hp, ncol, rstart, rend, *from;
  PetscReal *hn;
  Vec        v0, seq;
  VecScatter sc;
  IS         isFrom;

  PetscFunctionBeginUser;
  PetscCall(ROMTiedPairs(rom, contact, &ntie, &hp, &hn));
  PetscCall(PetscMalloc1(3 * ntie + 1, &from));
  for (PetscInt i = 0; i < ntie; i++)
    for (PetscInt d = 0; d < 3; d++) from[3 * i + d] = hp[2 * i] >= 0 ? hp[2 * i] + d : hp[2 * i + 1] + d; /* (clamped a: read anything, write 0) */
  PetscCall(BVGetColumn(V, 0, &v0));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 3 * ntie, from, PETSC_COPY_VALUES, &isFrom));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * ntie, &seq));
  PetscCall(VecScatterCreate(v0, isFrom, seq, NULL, &sc));
  PetscCall(VecGetOwnershipRange(v0, &rstart, &rend));
  PetscCall(BVRestoreColumn(V, 0, &v0));
  PetscCall(BVGetSizes(V, NULL, NULL, &ncol));
  for (PetscInt j = 0; j < ncol; j++) {
    Vec                v;
    PetscScalar       *x;
    const PetscScalar *s;
    PetscCall(BVGetColumn(V, j, &v));
    PetscCall(VecScatterBegin(sc, v, seq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, v, seq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArray(v, &x));
    PetscCall(VecGetArrayRead(seq, &s));
    for (PetscInt i = 0; i < ntie; i++) {
      const PetscInt b = hp[2 * i + 1];
      if (b < rstart || b >= rend) continue; /* (a node's three DOFs are on one rank) */
      if (normalOnly) { /* friction: the sticks keep their springs, the normal is tied */
        PetscReal rn = 0;
        for (PetscInt d = 0; d < 3; d++) rn += hn[3 * i + d] * (x[b - rstart + d] - (hp[2 * i] >= 0 ? s[3 * i + d] : 0));
        for (PetscInt d = 0; d < 3; d++) x[b - rstart + d] -= rn * hn[3 * i + d];
      } else
        for (PetscInt d = 0; d < 3; d++) x[b - rstart + d] = hp[2 * i] >= 0 ? s[3 * i + d] : 0;
    }
    PetscCall(VecRestoreArrayRead(seq, &s));
    PetscCall(VecRestoreArray(v, &x));
    PetscCall(BVRestoreColumn(V, j, &v));
  }
  PetscCall(BVOrthogonalize(V, NULL));
  PetscCall(PetscPrintf(rom->comm, "ROM: %" PetscInt_FMT " held node pairs tied in the basis\n", ntie));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&seq));
  PetscCall(ISDestroy(&isFrom));
  PetscCall(PetscFree(from));
  PetscCall(PetscFree(hp));
  PetscCall(PetscFree(hn));
  PetscFunctionReturn(0);
}
