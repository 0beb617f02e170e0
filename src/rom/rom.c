/* The reduced-order operator: small dense matrices on every rank, solved redundantly with
   LAPACK (cheaper than broadcasting the solution), and the contact DOFs reached through the
   rows of the basis: u_c = V_c q_r, F_r = sum_p D_p' F_p over the node pairs (each summed by
   one owner rank) and K_cr = sum_e V_e' K_e V_e (as D_e' M_e D_e, updated only for elements
   whose active points changed), with D = V_b - V_a at the node pairs. Both sums have the same
   bits on any partition (exact sums over ranks; K_cr under the nodal quadrature by one product
   every rank makes on the same gathered node pairs), and so has the ROM's history. Under the
   penalty law a time step needs neither u_c nor the sums while the contact state holds: the gaps
   come from node-pair rows (normal ones on flat surfaces), and the forces, K_cr and the opening
   test's coefficients are kept with the state's version. */
#include "boltrom.h"
#include <petscblaslapack.h>

/* u = A x for a column-major m x n block A (leading dimension lda) of rows of the basis. Each row
   is summed in the same order whatever its position in the block (a BLAS kernel may treat the
   rows of a vector block and of its tail differently), so a row gets the same bits on any
   partition. Where the CPU has AVX2 a clone with four rows per vector runs instead: the same
   products and sums per row (the file is compiled without contraction into FMAs), so the same
   bits. */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
static void ROMRowsTimes(PetscInt m, PetscInt n, const PetscScalar *A, PetscInt lda, const PetscScalar *x, PetscScalar *u)
{
  for (PetscInt i = 0; i < m; i++) u[i] = 0;
  for (PetscInt j = 0; j < n; j += 4) { /* four columns per pass over u, still in order j */
    const PetscInt     nb = PetscMin(4, n - j);
    const PetscScalar *restrict c0 = A + lda * j, x0 = x[j];
    PetscScalar *restrict       uu = u;
    if (nb == 4) {
      const PetscScalar *restrict c1 = c0 + lda, *restrict c2 = c1 + lda, *restrict c3 = c2 + lda, x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
      for (PetscInt i = 0; i < m; i++) uu[i] = uu[i] + c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
    } else
      for (PetscInt k = 0; k < nb; k++)
        for (PetscInt i = 0; i < m; i++) uu[i] += c0[i + lda * k] * x[j + k];
  }
}

/* u_c = V_c q, a contact DOF with the same bits on any partition. */
static PetscErrorCode ROMContactDisplacements(BoltOperator *op, Vec q)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  BoltContactSet    *c   = rom->contact;
  const PetscScalar *x;
  PetscScalar       *u;

  PetscFunctionBeginUser;
  if (!c->nlocal) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(q, &x));
  PetscCall(VecGetArray(c->uc, &u));
  ROMRowsTimes(c->nlocal, rom->n, rom->Vc, c->nlocal, x, u);
  PetscCall(VecRestoreArray(c->uc, &u));
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscFunctionReturn(0);
}

/* A point at a node pair (a changed point of the nodal quadrature, or an element's corner): its
   node pair (global DOFs of the x components on sides b and a, -1 where clamped), its name
   (4 x element key + corner) and where its record is. */
typedef struct {
  PetscInt dofB, dofA, name, pos;
} ROMPointRecord;

static int ROMPointByPairThenName(const void *x, const void *y)
{
  const ROMPointRecord *a = (const ROMPointRecord *)x, *b = (const ROMPointRecord *)y;
  if (a->dofB != b->dofB) return a->dofB < b->dofB ? -1 : 1;
  if (a->dofA != b->dofA) return a->dofA < b->dofA ? -1 : 1;
  return a->name < b->name ? -1 : (a->name > b->name ? 1 : 0);
}

static int ROMPointByName(const void *x, const void *y)
{
  const ROMPointRecord *a = (const ROMPointRecord *)x, *b = (const ROMPointRecord *)y;
  return a->name < b->name ? -1 : (a->name > b->name ? 1 : 0);
}

/* The node pairs of nrec point records: rec sorted by pair, then name; first[k] the first point of
   pair k, its pos where the pair's points start in rec, the pairs in the order of those points'
   names. The global DOFs group the points on any partition; only the names order them. Returns
   the number of pairs. */
static PetscInt ROMNodePairs(PetscInt nrec, ROMPointRecord rec[], ROMPointRecord first[])
{
  PetscInt npair = 0;

  qsort(rec, (size_t)nrec, sizeof(ROMPointRecord), ROMPointByPairThenName);
  for (PetscInt i = 0; i < nrec; i++) {
    if (i > 0 && rec[i].dofB == rec[i - 1].dofB && rec[i].dofA == rec[i - 1].dofA) continue;
    first[npair]     = rec[i];
    first[npair].pos = i;
    npair++;
  }
  qsort(first, (size_t)npair, sizeof(ROMPointRecord), ROMPointByName);
  return npair;
}

/* g = D_p' F_p (n values), owned pair k's term of F_r, each value summed over the three
   components in that order. */
static void ROMPairForceTerm(const BoltROM *rom, PetscInt k, PetscReal g_[])
{
  const PetscInt            n = rom->n;
  const PetscReal *restrict D = &rom->npRowsAll[3 * n * rom->npGlobalOf[k]];
  const PetscReal           f0 = rom->npF[3 * k], f1 = rom->npF[3 * k + 1], f2 = rom->npF[3 * k + 2];
  PetscReal *restrict       g = g_;

  for (PetscInt j = 0; j < n; j++) g[j] = D[j] * f0 + D[n + j] * f1 + D[2 * n + j] * f2;
}

/* F_p of every owned node pair from the multipliers: the local elements' nodal forces go to the
   pairs' owners, which sum each pair's points in the order of their names. Returns the global
   bound max_p max|D_p| |F_p|_1 of the terms (collective). */
static PetscErrorCode ROMPairForces(BoltROM *rom, const PetscReal lambda[], PetscReal *bound)
{
  BoltContactSet *c = rom->contact;
  PetscReal       b = 0;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < c->nelem; e++) BoltContactElementForces(c, e, lambda, &rom->felem[12 * e]);
  PetscCall(PetscSFReduceBegin(rom->npSF, MPIU_REAL, rom->felem, rom->npSlotF, MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(rom->npSF, MPIU_REAL, rom->felem, rom->npSlotF, MPI_REPLACE));
  for (PetscInt k = 0; k < rom->npOwned; k++) {
    PetscReal       *F = &rom->npF[3 * k];
    const PetscReal *s = &rom->npSlotF[3 * rom->npSlotStart[k]];
    F[0] = s[0];
    F[1] = s[1];
    F[2] = s[2];
    for (PetscInt i = rom->npSlotStart[k] + 1; i < rom->npSlotStart[k + 1]; i++)
      for (PetscInt l = 0; l < 3; l++) F[l] += rom->npSlotF[3 * i + l];
    b = PetscMax(b, rom->npDMax[k] * (PetscAbsReal(F[0]) + PetscAbsReal(F[1]) + PetscAbsReal(F[2])));
  }
  PetscCall(MPIU_Allreduce(&b, bound, 1, MPIU_REAL, MPI_MAX, rom->comm));
  PetscFunctionReturn(0);
}

/* The node pairs' owners and slots, their rows D_p and the forces' star forest. Every rank
   gathers the names of all points with a node pair and orders the pairs alike: pair k (in the
   order of its first point's name) belongs to rank k mod size, and its points take its slots in
   the order of their names. The rows come from the rank of the pair's first point. A pair is
   live if any of its points may change (mayChange NULL: all may). */
static PetscErrorCode ROMSetUpPairForces(BoltROM *rom, const PetscBool mayChange[])
{
  BoltContactSet *c = rom->contact;
  const PetscInt  n = rom->n, recLen = 1 + 3 * n;
  PetscMPIInt     size, rank;
  PetscInt        nmine = 0, total, nrec, npair = 0, nleaves = 0, nsend = 0, own = 0, nslots = 0, *recs, *all, *count, *ilocal, *npts;
  PetscBool      *live;
  ROMPointRecord *rec, *first;
  PetscSFNode    *iremote;
  PetscReal      *send, *recv;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(rom->comm, &size));
  PetscCallMPI(MPI_Comm_rank(rom->comm, &rank));
  PetscCall(PetscFree6(rom->npSlotStart, rom->npGlobalOf, rom->npDMax, rom->npSlotF, rom->npF, rom->npFSum));
  PetscCall(PetscFree3(rom->npRowOf, rom->npRows, rom->npGap));
  PetscCall(PetscFree2(rom->npRowsAll, rom->npOfPoint));
  PetscCall(PetscSFDestroy(&rom->npSF));
  PetscCall(PetscMalloc1(24 * c->nelem + 1, &recs));
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt *r = &recs[6 * nmine];
      if (c->elem[e].dofs[3 * a] < 0 && c->elem[e].dofs[12 + 3 * a] < 0) continue; /* both nodes clamped */
      r[0] = c->elem[e].dofs[12 + 3 * a];
      r[1] = c->elem[e].dofs[3 * a];
      r[2] = 4 * c->elem[e].key + a;
      r[3] = rank;
      r[4] = 12 * e + 3 * a; /* its forces in felem */
      r[5] = !mayChange || mayChange[4 * e + a];
      nmine++;
    }
  PetscCall(BoltGatherAll(rom->comm, MPIU_INT, recs, 6 * nmine, &all, NULL, &total, NULL));
  PetscCall(PetscFree(recs));
  nrec = total / 6;
  PetscCall(PetscMalloc6(nrec + 1, &rec, nrec + 1, &first, size, &count, 3 * nmine + 1, &ilocal, nrec + 1, &npts, nrec + 1, &live));
  PetscCall(PetscMalloc1(3 * nmine + 1, &iremote));
  for (PetscInt i = 0; i < nrec; i++) {
    rec[i].dofB = all[6 * i];
    rec[i].dofA = all[6 * i + 1];
    rec[i].name = all[6 * i + 2];
    rec[i].pos  = i;
  }
  npair = ROMNodePairs(nrec, rec, first);
  rom->npGlobal = npair;
  rom->npOwned  = npair / size + (rank < npair % size ? 1 : 0);
  rom->npLive   = 0;
  for (PetscInt k = 0; k < npair; k++) { /* each pair's number of points, and whether it is live */
    const PetscInt i0 = first[k].pos;
    npts[k]           = 1;
    while (i0 + npts[k] < nrec && rec[i0 + npts[k]].dofB == first[k].dofB && rec[i0 + npts[k]].dofA == first[k].dofA) npts[k]++;
    live[k] = PETSC_FALSE;
    for (PetscInt t = 0; t < npts[k]; t++) live[k] = (PetscBool)(live[k] || all[6 * rec[i0 + t].pos + 5]);
    if (k % size == rank) nslots += npts[k];
    if (k % size == rank && live[k]) rom->npLive++;
  }
  PetscCall(PetscMalloc6(rom->npOwned + 1, &rom->npSlotStart, rom->npOwned + 1, &rom->npGlobalOf, rom->npOwned + 1, &rom->npDMax, 3 * nslots + 1, &rom->npSlotF, 3 * rom->npOwned + 1, &rom->npF, 3 * rom->npOwned + 1, &rom->npFSum));
  PetscCall(PetscMalloc2(3 * n * npair + 1, &rom->npRowsAll, 4 * c->nelem + 1, &rom->npOfPoint));
  for (PetscInt i = 0; i < 4 * c->nelem; i++) rom->npOfPoint[i] = -1;
  PetscCall(PetscMalloc1(recLen * nmine + 1, &send));
  for (PetscMPIInt r = 0; r < size; r++) count[r] = 0;
  for (PetscInt k = 0; k < npair; k++) {
    const PetscInt    i0 = first[k].pos, m = npts[k];
    const PetscMPIInt owner = (PetscMPIInt)(k % size);
    if (owner == rank) rom->npSlotStart[own++] = count[rank];
    for (PetscInt t = 0; t < m; t++) { /* the pair's points are in name order from i0 */
      const PetscInt *r = &all[6 * rec[i0 + t].pos];
      if (r[3] != rank) continue;
      rom->npOfPoint[4 * (r[4] / 12) + (r[4] % 12) / 3] = k;
      for (PetscInt l = 0; l < 3; l++, nleaves++) {
        ilocal[nleaves]        = r[4] + l;
        iremote[nleaves].rank  = owner;
        iremote[nleaves].index = 3 * (count[owner] + t) + l;
      }
      if (t == 0) { /* the rows, from the first point's element */
        const PetscReal *D = &rom->De[12 * n * (r[4] / 12) + r[4] % 12];
        PetscReal       *x = &send[recLen * nsend++];
        x[0]               = (PetscReal)k;
        for (PetscInt j = 0; j < n; j++)
          for (PetscInt l = 0; l < 3; l++) x[1 + 3 * j + l] = D[l + 12 * j];
      }
    }
    count[owner] += m;
  }
  rom->npSlotStart[own] = count[rank];
  PetscCall(BoltGatherAll(rom->comm, MPIU_REAL, send, recLen * nsend, &recv, NULL, &total, NULL));
  for (PetscInt i = 0; i < total / recLen; i++) {
    const PetscReal *x = &recv[recLen * i];
    const PetscInt   k = (PetscInt)x[0];
    PetscReal        mx = 0;
    for (PetscInt j = 0; j < n; j++)
      for (PetscInt l = 0; l < 3; l++) rom->npRowsAll[3 * n * k + n * l + j] = x[1 + 3 * j + l];
    if (k % size != rank) continue;
    rom->npGlobalOf[k / size] = k;
    for (PetscInt j = 0; j < 3 * n; j++) mx = PetscMax(mx, PetscAbsReal(x[1 + j]));
    rom->npDMax[k / size] = mx;
  }
  if (rom->pairGaps) { /* the rows of the live pairs first, then the others, in the pairs' order */
    const PetscInt ld = 3 * rom->npOwned;
    PetscCall(PetscMalloc3(rom->npOwned + 1, &rom->npRowOf, ld * n + 1, &rom->npRows, ld + 1, &rom->npGap));
    for (PetscInt k = rank, o = 0, nl = 0, nh = 0; k < npair; k += size, o++) rom->npRowOf[o] = live[k] ? 3 * nl++ : 3 * (rom->npLive + nh++);
    for (PetscInt k = 0; k < rom->npOwned; k++)
      for (PetscInt j = 0; j < n; j++)
        for (PetscInt l = 0; l < 3; l++) rom->npRows[rom->npRowOf[k] + l + ld * j] = rom->npRowsAll[3 * n * rom->npGlobalOf[k] + n * l + j];
  }
  PetscCall(PetscFree(recv));
  PetscCall(PetscFree(send));
  PetscCall(PetscFree(all));
  PetscCall(PetscSFCreate(rom->comm, &rom->npSF));
  PetscCall(PetscSFSetGraph(rom->npSF, 3 * nslots, nleaves, ilocal, PETSC_COPY_VALUES, iremote, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(rom->npSF));
  PetscCall(PetscFree6(rec, first, count, ilocal, npts, live));
  PetscFunctionReturn(0);
}

/* F_r of the state's own multipliers, where the ROM takes low-rank updates (the strict law):
   after a change of the active set only the node pairs whose forces changed are summed again.
   Each rank keeps its partial exact sum on a grid that stays while the terms fit it, and each
   owned pair's term as it was split onto the grid; a changed pair's old parts are taken out
   (exactly) and its new term added. The partial sums then hold exactly the parts of the current
   terms, so F_r has the bits of a sum made afresh on that grid, on any number of ranks. */
static PetscErrorCode ROMContactForcesChanged(BoltOperator *op, const PetscReal lambda[], Vec F)
{
  BoltROM       *rom = (BoltROM *)op->ctx;
  const PetscInt n   = rom->n;
  PetscReal      bound, *g = rom->work;
  PetscBool      fresh;
  PetscScalar   *y;

  PetscFunctionBeginUser;
  PetscCall(ROMPairForces(rom, lambda, &bound));
  /* a new grid where a term outgrows it or the terms shrank so far that it is too coarse */
  if (!rom->fGridValid || bound > rom->fGridBound || bound < ldexp(rom->fGridBound, -20)) {
    rom->fGridBound  = bound;
    rom->fGridValid  = PETSC_TRUE;
    rom->fPartsValid = PETSC_FALSE;
  }
  fresh = (PetscBool)!rom->fPartsValid;
  PetscCall(BoltExactSumBegin(&rom->sum, n, rom->fGridBound, rom->npGlobal));
  if (!fresh) PetscCall(PetscArraycpy(rom->sum.acc, rom->fAcc, 2 * n));
  for (PetscInt k = 0; k < rom->npOwned; k++) {
    const PetscReal *f    = &rom->npF[3 * k];
    PetscReal       *fsum = &rom->npFSum[3 * k], *p = &rom->fParts[2 * n * k];
    if (!fresh && f[0] == fsum[0] && f[1] == fsum[1] && f[2] == fsum[2]) continue;
    ROMPairForceTerm(rom, k, g);
    if (fresh) BoltExactSumAddParts(&rom->sum, g, p, p + n);
    else BoltExactSumReplaceParts(&rom->sum, g, p, p + n);
    PetscCall(PetscArraycpy(fsum, f, 3));
  }
  PetscCall(PetscArraycpy(rom->fAcc, rom->sum.acc, 2 * n));
  rom->fPartsValid = PETSC_TRUE;
  PetscCall(VecGetArray(F, &y));
  PetscCall(BoltExactSumEnd(&rom->sum, rom->comm, y));
  PetscCall(PetscArraycpy(rom->Fr, y, n));
  PetscCall(VecRestoreArray(F, &y));
  rom->FrVersion = op->state->version;
  rom->FrValid   = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* F_r = sum_p D_p' F_p over the node pairs of all ranks (F_p the side-b nodal force of the
   Gauss-point tractions at the pair; side a takes -F_p). A pair's term does not depend on the
   partition, and the sum over pairs is exact on fixed grids (BoltExactSum), so F_r has the same
   bits on any number of ranks. The forces of the state's own multipliers are kept while the
   state's version holds: under the penalty law they are the same every step. */
static PetscErrorCode ROMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F)
{
  BoltROM       *rom = (BoltROM *)op->ctx;
  const PetscInt n   = rom->n;
  /* the state's multipliers, with or without its anchors (a rank without anchors hands lambda
     itself): a decision every rank takes alike, as the cache skips reductions */
  const PetscBool own = (PetscBool)(lambda == op->state->lambda || lambda == op->state->lambdaForce);
  PetscReal       bound, *g = rom->work;
  PetscScalar    *y;

  PetscFunctionBeginUser;
  if (own && rom->FrValid && rom->FrVersion == op->state->version) {
    PetscCall(VecGetArray(F, &y));
    PetscCall(PetscArraycpy(y, rom->Fr, n));
    PetscCall(VecRestoreArray(F, &y));
    PetscFunctionReturn(0);
  }
  if (own && rom->update) {
    PetscCall(ROMContactForcesChanged(op, lambda, F));
    PetscFunctionReturn(0);
  }
  PetscCall(ROMPairForces(rom, lambda, &bound));
  PetscCall(BoltExactSumBegin(&rom->sum, n, bound, rom->npGlobal));
  for (PetscInt k = 0; k < rom->npOwned && bound > 0; k++) {
    ROMPairForceTerm(rom, k, g);
    BoltExactSumAdd(&rom->sum, g);
  }
  PetscCall(VecGetArray(F, &y));
  PetscCall(BoltExactSumEnd(&rom->sum, rom->comm, y));
  if (own) {
    PetscCall(PetscArraycpy(rom->Fr, y, n));
    rom->FrVersion = op->state->version;
    rom->FrValid   = PETSC_TRUE;
  }
  PetscCall(VecRestoreArray(F, &y));
  PetscFunctionReturn(0);
}

/* K_cr += the symmetric matrix whose upper triangle is packed (column by column): the triangle
   into both halves, so that K_cr stays exactly symmetric. */
static PetscErrorCode ROMAddPackedToKcr(BoltROM *rom, const PetscScalar packed[])
{
  const PetscInt n = rom->n;
  PetscScalar   *K;

  PetscFunctionBeginUser;
  PetscCall(MatDenseGetArray(rom->Kcr, &K));
  for (PetscInt l = 0, k = 0; l < n; l++)
    for (PetscInt j = 0; j <= l; j++, k++) {
      K[j + n * l] += packed[k];
      if (j != l) K[l + n * j] += packed[k];
    }
  PetscCall(MatDenseRestoreArray(rom->Kcr, &K));
  PetscCall(MatAssemblyBegin(rom->Kcr, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(rom->Kcr, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* K_cr += Tm Dm' (n x n, symmetric), by its upper triangle only and shared among the ranks.
   The columns are cut into ROM_KCR_BLOCKS blocks of about equal triangle (bounds n sqrt(b/B),
   set by n alone); a block's part of the triangle is one GEMM of its rows 0..c1 and its columns
   c0..c1, made by the rank that owns the block. Ranks own consecutive blocks, so their packed
   columns follow each other as in the packed triangle and one Allgatherv puts the whole triangle
   on every rank. Each block is the same call on the same data on any number of ranks: K_cr keeps
   the same bits on any partition, and the work per rank is a quarter of a full GEMM on two. */
#define ROM_KCR_BLOCKS 8
static PetscErrorCode ROMAddUpperProduct(BoltROM *rom, PetscInt npair, const PetscReal Tm[], const PetscReal Dm[])
{
  const PetscInt n = rom->n;
  PetscMPIInt    size, rank, *rcounts, *rdispls;
  PetscInt       cut[ROM_KCR_BLOCKS + 1];
  PetscBLASInt   bk, bn;
  PetscScalar    one = 1.0, zero = 0.0, *packed = rom->packed, *C = rom->dK;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(rom->comm, &size));
  PetscCallMPI(MPI_Comm_rank(rom->comm, &rank));
  PetscCall(PetscBLASIntCast(3 * npair, &bk));
  PetscCall(PetscBLASIntCast(n, &bn));
  for (PetscInt b = 0; b <= ROM_KCR_BLOCKS; b++) cut[b] = (PetscInt)PetscFloorReal(n * PetscSqrtReal((PetscReal)b / ROM_KCR_BLOCKS) + 0.5);
  cut[ROM_KCR_BLOCKS] = n;
  PetscCall(PetscMalloc2(size, &rcounts, size, &rdispls));
  for (PetscMPIInt r = 0; r < size; r++) {
    const PetscInt c0 = cut[(ROM_KCR_BLOCKS * r) / size], c1 = cut[(ROM_KCR_BLOCKS * (r + 1)) / size];
    PetscCall(PetscMPIIntCast(c1 * (c1 + 1) / 2 - c0 * (c0 + 1) / 2, &rcounts[r]));
    PetscCall(PetscMPIIntCast(c0 * (c0 + 1) / 2, &rdispls[r]));
  }
  for (PetscInt b = (ROM_KCR_BLOCKS * rank) / size; b < (ROM_KCR_BLOCKS * (rank + 1)) / size; b++) {
    const PetscInt c0 = cut[b], c1 = cut[b + 1];
    PetscBLASInt   bm, bw;
    if (c1 <= c0) continue;
    PetscCall(PetscBLASIntCast(c1, &bm));
    PetscCall(PetscBLASIntCast(c1 - c0, &bw));
    PetscCallBLAS("BLASgemm", BLASgemm_("N", "T", &bm, &bw, &bk, &one, Tm, &bn, &Dm[c0], &bn, &zero, C, &bm));
    for (PetscInt l = c0, k = l * (l + 1) / 2; l < c1; l++)
      for (PetscInt j = 0; j <= l; j++) packed[k++] = C[j + c1 * (l - c0)];
  }
  PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, packed, rcounts, rdispls, MPIU_SCALAR, rom->comm));
  PetscCall(PetscFree2(rcounts, rdispls));
  PetscCall(ROMAddPackedToKcr(rom, packed));
  PetscFunctionReturn(0);
}

/* K_cr += sum_p D_p' dB_p D_p over the node pairs p whose 3 x 3 blocks changed. Under the nodal
   quadrature an element's M_e is block diagonal in its four points, and the points of the (up to
   four) elements at a node pair share its rows D_p of D = V_b - V_a: one term per node pair, and
   all of them in one BLAS-3 product, instead of an n x n exact sum per element. Every rank
   gathers the changed points (pair, name, block; the pairs' rows are on every rank), sums each
   node pair's blocks in the order of the points' names and takes the node pairs in the order of
   their first changed point's name, so all ranks hold the same factors Tm and Dm, whose product
   they share (ROMAddUpperProduct). */
static PetscErrorCode ROMContactStiffnessNodePairs(BoltROM *rom, PetscInt ndirty, const PetscInt dirty[], const PetscReal delta[])
{
  BoltContactSet *c = rom->contact;
  const PetscInt  n = rom->n, recLen = 2 + 9;
  PetscInt        nsend = 0, total = 0, nrec, npair = 0;
  PetscReal      *send, *recv, *Dm, *Tm;
  ROMPointRecord *rec, *first;

  PetscFunctionBeginUser;
  PetscCall(BoltGrowReal(&rom->kcrSend, &rom->kcrSendAlloc, recLen * 4 * ndirty + 1));
  send = rom->kcrSend;
  for (PetscInt i = 0; i < ndirty; i++) {
    const PetscInt   e = dirty[i];
    const PetscReal *d = &delta[144 * i];
    for (PetscInt a = 0; a < 4; a++) {
      PetscReal *r = &send[nsend];
      PetscBool  changed = PETSC_FALSE;
      if (rom->npOfPoint[4 * e + a] < 0) continue; /* both nodes clamped */
      for (PetscInt p = 0; p < 12; p++) /* off the point's own block the nodal M_e is zero */
        for (PetscInt q = 0; q < 12; q++) {
          if (p / 3 == a && q / 3 == a) changed = (PetscBool)(changed || d[12 * p + q] != 0);
          else if ((p / 3 == a || q / 3 == a) && d[12 * p + q] != 0) SETERRQ(rom->comm, PETSC_ERR_PLIB, "nodal contact stiffness couples two points of an element");
        }
      if (!changed) continue;
      r[0] = (PetscReal)rom->npOfPoint[4 * e + a];
      r[1] = (PetscReal)(4 * c->elem[e].key + a);
      for (PetscInt p = 0; p < 3; p++)
        for (PetscInt q = 0; q < 3; q++) r[2 + 3 * p + q] = d[12 * (3 * a + p) + 3 * a + q];
      nsend += recLen;
    }
  }
  PetscCall(BoltGatherAll(rom->comm, MPIU_REAL, send, nsend, &rom->kcrRecv, &rom->kcrRecvAlloc, &total, NULL));
  recv = rom->kcrRecv;
  nrec = total / recLen;
  PetscCall(PetscMalloc2(nrec + 1, &rec, nrec + 1, &first));
  for (PetscInt i = 0; i < nrec; i++) {
    const PetscReal *r = &recv[recLen * i];
    rec[i].dofB = (PetscInt)r[0]; /* the pair's index stands for its two nodes */
    rec[i].dofA = 0;
    rec[i].name = (PetscInt)r[1];
    rec[i].pos  = recLen * i;
  }
  npair = ROMNodePairs(nrec, rec, first);
  /* Dm (n x 3m) and Tm = Dm blockdiag(dB_p) */
  PetscCall(BoltGrowReal(&rom->kcrDT, &rom->kcrDTAlloc, 6 * n * npair + 2));
  Dm = rom->kcrDT;
  Tm = Dm + 3 * n * npair + 1;
  for (PetscInt k = 0; k < npair; k++) {
    PetscReal        dB[9];
    const PetscReal *r0 = &recv[rec[first[k].pos].pos], *D = &rom->npRowsAll[3 * n * first[k].dofB];
    PetscCall(PetscArraycpy(dB, r0 + 2, 9));
    for (PetscInt i = first[k].pos + 1; i < nrec && rec[i].dofB == first[k].dofB; i++)
      for (PetscInt l = 0; l < 9; l++) dB[l] += recv[rec[i].pos + 2 + l];
    PetscCall(PetscArraycpy(&Dm[3 * n * k], D, 3 * n));
    for (PetscInt q = 0; q < 3; q++)
      for (PetscInt j = 0; j < n; j++) Tm[3 * n * k + n * q + j] = D[j] * dB[q] + D[n + j] * dB[3 + q] + D[2 * n + j] * dB[6 + q];
  }
  PetscCall(PetscFree2(rec, first));
  if (npair > 0) PetscCall(ROMAddUpperProduct(rom, npair, Tm, Dm));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMContactStiffness(BoltOperator *op, Mat *Kc)
{
  BoltROM          *rom = (BoltROM *)op->ctx;
  BoltContactSet   *c   = rom->contact;
  BoltContactState *s   = op->state;
  const PetscInt  n   = rom->n;
  PetscInt        ndirty = 0, *dirty = rom->dirtyElems;
  PetscReal       bound = 0, *delta = rom->dMe, *T = rom->work2, *dK = rom->dK, Knew[576];

  PetscFunctionBeginUser;
  /* the same state as at the last update: nothing is due (and no rank needs to ask the others) */
  if (rom->KcrValid && rom->KcrVersion == s->version) {
    *Kc = rom->Kcr;
    PetscFunctionReturn(0);
  }
  /* K_e = [M -M; -M M] (B = [-N, N]), so V_e' K_e V_e = D_e' M D_e with D_e = V_b - V_a, the
     relative displacements of the node pairs. Working with D_e spares the directions that open
     no gap the penalty's round-off (through K_e it would be about eps_N |V|^2 u, large under a
     near-hard penalty against the joint's soft stiffness). First the change of M of every
     element whose points changed, and a bound of its reduced part for the exact sum */
  for (PetscInt e = 0; e < c->nelem; e++) {
    PetscReal *d = &delta[144 * ndirty], size = 0;
    if (!s->dirty[e]) continue;
    PetscCall(BoltContactSetElementStiffness(c, e, s->epsN[c->elem[e].pair], BoltContactStateStickStiffness(s, c->elem[e].pair), &s->active[4 * e], &s->released[4 * e], BoltContactStateSlipDirs(s, e), Knew));
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) {
        d[12 * a + b]                 = Knew[24 * a + b] - rom->Ke[144 * e + 12 * a + b];
        rom->Ke[144 * e + 12 * a + b] = Knew[24 * a + b];
        size += PetscAbsReal(d[12 * a + b]);
      }
    s->dirty[e] = PETSC_FALSE;
    BoltROMUpdateSummed(rom->update, rom, e);
    bound       = PetscMax(bound, PetscSqr(rom->DeMax[e]) * size);
    dirty[ndirty++] = e;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bound, 1, MPIU_REAL, MPI_MAX, rom->comm));
  if (bound > 0 && c->quadrature == BOLT_QUADRATURE_NODAL) PetscCall(ROMContactStiffnessNodePairs(rom, ndirty, dirty, delta));
  else if (bound > 0) {
    /* K_cr += sum_e D_e' (M_new - M_old) D_e: per element by BLAS (the same call on the same data
       on any partition), summed exactly over its upper triangle */
    PetscBLASInt bn, b12 = 12;
    PetscScalar  one = 1.0, zero = 0.0, *packed = rom->packed;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(BoltExactSumBegin(&rom->sum, n * (n + 1) / 2, bound, c->ngpGlobal / 4));
    for (PetscInt i = 0; i < ndirty; i++) {
      PetscScalar *d = &delta[144 * i], *D = &rom->De[12 * n * dirty[i]];
      PetscCallBLAS("BLASgemm", BLASgemm_("N", "N", &b12, &bn, &b12, &one, d, &b12, D, &b12, &zero, T, &b12));
      PetscCallBLAS("BLASgemm", BLASgemm_("T", "N", &bn, &bn, &b12, &one, D, &b12, T, &b12, &zero, dK, &bn));
      for (PetscInt l = 0, k = 0; l < n; l++)
        for (PetscInt j = 0; j <= l; j++) packed[k++] = dK[j + n * l];
      BoltExactSumAdd(&rom->sum, packed);
    }
    PetscCall(BoltExactSumEnd(&rom->sum, rom->comm, packed));
    PetscCall(ROMAddPackedToKcr(rom, packed));
  }
  rom->KcrVersion = s->version;
  rom->KcrValid   = PETSC_TRUE;
  *Kc             = rom->Kcr;
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMProbe(BoltOperator *op, Vec q, PetscReal *value)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  const PetscScalar *x;
  PetscReal          v = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(q, &x));
  for (PetscInt j = 0; j < rom->n; j++) v += rom->Vprobe[j] * PetscRealPart(x[j]);
  PetscCall(VecRestoreArrayRead(q, &x));
  *value = v;
  PetscFunctionReturn(0);
}

/* Checkpoints: the reduced vectors as they are (the same on every rank), written by rank 0. */
static PetscErrorCode ROMVectorsSave(BoltOperator *op, PetscViewer v, PetscInt n, const char *const names[], Vec x[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltHDF5WriteVecs(v, op->comm, n, names, x, PETSC_TRUE));
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMVectorsLoad(BoltOperator *op, PetscViewer v, PetscInt nvec, const char *const names[], Vec y[], PetscInt *missing)
{
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < nvec; f++) {
    PetscScalar *a;
    PetscReal   *x;
    PetscInt     n, nloc;
    PetscCall(VecGetLocalSize(y[f], &nloc));
    PetscCall(BoltReadAll(v, op->comm, names[f], &n, &x));
    PetscCheck(n == nloc, op->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint holds %" PetscInt_FMT " reduced coordinates, this ROM has %" PetscInt_FMT, n, nloc);
    PetscCall(VecGetArray(y[f], &a));
    for (PetscInt i = 0; i < nloc; i++) a[i] = x[i];
    PetscCall(VecRestoreArray(y[f], &a));
    PetscCall(PetscFree(x));
  }
  PetscFunctionReturn(0);
}

/* The reduced contact stiffness is a sum updated element by element: its round-off depends on
   the path, so a checkpoint keeps it as it is rather than rebuilding it. */
static PetscErrorCode ROMStateSave(BoltOperator *op, PetscViewer v)
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  Mat                Kc;
  const PetscScalar *a;
  PetscInt           nr;

  PetscFunctionBeginUser;
  PetscCall(BoltROMUpdateSettle(op)); /* K_cr of the current state, factorised */
  PetscCall(ROMContactStiffness(op, &Kc));
  PetscCall(MatGetSize(Kc, &nr, NULL));
  PetscCall(MatDenseGetArrayRead(Kc, &a));
  PetscCall(BoltHDF5WriteValues(v, op->comm, "reduced_contact_stiffness", nr * nr, 1, a, PETSC_TRUE));
  PetscCall(MatDenseRestoreArrayRead(Kc, &a));
  if (rom->update) { /* the grid of the reduced forces' sums: the continued run sums on it too */
    const PetscScalar grid[2] = {rom->fGridBound, rom->fGridValid ? 1.0 : 0.0};
    PetscCall(BoltHDF5WriteValues(v, op->comm, "reduced_forces_grid", 2, 1, grid, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* After the contact state was restored: K_cr brought up to date, then replaced by the saved sum. */
static PetscErrorCode ROMStateLoad(BoltOperator *op, PetscViewer v)
{
  BoltROM     *rom = (BoltROM *)op->ctx;
  Mat          Kc;
  PetscScalar *a;
  PetscReal   *x;
  PetscInt     n, nr;

  PetscFunctionBeginUser;
  PetscCall(ROMContactStiffness(op, &Kc));
  PetscCall(MatGetSize(Kc, &nr, NULL));
  PetscCall(BoltReadAll(v, op->comm, "reduced_contact_stiffness", &n, &x));
  PetscCheck(n == nr * nr, op->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint is damaged (reduced contact stiffness of %" PetscInt_FMT " values)", n);
  PetscCall(MatDenseGetArray(Kc, &a));
  for (PetscInt i = 0; i < n; i++) a[i] = x[i];
  PetscCall(MatDenseRestoreArray(Kc, &a));
  PetscCall(MatAssemblyBegin(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(x));
  if (rom->update) {
    PetscCall(BoltReadAll(v, op->comm, "reduced_forces_grid", &n, &x));
    PetscCheck(n == 2, op->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint is damaged (reduced forces' grid of %" PetscInt_FMT " values)", n);
    rom->fGridBound  = x[0];
    rom->fGridValid  = (PetscBool)(x[1] != 0);
    rom->fPartsValid = PETSC_FALSE;
    PetscCall(PetscFree(x));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMView(BoltOperator *op, PetscViewer viewer)
{
  BoltROM *rom = (BoltROM *)op->ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  reduced dimension %" PetscInt_FMT ", penalties %g x the FOM's, opening band %g x\n", rom->n, (double)rom->penaltyScale, (double)rom->bandScale));
  PetscCall(BoltROMUpdateView(rom->update, viewer));
  PetscFunctionReturn(0);
}

/* The gaps at the local contact points from rows of node-pair differences D = V_b - V_a (a
   sixth or half of the rows of V_c, and free of the cancellation in u_b - u_a), under the
   penalty law: there the multipliers do not take the trial traction, so the gaps only feed the
   decisions and the penalty acts through K_cr. On flat surfaces only the normal part,
   g = (sum_a N_a n' D_a q) n: the decisions read t.n, where the tangential part cancels to
   round-off; friction's decisions read the slip too, so there the whole gap. With augmentation
   (the multipliers take the trial traction): u_c and the set's interpolation, as the full
   model. */
static PetscErrorCode ROMContactGaps(BoltOperator *op, Vec q, PetscReal gap[])
{
  BoltROM           *rom = (BoltROM *)op->ctx;
  BoltContactSet    *c   = rom->contact;
  const PetscScalar *x;
  PetscBool          whole;
  PetscReal          xmax = 0;

  PetscFunctionBeginUser;
  if (op->state->augment) {
    PetscCall(ROMContactDisplacements(op, q));
    PetscCall(BoltContactSetGapsOf(c, gap));
    PetscFunctionReturn(0);
  }
  if (rom->pairGaps) { /* the owned pairs' gaps (the held ones once), sent to their points */
    PetscCall(VecGetArrayRead(q, &x));
    ROMRowsTimes(rom->heldRowsDone && !rom->gapsEverywhere ? 3 * rom->npLive : 3 * rom->npOwned, rom->n, rom->npRows, 3 * rom->npOwned, x, rom->npGap);
    PetscCall(VecRestoreArrayRead(q, &x));
    rom->heldRowsDone = PETSC_TRUE;
    for (PetscInt k = 0; k < rom->npOwned; k++)
      for (PetscInt i = rom->npSlotStart[k]; i < rom->npSlotStart[k + 1]; i++)
        for (PetscInt l = 0; l < 3; l++) rom->npSlotF[3 * i + l] = PetscRealPart(rom->npGap[rom->npRowOf[k] + l]);
    PetscCall(PetscArrayzero(gap, 12 * c->nelem)); /* a point whose nodes are both clamped has no gap */
    PetscCall(PetscSFBcastBegin(rom->npSF, MPIU_REAL, rom->npSlotF, gap, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(rom->npSF, MPIU_REAL, rom->npSlotF, gap, MPI_REPLACE));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(q, &x));
  /* the rows of points that may change; those of held points (their state is kept, so no decision
     reads their gaps) once, for gaps that stay defined */
  ROMRowsTimes(rom->heldRowsDone && !rom->gapsEverywhere ? rom->nLiveRows : rom->nGapRows, rom->n, rom->Rn, rom->nGapRows, x, rom->gnRow);
  rom->heldRowsDone = PETSC_TRUE;
  whole = (PetscBool)(c->law.strict && c->reanchor && !rom->wholeRows && c->quadrature == BOLT_QUADRATURE_NODAL);
  for (PetscInt j = 0; j < rom->n && whole; j++) xmax = PetscMax(xmax, PetscAbsReal(PetscRealPart(x[j])));
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscInt  *r = &rom->gpRows[4 * gp];
    const PetscReal *N = &c->gpN[4 * gp], *n = &c->gpNormal[3 * gp]; /* gpN: 4 per point */
    PetscReal       *g = &gap[3 * gp];
    if (!rom->wholeRows) {
      PetscReal gn = 0;
      if (c->quadrature == BOLT_QUADRATURE_NODAL) gn = r[gp % 4] >= 0 ? PetscRealPart(rom->gnRow[r[gp % 4]]) : 0; /* its own node, weight 1 */
      else
        for (PetscInt a = 0; a < 4; a++)
          if (r[a] >= 0) gn += N[a] * PetscRealPart(rom->gnRow[r[a]]);
      for (PetscInt k = 0; k < 3; k++) g[k] = gn * n[k];
      /* an open pair that closes sticks where it closes: its anchor needs the whole gap, from its
         node pair's rows of D_e in a fixed order (the same bits on any partition). Only where it
         may close: elsewhere the decision -g.n > activationGap is the same with the normal gap
         alone, whose rounding differs from the whole gap's by less than the bound. */
      if (whole && !op->state->active[gp] && (rom->gapsEverywhere || ((!op->state->mayChange || op->state->mayChange[gp]) && -gn > op->state->activationGap - rom->wholeGapBound[gp] * xmax))) {
        PetscScalar whole3[3];
        ROMRowsTimes(3, rom->n, &rom->De[12 * rom->n * (gp / 4) + 3 * (gp % 4)], 12, x, whole3);
        for (PetscInt k = 0; k < 3; k++) g[k] = PetscRealPart(whole3[k]);
      }
    } else if (c->quadrature == BOLT_QUADRATURE_NODAL) /* its own node, weight 1 */
      for (PetscInt k = 0; k < 3; k++) g[k] = r[gp % 4] >= 0 ? PetscRealPart(rom->gnRow[r[gp % 4] + k]) : 0;
    else
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal v = 0;
        for (PetscInt a = 0; a < 4; a++)
          if (r[a] >= 0) v += N[a] * PetscRealPart(rom->gnRow[r[a] + k]);
        g[k] = v;
      }
  }
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscFunctionReturn(0);
}

/* The opening test's traction. Under the penalty law the trial traction of a point is affine in
   its gap, t = lambda + P g, so where the test reads t.n of the point alone, or (nodal quadrature,
   flat surfaces) of the points of its own node pair, its traction is C + K g.n per point: C the
   test applied to the multipliers, K to the traction of a unit normal gap. Both change only with
   the state, and are made again (collectively) when its version moves. */
static PetscErrorCode ROMOpenTraction(BoltOperator *op, PetscReal tn[])
{
  BoltROM          *rom = (BoltROM *)op->ctx;
  BoltContactSet   *c   = rom->contact;
  BoltContactState *s   = op->state;
  const PetscInt    ngp = 4 * c->nelem;

  PetscFunctionBeginUser;
  if (s->augment || s->law.friction || (s->openTest == BOLT_OPEN_NODAL && !(c->quadrature == BOLT_QUADRATURE_NODAL && rom->flat))) {
    PetscCall(BoltContactStateOpenTraction(s, tn));
    PetscFunctionReturn(0);
  }
  if (!rom->tnValid || rom->tnVersion != s->version) {
    for (PetscInt pass = 0; pass < 2; pass++) {
      PetscReal *out = pass ? rom->tnK : rom->tnC;
      for (PetscInt gp = 0; gp < ngp; gp++) {
        const PetscInt   pair = c->elem[gp / 4].pair;
        const PetscReal *n    = &c->gpNormal[3 * gp], zero[3] = {0, 0, 0};
        PetscReal       *t    = &c->tau[3 * gp];
        if (!s->active[gp]) t[0] = t[1] = t[2] = 0;
        else if (!pass) PetscCall(PetscArraycpy(t, &s->lambda[3 * gp], 3));
        else s->law.traction(zero, n, n, s->epsN[pair], BoltContactStateEpsT(s, gp, pair), t);
      }
      if (s->openTest == BOLT_OPEN_NODAL) PetscCall(BoltContactSetSmoothedNormalTraction(c, c->tau, out));
      else
        for (PetscInt gp = 0; gp < ngp; gp++) {
          const PetscReal *t = &c->tau[3 * gp], *n = &c->gpNormal[3 * gp];
          out[gp] = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        }
    }
    rom->tnVersion = s->version;
    rom->tnValid   = PETSC_TRUE;
  }
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscReal *g = &s->gap[3 * gp], *n = &c->gpNormal[3 * gp];
    tn[gp] = rom->tnC[gp] + rom->tnK[gp] * (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]);
  }
  PetscFunctionReturn(0);
}

/* A point's normal rounded to 2^-40: the normals of a flat face's points differ in their last
   bits; rounded, they are one normal, whichever point of whichever rank makes a row. */
static void ROMRowNormal(const PetscReal n[3], PetscReal nr[3])
{
  for (PetscInt k = 0; k < 3; k++) nr[k] = ldexp(rint(ldexp(n[k], 40)), -40);
}

/* The gap rows, from the elements' D_e so that a row has the same bits on any partition. Whether
   the surfaces are flat: at every node the normals of all points around it, over all ranks (the
   nodal area vector sums them), agree with each point's to 1e-12. On flat surfaces one row n' D
   per node pair and rounded point normal (one per node pair), else the three rows of D. */
static PetscErrorCode ROMSetUpGapRows(BoltROM *rom, const PetscBool mayChange[])
{
  BoltContactSet *c = rom->contact;
  const PetscInt  n = rom->n, ngp = 4 * c->nelem;
  PetscInt       *first, *next, *rowGp, *rowNode, *pos, width;
  PetscBool       flat = PETSC_TRUE, *live;

  PetscFunctionBeginUser;
  PetscCall(PetscFree4(rom->gpRows, rom->tnC, rom->tnK, rom->wholeGapBound));
  PetscCall(PetscFree2(rom->Rn, rom->gnRow));
  PetscCall(PetscMalloc4(4 * ngp + 1, &rom->gpRows, ngp + 1, &rom->tnC, ngp + 1, &rom->tnK, ngp + 1, &rom->wholeGapBound));
  PetscCall(PetscMalloc4(c->nlocal + 1, &first, 4 * ngp + 1, &next, 4 * ngp + 1, &rowGp, 4 * ngp + 1, &rowNode));
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  *loc = &c->elemLocal[24 * (gp / 4)];
    const PetscReal *N = &c->gpN[4 * gp], *n = &c->gpNormal[3 * gp];
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt *ii = loc[12 + 3 * a] >= 0 ? &loc[12 + 3 * a] : &loc[3 * a]; /* the pair's DOFs on side b, or a */
      PetscReal       A[3], x[3];
      if (N[a] == 0 || ii[0] < 0) continue;
      for (PetscInt k = 0; k < 3; k++) A[k] = c->nodalArea[ii[k]];
      x[0] = A[1] * n[2] - A[2] * n[1]; /* A x n */
      x[1] = A[2] * n[0] - A[0] * n[2];
      x[2] = A[0] * n[1] - A[1] * n[0];
      if (PetscSqrtReal(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-12 * PetscSqrtReal(A[0] * A[0] + A[1] * A[1] + A[2] * A[2])) flat = PETSC_FALSE;
    }
  }
  PetscCall(MPIU_Allreduce(&flat, &rom->flat, 1, MPIU_BOOL, MPI_LAND, rom->comm));
  /* friction reads the tangential gaps too (the augmented ROM takes u_c = V_c q instead) */
  rom->wholeRows = (PetscBool)(!rom->flat || c->law.friction);
  width          = rom->wholeRows ? 3 : 1;
  /* each point's gap is its own node pair's: the pairs' owners make them (ROMSetUpPairForces) */
  rom->pairGaps = (PetscBool)(rom->wholeRows && c->quadrature == BOLT_QUADRATURE_NODAL && !rom->augment);
  if (rom->pairGaps) {
    rom->nGapRows = rom->nLiveRows = 0;
    rom->heldRowsDone = PETSC_FALSE;
    PetscCall(PetscMalloc2(1, &rom->Rn, 1, &rom->gnRow));
    PetscCall(PetscFree4(first, next, rowGp, rowNode));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->nlocal; i++) first[i] = -1;
  rom->nGapRows = 0;
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  *loc = &c->elemLocal[24 * (gp / 4)];
    const PetscReal *N = &c->gpN[4 * gp];
    PetscReal        n[3];
    ROMRowNormal(&c->gpNormal[3 * gp], n);
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt slot = loc[12 + 3 * a] >= 0 ? loc[12 + 3 * a] : loc[3 * a]; /* the pair's first DOF on side b, or a */
      PetscInt       r;
      rom->gpRows[4 * gp + a] = -1;
      PetscCheck(c->quadrature != BOLT_QUADRATURE_NODAL || N[a] == (a == gp % 4 ? 1.0 : 0.0), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Nodal quadrature: point %" PetscInt_FMT " is not at its own node", gp);
      if (N[a] == 0 || slot < 0) continue; /* no weight, or both sides clamped: no gap */
      for (r = first[slot]; r >= 0; r = next[r]) {
        PetscReal m[3];
        ROMRowNormal(&c->gpNormal[3 * rowGp[r]], m);
        if (rom->wholeRows || (m[0] == n[0] && m[1] == n[1] && m[2] == n[2])) break;
      }
      if (r < 0) {
        r = rom->nGapRows;
        rom->nGapRows += width;
        next[r]     = first[slot];
        first[slot] = r;
        rowGp[r]    = gp;
        rowNode[r]  = a;
      }
      rom->gpRows[4 * gp + a] = r;
    }
  }
  /* the rows of node pairs with a point that may change first (live), then the held ones */
  PetscCall(PetscCalloc2(rom->nGapRows + 1, &live, rom->nGapRows + 1, &pos));
  for (PetscInt gp = 0; gp < ngp; gp++)
    for (PetscInt a = 0; a < 4; a++)
      if (rom->gpRows[4 * gp + a] >= 0 && (!mayChange || mayChange[gp])) live[rom->gpRows[4 * gp + a]] = PETSC_TRUE;
  rom->nLiveRows = 0;
  for (PetscInt pass = 0, k = 0; pass < 2; pass++)
    for (PetscInt r = 0; r < rom->nGapRows; r += width) {
      if (live[r] != (pass == 0)) continue;
      pos[r] = k;
      k += width;
      if (!pass) rom->nLiveRows = k;
    }
  for (PetscInt i = 0; i < 4 * ngp; i++)
    if (rom->gpRows[i] >= 0) rom->gpRows[i] = pos[rom->gpRows[i]];
  rom->heldRowsDone = PETSC_FALSE;
  /* |n' D x - nr' D x| and the two sums' rounding stay below 1e-12 sum_jk |D_kj| |x|_max (n up to
     a few thousand); 1e-9 leaves room */
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscReal *D = &rom->De[12 * n * (gp / 4) + 3 * (gp % 4)];
    PetscReal        b = 0;
    for (PetscInt j = 0; j < n; j++) b += PetscAbsReal(D[12 * j]) + PetscAbsReal(D[12 * j + 1]) + PetscAbsReal(D[12 * j + 2]);
    rom->wholeGapBound[gp] = 1e-9 * b;
  }
  PetscCall(PetscMalloc2(rom->nGapRows * n + 1, &rom->Rn, rom->nGapRows + 1, &rom->gnRow));
  for (PetscInt i = 0; i < c->nlocal; i++)
    for (PetscInt r = first[i]; r >= 0; r = next[r]) {
      const PetscReal *D = &rom->De[12 * n * (rowGp[r] / 4) + 3 * rowNode[r]];
      PetscReal        nr[3];
      ROMRowNormal(&c->gpNormal[3 * rowGp[r]], nr);
      for (PetscInt j = 0; j < n; j++) {
        if (!rom->wholeRows) rom->Rn[pos[r] + rom->nGapRows * j] = nr[0] * D[12 * j] + nr[1] * D[12 * j + 1] + nr[2] * D[12 * j + 2];
        else
          for (PetscInt k = 0; k < 3; k++) rom->Rn[pos[r] + k + rom->nGapRows * j] = D[12 * j + k];
      }
    }
  PetscCall(PetscFree4(first, next, rowGp, rowNode));
  PetscCall(PetscFree2(live, pos));
  PetscFunctionReturn(0);
}

/* The ROM's operator: its matrices, and its own contact state with the ROM's law, penalties and
   opening band. */
PetscErrorCode BoltROMOperatorCreate(BoltROM *rom, BoltOperator **opp)
{
  BoltOperator *op;
  PetscInt      n = rom->n;

  PetscFunctionBeginUser;
  PetscCall(BoltOperatorCreate(rom->comm, "ROM", rom->contact, &op));
  op->solverType       = MATSOLVERPETSC;
  op->exactConstraints = (rom->nCCM + rom->nJIM) ? PETSC_FALSE : PETSC_TRUE;
  op->keepStructural   = PETSC_TRUE; /* n^2 values: a factorisation then adds K_cr to a copy */
  op->state->augment   = rom->augment; /* -rom_contact_augment */
  PetscCall(PetscStrncpy(op->prefix, "rom_", sizeof(op->prefix)));
  PetscCall(BoltOperatorSetSystem(op, rom->Mr, NULL, rom->Kr, rom->loadr, rom->preloadr));
  PetscCall(BoltOperatorSetDamping(op, rom->Cr, rom->rayleigh[0], rom->rayleigh[1]));
  op->ctx                      = rom;
  op->ops.contactDisplacements = ROMContactDisplacements;
  op->ops.contactForces        = ROMContactForces;
  op->ops.contactStiffness     = ROMContactStiffness;
  op->ops.probe                = ROMProbe;
  op->ops.vectorsSave          = ROMVectorsSave;
  op->ops.vectorsLoad          = ROMVectorsLoad;
  op->ops.stateSave            = ROMStateSave;
  op->ops.stateLoad            = ROMStateLoad;
  op->ops.view                 = ROMView;
  PetscCall(BoltContactStateSetPenaltyScale(op->state, rom->penaltyScale, rom->bandScale));
/* K_cr starts empty; every element is due for an update (marked with the penalties) */
  if (!rom->Kcr) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &rom->Kcr));
  PetscCall(MatZeroEntries(rom->Kcr));
  rom->KcrValid = rom->FrValid = rom->tnValid = PETSC_FALSE; /* a new state: its versions start afresh */
  PetscCall(PetscFree(rom->Ke));
  PetscCall(PetscCalloc1(144 * rom->contact->nelem + 1, &rom->Ke));
  PetscCall(PetscFree5(rom->work, rom->work2, rom->dK, rom->packed, rom->Fr));
  PetscCall(PetscMalloc5(12 * n + 1, &rom->work, 12 * n + 1, &rom->work2, n * n + 1, &rom->dK, n * (n + 1) / 2 + 1, &rom->packed, n + 1, &rom->Fr));
  /* D_e = V_b - V_a of every local contact element, kept for the forces and K_cr */
  {
    BoltContactSet *c = rom->contact;
    const PetscInt  m = c->nlocal;
    PetscCall(PetscFree5(rom->De, rom->DeMax, rom->felem, rom->dMe, rom->dirtyElems));
    PetscCall(PetscMalloc5(12 * n * c->nelem + 1, &rom->De, c->nelem + 1, &rom->DeMax, 12 * c->nelem + 1, &rom->felem, 144 * c->nelem + 1, &rom->dMe, c->nelem + 1, &rom->dirtyElems));
    for (PetscInt e = 0; e < c->nelem; e++) {
      PetscReal *D = &rom->De[12 * n * e], mx = 0;
      for (PetscInt k = 0; k < 12; k++) {
        PetscInt la = c->elemLocal[24 * e + k], lb = c->elemLocal[24 * e + 12 + k];
        for (PetscInt j = 0; j < n; j++) {
          D[k + 12 * j] = (lb >= 0 ? PetscRealPart(rom->Vc[lb + m * j]) : 0.0) - (la >= 0 ? PetscRealPart(rom->Vc[la + m * j]) : 0.0);
          mx            = PetscMax(mx, PetscAbsReal(D[k + 12 * j]));
        }
      }
      rom->DeMax[e] = mx;
    }
  }
  /* with opening shapes, only the points the opening solves changed may change state: the basis
     has no shapes to open the others, and freed they chattered at the washers' rims (the
     augmented ROM, without interface reduction, can open any pair) */
  op->state->mayChange = (rom->holdUnmarked && rom->marked && rom->nOpeningPairs > 0 && !rom->augment) ? rom->marked : NULL;
  PetscCall(ROMSetUpGapRows(rom, op->state->mayChange));
  op->ops.contactGaps  = ROMContactGaps;
  op->ops.openTraction = ROMOpenTraction;
  /* low-rank updates of the factorisation: by default where the active set is expected to move
     (the strict law's penalty ROM); the stick law's keeps refactorising, as in the paper */
  rom->updateRankUsed = rom->updateRank >= 0 ? rom->updateRank : (rom->contact->law.strict && !rom->augment ? (3 * n) / 5 : 0);
  PetscCall(BoltROMUpdateCreate(rom, op, rom->updateRankUsed));
  PetscCall(ROMSetUpPairForces(rom, op->state->mayChange));
  PetscCall(PetscFree2(rom->fAcc, rom->fParts));
  if (rom->update) PetscCall(PetscMalloc2(2 * n + 1, &rom->fAcc, 2 * n * rom->npOwned + 1, &rom->fParts));
  rom->fGridValid = rom->fPartsValid = PETSC_FALSE;
  *opp = op;
  PetscFunctionReturn(0);
}

/* Start the reduced dual loop from the FOM's preloaded state: its multipliers (scaled to this
   preload: with a fixed active set the static contact problem is linear in it) and its active
   set (under friction its active set only). They stay frozen (penalty law), so the preload
   vector is used as built, uncalibrated. nm runs the ROM's operator, whose state has the ROM's
   penalties. */
PetscErrorCode BoltROMSetPreloadState(BoltROM *rom, BoltNewmark *nm, PetscReal preloadForce)
{
  BoltContactSet   *c = rom->contact;
  BoltContactState *s = nm->op->state;

  PetscFunctionBeginUser;
  if (!rom->preloadState) PetscFunctionReturn(0);
  /* The FOM's traction at its preloaded state is lambda0 + P g0 (its penalty P on the residual
     gaps g0 its loop leaves), or lambda0 itself after the strict law's loop (its multipliers are
     already the trial tractions of its last solve); the ROM's penalty is s P, so the frozen
     multipliers take lambda0 - (s - 1) P g0, or lambda0 - s P g0: the ROM's traction there is
     the FOM's, its penalty acts on increments */
  const PetscReal g0Share = s->law.strict ? 1.0 : 1 - 1 / rom->penaltyScale;

  PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0)); /* sliding points first: their traction is normal */
  BoltContactStateSetAnchors(s, NULL); /* the FOM's anchors are in the frozen multipliers (raw gaps g0) */
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt  gp = 4 * e + q;
      PetscReal lam[3], g[3];
      /* open in the preload: no traction, and none frozen here. Under friction none anywhere: the
         normal is the penalty's alone, and the ROM solves its own preloaded state on the FOM's set
         (its pairs stick or slip there as the FOM's did) */
      if (!rom->active0[gp] || s->law.friction) {
        s->lambda[3 * gp] = s->lambda[3 * gp + 1] = s->lambda[3 * gp + 2] = 0;
        continue;
      }
      for (PetscInt k = 0; k < 3; k++) {
        lam[k] = rom->lambda0[3 * gp + k] * preloadForce;
        g[k]   = -g0Share * rom->gap0[3 * gp + k] * preloadForce;
      }
      s->law.traction(lam, g, &c->gpNormal[3 * gp], s->epsN[pair], BoltContactStateEpsT(s, gp, pair), &s->lambda[3 * gp]);
    }
  }
  BoltContactStateChanged(s);
  nm->calibratePreload = PETSC_FALSE;
  /* the static state is the FOM's by construction: its active set is not judged again there
     (under the ROM's stiffer penalty, points at the rim whose traction is within the band of
     zero would open on gap differences of a fraction of a nanometre) */
  nm->dual->keepActiveSet = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The tied joint in the Laplace domain at s = s0: (s0^2 M + s0 C + K + K_c) q = f with every
   contact point active, by the FOM (MUMPS) and the ROM (LAPACK). Returns the relative error of
   the ROM at the contact DOFs and the probe: the paper's central claim in its exact form. */
PetscErrorCode BoltROMCheckAtS0(BoltROM *rom, BoltOperator *op, BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, PetscReal *err)
{
  Mat       A, Ar, Kc, Kcr, C;
  Vec       q, f, qr;
  KSP       ksp, kspr;
  PetscReal s0 = rom->s0, num[2] = {0, 0}, den[2] = {0, 0}, pf, pr;
  Vec       ucFull;
  BoltContactState *sFull;

  PetscFunctionBeginUser;
  /* ROM first: its contact stiffness takes the (all active, all dirty) state */
  PetscCall(op->ops.contactStiffness(op, &Kcr));
  PetscCall(MatDuplicate(rom->Kr, MAT_COPY_VALUES, &Ar));
  PetscCall(MatAXPY(Ar, s0, rom->Cr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, s0 * s0, rom->Mr, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(Ar, 1.0, Kcr, SAME_NONZERO_PATTERN));
  PetscCall(VecDuplicate(rom->loadr, &qr));
  PetscCall(BoltDirectSolverCreate(PETSC_COMM_SELF, NULL, Ar, PETSC_FALSE, NULL, &kspr)); /* LAPACK: PETSc's default for dense */
  PetscCall(KSPSolve(kspr, rom->loadr, qr));
  /* FOM, with the ROM's penalties: a state of its own, every point active */
  PetscCall(BoltContactStateCreate(c, &sFull));
  PetscCall(BoltContactStateSetPenaltyScale(sFull, rom->penaltyScale, rom->bandScale));
  PetscCall(BoltContactStateStiffness(sFull, &Kc));
  PetscCall(BoltAssemblerDamping(asmb, &C));
  PetscCall(MatDuplicate(asmb->K, MAT_COPY_VALUES, &A));
  PetscCall(MatAXPY(A, s0, C, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, s0 * s0, asmb->M, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(A, 1.0, Kc, DIFFERENT_NONZERO_PATTERN));
  PetscCall(VecDuplicate(loads->load, &q));
  f = loads->load;
  PetscCall(BoltDirectSolverCreate(rom->comm, NULL, A, PETSC_FALSE, MATSOLVERMUMPS, &ksp));
  PetscCall(KSPSolve(ksp, f, q));
  /* compare at the contact DOFs and the probe */
  PetscCall(BoltContactSetScatter(c, q));
  PetscCall(VecDuplicate(c->uc, &ucFull));
  PetscCall(VecCopy(c->uc, ucFull));
  PetscCall(op->ops.contactDisplacements(op, qr));
  {
    const PetscScalar *a, *b;
    PetscCall(VecGetArrayRead(ucFull, &a));
    PetscCall(VecGetArrayRead(c->uc, &b));
    for (PetscInt i = 0; i < c->nlocal; i++) {
      num[0] += PetscSqr(PetscRealPart(a[i] - b[i]));
      den[0] += PetscSqr(PetscRealPart(a[i]));
    }
    PetscCall(VecRestoreArrayRead(ucFull, &a));
    PetscCall(VecRestoreArrayRead(c->uc, &b));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, num, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, den, 1, MPIU_REAL, MPI_SUM, rom->comm));
  PetscCall(BoltLoadSetProbe(loads, q, &pf));
  PetscCall(op->ops.probe(op, qr, &pr));
  *err = PetscMax(PetscSqrtReal(num[0] / den[0]), PetscAbsReal(pr - pf) / PetscAbsReal(pf));
  PetscCall(PetscPrintf(rom->comm, "ROM check at s0 = %g rad/s, tied joint: relative error %.3e at the contact DOFs, %.3e at the probe\n", (double)s0, (double)PetscSqrtReal(num[0] / den[0]), (double)(PetscAbsReal(pr - pf) / PetscAbsReal(pf))));
  PetscCall(VecDestroy(&ucFull));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&qr));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(KSPDestroy(&kspr));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&Ar));
  PetscCall(MatDestroy(&C));
  PetscCall(BoltContactStateDestroy(&sFull));
  PetscFunctionReturn(0);
}
