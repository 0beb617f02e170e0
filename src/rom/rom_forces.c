/* The reduced model's contact forces: u_c = V_c q at the contact DOFs, and F_r = sum_p D_p' F_p
   over the node pairs, each pair summed by one owner rank with an exact sum over ranks, so the
   force has the same bits on any partition. */
#include "private/rom.h"
#include <petscblaslapack.h>

/* u_c = V_c q, a contact DOF with the same bits on any partition. */
PetscErrorCode ROMContactDisplacements(BoltOperator *op, Vec q)
{
  BoltROM           *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactSet    *c   = rom->contact;
  const PetscInt  nloc = BoltContactSetLocalSize(c);
  const PetscScalar *x;
  PetscScalar       *u;
  Vec                uc;

  PetscFunctionBeginUser;
  if (!nloc) PetscFunctionReturn(0);
  PetscCall(BoltContactWorkGetDisplacements(BoltContactStateWork(BoltOperatorState(op)), &uc)); /* this operator's own */
  PetscCall(VecGetArrayRead(q, &x));
  PetscCall(VecGetArray(uc, &u));
  ROMRowsTimes(nloc, rom->n, rom->Vc, nloc, x, u);
  PetscCall(VecRestoreArray(uc, &u));
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscFunctionReturn(0);
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
  for (PetscInt e = 0, ne = BoltContactSetElementCount(c); e < ne; e++) BoltContactElementForces(c, e, lambda, &rom->felem[12 * e]);
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
PetscErrorCode ROMSetUpPairForces(BoltROM *rom, const PetscBool mayChange[])
{
  BoltContactSet *c = rom->contact;
  const PetscInt  ne = BoltContactSetElementCount(c);
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
  PetscCall(PetscMalloc1(24 * ne + 1, &recs));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt *r = &recs[6 * nmine];
      if (BoltContactSetElementDofs(c, e)[3 * a] < 0 && BoltContactSetElementDofs(c, e)[12 + 3 * a] < 0) continue; /* both nodes clamped */
      r[0] = BoltContactSetElementDofs(c, e)[12 + 3 * a];
      r[1] = BoltContactSetElementDofs(c, e)[3 * a];
      r[2] = 4 * BoltContactSetElementKey(c, e) + a;
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
  PetscCall(PetscMalloc2(3 * n * npair + 1, &rom->npRowsAll, 4 * ne + 1, &rom->npOfPoint));
  for (PetscInt i = 0; i < 4 * ne; i++) rom->npOfPoint[i] = -1;
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
  BoltROM       *rom = (BoltROM *)BoltOperatorContext(op);
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
  PetscCall(BoltExactSumBegin(rom->sum, n, rom->fGridBound, rom->npGlobal));
  if (!fresh) PetscCall(BoltExactSumSetPartials(rom->sum, rom->fAcc));
  for (PetscInt k = 0; k < rom->npOwned; k++) {
    const PetscReal *f    = &rom->npF[3 * k];
    PetscReal       *fsum = &rom->npFSum[3 * k], *p = &rom->fParts[2 * n * k];
    if (!fresh && f[0] == fsum[0] && f[1] == fsum[1] && f[2] == fsum[2]) continue;
    ROMPairForceTerm(rom, k, g);
    if (fresh) BoltExactSumAddParts(rom->sum, g, p, p + n);
    else BoltExactSumReplaceParts(rom->sum, g, p, p + n);
    PetscCall(PetscArraycpy(fsum, f, 3));
  }
  PetscCall(BoltExactSumGetPartials(rom->sum, rom->fAcc));
  rom->fPartsValid = PETSC_TRUE;
  PetscCall(VecGetArray(F, &y));
  PetscCall(BoltExactSumEnd(rom->sum, rom->comm, y));
  PetscCall(PetscArraycpy(rom->Fr, y, n));
  PetscCall(VecRestoreArray(F, &y));
  rom->FrVersion = BoltContactStateVersion(BoltOperatorState(op));
  rom->FrValid   = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* F_r = sum_p D_p' F_p over the node pairs of all ranks (F_p the side-b nodal force of the
   Gauss-point tractions at the pair; side a takes -F_p). A pair's term does not depend on the
   partition, and the sum over pairs is exact on fixed grids (BoltExactSum), so F_r has the same
   bits on any number of ranks. The forces of the state's own multipliers are kept while the
   state's version holds: under the penalty law they are the same every step. */
PetscErrorCode ROMContactForces(BoltOperator *op, const PetscReal lambda[], Vec F)
{
  BoltROM       *rom = (BoltROM *)BoltOperatorContext(op);
  const PetscInt n   = rom->n;
  /* the state's multipliers, with or without its anchors (a rank without anchors hands lambda
     itself): a decision every rank takes alike, as the cache skips reductions */
  const PetscBool own = (PetscBool)(lambda == BoltContactStateLambda(BoltOperatorState(op)) || lambda == BoltContactStateLambdaForce(BoltOperatorState(op)));
  PetscReal       bound, *g = rom->work;
  PetscScalar    *y;

  PetscFunctionBeginUser;
  if (own && rom->FrValid && rom->FrVersion == BoltContactStateVersion(BoltOperatorState(op))) {
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
  PetscCall(BoltExactSumBegin(rom->sum, n, bound, rom->npGlobal));
  for (PetscInt k = 0; k < rom->npOwned && bound > 0; k++) {
    ROMPairForceTerm(rom, k, g);
    BoltExactSumAdd(rom->sum, g);
  }
  PetscCall(VecGetArray(F, &y));
  PetscCall(BoltExactSumEnd(rom->sum, rom->comm, y));
  if (own) {
    PetscCall(PetscArraycpy(rom->Fr, y, n));
    rom->FrVersion = BoltContactStateVersion(BoltOperatorState(op));
    rom->FrValid   = PETSC_TRUE;
  }
  PetscCall(VecRestoreArray(F, &y));
  PetscFunctionReturn(0);
}
