/* Offline reduction: the input matrix B (contact node pairs, load, preload), the second-order
   Krylov basis of boltrom_krylov.h, and the projection onto it (BoltROM). */
#include "boltrom.h"
#include <petscblaslapack.h>
#include "boltrom_krylov.h"
#include "boltrom_interface.h"

/* The distinct matched node pairs, over all ranks, as (a dof, b dof) of their x component (-1 on a
   clamped side): every pair of the local elements, or with a mask (4 per element) only those of
   the points it marks. Every rank gets the same list, in the same order. With pointDir (nd unit
   directions per point, 3 components each) also those directions per pair: the sum over the
   pair's points, normalised. */
static PetscErrorCode BoltNodePairsDirected(BoltContactSet *c, const PetscBool mask[], PetscInt nd, const PetscReal pointDir[], PetscInt *npairsOut, PetscInt **pairsOut, PetscReal **dirOut)
{
  MPI_Comm    comm = c->mesh->comm;
  const PetscInt m = 3 * nd;
  PetscInt    nloc = 0, npairs, *pairs, *all, ndir;
  PetscReal  *dirs = NULL, *allDir = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(8 * c->nelem + 2, &pairs));
  if (pointDir) PetscCall(PetscMalloc1(4 * m * c->nelem + 1, &dirs));
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt a = 0; a < 4; a++) {
      if (mask && !mask[4 * e + a]) continue;
      pairs[2 * nloc]     = c->elem[e].dofs[3 * a];
      pairs[2 * nloc + 1] = c->elem[e].dofs[12 + 3 * a];
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

static PetscErrorCode BoltNodePairs(BoltContactSet *c, const PetscBool mask[], PetscInt *npairsOut, PetscInt **pairsOut)
{
  PetscFunctionBeginUser;
  PetscCall(BoltNodePairsDirected(c, mask, 0, NULL, npairsOut, pairsOut, NULL));
  PetscFunctionReturn(0);
}

/* v = sum_i coef_i (dir_i at a_i, -dir_i at b_i): a pattern of force pairs on node pairs, added in
   the order of the pairs (the same bits on any partition); dirs holds stride reals per pair */
static PetscErrorCode BoltNodePairsCombination(PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, const PetscReal coef[], Vec v)
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
static PetscErrorCode BoltNodePairVectorAlong(PetscInt a, PetscInt b, const PetscReal dir[3], Vec v)
{
  const PetscInt  pair[2] = {a, b};
  const PetscReal one     = 1;

  PetscFunctionBeginUser;
  PetscCall(BoltNodePairsCombination(1, pair, dir, 3, &one, v));
  PetscFunctionReturn(0);
}

/* v = e_a - e_b in direction d of node pair (a, b) (x-component DOFs, -1 if clamped) */
static PetscErrorCode BoltNodePairVector(PetscInt a, PetscInt b, PetscInt d, Vec v)
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
static PetscErrorCode BoltNodePairPatterns(MPI_Comm comm, PetscInt npair, const PetscInt pairs[], const PetscReal dirs[], PetscInt stride, PetscInt nsnap, Vec snap[], PetscInt kmax, PetscInt *kout, PetscReal **patterns)
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
     5.4 %: docs/reduction.md, "Cone modes") */
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
  PetscCall(PetscPrintf(comm, "ROM: %" PetscInt_FMT " node pairs in %" PetscInt_FMT " snapshots, singular values relative to the largest:", npair, ns));
  for (PetscInt l = 0; l < PetscMin(k + 1, PetscMin(npair, ns)); l++) PetscCall(PetscPrintf(comm, " %.1e", (double)(sv[l] / sv[0])));
  PetscCall(PetscPrintf(comm, " (%" PetscInt_FMT " kept)\n", k));
  PetscCall(PetscMalloc1(npair * k + 1, patterns));
  PetscCall(PetscArraycpy(*patterns, U, npair * k));
  *kout = k;
  PetscCall(PetscFree(work));
  PetscCall(PetscFree2(sv, U));
  PetscCall(PetscFree2(Ra, Rb));
  PetscFunctionReturn(0);
}

/* Columns e_a - e_b for every matched node pair and direction, then the load and the preload. */
static PetscErrorCode BoltInputMatrix(BoltContactSet *c, BoltLoadSet *loads, Vec layout, BV *B, PetscInt *ncols)
{
  PetscInt npairs, *pairs, col = 0;

  PetscFunctionBeginUser;
  PetscCall(BoltNodePairs(c, NULL, &npairs, &pairs));
  *ncols = 3 * npairs + 2;
  PetscCall(BVCreate(c->mesh->comm, B));
  PetscCall(BVSetSizesFromVec(*B, layout, *ncols));
  PetscCall(BVSetFromOptions(*B));
  for (PetscInt i = 0; i < npairs; i++)
    for (PetscInt d = 0; d < 3; d++) {
      Vec v;
      PetscCall(BVGetColumn(*B, col, &v));
      PetscCall(BoltNodePairVector(pairs[2 * i], pairs[2 * i + 1], d, v));
      PetscCall(BVRestoreColumn(*B, col, &v));
      col++;
    }
  PetscCall(BVInsertVec(*B, col++, loads->loadUnit));
  PetscCall(BVInsertVec(*B, col++, loads->preload));
  PetscCall(PetscFree(pairs));
  PetscFunctionReturn(0);
}

/* Rows of V at this rank's contact DOFs (through the contact scatter) and at the probe. */
static PetscErrorCode BoltROMExtractRows(BoltROM *rom, BV V, BoltLoadSet *loads)
{
  BoltContactSet *c = rom->contact;
  Vec             e;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(c->nlocal * rom->n + 1, &rom->Vc));
  for (PetscInt j = 0; j < rom->n; j++) {
    Vec                v;
    const PetscScalar *u;
    PetscCall(BVGetColumn(V, j, &v));
    PetscCall(BoltContactSetScatter(c, v));
    PetscCall(BVRestoreColumn(V, j, &v));
    PetscCall(VecGetArrayRead(c->uc, &u));
    for (PetscInt i = 0; i < c->nlocal; i++) rom->Vc[i + c->nlocal * j] = u[i];
    PetscCall(VecRestoreArrayRead(c->uc, &u));
  }
  PetscCall(VecDuplicate(loads->load, &e));
  PetscCall(VecZeroEntries(e));
  if (loads->probeDof >= 0) PetscCall(VecSetValue(e, loads->probeDof, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(e));
  PetscCall(VecAssemblyEnd(e));
  PetscCall(PetscMalloc1(rom->n + 1, &rom->Vprobe));
  {
    PetscScalar *d;
    PetscCall(PetscMalloc1(rom->n + 1, &d));
    PetscCall(BVDotVec(V, e, d));
    for (PetscInt j = 0; j < rom->n; j++) rom->Vprobe[j] = PetscRealPart(d[j]);
    PetscCall(PetscFree(d));
  }
  PetscCall(VecDestroy(&e));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltProject(BV V, Mat A, Mat *Ar)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &n));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, Ar));
  PetscCall(BVMatProject(V, A, V, *Ar));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltProjectVec(BV V, Vec f, Vec *fr)
{
  PetscInt     n;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &n));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, fr));
  PetscCall(VecGetArray(*fr, &a));
  PetscCall(BVDotVec(V, f, a));
  PetscCall(VecRestoreArray(*fr, &a));
  PetscFunctionReturn(0);
}

/* Static Krylov vectors of the joint in its current contact state: out[k] = q(base + f_k) - qBase,
   with f_k = M out[k-1] (f_0 = M w0) scaled to the norm nforce, each solved by the dual loop from
   the state left by the one before (keepActiveSet, if set, holds the active set). work is
   overwritten. */
static PetscErrorCode BoltStaticKrylov(BoltDual *dual, Mat M, Vec base, Vec qBase, Vec w0, PetscReal nforce, PetscInt n, const char what[], Vec work, Vec rhs, Vec q, Vec out[])
{
  BoltOperator *op = dual->op;
  PetscInt      nout, nin;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; k++) {
    PetscReal nf;
    PetscCall(MatMult(M, k ? out[k - 1] : w0, work));
    PetscCall(VecNorm(work, NORM_2, &nf));
    PetscCheck(nf > 0, op->comm, PETSC_ERR_NOT_CONVERGED, "%s Krylov vector %" PetscInt_FMT " is zero", what, k + 1);
    PetscCall(VecScale(work, (nforce > 0 ? nforce : 1.0) / nf));
    PetscCall(VecCopy(base, rhs));
    PetscCall(VecAXPY(rhs, 1.0, work));
    PetscCall(BoltDualSolveStatic(dual, rhs, q, 0, &nout, &nin));
    PetscCall(VecDuplicate(q, &out[k]));
    PetscCall(VecWAXPY(out[k], -1.0, qBase, q));
    PetscCall(PetscPrintf(op->comm, "ROM: %s Krylov vector %" PetscInt_FMT ": %" PetscInt_FMT " outer / %" PetscInt_FMT " inner iterations, %" PetscInt_FMT " points closed\n", what, k + 1, nout, nin, op->state->nactive));
  }
  PetscFunctionReturn(0);
}

/* How far point gp's traction t is along its friction cone: |t_T| / (mu |t_N|) (infinite without
   pressure, zero without tangential traction); with tangent, also the unit direction of t_T. */
static PetscReal BoltConeFraction(const BoltContactSet *c, PetscInt gp, const PetscReal t[3], PetscReal tangent[3])
{
  const PetscReal *n  = &c->gpNormal[3 * gp];
  const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], bound = c->friction[c->elem[gp / 4].pair] * PetscMax(-tn, 0.0);
  PetscReal        tt = 0;

  for (PetscInt k = 0; k < 3; k++) tt += PetscSqr(t[k] - tn * n[k]);
  tt = PetscSqrtReal(tt);
  if (tangent)
    for (PetscInt k = 0; k < 3; k++) tangent[k] = tt > 0 ? (t[k] - tn * n[k]) / tt : 0;
  if (tt == 0) return 0;
  return bound > 0 ? tt / bound : PETSC_INFINITY;
}

/* Friction: marks the closed points whose traction, sticking, is beyond the cone mu |t_N|: they
   slip under that load, and like a pair that opens, a pair that slips needs its own shapes (the
   interface modes are those of the stuck interface: measured on the joint at level 0.5, 5 kN and
   300 N, without them the ROM dissipated half of the FOM's energy). */
static void BoltMarkBeyondCone(BoltContactState *s, PetscBool mark[])
{
  BoltContactSet *c = s->set;

  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++)
    if (s->active[gp] && BoltConeFraction(c, gp, &s->lambda[3 * gp], NULL) > 1) mark[gp] = PETSC_TRUE;
}

/* *v becomes a copy of src of its own (an operator's vector that a calibration may scale). */
static PetscErrorCode BoltVecReplaceByCopy(Vec src, Vec *v)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(v));
  PetscCall(VecDuplicate(src, v));
  PetscCall(VecCopy(src, *v));
  PetscFunctionReturn(0);
}

/* The FOM's static preloaded equilibrium (the FOM run's if it ran, else solved here): q0, the
   multipliers (per newton of preload) and the active set, then the static response to the scene's load from that state with the
   contact closed by the augmented Lagrangian. The interface-reduced ROM cannot close its gaps
   (fewer DOFs than constraints), so under the penalty law alone it penetrates by micrometres
   under the clamp and starts from a tilted state; with q0 in its basis and the FOM's multipliers
   frozen it starts exactly where the FOM does, and the load response gives it one gap-free
   shape, which lets a stiffer penalty carry the increments without locking. */
static PetscErrorCode BoltROMPreloadSolve(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, PetscInt nClosed, PetscReal staticPenaltyScale, PetscBool keepActive, PetscReal openingScale, PetscInt nOpenKrylov, const BoltPreloadState *shared, PetscInt nsnap, Vec snap[], PetscInt *nextra, Vec **extrap, Vec *preload)
{
  BoltOperator     *op;
  BoltContactState *s;
  BoltDual         *dual;
  Vec               q, rhs;
  PetscReal         F = loads->preloadForce, outer, inner;
  PetscInt          nout, nin, npairs = 0, *pairs = NULL;
  PetscBool        *changed = NULL;
  Vec              *extra, *openK = NULL;
  PetscInt          nConePairs = 0, *conePairs = NULL;
  PetscReal        *coneDirs = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 + nClosed, &extra));
  PetscCall(BoltFOMCreate(asmb, c, loads, PETSC_FALSE, &op)); /* static solves only: no damping */
  s = op->state;
  /* the calibration scales the preload vector and the load response may scale the load: work
     on copies, the scene's stay as they are */
  PetscCall(BoltVecReplaceByCopy(loads->preload, &op->preload));
  PetscCall(BoltVecReplaceByCopy(loads->load, &op->load));
  PetscCall(BoltDualCreate(op, &dual));
  PetscCall(BoltDualSetFromOptions(dual));
  PetscCall(BoltDualSetUp(dual));
  PetscCall(VecDuplicate(op->preload, &q));
  PetscCall(VecDuplicate(op->preload, &rhs));
  if (shared) { /* the FOM of this run solved it */
    PetscCall(BoltPreloadStateApply(shared, op, q));
    outer = shared->outer;
    inner = shared->inner;
  } else {
    /* as the FOM's time integrator would solve it (newmark.c): the same two scene options, on an
       operator of its own whose state is then handed over as the FOM's would be (a state that
       went through the solve keeps the friction's working data, and the shapes below then saw
       another joint: 53 slipping node pairs marked instead of 147 on a 100 N sine along x) */
    PetscBool         calibrate = PETSC_TRUE, withLoad = PETSC_FALSE;
    BoltOperator     *fom;
    BoltDual         *fomDual;
    BoltPreloadState *st;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-preload_calibrate", &calibrate, NULL));
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-static_contact_load", &withLoad, NULL));
    PetscCall(BoltFOMCreate(asmb, c, loads, PETSC_FALSE, &fom));
    PetscCall(BoltVecReplaceByCopy(op->preload, &fom->preload));
    PetscCall(BoltDualCreate(fom, &fomDual));
    PetscCall(BoltDualSetFromOptions(fomDual));
    PetscCall(BoltDualSetUp(fomDual));
    PetscCall(VecCopy(fom->preload, rhs));
    if (withLoad) PetscCall(VecAXPY(rhs, 1.0, op->load));
    PetscCall(BoltDualSolveStatic(fomDual, rhs, q, calibrate && !withLoad ? F : 0, &nout, &nin));
    outer = nout;
    inner = nin;
    PetscCall(BoltPreloadStateCreate(fom, q, outer, inner, &st));
    PetscCall(BoltPreloadStateApply(st, op, q));
    PetscCall(BoltPreloadStateDestroy(&st));
    PetscCall(BoltDualDestroy(&fomDual));
    PetscCall(BoltOperatorDestroy(&fom));
  }
  /* The preloaded state above is the FOM's, with its slip under friction. The basis's static
     shapes from here on are solved with closed pairs sticking (elastically): a load beyond the
     friction limit has no static equilibrium, and the shapes need none (friction acts online) */
  s->stickOnly = PETSC_TRUE;
  PetscCall(VecDuplicate(q, &extra[0]));
  PetscCall(VecCopy(q, extra[0]));
  PetscCall(VecDuplicate(op->preload, preload));
  PetscCall(VecCopy(op->preload, *preload));
  PetscCall(PetscMalloc4(12 * c->nelem + 1, &rom->lambda0, 12 * c->nelem + 1, &rom->gap0, 4 * c->nelem + 1, &rom->active0, 4 * c->nelem + 1, &rom->released0));
  PetscCall(BoltContactSetScatter(c, extra[0]));
  PetscCall(BoltContactStateGaps(s));
  for (PetscInt k = 0; k < 12 * c->nelem; k++) {
    rom->lambda0[k] = s->lambda[k] / F;
    rom->gap0[k]    = (s->gap[k] + s->anchor[k]) / F; /* raw: the ROM's frozen multipliers hold any anchor */
  }
  PetscCall(PetscArraycpy(rom->active0, s->active, 4 * c->nelem));
  PetscCall(PetscArraycpy(rom->released0, s->released, 4 * c->nelem));
  /* The solves below end with the active gaps closed, and the multipliers that close them do not
     depend on the penalty, nor does the active-set test (multipliers against the band). A stiffer
     penalty clusters the multiplier CG's operator B (K + eps B'B)^-1 B' near 1/eps, so the CG
     needs far fewer iterations on fine meshes. The preload itself
     stays the FOM's; this operator's state is its own, so the FOM's penalties are not touched. */
  PetscCall(BoltContactStateSetPenaltyScale(s, staticPenaltyScale, 1.0)); /* the band as it is */
  PetscCall(PetscPrintf(rom->comm, "ROM: the FOM's preloaded state (%s): %g outer / %g inner iterations, %" PetscInt_FMT " of %" PetscInt_FMT " points closed", shared ? "the FOM run's" : "solved offline", (double)outer, (double)inner, s->nactive, c->ngpGlobal));
  /* the load on top, from the preloaded state (multipliers warm, active set free to change).
     The contact loop's tolerance is relative to the preload's multipliers, so a load below
     1e-3 of the preload's norm is raised to that (its response then rises above the loop's
     residual; with the joint closed the response is linear in the load, and the scale is lost
     in the orthonormalisation anyway) */
  PetscReal nload, npre, raise;
  PetscCall(VecNorm(op->load, NORM_2, &nload));
  PetscCall(VecNorm(op->preload, NORM_2, &npre));
  raise = nload > 0 ? PetscMax(1.0, 1e-3 * npre / nload) : 1.0;
  PetscCall(VecScale(op->load, raise));
  PetscCall(VecCopy(op->preload, rhs));
  PetscCall(VecAXPY(rhs, 1.0, op->load));
  PetscCall(BoltDualSolveStatic(dual, rhs, q, 0, &nout, &nin));
  PetscCall(VecDuplicate(q, &extra[1]));
  PetscCall(VecWAXPY(extra[1], -1.0, extra[0], q));
  PetscCall(VecScale(extra[1], 1.0 / raise));
  PetscCall(PetscPrintf(rom->comm, "; load response (load x %g) %g inner iterations\n", (double)raise, (double)nin));
  /* Opening shapes: the node pairs whose state the load changes statically at -openingScale or
     +openingScale x its amplitude (a step load's response swings up to twice its static one, a
     sine load's to either side); under friction also those it makes slip. The positive one
     last: its state starts the opened-joint Krylov vectors. */
  if (openingScale > 0) {
    PetscCall(PetscCalloc1(4 * c->nelem + 1, &changed));
    /* Friction: the pairs beyond the cone, sticking, under -/+ slipScale x the load. Sticking, the
       joint keeps the load where the slip zone would shed it onto its neighbours, so the zone
       beyond the cone at the swing's own size is narrower than the zone that slips (on a 300 N
       sine along x at level 0.5, shapes at twice the load left the ROM 9.5 % short of the FOM's
       dissipation per cycle; at four times, 0.3 %) */
    if (s->law.friction && rom->slipScale > 0 && rom->slipScale != openingScale)
      for (PetscInt sign = -1; sign <= 1; sign += 2) {
        PetscCall(VecCopy(op->preload, rhs));
        PetscCall(VecAXPY(rhs, sign * rom->slipScale / raise, op->load));
        PetscCall(BoltDualSolveStatic(dual, rhs, q, 0, &nout, &nin));
        BoltMarkBeyondCone(s, changed);
      }
    for (PetscInt sign = -1; sign <= 1; sign += 2) {
      PetscCall(VecCopy(op->preload, rhs));
      PetscCall(VecAXPY(rhs, sign * openingScale / raise, op->load));
      PetscCall(BoltDualSolveStatic(dual, rhs, q, 0, &nout, &nin));
      for (PetscInt k = 0; k < 4 * c->nelem; k++) changed[k] = (PetscBool)(changed[k] || s->active[k] != rom->active0[k]);
      if (s->law.friction) BoltMarkBeyondCone(s, changed);
    }
    PetscCall(BoltNodePairs(c, changed, &npairs, &pairs));
    PetscCall(PetscFree(rom->marked));
    rom->marked = changed; /* kept: online the other points may hold their preloaded state */
    rom->nOpeningPairs = npairs;
    if (rom->slipScale > 0) PetscCall(PetscPrintf(rom->comm, "ROM: -/+ %g x the load change, or -/+ %g x the load makes slip, %" PetscInt_FMT " node pairs (%" PetscInt_FMT " points closed under +)\n", (double)openingScale, (double)rom->slipScale, npairs, s->nactive));
    else PetscCall(PetscPrintf(rom->comm, "ROM: -/+ %g x the load change %" PetscInt_FMT " node pairs (%" PetscInt_FMT " points closed under +)\n", (double)openingScale, npairs, s->nactive));
    if (nOpenKrylov > 0 && npairs > 0) { /* the opened joint's low-frequency shapes, its active set kept (none when no pair changes: it is the preloaded joint) */
      Vec base, q2, work;
      PetscCall(VecDuplicate(q, &base));
      PetscCall(VecDuplicate(q, &q2));
      PetscCall(VecDuplicate(q, &work));
      PetscCall(VecCopy(rhs, base)); /* the + solve's right-hand side and state */
      PetscCall(VecCopy(q, q2));
      PetscCall(PetscMalloc1(nOpenKrylov, &openK));
      dual->keepActiveSet = PETSC_TRUE;
      PetscCall(BoltStaticKrylov(dual, asmb->M, base, q2, extra[1], 1e-3 * npre, nOpenKrylov, "opened-joint", work, rhs, q, openK));
      dual->keepActiveSet = PETSC_FALSE;
      PetscCall(VecDestroy(&base));
      PetscCall(VecDestroy(&q2));
      PetscCall(VecDestroy(&work));
    }
  }
  /* Friction: the pairs the preloaded state leaves on (or near) the cone. Under a small load
     their creep is all the joint dissipates, in bursts that die out cycle by cycle. The interface
     modes are the stuck interface's, and snapshot modes mix every pair's slip; these pairs get
     shapes of their own, the responses to a unit force pair along their normal (the pressure they
     shed and take moves their cone: on the joint at level 0.5, a ROM that was 16 - 52 % over in
     the last bursts at 10 - 30 N came within 2.5 % with these) and along their tangential traction
     (with both, within 1.5 %; with the traction alone no nearer) */
  if (rom->coneShapes > 0 && s->law.friction) {
    PetscInt   ncone = 0, nconeGlobal;
    PetscBool *cone;
    PetscReal *dir; /* per point: the tangential traction's direction, then the normal */
    PetscCall(PetscCalloc1(4 * c->nelem + 1, &cone));
    PetscCall(PetscCalloc1(24 * c->nelem + 1, &dir));
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      PetscReal fraction;
      if (!rom->active0[gp]) continue;
      fraction = BoltConeFraction(c, gp, &rom->lambda0[3 * gp], &dir[6 * gp]);
      if (fraction > 0 && (rom->released0[gp] || fraction >= rom->coneShapes)) {
        ncone++;
        cone[gp] = PETSC_TRUE;
        for (PetscInt k = 0; k < 3; k++) dir[6 * gp + 3 + k] = c->gpNormal[3 * gp + k];
      } else
        for (PetscInt k = 0; k < 3; k++) dir[6 * gp + k] = 0;
    }
    PetscCall(MPIU_Allreduce(&ncone, &nconeGlobal, 1, MPIU_INT, MPI_SUM, rom->comm));
    PetscCall(BoltNodePairsDirected(c, cone, 2, dir, &nConePairs, &conePairs, &coneDirs));
    PetscCall(PetscFree(dir));
    /* marked too: these points are free online whatever -rom_hold_unmarked says */
    if (!rom->marked) {
      rom->marked = cone;
      cone        = NULL;
    } else
      for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) rom->marked[gp] = (PetscBool)(rom->marked[gp] || cone[gp]);
    PetscCall(PetscFree(cone));
    rom->nConePairs = nConePairs;
    PetscCall(PetscPrintf(rom->comm, "ROM: %" PetscInt_FMT " points at %g of the cone or beyond in the preloaded state, on %" PetscInt_FMT " node pairs\n", nconeGlobal, (double)rom->coneShapes, nConePairs));
  }
  /* closed-contact Krylov vectors: w_k = static response, from the preloaded state, to M w_(k-1),
     so the basis holds the closed joint's low-frequency shapes too. Forced at 1e-3 of the
     preload's norm: small enough that the joint stays closed, large enough to rise above the
     contact loop's residual (the shapes are those of the closed joint; their scale is lost in
     the orthonormalisation). By default they keep the preloaded active set: the forcing, spread
     over the whole volume, opens points at the rim on fine meshes, and the basis of that opened
     joint is less accurate than the one with the set kept (docs/reduction.md) */
  if (nClosed > 0) {
    PetscReal nforce = 1e-3 * npre;
    PetscCall(PetscPrintf(rom->comm, "ROM: closed-contact Krylov forcing of norm %g (load %g, preload %g)\n", (double)nforce, (double)nload, (double)npre));
    if (keepActive) {
      PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0));
      dual->keepActiveSet = PETSC_TRUE;
    }
    /* op->load, this solve's own copy, is the forcing of each vector in turn */
    PetscCall(BoltStaticKrylov(dual, asmb->M, op->preload, extra[0], extra[1], nforce, nClosed, "closed-contact", op->load, rhs, q, &extra[2]));
  }
  *nextra = 2 + nClosed;
  /* Each opening shape is the preloaded joint's static response to a unit force pair on one of
     those node pairs, in one direction. A node pair's penalty is a rank-3 term on its relative
     displacement, so by Sherman-Morrison the joint's response with that pair open, to any forces
     on it, lies in the span of its three shapes, and together they span the response of the
     joint with any subset of those pairs open (Woodbury); the interface modes do not. */
  if (npairs + nConePairs > 0) {
    Vec     *all;
    PetscInt ncone = 0;
    PetscCall(PetscMalloc1(*nextra + 3 * npairs + 2 * nConePairs + nOpenKrylov, &all));
    PetscCall(PetscArraycpy(all, extra, *nextra));
    PetscCall(PetscFree(extra));
    extra = all;
    if (!(keepActive && nClosed > 0)) { /* else the closed-contact vectors' last solve factored K + K_c of the preloaded set */
      PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0));
      dual->keepActiveSet = PETSC_TRUE;
      PetscCall(BoltDualSolveStatic(dual, op->preload, q, 0, &nout, &nin));
    }
    for (PetscInt i = 0; i < npairs; i++)
      for (PetscInt d = 0; d < 3; d++) {
        PetscCall(BoltNodePairVector(pairs[2 * i], pairs[2 * i + 1], d, rhs));
        PetscCall(VecDuplicate(q, &extra[*nextra]));
        PetscCall(KSPSolve(dual->ksp, rhs, extra[*nextra]));
        (*nextra)++;
      }
    if (rom->coneModes > 0) /* compressed: the responses to the training run's patterns at the cone pairs, per direction */
      for (PetscInt j = rom->coneTraction ? 0 : 1; j < 2; j++) {
        PetscInt   k;
        PetscReal *patterns;
        PetscCall(BoltNodePairPatterns(rom->comm, nConePairs, conePairs, coneDirs + 3 * j, 6, nsnap, snap, rom->coneModes, &k, &patterns));
        for (PetscInt l = 0; l < k; l++) {
          PetscCall(BoltNodePairsCombination(nConePairs, conePairs, coneDirs + 3 * j, 6, &patterns[nConePairs * l], rhs));
          PetscCall(VecDuplicate(q, &extra[*nextra]));
          PetscCall(KSPSolve(dual->ksp, rhs, extra[*nextra]));
          (*nextra)++;
          ncone++;
        }
        PetscCall(PetscFree(patterns));
      }
    else
      for (PetscInt i = 0; i < nConePairs; i++)
        for (PetscInt j = rom->coneTraction ? 0 : 1; j < 2; j++) {
          PetscCall(BoltNodePairVectorAlong(conePairs[2 * i], conePairs[2 * i + 1], &coneDirs[6 * i + 3 * j], rhs));
          PetscCall(VecDuplicate(q, &extra[*nextra]));
          PetscCall(KSPSolve(dual->ksp, rhs, extra[*nextra]));
          (*nextra)++;
          ncone++;
        }
    rom->nConeModes = rom->coneModes > 0 ? ncone : 0;
    PetscCall(PetscPrintf(rom->comm, "ROM: %" PetscInt_FMT " opening shapes, %" PetscInt_FMT " cone shapes\n", 3 * npairs, ncone));
    for (PetscInt k = 0; k < nOpenKrylov; k++) extra[(*nextra)++] = openK[k];
    PetscCall(PetscFree(openK));
  }
  PetscCall(PetscFree(pairs));
  PetscCall(PetscFree(conePairs));
  PetscCall(PetscFree(coneDirs));
  *extrap = extra;
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&rhs));
  PetscCall(BoltDualDestroy(&dual));
  PetscCall(BoltOperatorDestroy(&op));
  PetscFunctionReturn(0);
}

/* Appends the static shapes to the basis, orthonormalised against it; dependent ones are
   dropped. The remainders are printed: without interface reduction a shape can lie very close to
   the Krylov vectors' span, and the orthogonalisation then amplifies round-off (separate builds
   on different rank counts differ more than their Krylov vectors do; docs/reduction.md). With
   tol > 0 a shape whose remainder is below tol of its norm is taken for round-off and dropped
   too (the opened-joint Krylov vectors, where the load opens few pairs, lie that close to the
   opening shapes' span). */
static PetscErrorCode BoltBasisAppend(BV V, const char what[], PetscInt nv, Vec v[], PetscReal tol, PetscInt *added)
{
  PetscInt k, j = 0;

  PetscFunctionBeginUser;
  PetscCall(BVGetSizes(V, NULL, NULL, &k));
  PetscCall(BVResize(V, k + nv, PETSC_TRUE));
  if (nv == 0) {
    *added = 0;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), "ROM: %s, remainder after orthogonalisation / norm:", what));
  for (PetscInt i = 0; i < nv; i++) {
    PetscReal nrm, n0;
    PetscBool dep;
    PetscCall(VecNorm(v[i], NORM_2, &n0));
    PetscCall(BVSetActiveColumns(V, 0, k + j + 1));
    PetscCall(BVInsertVec(V, k + j, v[i]));
    PetscCall(BVOrthonormalizeColumn(V, k + j, PETSC_TRUE, &nrm, &dep));
    if (nrm <= tol * n0) dep = PETSC_TRUE;
    PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), " %.2e%s", (double)(n0 > 0 ? nrm / n0 : 0), dep ? " (dropped)" : ""));
    if (!dep) j++;
  }
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), "\n"));
  if (j < nv) PetscCall(BVResize(V, k + j, PETSC_TRUE));
  PetscCall(BVSetActiveColumns(V, 0, k + j));
  *added = j;
  PetscFunctionReturn(0);
}

/* POD modes of the FOM's displacement snapshots of this run: each snapshot's remainder against
   the basis, then the leading left singular vectors of the remainders (by the eigenvectors of
   their Gram matrix, which is small: one column per snapshot), at most nmodes of them and only
   those whose singular value is above tol of the largest. They give the basis what the FOM did
   and the static shapes miss, such as the joint's slip fields under friction. */
static PetscErrorCode BoltSnapshotModes(BV V, PetscInt nsnap, Vec snap[], PetscInt nmodes, PetscReal tol, PetscInt *nout, Vec **modes)
{
  BV            X;
  Mat           G;
  PetscScalar  *g, *w, *work, *coef;
  PetscBLASInt  bn, lwork, info;
  PetscInt      ns = nsnap - 1, k = 0;
  Vec           x;

  PetscFunctionBeginUser;
  *nout  = 0;
  *modes = NULL;
  if (ns <= 0 || nmodes <= 0) PetscFunctionReturn(0);
  PetscCall(BVCreate(PetscObjectComm((PetscObject)V), &X));
  PetscCall(BVSetSizesFromVec(X, snap[0], ns));
  PetscCall(BVSetFromOptions(X));
  for (PetscInt j = 0; j < ns; j++) { /* the motion from the preloaded state, less what V spans */
    PetscCall(BVGetColumn(X, j, &x));
    PetscCall(VecWAXPY(x, -1.0, snap[0], snap[j + 1]));
    PetscCall(BVOrthogonalizeVec(V, x, NULL, NULL, NULL));
    PetscCall(BVOrthogonalizeVec(V, x, NULL, NULL, NULL)); /* twice: the remainders are small */
    PetscCall(BVRestoreColumn(X, j, &x));
  }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, ns, ns, NULL, &G));
  PetscCall(BVDot(X, X, G));
  PetscCall(MatDenseGetArray(G, &g));
  PetscCall(PetscBLASIntCast(ns, &bn));
  lwork = 8 * bn;
  PetscCall(PetscMalloc3(ns, &w, (size_t)lwork, &work, ns, &coef));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, g, &bn, w, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed on the snapshots' Gram matrix (info %d)", (int)info);
  PetscCall(PetscMalloc1(nmodes, modes));
  PetscCall(BVSetActiveColumns(X, 0, ns));
  for (PetscInt i = ns - 1; i >= 0 && k < nmodes; i--) { /* eigenvalues ascend */
    if (!(w[i] > tol * tol * w[ns - 1]) || w[i] <= 0) break;
    for (PetscInt j = 0; j < ns; j++) coef[j] = g[j + (size_t)ns * i] / PetscSqrtReal(w[i]);
    PetscCall(BVCreateVec(X, &(*modes)[k]));
    PetscCall(BVMultVec(X, 1.0, 0.0, (*modes)[k], coef));
    k++;
  }
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), "ROM: %" PetscInt_FMT " snapshots, their remainders' singular values relative to the largest:", ns));
  for (PetscInt i = ns - 1; i >= 0 && i >= ns - k - 1; i--) PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), " %.1e", (double)PetscSqrtReal(PetscMax(w[i], 0) / w[ns - 1])));
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)V), " (%" PetscInt_FMT " kept)\n", k));
  PetscCall(MatDenseRestoreArray(G, &g));
  PetscCall(PetscFree3(w, work, coef));
  PetscCall(MatDestroy(&G));
  PetscCall(BVDestroy(&X));
  *nout = k;
  PetscFunctionReturn(0);
}

/* The ROM's activation band (the tension at which a closed point opens), relative to the FOM's.
   Under the near-hard penalty a reduced gap error of a nanometre is a traction of megapascals:
   at the rim of the preloaded zone the FOM's band lets such errors open points the FOM keeps
   closed. A wider band helps there but not in paper-step (docs/results.md), so 1 stays the default
   for the stick law. Under the strict law the band (1e-10 E) is its FOM's solver tolerance. An
   interface-reduced ROM without opening shapes cannot resolve tractions at single rim pairs that
   finely (its rim pairs then open and close about a hundred times in paper-step at level 1 while
   the FOM's set holds) and judges with the stick law's band, 2e5 times the strict one. With
   opening shapes, or snapshot modes of the FOM's run, it can open the pairs the load opens, and
   keeps the strict band (docs/reduction.md).
   Which applies is known once the basis is. */
static PetscReal BoltROMDefaultBand(BoltReductionOptions *o, BoltContactSet *contact, BoltROM *rom)
{
  if (o->bandScale > 0) return o->bandScale;
  return contact->law.strict && !rom->augment && rom->nOpeningPairs == 0 && rom->nSnapshotModes == 0 ? 2e5 : 1.0;
}

/* Whether the points outside the opening shapes keep their preloaded state online: yes, unless
   told, but not under friction. There a pair the static solves leave sticking may still slip in
   the dynamic response, and the basis gives it some room to (level 0.5, 20 kN and a 300 N step,
   mu 0.1: held, e_L2 1.2e-3 and 5.2 % less dissipation than the FOM; free, 1.6e-4 and 0.7 %; the
   same on two other scenes either way). */
static PetscBool BoltROMDefaultHold(BoltReductionOptions *o, BoltContactSet *contact)
{
  return o->holdUnmarkedSet ? o->holdUnmarked : (PetscBool)!contact->law.friction;
}

PetscErrorCode BoltROMBuild(BoltReductionOptions *o, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads, BoltROM **romp)
{
  BoltROM       *rom;
  BoltKrylov    *kry;
  BoltInterface *ir = NULL;
  BV             B, V;
  Mat            C;
  Vec            preloadCalibrated = NULL; /* the preload layer forces that clamp with -preload_force */
  PetscLogDouble t0, t1, t2, t3;
  PetscBool      staticShapes;
  PetscReal      staticPenaltyScale;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscNew(&rom));
  rom->comm        = o->comm;
  rom->contact     = contact;
  rom->rayleigh[0] = asmb->rayleighAlpha; /* C_r = V' C V (a ROM file holds the same: its fingerprint has them) */
  rom->rayleigh[1] = asmb->rayleighBeta;
  /* With interface reduction the ROM has fewer DOFs than contact constraints: multipliers that
     close every active gap are not unique (their signs, which decide the active set, are
     arbitrary) and closing the gaps exactly locks the reduced interface. The penalty law keeps
     the reduced contact problem well posed, so it is the default there. */
  rom->augment = o->augmentSet ? o->augment : (PetscBool)(contact->augment && o->nCCM + o->nJIM == 0);
  PetscCheck(o->krylov, o->comm, PETSC_ERR_ARG_WRONGSTATE, "BoltROMBuild needs the Krylov options: configure the reduction with BoltReductionSetFromOptions");
  kry = o->krylov;
  PetscCall(BoltROMFingerprint(asmb, contact, loads, kry->order, kry->s0, kry->deflationTol, o->nCCM, o->nJIM, rom->fingerprint, sizeof(rom->fingerprint)));
  /* the preloaded state needs the penalty law (the augmented ROM closes its own gaps) and a preload */
  rom->preloadState = (PetscBool)(o->preloadState && !rom->augment && loads->hasPreload && loads->preloadForce != 0);
  PetscCheck(!(o->preloadStateSet && o->preloadState) || rom->preloadState, o->comm, PETSC_ERR_USER_INPUT, "-rom_preload_state needs a ROM with the penalty law (interface reduction, -rom_contact_augment false) and a nonzero bolt preload");
  /* Against a FOM that closes its gaps the increments want a near-hard penalty: 1e5 E/m (500 x
     the paper's), where the penalty law alone matches the augmented FOM. Without the closed-contact
     Krylov shapes so stiff a penalty locks the reduced interface, and 4e3 E/m (20 x the paper's)
     does best (docs/reduction.md). The scale is relative to the FOM's penalty, whatever its law. */
  rom->penaltyScale = o->penaltyScale > 0 ? o->penaltyScale : (rom->preloadState && contact->augment ? (o->nClosed > 0 ? 1e5 : 4e3) / contact->penaltyFactor : 1.0);
  /* the static shapes enrich the augmented ROM's basis too, where its own multipliers close the gaps */
  staticShapes = (PetscBool)(rom->preloadState || (o->staticShapes && rom->augment && loads->hasPreload && loads->preloadForce != 0));
  rom->nClosed = staticShapes ? o->nClosed : 0;
  /* Opening shapes by default for the interface-reduced ROM under the strict law (the ROM without
     interface reduction has every node pair's force among its inputs; the stick law's scenes are
     the paper's, whose figures stay as they were) */
  /* ... and none by default with snapshot modes, which carry the openings and slips the FOM made */
  rom->openingScale = staticShapes ? (o->openingScaleSet ? o->openingScale : (contact->law.strict && rom->preloadState && o->nSnapshotModes == 0 ? o->openingScale : 0.0)) : 0;
  rom->nOpenKrylov  = rom->openingScale > 0 ? o->nOpenKrylov : 0;
  rom->slipScale    = rom->openingScale > 0 && contact->law.friction ? o->slipScale : 0;
  rom->coneShapes   = staticShapes && rom->preloadState && contact->law.friction ? o->coneShapes : 0;
  rom->coneTraction = o->coneTraction;
  rom->coneModes    = rom->coneShapes > 0 ? o->coneModes : 0;
  staticPenaltyScale = o->staticPenaltyScale > 0 ? o->staticPenaltyScale : PetscMax(1.0, 2e6 / contact->penaltyFactor); /* 2e6 E/m */
  if (staticShapes) {
    char more[64];
    PetscCall(PetscStrlcat(rom->fingerprint, rom->preloadState ? "; preload state" : "; static shapes", sizeof(rom->fingerprint)));
    if (o->nClosed > 0) { /* the active set named either way, so that files built with the set free are rebuilt */
      PetscCall(PetscSNPrintf(more, sizeof(more), "; closed-contact Krylov %" PetscInt_FMT " (%s)", o->nClosed, o->closedKeepActive ? "preloaded set kept" : "set free"));
      PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
    }
    PetscCall(PetscSNPrintf(more, sizeof(more), "; static penalty x %g", (double)staticPenaltyScale));
    PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
    if (rom->openingScale > 0) {
      PetscCall(PetscSNPrintf(more, sizeof(more), "; opening shapes at -/+ %g x the load, %" PetscInt_FMT " opened-joint Krylov", (double)rom->openingScale, rom->nOpenKrylov));
      PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
    }
    if (rom->slipScale > 0) {
      PetscCall(PetscSNPrintf(more, sizeof(more), "; slip shapes at -/+ %g x the load", (double)rom->slipScale));
      PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
    }
    if (rom->coneShapes > 0) {
      PetscCall(PetscSNPrintf(more, sizeof(more), "; cone shapes at %g%s", (double)rom->coneShapes, rom->coneTraction ? "" : " (normal)"));
      if (rom->coneModes > 0) PetscCall(PetscSNPrintf(more + strlen(more), sizeof(more) - strlen(more), ", %" PetscInt_FMT " modes", rom->coneModes));
      PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
    }
  }
  if (o->nSnapshotModes > 0) {
    char more[64];
    PetscCall(PetscSNPrintf(more, sizeof(more), "; snapshot modes %" PetscInt_FMT " above %g", o->nSnapshotModes, (double)o->snapshotTol));
    PetscCall(PetscStrlcat(rom->fingerprint, more, sizeof(rom->fingerprint)));
  }
  if (o->file[0]) {
    PetscBool exists, matched;
    char      why[256];
    PetscCall(PetscTestFile(o->file, 'r', &exists));
    if (exists) {
      BoltROM *loaded = NULL;
      PetscCall(BoltROMLoad(o->file, rom->fingerprint, o, contact, loads, &loaded, &matched, why, sizeof(why)));
      if (matched) {
        PetscCall(PetscTime(&t3));
        loaded->tOffline = t3 - t0;
        loaded->augment  = rom->augment;
        loaded->rayleigh[0] = rom->rayleigh[0];
        loaded->rayleigh[1] = rom->rayleigh[1];
        loaded->penaltyScale = rom->penaltyScale;
        loaded->nClosed      = rom->nClosed;
        loaded->openingScale = rom->openingScale;
        loaded->nOpenKrylov  = rom->nOpenKrylov;
        loaded->slipScale    = rom->slipScale;
        loaded->bandScale    = BoltROMDefaultBand(o, contact, loaded);
        loaded->updateRank   = o->updateRank;
        loaded->holdUnmarked = BoltROMDefaultHold(o, contact);
        loaded->gapsEverywhere = o->gapsEverywhere;
        PetscCall(PetscStrncpy(loaded->fingerprint, rom->fingerprint, sizeof(loaded->fingerprint)));
        PetscCall(PetscPrintf(o->comm, "ROM: reusing %s (dimension %" PetscInt_FMT "): the offline phase is skipped\n", o->file, loaded->n));
        PetscCall(PetscFree(rom));
        *romp = loaded;
        PetscFunctionReturn(0);
      }
      PetscCheck(o->rebuild, o->comm, PETSC_ERR_USER_INPUT, "ROM file %s does not match this scene (%s): remove it, point -rom_file elsewhere, or let it be rebuilt with -rom_rebuild", o->file, why);
      PetscCall(PetscPrintf(o->comm, "ROM file %s does not match this scene (%s): rebuilding it\n", o->file, why));
    }
  }
  /* built here: the snapshot modes, and the cone modes in the static solves, read this run's snapshots */
  PetscCheck(o->nSnapshotModes == 0 || o->nFomSnapshots > 1, o->comm, PETSC_ERR_USER_INPUT, "-rom_snapshot_modes needs the FOM's snapshots of the same run: add -fom true -snapshot_every k");
  PetscCall(BoltAssemblerDamping(asmb, &C));
  rom->nCCM = o->nCCM;
  rom->nJIM = o->nJIM;
  if (o->nCCM + o->nJIM > 0) {
    /* the contact inputs collapse onto the reduced interface: inputs E_I V_IR, load, preload */
    PetscCall(PetscLogEventBegin(boltLog.interfaceReduction, 0, 0, 0, 0));
    PetscCall(BoltInterfaceBuild(contact, asmb->M, C, asmb->K, kry->s0, o->nCCM, o->nJIM, kry->deflationTol, &ir));
    PetscCall(PetscLogEventEnd(boltLog.interfaceReduction, 0, 0, 0, 0));
    PetscCall(BVCreate(o->comm, &B));
    PetscCall(BVSetSizesFromVec(B, loads->load, ir->nIR + 2));
    PetscCall(BVSetFromOptions(B));
    PetscCall(BoltInterfaceInputs(ir, B, 0));
    PetscCall(BVInsertVec(B, ir->nIR, loads->loadUnit));
    PetscCall(BVInsertVec(B, ir->nIR + 1, loads->preload));
    rom->ninputs  = ir->nIR + 2;
    kry->solve    = BoltInterfaceSolve;
    kry->solveCtx = ir;
    rom->nCCM     = ir->rankCCM;
    rom->nJIM     = ir->rankJIM;
  } else PetscCall(BoltInputMatrix(contact, loads, loads->load, &B, &rom->ninputs));
  PetscCall(PetscTime(&t1));
  rom->tInterface = t1 - t0;
  PetscCall(PetscLogEventBegin(boltLog.basis, 0, 0, 0, 0));
  PetscCall(BoltKrylovBuild(kry, asmb->M, C, asmb->K, B, &V));
  PetscCall(PetscLogEventEnd(boltLog.basis, 0, 0, 0, 0));
  PetscCall(BoltInterfaceDestroy(&ir)); /* its factorisations are not needed from here on */
  kry->solve    = NULL;
  kry->solveCtx = NULL;
  PetscCall(BVDestroy(&B));
  /* the preloaded state's static solves factor the FOM: the damping matrix is rebuilt after them
     rather than held through them (at 562k DOFs the two did not fit in 24 GB together) */
  if (staticShapes) PetscCall(MatDestroy(&C));
  PetscCall(BoltMemoryRelease());
  PetscCall(BoltMemoryPrint(o->comm, "the Krylov basis"));
  if (staticShapes) {
    Vec     *extra;
    PetscInt added, nextra;
    PetscCall(PetscLogEventBegin(boltLog.basis, 0, 0, 0, 0));
    PetscCall(BoltROMPreloadSolve(asmb, contact, loads, rom, o->nClosed, staticPenaltyScale, o->closedKeepActive, rom->openingScale, rom->nOpenKrylov, o->fomPreload, o->nFomSnapshots, o->fomSnapshots, &nextra, &extra, &preloadCalibrated));
    PetscCall(BoltMemoryPrint(o->comm, "the preloaded state's static solves"));
    PetscCall(BoltAssemblerDamping(asmb, &C));
    PetscCall(BoltBasisAppend(V, "static shapes", 2 + o->nClosed, extra, 0, &added));
    PetscCall(BoltBasisAppend(V, "opening shapes", nextra - 2 - o->nClosed, extra + 2 + o->nClosed, kry->deflationTol, &added));
    for (PetscInt k = 0; k < nextra; k++) PetscCall(VecDestroy(&extra[k]));
    PetscCall(PetscFree(extra));
    if (!rom->preloadState) { /* shapes only: the augmented ROM solves its own preload */
      PetscCall(PetscFree4(rom->lambda0, rom->gap0, rom->active0, rom->released0));
      PetscCall(VecDestroy(&preloadCalibrated));
    }
    PetscCall(PetscLogEventEnd(boltLog.basis, 0, 0, 0, 0));
  }
  if (o->nSnapshotModes > 0) {
    Vec     *modes;
    PetscInt nmodes, added;
    PetscCall(BoltSnapshotModes(V, o->nFomSnapshots, o->fomSnapshots, o->nSnapshotModes, o->snapshotTol, &nmodes, &modes));
    PetscCall(BoltBasisAppend(V, "snapshot modes", nmodes, modes, kry->deflationTol, &added));
    rom->nSnapshotModes = added;
    for (PetscInt k = 0; k < nmodes; k++) PetscCall(VecDestroy(&modes[k]));
    PetscCall(PetscFree(modes));
  }
  rom->bandScale  = BoltROMDefaultBand(o, contact, rom);
  rom->updateRank = o->updateRank;
  rom->holdUnmarked = BoltROMDefaultHold(o, contact);
  rom->gapsEverywhere = o->gapsEverywhere;
  PetscCall(PetscTime(&t2));
  PetscCall(BVGetSizes(V, NULL, NULL, &rom->n));
  rom->orthogonality = -1;
  if (o->checkOrthogonality) { /* max |V'V - I| */
    Mat G;
    const PetscScalar *g;
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, rom->n, rom->n, NULL, &G));
    PetscCall(BVDot(V, V, G));
    PetscCall(MatDenseGetArrayRead(G, &g));
    rom->orthogonality = 0;
    for (PetscInt i = 0; i < rom->n; i++)
      for (PetscInt j = 0; j < rom->n; j++) rom->orthogonality = PetscMax(rom->orthogonality, PetscAbsScalar(g[i + rom->n * j] - (i == j ? 1.0 : 0.0)));
    PetscCall(MatDenseRestoreArrayRead(G, &g));
    PetscCall(MatDestroy(&G));
  }
  PetscCall(PetscLogEventBegin(boltLog.projection, 0, 0, 0, 0));
  PetscCall(BoltProject(V, asmb->M, &rom->Mr));
  PetscCall(BoltProject(V, C, &rom->Cr));
  PetscCall(BoltProject(V, asmb->K, &rom->Kr));
  PetscCall(BoltProjectVec(V, loads->load, &rom->loadr));
  PetscCall(BoltProjectVec(V, loads->loadUnit, &rom->loadUnitr));
  PetscCall(BoltProjectVec(V, preloadCalibrated ? preloadCalibrated : loads->preload, &rom->preloadr));
  PetscCall(VecDestroy(&preloadCalibrated));
  PetscCall(BoltROMExtractRows(rom, V, loads));
  PetscCall(PetscLogEventEnd(boltLog.projection, 0, 0, 0, 0));
  PetscCall(PetscTime(&t3));
  rom->order = kry->order;
  rom->s0    = kry->s0;
  for (PetscInt k = 0; k < 8; k++) rom->rankPerOrder[k] = kry->rankPerOrder[k];
  rom->tInputs  = ir ? 0 : t1 - t0;
  if (!ir) rom->tInterface = 0;
  rom->tBasis   = t2 - t1;
  rom->tProject = t3 - t2;
  rom->tFactor  = kry->tFactor;
  rom->tSolve   = kry->tSolve;
  rom->tOrth    = kry->tOrth;
  rom->tOffline = t3 - t0;
  PetscCall(PetscPrintf(o->comm, "ROM: rank kept per order:"));
  for (PetscInt k = 0; k < rom->order; k++) PetscCall(PetscPrintf(o->comm, " %" PetscInt_FMT, rom->rankPerOrder[k]));
  PetscCall(PetscPrintf(o->comm, "\n"));
  PetscCall(PetscPrintf(o->comm, "ROM: %" PetscInt_FMT " inputs, order %" PetscInt_FMT ", s0 %g rad/s: dimension %" PetscInt_FMT " (offline %.2f s: inputs %.2f, basis %.2f [factor %.2f, solves %.2f, orthogonalisation %.2f], projection %.2f)\n", rom->ninputs, rom->order, (double)rom->s0, rom->n, (double)rom->tOffline, (double)rom->tInputs, (double)rom->tBasis, (double)rom->tFactor, (double)rom->tSolve, (double)rom->tOrth, (double)rom->tProject));
  if (o->file[0]) PetscCall(BoltROMSave(rom, V, asmb, loads, o->file, rom->fingerprint));
  PetscCall(BVDestroy(&V));
  PetscCall(MatDestroy(&C));
  *romp = rom;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMDestroy(BoltROM **romp)
{
  BoltROM *rom = *romp;

  PetscFunctionBeginUser;
  if (!rom) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&rom->Mr));
  PetscCall(MatDestroy(&rom->Cr));
  PetscCall(MatDestroy(&rom->Kr));
  PetscCall(MatDestroy(&rom->Kcr));
  PetscCall(VecDestroy(&rom->loadr));
  PetscCall(VecDestroy(&rom->loadUnitr));
  PetscCall(VecDestroy(&rom->preloadr));
  PetscCall(PetscFree(rom->Vc));
  PetscCall(PetscFree(rom->Vprobe));
  PetscCall(PetscFree(rom->Ke));
  PetscCall(PetscFree5(rom->work, rom->work2, rom->dK, rom->packed, rom->Fr));
  PetscCall(PetscFree5(rom->De, rom->DeMax, rom->felem, rom->dMe, rom->dirtyElems));
  /* grown one by one (BoltGrowReal), so freed one by one: PetscFree3 frees a coalesced block */
  PetscCall(PetscFree(rom->kcrSend));
  PetscCall(PetscFree(rom->kcrRecv));
  PetscCall(PetscFree(rom->kcrDT));
  PetscCall(PetscFree4(rom->gpRows, rom->tnC, rom->tnK, rom->wholeGapBound));
  PetscCall(PetscFree2(rom->Rn, rom->gnRow));
  PetscCall(BoltExactSumDestroy(&rom->sum));
  PetscCall(PetscFree4(rom->lambda0, rom->gap0, rom->active0, rom->released0));
  PetscCall(PetscFree(rom->marked));
  PetscCall(BoltROMUpdateDestroy(&rom->update));
  PetscCall(PetscFree2(rom->fAcc, rom->fParts));
  PetscCall(PetscFree6(rom->npSlotStart, rom->npGlobalOf, rom->npDMax, rom->npSlotF, rom->npF, rom->npFSum));
  PetscCall(PetscFree2(rom->npRowsAll, rom->npOfPoint));
  PetscCall(PetscSFDestroy(&rom->npSF));
  PetscCall(PetscFree3(rom->npRowOf, rom->npRows, rom->npGap));
  PetscCall(PetscFree(*romp));
  PetscFunctionReturn(0);
}

/* Errors of a ROM history against the FOM's (docs/reduction.md, "Errors and speedup"): relative L2 over all steps, and
   the mean pointwise relative error over the steps where |u_FOM| > 1% of its maximum. */
PetscErrorCode BoltHistoryErrors(PetscInt n, const PetscReal fom[], const PetscReal rom[], PetscReal *eL2, PetscReal *eMean)
{
  PetscReal num = 0, den = 0, umax = 0, sum = 0;
  PetscInt  cnt = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    num += PetscSqr(rom[i] - fom[i]);
    den += PetscSqr(fom[i]);
    umax = PetscMax(umax, PetscAbsReal(fom[i]));
  }
  for (PetscInt i = 0; i < n; i++)
    if (PetscAbsReal(fom[i]) > 0.01 * umax) {
      sum += PetscAbsReal(rom[i] - fom[i]) / PetscAbsReal(fom[i]);
      cnt++;
    }
  *eL2   = den > 0 ? PetscSqrtReal(num / den) : 0;
  *eMean = cnt ? sum / cnt : 0;
  PetscFunctionReturn(0);
}
