/* The dual contact loop (the paper's Algorithm 1), written once against BoltOperator so that the
   full and the reduced model, in time steps and in the offline static solves, run the same code.
   Outer loop: the active set, until it stops changing; inner loop: the multipliers of that set,
   by a registered inner solver, until they stop changing and the penetration is small. */
#include "private/solve.h"

/* The active set judged on the last solve: the opening test's tractions (the model's own way, if
   it has one), then the state's decisions. */
static PetscErrorCode BoltDualUpdateActive(BoltDual *d, PetscInt *nchanged, PetscBool *cycling)
{
  BoltOperator *op = d->op;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
  /* a settled set that the model proves unchanged: the update would leave the state as it is */
  if (op->ops.setKept && BoltContactStateSettled(op->state)) {
    PetscBool kept;
    PetscCall(op->ops.setKept(op, &kept));
    if (kept) {
      *nchanged = 0;
      *cycling  = PETSC_FALSE;
      d->keptUpdates++;
      PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
      PetscFunctionReturn(0);
    }
  }
  if (op->ops.openTraction) PetscCall(op->ops.openTraction(op, d->tnOpen));
  else PetscCall(BoltContactStateOpenTraction(op->state, d->tnOpen));
  PetscCall(BoltContactStateUpdateActive(op->state, d->tnOpen, nchanged, cycling));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualCreate(BoltOperator *op, BoltDual **dp)
{
  BoltDual *d;

  PetscFunctionBeginUser;
  PetscCall(BoltDualInnerRegisterAll());
  PetscCall(PetscNew(&d));
  d->op             = op;
  d->maxOuter       = 20;
  d->maxInner       = 5000;
  d->tolLambda      = 1e-4;
  d->tolPenetration = 1e-9;
  d->tolFriction    = 1e-7;
  d->warmStart      = PETSC_TRUE;
  d->extrapolate    = PETSC_TRUE;
  d->closeCycles    = PETSC_TRUE;
  d->preloadScale   = 1.0;
  d->checkEvery     = 25; /* docs/decisions.md */
  PetscCall(PetscStrncpy(d->innerType, "cg", sizeof(d->innerType)));
  *dp = d;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualSetFromOptions(BoltDual *d)
{
  MPI_Comm comm = d->op->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Contact loop", "boltrom");
  PetscCall(PetscOptionsFList("-contact_inner", "Inner loop: uzawa (augmentations, as the paper) or cg (conjugate gradients on the multipliers, same fixed point, fewer solves)", "BoltDual", BoltDualInnerList, d->innerType, d->innerType, sizeof(d->innerType), NULL));
  PetscCall(PetscOptionsInt("-contact_max_outer", "Outer (active set) iterations per step (strict law: active sets per step)", NULL, d->maxOuter, &d->maxOuter, NULL));
  PetscCall(PetscOptionsInt("-contact_max_inner", "Inner (augmentation) iterations per outer iteration (strict law: solves per step)", NULL, d->maxInner, &d->maxInner, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_lambda", "Tolerance on the relative change of the multipliers", NULL, d->tolLambda, &d->tolLambda, NULL));
  PetscCall(PetscOptionsReal("-contact_tol_penetration", "Tolerance on the largest penetration of an active point [m] (strict law: 1e-9 x the shortest contact-face edge; stick law: 1e-9 m)", NULL, d->tolPenetration, &d->tolPenetration, &d->tolPenetrationSet));
  PetscCall(PetscOptionsReal("-contact_tol_friction", "Coulomb friction: tolerance on the largest change of a slipping pair's tangential traction after a solve, relative to the largest contact pressure", NULL, d->tolFriction, &d->tolFriction, NULL));
  PetscCall(PetscOptionsBool("-contact_warm_start", "Start each outer iteration from the last multipliers (false: from zero, as the paper)", NULL, d->warmStart, &d->warmStart, NULL));
  PetscCall(PetscOptionsBool("-contact_cycle_close", "When the active set cycles or has not settled in half of -contact_max_outer, points may only close for the rest of the step", NULL, d->closeCycles, &d->closeCycles, NULL));
  PetscCall(PetscOptionsBool("-contact_extrapolate", "Strict law: start each step's loop from the multipliers of the last two steps, extrapolated linearly in time", NULL, d->extrapolate, &d->extrapolate, NULL));
  PetscCall(PetscOptionsBool("-contact_continue", "On non-convergence, warn and go on instead of stopping", NULL, d->continueOnFailure, &d->continueOnFailure, NULL));
  PetscCall(PetscOptionsInt("-contact_check_every", "Check every node pair's contact conditions (held ones included) after every k-th step of the transient; 0: never", NULL, d->checkEvery, &d->checkEvery, NULL));
  PetscCall(PetscOptionsInt("-contact_monitor", "Print the contact loop: 1 a line per outer iteration, 2 also per inner CG iteration", NULL, d->monitor, &d->monitor, NULL));
  PetscOptionsEnd();
  PetscCheck(d->maxOuter >= 1 && d->maxInner >= 1, comm, PETSC_ERR_USER_INPUT, "-contact_max_outer and -contact_max_inner must be >= 1");
  PetscCheck(d->checkEvery >= 0, comm, PETSC_ERR_USER_INPUT, "-contact_check_every must be >= 0 (0: no check)");
  PetscCall(PetscFunctionListFind(BoltDualInnerList, d->innerType, &d->inner));
  PetscCheck(d->inner, comm, PETSC_ERR_USER_INPUT, "Unknown -contact_inner %s: use uzawa or cg", d->innerType);
  PetscFunctionReturn(0);
}

/* The effective matrix's pattern, its direct solver (prefix fom_ or rom_), the work space. */
PetscErrorCode BoltDualSetUp(BoltDual *d)
{
  BoltOperator *op = d->op;
  PetscInt      ng = 12 * BoltContactSetElementCount(op->contact) + 1;
  Mat           Kc, Z;

  PetscFunctionBeginUser;
  if (BoltContactStateIsComplementarity(op->state) && !d->tolPenetrationSet) d->tolPenetration = BoltContactSetGapTolerance(op->contact);
  PetscCall(MatCreateVecs(op->K, &d->Fc, NULL));
  PetscCall(VecDuplicate(d->Fc, &d->work));
  PetscCall(VecDuplicate(d->Fc, &d->qp));
  PetscCall(VecDuplicate(d->Fc, &d->FcLambda));
  PetscCall(PetscMalloc4(ng, &d->cgR, ng, &d->cgP, ng, &d->cgAp, 4 * BoltContactSetElementCount(op->contact) + 1, &d->tnOpen));
  /* K_eff gets the union of the structural and the contact pattern once, so that it keeps one
     pattern and MUMPS repeats only the numeric factorisation */
  PetscCall(op->ops.contactStiffness(op, &Kc));
  PetscCall(MatDuplicate(Kc, MAT_DO_NOT_COPY_VALUES, &Z));
  PetscCall(MatDuplicate(op->K, MAT_COPY_VALUES, &d->Keff));
  PetscCall(MatAXPY(d->Keff, 1.0, Z, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&Z));
  {
    /* K_eff is symmetric (the stick penalty is): Cholesky (LDL' in MUMPS) halves the factor */
    PetscBool set, sym;
    PetscCall(MatIsSymmetricKnown(op->K, &set, &sym));
    if (set && sym) PetscCall(MatSetOption(d->Keff, MAT_SYMMETRIC, PETSC_TRUE));
    PetscCall(BoltDirectSolverCreate(PetscObjectComm((PetscObject)op->K), op->prefix, NULL, (PetscBool)(set && sym), op->solverType, &d->ksp));
  }
  PetscFunctionReturn(0);
}

/* The next factorisations: K + K_c (static), or a1 M + a4 C + K + K_c (a Newmark step). */
PetscErrorCode BoltDualSetEffective(BoltDual *d, PetscBool dynamic, PetscReal massCoef, PetscReal dampingCoef)
{
  PetscFunctionBeginUser;
  d->dynamic     = dynamic;
  d->massCoef    = massCoef;
  d->dampingCoef = dampingCoef;
  PetscFunctionReturn(0);
}

/* The preload layers bound an elastic element layer of the stud, which takes part of the
   applied force; the clamping force is what a preload means. With zero initial gaps and a fixed
   active set the static contact problem is linear in the load, so scaling the solution, the
   multipliers, the gaps and the preload vector by target / transmitted is exact. It is done
   after every inner solve of the preload, before the active set is updated: the activation band
   is absolute (metres, pascals), so the set must be judged on the tractions of the calibrated
   preload, not on those of the applied layer forces (about 15 times smaller for the joint). */
static PetscErrorCode BoltDualCalibrate(BoltDual *d, Vec rhs0, Vec q)
{
  BoltContactState *s = d->op->state;
  BoltContactSet   *c = BoltContactStateSet(s);
  PetscReal         force[BOLTROM_MAX_PAIRS], fmax = 0, scale;

  PetscFunctionBeginUser;
  PetscCall(BoltContactStateNormalForcePerPair(s, force));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) fmax = PetscMax(fmax, PetscAbsReal(force[p]));
  PetscCheck(fmax > 0, d->op->comm, PETSC_ERR_USER_INPUT, "The preload transmits no contact force: check the preload groups and the bolt axis (-preload_axis)");
  scale = d->preloadTarget / fmax;
  d->preloadScale *= scale;
  PetscCall(VecScale(q, scale));
  PetscCall(VecScale(d->op->preload, scale));
  if (rhs0 != d->op->preload) PetscCall(VecScale(rhs0, scale));
  {
    PetscReal *lambda = BoltContactStateLambda(s), *gap = BoltContactStateGap(s), *anchor = BoltContactStateAnchor(s);
    for (PetscInt k = 0; k < 12 * BoltContactSetElementCount(c); k++) {
      lambda[k] *= scale;
      gap[k] *= scale;
      anchor[k] *= scale; /* the preload's problem is linear in its scale, positions included */
    }
  }
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* One solve's outer and inner iterations, returned and added to the loop's counters. */
static PetscErrorCode BoltDualCount(BoltDual *d, PetscInt outer, PetscInt inner, PetscInt *nouter, PetscInt *ninner)
{
  PetscFunctionBeginUser;
  *nouter = outer;
  *ninner = inner;
  d->outerTotal += outer;
  d->innerTotal += inner;
  d->outerMax = PetscMax(d->outerMax, outer);
  d->innerMax = PetscMax(d->innerMax, inner);
  PetscFunctionReturn(0);
}

/* Anti-cycling (-contact_cycle_close): after a two-set cycle the toggling points are closed, and
   for the rest of the step points may only close, so the set can only grow and the loop ends. */
static PetscErrorCode BoltDualCloseOnly(BoltDual *d, PetscBool cycling, PetscInt sets)
{
  BoltContactState *s       = d->op->state;
  PetscInt          nclosed = 0;

  PetscFunctionBeginUser;
  if (cycling) PetscCall(BoltContactStateCloseCycle(s, &nclosed));
  PetscCall(BoltContactStateSetCloseOnly(s, PETSC_TRUE));
  d->cycles++;
  if (d->monitor > 0 || d->cycles <= 10) PetscCall(PetscPrintf(d->op->comm, "%s step %" PetscInt_FMT ", t = %g s: the active set %s after %" PetscInt_FMT " outer iterations; from now on in this step points only close (%" PetscInt_FMT " points re-closed, %" PetscInt_FMT " active)%s\n", d->op->name, d->step, (double)d->time, cycling ? "cycles between two sets" : "has not settled", sets, nclosed, BoltContactStateActiveCount(s), d->cycles == 10 ? "; further cycles are counted, not printed" : ""));
  PetscFunctionReturn(0);
}

/* The strict law's loop: the active set and the multipliers are updated together after every
   solve (a primal-dual active-set iteration on the augmented Lagrangian). Each iteration solves
   with the current multipliers and the stiff penalty of the closed pairs, takes the trial
   tractions lambda + P g as the new multipliers (they balance the solved displacement exactly),
   and re-decides every node pair from them: a closed pair opens under tension, an open one
   closes when it penetrates. The loop ends when the set holds and no closed pair is off its
   contact by more than the tolerance; the multipliers' error is then that tolerance times the
   structure's stiffness, not times the penalty. Warm-started from the last step, a step in
   which the set does not change costs one solve; a set change costs a factorisation. */
static PetscErrorCode BoltDualSolveActiveSet(BoltDual *d, Vec rhs0, Vec q, PetscBool refactor, PetscInt *nouter, PetscInt *ninner)
{
  BoltOperator     *op   = d->op;
  BoltContactState *s    = op->state;
  MPI_Comm          comm = op->comm;
  PetscInt          sets = 1, solves = 0, frictionStall = 0;
  PetscReal         frictionBest = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(BoltContactStateSetCloseOnly(s, PETSC_FALSE));
  if (d->extrapolate && d->dynamic) BoltContactStateExtrapolate(s);
  for (;;) {
    PetscInt  nchanged;
    PetscBool cycling;
    PetscReal rel, viol;

    if (refactor) PetscCall(BoltDualFactor(d));
    refactor = PETSC_FALSE;
    PetscCall(BoltDualSolveWithForces(d, rhs0, BoltContactStateForceMultipliers(s), q));
    PetscCall(BoltDualGapsOf(d, q, BoltContactStateGap(s)));
    BoltContactStateAnchorGaps(s, BoltContactStateGap(s));
    solves++;
    PetscCall(PetscLogEventBegin(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
    PetscCall(BoltContactStateAugment(s, &rel, &viol));
    PetscCall(PetscLogEventEnd(BOLT_EVENT_CONTACT_UPDATE, 0, 0, 0, 0));
    PetscCheck(!PetscIsInfOrNanReal(rel) && !PetscIsInfOrNanReal(viol), comm, PETSC_ERR_FP, "%s: NaN in the contact loop at step %" PetscInt_FMT ", t = %g s", op->name, d->step, (double)d->time);
    d->lastChange      = rel;
    d->lastPenetration = viol;
    if (d->calibrating) PetscCall(BoltDualCalibrate(d, rhs0, q));
    if (d->keepActiveSet && !d->dynamic) {
      cycling = PETSC_FALSE;
      nchanged = 0;
      if (BoltContactStateHasFriction(s) && !BoltContactStateStickOnly(s)) { /* the set kept; its closed pairs still stick or slip (a ROM's preload, as the FOM's) */
        PetscCall(BoltContactStateSetHoldContact(s, PETSC_TRUE));
        PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
        PetscCall(BoltContactStateSetHoldContact(s, PETSC_FALSE));
      }
    } else PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
    if (d->monitor > 0) PetscCall(BoltContactMonitorOuter(d, sets, solves, nchanged, cycling));
    if (!nchanged && viol <= d->tolPenetration && (!BoltContactStateHasFriction(s) || BoltContactStateFrictionChange(s) <= d->tolFriction)) break;
    /* friction at its rounding floor: the set holds, and the slipping tractions' residual, within
       ten times the tolerance, has not halved in five solves (a reduced model's gaps, differences
       of basis rows, are that much less precise than the full model's) */
    if (BoltContactStateHasFriction(s) && !nchanged && viol <= d->tolPenetration) {
      if (BoltContactStateFrictionChange(s) < 0.5 * frictionBest) {
        frictionBest = BoltContactStateFrictionChange(s);
        frictionStall = 0;
      } else if (++frictionStall >= 5 && BoltContactStateFrictionChange(s) <= 10 * d->tolFriction) break;
    } else frictionBest = PETSC_MAX_REAL, frictionStall = 0;
    if (nchanged) {
      sets++;
      refactor = PETSC_TRUE;
      if (d->closeCycles && !BoltContactStateCloseOnly(s) && (cycling || 2 * sets >= d->maxOuter)) PetscCall(BoltDualCloseOnly(d, cycling, sets));
    }
    if ((nchanged && (sets > d->maxOuter || (cycling && !d->closeCycles))) || solves >= d->maxInner) {
      d->failures++;
      char friction[160] = "";

      if (BoltContactStateHasFriction(s)) PetscCall(PetscSNPrintf(friction, sizeof(friction), ", and the slipping pairs' tractions move by %.3e of the largest pressure (tolerance %.1e: -contact_tol_friction)", (double)BoltContactStateFrictionChange(s), (double)d->tolFriction));
      PetscCheck(d->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: the contact loop did not converge at step %" PetscInt_FMT ", t = %g s: after %" PetscInt_FMT " solves and %" PetscInt_FMT " active sets, %" PetscInt_FMT " pairs changed and a closed pair is off its contact by %.3e m (tolerance %.1e)%s; raise -contact_max_outer / -contact_max_inner or add -contact_continue to go on with a warning", op->name, d->step, (double)d->time, solves, sets, nchanged, (double)viol, (double)d->tolPenetration, friction);
      PetscCall(PetscPrintf(comm, "WARNING %s: contact loop not converged at step %" PetscInt_FMT ", t = %g s; going on\n", op->name, d->step, (double)d->time));
      if (refactor) PetscCall(BoltDualFactor(d)); /* the next step starts consistent */
      break;
    }
  }
  {
    PetscReal pen, ten, comp, prod;
    PetscCall(BoltContactStateComplementarity(s, &pen, &ten, &comp, &prod));
    d->worstPenetration = PetscMax(d->worstPenetration, pen);
    d->worstTension     = PetscMax(d->worstTension, ten);
    d->worstCompression = PetscMax(d->worstCompression, comp);
    d->worstProduct     = PetscMax(d->worstProduct, prod);
  }
  if (d->dynamic) BoltContactStateEndStep(s);
  BoltContactStateEndSolve(s, d->dynamic);
  PetscCall(BoltDualCount(d, sets, solves, nouter, ninner));
  PetscFunctionReturn(0);
}

/* The dual loop for one solve: K_eff q = rhs0 - B' lambda with contact. */
PetscErrorCode BoltDualSolve(BoltDual *d, Vec rhs0, Vec q, PetscBool refactor, PetscInt *nouter, PetscInt *ninner)
{
  BoltOperator     *op   = d->op;
  BoltContactState *s    = op->state;
  MPI_Comm          comm = op->comm;
  PetscInt          outer, inner = 0, innerTotal = 0;

  PetscFunctionBeginUser;
  if (BoltContactStateLambdaIsTraction(s)) {
    PetscCall(BoltDualSolveActiveSet(d, rhs0, q, refactor, nouter, ninner));
    PetscFunctionReturn(0);
  }
  PetscCall(BoltContactStateSetCloseOnly(s, PETSC_FALSE));
  for (outer = 1;; outer++) {
    PetscInt  nchanged;
    PetscBool cycling;

    if (refactor) PetscCall(BoltDualFactor(d));
    /* under the penalty law the multipliers are not unknowns (zero, or a ROM's frozen preload) */
    if (!d->warmStart && BoltContactStateAugmented(s)) {
      PetscCall(PetscArrayzero(BoltContactStateLambda(s), 12 * BoltContactSetElementCount(op->contact)));
      BoltContactStateChanged(s);
    }
    PetscCall((*d->inner)(d, rhs0, q, &inner));
    innerTotal += inner;
    if (d->calibrating) PetscCall(BoltDualCalibrate(d, rhs0, q));
    if (d->monitor > 0 && BoltContactStateAugmented(s)) PetscCall(BoltContactMonitorTension(d));
    if (d->keepActiveSet && !d->dynamic) break;
    PetscCall(BoltDualUpdateActive(d, &nchanged, &cycling));
    if (d->monitor > 0) PetscCall(BoltContactMonitorOuter(d, outer, inner, nchanged, cycling));
    if (!nchanged) break;
    refactor = PETSC_TRUE;
    /* Anti-cycling: once the set returns to the one of two iterations before, or has not settled
       in half the allowed iterations, points may only close for the rest of the step (after a
       two-set cycle its toggling points are closed first). The set can then only grow, so the
       loop ends; closed is the side that lets nothing penetrate. */
    if (d->closeCycles && !BoltContactStateCloseOnly(s) && (cycling || 2 * outer >= d->maxOuter)) {
      PetscCall(BoltDualCloseOnly(d, cycling, outer));
      continue;
    }
    if (cycling || outer >= d->maxOuter) {
      if (cycling) d->cycles++;
      d->failures++;
      PetscCheck(d->continueOnFailure, comm, PETSC_ERR_NOT_CONVERGED, "%s: the active set did not settle at step %" PetscInt_FMT ", t = %g s: %s after %" PetscInt_FMT " outer iterations (%" PetscInt_FMT " points changed, %" PetscInt_FMT " active); raise -contact_max_outer or add -contact_continue to go on with a warning", op->name, d->step, (double)d->time, cycling ? "it cycles between two sets" : "limit reached", outer, nchanged, BoltContactStateActiveCount(s));
      PetscCall(PetscPrintf(comm, "WARNING %s: active set %s at step %" PetscInt_FMT ", t = %g s; going on\n", op->name, cycling ? "cycles between two sets" : "not settled", d->step, (double)d->time));
      /* the last solve used the previous set: refactor so the next step starts consistent */
      PetscCall(BoltDualFactor(d));
      break;
    }
  }
  PetscCall(BoltDualCount(d, outer, innerTotal, nouter, ninner));
  PetscFunctionReturn(0);
}

/* A static contact solve (K + K_c) q = rhs - B' lambda from the current contact state. With
   target > 0 the preload is calibrated on the way to that clamping force [N]: q, the operator's
   preload, rhs and the multipliers are scaled, and preloadScale says by how much. */
PetscErrorCode BoltDualSolveStatic(BoltDual *d, Vec rhs, Vec q, PetscReal target, PetscInt *nouter, PetscInt *ninner)
{
  PetscFunctionBeginUser;
  PetscCall(BoltDualSetEffective(d, PETSC_FALSE, 0, 0));
  d->step          = 0;
  d->time          = 0;
  d->preloadScale  = 1.0;
  d->preloadTarget = target;
  d->calibrating   = target > 0 ? PETSC_TRUE : PETSC_FALSE;
  BoltContactStateStaticStart(d->op->state);
  PetscCall(BoltDualSolve(d, rhs, q, PETSC_TRUE, nouter, ninner));
  d->calibrating = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualResetCounters(BoltDual *d)
{
  PetscFunctionBeginUser;
  d->factorizations = d->updates = d->solves = d->outerTotal = d->innerTotal = d->outerMax = d->innerMax = d->keptUpdates = 0;
  d->worstPenetration = d->worstTension = d->worstCompression = d->worstProduct = 0;
  d->tContactStiffness = d->tDisplacements = d->tContactForces = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualView(BoltDual *d, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  contact loop (%s inner): %" PetscInt_FMT " factorisations, %" PetscInt_FMT " low-rank updates, %" PetscInt_FMT " solves, outer %" PetscInt_FMT " (max %" PetscInt_FMT "), inner %" PetscInt_FMT " (max %" PetscInt_FMT "/solve)\n", d->innerType, d->factorizations, d->updates, d->solves, d->outerTotal, d->outerMax, d->innerTotal, d->innerMax));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  phases: contact stiffness %.3f s, displacements %.3f s, contact forces %.3f s\n", (double)d->tContactStiffness, (double)d->tDisplacements, (double)d->tContactForces));
  PetscFunctionReturn(0);
}

/* Frees the factorisation and the effective matrix (the largest part of a finished run). */
PetscErrorCode BoltDualReleaseSolver(BoltDual *d)
{
  PetscFunctionBeginUser;
  if (d->ksp) PetscCall(KSPReset(d->ksp));
  PetscCall(MatDestroy(&d->Keff));
  PetscCall(MatDestroy(&d->Kstruct));
  PetscFunctionReturn(0);
}

/* Whether a static solve keeps the active set it is given (a time step judges it always). */
PetscErrorCode BoltDualSetKeepActiveSet(BoltDual *d, PetscBool keep)
{
  PetscFunctionBeginUser;
  d->keepActiveSet = keep;
  PetscFunctionReturn(0);
}

/* The effective matrix's coefficients: whether it is a time step's, and its mass and damping
   factors (K + massCoef M + dampingCoef C). */
PetscErrorCode BoltDualGetEffective(BoltDual *d, PetscBool *dynamic, PetscReal *massCoef, PetscReal *dampingCoef)
{
  PetscFunctionBeginUser;
  *dynamic     = d->dynamic;
  *massCoef    = d->massCoef;
  *dampingCoef = d->dampingCoef;
  PetscFunctionReturn(0);
}

/* Time spent updating the factorisation to a new contact stiffness by the operator's own means
   (a low-rank update counts as one update). */
PetscErrorCode BoltDualLogStiffnessUpdate(BoltDual *d, PetscLogDouble seconds, PetscBool update)
{
  PetscFunctionBeginUser;
  d->tContactStiffness += seconds;
  if (update) d->updates++;
  PetscFunctionReturn(0);
}

/* The operator and the solver of its factorised effective matrix (both the loop's). */
PetscErrorCode BoltDualGetSolver(BoltDual *d, BoltOperator **op, KSP *ksp)
{
  PetscFunctionBeginUser;
  if (op) *op = d->op;
  if (ksp) *ksp = d->ksp;
  PetscFunctionReturn(0);
}

/* The last solve's largest penetration [m] and relative change of the multipliers. */
PetscErrorCode BoltDualGetLastConvergence(BoltDual *d, PetscReal *penetration, PetscReal *change)
{
  PetscFunctionBeginUser;
  *penetration = d->lastPenetration;
  *change      = d->lastChange;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltDualDestroy(BoltDual **dp)
{
  BoltDual *d = *dp;

  PetscFunctionBeginUser;
  if (!d) PetscFunctionReturn(0);
  PetscCall(PetscFree(d->checkGaps));
  PetscCall(PetscFree2(d->checkAnchored, d->checkTn));
  PetscCall(VecDestroy(&d->Fc));
  PetscCall(VecDestroy(&d->work));
  PetscCall(VecDestroy(&d->qp));
  PetscCall(VecDestroy(&d->FcLambda));
  PetscCall(PetscFree4(d->cgR, d->cgP, d->cgAp, d->tnOpen));
  PetscCall(MatDestroy(&d->Keff));
  PetscCall(MatDestroy(&d->Kstruct));
  PetscCall(KSPDestroy(&d->ksp));
  PetscCall(PetscFree(*dp));
  PetscFunctionReturn(0);
}
