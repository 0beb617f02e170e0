/* Newmark time integration with the dual contact loop (the paper's Algorithm 1), written once
   against BoltOperator so that the full and the reduced model run literally the same code.
   Outer loop: the active set, until it stops changing; inner loop: augmentations of the
   multipliers, until they stop changing and the penetration is small. */
#include "boltrom.h"

PetscErrorCode BoltNewmarkCreate(BoltOperator *op, BoltNewmark **nmp)
{
  BoltNewmark *nm;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&nm));
  nm->op             = op;
  nm->beta           = 0.25;
  nm->gamma          = 0.5;
  nm->dt             = 2.5e-4;
  nm->tEnd           = 0.1;
  nm->history        = BOLT_LOAD_STEP;
  nm->frequency      = 50.0;
  nm->maxOuter       = 20;
  nm->maxInner       = 5000;
  nm->tolLambda      = 1e-4;
  nm->tolPenetration = 1e-9;
  nm->inner          = 1;
  nm->calibratePreload = PETSC_TRUE;
  nm->closeCycles    = PETSC_TRUE;
  nm->preloadScale   = 1.0;
  PetscCall(PetscStrncpy(nm->checkpointBase, "output/joint", sizeof(nm->checkpointBase)));
  *nmp               = nm;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkSetFromOptions(BoltNewmark *nm)
{
  MPI_Comm    comm = nm->op->comm;
  const char *hist[] = {"step", "sine", "BoltLoadHistory", "BOLT_LOAD_", NULL};

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Time integration and contact loop", "boltrom");
  PetscCall(PetscOptionsReal("-ts_dt", "Time step [s]", NULL, nm->dt, &nm->dt, NULL));
  PetscCall(PetscOptionsReal("-ts_end", "End time [s]", NULL, nm->tEnd, &nm->tEnd, NULL));
  PetscCall(PetscOptionsReal("-newmark_beta", "Newmark beta", NULL, nm->beta, &nm->beta, NULL));
  PetscCall(PetscOptionsReal("-newmark_gamma", "Newmark gamma", NULL, nm->gamma, &nm->gamma, NULL));
  PetscCall(PetscOptionsEnum("-load_history", "Time history of the external load: step (on from t > 0) or sine", "BoltLoadHistory", hist, (PetscEnum)nm->history, (PetscEnum *)&nm->history, NULL));
  PetscCall(PetscOptionsReal("-load_frequency", "Frequency of the sine load [Hz]", NULL, nm->frequency, &nm->frequency, NULL));
  {
    const char *inner[] = {"uzawa", "cg"};
    PetscCall(PetscOptionsEList("-contact_inner", "Inner loop: uzawa (augmentations, as the paper) or cg (conjugate gradients on the multipliers, same fixed point, fewer solves)", NULL, inner, 2, inner[nm->inner], &nm->inner, NULL));
  }
  PetscCall(PetscOptionsInt("-contact_max_outer", "Outer (active set) iterations per step", NULL, nm->maxOuter, &nm->maxOuter, NULL));
  PetscCall(PetscOptionsInt("-contact_max_inner", "Inner (augmentation) iterations per outer iteration", NULL, nm->maxInner, &nm->maxInner, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_lambda", "Tolerance on the relative change of the multipliers", NULL, nm->tolLambda, &nm->tolLambda, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_penetration", "Tolerance on the largest penetration of an active point [m]", NULL, nm->tolPenetration, &nm->tolPenetration, NULL));
  PetscCall(PetscOptionsBool("-contact_cycle_close", "Anti-cycling: when the active set cycles between two sets (its toggling points are then closed) or has not settled in half of -contact_max_outer, points may only close for the rest of the step; false: a cycle stops the run (or warns, with -contact_continue)", NULL, nm->closeCycles, &nm->closeCycles, NULL));
  PetscCall(PetscOptionsBool("-contact_continue", "On non-convergence, warn and go on instead of stopping", NULL, nm->continueOnFailure, &nm->continueOnFailure, NULL));
  PetscCall(PetscOptionsBool("-static_contact_load", "The static contact solve carries the external load as well as the preload", NULL, nm->staticWithLoad, &nm->staticWithLoad, NULL));
  PetscCall(PetscOptionsBool("-preload_calibrate", "Scale the preload layer forces so that the bolt clamps with -preload_force (the layer between them is elastic)", NULL, nm->calibratePreload, &nm->calibratePreload, NULL));
  PetscCall(PetscOptionsInt("-snapshot_every", "Keep the displacement field every this many steps for ParaView (0: none)", NULL, nm->snapshotEvery, &nm->snapshotEvery, NULL));
  PetscCall(PetscOptionsBool("-monitor", "Print a line per time step", NULL, nm->monitor, &nm->monitor, NULL));
  PetscCall(PetscOptionsInt("-checkpoint_every", "Write a checkpoint every this many steps (0: none); files <-checkpoint_file>-fom.ckpt.h5 and -rom.ckpt.h5", NULL, nm->checkpointEvery, &nm->checkpointEvery, NULL));
  PetscCall(PetscOptionsString("-checkpoint_file", "Base name of the checkpoint files (default: <output_dir>/<output_name>)", NULL, nm->checkpointBase, nm->checkpointBase, sizeof(nm->checkpointBase), NULL));
  PetscCall(PetscOptionsBool("-restart", "Continue each model's transient from its checkpoint (same mesh, ranks, time step; -ts_end may be later)", NULL, nm->restart, &nm->restart, NULL));
  PetscCall(PetscOptionsInt("-contact_monitor", "Print the contact loop: 1 a line per outer iteration, 2 also per inner CG iteration", NULL, nm->contactMonitor, &nm->contactMonitor, NULL));
  PetscOptionsEnd();
  PetscCheck(nm->checkpointEvery >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_every must be >= 0 (got %" PetscInt_FMT ")", nm->checkpointEvery);
  if (nm->checkpointEvery > 0) PetscCall(BoltMakeParentDir(comm, nm->checkpointBase)); /* fail now, not at the first checkpoint */
  PetscCheck(nm->dt > 0, comm, PETSC_ERR_USER_INPUT, "-ts_dt must be > 0 (got %g)", (double)nm->dt);
  PetscCheck(nm->tEnd >= nm->dt, comm, PETSC_ERR_USER_INPUT, "-ts_end (%g) must be at least one time step -ts_dt (%g)", (double)nm->tEnd, (double)nm->dt);
  PetscCheck(nm->beta > 0 && nm->gamma >= 0.5, comm, PETSC_ERR_USER_INPUT, "Newmark needs beta > 0 and gamma >= 1/2 (got %g, %g)", (double)nm->beta, (double)nm->gamma);
  PetscCheck(nm->snapshotEvery >= 0, comm, PETSC_ERR_USER_INPUT, "-snapshot_every must be >= 0");
  PetscCheck(nm->maxOuter >= 1 && nm->maxInner >= 1, comm, PETSC_ERR_USER_INPUT, "-contact_max_outer and -contact_max_inner must be >= 1");
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkSetUp(BoltNewmark *nm)
{
  BoltOperator *op = nm->op;
  PetscReal     b = nm->beta, g = nm->gamma, dt = nm->dt;
  PC            pc;
  Mat           Kc, Z;

  PetscFunctionBeginUser;
  nm->a[1]   = 1.0 / (b * dt * dt);
  nm->a[2]   = 1.0 / (b * dt);
  nm->a[3]   = 1.0 / (2 * b) - 1.0;
  nm->a[4]   = g / (b * dt);
  nm->a[5]   = g / b - 1.0;
  nm->a[6]   = dt * (g / (2 * b) - 1.0);
  nm->nsteps = (PetscInt)PetscFloorReal(nm->tEnd / dt + 1e-9);
  PetscCall(MatCreateVecs(op->K, &nm->q, NULL));
  PetscCall(VecDuplicate(nm->q, &nm->v));
  PetscCall(VecDuplicate(nm->q, &nm->acc));
  PetscCall(VecDuplicate(nm->q, &nm->rhs));
  PetscCall(VecDuplicate(nm->q, &nm->Fc));
  PetscCall(VecDuplicate(nm->q, &nm->work));
  PetscCall(VecDuplicate(nm->q, &nm->qp));
  PetscCall(VecDuplicate(nm->q, &nm->FcLambda));
  PetscCall(PetscMalloc3(12 * op->contact->nelem + 1, &nm->cgR, 12 * op->contact->nelem + 1, &nm->cgP, 12 * op->contact->nelem + 1, &nm->cgAp));
  PetscCall(PetscCalloc3(nm->nsteps + 1, &nm->probeTime, nm->nsteps + 1, &nm->probeValue, nm->nsteps + 1, &nm->energy));
  if (nm->snapshotEvery > 0) {
    PetscInt n = nm->nsteps / nm->snapshotEvery + 1;
    PetscCall(PetscCalloc1(n, &nm->snapTime));
    PetscCall(VecDuplicateVecs(nm->q, n, &nm->snap));
  }
  /* K_eff gets the union of the structural and the contact pattern once, so that it keeps one
     pattern and MUMPS repeats only the numeric factorisation */
  PetscCall(op->contactStiffness(op, &Kc));
  PetscCall(MatDuplicate(Kc, MAT_DO_NOT_COPY_VALUES, &Z));
  PetscCall(MatDuplicate(op->K, MAT_COPY_VALUES, &nm->Keff));
  PetscCall(MatAXPY(nm->Keff, 1.0, Z, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&Z));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)op->K), &nm->ksp)); /* the matrices' communicator */
  PetscCall(KSPSetOptionsPrefix(nm->ksp, op->prefix));
  PetscCall(KSPSetType(nm->ksp, KSPPREONLY));
  PetscCall(KSPGetPC(nm->ksp, &pc));
  {
    /* K_eff is symmetric (the stick penalty is): Cholesky (LDL' in MUMPS) halves the factor */
    PetscBool set, sym;
    PetscCall(MatIsSymmetricKnown(op->K, &set, &sym));
    if (set && sym) PetscCall(MatSetOption(nm->Keff, MAT_SYMMETRIC, PETSC_TRUE));
    PetscCall(PCSetType(pc, set && sym ? PCCHOLESKY : PCLU));
  }
  PetscCall(PCFactorSetMatSolverType(pc, op->solverType));
  PetscCall(KSPSetFromOptions(nm->ksp));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltNewmarkFactor(BoltNewmark *nm)
{
  BoltOperator  *op = nm->op;
  Mat            Kc;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactStiffness, 0, 0, 0, 0));
  PetscCall(op->contactStiffness(op, &Kc));
  /* summed afresh in the pattern fixed at set-up, in the order a kept copy of the structural
     part would give (no FOM-sized copy of it is held: at 562k DOFs memory is the limit) */
  PetscCall(MatZeroEntries(nm->Keff));
  PetscCall(MatAXPY(nm->Keff, 1.0, op->K, SUBSET_NONZERO_PATTERN));
  if (nm->dynamic) {
    PetscCall(MatAXPY(nm->Keff, nm->a[1], op->M, SUBSET_NONZERO_PATTERN));
    PetscCall(MatAXPY(nm->Keff, nm->a[4], op->C, SUBSET_NONZERO_PATTERN));
  }
  PetscCall(MatAXPY(nm->Keff, 1.0, Kc, SUBSET_NONZERO_PATTERN));
  PetscCall(PetscLogEventEnd(boltLog.contactStiffness, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  nm->tContactStiffness += t1 - t0;
  PetscCall(PetscLogEventBegin(boltLog.factorization, 0, 0, 0, 0));
  PetscCall(KSPSetOperators(nm->ksp, nm->Keff, nm->Keff));
  PetscCall(KSPSetUp(nm->ksp));
  PetscCall(PetscLogEventEnd(boltLog.factorization, 0, 0, 0, 0));
  {
    PC            pc;
    PCFailedReason reason;
    PetscCall(KSPGetPC(nm->ksp, &pc));
    PetscCall(PCGetFailedReason(pc, &reason));
    PetscCheck(reason == PC_NOERROR, nm->op->comm, PETSC_ERR_NOT_CONVERGED, "%s: factorisation of the effective stiffness failed (%s) at step %" PetscInt_FMT ", t = %g s: the system is singular (a part held by contact alone lost all contact?)", op->name, PCFailedReasons[reason], nm->step, (double)(nm->step * nm->dt));
  }
  PetscCall(PetscTime(&t0));
  nm->tDisplacements += t0 - t1;
  nm->factorizations++;
  PetscFunctionReturn(0);
}

/* Timed pieces of the inner loops: q = K_eff^-1 (rhs0 - B' lambda), and the gaps of q. */
static PetscErrorCode BoltSolveWithForces(BoltNewmark *nm, Vec rhs0, const PetscReal lambda[], Vec q)
{
  BoltOperator  *op = nm->op;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(op->contactForces(op, lambda, nm->Fc));
  if (rhs0) PetscCall(VecWAXPY(nm->work, -1.0, nm->Fc, rhs0));
  else PetscCall(VecCopy(nm->Fc, nm->work));
  PetscCall(PetscLogEventEnd(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogEventBegin(boltLog.displacements, 0, 0, 0, 0));
  PetscCall(KSPSolve(nm->ksp, nm->work, q));
  PetscCall(PetscLogEventEnd(boltLog.displacements, 0, 0, 0, 0));
  PetscCall(PetscTime(&t2));
  nm->solves++;
  nm->tContactForces += t1 - t0;
  nm->tDisplacements += t2 - t1;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltGapsOf(BoltNewmark *nm, Vec q, PetscReal gap[])
{
  BoltOperator  *op = nm->op;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(op->contactDisplacements(op, q));
  PetscCall(BoltContactSetGapsOf(op->contact, gap));
  PetscCall(PetscLogEventEnd(boltLog.contactForces, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  nm->tContactForces += t1 - t0;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltInnerFailure(BoltNewmark *nm, PetscInt inner, PetscReal rel, PetscReal pen)
{
  MPI_Comm comm = nm->op->comm;

  PetscFunctionBeginUser;
  nm->failures++;
  PetscCheck(nm->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: contact augmentations did not converge at step %" PetscInt_FMT ", t = %g s: after %" PetscInt_FMT " iterations the multipliers change by %.3e (tolerance %.1e) and the penetration is %.3e m (tolerance %.1e); raise -contact_max_inner or loosen -contact_tol_lambda / -contact_tol_penetration, or add -contact_continue to go on with a warning", nm->op->name, nm->step, (double)(nm->step * nm->dt), inner, (double)rel, (double)nm->tolLambda, (double)pen, (double)nm->tolPenetration);
  PetscCall(PetscPrintf(comm, "WARNING %s: augmentations not converged at step %" PetscInt_FMT ", t = %g s (change %.3e, penetration %.3e m)\n", nm->op->name, nm->step, (double)(nm->step * nm->dt), (double)rel, (double)pen));
  PetscFunctionReturn(0);
}

/* Inner loop, the paper's way: lambda <- lambda + P g at the active points until the
   multipliers stop changing and the penetration is small. */
static PetscErrorCode BoltInnerUzawa(BoltNewmark *nm, Vec rhs0, PetscInt *ninner)
{
  BoltContactSet *c = nm->op->contact;
  PetscReal       rel = 0, pen = 0;
  PetscInt        inner;

  PetscFunctionBeginUser;
  for (inner = 1;; inner++) {
    PetscCall(BoltSolveWithForces(nm, rhs0, c->lambda, nm->q));
    PetscCall(BoltGapsOf(nm, nm->q, c->gap));
    PetscCall(BoltContactSetAugment(c, &rel, &pen));
    nm->lastChange      = rel;
    nm->lastPenetration = pen;
    PetscCheck(!PetscIsInfOrNanReal(rel) && !PetscIsInfOrNanReal(pen), nm->op->comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", nm->op->name, nm->step, (double)(nm->step * nm->dt));
    if (!c->augment) break;
    if (rel <= nm->tolLambda && (pen <= nm->tolPenetration || !nm->op->exactConstraints)) break;
    if (inner >= nm->maxInner) {
      PetscCall(BoltInnerFailure(nm, inner, rel, pen));
      break;
    }
  }
  *ninner = inner;
  PetscFunctionReturn(0);
}

/* Inner loop by conjugate gradients on the multipliers. For a fixed active set the gaps are
   affine in the multipliers, g(lambda) = g(0) - A lambda with A = B K_eff^-1 B' W symmetric
   in the area-weighted product, and the augmentations are Richardson iterations towards
   g = 0; CG reaches the same multipliers in far fewer solves (one solve per iteration). */
static PetscErrorCode BoltInnerCG(BoltNewmark *nm, Vec rhs0, PetscInt *ninner)
{
  BoltContactSet *c  = nm->op->contact;
  PetscInt        ng = 12 * c->nelem, inner;
  PetscReal      *r = nm->cgR, *p = nm->cgP, *Ap = nm->cgAp, rr, rr0, pAp, alpha, rel = 0, pen = 0, lnorm, pnorm;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++)
    if (!c->active[gp]) c->lambda[3 * gp] = c->lambda[3 * gp + 1] = c->lambda[3 * gp + 2] = 0;
  PetscCall(BoltSolveWithForces(nm, rhs0, c->lambda, nm->q));
  PetscCall(VecCopy(nm->Fc, nm->FcLambda)); /* the contact forces of lambda, kept up to date */
  PetscCall(BoltGapsOf(nm, nm->q, r));
  PetscCall(BoltContactSetPenetration(c, r, &pen));
  PetscCall(PetscArraycpy(p, r, ng));
  PetscCall(BoltContactSetDot(c, r, r, &rr));
  rr0 = rr;
  for (inner = 1;; inner++) {
    PetscReal rrNew;

    nm->lastPenetration = pen;
    if (!c->augment) break;
    if (rr == 0) { /* nothing active, or exactly closed */
      rel = 0;
      break;
    }
    /* A p: the gaps that the multipliers p alone produce (with a minus sign) */
    PetscCall(BoltSolveWithForces(nm, NULL, p, nm->qp));
    PetscCall(BoltGapsOf(nm, nm->qp, Ap));
    PetscCall(BoltContactSetPenetration(c, Ap, &pnorm)); /* zeroes inactive points */
    PetscCall(BoltContactSetDot(c, p, Ap, &pAp));
    PetscCheck(!PetscIsInfOrNanReal(pAp) && !PetscIsInfOrNanReal(rr), nm->op->comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", nm->op->name, nm->step, (double)(nm->step * nm->dt));
    if (pAp <= 0) break; /* the remaining gaps are invisible to the multipliers */
    alpha = rr / pAp;
    for (PetscInt k = 0; k < ng; k++) {
      c->lambda[k] += alpha * p[k];
      r[k] -= alpha * Ap[k];
    }
    PetscCall(VecAXPY(nm->q, -alpha, nm->qp));
    /* change of the multipliers, measured by the nodal forces they exert: components of lambda
       that exert no force (there are more Gauss points than nodes) change nothing */
    PetscCall(VecAXPY(nm->FcLambda, alpha, nm->Fc));
    PetscCall(VecNorm(nm->Fc, NORM_2, &pnorm));
    PetscCall(VecNorm(nm->FcLambda, NORM_2, &lnorm));
    rel = lnorm > 0 ? PetscAbsReal(alpha) * pnorm / lnorm : 0;
    PetscCall(BoltContactSetPenetration(c, r, &pen));
    nm->lastChange      = rel;
    nm->lastPenetration = pen;
    if (nm->contactMonitor > 1) {
      PetscReal rrN, trueRes = 0, drift = 0;
      PetscCall(BoltContactSetDot(c, r, r, &rrN));
      if (inner % 10 == 0) { /* the true residual: gaps of the current q, and of a fresh solve */
        PetscReal *tg, dd, tt;
        Vec        qt;
        PetscCall(PetscMalloc1(ng + 1, &tg));
        PetscCall(VecDuplicate(nm->q, &qt));
        PetscCall(BoltSolveWithForces(nm, rhs0, c->lambda, qt));
        PetscCall(BoltGapsOf(nm, qt, tg));
        PetscCall(VecDestroy(&qt));
        PetscCall(BoltContactSetPenetration(c, tg, &tt));
        for (PetscInt k = 0; k < ng; k++) Ap[k] = tg[k] - r[k];
        PetscCall(BoltContactSetDot(c, Ap, Ap, &dd));
        PetscCall(BoltContactSetDot(c, tg, tg, &tt));
        trueRes = PetscSqrtReal(tt / rr0);
        drift   = PetscSqrtReal(dd / rr0);
        PetscCall(PetscFree(tg));
      }
      PetscCall(PetscPrintf(nm->op->comm, "    CG %4" PetscInt_FMT " rel %.3e |r|/|r0| %.3e true %.3e drift %.3e pen %.3e alpha %.3e\n", inner, (double)rel, (double)PetscSqrtReal(rrN / rr0), (double)trueRes, (double)drift, (double)pen, (double)alpha));
    }
    /* a reduced model may have fewer DOFs than contact constraints: there the penetration
       cannot vanish everywhere, and the loop ends when the gaps (the dual residual) have dropped
       by the tolerance, or the reduced forces stop changing */
    if (rel <= nm->tolLambda && pen <= nm->tolPenetration) break;
    PetscCall(BoltContactSetDot(c, r, r, &rrNew));
    if (!nm->op->exactConstraints && (PetscSqrtReal(rrNew / rr0) <= nm->tolLambda || rel <= 1e-2 * nm->tolLambda)) break;
    if (inner >= nm->maxInner) {
      PetscCall(BoltInnerFailure(nm, inner, rel, pen));
      break;
    }
    for (PetscInt k = 0; k < ng; k++) p[k] = r[k] + (rrNew / rr) * p[k];
    rr = rrNew;
  }
  /* the true gaps of the final displacement at every point: r holds them only at active points
     (zeroed elsewhere), and an inactive point must be able to close again */
  PetscCall(BoltGapsOf(nm, nm->q, c->gap));
  *ninner = inner;
  PetscFunctionReturn(0);
}

/* Diagnostics of one outer iteration: points opened / closed per pair, the distance from the
   pair's centroid (the bolt axis for the joint) of the points that changed, and the largest
   distance of an active point (the edge of the contact zone). */
static PetscErrorCode BoltContactMonitorOuter(BoltNewmark *nm, PetscInt outer, PetscInt inner, PetscInt nchanged, PetscBool cycling)
{
  BoltContactSet *c = nm->op->contact;
  const PetscInt  P = BOLTROM_MAX_PAIRS;
  PetscInt        cnt[2 * BOLTROM_MAX_PAIRS];
  PetscReal       ctr[3 * BOLTROM_MAX_PAIRS], rmin[BOLTROM_MAX_PAIRS], rmax[2 * BOLTROM_MAX_PAIRS];

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < 2 * P; p++) {
    cnt[p]  = 0;
    rmax[p] = 0;
  }
  for (PetscInt p = 0; p < P; p++) rmin[p] = PETSC_MAX_REAL;
  for (PetscInt p = 0; p < 3 * P; p++) ctr[p] = 0;
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt q = 0; q < 4; q++)
      for (PetscInt a = 0; a < 4; a++)
        for (PetscInt d = 0; d < 3; d++) ctr[3 * c->elem[e].pair + d] += c->gpW[4 * e + q] * c->gpN[16 * e + 4 * q + a] * c->elem[e].Xa[3 * a + d] / c->areaPerPair[c->elem[e].pair];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ctr, 3 * P, MPIU_REAL, MPI_SUM, nm->op->comm));
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt  gp = 4 * e + q, p = c->elem[e].pair;
      PetscReal x[3] = {0, 0, 0}, r;
      for (PetscInt a = 0; a < 4; a++)
        for (PetscInt d = 0; d < 3; d++) x[d] += c->gpN[16 * e + 4 * q + a] * c->elem[e].Xa[3 * a + d];
      r = PetscSqrtReal(PetscSqr(x[0] - ctr[3 * p]) + PetscSqr(x[1] - ctr[3 * p + 1]));
      if (c->active[gp]) rmax[P + p] = PetscMax(rmax[P + p], r);
      if (c->active[gp] == c->activeOld[gp]) continue;
      cnt[2 * p + (c->active[gp] ? 1 : 0)]++;
      rmin[p] = PetscMin(rmin[p], r);
      rmax[p] = PetscMax(rmax[p], r);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2 * P, MPIU_INT, MPI_SUM, nm->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rmin, P, MPIU_REAL, MPI_MIN, nm->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rmax, 2 * P, MPIU_REAL, MPI_MAX, nm->op->comm));
  PetscCall(PetscPrintf(nm->op->comm, "  %s step %" PetscInt_FMT " outer %3" PetscInt_FMT ": inner %4" PetscInt_FMT " change %.3e pen %.3e | changed %" PetscInt_FMT " active %" PetscInt_FMT "%s |", nm->op->name, nm->step, outer, inner, (double)nm->lastChange, (double)nm->lastPenetration, nchanged, c->nactive, cycling ? " CYCLING" : ""));
  for (PetscInt p = 0; p < c->npairs; p++)
    if (cnt[2 * p] || cnt[2 * p + 1]) PetscCall(PetscPrintf(nm->op->comm, " %s -%" PetscInt_FMT " +%" PetscInt_FMT " at r %.2f..%.2f mm, active to %.2f mm;", c->pairName[p], cnt[2 * p], cnt[2 * p + 1], (double)(1e3 * rmin[p]), (double)(1e3 * rmax[p]), (double)(1e3 * rmax[P + p])));
  PetscCall(PetscPrintf(nm->op->comm, "\n"));
  PetscFunctionReturn(0);
}

/* Diagnostics before an active-set update: the active points whose multiplier is tensile beyond
   the band (they are about to open), and for them the normal traction smoothed through the
   nodes (nodal normal force / nodal area, interpolated back to the Gauss point): a multiplier
   that exerts a tensile force shows it in both, a spurious one in the first only. */
static PetscErrorCode BoltContactMonitorTension(BoltNewmark *nm)
{
  BoltContactSet *c = nm->op->contact;
  PetscInt        cnt[2] = {0, 0};
  PetscReal      *ts, mx[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, mn = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(4 * c->nelem + 1, &ts));
  PetscCall(BoltContactSetSmoothedNormalTraction(c, c->lambda, ts));
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscReal band = c->bandTraction[c->elem[e].pair];
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      const PetscReal *n = &c->gpNormal[3 * gp], *l = &c->lambda[3 * gp];
      PetscReal        ln = l[0] * n[0] + l[1] * n[1] + l[2] * n[2], ps = ts[gp];
      if (!c->active[gp]) continue;
      mx[2] = PetscMax(mx[2], ps);
      if (ln < band) continue;
      cnt[0]++;
      if (ps < 0) cnt[1]++;
      mx[0] = PetscMax(mx[0], ln);
      mx[1] = PetscMax(mx[1], ps);
      mn    = PetscMin(mn, ps);
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, nm->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mx, 3, MPIU_REAL, MPI_MAX, nm->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &mn, 1, MPIU_REAL, MPI_MIN, nm->op->comm));
  PetscCall(PetscPrintf(nm->op->comm, "    tension: %" PetscInt_FMT " active points with lambda_n >= band (max %.3e Pa); their nodal-smoothed traction %.3e..%.3e Pa, compressive at %" PetscInt_FMT "; max smoothed over the active set %.3e Pa\n", cnt[0], (double)mx[0], (double)mn, (double)mx[1], cnt[1], (double)mx[2]));
  PetscCall(PetscFree(ts));
  PetscFunctionReturn(0);
}

/* The preload layers bound an elastic element layer of the stud, which takes part of the
   applied force; the clamping force is what a preload means. With zero initial gaps and a fixed
   active set the static contact problem is linear in the load, so scaling the solution, the
   multipliers, the gaps and the preload vector by target / transmitted is exact. It is done
   after every inner solve of the preload, before the active set is updated: the activation band
   is absolute (metres, pascals), so the set must be judged on the tractions of the calibrated
   preload, not on those of the applied layer forces (about 15 times smaller for the joint). */
static PetscErrorCode BoltPreloadCalibrate(BoltNewmark *nm, Vec rhs0)
{
  BoltContactSet *c = nm->op->contact;
  PetscReal       force[BOLTROM_MAX_PAIRS], fmax = 0, scale;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetNormalForcePerPair(c, force));
  for (PetscInt p = 0; p < c->npairs; p++) fmax = PetscMax(fmax, PetscAbsReal(force[p]));
  PetscCheck(fmax > 0, nm->op->comm, PETSC_ERR_USER_INPUT, "The preload transmits no contact force: check the preload groups and the bolt axis (-preload_axis)");
  scale = nm->preloadTarget / fmax;
  nm->preloadScale *= scale;
  PetscCall(VecScale(nm->q, scale));
  PetscCall(VecScale(nm->op->preload, scale));
  if (rhs0 != nm->op->preload) PetscCall(VecScale(rhs0, scale));
  for (PetscInt k = 0; k < 12 * c->nelem; k++) {
    c->lambda[k] *= scale;
    c->gap[k] *= scale;
  }
  PetscFunctionReturn(0);
}

/* The dual loop for one solve: K_eff q = rhs0 - B' lambda with contact. */
static PetscErrorCode BoltDualLoop(BoltNewmark *nm, Vec rhs0, PetscBool refactor, PetscInt *nouter, PetscInt *ninner)
{
  BoltOperator   *op   = nm->op;
  BoltContactSet *c    = op->contact;
  MPI_Comm        comm = op->comm;
  PetscReal       t    = nm->step * nm->dt;
  PetscInt        outer, inner = 0, innerTotal = 0;

  PetscFunctionBeginUser;
  c->closeOnly = PETSC_FALSE;
  for (outer = 1;; outer++) {
    PetscInt  nchanged;
    PetscBool cycling;

    if (refactor) PetscCall(BoltNewmarkFactor(nm));
    /* under the penalty law the multipliers are not unknowns (zero, or a ROM's frozen preload) */
    if (!c->warmStart && c->augment) PetscCall(PetscArrayzero(c->lambda, 12 * c->nelem));
    if (nm->inner == 1 && c->augment) PetscCall(BoltInnerCG(nm, rhs0, &inner));
    else PetscCall(BoltInnerUzawa(nm, rhs0, &inner));
    innerTotal += inner;
    if (nm->calibrating) PetscCall(BoltPreloadCalibrate(nm, rhs0));
    if (nm->contactMonitor > 0 && c->augment) PetscCall(BoltContactMonitorTension(nm));
    if (nm->keepStaticActiveSet && !nm->dynamic) break;
    PetscCall(BoltContactSetUpdateActive(c, &nchanged, &cycling));
    if (nm->contactMonitor > 0) PetscCall(BoltContactMonitorOuter(nm, outer, inner, nchanged, cycling));
    if (!nchanged) break;
    refactor = PETSC_TRUE;
    /* Anti-cycling: once the set returns to the one of two iterations before, or has not settled
       in half the allowed iterations, points may only close for the rest of the step (after a
       two-set cycle its toggling points are closed first). The set can then only grow, so the
       loop ends; closed is the side that lets nothing penetrate. */
    if (nm->closeCycles && !c->closeOnly && (cycling || 2 * outer >= nm->maxOuter)) {
      PetscInt nclosed = 0;
      if (cycling) PetscCall(BoltContactSetCloseCycle(c, &nclosed));
      c->closeOnly = PETSC_TRUE;
      nm->cycles++;
      if (nm->contactMonitor > 0 || nm->cycles <= 10) PetscCall(PetscPrintf(comm, "%s step %" PetscInt_FMT ", t = %g s: the active set %s after %" PetscInt_FMT " outer iterations; from now on in this step points only close (%" PetscInt_FMT " points re-closed, %" PetscInt_FMT " active)%s\n", op->name, nm->step, (double)t, cycling ? "cycles between two sets" : "has not settled", outer, nclosed, c->nactive, nm->cycles == 10 ? "; further cycles are counted, not printed" : ""));
      continue;
    }
    if (cycling || outer >= nm->maxOuter) {
      if (cycling) nm->cycles++;
      nm->failures++;
      PetscCheck(nm->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: the active set did not settle at step %" PetscInt_FMT ", t = %g s: %s after %" PetscInt_FMT " outer iterations (%" PetscInt_FMT " points changed, %" PetscInt_FMT " active); raise -contact_max_outer or add -contact_continue to go on with a warning", op->name, nm->step, (double)t, cycling ? "it cycles between two sets" : "limit reached", outer, nchanged, c->nactive);
      PetscCall(PetscPrintf(comm, "WARNING %s: active set %s at step %" PetscInt_FMT ", t = %g s; going on\n", op->name, cycling ? "cycles between two sets" : "not settled", nm->step, (double)t));
      /* the last solve used the previous set: refactor so the next step starts consistent */
      PetscCall(BoltNewmarkFactor(nm));
      break;
    }
  }
  *nouter = outer;
  *ninner = innerTotal;
  nm->outerTotal += outer;
  nm->innerTotal += innerTotal;
  nm->outerMax = PetscMax(nm->outerMax, outer);
  nm->innerMax = PetscMax(nm->innerMax, innerTotal);
  PetscFunctionReturn(0);
}

/* The static preloaded equilibrium: K q + K_c q = F_preload - B' lambda, every point active
   at the start. Leaves q; v = a = 0. */
PetscErrorCode BoltNewmarkPreload(BoltNewmark *nm)
{
  PetscInt nout, nin;

  PetscFunctionBeginUser;
  nm->op->contact->augment = nm->op->augment; /* the contact set serves FOM and ROM: this model's law */
  nm->dynamic = PETSC_FALSE; /* the next factorisations: K + K_c */
  nm->step = 0;
  nm->preloadScale = 1.0;
  nm->calibrating  = (nm->calibratePreload && nm->preloadTarget > 0 && !nm->staticWithLoad) ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(VecCopy(nm->op->preload, nm->rhs));
  if (nm->staticWithLoad) PetscCall(VecAXPY(nm->rhs, 1.0, nm->op->load));
  PetscCall(BoltDualLoop(nm, nm->rhs, PETSC_TRUE, &nout, &nin));
  nm->staticOuter = nout;
  nm->staticInner = nin;
  nm->calibrating = PETSC_FALSE;
  PetscCall(VecZeroEntries(nm->v));
  PetscCall(VecZeroEntries(nm->acc));
  PetscFunctionReturn(0);
}

static PetscReal BoltLoadAmplitude(BoltNewmark *nm, PetscReal t)
{
  if (nm->history == BOLT_LOAD_SINE) return PetscSinReal(2 * PETSC_PI * nm->frequency * t);
  return t > 0 ? 1.0 : 0.0;
}

/* Energy of the current state: kinetic + strain (structure and contact penalty) - external work
   potential of the current load. Constant for an undamped step with a fixed active set. */
static PetscErrorCode BoltNewmarkEnergy(BoltNewmark *nm, PetscReal amp, PetscReal *E)
{
  BoltOperator *op = nm->op;
  Mat           Kc;
  PetscScalar   ek, es, ec, ef, ep;

  PetscFunctionBeginUser;
  PetscCall(MatMult(op->M, nm->v, nm->work));
  PetscCall(VecDot(nm->v, nm->work, &ek));
  PetscCall(MatMult(op->K, nm->q, nm->work));
  PetscCall(VecDot(nm->q, nm->work, &es));
  PetscCall(op->contactStiffness(op, &Kc));
  PetscCall(MatMult(Kc, nm->q, nm->work));
  PetscCall(VecDot(nm->q, nm->work, &ec));
  PetscCall(VecDot(nm->q, op->load, &ef));
  PetscCall(VecDot(nm->q, op->preload, &ep));
  *E = 0.5 * PetscRealPart(ek + es + ec) - amp * PetscRealPart(ef) - PetscRealPart(ep);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkRun(BoltNewmark *nm)
{
  BoltOperator  *op   = nm->op;
  MPI_Comm       comm = op->comm;
  PetscReal     *a    = nm->a;
  Vec            qOld;
  PetscLogDouble t0, t1;
  PetscInt       step0;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(VecDuplicate(nm->q, &qOld));
  nm->dynamic = PETSC_TRUE; /* the next factorisations: a1 M + a4 C + K + K_c */
  nm->tOnlineBefore = nm->tCheckpoint = 0;
  /* counters from here on describe the transient; the static solve keeps its own */
  nm->staticFactorizations = nm->factorizations;
  nm->staticSolves         = nm->solves;
  nm->factorizations = nm->solves = nm->outerTotal = nm->innerTotal = nm->outerMax = nm->innerMax = 0;
  nm->tContactStiffness = nm->tDisplacements = nm->tContactForces = 0;
  nm->step = 0;
  PetscCall(op->probe(op, nm->q, &nm->probeValue[0]));
  if (nm->snapshotEvery > 0) {
    PetscCall(VecCopy(nm->q, nm->snap[0]));
    nm->snapTime[0] = 0;
    nm->nsnap       = 1;
  }
  PetscCall(BoltNewmarkEnergy(nm, 0.0, &nm->energy[0]));
  if (nm->restart) PetscCall(BoltNewmarkCheckpointRead(nm)); /* state, contact state and histories */
  step0 = nm->step;
  for (PetscInt n = step0 + 1; n <= nm->nsteps; n++) {
    PetscReal t = n * nm->dt, amp = BoltLoadAmplitude(nm, t);
    PetscInt  nout, nin;

    nm->step = n;
    /* rhs = F(t) + M (a1 q + a2 v + a3 a) + C (a4 q + a5 v + a6 a) */
    PetscCall(VecCopy(nm->q, qOld));
    PetscCall(VecCopy(nm->q, nm->work));
    PetscCall(VecAXPBYPCZ(nm->work, a[2], a[3], a[1], nm->v, nm->acc));
    PetscCall(MatMult(op->M, nm->work, nm->rhs));
    PetscCall(VecCopy(nm->q, nm->work));
    PetscCall(VecAXPBYPCZ(nm->work, a[5], a[6], a[4], nm->v, nm->acc));
    PetscCall(MatMultAdd(op->C, nm->work, nm->rhs, nm->rhs));
    PetscCall(VecAXPY(nm->rhs, amp, op->load));
    PetscCall(VecAXPY(nm->rhs, 1.0, op->preload));
    PetscCall(BoltDualLoop(nm, nm->rhs, n == step0 + 1 ? PETSC_TRUE : PETSC_FALSE, &nout, &nin));
    /* a_new = a1 (q - q_old) - a2 v - a3 a;  v_new = v + dt ((1 - gamma) a + gamma a_new) */
    PetscCall(VecWAXPY(nm->work, -1.0, qOld, nm->q));
    PetscCall(VecAXPBYPCZ(nm->work, -a[2], -a[3], a[1], nm->v, nm->acc));
    PetscCall(VecAXPBYPCZ(nm->v, (1 - nm->gamma) * nm->dt, nm->gamma * nm->dt, 1.0, nm->acc, nm->work));
    PetscCall(VecCopy(nm->work, nm->acc));
    nm->probeTime[n] = t;
    if (nm->snapshotEvery > 0 && n % nm->snapshotEvery == 0) {
      PetscCall(VecCopy(nm->q, nm->snap[nm->nsnap]));
      nm->snapTime[nm->nsnap++] = t;
    }
    PetscCall(op->probe(op, nm->q, &nm->probeValue[n]));
    PetscCall(BoltNewmarkEnergy(nm, amp, &nm->energy[n]));
    if (nm->monitor) PetscCall(PetscPrintf(comm, "%s step %5" PetscInt_FMT " t %.6e outer %2" PetscInt_FMT " inner %3" PetscInt_FMT " active %" PetscInt_FMT "/%" PetscInt_FMT " energy %.10e probe %.6e\n", op->name, n, (double)t, nout, nin, op->contact->nactive, op->contact->ngpGlobal, (double)nm->energy[n], (double)nm->probeValue[n]));
    if (nm->checkpointEvery > 0 && n % nm->checkpointEvery == 0) {
      PetscLogDouble tc0, tc1;
      PetscCall(PetscTime(&tc0));
      nm->tOnline = nm->tOnlineBefore + (tc0 - t0) - nm->tCheckpoint;
      PetscCall(BoltNewmarkCheckpointWrite(nm));
      PetscCall(PetscTime(&tc1));
      nm->tCheckpoint += tc1 - tc0;
    }
  }
  PetscCall(VecDestroy(&qOld));
  PetscCall(PetscTime(&t1));
  nm->tOnline = nm->tOnlineBefore + (t1 - t0) - nm->tCheckpoint;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkView(BoltNewmark *nm, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s Newmark (beta %g, gamma %g), dt %g s, %" PetscInt_FMT " steps: %" PetscInt_FMT " factorisations, %" PetscInt_FMT " solves, outer %" PetscInt_FMT " (max %" PetscInt_FMT "), inner %" PetscInt_FMT " (max %" PetscInt_FMT "/step)\n", nm->op->name, (double)nm->beta, (double)nm->gamma, (double)nm->dt, nm->nsteps, nm->factorizations, nm->solves, nm->outerTotal, nm->outerMax, nm->innerTotal, nm->innerMax));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  online %.3f s: contact stiffness %.3f s, displacements %.3f s, contact forces %.3f s\n", (double)nm->tOnline, (double)nm->tContactStiffness, (double)nm->tDisplacements, (double)nm->tContactForces));
  PetscFunctionReturn(0);
}

/* After the run: frees the factorisation and the effective matrices, keeping the histories and
   the final state (a run that is over does not need them; they are the largest part of it). */
PetscErrorCode BoltNewmarkReleaseSolver(BoltNewmark *nm)
{
  PetscFunctionBeginUser;
  PetscCall(KSPReset(nm->ksp));
  PetscCall(MatDestroy(&nm->Keff));
  PetscFunctionReturn(0);
}

/* The static preloaded state just solved (call after BoltNewmarkPreload, before the transient). */
PetscErrorCode BoltNewmarkPreloadStateGet(BoltNewmark *nm, BoltPreloadState **stp)
{
  BoltContactSet   *c = nm->op->contact;
  BoltPreloadState *st;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&st));
  PetscCall(VecDuplicate(nm->q, &st->q));
  PetscCall(VecCopy(nm->q, st->q));
  PetscCall(VecDuplicate(nm->op->preload, &st->preload));
  PetscCall(VecCopy(nm->op->preload, st->preload));
  PetscCall(PetscMalloc2(12 * c->nelem + 1, &st->lambda, 4 * c->nelem + 1, &st->active));
  PetscCall(PetscArraycpy(st->lambda, c->lambda, 12 * c->nelem));
  PetscCall(PetscArraycpy(st->active, c->active, 4 * c->nelem));
  st->outer   = nm->staticOuter;
  st->inner   = nm->staticInner;
  *stp        = st;
  PetscFunctionReturn(0);
}

/* Puts a preloaded state in place of BoltNewmarkPreload's solve, on an operator of the same
   scene (same contact set, same layout): q, the calibrated preload, the multipliers and the
   active set, with every contact element due for a stiffness update. */
PetscErrorCode BoltNewmarkPreloadStateSet(BoltNewmark *nm, const BoltPreloadState *st)
{
  BoltContactSet *c = nm->op->contact;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(st->q, nm->q));
  PetscCall(VecCopy(st->preload, nm->op->preload));
  PetscCall(VecZeroEntries(nm->v));
  PetscCall(VecZeroEntries(nm->acc));
  PetscCall(PetscArraycpy(c->lambda, st->lambda, 12 * c->nelem));
  PetscCall(BoltContactSetSetActive(c, st->active));
  nm->step         = 0;
  nm->staticOuter  = st->outer;
  nm->staticInner  = st->inner;
  nm->preloadScale = 1.0;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltPreloadStateDestroy(BoltPreloadState **stp)
{
  BoltPreloadState *st = *stp;

  PetscFunctionBeginUser;
  if (!st) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&st->q));
  PetscCall(VecDestroy(&st->preload));
  PetscCall(PetscFree2(st->lambda, st->active));
  PetscCall(PetscFree(*stp));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkDestroy(BoltNewmark **nmp)
{
  BoltNewmark *nm = *nmp;

  PetscFunctionBeginUser;
  if (!nm) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&nm->q));
  PetscCall(VecDestroy(&nm->v));
  PetscCall(VecDestroy(&nm->acc));
  PetscCall(VecDestroy(&nm->rhs));
  PetscCall(VecDestroy(&nm->Fc));
  PetscCall(VecDestroy(&nm->work));
  PetscCall(VecDestroy(&nm->qp));
  PetscCall(VecDestroy(&nm->FcLambda));
  PetscCall(PetscFree3(nm->cgR, nm->cgP, nm->cgAp));
  PetscCall(MatDestroy(&nm->Keff));
  PetscCall(KSPDestroy(&nm->ksp));
  PetscCall(PetscFree3(nm->probeTime, nm->probeValue, nm->energy));
  if (nm->snap) PetscCall(VecDestroyVecs(nm->nsteps / nm->snapshotEvery + 1, &nm->snap));
  PetscCall(PetscFree(nm->snapTime));
  PetscCall(PetscFree(*nmp));
  PetscFunctionReturn(0);
}
