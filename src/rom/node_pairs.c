/* Node pairs of the contact set as inputs of the reduction: the pairs of a set of points, the
   unit force pair on one of them (along a direction or a component), combinations of them, and
   the patterns of a training run's change at them (SVD of the snapshots' relative motion). */
#include "private/rom.h"
#include <petscblaslapack.h>
#include "private/boltrom_krylov.h"
#include "private/boltrom_interface.h"

/* The distinct matched node pairs, over all ranks, as (a dof, b dof) of their x component (-1 on a
   clamped side): every pair of the local elements, or with a mask (4 per element) only those of
   the points it marks. Every rank gets the same list, in the same order. With pointDir (nd unit
   directions per point, 3 components each) also those directions per pair: the sum over the
   pair's points, normalised. */
PetscErrorCode BoltNodePairsDirected(BoltContactSet *c, const PetscBool mask[], PetscInt nd, const PetscReal pointDir[], PetscInt *npairsOut, PetscInt **pairsOut, PetscReal **dirOut)
{
  MPI_Comm    comm = BoltMeshComm(BoltContactSetMesh(c));
  const PetscInt m = 3 * nd;
  PetscInt    nloc = 0, npairs, *pairs, *all, ndir;
  PetscReal  *dirs = NULL, *allDir = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(8 * BoltContactSetElementCount(c) + 2, &pairs));
  if (pointDir) PetscCall(PetscMalloc1(4 * m * BoltContactSetElementCount(c) + 1, &dirs));
  for (PetscInt e = 0; e < BoltContactSetElementCount(c); e++)
    for (PetscInt a = 0; a < 4; a++) {
      if (mask && !mask[4 * e + a]) continue;
      pairs[2 * nloc]     = BoltContactSetElementDofs(c, e)[3 * a];
      pairs[2 * nloc + 1] = BoltContactSetElementDofs(c, e)[12 + 3 * a];
      if (pointDir)
        for (PetscInt d = 0; d < m; d++) dirs[m * nloc + d] = pointDir[m * (4 * e + a) + d];
      nloc++;
    }
  PetscCall(BoltGatherAll(comm, MPIU_INT, pairs, 2 * nloc, &all, NULL, &npairs, NULL));
  npairs /= 2;
  if (pointDir) {
    PetscCall(BoltGatherAll(comm, MPIU_REAL, dirs, m * nloc, &allDir, NULL, &ndir, NULL));
    PetscCall(PetscFree(dirs));
    PetscCall(PetscMalloc1(m * npairs + 1, &dirs));
  }
  /* unique by the pair (a, b): sort on a key (a and b are both global DOFs, or -1 if clamped);
     the global list can be longer than this rank's */
  PetscCall(PetscFree(pairs));
  PetscCall(PetscMalloc1(2 * npairs + 2, &pairs));
  {
    PetscInt *key, *perm, n = 0;
    PetscCall(PetscMalloc2(npairs + 1, &key, npairs + 1, &perm));
    for (PetscInt i = 0; i < npairs; i++) {
      key[i]  = all[2 * i] >= 0 ? all[2 * i] : -1 - all[2 * i + 1];
      perm[i] = i;
    }
    PetscCall(PetscSortIntWithPermutation(npairs, key, perm));
    for (PetscInt i = 0; i < npairs; i++) {
      PetscInt k = perm[i];
      if (i > 0 && key[perm[i - 1]] == key[k]) { /* the same pair seen from another element */
        if (dirs)
          for (PetscInt d = 0; d < m; d++) dirs[m * (n - 1) + d] += allDir[m * k + d];
        continue;
      }
      pairs[2 * n]     = all[2 * k];
      pairs[2 * n + 1] = all[2 * k + 1];
      if (dirs)
        for (PetscInt d = 0; d < m; d++) dirs[m * n + d] = allDir[m * k + d];
      n++;
    }
    npairs = n;
    PetscCall(PetscFree2(key, perm));
  }
  for (PetscInt i = 0; dirs && i < nd * npairs; i++) {
    PetscReal *v = &dirs[3 * i];
    const PetscReal len = PetscSqrtReal(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (PetscInt d = 0; d < 3; d++) v[d] = len > 0 ? v[d] / len : 0;
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree(allDir));
  *npairsOut = npairs;
  *pairsOut  = pairs;
  if (dirOut) *dirOut = dirs;
  else PetscCall(PetscFree(dirs));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNodePairs(BoltContactSet *c, const PetscBool mask[], PetscInt *npairsOut, PetscInt **pairsOut)
{
  PetscFunctionBeginUser;
  PetscCall(BoltNodePairsDirected(c, mask, 0, NULL, npairsOut, pairsOut, NULL));
  PetscFunctionReturn(0);
}

/* v = sum_i coef_i (dir_i at a_i, -dir_i at b_i): a pattern of force pairs on node pairs, added in
   the order of the pairs (the same bits on any partition); dirs holds stride reals per pair */
PetscErrorCode BoltNodePairsCombination(PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, const PetscReal coef[], Vec v)
{
  PetscInt     rstart, rend;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(v, &rstart, &rend));
  PetscCall(VecGetArray(v, &x));
  for (PetscInt k = 0; k < rend - rstart; k++) x[k] = 0;
  for (PetscInt i = 0; i < npair; i++)
    for (PetscInt d = 0; d < 3; d++) {
      const PetscInt a = pairs[2 * i], b = pairs[2 * i + 1];
      const PetscReal f = coef[i] * dirs[stride * i + d];
      if (f == 0) continue;
      if (a >= 0 && a + d >= rstart && a + d < rend) x[a + d - rstart] += f;
      if (b >= 0 && b + d >= rstart && b + d < rend) x[b + d - rstart] -= f;
    }
  PetscCall(VecRestoreArray(v, &x));
  PetscFunctionReturn(0);
}

/* v = dir_a - dir_b: a unit force pair along dir on node pair (a, b) (x-component DOFs, -1 if clamped) */
PetscErrorCode BoltNodePairVectorAlong(PetscInt a, PetscInt b, const PetscReal dir[3], Vec v)
{
  const PetscInt  pair[2] = {a, b};
  const PetscReal one     = 1;

  PetscFunctionBeginUser;
  PetscCall(BoltNodePairsCombination(1, pair, dir, 3, &one, v));
  PetscFunctionReturn(0);
}

/* v = e_a - e_b in direction d of node pair (a, b) (x-component DOFs, -1 if clamped) */
PetscErrorCode BoltNodePairVector(PetscInt a, PetscInt b, PetscInt d, Vec v)
{
  PetscReal e[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  e[d] = 1;
  PetscCall(BoltNodePairVectorAlong(a, b, e, v));
  PetscFunctionReturn(0);
}

/* dir . (x - x0) at the node whose x component is local entry i */
static PetscReal BoltNodeChangeAlong(const PetscReal dir[3], const PetscScalar x[], const PetscScalar x0[], PetscInt i)
{
  return dir[0] * (x[i] - x0[i]) + dir[1] * (x[i + 1] - x0[i + 1]) + dir[2] * (x[i + 2] - x0[i + 2]);
}

/* The leading patterns of a training run at some node pairs: R(i, j) = dir_i . (u_a - u_b) in
   snapshot j + 1 less the preloaded snapshot 0, each column scaled to unit norm, and R's leading
   left singular vectors (LAPACK), at most kmax, none below 1e-8 of the largest. Each side of a
   pair is summed over the ranks apart (one rank owns it: the sums are exact), so every rank holds
   the same R and patterns. */
PetscErrorCode BoltNodePairPatterns(MPI_Comm comm, PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, PetscInt nsnap, Vec snap[], PetscInt kmax, PetscInt *kout, PetscReal **patterns)
{
  const PetscInt ns = nsnap - 1;
  PetscInt       rstart, rend, k = 0;
  PetscReal     *Ra, *Rb, *sv, *U, *work, wq, dummy;
  PetscBLASInt   bm, bn, lwork = -1, info, one = 1;
  const PetscScalar *x0;

  PetscFunctionBeginUser;
  *kout     = 0;
  *patterns = NULL;
  if (npair == 0 || ns <= 0 || kmax <= 0) PetscFunctionReturn(0);
  PetscCall(PetscCalloc2(npair * ns, &Ra, npair * ns, &Rb));
  PetscCall(VecGetOwnershipRange(snap[0], &rstart, &rend));
  PetscCall(VecGetArrayRead(snap[0], &x0));
  for (PetscInt j = 0; j < ns; j++) {
    const PetscScalar *x;
    PetscCall(VecGetArrayRead(snap[j + 1], &x));
    for (PetscInt i = 0; i < npair; i++) {
      const PetscInt   a = pairs[2 * i], b = pairs[2 * i + 1];
      const PetscReal *dir = &dirs[stride * i];
      if (a >= rstart && a < rend) Ra[i + npair * j] = BoltNodeChangeAlong(dir, x, x0, a - rstart);
      if (b >= rstart && b < rend) Rb[i + npair * j] = BoltNodeChangeAlong(dir, x, x0, b - rstart);
    }
    PetscCall(VecRestoreArrayRead(snap[j + 1], &x));
  }
  PetscCall(VecRestoreArrayRead(snap[0], &x0));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Ra, npair * ns, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, Rb, npair * ns, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt l = 0; l < npair * ns; l++) Ra[l] -= Rb[l];
  /* every snapshot's pattern at unit norm: the small loads' creep shapes the patterns as much as
     the large loads' slip (unscaled, the leading patterns were the large cycles', and a ROM with
     72 of them was 25 - 28 % over in the creep bursts at 10 and 30 N; scaled, 80 kept it within
     5.4 %: docs/decisions.md, -rom_cone_modes) */
  for (PetscInt j = 0; j < ns; j++) {
    PetscReal nrm = 0;
    for (PetscInt i = 0; i < npair; i++) nrm += Ra[i + npair * j] * Ra[i + npair * j];
    nrm = PetscSqrtReal(nrm);
    for (PetscInt i = 0; nrm > 0 && i < npair; i++) Ra[i + npair * j] /= nrm;
  }
  PetscCall(PetscBLASIntCast(npair, &bm));
  PetscCall(PetscBLASIntCast(ns, &bn));
  PetscCall(PetscMalloc2(PetscMin(npair, ns), &sv, npair * PetscMin(npair, ns), &U));
  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("S", "N", &bm, &bn, Ra, &bm, sv, U, &bm, &dummy, &one, &wq, &lwork, &info));
  PetscCall(PetscBLASIntCast((PetscInt)wq, &lwork));
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("S", "N", &bm, &bn, Ra, &bm, sv, U, &bm, &dummy, &one, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK gesvd failed on the node pairs' snapshot patterns (info %d)", (int)info);
  while (k < PetscMin(kmax, PetscMin(npair, ns)) && sv[k] > 1e-8 * sv[0]) k++;
  PetscCall(PetscPrintf(comm, "ROM: %" PetscInt_FMT " node pairs in %" PetscInt_FMT " snapshots: %" PetscInt_FMT " patterns kept, the last at %.1e of the largest singular value, the next at %.1e\n", npair, ns, k, k > 0 ? (double)(sv[k - 1] / sv[0]) : 0.0, k < PetscMin(npair, ns) ? (double)(sv[k] / sv[0]) : 0.0));
  PetscCall(PetscMalloc1(npair * k + 1, patterns));
  PetscCall(PetscArraycpy(*patterns, U, npair * k));
  *kout = k;
  PetscCall(PetscFree(work));
  PetscCall(PetscFree2(sv, U));
  PetscCall(PetscFree2(Ra, Rb));
  PetscFunctionReturn(0);
}
