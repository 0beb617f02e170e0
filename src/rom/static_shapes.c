/* The static shapes of the ROM's basis, solved offline on an operator of its own: the FOM's
   preloaded state, the load response, closed-contact and opened-joint static Krylov vectors, and
   the responses to unit force pairs where the load opens the joint or makes it slip. */
#include "private/rom.h"
#include <petscblaslapack.h>
#include "private/boltrom_krylov.h"
#include "private/boltrom_interface.h"

/* Every static solve of the offline phase goes through here: by the contact loop (dual), or with
   ksp by its last factorisation alone. A free model (R, its rigid motions, mass-orthonormal) has
   a singular operator: the right-hand side is balanced first under inertia relief, f - M R R' f
   (a load, or the mass-proportional forcing of a Krylov vector, would otherwise have no static
   solution), and the arbitrary rigid motion the solve leaves is taken out, R' M q = 0, as the
   FOM's preload solve does. A held model (R NULL) solves as it is. */
static PetscErrorCode ROMStaticSolve(BV R, BoltDual *dual, KSP ksp, Vec rhs, Vec q, PetscReal target, PetscInt *nout, PetscInt *nin)
{
  Vec      f = rhs;
  PetscInt o = 0, i = 0;

  PetscFunctionBeginUser;
  if (R) {
    Mat M;
    PetscCall(BVGetMatrix(R, &M, NULL));
    PetscCall(VecDuplicate(rhs, &f));
    PetscCall(VecCopy(rhs, f));
    PetscCall(BoltRigidRelieve(R, M, f));
  }
  if (ksp) PetscCall(KSPSolve(ksp, f, q));
  else PetscCall(BoltDualSolveStatic(dual, f, q, target, &o, &i));
  if (R) {
    PetscCall(BoltRigidProject(R, q));
    PetscCall(VecDestroy(&f));
  }
  if (nout) *nout = o;
  if (nin) *nin = i;
  PetscFunctionReturn(0);
}

/* Static Krylov vectors of the joint in its current contact state: out[k] = q(base + f_k) - qBase,
   with f_k = M out[k-1] (f_0 = M w0) scaled to the norm nforce, each solved by the dual loop from
   the state left by the one before (keepActiveSet, if set, holds the active set). work is
   overwritten. */
static PetscErrorCode BoltStaticKrylov(BV R, BoltDual *dual, Mat M, Vec base, Vec qBase, Vec w0, PetscReal nforce, PetscInt n, const char what[], Vec work, Vec rhs, Vec q, Vec out[])
{
  BoltOperator *op;
  PetscInt      nout, nin;

  PetscFunctionBeginUser;
  PetscCall(BoltDualGetSolver(dual, &op, NULL));
  for (PetscInt k = 0; k < n; k++) {
    PetscReal nf;
    PetscCall(MatMult(M, k ? out[k - 1] : w0, work));
    PetscCall(VecNorm(work, NORM_2, &nf));
    PetscCheck(nf > 0, BoltOperatorComm(op), PETSC_ERR_NOT_CONVERGED, "%s Krylov vector %" PetscInt_FMT " is zero", what, k + 1);
    PetscCall(VecScale(work, (nforce > 0 ? nforce : 1.0) / nf));
    PetscCall(VecCopy(base, rhs));
    PetscCall(VecAXPY(rhs, 1.0, work));
    PetscCall(ROMStaticSolve(R, dual, NULL, rhs, q, 0, &nout, &nin));
    PetscCall(VecDuplicate(q, &out[k]));
    PetscCall(VecWAXPY(out[k], -1.0, qBase, q));
    PetscCall(PetscPrintf(BoltOperatorComm(op), "ROM: %s Krylov vector %" PetscInt_FMT ": %" PetscInt_FMT " outer / %" PetscInt_FMT " inner iterations, %" PetscInt_FMT " points closed\n", what, k + 1, nout, nin, BoltContactStateActiveCount(BoltOperatorState(op))));
  }
  PetscFunctionReturn(0);
}

/* How far point gp's traction t is along its friction cone: |t_T| / (mu |t_N|) (infinite without
   pressure, zero without tangential traction); with tangent, also the unit direction of t_T. */
static PetscReal BoltConeFraction(const BoltContactSet *c, PetscInt gp, const PetscReal t[3], PetscReal tangent[3])
{
  const PetscReal *n  = &BoltContactSetNormals(c)[3 * gp];
  const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], bound = BoltContactSetFriction(c, BoltContactSetElementPair(c, gp / 4)) * PetscMax(-tn, 0.0);
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
  BoltContactSet *c = BoltContactStateSet(s);

  for (PetscInt gp = 0; gp < 4 * BoltContactSetElementCount(c); gp++)
    if (BoltContactStateActive(s)[gp] && BoltConeFraction(c, gp, &BoltContactStateLambda(s)[3 * gp], NULL) > 1) mark[gp] = PETSC_TRUE;
}

/* The FOM's preloaded state on the offline operator op (handed over, or solved as the FOM's
   time integrator would), kept per newton of preload in rom (multipliers, raw gaps, active
   set) and as the first static shape; the operator's penalties then scaled for the solves. */
static PetscErrorCode ROMPreloadedStart(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, BoltOperator *op, PetscReal staticPenaltyScale, const BoltPreloadState *shared, Vec q, Vec rhs, Vec *start, Vec *preload, BoltPreloadState **solved)
{
  BoltContactState *s = BoltOperatorState(op);
  PetscReal         F = BoltLoadSetPreloadForce(loads), outer, inner;
  PetscInt          nout, nin;

  PetscFunctionBeginUser;
  if (shared) { /* the FOM of this run solved it */
    PetscCall(BoltPreloadStateApply(shared, op, q));
    PetscCall(BoltPreloadStateGetIterations(shared, &outer, &inner));
  } else {
    PetscCheck(!BoltLoadSetBoltCount(loads), rom->comm, PETSC_ERR_SUP, "The ROM of several bolts (-preload_bolts) starts from the FOM's calibrated bolts: add -fom true, or give a -rom_file built for these bolts");
    /* as the FOM's time integrator would solve it (newmark.c): the same two scene options, on an
       operator of its own whose state is then handed over as the FOM's would be (a state that
       went through the solve keeps the friction's working data, and the shapes below then saw
       another joint: 53 slipping node pairs marked instead of 147 on a 100 N sine along x) */
    PetscBool         calibrate, withLoad;
    BoltOperator     *fom;
    BoltDual         *fomDual;
    BoltPreloadState *st;
    PetscCall(BoltNewmarkStaticStartOptions(&calibrate, &withLoad));
    PetscCall(BoltFOMCreate(asmb, c, loads, PETSC_FALSE, &fom));
    PetscCall(BoltOperatorCopyLoads(fom, NULL, BoltOperatorPreloadVec(op)));
    PetscCall(BoltDualCreate(fom, &fomDual));
    PetscCall(BoltDualSetFromOptions(fomDual));
    PetscCall(BoltDualSetUp(fomDual));
    PetscCall(VecCopy(BoltOperatorPreloadVec(fom), rhs));
    if (withLoad) PetscCall(VecAXPY(rhs, 1.0, BoltOperatorLoadVec(op)));
    PetscCall(ROMStaticSolve(rom->rigid, fomDual, NULL, rhs, q, calibrate && !withLoad ? F : 0, &nout, &nin));
    outer = nout;
    inner = nin;
    PetscCall(BoltPreloadStateCreate(fom, q, outer, inner, &st));
    PetscCall(BoltPreloadStateApply(st, op, q));
    if (solved) *solved = st; /* the caller's: later solves start from it as from the FOM's */
    else PetscCall(BoltPreloadStateDestroy(&st));
    PetscCall(BoltDualDestroy(&fomDual));
    PetscCall(BoltOperatorDestroy(&fom));
  }
  /* The preloaded state above is the FOM's, with its slip under friction. The basis's static
     shapes from here on are solved with closed pairs sticking (elastically): a load beyond the
     friction limit has no static equilibrium, and the shapes need none (friction acts online) */
  PetscCall(BoltContactStateSetStickOnly(s, PETSC_TRUE));
  PetscCall(VecDuplicate(q, &*start));
  PetscCall(VecCopy(q, *start));
  PetscCall(VecDuplicate(BoltOperatorPreloadVec(op), preload));
  PetscCall(VecCopy(BoltOperatorPreloadVec(op), *preload));
  PetscCall(PetscMalloc4(12 * BoltContactSetElementCount(c) + 1, &rom->lambda0, 12 * BoltContactSetElementCount(c) + 1, &rom->gap0, 4 * BoltContactSetElementCount(c) + 1, &rom->active0, 4 * BoltContactSetElementCount(c) + 1, &rom->released0));
  PetscCall(BoltContactSetScatter(c, BoltContactStateWork(s), *start));
  PetscCall(BoltContactStateGaps(s));
  for (PetscInt k = 0; k < 12 * BoltContactSetElementCount(c); k++) {
    rom->lambda0[k] = BoltContactStateLambda(s)[k] / F;
    rom->gap0[k]    = (BoltContactStateGap(s)[k] + BoltContactStateAnchor(s)[k]) / F; /* raw: the ROM's frozen multipliers hold any anchor */
  }
  PetscCall(PetscArraycpy(rom->active0, BoltContactStateActive(s), 4 * BoltContactSetElementCount(c)));
  PetscCall(PetscArraycpy(rom->released0, BoltContactStateReleased(s), 4 * BoltContactSetElementCount(c)));
  /* The solves below end with the active gaps closed, and the multipliers that close them do not
     depend on the penalty, nor does the active-set test (multipliers against the band). A stiffer
     penalty clusters the multiplier CG's operator B (K + eps B'B)^-1 B' near 1/eps, so the CG
     needs far fewer iterations on fine meshes. The preload itself
     stays the FOM's; this operator's state is its own, so the FOM's penalties are not touched. */
  PetscCall(BoltContactStateSetPenaltyScale(s, staticPenaltyScale, 1.0)); /* the band as it is */
  PetscCall(PetscPrintf(rom->comm, "ROM: the FOM's preloaded state (%s): %" PetscInt_FMT " outer / %" PetscInt_FMT " inner iterations, %" PetscInt_FMT " of %" PetscInt_FMT " points closed", shared && shared != rom->solvedPreload ? "the FOM run's" : "solved offline", (PetscInt)outer, (PetscInt)inner, BoltContactStateActiveCount(s), BoltContactSetPointCountGlobal(c)));
  PetscFunctionReturn(0);
}

/* The node pairs whose state the load changes statically at -/+ openingScale x its amplitude
   (under friction also those it makes slip), marked in rom, and with nOpenKrylov > 0 the opened
   joint's low-frequency static shapes (openK). Leaves the + solve's state in the dual loop. */
static PetscErrorCode ROMOpeningPairs(BoltAssembler *asmb, BoltContactSet *c, BoltROM *rom, BoltOperator *op, BoltDual *dual, PetscReal openingScale, PetscReal raise, PetscReal npre, PetscInt nOpenKrylov, Vec q, Vec rhs, Vec response, PetscInt *npairsOut, PetscInt **pairsOut, Vec **openKOut)
{
  BoltContactState *s = BoltOperatorState(op);
  PetscBool        *changed;
  PetscInt          nout, nin, npairs = 0, *pairs = NULL;
  Vec              *openK = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(4 * BoltContactSetElementCount(c) + 1, &changed));
  /* Friction: the pairs beyond the cone, sticking, under -/+ slipScale x the load. Sticking, the
     joint keeps the load where the slip zone would shed it onto its neighbours, so the zone
     beyond the cone at the swing's own size is narrower than the zone that slips; and a sine
     near a mode of the joint swings several times its static response (docs/decisions.md) */
  if (BoltContactStateHasFriction(s) && rom->slipScale > 0 && rom->slipScale != openingScale)
    for (PetscInt sign = -1; sign <= 1; sign += 2) {
      PetscCall(VecCopy(BoltOperatorPreloadVec(op), rhs));
      PetscCall(VecAXPY(rhs, sign * rom->slipScale / raise, BoltOperatorLoadVec(op)));
      PetscCall(ROMStaticSolve(rom->rigid, dual, NULL, rhs, q, 0, &nout, &nin));
      BoltMarkBeyondCone(s, changed);
    }
  for (PetscInt sign = -1; sign <= 1; sign += 2) {
    PetscCall(VecCopy(BoltOperatorPreloadVec(op), rhs));
    PetscCall(VecAXPY(rhs, sign * openingScale / raise, BoltOperatorLoadVec(op)));
    PetscCall(ROMStaticSolve(rom->rigid, dual, NULL, rhs, q, 0, &nout, &nin));
    for (PetscInt k = 0; k < 4 * BoltContactSetElementCount(c); k++) changed[k] = (PetscBool)(changed[k] || BoltContactStateActive(s)[k] != rom->active0[k]);
    if (BoltContactStateHasFriction(s)) BoltMarkBeyondCone(s, changed);
  }
  PetscCall(BoltNodePairs(c, changed, &npairs, &pairs));
  PetscCall(PetscFree(rom->marked));
  rom->marked = changed; /* kept: online the other points may hold their preloaded state */
  rom->nOpeningPairs = npairs;
  if (rom->slipScale > 0) PetscCall(PetscPrintf(rom->comm, "ROM: -/+ %g x the load change, or -/+ %g x the load makes slip, %" PetscInt_FMT " node pairs (%" PetscInt_FMT " points closed under +)\n", (double)openingScale, (double)rom->slipScale, npairs, BoltContactStateActiveCount(s)));
  else PetscCall(PetscPrintf(rom->comm, "ROM: -/+ %g x the load change %" PetscInt_FMT " node pairs (%" PetscInt_FMT " points closed under +)\n", (double)openingScale, npairs, BoltContactStateActiveCount(s)));
  if (nOpenKrylov > 0 && npairs > 0) { /* the opened joint's low-frequency shapes, its active set kept (none when no pair changes: it is the preloaded joint) */
    Vec base, q2, work;
    PetscCall(VecDuplicate(q, &base));
    PetscCall(VecDuplicate(q, &q2));
    PetscCall(VecDuplicate(q, &work));
    PetscCall(VecCopy(rhs, base)); /* the + solve's right-hand side and state */
    PetscCall(VecCopy(q, q2));
    PetscCall(PetscMalloc1(nOpenKrylov, &openK));
    PetscCall(BoltDualSetKeepActiveSet(dual, PETSC_TRUE));
    PetscCall(BoltStaticKrylov(rom->rigid, dual, BoltOperatorMass(op), base, q2, response, 1e-3 * npre, nOpenKrylov, "opened-joint", work, rhs, q, openK));
    PetscCall(BoltDualSetKeepActiveSet(dual, PETSC_FALSE));
    PetscCall(VecDestroy(&base));
    PetscCall(VecDestroy(&q2));
    PetscCall(VecDestroy(&work));
  }
  *npairsOut = npairs;
  *pairsOut  = pairs;
  *openKOut  = openK;
  PetscFunctionReturn(0);
}

/* The node pairs at coneShapes of the cone or beyond in the preloaded state (or slipping in
   it), each with its tangential traction's direction and its normal; marked in rom. */
static PetscErrorCode ROMConePairs(BoltContactSet *c, BoltROM *rom, PetscInt *nConePairs, PetscInt **conePairs, PetscReal **coneDirs)
{
  PetscFunctionBeginUser;
  PetscInt   ncone = 0, nconeGlobal;
  PetscBool *cone;
  PetscReal *dir; /* per point: the tangential traction's direction, then the normal */
  PetscCall(PetscCalloc1(4 * BoltContactSetElementCount(c) + 1, &cone));
  PetscCall(PetscCalloc1(24 * BoltContactSetElementCount(c) + 1, &dir));
  for (PetscInt gp = 0; gp < 4 * BoltContactSetElementCount(c); gp++) {
    PetscReal fraction;
    if (!rom->active0[gp]) continue;
    fraction = BoltConeFraction(c, gp, &rom->lambda0[3 * gp], &dir[6 * gp]);
    if (fraction > 0 && (rom->released0[gp] || fraction >= rom->coneShapes)) {
      ncone++;
      cone[gp] = PETSC_TRUE;
      for (PetscInt k = 0; k < 3; k++) dir[6 * gp + 3 + k] = BoltContactSetNormals(c)[3 * gp + k];
    } else
      for (PetscInt k = 0; k < 3; k++) dir[6 * gp + k] = 0;
  }
  PetscCall(MPIU_Allreduce(&ncone, &nconeGlobal, 1, MPIU_INT, MPI_SUM, rom->comm));
  PetscCall(BoltNodePairsDirected(c, cone, 2, dir, nConePairs, conePairs, coneDirs));
  PetscCall(PetscFree(dir));
  /* marked too: these points are free online whether or not unmarked points are held */
  if (!rom->marked) {
    rom->marked = cone;
    cone        = NULL;
  } else
    for (PetscInt gp = 0; gp < 4 * BoltContactSetElementCount(c); gp++) rom->marked[gp] = (PetscBool)(rom->marked[gp] || cone[gp]);
  PetscCall(PetscFree(cone));
  rom->nConePairs = *nConePairs;
  PetscCall(PetscPrintf(rom->comm, "ROM: %" PetscInt_FMT " points at %g of the cone or beyond in the preloaded state, on %" PetscInt_FMT " node pairs\n", nconeGlobal, (double)rom->coneShapes, *nConePairs));
  PetscFunctionReturn(0);
}

/* The preloaded joint's static responses to unit force pairs: three per opening node pair, and
   at the cone pairs one per direction (or, compressed, one per training pattern), appended to
   the static shapes with the opened-joint shapes after them. */
static PetscErrorCode ROMNodePairShapes(BoltContactSet *c, BoltROM *rom, BoltOperator *op, BoltDual *dual, PetscInt nClosed, PetscInt npairs, const PetscInt pairs[], PetscInt nConePairs, const PetscInt conePairs[], const PetscReal coneDirs[], PetscInt nOpenKrylov, Vec openK[], PetscInt nsnap, Vec snap[], Vec q, Vec rhs, PetscInt *nextra, Vec **extrap)
{
  BoltContactState *s     = BoltOperatorState(op);
  Vec              *extra = *extrap, *all;
  PetscInt          nout, nin, ncone = 0;
  KSP               ksp;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(*nextra + 3 * npairs + 2 * nConePairs + nOpenKrylov, &all));
  PetscCall(PetscArraycpy(all, extra, *nextra));
  PetscCall(PetscFree(extra));
  extra = all;
  if (nClosed == 0) { /* else the closed-contact vectors' last solve factored K + K_c of the preloaded set */
    PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0));
    PetscCall(BoltDualSetKeepActiveSet(dual, PETSC_TRUE));
    PetscCall(ROMStaticSolve(rom->rigid, dual, NULL, BoltOperatorPreloadVec(op), q, 0, &nout, &nin));
  }
  PetscCall(BoltDualGetSolver(dual, NULL, &ksp)); /* factored by the last solve */
  for (PetscInt i = 0; i < npairs; i++)
    for (PetscInt d = 0; d < 3; d++) {
      PetscCall(BoltNodePairVector(pairs[2 * i], pairs[2 * i + 1], d, rhs));
      PetscCall(VecDuplicate(q, &extra[*nextra]));
      PetscCall(ROMStaticSolve(rom->rigid, dual, ksp, rhs, extra[*nextra], 0, NULL, NULL));
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
        PetscCall(ROMStaticSolve(rom->rigid, dual, ksp, rhs, extra[*nextra], 0, NULL, NULL));
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
        PetscCall(ROMStaticSolve(rom->rigid, dual, ksp, rhs, extra[*nextra], 0, NULL, NULL));
        (*nextra)++;
        ncone++;
      }
  rom->nConeModes = rom->coneModes > 0 ? ncone : 0;
  PetscCall(PetscPrintf(rom->comm, "ROM: %" PetscInt_FMT " opening shapes, %" PetscInt_FMT " cone shapes\n", 3 * npairs, ncone));
  for (PetscInt k = 0; k < nOpenKrylov; k++) extra[(*nextra)++] = openK[k]; /* the array itself is the caller's to free */
  *extrap = extra;
  PetscFunctionReturn(0);
}

/* The offline static solves' operator (a FOM without damping: static solves only), its contact
   loop, and two work vectors. The calibration scales the preload vector and the load response may
   scale the load: it works on copies, the scene's stay as they are. */
static PetscErrorCode ROMOfflineOperator(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltOperator **op, BoltDual **dual, Vec *q, Vec *rhs)
{
  PetscFunctionBeginUser;
  PetscCall(BoltFOMCreate(asmb, c, loads, PETSC_FALSE, op));
  PetscCall(BoltOperatorCopyLoads(*op, BoltLoadSetLoad(loads), BoltLoadSetPreload(loads)));
  PetscCall(BoltDualCreate(*op, dual));
  PetscCall(BoltDualSetFromOptions(*dual));
  PetscCall(BoltDualSetUp(*dual));
  PetscCall(VecDuplicate(BoltOperatorPreloadVec(*op), q));
  PetscCall(VecDuplicate(BoltOperatorPreloadVec(*op), rhs));
  PetscFunctionReturn(0);
}

/* The offline operator's load (its own copy) raised to at least 1e-3 of the preload's norm: the
   contact loop's tolerance is relative to the preload's multipliers, and a smaller load's response
   would sink into the loop's residual. nload and npre: the norms before; raise: the factor. */
static PetscErrorCode ROMRaiseLoad(BoltOperator *op, PetscReal *nload, PetscReal *npre, PetscReal *raise)
{
  PetscFunctionBeginUser;
  PetscCall(VecNorm(BoltOperatorLoadVec(op), NORM_2, nload));
  PetscCall(VecNorm(BoltOperatorPreloadVec(op), NORM_2, npre));
  *raise = *nload > 0 ? PetscMax(1.0, 1e-3 * *npre / *nload) : 1.0;
  PetscCall(VecScale(BoltOperatorLoadVec(op), *raise));
  PetscFunctionReturn(0);
}

/* The FOM's static preloaded equilibrium (the FOM run's if it ran, else solved here): q0, the
   multipliers (per newton of preload) and the active set, then the static response to the scene's load from that state with the
   contact closed by the augmented Lagrangian. The interface-reduced ROM cannot close its gaps
   (fewer DOFs than constraints), so under the penalty law alone it penetrates by micrometres
   under the clamp and starts from a tilted state; with q0 in its basis and the FOM's multipliers
   frozen it starts exactly where the FOM does, and the load response gives it one gap-free
   shape, which lets a stiffer penalty carry the increments without locking. */
PetscErrorCode BoltROMPreloadSolve(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, PetscInt nClosed, PetscReal staticPenaltyScale, PetscReal openingScale, PetscInt nOpenKrylov, const BoltPreloadState *shared, PetscInt nsnap, Vec snap[], PetscInt *nextra, Vec **extrap, Vec *preload)
{
  BoltOperator     *op;
  BoltContactState *s;
  BoltDual         *dual;
  Vec               q, rhs;
  PetscInt          nout, nin, npairs = 0, *pairs = NULL;
  Vec              *extra, *openK = NULL;
  PetscInt          nConePairs = 0, *conePairs = NULL;
  PetscReal        *coneDirs = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 + nClosed, &extra));
  PetscCall(ROMOfflineOperator(asmb, c, loads, &op, &dual, &q, &rhs));
  s = BoltOperatorState(op);
  PetscCall(ROMPreloadedStart(asmb, c, loads, rom, op, staticPenaltyScale, shared, q, rhs, &extra[0], preload, NULL));
  /* the load on top, from the preloaded state (multipliers warm, active set free to change).
     The contact loop's tolerance is relative to the preload's multipliers, so a load below
     1e-3 of the preload's norm is raised to that (its response then rises above the loop's
     residual; with the joint closed the response is linear in the load, and the scale is lost
     in the orthonormalisation anyway) */
  PetscReal nload, npre, raise;
  PetscCall(ROMRaiseLoad(op, &nload, &npre, &raise));
  PetscCall(VecCopy(BoltOperatorPreloadVec(op), rhs));
  PetscCall(VecAXPY(rhs, 1.0, BoltOperatorLoadVec(op)));
  PetscCall(ROMStaticSolve(rom->rigid, dual, NULL, rhs, q, 0, &nout, &nin));
  PetscCall(VecDuplicate(q, &extra[1]));
  PetscCall(VecWAXPY(extra[1], -1.0, extra[0], q));
  PetscCall(VecScale(extra[1], 1.0 / raise));
  PetscCall(PetscPrintf(rom->comm, "; load response (load x %g) %" PetscInt_FMT " inner iterations\n", (double)raise, nin));
  /* Opening shapes: the node pairs whose state the load changes statically at -openingScale or
     +openingScale x its amplitude (a step load's response swings up to twice its static one, a
     sine load's to either side); under friction also those it makes slip. The positive one
     last: its state starts the opened-joint Krylov vectors. */
  if (openingScale > 0) PetscCall(ROMOpeningPairs(asmb, c, rom, op, dual, openingScale, raise, npre, nOpenKrylov, q, rhs, extra[1], &npairs, &pairs, &openK));
  /* Friction: the pairs the preloaded state leaves on (or near) the cone. Under a small load
     their creep is all the joint dissipates, in bursts that die out cycle by cycle. The interface
     modes are the stuck interface's, and snapshot modes mix every pair's slip; these pairs get
     shapes of their own, the responses to a unit force pair along their normal (the pressure they
     shed and take moves their cone: on the joint at level 0.5, a ROM that was 16 - 52 % over in
     the last bursts at 10 - 30 N came within 2.5 % with these) and along their tangential traction
     (with both, within 1.5 %; with the traction alone no nearer) */
  if (rom->coneShapes > 0 && BoltContactStateHasFriction(s)) PetscCall(ROMConePairs(c, rom, &nConePairs, &conePairs, &coneDirs));
  /* closed-contact Krylov vectors: w_k = static response, from the preloaded state, to M w_(k-1),
     so the basis holds the closed joint's low-frequency shapes too. Forced at 1e-3 of the
     preload's norm: small enough that the joint stays closed, large enough to rise above the
     contact loop's residual (the shapes are those of the closed joint; their scale is lost in
     the orthonormalisation). They keep the preloaded active set: the forcing, spread over the
     whole volume, opened points at the rim on fine meshes, and the basis of that opened joint
     was less accurate than the one with the set kept (docs/decisions.md) */
  if (nClosed > 0) {
    PetscReal nforce = 1e-3 * npre;
    PetscCall(PetscPrintf(rom->comm, "ROM: closed-contact Krylov forcing of norm %g (load %g, preload %g)\n", (double)nforce, (double)nload, (double)npre));
    PetscCall(BoltContactStateSetActive(s, rom->active0, rom->released0));
    PetscCall(BoltDualSetKeepActiveSet(dual, PETSC_TRUE));
    /* BoltOperatorLoadVec(op), this solve's own copy, is the forcing of each vector in turn */
    PetscCall(BoltStaticKrylov(rom->rigid, dual, BoltOperatorMass(op), BoltOperatorPreloadVec(op), extra[0], extra[1], nforce, nClosed, "closed-contact", BoltOperatorLoadVec(op), rhs, q, &extra[2]));
  }
  *nextra = 2 + nClosed;
  /* Each opening shape is the preloaded joint's static response to a unit force pair on one of
     those node pairs, in one direction. A node pair's penalty is a rank-3 term on its relative
     displacement, so by Sherman-Morrison the joint's response with that pair open, to any forces
     on it, lies in the span of its three shapes, and together they span the response of the
     joint with any subset of those pairs open (Woodbury); the interface modes do not. */
  if (npairs + nConePairs > 0) PetscCall(ROMNodePairShapes(c, rom, op, dual, nClosed, npairs, pairs, nConePairs, conePairs, coneDirs, nOpenKrylov, openK, nsnap, snap, q, rhs, nextra, &extra));
  PetscCall(PetscFree(openK));
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

/* -rom_train static: the points whose state the load changes statically at -/+ the opening scale
   x its amplitude (under friction also those beyond the cone at -/+ the slip scale), from the
   FOM's preloaded state (the FOM run's, or solved here and handed back in solved), as the opening
   shapes mark them; what a FOM run would tell a trained ROM, without that run. */
PetscErrorCode BoltROMStaticChanges(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, BoltROM *rom, const BoltPreloadState *shared, PetscBool **changed, BoltPreloadState **solved)
{
  BoltOperator *op;
  BoltDual     *dual;
  Vec           q, rhs, start, preload;
  PetscInt      npairs, *pairs;
  PetscReal     nload, npre, raise;
  Vec          *openK;

  PetscFunctionBeginUser;
  *solved = NULL;
  if (BoltMeshIsFree(BoltContactSetMesh(c)) && !rom->rigid) PetscCall(BoltAssemblerRigidModes(asmb, &rom->rigid)); /* the solves' inertia relief, kept for the basis */
  PetscCall(ROMOfflineOperator(asmb, c, loads, &op, &dual, &q, &rhs));
  PetscCall(ROMPreloadedStart(asmb, c, loads, rom, op, rom->staticPenaltyScale, shared, q, rhs, &start, &preload, shared ? NULL : solved));
  PetscCall(PetscPrintf(rom->comm, "\n"));
  PetscCall(ROMRaiseLoad(op, &nload, &npre, &raise));
  PetscCall(ROMOpeningPairs(asmb, c, rom, op, dual, rom->openingScale, raise, npre, 0, q, rhs, NULL, &npairs, &pairs, &openK));
  *changed    = rom->marked;
  rom->marked = NULL;
  PetscCall(PetscFree(pairs));
  PetscCall(PetscFree4(rom->lambda0, rom->gap0, rom->active0, rom->released0)); /* made again with the basis's static shapes */
  PetscCall(VecDestroy(&start));
  PetscCall(VecDestroy(&preload));
  PetscCall(VecDestroy(&q));
  PetscCall(VecDestroy(&rhs));
  PetscCall(BoltDualDestroy(&dual));
  PetscCall(BoltOperatorDestroy(&op));
  PetscFunctionReturn(0);
}
