/* Low-rank updates of the FOM's factorised effective matrix in the transient. Under friction the
   contact state changes a few times a step as pairs stick and slip, and each change cost a new
   factorisation of a1 M + a4 C + K + K_c (90 % of a frictional run's time at 16k DOFs). Instead
   the last factorisation A_ref is kept and a solve takes the difference as a Woodbury correction:

     A = A_ref + U S U',   x = y - Z w,   (I + S G) w = S U' y,   y = A_ref^-1 b,

   U holding, per node pair whose penalty block differs from the reference's, the three columns
   e_b - e_a (a contact element's matrix is [D -D; -D D] over its two sides), S the differences
   of the blocks D summed per pair, Z = A_ref^-1 U and G = U' Z. The pairs that have differed
   keep their columns of Z and G (the pool), so a change costs the solves of the pairs new to it
   and the system of I + S G (3k for k pairs; src/sys/capacitance.c). Past -fom_update_rank
   columns, a full pool or a singular I + S G, the state is factorised afresh and becomes the
   reference.

   Every rank holds the correction (S, G, I + S G), built from the differing elements' records
   gathered and put in the order of their keys; Z and the vectors are distributed as K's rows. */
#include "private/solve.h"
#include <petscblaslapack.h>

#define FOM_RECORD (1 + 24 + 144) /* element key, its 24 DOFs, the difference of its block D */

typedef struct {
  PetscInt64 key;
  PetscInt   dofA[3], dofB[3];
} FOMPair;

struct _n_BoltFOMUpdate {
  PetscInt   maxRank, alloc; /* the largest correction [columns]; pairs in the pool */
  BoltDual  *dual;
  PetscBool  valid;          /* the loop's factorisation is a transient reference */
  PetscReal  massCoef, dampingCoef;
  PetscReal *Ke;     /* 576 per local element: the blocks factorised */
  PetscInt   npool;  /* pairs in the pool, the same on every rank */
  FOMPair   *pool;
  PetscInt  *sorted; /* pool slots in key order */
  PetscReal *Z, *G;  /* nloc x 3 per pool pair; 3 alloc x 3 alloc (column-major) */
  PetscInt   nloc, rstart, N; /* this rank's rows, the first, and the model's DOFs */
  /* the correction in force: k pairs in key order */
  PetscInt      k, kAlloc, pAlloc;
  FOMPair      *pairs;
  PetscInt        *act, *idx;  /* each pair's pool slot; each column's row of G */
  PetscReal       *S, *t, *w;  /* 3k x 3k, 3k, 3k */
  BoltCapacitance *cap;        /* the system of I + S G */
  /* gathering */
  PetscReal *send, *recv;
  PetscInt   sendAlloc, recvAlloc;
  PetscInt   updates, references, largestBatch;
};

static PetscBool FOMBlockDiffers(const PetscReal *cur, const PetscReal *ref)
{
  for (PetscInt i = 0; i < 12; i++)
    for (PetscInt j = 0; j < 12; j++)
      if (cur[24 * i + j] != ref[24 * i + j]) return PETSC_TRUE;
  return PETSC_FALSE;
}

static int FOMPairCompare(const void *a, const void *b)
{
  const PetscInt64 ka = ((const FOMPair *)a)->key, kb = ((const FOMPair *)b)->key;
  return ka < kb ? -1 : (ka > kb ? 1 : 0);
}

/* A node pair's key, from its two nodes' first DOFs (-1 where clamped). */
static PetscInt64 FOMPairKey(const BoltFOMUpdate *u, PetscInt dofA, PetscInt dofB)
{
  return (PetscInt64)(dofA + 1) * (PetscInt64)(u->N + 1) + (PetscInt64)(dofB + 1);
}

/* Where key is among n pairs in key order (pairs[order[i]], or pairs[i] if order is NULL), or -1. */
static PetscInt FOMPairFind(const FOMPair *pairs, const PetscInt *order, PetscInt n, PetscInt64 key)
{
  PetscInt lo = 0, hi = n - 1;
  while (lo <= hi) {
    const PetscInt   mid = (lo + hi) / 2, at = order ? order[mid] : mid;
    const PetscInt64 km  = pairs[at].key;
    if (km == key) return at;
    if (km < key) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

/* A DOF's row in this rank's part of the vectors, -1 if another rank's (or clamped). */
static PetscInt FOMLocalRow(const BoltFOMUpdate *u, PetscInt dof)
{
  return dof >= u->rstart && dof < u->rstart + u->nloc ? dof - u->rstart : -1;
}

static PetscErrorCode FOMPoolInsert(BoltFOMUpdate *u, const FOMPair *p)
{
  PetscInt at = u->npool;

  PetscFunctionBeginUser;
  while (at > 0 && u->pool[u->sorted[at - 1]].key > p->key) {
    u->sorted[at] = u->sorted[at - 1];
    at--;
  }
  u->pool[u->npool] = *p;
  u->sorted[at]     = u->npool++;
  PetscFunctionReturn(0);
}

/* The largest correction, from the first transient factorisation (by MUMPS; another solver
   takes FOM_RANK_OTHER): the dense system of I + S G, up to 2 m^3 / 3 flops, is paid at every
   state change (two or three a step under friction) and a factorisation once per reference, so
   the state is factorised afresh once m^3 would pass a third of the factorisation's flops
   (docs/decisions.md); and a full pool of Z (2 m columns) may take up to four times the
   factorisation's memory. */
#define FOM_RANK_OTHER 900
static PetscErrorCode FOMResolveRank(BoltFOMUpdate *u, BoltDual *d)
{
  PC            pc;
  MatSolverType type;
  PetscMPIInt   size;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(d->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)d->ksp), &size));
  if (u->maxRank > 0) { /* given */
  } else if (type && !strcmp(type, MATSOLVERMUMPS)) {
    Mat       F;
    PetscReal flops, cap;
    PetscInt  megabytes, nmax = u->nloc;
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatMumpsGetRinfog(F, 3, &flops));
    PetscCall(MatMumpsGetInfog(F, 22, &megabytes));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nmax, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)d->ksp)));
    cap        = 4e6 * (PetscReal)megabytes / size / (2.0 * sizeof(PetscReal) * PetscMax(nmax, 1));
    u->maxRank = (PetscInt)PetscMin(PetscCbrtReal(flops / 3), cap);
    PetscCall(PetscPrintf(PetscObjectComm((PetscObject)d->ksp), "FOM: contact state changes taken as low-rank updates of rank up to %" PetscInt_FMT " (the factorisation: %.3g flops, %" PetscInt_FMT " MB)\n", PetscMax(u->maxRank, 3), (double)flops, megabytes));
  } else u->maxRank = FOM_RANK_OTHER;
  u->maxRank = PetscMax(u->maxRank, 3);
  u->alloc   = PetscMax(1, (2 * u->maxRank) / 3); /* pairs: two full corrections' columns */
  PetscCall(PetscMalloc2(u->alloc, &u->pool, u->alloc, &u->sorted));
  PetscCall(PetscMalloc2((size_t)u->nloc * 3 * u->alloc + 1, &u->Z, (size_t)9 * u->alloc * u->alloc, &u->G));
  PetscFunctionReturn(0);
}

/* The current state factorised by the loop and made the reference, its pool emptied. */
static PetscErrorCode FOMReferenceMake(BoltFOMUpdate *u, BoltOperator *op, BoltDual *d)
{
  const PetscInt ne = BoltContactSetElementCount(BoltOperatorContact(op));
  PetscBool      dynamic;

  PetscFunctionBeginUser;
  PetscCall(BoltDualFactorInto(d, d->Keff, d->ksp)); /* brings the state's blocks up to date */
  if (!u->alloc) PetscCall(FOMResolveRank(u, d));
  PetscCall(BoltDualGetEffective(d, &dynamic, &u->massCoef, &u->dampingCoef));
  PetscCall(PetscArraycpy(u->Ke, BoltContactStateElementBlocks(BoltOperatorState(op)), 576 * ne));
  u->valid = PETSC_TRUE;
  u->npool = 0;
  u->k     = 0;
  u->references++;
  PetscFunctionReturn(0);
}

/* Room for np candidate pairs, and for a correction of k pairs. */
static PetscErrorCode FOMCorrectionReserve(BoltFOMUpdate *u, PetscInt np, PetscInt k)
{
  PetscFunctionBeginUser;
  if (np > u->pAlloc) {
    u->pAlloc = PetscMax(np, 2 * u->pAlloc);
    PetscCall(PetscFree(u->pairs));
    PetscCall(PetscMalloc1(u->pAlloc, &u->pairs));
  }
  if (k > u->kAlloc) {
    u->kAlloc = PetscMax(k, PetscMin(2 * u->kAlloc, u->maxRank / 3 + 1));
    PetscCall(PetscFree2(u->act, u->idx));
    PetscCall(PetscFree3(u->S, u->t, u->w));
    PetscCall(PetscMalloc2(u->kAlloc, &u->act, 3 * u->kAlloc, &u->idx));
    PetscCall(PetscMalloc3(9 * u->kAlloc * u->kAlloc, &u->S, 3 * u->kAlloc, &u->t, 3 * u->kAlloc, &u->w));
  }
  PetscFunctionReturn(0);
}

/* Z = A_ref^-1 U for the pool's nnew pairs from slot first, and their rows and columns of G. */
static PetscErrorCode FOMPoolSolve(BoltFOMUpdate *u, BoltDual *d, MPI_Comm comm, PetscInt first, PetscInt nnew)
{
  const PetscInt nloc = u->nloc, mn = 3 * nnew, mo = 3 * first, m = 3 * u->npool, LD = 3 * u->alloc;
  Mat            B, X;
  PetscScalar   *b;
  PetscReal     *Gnew;

  PetscFunctionBeginUser;
  PetscCall(MatCreateDense(comm, nloc, PETSC_DECIDE, PETSC_DETERMINE, mn, NULL, &B));
  PetscCall(MatDenseGetArrayWrite(B, &b));
  PetscCall(PetscArrayzero(b, nloc * mn));
  for (PetscInt j = 0; j < nnew; j++)
    for (PetscInt l = 0; l < 3; l++) {
      const FOMPair *p = &u->pool[first + j];
      const PetscInt rb = FOMLocalRow(u, p->dofB[l]), ra = FOMLocalRow(u, p->dofA[l]);
      if (rb >= 0) b[rb + nloc * (3 * j + l)] += 1.0;
      if (ra >= 0) b[ra + nloc * (3 * j + l)] -= 1.0;
    }
  PetscCall(MatDenseRestoreArrayWrite(B, &b));
  PetscCall(MatCreateDense(comm, nloc, PETSC_DECIDE, PETSC_DETERMINE, mn, &u->Z[nloc * mo], &X));
  PetscCall(KSPMatSolve(d->ksp, B, X));
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&X));
  /* G's new columns U' Z_new from each rank's rows, summed; the new rows by symmetry */
  PetscCall(PetscCalloc1(m * mn, &Gnew));
  for (PetscInt i = 0; i < u->npool; i++)
    for (PetscInt l = 0; l < 3; l++) {
      const FOMPair *p  = &u->pool[i];
      const PetscInt rb = FOMLocalRow(u, p->dofB[l]), ra = FOMLocalRow(u, p->dofA[l]);
      for (PetscInt c = 0; c < mn; c++) {
        const PetscReal *z = &u->Z[nloc * (mo + c)];
        PetscReal        v = 0;
        if (rb >= 0) v += z[rb];
        if (ra >= 0) v -= z[ra];
        Gnew[3 * i + l + m * c] = v;
      }
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Gnew, m * mn, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt c = 0; c < mn; c++)
    for (PetscInt i = 0; i < m; i++) u->G[i + LD * (mo + c)] = Gnew[i + m * c];
  for (PetscInt c = 0; c < mn; c++)
    for (PetscInt i = 0; i < mo; i++) u->G[mo + c + LD * i] = Gnew[i + m * c];
  PetscCall(PetscFree(Gnew));
  u->largestBatch = PetscMax(u->largestBatch, nnew);
  PetscFunctionReturn(0);
}

/* The correction of the reference for the current state, if it fits. */
static PetscErrorCode FOMCorrect(BoltFOMUpdate *u, BoltOperator *op, BoltDual *d, PetscBool *done)
{
  BoltContactSet  *c  = BoltOperatorContact(op);
  const PetscReal *Ke = BoltContactStateElementBlocks(BoltOperatorState(op));
  const PetscInt   ne = BoltContactSetElementCount(c), LD = 3 * u->alloc;
  MPI_Comm         comm = BoltOperatorComm(op);
  PetscInt         nsend = 0, total, nrec, np = 0, k, nnew = 0, m, *keys, *perm;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  for (PetscInt e = 0; e < ne; e++)
    if (FOMBlockDiffers(&Ke[576 * e], &u->Ke[576 * e])) nsend += FOM_RECORD;
  PetscCall(BoltGrowReal(&u->send, &u->sendAlloc, nsend + 1));
  nsend = 0;
  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal *cur = &Ke[576 * e], *ref = &u->Ke[576 * e];
    const PetscInt  *dofs = BoltContactSetElementDofs(c, e);
    PetscReal       *r0   = &u->send[nsend];
    if (!FOMBlockDiffers(cur, ref)) continue;
    r0[0] = (PetscReal)BoltContactSetElementKey(c, e);
    for (PetscInt i = 0; i < 24; i++) r0[1 + i] = (PetscReal)dofs[i];
    for (PetscInt i = 0; i < 12; i++)
      for (PetscInt j = 0; j < 12; j++) r0[25 + 12 * i + j] = cur[24 * i + j] - ref[24 * i + j];
    nsend += FOM_RECORD;
  }
  PetscCall(BoltGatherAll(comm, MPIU_REAL, u->send, nsend, &u->recv, &u->recvAlloc, &total, NULL));
  nrec = total / FOM_RECORD;
  if (nrec / 4 * 3 > u->maxRank) PetscFunctionReturn(0); /* a pair lies in at most four elements */
  PetscCall(PetscMalloc2(nrec + 1, &keys, nrec + 1, &perm));
  for (PetscInt i = 0; i < nrec; i++) {
    keys[i] = (PetscInt)u->recv[FOM_RECORD * i];
    perm[i] = i;
  }
  PetscCall(PetscSortIntWithArray(nrec, keys, perm)); /* the records in the order of their keys */
  /* the pairs: each element node whose rows of D changed, once, in key order */
  PetscCall(FOMCorrectionReserve(u, 4 * nrec, 0));
  for (PetscInt i = 0; i < nrec; i++) {
    const PetscReal *r0 = &u->recv[FOM_RECORD * perm[i]];
    for (PetscInt a = 0; a < 4; a++) {
      PetscBool nz = PETSC_FALSE;
      FOMPair  *p  = &u->pairs[np];
      for (PetscInt q = 3 * a; q < 3 * a + 3 && !nz; q++)
        for (PetscInt j = 0; j < 12 && !nz; j++) nz = (PetscBool)(r0[25 + 12 * q + j] != 0 || r0[25 + 12 * j + q] != 0);
      for (PetscInt l = 0; l < 3; l++) {
        p->dofA[l] = (PetscInt)r0[1 + 3 * a + l];
        p->dofB[l] = (PetscInt)r0[13 + 3 * a + l];
      }
      if (!nz || (p->dofA[0] < 0 && p->dofB[0] < 0)) continue;
      p->key = FOMPairKey(u, p->dofA[0], p->dofB[0]);
      np++;
    }
  }
  qsort(u->pairs, (size_t)np, sizeof(FOMPair), FOMPairCompare);
  k = 0;
  for (PetscInt i = 0; i < np; i++)
    if (k == 0 || u->pairs[k - 1].key != u->pairs[i].key) u->pairs[k++] = u->pairs[i];
  if (3 * k > u->maxRank) goto out;
  PetscCall(FOMCorrectionReserve(u, 0, k));
  for (PetscInt i = 0; i < k; i++) { /* each pair's pool slot, -1 if it is new */
    u->act[i] = FOMPairFind(u->pool, u->sorted, u->npool, u->pairs[i].key);
    if (u->act[i] < 0) nnew++;
  }
  if (u->npool + nnew > u->alloc) goto out;
  if (nnew) { /* the new pairs join the pool */
    const PetscInt first = u->npool;
    for (PetscInt i = 0; i < k; i++)
      if (u->act[i] < 0) {
        u->act[i] = u->npool;
        PetscCall(FOMPoolInsert(u, &u->pairs[i]));
      }
    PetscCall(FOMPoolSolve(u, d, comm, first, nnew));
  }
  /* S: the blocks' differences summed per pair, in the order of the element keys */
  m = 3 * k;
  PetscCall(PetscArrayzero(u->S, m * m));
  for (PetscInt i = 0; i < nrec; i++) {
    const PetscReal *r0 = &u->recv[FOM_RECORD * perm[i]];
    PetscInt         at[4];
    for (PetscInt a = 0; a < 4; a++) at[a] = FOMPairFind(u->pairs, NULL, k, FOMPairKey(u, (PetscInt)r0[1 + 3 * a], (PetscInt)r0[13 + 3 * a]));
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt b = 0; b < 4; b++) {
        if (at[a] < 0 || at[b] < 0) continue;
        for (PetscInt l = 0; l < 3; l++)
          for (PetscInt q = 0; q < 3; q++) u->S[3 * at[a] + l + m * (3 * at[b] + q)] += r0[25 + 12 * (3 * a + l) + 3 * b + q];
      }
  }
  /* the system of I + S G over the pairs' columns of G */
  if (m > 0) {
    PetscBool ok;
    for (PetscInt j = 0; j < m; j++) u->idx[j] = 3 * u->act[j / 3] + j % 3;
    PetscCall(BoltCapacitanceFactor(u->cap, m, u->S, u->G, LD, u->idx, &ok));
    if (!ok) goto out; /* singular: the reference cannot carry the state */
  }
  u->k  = k;
  *done = PETSC_TRUE;
out:
  PetscCall(PetscFree2(keys, perm));
  PetscFunctionReturn(0);
}

/* The dual loop's factorisation, for the FOM: in the transient a correction of the reference if
   one fits, else a new reference; static solves factorise as they always did. */
static PetscErrorCode FOMUpdateFactor(BoltOperator *op, BoltDual *d)
{
  BoltFOMUpdate *u = ((BoltFOMCtx *)BoltOperatorContext(op))->update;
  PetscBool      dynamic, done = PETSC_FALSE;
  PetscReal      massCoef, dampingCoef;
  PetscLogDouble t0, t1;
  Mat            Kc;

  PetscFunctionBeginUser;
  u->dual = d;
  PetscCall(BoltDualGetEffective(d, &dynamic, &massCoef, &dampingCoef));
  if (!dynamic) {
    u->valid = PETSC_FALSE;
    u->k     = 0;
    PetscCall(BoltDualFactorInto(d, d->Keff, d->ksp));
    PetscFunctionReturn(0);
  }
  if (u->valid && massCoef == u->massCoef && dampingCoef == u->dampingCoef) {
    PetscCall(PetscTime(&t0));
    PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
    PetscCall(BoltContactStateStiffness(BoltOperatorState(op), &Kc)); /* the blocks up to date */
    PetscCall(FOMCorrect(u, op, d, &done));
    PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_STIFFNESS, 0, 0, 0, 0));
    PetscCall(PetscTime(&t1));
    PetscCall(BoltDualLogStiffnessUpdate(d, t1 - t0, done));
    if (done) {
      u->updates++;
      PetscFunctionReturn(0);
    }
  }
  PetscCall(FOMReferenceMake(u, op, d));
  PetscFunctionReturn(0);
}

/* x = A^-1 b: the reference's solve, corrected. */
static PetscErrorCode FOMUpdateSolve(BoltOperator *op, BoltDual *d, Vec b, Vec x)
{
  BoltFOMUpdate *u = ((BoltFOMCtx *)BoltOperatorContext(op))->update;
  const PetscInt k = u->valid ? u->k : 0, m = 3 * k, nloc = u->nloc;
  PetscScalar   *xa;
  PetscBLASInt   bn, one = 1, three = 3;
  PetscReal      pone = 1, mone = -1;

  PetscFunctionBeginUser;
  PetscCall(KSPSolve(d->ksp, b, x));
  if (!k) PetscFunctionReturn(0);
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < k; i++)
    for (PetscInt l = 0; l < 3; l++) {
      const FOMPair *p  = &u->pairs[i];
      const PetscInt rb = FOMLocalRow(u, p->dofB[l]), ra = FOMLocalRow(u, p->dofA[l]);
      PetscReal      v  = 0;
      if (rb >= 0) v += PetscRealPart(xa[rb]);
      if (ra >= 0) v -= PetscRealPart(xa[ra]);
      u->t[3 * i + l] = v;
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, u->t, m, MPIU_REAL, MPIU_SUM, BoltOperatorComm(op)));
  PetscCall(BoltCapacitanceSolve(u->cap, u->t, u->w));
  PetscCall(PetscBLASIntCast(nloc, &bn));
  if (nloc > 0)
    for (PetscInt i = 0; i < k; i++) PetscCallBLAS("BLASgemv", BLASgemv_("N", &bn, &three, &mone, &u->Z[nloc * 3 * u->act[i]], &bn, &u->w[3 * i], &one, &pone, xa, &one));
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* Before a checkpoint: the current state factorised as the reference, as a run continued from
   the checkpoint (which factorises what it restores) will have it. */
static PetscErrorCode FOMUpdateSettle(BoltOperator *op, PetscViewer v)
{
  BoltFOMUpdate *u = ((BoltFOMCtx *)BoltOperatorContext(op))->update;

  PetscFunctionBeginUser;
  (void)v;
  if (!u->valid) PetscFunctionReturn(0);
  PetscCall(FOMReferenceMake(u, op, u->dual));
  PetscFunctionReturn(0);
}

static PetscErrorCode FOMUpdateView(BoltOperator *op, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(BoltFOMUpdateView(((BoltFOMCtx *)BoltOperatorContext(op))->update, viewer));
  PetscFunctionReturn(0);
}

/* The FOM's factorisations and solves from here (maxRank > 0; -1: resolved at the first
   transient factorisation). */
PetscErrorCode BoltFOMUpdateCreate(BoltOperator *op, PetscInt maxRank)
{
  BoltFOMCtx    *ctx = (BoltFOMCtx *)BoltOperatorContext(op);
  BoltFOMUpdate *u;
  PetscInt       rend;

  PetscFunctionBeginUser;
  PetscCall(BoltFOMUpdateDestroy(&ctx->update));
  if (maxRank == 0) { /* every change factorised (and the columns of any earlier update freed) */
    PetscCall(BoltOperatorSetOperation(op, BOLT_OP_FACTOR, NULL));
    PetscCall(BoltOperatorSetOperation(op, BOLT_OP_SOLVE, NULL));
    PetscCall(BoltOperatorSetOperation(op, BOLT_OP_STATE_SAVE, NULL));
    PetscCall(BoltOperatorSetOperation(op, BOLT_OP_VIEW, NULL));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscNew(&u));
  u->maxRank = maxRank;
  PetscCall(MatGetOwnershipRange(BoltOperatorStiffness(op), &u->rstart, &rend));
  u->nloc = rend - u->rstart;
  PetscCall(MatGetSize(BoltOperatorStiffness(op), &u->N, NULL));
  PetscCall(PetscMalloc1(576 * BoltContactSetElementCount(BoltOperatorContact(op)) + 1, &u->Ke));
  PetscCall(BoltCapacitanceCreate(&u->cap));
  ctx->update = u;
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_FACTOR, (void (*)(void))FOMUpdateFactor));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_SOLVE, (void (*)(void))FOMUpdateSolve));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_STATE_SAVE, (void (*)(void))FOMUpdateSettle));
  PetscCall(BoltOperatorSetOperation(op, BOLT_OP_VIEW, (void (*)(void))FOMUpdateView));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltFOMUpdateView(BoltFOMUpdate *u, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!u) PetscFunctionReturn(0);
  if (u->maxRank < 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  transient: contact state changes taken as low-rank updates of the last factorisation (-fom_update_rank: its largest rank from the first one)\n"));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  transient: contact state changes taken as low-rank updates of the last factorisation, rank up to %" PetscInt_FMT " (-fom_update_rank; so far %" PetscInt_FMT " updates, %" PetscInt_FMT " factorisations, at most %" PetscInt_FMT " pairs joining the pool at once)\n", u->maxRank, u->updates, u->references, u->largestBatch));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltFOMUpdateDestroy(BoltFOMUpdate **up)
{
  BoltFOMUpdate *u = *up;

  PetscFunctionBeginUser;
  if (!u) PetscFunctionReturn(0);
  PetscCall(PetscFree(u->Ke));
  PetscCall(PetscFree2(u->pool, u->sorted));
  PetscCall(PetscFree2(u->Z, u->G));
  PetscCall(PetscFree(u->pairs));
  PetscCall(PetscFree2(u->act, u->idx));
  PetscCall(PetscFree3(u->S, u->t, u->w));
  PetscCall(BoltCapacitanceDestroy(&u->cap));
  PetscCall(PetscFree(u->send));
  PetscCall(PetscFree(u->recv));
  PetscCall(PetscFree(*up));
  PetscFunctionReturn(0);
}
