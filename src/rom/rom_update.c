/* Low-rank updates of the ROM's factorised effective matrix. Where the joint opens, the reduced
   active set changes once or more per step; each change made the ROM sum the changed elements
   into K_cr (an exact sum of n^2/2 terms per element) and factorise A = a1 M + a4 C + K + K_cr
   afresh. Instead, a few factorised references A_ref (states met before) are kept, and a solve
   takes the difference from the nearest one as a Woodbury correction:

     A = A_ref + U S U',   x = y - Z w,   (I + S G) w = S U' y,   y = A_ref^-1 b,

   U holding the rows of D = V_b - V_a of the node pairs whose penalty blocks differ from the
   reference's (three columns per node pair, a "slot": the points of one pair, in up to four
   contact elements, share its rows, so their differences sum into one 3 x 3 block; taken per
   point, the correction would have three to four times the rank it needs), S those blocks, Z =
   A_ref^-1 U and G = U' Z. Each reference keeps Z and G of every slot that has differed from it
   (its pool), so a change of the set costs the solves of the slots new to the pool and the
   factorisation of I + S G, the symmetric system of the k differing slots' blocks
   (src/sys/capacitance.c). Updates need nodal points (each point's block touches its own node
   alone); the ROM refactorises otherwise. Where every reference differs by more columns than the
   largest update (3/5 of the dimension; 0 with -rom_verify), or its pool is full, or I + S G is
   singular, the current state is factorised and becomes a reference, replacing the one unused
   longest. The joint opens and closes through the same states period after period, so a few
   references carry a whole run.

   Every rank holds the references and the correction, built from the differing points' records
   gathered, put in the order of their names (element key and node) and merged per node pair in
   that order: the ROM's history has the same
   bits on any partition (each rank makes the same BLAS and LAPACK calls on the same data, or
   takes its share of calls cut the same way on any number of ranks and gathers the others'). */
#include "private/rom.h"
#include <petscblaslapack.h>

#define ROM_REFERENCES 4 /* kept factorisations (docs/reduction.md, section 7): 4 to 16 did about as well */

typedef struct {
  PetscBool  valid;
  PetscInt   lastUsed;
  PetscBool  dynamic; /* the Newmark coefficients it was made with */
  PetscReal  massCoef, dampingCoef;
  Mat        A;
  KSP        ksp;
  PetscReal *Ke;       /* 144 per local element: its penalty blocks */
  PetscBool *dev;      /* per local element: the current block differs from it */
  PetscInt  *slotOf;   /* per node pair (all of them): its slot in the pool, -1 if none */
  PetscInt   nslot;    /* its pool, the same on every rank */
  PetscReal *U, *Z, *G; /* n x 3 per slot, n x 3 per slot, 3 alloc x 3 alloc (column-major) */
} ROMReference;

struct BoltROMUpdate_s {
  PetscInt     maxRank, alloc; /* the largest correction [columns]; slots per pool */
  ROMReference ref[ROM_REFERENCES];
  PetscInt     cur, clock;     /* the reference in force (-1: none), and a use counter */
  BoltDual    *dual;           /* the loop whose solves these are */
  PetscReal   *Kcur;           /* 144 per local element: the current penalty blocks */
  PetscBool   *devRun;         /* per local element: the current block differs from the one in K_cr */
  /* the correction in force: k node pairs, in the order of their first point's name */
  PetscInt      k;
  PetscInt     *act;             /* per active pair: its pool slot */
  PetscInt     *pairAt, *pairOf; /* per node pair (all): its place among the active ones (-1: none); per active one: its node pair */
  PetscInt     *mark;            /* per reference and node pair: whether the pair differs from it (counting) */
  PetscReal    *t, *w;
  PetscReal       *B;   /* S's 3 x 3 block per active pair */
  PetscInt        *idx; /* each column's row of G */
  BoltCapacitance *cap; /* the system of I + S G */
  /* gathering */
  PetscReal   *send, *recv;
  PetscInt     sendAlloc, recvAlloc, recAlloc;
  PetscInt    *name, *perm;      /* per gathered record: its name, and where it starts */
  PetscInt     updates, references;
  PetscInt     largestBatch; /* the most slots that joined a pool at once */
};

/* Whether slot a of a 12 x 12 difference is non-zero (its rows or its columns). */
static PetscBool ROMSlotDiffers(const PetscReal *cur, const PetscReal *ref, PetscInt a)
{
  for (PetscInt r = 3 * a; r < 3 * a + 3; r++)
    for (PetscInt b = 0; b < 12; b++)
      if (cur[12 * r + b] != ref[12 * r + b] || cur[12 * b + r] != ref[12 * b + r]) return PETSC_TRUE;
  return PETSC_FALSE;
}

static PetscBool ROMBlockDiffers(const PetscReal *cur, const PetscReal *ref)
{
  for (PetscInt i = 0; i < 144; i++)
    if (cur[i] != ref[i]) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* The current state factorised as reference r by the dual loop's factorisation: K_cr brought to
   it there (the exact sums of ROMContactStiffness over the elements that differ from the state in
   K_cr, whose dirty flags are raised again here). */
static PetscErrorCode ROMReferenceMake(BoltROM *rom, BoltOperator *op, BoltDual *d, PetscInt r)
{
  BoltROMUpdate  *u   = rom->update;
  ROMReference   *ref = &u->ref[r];
  const PetscInt  ne  = BoltContactSetElementCount(rom->contact);

  PetscFunctionBeginUser;
  if (!ref->Ke) { /* made when first needed: a scene whose set holds uses one */
    PetscCall(PetscMalloc3(144 * ne + 1, &ref->Ke, ne + 1, &ref->dev, rom->npGlobal + 1, &ref->slotOf));
    PetscCall(PetscMalloc3(3 * rom->n * u->alloc, &ref->U, 3 * rom->n * u->alloc, &ref->Z, 9 * u->alloc * u->alloc, &ref->G));
  }
  for (PetscInt e = 0; e < ne; e++) {
    if (u->devRun[e]) BoltContactStateDirty(BoltOperatorState(op))[e] = PETSC_TRUE;
    u->devRun[e] = PETSC_FALSE;
  }
  rom->KcrValid = PETSC_FALSE; /* its version may have been taken while the flags were held here */
  if (!ref->A) PetscCall(MatDuplicate(BoltOperatorStiffness(op), MAT_DO_NOT_COPY_VALUES, &ref->A));
  if (!ref->ksp) {
    const char   *prefix;
    MatSolverType type;
    PetscCall(BoltOperatorGetSolver(op, &prefix, &type));
    PetscCall(BoltDirectSolverCreate(PETSC_COMM_SELF, prefix, NULL, PETSC_FALSE, type, &ref->ksp));
  }
  PetscCall(BoltDualFactorInto(d, ref->A, ref->ksp)); /* K_cr brought to the current state there */
  PetscCall(PetscArraycpy(ref->Ke, u->Kcur, 144 * ne));
  for (PetscInt e = 0; e < ne; e++) ref->dev[e] = PETSC_FALSE;
  for (PetscInt i = 0; i < rom->npGlobal; i++) ref->slotOf[i] = -1;
  ref->nslot       = 0;
  ref->valid       = PETSC_TRUE;
  PetscCall(BoltDualGetEffective(d, &ref->dynamic, &ref->massCoef, &ref->dampingCoef));
  ref->lastUsed    = u->clock++;
  u->cur           = r;
  u->k             = 0;
  u->references++;
  PetscFunctionReturn(0);
}

/* A new reference in place of the one unused longest (or of a free one). */
static PetscErrorCode ROMReferenceNew(BoltROM *rom, BoltOperator *op, BoltDual *d)
{
  BoltROMUpdate *u = rom->update;
  PetscInt       r = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ROM_REFERENCES; i++) {
    if (!u->ref[i].valid) {
      r = i;
      break;
    }
    if (u->ref[i].lastUsed < u->ref[r].lastUsed) r = i;
  }
  PetscCall(ROMReferenceMake(rom, op, d, r));
  PetscFunctionReturn(0);
}

/* Z = A_ref^-1 U for the pool's nnew new slots from slot first, shared among the ranks: the slots
   are cut into chunks of ROM_SOLVE_CHUNK (set by nnew alone), each solved by one rank, the ranks
   owning consecutive chunks, and one Allgatherv puts every column on every rank. A chunk is the
   same solve on the same data on any number of ranks, so Z keeps its bits on any partition. */
#define ROM_SOLVE_CHUNK 16
static PetscErrorCode ROMSolveNewSlots(BoltROM *rom, ROMReference *ref, PetscInt first, PetscInt nnew)
{
  const PetscInt n = rom->n, nchunk = (nnew + ROM_SOLVE_CHUNK - 1) / ROM_SOLVE_CHUNK;
  PetscMPIInt    size, rank, *counts, *displs;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(rom->comm, &size));
  PetscCallMPI(MPI_Comm_rank(rom->comm, &rank));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  for (PetscMPIInt r = 0; r < size; r++) {
    const PetscInt s0 = PetscMin(nnew, ROM_SOLVE_CHUNK * ((nchunk * r) / size)), s1 = PetscMin(nnew, ROM_SOLVE_CHUNK * ((nchunk * (r + 1)) / size));
    PetscCall(PetscMPIIntCast(3 * n * (first + s0), &displs[r]));
    PetscCall(PetscMPIIntCast(3 * n * (s1 - s0), &counts[r]));
  }
  for (PetscInt b = (nchunk * rank) / size; b < (nchunk * (rank + 1)) / size; b++) {
    const PetscInt s0 = first + ROM_SOLVE_CHUNK * b, ns = PetscMin(ROM_SOLVE_CHUNK, first + nnew - s0);
    Mat            B, X;
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, 3 * ns, &ref->U[3 * n * s0], &B));
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, 3 * ns, &ref->Z[3 * n * s0], &X));
    PetscCall(KSPMatSolve(ref->ksp, B, X));
    PetscCall(MatDestroy(&B));
    PetscCall(MatDestroy(&X));
  }
  if (size > 1) PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, ref->Z, counts, displs, MPIU_REAL, rom->comm));
  PetscCall(PetscFree2(counts, displs));
  PetscFunctionReturn(0);
}

/* The correction of reference r for the current state, if it fits: the differing points' records
   gathered in the order of their names, merged per node pair (the points of a pair share its rows
   D: one slot each, its block the sum of theirs, added in name order), new slots added to its pool
   (their columns of U from the node pairs' rows every rank holds), I + S G factorised. With nodal
   points S is block-diagonal, a symmetric 3 x 3 block per pair; otherwise nothing is corrected. */
static PetscErrorCode ROMReferenceCorrect(BoltROM *rom, PetscInt r, PetscBool *done)
{
  BoltROMUpdate  *u   = rom->update;
  ROMReference   *ref = &u->ref[r];
  BoltContactSet *c   = rom->contact;
  const PetscInt  ne = BoltContactSetElementCount(c);
  const PetscInt  n = rom->n, recLen = 3 + 9, LD = 3 * u->alloc;
  PetscBool       ok, blocks = PETSC_TRUE;
  PetscInt        nsend = 0, total = 0, nrec, npair = 0, nnew = 0;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  /* a record per differing point of a node pair: name, node pair, whether its difference is its
     own node's block alone, that block */
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt a = 0; a < 4 && ref->dev[e]; a++)
      if (rom->npOfPoint[4 * e + a] >= 0 && ROMSlotDiffers(&u->Kcur[144 * e], &ref->Ke[144 * e], a)) nsend += recLen;
  PetscCall(BoltGrowReal(&u->send, &u->sendAlloc, nsend + 1));
  nsend = 0;
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt a = 0; a < 4 && ref->dev[e]; a++) {
      const PetscReal *cur = &u->Kcur[144 * e], *ke = &ref->Ke[144 * e];
      PetscReal       *r0  = &u->send[nsend];
      PetscBool        own = PETSC_TRUE;
      if (rom->npOfPoint[4 * e + a] < 0 || !ROMSlotDiffers(cur, ke, a)) continue; /* both nodes clamped: nothing reaches the ROM */
      for (PetscInt q = 0; q < 3; q++)
        for (PetscInt b = 0; b < 12; b++) {
          const PetscReal d = cur[12 * (3 * a + q) + b] - ke[12 * (3 * a + q) + b];
          if (b / 3 == a) r0[3 + q + 3 * (b % 3)] = d;
          else if (d != 0) own = PETSC_FALSE;
        }
      for (PetscInt q = 0; q < 3 && own; q++)
        for (PetscInt l = 0; l < 3; l++)
          if (r0[3 + q + 3 * l] != r0[3 + l + 3 * q]) own = PETSC_FALSE;
      r0[0] = (PetscReal)(4 * BoltContactSetElementKey(c, e) + a);
      r0[1] = (PetscReal)rom->npOfPoint[4 * e + a];
      r0[2] = own ? 1.0 : 0.0;
      nsend += recLen;
    }
  PetscCall(BoltGatherAll(rom->comm, MPIU_REAL, u->send, nsend, &u->recv, &u->recvAlloc, &total, NULL));
  nrec = total / recLen;
  if (nrec > u->recAlloc) {
    u->recAlloc = PetscMax(nrec, 2 * u->recAlloc);
    PetscCall(PetscFree2(u->name, u->perm));
    PetscCall(PetscMalloc2(u->recAlloc, &u->name, u->recAlloc, &u->perm));
  }
  for (PetscInt pos = 0, i = 0; pos < total; i++) {
    u->name[i] = (PetscInt)u->recv[pos];
    u->perm[i] = pos;
    if (u->recv[pos + 2] == 0) blocks = PETSC_FALSE;
    pos += recLen;
  }
  if (!blocks) PetscFunctionReturn(0);
  PetscCall(PetscSortIntWithArray(nrec, u->name, u->perm)); /* names in order, perm: where their records are */
  /* the node pairs in the order of their first point's name, each block summed in name order */
  for (PetscInt i = 0; i < nrec; i++) {
    const PetscReal *r0 = &u->recv[u->perm[i]];
    const PetscInt   k  = (PetscInt)r0[1];
    if (u->pairAt[k] < 0) {
      if (npair == u->alloc) break; /* more pairs than any pool holds */
      u->pairAt[k]     = npair;
      u->pairOf[npair] = k;
      PetscCall(PetscArrayzero(&u->B[9 * npair], 9));
      if (ref->slotOf[k] < 0) nnew++;
      npair++;
    }
    for (PetscInt j = 0; j < 9; j++) u->B[9 * u->pairAt[k] + j] += r0[3 + j];
  }
  for (PetscInt i = 0; i < npair; i++) u->pairAt[u->pairOf[i]] = -1;
  if (npair == u->alloc || 3 * npair > u->maxRank || ref->nslot + nnew > u->alloc) PetscFunctionReturn(0);
  /* new slots join the pool, side by side after the others: Z = A_ref^-1 U in solves with many
     right-hand sides shared among the ranks, and G's new columns U' Z_new (and rows, by symmetry) */
  if (nnew) {
    const PetscInt first = ref->nslot, mo = 3 * first, mn = 3 * nnew;
    PetscBLASInt   bn, bmo, bmn, bld;
    PetscReal      one = 1, zero = 0;
    u->largestBatch = PetscMax(u->largestBatch, nnew);
    for (PetscInt i = 0; i < npair; i++) {
      const PetscInt k = u->pairOf[i];
      if (ref->slotOf[k] >= 0) continue;
      PetscCall(PetscArraycpy(&ref->U[3 * n * ref->nslot], &rom->npRowsAll[3 * n * k], 3 * n));
      ref->slotOf[k] = ref->nslot++;
    }
    PetscCall(ROMSolveNewSlots(rom, ref, first, nnew));
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(PetscBLASIntCast(mo + mn, &bmo));
    PetscCall(PetscBLASIntCast(mn, &bmn));
    PetscCall(PetscBLASIntCast(LD, &bld));
    PetscCallBLAS("BLASgemm", BLASgemm_("T", "N", &bmo, &bmn, &bn, &one, ref->U, &bn, &ref->Z[3 * n * first], &bn, &zero, &ref->G[LD * mo], &bld));
    for (PetscInt j = mo; j < mo + mn; j++) /* the new rows: the old columns' part, transposed */
      for (PetscInt i = 0; i < mo; i++) ref->G[j + LD * i] = ref->G[i + LD * j];
  }
  /* the correction: its slots and I + S G factorised (src/sys/capacitance.c) */
  for (PetscInt i = 0; i < npair; i++) u->act[i] = ref->slotOf[u->pairOf[i]];
  for (PetscInt i = 0; i < 3 * npair; i++) u->idx[i] = 3 * u->act[i / 3] + i % 3;
  PetscCall(BoltCapacitanceFactorBlocks(u->cap, npair, u->B, ref->G, LD, u->idx, &ok));
  if (!ok) PetscFunctionReturn(0); /* singular: this reference cannot carry the state */
  u->k          = npair;
  u->cur        = r;
  ref->lastUsed = u->clock++;
  *done         = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The dual loop's factorisation, for the ROM: a correction of the nearest reference if one fits,
   else a new reference. */
static PetscErrorCode ROMUpdateFactor(BoltOperator *op, BoltDual *d)
{
  BoltROM          *rom = (BoltROM *)BoltOperatorContext(op);
  BoltROMUpdate    *u   = rom->update;
  BoltContactSet   *c   = rom->contact;
  BoltContactState *s   = BoltOperatorState(op);
  PetscBool        *stale = BoltContactStateDirty(s); /* elements whose block changed */
  PetscInt          slots[ROM_REFERENCES], order[ROM_REFERENCES], nvalid = 0;
  PetscReal         Knew[576];
  PetscLogDouble    t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
  u->dual = d;
  /* references made under other Newmark coefficients (the static preload, another step) go */
  {
    PetscBool dynamic;
    PetscReal massCoef, dampingCoef;
    PetscCall(BoltDualGetEffective(d, &dynamic, &massCoef, &dampingCoef));
    for (PetscInt r = 0; r < ROM_REFERENCES; r++) {
      ROMReference *ref = &u->ref[r];
      if (ref->valid && !(ref->dynamic == dynamic && ref->massCoef == massCoef && ref->dampingCoef == dampingCoef)) ref->valid = PETSC_FALSE;
    }
  }
  /* the changed elements' blocks, and whom they differ from */
  for (PetscInt e = 0, ne = BoltContactSetElementCount(c); e < ne; e++) {
    PetscReal *cur = &u->Kcur[144 * e];
    if (!stale[e]) continue;
    stale[e] = PETSC_FALSE;
    PetscCall(BoltContactStateElementStiffness(s, e, Knew));
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) cur[12 * a + b] = Knew[24 * a + b];
    if (rom->DeMax[e] == 0) { /* both sides clamped: nothing of it reaches the ROM */
      PetscCall(PetscArraycpy(&rom->Ke[144 * e], cur, 144));
      for (PetscInt r = 0; r < ROM_REFERENCES; r++)
        if (u->ref[r].valid) PetscCall(PetscArraycpy(&u->ref[r].Ke[144 * e], cur, 144));
      continue;
    }
    u->devRun[e] = ROMBlockDiffers(cur, &rom->Ke[144 * e]);
    for (PetscInt r = 0; r < ROM_REFERENCES; r++)
      if (u->ref[r].valid) u->ref[r].dev[e] = ROMBlockDiffers(cur, &u->ref[r].Ke[144 * e]);
  }
  /* the references by the number of node pairs they differ in (over all ranks) */
  PetscCall(PetscArrayzero(u->mark, ROM_REFERENCES * rom->npGlobal));
  for (PetscInt r = 0; r < ROM_REFERENCES; r++) {
    ROMReference *ref = &u->ref[r];
    if (!ref->valid) continue;
    for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++)
      for (PetscInt a = 0; a < 4 && ref->dev[e]; a++)
        if (rom->npOfPoint[4 * e + a] >= 0 && ROMSlotDiffers(&u->Kcur[144 * e], &ref->Ke[144 * e], a)) u->mark[rom->npGlobal * r + rom->npOfPoint[4 * e + a]] = 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, u->mark, ROM_REFERENCES * rom->npGlobal, MPIU_INT, MPI_MAX, rom->comm));
  for (PetscInt r = 0; r < ROM_REFERENCES; r++) {
    slots[r] = 0;
    for (PetscInt k = 0; k < rom->npGlobal; k++) slots[r] += u->mark[rom->npGlobal * r + k];
  }
  for (PetscInt r = 0; r < ROM_REFERENCES; r++)
    if (u->ref[r].valid && 3 * slots[r] <= u->maxRank) order[nvalid++] = r;
  for (PetscInt i = 1; i < nvalid; i++) /* nearest first; ties: the one used last */
    for (PetscInt j = i; j > 0; j--) {
      const PetscInt a = order[j - 1], b = order[j];
      if (slots[b] < slots[a] || (slots[b] == slots[a] && u->ref[b].lastUsed > u->ref[a].lastUsed)) {
        order[j - 1] = b;
        order[j]     = a;
      }
    }
  for (PetscInt i = 0; i < nvalid; i++) {
    PetscBool done;
    PetscCall(ROMReferenceCorrect(rom, order[i], &done));
    if (done) {
      PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
      PetscCall(PetscTime(&t1));
      PetscCall(BoltDualLogStiffnessUpdate(d, t1 - t0, PETSC_TRUE));
      u->updates++;
      PetscFunctionReturn(0);
    }
  }
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  PetscCall(BoltDualLogStiffnessUpdate(d, t1 - t0, PETSC_FALSE));
  PetscCall(ROMReferenceNew(rom, op, d));
  PetscFunctionReturn(0);
}

/* x = A^-1 b: the reference's solve, corrected. */
static PetscErrorCode ROMUpdateSolve(BoltOperator *op, BoltDual *d, Vec b, Vec x)
{
  BoltROM       *rom = (BoltROM *)BoltOperatorContext(op);
  BoltROMUpdate *u   = rom->update;
  const PetscInt n = rom->n, k = u->k;
  PetscScalar   *xa;
  ROMReference  *ref;
  PetscBLASInt   bn, one = 1, three = 3;
  PetscReal      pone = 1, zero = 0, mone = -1;

  PetscFunctionBeginUser;
  PetscCheck(u->cur >= 0 && u->ref[u->cur].valid, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ROM: a solve before a factorisation");
  ref = &u->ref[u->cur];
  PetscCall(KSPSolve(ref->ksp, b, x));
  if (!k) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(VecGetArray(x, &xa));
  /* U' x and x - Z w slot by slot, on the pool's columns where they are (a copy of the active
     ones side by side cost more, at every set change, than these calls) */
  for (PetscInt i = 0; i < k; i++) PetscCallBLAS("BLASgemv", BLASgemv_("T", &bn, &three, &pone, &ref->U[3 * n * u->act[i]], &bn, xa, &one, &zero, &u->t[3 * i], &one));
  PetscCall(BoltCapacitanceSolve(u->cap, u->t, u->w));
  for (PetscInt i = 0; i < k; i++) PetscCallBLAS("BLASgemv", BLASgemv_("N", &bn, &three, &mone, &ref->Z[3 * n * u->act[i]], &bn, &u->w[3 * i], &one, &pone, xa, &one));
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* Before a checkpoint: the references go and the current state is factorised as the only one,
   as a run continued from the checkpoint (which factorises what it restores) will have it. */
PetscErrorCode BoltROMUpdateSettle(BoltOperator *op)
{
  BoltROM       *rom = (BoltROM *)BoltOperatorContext(op);
  BoltROMUpdate *u   = rom->update;

  PetscFunctionBeginUser;
  if (!u || u->cur < 0) PetscFunctionReturn(0);
  for (PetscInt r = 0; r < ROM_REFERENCES; r++) u->ref[r].valid = PETSC_FALSE;
  PetscCall(ROMReferenceMake(rom, op, u->dual, 0));
  PetscFunctionReturn(0);
}

/* ROMContactStiffness summed element e's current block into K_cr (rom->Ke). */
void BoltROMUpdateSummed(BoltROMUpdate *u, BoltROM *rom, PetscInt e)
{
  if (!u) return;
  for (PetscInt i = 0; i < 144; i++) u->Kcur[144 * e + i] = rom->Ke[144 * e + i];
  u->devRun[e] = PETSC_FALSE;
  for (PetscInt r = 0; r < ROM_REFERENCES; r++)
    if (u->ref[r].valid) u->ref[r].dev[e] = ROMBlockDiffers(&u->Kcur[144 * e], &u->ref[r].Ke[144 * e]);
}

/* The ROM's operator takes its factorisations and solves from here when maxRank > 0. */
PetscErrorCode BoltROMUpdateCreate(BoltROM *rom, BoltOperator *op, PetscInt maxRank)
{
  BoltROMUpdate *u;
  const PetscInt n = rom->n, ne = BoltContactSetElementCount(rom->contact);

  PetscFunctionBeginUser;
  PetscCall(BoltROMUpdateDestroy(&rom->update));
  if (maxRank <= 0) PetscFunctionReturn(0);
  PetscCall(PetscNew(&u));
  u->maxRank = maxRank;
  u->alloc   = PetscMax(1, (3 * n) / 5); /* slots per pool: beyond some 2n columns a new reference is cheaper */
  u->cur     = -1;
  PetscCall(PetscMalloc2(144 * ne + 1, &u->Kcur, ne + 1, &u->devRun));
  PetscCall(PetscArraycpy(u->Kcur, rom->Ke, 144 * ne)); /* K_cr is built: its blocks are the current ones */
  for (PetscInt e = 0; e < ne; e++) u->devRun[e] = PETSC_FALSE;
  PetscCall(PetscMalloc4(u->alloc, &u->act, rom->npGlobal + 1, &u->pairAt, u->alloc, &u->pairOf, ROM_REFERENCES * rom->npGlobal + 1, &u->mark));
  for (PetscInt k = 0; k < rom->npGlobal; k++) u->pairAt[k] = -1;
  PetscCall(PetscMalloc2(3 * u->alloc, &u->t, 3 * u->alloc, &u->w));
  PetscCall(PetscMalloc2(9 * u->alloc, &u->B, 3 * u->alloc, &u->idx));
  PetscCall(BoltCapacitanceCreate(&u->cap));
  rom->update    = u;
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_FACTOR, (void (*)(void))ROMUpdateFactor));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_SOLVE, (void (*)(void))ROMUpdateSolve));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMUpdateView(BoltROMUpdate *u, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!u) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  set changes taken as low-rank updates of up to %d kept factorisations, rank up to %" PetscInt_FMT " (so far %" PetscInt_FMT " updates, %" PetscInt_FMT " factorisations, at most %" PetscInt_FMT " slots joining a pool at once)\n", ROM_REFERENCES, u->maxRank, u->updates, u->references, u->largestBatch));
  PetscFunctionReturn(0);
}

/* The most slots that joined a pool at once (their solves are shared among the ranks in chunks). */
PetscInt BoltROMUpdateLargestBatch(const BoltROMUpdate *u)
{
  return u ? u->largestBatch : 0;
}

PetscErrorCode BoltROMUpdateDestroy(BoltROMUpdate **up)
{
  BoltROMUpdate *u = *up;

  PetscFunctionBeginUser;
  if (!u) PetscFunctionReturn(0);
  for (PetscInt r = 0; r < ROM_REFERENCES; r++) {
    ROMReference *ref = &u->ref[r];
    PetscCall(PetscFree3(ref->Ke, ref->dev, ref->slotOf));
    PetscCall(PetscFree3(ref->U, ref->Z, ref->G));
    PetscCall(MatDestroy(&ref->A));
    PetscCall(KSPDestroy(&ref->ksp));
  }
  PetscCall(PetscFree2(u->Kcur, u->devRun));
  PetscCall(PetscFree4(u->act, u->pairAt, u->pairOf, u->mark));
  PetscCall(PetscFree2(u->t, u->w));
  PetscCall(PetscFree2(u->B, u->idx));
  PetscCall(BoltCapacitanceDestroy(&u->cap));
  PetscCall(PetscFree(u->send));
  PetscCall(PetscFree(u->recv));
  PetscCall(PetscFree2(u->name, u->perm));
  PetscCall(PetscFree(*up));
  PetscFunctionReturn(0);
}
