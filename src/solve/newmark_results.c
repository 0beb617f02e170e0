/* What a Newmark run hands the rest of the program: its histories, snapshots, final state,
   timings and static start, and its keys of the run summary. Read-only: the run owns them. */
#include "private/solve.h"

/* The history of one quantity: nsteps + 1 values (BOLT_HISTORY_LEDGER: BOLT_LEDGER rows of
   them; BOLT_HISTORY_PAIR_FORCE: BOLT_PAIR_FORCE per contact pair per step). */
PetscErrorCode BoltNewmarkGetHistory(BoltNewmark *nm, BoltHistory which, PetscInt *nsteps, const PetscReal **values)
{
  PetscFunctionBeginUser;
  if (nsteps) *nsteps = nm->nsteps;
  switch (which) {
  case BOLT_HISTORY_TIME: *values = nm->probeTime; break;
  case BOLT_HISTORY_PROBE: *values = nm->probeValue; break;
  case BOLT_HISTORY_ENERGY: *values = nm->energy; break;
  case BOLT_HISTORY_SLIPPING: *values = nm->slipping; break;
  case BOLT_HISTORY_DISSIPATED: *values = nm->dissipated; break;
  case BOLT_HISTORY_LEDGER: *values = nm->ledger; break;
  case BOLT_HISTORY_PAIR_FORCE: *values = nm->pairForce; break;
  default: SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Unknown history %d", (int)which);
  }
  PetscFunctionReturn(0);
}

/* The displacement snapshots (-snapshot_every), their times and contact states. */
PetscErrorCode BoltNewmarkGetSnapshots(BoltNewmark *nm, PetscInt *n, Vec **snap, const PetscReal **time, const unsigned char **codes)
{
  PetscFunctionBeginUser;
  *n = nm->nsnap;
  if (snap) *snap = nm->snap;
  if (time) *time = nm->snapTime;
  if (codes) *codes = nm->snapCodes;
  PetscFunctionReturn(0);
}

/* The operator it integrates, its dual loop and its current displacement (all the run's). */
PetscErrorCode BoltNewmarkGetModel(BoltNewmark *nm, BoltOperator **op, BoltDual **dual, Vec *q)
{
  PetscFunctionBeginUser;
  if (op) *op = nm->op;
  if (dual) *dual = nm->dual;
  if (q) *q = nm->q;
  PetscFunctionReturn(0);
}

/* The time step [s] and the online time of the transient [s]. */
PetscErrorCode BoltNewmarkGetTiming(BoltNewmark *nm, PetscReal *dt, PetscReal *tOnline)
{
  PetscFunctionBeginUser;
  if (dt) *dt = nm->dt;
  if (tOnline) *tOnline = nm->tOnline;
  PetscFunctionReturn(0);
}

/* The static preloaded start's iterations. */
PetscErrorCode BoltNewmarkGetStaticSolve(BoltNewmark *nm, PetscReal *outer, PetscReal *inner)
{
  PetscFunctionBeginUser;
  *outer = nm->staticOuter;
  *inner = nm->staticInner;
  PetscFunctionReturn(0);
}

/* The load's time history and its frequency [Hz] (sine and sweep; else 0). */
PetscErrorCode BoltNewmarkGetLoad(BoltNewmark *nm, BoltLoadHistory *history, PetscReal *frequency)
{
  PetscFunctionBeginUser;
  *history   = nm->history;
  *frequency = (nm->history == BOLT_LOAD_SINE || nm->history == BOLT_LOAD_SWEEP) ? nm->frequency : 0;
  PetscFunctionReturn(0);
}

/* The checkpoints' base name (set before SetFromOptions, which -checkpoint_file may change). */
PetscErrorCode BoltNewmarkSetCheckpointBase(BoltNewmark *nm, const char base[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(nm->checkpointBase, base, sizeof(nm->checkpointBase)));
  PetscFunctionReturn(0);
}

/* The time integrator's options read before any model exists (the FOM's and the ROM's read the
   same ones): a wrong one stops the run at once. checkpointBase: the checkpoints' base name
   (base unless -checkpoint_file) if they are written, else "". */
PetscErrorCode BoltNewmarkOptionsCheck(MPI_Comm comm, const char base[], char checkpointBase[])
{
  BoltOperator stub = {0}; /* the options need no model */
  BoltNewmark *nm;

  PetscFunctionBeginUser;
  stub.comm = comm;
  stub.name = "FOM";
  PetscCall(PetscStrncpy(stub.prefix, "fom_", sizeof(stub.prefix)));
  PetscCall(BoltNewmarkCreate(&stub, &nm));
  PetscCall(BoltNewmarkSetCheckpointBase(nm, base));
  PetscCall(BoltNewmarkSetFromOptions(nm));
  PetscCall(PetscStrncpy(checkpointBase, nm->checkpointEvery > 0 ? nm->checkpointBase : "", PETSC_MAX_PATH_LEN));
  PetscCall(BoltNewmarkDestroy(&nm));
  PetscFunctionReturn(0);
}

/* The static preloaded start's keys of the run summary. */
PetscErrorCode BoltNewmarkPreloadSummaryWrite(BoltNewmark *nm, BoltJSON *j)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONReal(j, "layer_force_scale", nm->preloadScale));
  PetscCall(BoltJSONReal(j, "outer", nm->staticOuter));
  PetscCall(BoltJSONReal(j, "inner", nm->staticInner));
  PetscCall(BoltJSONInt(j, "factorizations", nm->staticFactorizations));
  PetscCall(BoltJSONInt(j, "solves", nm->staticSolves));
  PetscCall(BoltNewmarkBoltsSummaryWrite(nm, j));
  PetscFunctionReturn(0);
}

/* The run's keys of the summary, the FOM's and the ROM's alike; full (the FOM's) adds the time
   step, the largest iteration counts, the contact points and the probe's range. */
PetscErrorCode BoltNewmarkSummaryWrite(BoltNewmark *nm, BoltJSON *j, PetscBool full)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONInt(j, "steps", nm->nsteps));
  if (full) PetscCall(BoltJSONReal(j, "dt", nm->dt));
  PetscCall(BoltJSONReal(j, "online_s", nm->tOnline));
  PetscCall(BoltDualSummaryWrite(nm->dual, j, full));
  if (full) {
    PetscInt nsliding, nanchored;
    PetscCall(BoltJSONInt(j, "active_points", BoltContactStateActiveCount(nm->op->state)));
    PetscCall(BoltContactStateCountReclosed(nm->op->state, &nsliding, &nanchored));
    PetscCall(BoltJSONInt(j, "sliding_points", nsliding));
    PetscCall(BoltJSONInt(j, "reclosed_points", nanchored));
    PetscCall(BoltJSONInt(j, "contact_points", BoltContactSetPointCountGlobal(nm->op->contact)));
  }
  PetscCall(BoltJSONReal(j, "probe_final", nm->probeValue[nm->nsteps]));
  if (full) {
    PetscReal mn = 0, mx = 0;
    for (PetscInt i = 0; i <= nm->nsteps; i++) {
      mn = PetscMin(mn, nm->probeValue[i]);
      mx = PetscMax(mx, nm->probeValue[i]);
    }
    PetscCall(BoltJSONReal(j, "probe_min", mn));
    PetscCall(BoltJSONReal(j, "probe_max", mx));
  }
  if (full && BoltContactStateLambdaIsTraction(nm->op->state)) {
    /* the energy accounting at the end, and its balance's largest value over the run relative
       to the largest term (the strict laws' loop measures the contact work) */
    const PetscReal *L = nm->ledger;
    const PetscInt   N = nm->nsteps + 1, e = nm->nsteps;
    PetscReal        worst = 0, scale = 0;
    for (PetscInt i = 0; i < N; i++) {
      worst = PetscMax(worst, PetscAbsReal(L[BOLT_LEDGER_BALANCE * N + i]));
      scale = PetscMax(scale, PetscAbsReal(L[BOLT_LEDGER_EXTERNAL * N + i]));
      scale = PetscMax(scale, L[BOLT_LEDGER_KINETIC * N + i]);
      scale = PetscMax(scale, PetscAbsReal(L[BOLT_LEDGER_STRAIN * N + i] - L[BOLT_LEDGER_STRAIN * N]));
      scale = PetscMax(scale, L[BOLT_LEDGER_RAYLEIGH * N + i]);
      scale = PetscMax(scale, PetscAbsReal(L[BOLT_LEDGER_CONTACT * N + i]));
    }
    PetscCall(BoltJSONBeginObject(j, "energy"));
    PetscCall(BoltJSONReal(j, "external_work", L[BOLT_LEDGER_EXTERNAL * N + e]));
    PetscCall(BoltJSONReal(j, "kinetic_change", L[BOLT_LEDGER_KINETIC * N + e] - L[BOLT_LEDGER_KINETIC * N]));
    PetscCall(BoltJSONReal(j, "strain_change", L[BOLT_LEDGER_STRAIN * N + e] - L[BOLT_LEDGER_STRAIN * N]));
    PetscCall(BoltJSONReal(j, "rayleigh", L[BOLT_LEDGER_RAYLEIGH * N + e]));
    PetscCall(BoltJSONReal(j, "contact_work", L[BOLT_LEDGER_CONTACT * N + e]));
    if (BoltContactStateHasFriction(nm->op->state)) {
      PetscReal stick;
      PetscCall(BoltContactStateStickEnergy(nm->op->state, &stick));
      PetscCall(BoltJSONReal(j, "friction", nm->dissipated[e]));
      PetscCall(BoltJSONReal(j, "stick_energy_change", stick - nm->stickEnergy0));
    }
    PetscCall(BoltJSONReal(j, "balance_rel", scale > 0 ? worst / scale : 0));
    PetscCall(BoltJSONEndObject(j));
  }
  PetscFunctionReturn(0);
}
