/* Newmark time integration, written once against BoltOperator so that the full and the reduced
   model run literally the same code: the static preloaded start, then the time steps, each one
   a solve of the dual contact loop (BoltDual, dual.c) on the effective system. */
#include "private/solve.h"

/* The static start's defaults: the preload calibrated to its clamp force, the load not carried. */
static PetscErrorCode BoltNewmarkStaticStartDefaults(PetscBool *calibrate, PetscBool *withLoad)
{
  PetscFunctionBeginUser;
  *calibrate = PETSC_TRUE;
  *withLoad  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The static start's two scene options (-preload_calibrate, -static_contact_load) as a time
   integrator of this run reads them: for the ROM's offline static solves and its file's
   fingerprint, which run without one. */
PetscErrorCode BoltNewmarkStaticStartOptions(PetscBool *calibrate, PetscBool *withLoad)
{
  PetscFunctionBeginUser;
  PetscCall(BoltNewmarkStaticStartDefaults(calibrate, withLoad));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-preload_calibrate", calibrate, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-static_contact_load", withLoad, NULL));
  PetscFunctionReturn(0);
}

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
  nm->sweepStart     = 0.1;
  PetscCall(BoltNewmarkStaticStartDefaults(&nm->calibratePreload, &nm->staticWithLoad));
  nm->preloadScale   = 1.0;
  PetscCall(PetscStrncpy(nm->checkpointBase, "output/joint", sizeof(nm->checkpointBase)));
  PetscCall(BoltDualCreate(op, &nm->dual));
  *nmp               = nm;
  PetscFunctionReturn(0);
}

static const char *const BoltLoadHistories[] = {"step", "sine", "ramp", "release", "sweep", "BoltLoadHistory", "BOLT_LOAD_", NULL};

/* The load's history as -load_history gives it (step if not given), for what is decided before
   a time integrator exists: the ROM's construction depends on whether the load is periodic. */
PetscErrorCode BoltLoadHistoryFromOptions(BoltLoadHistory *history)
{
  PetscFunctionBeginUser;
  *history = BOLT_LOAD_STEP;
  PetscCall(PetscOptionsGetEnum(NULL, NULL, "-load_history", BoltLoadHistories, (PetscEnum *)history, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkSetFromOptions(BoltNewmark *nm)
{
  MPI_Comm comm = nm->op->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Time integration", "boltrom");
  PetscCall(PetscOptionsReal("-ts_dt", "Time step [s]", NULL, nm->dt, &nm->dt, NULL));
  PetscCall(PetscOptionsReal("-ts_end", "End time [s]", NULL, nm->tEnd, &nm->tEnd, NULL));
  PetscCall(PetscOptionsReal("-newmark_beta", "Newmark beta", NULL, nm->beta, &nm->beta, NULL));
  PetscCall(PetscOptionsReal("-newmark_gamma", "Newmark gamma", NULL, nm->gamma, &nm->gamma, NULL));
  PetscCall(PetscOptionsEnum("-load_history", "Time history of the load: step, sine, ramp (to -load_ramp_time, then held), release (ramp removed at -load_release_time) or sweep", "BoltLoadHistory", BoltLoadHistories, (PetscEnum)nm->history, (PetscEnum *)&nm->history, NULL));
  PetscCall(PetscOptionsReal("-load_frequency", "Frequency of the sine load [Hz]", NULL, nm->frequency, &nm->frequency, NULL));
  PetscCall(PetscOptionsReal("-load_ramp_time", "Time at which the ramp load reaches its full value [s] (default: -ts_end)", NULL, nm->rampTime, &nm->rampTime, NULL));
  PetscCall(PetscOptionsReal("-load_release_time", "Time at which the release load drops to zero [s] (-load_history release)", NULL, nm->releaseTime, &nm->releaseTime, NULL));
  PetscCall(PetscOptionsReal("-load_sweep_start", "The stepped sine's amplitude in its first cycle, as a fraction of -load_force (-load_history sweep)", NULL, nm->sweepStart, &nm->sweepStart, NULL));
  PetscCall(PetscOptionsBool("-ts_quasistatic", "Quasi-static steps: no inertia or damping, each step the static equilibrium under its load, contact and friction state carried", NULL, nm->quasiStatic, &nm->quasiStatic, NULL));
  PetscCall(PetscOptionsBool("-static_contact_load", "The static contact solve carries the external load as well as the preload (added after the preload is calibrated alone)", NULL, nm->staticWithLoad, &nm->staticWithLoad, NULL));
  PetscCall(PetscOptionsBool("-preload_calibrate", "Scale the preload layer forces so that the bolt clamps with -preload_force (the layer between them is elastic)", NULL, nm->calibratePreload, &nm->calibratePreload, NULL));
  PetscCall(PetscOptionsInt("-snapshot_every", "Keep the displacement field every this many steps for ParaView (0: none)", NULL, nm->snapshotEvery, &nm->snapshotEvery, NULL));
  PetscCall(PetscOptionsBool("-monitor", "Print a line per time step", NULL, nm->monitor, &nm->monitor, NULL));
  PetscCall(PetscOptionsInt("-checkpoint_every", "Write a checkpoint every this many steps (0: none); files <-checkpoint_file>-fom.ckpt.h5 and -rom.ckpt.h5", NULL, nm->checkpointEvery, &nm->checkpointEvery, NULL));
  PetscCall(PetscOptionsString("-checkpoint_file", "Base name of the checkpoint files (default: <output_dir>/<output_name>)", NULL, nm->checkpointBase, nm->checkpointBase, sizeof(nm->checkpointBase), NULL));
  PetscCall(PetscOptionsBool("-restart", "Continue each model's transient from its checkpoint (same mesh, ranks, time step; -ts_end may be later)", NULL, nm->restart, &nm->restart, NULL));
  PetscOptionsEnd();
  PetscCall(BoltDualSetFromOptions(nm->dual));
  PetscCheck(nm->checkpointEvery >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_every must be >= 0 (got %" PetscInt_FMT ")", nm->checkpointEvery);
  if (nm->checkpointEvery > 0) PetscCall(BoltMakeParentDir(comm, nm->checkpointBase)); /* fail now, not at the first checkpoint */
  PetscCheck(nm->dt > 0, comm, PETSC_ERR_USER_INPUT, "-ts_dt must be > 0 (got %g)", (double)nm->dt);
  PetscCheck(nm->tEnd >= nm->dt, comm, PETSC_ERR_USER_INPUT, "-ts_end (%g) must be at least one time step -ts_dt (%g)", (double)nm->tEnd, (double)nm->dt);
  PetscCheck(nm->beta > 0 && nm->gamma >= 0.5, comm, PETSC_ERR_USER_INPUT, "Newmark needs beta > 0 and gamma >= 1/2 (got %g, %g)", (double)nm->beta, (double)nm->gamma);
  PetscCheck(nm->snapshotEvery >= 0, comm, PETSC_ERR_USER_INPUT, "-snapshot_every must be >= 0");
  PetscCheck(nm->history != BOLT_LOAD_RELEASE || (nm->rampTime > 0 && nm->releaseTime > nm->rampTime), comm, PETSC_ERR_USER_INPUT, "-load_history release needs 0 < -load_ramp_time < -load_release_time (got %g and %g)", (double)nm->rampTime, (double)nm->releaseTime);
  PetscCheck(nm->sweepStart > 0 && nm->sweepStart <= 1, comm, PETSC_ERR_USER_INPUT, "-load_sweep_start must be in (0, 1] (got %g): the first cycle's amplitude as a fraction of -load_force", (double)nm->sweepStart);
  PetscCheck(nm->history != BOLT_LOAD_SWEEP || nm->frequency > 0, comm, PETSC_ERR_USER_INPUT, "-load_history sweep needs -load_frequency > 0 (got %g)", (double)nm->frequency);
  PetscCheck(nm->rampTime >= 0, comm, PETSC_ERR_USER_INPUT, "-load_ramp_time must be >= 0 (got %g; 0: -ts_end)", (double)nm->rampTime);
  PetscFunctionReturn(0);
}

static Vec *BoltNewmarkProductVec(BoltNewmark *nm, PetscInt i)
{
  Vec *all[8] = {&nm->Mq, &nm->Mv, &nm->Ma, &nm->Kq, &nm->Kv, &nm->Ka, &nm->MvOld, &nm->KvOld};
  return all[i];
}

PetscErrorCode BoltNewmarkSetUp(BoltNewmark *nm)
{
  BoltOperator *op = nm->op;
  PetscReal     b = nm->beta, g = nm->gamma, dt = nm->dt;

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
  PetscCall(VecDuplicate(nm->q, &nm->work));
  PetscCall(PetscCalloc6(nm->nsteps + 1, &nm->probeTime, nm->nsteps + 1, &nm->probeValue, nm->nsteps + 1, &nm->energy, nm->nsteps + 1, &nm->slipping, nm->nsteps + 1, &nm->dissipated, BOLT_LEDGER * (nm->nsteps + 1), &nm->ledger));
  PetscCall(PetscCalloc1(BOLT_PAIR_FORCE * BoltContactSetPairCount(op->contact) * (nm->nsteps + 1) + 1, &nm->pairForce));
  PetscCall(VecDuplicate(nm->q, &nm->dq));
  for (PetscInt i = 0; i < 8; i++) PetscCall(VecDuplicate(nm->q, BoltNewmarkProductVec(nm, i)));
  if (nm->snapshotEvery > 0) {
    PetscInt n = nm->nsteps / nm->snapshotEvery + 1;
    PetscCall(PetscCalloc1(n, &nm->snapTime));
    PetscCall(VecDuplicateVecs(nm->q, n, &nm->snap));
    PetscCall(PetscCalloc1(n * 4 * BoltContactSetElementCount(op->contact) + 1, &nm->snapCodes));
  }
  PetscCall(BoltDualSetUp(nm->dual));
  PetscFunctionReturn(0);
}

/* The static preloaded equilibrium: K q + K_c q = F_preload - B' lambda, every point active
   at the start. Leaves q; v = a = 0. */
PetscErrorCode BoltNewmarkPreload(BoltNewmark *nm)
{
  PetscInt nout, nin;

  PetscFunctionBeginUser;
  nm->step = 0;
  PetscCall(VecCopy(nm->op->preload, nm->rhs));
  if (nm->bolts && nm->calibratePreload) { /* several bolts, each to its own clamp force */
    PetscCall(BoltNewmarkPreloadBolts(nm, &nout, &nin));
    if (nm->staticWithLoad) {
      PetscInt nout0 = nout, nin0 = nin;
      PetscCall(VecCopy(nm->op->preload, nm->rhs));
      PetscCall(VecAXPY(nm->rhs, 1.0, nm->op->load));
      PetscCall(BoltDualSolveStatic(nm->dual, nm->rhs, nm->q, 0, &nout, &nin));
      nout += nout0;
      nin += nin0;
    }
  } else if (nm->staticWithLoad && nm->calibratePreload && nm->preloadTarget > 0) {
    /* the preload is calibrated on its own (the load changes the pair forces), then the load
       is added to the calibrated preload, from that state */
    PetscInt nout0, nin0;
    PetscCall(BoltDualSolveStatic(nm->dual, nm->rhs, nm->q, nm->preloadTarget, &nout0, &nin0));
    nm->preloadScale = nm->dual->preloadScale;
    PetscCall(VecCopy(nm->op->preload, nm->rhs));
    PetscCall(VecAXPY(nm->rhs, 1.0, nm->op->load));
    PetscCall(BoltDualSolveStatic(nm->dual, nm->rhs, nm->q, 0, &nout, &nin));
    nout += nout0;
    nin += nin0;
  } else {
    if (nm->staticWithLoad) PetscCall(VecAXPY(nm->rhs, 1.0, nm->op->load));
    PetscCall(BoltDualSolveStatic(nm->dual, nm->rhs, nm->q, nm->calibratePreload ? nm->preloadTarget : 0, &nout, &nin));
    nm->preloadScale = nm->dual->preloadScale;
  }
  nm->staticOuter = nout;
  nm->staticInner = nin;
  /* a free model's static solution holds an arbitrary rigid motion (its operator is singular, the
     preload self-balanced): taken out, it changes no gap and no force */
  if (nm->rigid) PetscCall(BoltRigidProject(nm->rigid, nm->q));
  PetscCall(VecZeroEntries(nm->v));
  PetscCall(VecZeroEntries(nm->acc));
  PetscFunctionReturn(0);
}

static PetscReal BoltLoadAmplitude(BoltNewmark *nm, PetscReal t)
{
  if (nm->history == BOLT_LOAD_SINE) return PetscSinReal(2 * PETSC_PI * nm->frequency * t);
  if (nm->history == BOLT_LOAD_SWEEP) { /* cycle k of n at sweepStart^((n - 1 - k) / (n - 1)) */
    PetscInt n = PetscMax(1, (PetscInt)PetscFloorReal(nm->tEnd * nm->frequency + 0.5)), k = PetscMin(n - 1, (PetscInt)PetscFloorReal(t * nm->frequency));
    return (n > 1 ? PetscPowReal(nm->sweepStart, (PetscReal)(n - 1 - k) / (n - 1)) : 1.0) * PetscSinReal(2 * PETSC_PI * nm->frequency * t);
  }
  if (nm->history == BOLT_LOAD_RELEASE) return t < nm->releaseTime ? PetscMax(0.0, PetscMin(1.0, t / nm->rampTime)) : 0.0;
  if (nm->history == BOLT_LOAD_RAMP) return PetscMax(0.0, PetscMin(1.0, t / (nm->rampTime > 0 ? nm->rampTime : nm->tEnd)));
  return t > 0 ? 1.0 : 0.0;
}

/* Energy of the current state: kinetic + strain - external work potential of the current load,
   and under the penalty (stick) law the penalty's 1/2 q'K_c q: constant for an undamped step with
   a fixed active set. Under the strict laws K_c's penalty acts on raw displacements while the
   multipliers and anchors carry the contact force, so q'K_c q is no energy there (hundreds of J
   on a joint that took 1 J of work); their contact is in the ledger's contact work. Hands back
   v'M v and q'K q for the ledger. */
static PetscErrorCode BoltNewmarkEnergy(BoltNewmark *nm, PetscReal amp, PetscReal *E, PetscScalar *ekOut, PetscScalar *esOut)
{
  BoltOperator *op = nm->op;
  Mat           Kc;
  PetscScalar   ek, es, ec = 0, ef, ep;

  PetscFunctionBeginUser;
  PetscCall(VecDot(nm->v, nm->Mv, &ek));
  PetscCall(VecDot(nm->q, nm->Kq, &es));
  if (BoltContactStateHasPenaltyEnergy(op->state)) {
    PetscCall(op->ops.contactStiffness(op, &Kc));
    PetscCall(MatMult(Kc, nm->q, nm->work));
    PetscCall(VecDot(nm->q, nm->work, &ec));
  }
  PetscCall(VecDot(nm->q, op->load, &ef));
  PetscCall(VecDot(nm->q, op->preload, &ep));
  *E     = 0.5 * PetscRealPart(ek + es + ec) - amp * PetscRealPart(ef) - PetscRealPart(ep);
  *ekOut = ek;
  *esOut = es;
  PetscFunctionReturn(0);
}

/* Row n of the energy accounting (BoltLedger) from the step n-1 -> n: q, v and their products
   hold the new state, MvOld and KvOld the step's start, dq the displacement change; amp0, amp
   the load's amplitudes at the step's ends; ek = v'M v and es = q'K q of the new state. Row 0:
   the preloaded start. */
static PetscErrorCode BoltNewmarkLedger(BoltNewmark *nm, PetscInt n, PetscReal amp0, PetscReal amp, PetscScalar ek, PetscScalar es)
{
  BoltOperator *op = nm->op;
  PetscReal    *L  = nm->ledger;
  PetscInt      N  = nm->nsteps + 1;
  PetscScalar   wl, wp, wc = 0, dr;

  PetscFunctionBeginUser;
  L[BOLT_LEDGER_KINETIC * N + n] = 0.5 * PetscRealPart(ek);
  L[BOLT_LEDGER_STRAIN * N + n]  = 0.5 * PetscRealPart(es);
  if (n > 0) {
    PetscCall(VecDot(nm->dq, op->load, &wl));
    PetscCall(VecDot(nm->dq, op->preload, &wp));
    /* C (v + v_old), Rayleigh's: rhs is free until the next step builds it */
    PetscCall(VecWAXPY(nm->work, 1.0, nm->MvOld, nm->Mv));
    PetscCall(VecWAXPY(nm->rhs, 1.0, nm->KvOld, nm->Kv));
    PetscCall(VecAXPBY(nm->rhs, op->rayleigh[0], op->rayleigh[1], nm->work));
    PetscCall(VecDot(nm->dq, nm->rhs, &dr));
    if (BoltContactStateLambdaIsTraction(op->state)) PetscCall(BoltContactStateContactWork(op->state, &wc));
    L[BOLT_LEDGER_EXTERNAL * N + n] = L[BOLT_LEDGER_EXTERNAL * N + n - 1] + 0.5 * (amp0 + amp) * PetscRealPart(wl) + PetscRealPart(wp);
    L[BOLT_LEDGER_RAYLEIGH * N + n] = L[BOLT_LEDGER_RAYLEIGH * N + n - 1] + 0.5 * PetscRealPart(dr);
    L[BOLT_LEDGER_CONTACT * N + n]  = PetscRealPart(wc);
  } else PetscCall(BoltContactStateStickEnergy(op->state, &nm->stickEnergy0));
  L[BOLT_LEDGER_BALANCE * N + n] = L[BOLT_LEDGER_EXTERNAL * N + n] - (L[BOLT_LEDGER_KINETIC * N + n] - L[BOLT_LEDGER_KINETIC * N]) - (L[BOLT_LEDGER_STRAIN * N + n] - L[BOLT_LEDGER_STRAIN * N]) - L[BOLT_LEDGER_RAYLEIGH * N + n] - L[BOLT_LEDGER_CONTACT * N + n];
  PetscFunctionReturn(0);
}

/* M and K times the state (q, v, a), afresh, at the start (a restart reads them from its
   checkpoint). */
static PetscErrorCode BoltNewmarkProductsFresh(BoltNewmark *nm)
{
  BoltOperator *op = nm->op;

  PetscFunctionBeginUser;
  PetscCall(BoltOperatorMult(op, 0, nm->q, nm->Mq));
  PetscCall(BoltOperatorMult(op, 0, nm->v, nm->Mv));
  PetscCall(BoltOperatorMult(op, 0, nm->acc, nm->Ma));
  PetscCall(BoltOperatorMult(op, 1, nm->q, nm->Kq));
  PetscCall(BoltOperatorMult(op, 1, nm->v, nm->Kv));
  PetscCall(BoltOperatorMult(op, 1, nm->acc, nm->Ka));
  PetscFunctionReturn(0);
}

/* The products of a step's new state from M q and K q alone. The new velocity and acceleration
   are linear in the displacements and the old state, so X v and X a follow by the same
   combinations; with Rayleigh damping the right-hand side and the energy accounting need nothing
   else. Two products a step instead of five (pointwise on a modal reduced basis,
   BoltOperatorMult). Keeps X v of the step's start for the Rayleigh work. */
static PetscErrorCode BoltNewmarkProductsStep(BoltNewmark *nm)
{
  BoltOperator   *op = nm->op;
  const PetscReal *a = nm->a, g = nm->gamma, dt = nm->dt;
  Vec              Xq[2]    = {nm->Mq, nm->Kq}, Xv[2] = {nm->Mv, nm->Kv}, Xa[2] = {nm->Ma, nm->Ka}, XvOld[2] = {nm->MvOld, nm->KvOld};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 2; i++) {
    PetscCall(BoltOperatorMult(op, i, nm->q, nm->work));
    PetscCall(VecAYPX(Xq[i], -1.0, nm->work));                              /* X (q - q_old) */
    PetscCall(VecAXPBYPCZ(Xq[i], -a[2], -a[3], a[1], Xv[i], Xa[i]));          /* X a_new */
    PetscCall(VecCopy(Xv[i], XvOld[i]));
    PetscCall(VecAXPBYPCZ(Xv[i], (1 - g) * dt, g * dt, 1.0, Xa[i], Xq[i])); /* X v_new */
    PetscCall(VecCopy(Xq[i], Xa[i]));
    PetscCall(VecCopy(nm->work, Xq[i]));
    if (nm->quasiStatic) {
      PetscCall(VecZeroEntries(Xv[i]));
      PetscCall(VecZeroEntries(Xa[i]));
      PetscCall(VecZeroEntries(XvOld[i]));
    }
  }
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
  PetscScalar    ek, es; /* v'M v and q'K q of the current state */

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(VecDuplicate(nm->q, &qOld));
  /* the next factorisations: a1 M + a4 C + K + K_c, or K + K_c for quasi-static steps (still
     steps of a history: the loop carries the contact state and the friction from one to the next) */
  PetscCall(BoltDualSetEffective(nm->dual, PETSC_TRUE, nm->quasiStatic ? 0 : a[1], nm->quasiStatic ? 0 : a[4]));
  nm->tOnlineBefore = nm->tCheckpoint = 0;
  /* counters from here on describe the transient; the static solve keeps its own */
  nm->staticFactorizations = nm->dual->factorizations;
  nm->staticSolves         = nm->dual->solves;
  PetscCall(BoltDualResetCounters(nm->dual));
  nm->step = 0;
  PetscCall(op->ops.probe(op, nm->q, &nm->probeValue[0]));
  PetscCall(BoltNewmarkTrackStart(nm));
  if (nm->snapshotEvery > 0) {
    PetscCall(VecCopy(nm->q, nm->snap[0]));
    BoltContactStatePointCodes(op->state, nm->snapCodes);
    nm->snapTime[0] = 0;
    nm->nsnap       = 1;
  }
  PetscCall(BoltNewmarkProductsFresh(nm));
  PetscCall(BoltNewmarkEnergy(nm, 0.0, &nm->energy[0], &ek, &es));
  PetscCall(BoltNewmarkLedger(nm, 0, 0, 0, ek, es));
  if (BoltContactSetPairCount(op->contact)) PetscCall(BoltOperatorPairForces(op, nm->q, nm->pairForce));
  if (BoltContactStateHasFriction(op->state)) { /* the pairs the preload left slipping */
    PetscInt nslip;
    PetscCall(BoltContactStateCountReclosed(op->state, &nslip, NULL));
    nm->slipping[0] = (PetscReal)nslip;
  }
  if (nm->restart) PetscCall(BoltNewmarkCheckpointRead(nm)); /* state, its products, contact state and histories */
  step0 = nm->step;
  for (PetscInt n = step0 + 1; n <= nm->nsteps; n++) {
    PetscReal t = n * nm->dt, amp = BoltLoadAmplitude(nm, t);
    PetscInt  nout, nin;

    nm->step = n;
    /* rhs = F(t) + M (a1 q + a2 v + a3 a) + C (a4 q + a5 v + a6 a), C = alpha M + beta K */
    PetscCall(VecCopy(nm->q, qOld));
    PetscCall(VecZeroEntries(nm->rhs));
    if (!nm->quasiStatic) {
      const PetscReal al = op->rayleigh[0], be = op->rayleigh[1];
      PetscScalar     coef[6] = {a[1] + al * a[4], a[2] + al * a[5], a[3] + al * a[6], be * a[4], be * a[5], be * a[6]};
      Vec             prod[6] = {nm->Mq, nm->Mv, nm->Ma, nm->Kq, nm->Kv, nm->Ka};
      PetscCall(VecMAXPY(nm->rhs, 6, coef, prod));
    }
    PetscCall(VecAXPY(nm->rhs, amp, op->load));
    PetscCall(VecAXPY(nm->rhs, 1.0, op->preload));
    nm->dual->step = n;
    nm->dual->time = t;
    PetscCall(BoltDualSolve(nm->dual, nm->rhs, nm->q, n == step0 + 1 ? PETSC_TRUE : PETSC_FALSE, &nout, &nin));
    BoltNewmarkTrackStep(nm);
    /* a_new = a1 (q - q_old) - a2 v - a3 a;  v_new = v + dt ((1 - gamma) a + gamma a_new) */
    PetscCall(VecWAXPY(nm->work, -1.0, qOld, nm->q));
    PetscCall(VecAXPBYPCZ(nm->work, -a[2], -a[3], a[1], nm->v, nm->acc));
    PetscCall(VecAXPBYPCZ(nm->v, (1 - nm->gamma) * nm->dt, nm->gamma * nm->dt, 1.0, nm->acc, nm->work));
    PetscCall(VecCopy(nm->work, nm->acc));
    if (nm->quasiStatic) { /* no motion between equilibria */
      PetscCall(VecZeroEntries(nm->v));
      PetscCall(VecZeroEntries(nm->acc));
    }
    PetscCall(BoltDualCheckStep(nm->dual, nm->q, nm->v, nm->acc, amp));
    PetscCall(BoltNewmarkProductsStep(nm));
    nm->probeTime[n] = t;
    if (nm->snapshotEvery > 0 && n % nm->snapshotEvery == 0) {
      PetscCall(VecCopy(nm->q, nm->snap[nm->nsnap]));
      BoltContactStatePointCodes(op->state, &nm->snapCodes[4 * BoltContactSetElementCount(op->contact) * nm->nsnap]);
      nm->snapTime[nm->nsnap++] = t;
    }
    PetscCall(op->ops.probe(op, nm->q, &nm->probeValue[n]));
    PetscCall(BoltNewmarkEnergy(nm, amp, &nm->energy[n], &ek, &es));
    PetscCall(VecWAXPY(nm->dq, -1.0, qOld, nm->q));
    PetscCall(BoltNewmarkLedger(nm, n, BoltLoadAmplitude(nm, t - nm->dt), amp, ek, es));
    if (BoltContactSetPairCount(op->contact)) PetscCall(BoltOperatorPairForces(op, nm->q, &nm->pairForce[BOLT_PAIR_FORCE * BoltContactSetPairCount(op->contact) * n]));
    if (BoltContactStateHasFriction(op->state)) {
      PetscInt nslip;
      PetscCall(BoltContactStateCountReclosed(op->state, &nslip, NULL));
      nm->slipping[n] = (PetscReal)nslip;
      PetscCall(BoltContactStateDissipated(op->state, &nm->dissipated[n]));
    }
    if (nm->monitor) PetscCall(PetscPrintf(comm, "%s step %5" PetscInt_FMT " t %.6e outer %2" PetscInt_FMT " inner %3" PetscInt_FMT " active %" PetscInt_FMT "/%" PetscInt_FMT " energy %.10e probe %.6e\n", op->name, n, (double)t, nout, nin, BoltContactStateActiveCount(op->state), BoltContactSetPointCountGlobal(op->contact), (double)nm->energy[n], (double)nm->probeValue[n]));
    if (n % PetscMax(1, nm->nsteps / 10) == 0 && n < nm->nsteps) { /* progress of a long run, every tenth of it */
      PetscLogDouble tp;
      PetscCall(PetscTime(&tp));
      if (tp - t0 > 10) PetscCall(PetscPrintf(comm, "%s: step %" PetscInt_FMT " of %" PetscInt_FMT ", t = %g s, %.0f s so far; %" PetscInt_FMT " solves, %" PetscInt_FMT " factorisations, %" PetscInt_FMT " of %" PetscInt_FMT " contact points closed\n", op->name, n, nm->nsteps, (double)t, tp - t0, nm->dual->solves, nm->dual->factorizations, BoltContactStateActiveCount(op->state), BoltContactSetPointCountGlobal(op->contact)));
    }
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s Newmark (beta %g, gamma %g), dt %g s, %" PetscInt_FMT " steps, online %.3f s\n", nm->op->name, (double)nm->beta, (double)nm->gamma, (double)nm->dt, nm->nsteps, (double)nm->tOnline));
  PetscCall(BoltDualView(nm->dual, viewer));
  PetscFunctionReturn(0);
}

/* After the run: frees the factorisation, the effective matrix and the contact matrices, keeping the histories and
   the final state (a run that is over does not need them; they are the largest part of it). */
PetscErrorCode BoltNewmarkReleaseSolver(BoltNewmark *nm)
{
  PetscFunctionBeginUser;
  PetscCall(BoltDualReleaseSolver(nm->dual));
  PetscCall(BoltContactStateReleaseStiffness(nm->op->state));
  PetscFunctionReturn(0);
}

/* The bolt's clamp force [N] the static start calibrates the preload layers to (0: none). */
PetscErrorCode BoltNewmarkSetPreloadTarget(BoltNewmark *nm, PetscReal force)
{
  PetscFunctionBeginUser;
  nm->preloadTarget = force;
  PetscFunctionReturn(0);
}

/* A free model (the FOM's global layout): its rigid motions R (mass-orthonormal), taken out of
   the preloaded state. The integrator keeps a reference. */
PetscErrorCode BoltNewmarkSetRigidModes(BoltNewmark *nm, BV R)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)R));
  PetscCall(BVDestroy(&nm->rigid));
  nm->rigid = R;
  PetscFunctionReturn(0);
}

/* The operator's contact state already holds the preloaded state (handed over by another
   model): the static start neither calibrates the preload nor judges that active set again. */
PetscErrorCode BoltNewmarkKeepGivenPreload(BoltNewmark *nm)
{
  PetscFunctionBeginUser;
  nm->calibratePreload = PETSC_FALSE;
  PetscCall(BoltDualSetKeepActiveSet(nm->dual, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkDestroy(BoltNewmark **nmp)
{
  BoltNewmark *nm = *nmp;

  PetscFunctionBeginUser;
  if (!nm) PetscFunctionReturn(0);
  PetscCall(BoltDualDestroy(&nm->dual));
  PetscCall(BVDestroy(&nm->rigid));
  PetscCall(VecDestroy(&nm->q));
  PetscCall(VecDestroy(&nm->v));
  PetscCall(VecDestroy(&nm->acc));
  PetscCall(VecDestroy(&nm->rhs));
  PetscCall(VecDestroy(&nm->work));
  PetscCall(PetscFree6(nm->probeTime, nm->probeValue, nm->energy, nm->slipping, nm->dissipated, nm->ledger));
  PetscCall(PetscFree(nm->pairForce));
  PetscCall(VecDestroy(&nm->dq));
  for (PetscInt i = 0; i < 8; i++) PetscCall(VecDestroy(BoltNewmarkProductVec(nm, i)));
  if (nm->snap) PetscCall(VecDestroyVecs(nm->nsteps / nm->snapshotEvery + 1, &nm->snap));
  PetscCall(PetscFree(nm->snapTime));
  PetscCall(PetscFree(nm->snapCodes));
  PetscCall(PetscFree3(nm->codes0, nm->codesNow, nm->changed));
  PetscCall(PetscFree(*nmp));
  PetscFunctionReturn(0);
}
