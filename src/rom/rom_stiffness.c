/* The reduced contact stiffness K_cr = sum_e D_e' K_e D_e, updated for the elements whose
   active points changed; under the nodal quadrature one product over the gathered node pairs,
   by its upper triangle in blocks shared among the ranks. */
#include "private/rom.h"
#include <petscblaslapack.h>

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
      r[1] = (PetscReal)(4 * BoltContactSetElementKey(c, e) + a);
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

PetscErrorCode ROMContactStiffness(BoltOperator *op, Mat *Kc)
{
  BoltROM          *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactSet   *c   = rom->contact;
  BoltContactState *s   = BoltOperatorState(op);
  PetscBool        *stale = BoltContactStateDirty(s); /* elements whose block changed */
  const PetscInt  n   = rom->n;
  PetscInt        ndirty = 0, *dirty = rom->dirtyElems;
  PetscReal       bound = 0, *delta = rom->dMe, *T = rom->work2, *dK = rom->dK, Knew[576];

  PetscFunctionBeginUser;
  /* the same state as at the last update: nothing is due (and no rank needs to ask the others) */
  if (rom->KcrValid && rom->KcrVersion == BoltContactStateVersion(s)) {
    *Kc = rom->Kcr;
    PetscFunctionReturn(0);
  }
  /* K_e = [M -M; -M M] (B = [-N, N]), so V_e' K_e V_e = D_e' M D_e with D_e = V_b - V_a, the
     relative displacements of the node pairs. Working with D_e spares the directions that open
     no gap the penalty's round-off (through K_e it would be about eps_N |V|^2 u, large under a
     near-hard penalty against the joint's soft stiffness). First the change of M of every
     element whose points changed, and a bound of its reduced part for the exact sum */
  for (PetscInt e = 0, ne = BoltContactSetElementCount(c); e < ne; e++) {
    PetscReal *d = &delta[144 * ndirty], size = 0;
    if (!stale[e]) continue;
    PetscCall(BoltContactStateElementStiffness(s, e, Knew));
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) {
        d[12 * a + b]                 = Knew[24 * a + b] - rom->Ke[144 * e + 12 * a + b];
        rom->Ke[144 * e + 12 * a + b] = Knew[24 * a + b];
        size += PetscAbsReal(d[12 * a + b]);
      }
    stale[e] = PETSC_FALSE;
    BoltROMUpdateSummed(rom->update, rom, e);
    bound       = PetscMax(bound, PetscSqr(rom->DeMax[e]) * size);
    dirty[ndirty++] = e;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bound, 1, MPIU_REAL, MPI_MAX, rom->comm));
  if (bound > 0 && BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL) PetscCall(ROMContactStiffnessNodePairs(rom, ndirty, dirty, delta));
  else if (bound > 0) {
    /* K_cr += sum_e D_e' (M_new - M_old) D_e: per element by BLAS (the same call on the same data
       on any partition), summed exactly over its upper triangle */
    PetscBLASInt bn, b12 = 12;
    PetscScalar  one = 1.0, zero = 0.0, *packed = rom->packed;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(BoltExactSumBegin(rom->sum, n * (n + 1) / 2, bound, BoltContactSetPointCountGlobal(c) / 4));
    for (PetscInt i = 0; i < ndirty; i++) {
      PetscScalar *d = &delta[144 * i], *D = &rom->De[12 * n * dirty[i]];
      PetscCallBLAS("BLASgemm", BLASgemm_("N", "N", &b12, &bn, &b12, &one, d, &b12, D, &b12, &zero, T, &b12));
      PetscCallBLAS("BLASgemm", BLASgemm_("T", "N", &bn, &bn, &b12, &one, D, &b12, T, &b12, &zero, dK, &bn));
      for (PetscInt l = 0, k = 0; l < n; l++)
        for (PetscInt j = 0; j <= l; j++) packed[k++] = dK[j + n * l];
      BoltExactSumAdd(rom->sum, packed);
    }
    PetscCall(BoltExactSumEnd(rom->sum, rom->comm, packed));
    PetscCall(ROMAddPackedToKcr(rom, packed));
  }
  rom->KcrVersion = BoltContactStateVersion(s);
  rom->KcrValid   = PETSC_TRUE;
  *Kc             = rom->Kcr;
  PetscFunctionReturn(0);
}
