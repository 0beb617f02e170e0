#ifndef BOLTROM_SOLVE_H
#define BOLTROM_SOLVE_H
/* boltrom's public solve API (src/solve): the operator a model shows the solvers, the dual contact loop and the time integrator. Included by boltrom.h. */

/* ------------------------------------------------------------------ operator.c */
/* What the dual loop and the time integrator need of a model, full or reduced: its matrices in
   its own coordinates, its contact state, and the maps to and from the contact DOFs. FOM and
   ROM both provide one, through an ops table. */
typedef struct BoltOperator_s BoltOperator;
typedef struct BoltDual_s     BoltDual;
typedef struct _n_BoltOperatorOps BoltOperatorOps;

PetscErrorCode BoltOperatorCreate(MPI_Comm, const char[], BoltContactSet *, BoltOperator **);
PetscErrorCode BoltOperatorSetSystem(BoltOperator *, Mat, Mat, Mat, Vec, Vec);
PetscErrorCode BoltOperatorSetDamping(BoltOperator *, Mat, PetscReal, PetscReal);
PetscErrorCode BoltOperatorSetRigidStiffness(BoltOperator *, Mat);
typedef enum { BOLT_OP_CONTACT_DISPLACEMENTS, BOLT_OP_CONTACT_FORCES, BOLT_OP_CONTACT_STIFFNESS, BOLT_OP_CONTACT_GAPS, BOLT_OP_OPEN_TRACTION, BOLT_OP_PROBE, BOLT_OP_VECTORS_SAVE, BOLT_OP_VECTORS_LOAD, BOLT_OP_STATE_SAVE, BOLT_OP_STATE_LOAD, BOLT_OP_VIEW, BOLT_OP_DESTROY, BOLT_OP_FACTOR, BOLT_OP_SOLVE, BOLT_OP_HELD_TRACTIONS, BOLT_OP_PAIR_FORCES, BOLT_OP_SET_KEPT, BOLT_OP_CHECK_GAPS, BOLT_OP_CHECK_TRACTION } BoltOperatorOp;
PetscErrorCode    BoltOperatorSetOperation(BoltOperator *, BoltOperatorOp, void (*)(void));
PetscErrorCode    BoltOperatorSetSolver(BoltOperator *, const char[], MatSolverType, PetscBool, PetscBool);
PetscErrorCode    BoltOperatorGetSolver(BoltOperator *, const char *[], MatSolverType *);
PetscErrorCode    BoltOperatorSetContext(BoltOperator *, void *);
PetscErrorCode    BoltOperatorCopyLoads(BoltOperator *, Vec, Vec);
PetscErrorCode    BoltOperatorContactDisplacements(BoltOperator *, Vec);
PetscErrorCode    BoltOperatorContactStiffness(BoltOperator *, Mat *);
PetscErrorCode    BoltOperatorProbe(BoltOperator *, Vec, PetscReal *);
PetscErrorCode    BoltOperatorMult(BoltOperator *, PetscInt, Vec, Vec);
PetscErrorCode    BoltOperatorSetDiagonalProducts(BoltOperator *);
PetscErrorCode    BoltOperatorPairForces(BoltOperator *, Vec, PetscReal[]);
void             *BoltOperatorContext(BoltOperator *);
BoltContactState *BoltOperatorState(BoltOperator *);
BoltContactSet   *BoltOperatorContact(BoltOperator *);
MPI_Comm          BoltOperatorComm(BoltOperator *);
Mat               BoltOperatorMass(BoltOperator *);
Mat               BoltOperatorStiffness(BoltOperator *);
PetscErrorCode    BoltOperatorReleaseDamping(BoltOperator *);
Vec               BoltOperatorLoadVec(BoltOperator *);
Vec               BoltOperatorPreloadVec(BoltOperator *);
PetscErrorCode BoltOperatorView(BoltOperator *, PetscViewer);
PetscErrorCode BoltOperatorDestroy(BoltOperator **);

/* A static preloaded equilibrium, kept so that a later solve of the same scene (the ROM's offline
   phase after the FOM's run) starts from it instead of solving it again. */
typedef struct _n_BoltPreloadState BoltPreloadState;

PetscErrorCode BoltPreloadStateCreate(BoltOperator *, Vec, PetscReal, PetscReal, BoltPreloadState **);
PetscErrorCode BoltPreloadStateApply(const BoltPreloadState *, BoltOperator *, Vec);
PetscErrorCode BoltPreloadStateGetIterations(const BoltPreloadState *, PetscReal *, PetscReal *);
PetscErrorCode BoltPreloadStateDestroy(BoltPreloadState **);

/* fom.c: the full-order operator */
PetscErrorCode BoltFOMCreate(BoltAssembler *, BoltContactSet *, BoltLoadSet *, PetscBool, BoltOperator **);
/* fom_update.c: the transient's state changes as low-rank updates of its factorisation */
PetscErrorCode BoltFOMUpdateCreate(BoltOperator *, PetscInt);

/* ------------------------------------------------------------------ dual.c */
/* The dual contact loop for one linear system K_eff q = rhs - B' lambda (the paper's Algorithm
   1): outer iterations on the active set, inner iterations on the multipliers by a registered
   inner solver (uzawa, cg). The time integrator and the offline static solves both use it. */
typedef PetscErrorCode (*BoltDualInnerFn)(BoltDual *, Vec, Vec, PetscInt *);
extern PetscFunctionList BoltDualInnerList;
PetscErrorCode BoltDualInnerRegister(const char[], BoltDualInnerFn);

PetscErrorCode BoltDualCreate(BoltOperator *, BoltDual **);
PetscErrorCode BoltDualSetFromOptions(BoltDual *);
PetscErrorCode BoltDualSetUp(BoltDual *);
PetscErrorCode BoltDualSetEffective(BoltDual *, PetscBool, PetscReal, PetscReal);
PetscErrorCode BoltDualFactorInto(BoltDual *, Mat, KSP);
PetscErrorCode BoltDualSolve(BoltDual *, Vec, Vec, PetscBool, PetscInt *, PetscInt *);
PetscErrorCode BoltDualSolveStatic(BoltDual *, Vec, Vec, PetscReal, PetscInt *, PetscInt *);
PetscErrorCode BoltDualResetCounters(BoltDual *);
PetscErrorCode BoltDualView(BoltDual *, PetscViewer);
PetscErrorCode BoltDualReleaseSolver(BoltDual *);
PetscErrorCode BoltDualDestroy(BoltDual **);
PetscErrorCode BoltDualSetKeepActiveSet(BoltDual *, PetscBool);
PetscErrorCode BoltDualGetEffective(BoltDual *, PetscBool *, PetscReal *, PetscReal *);
PetscErrorCode BoltDualLogStiffnessUpdate(BoltDual *, PetscLogDouble, PetscBool);
PetscErrorCode BoltDualGetSolver(BoltDual *, BoltOperator **, KSP *);
PetscErrorCode BoltDualGetLastConvergence(BoltDual *, PetscReal *, PetscReal *);
PetscErrorCode BoltDualSummaryWrite(BoltDual *, BoltJSON *, PetscBool);
/* dual_monitor.c: diagnostics of the loop (-contact_monitor) */
PetscErrorCode BoltContactMonitorOuter(BoltDual *, PetscInt, PetscInt, PetscInt, PetscBool);
PetscErrorCode BoltContactMonitorTension(BoltDual *);

/* ------------------------------------------------------------------ newmark.c */
typedef enum { BOLT_LOAD_STEP = 0, BOLT_LOAD_SINE = 1, BOLT_LOAD_RAMP = 2, BOLT_LOAD_RELEASE = 3, BOLT_LOAD_SWEEP = 4 } BoltLoadHistory;
/* The energy accounting of a Newmark run, per step (rows of BoltNewmark's ledger): the external
   work and the Rayleigh dissipation so far (trapezoidal rule over each step, the rule of the
   average-acceleration step), the kinetic and strain energy, the work of the contact tractions
   so far (BoltContactStateEndSolve; friction's part is the dissipated history), and the balance
   external - kinetic change - strain change - Rayleigh - contact. */
enum { BOLT_LEDGER_EXTERNAL, BOLT_LEDGER_KINETIC, BOLT_LEDGER_STRAIN, BOLT_LEDGER_RAYLEIGH, BOLT_LEDGER_CONTACT, BOLT_LEDGER_BALANCE, BOLT_LEDGER };

typedef struct _n_BoltNewmark BoltNewmark;

PetscErrorCode BoltNewmarkCreate(BoltOperator *, BoltNewmark **);
PetscErrorCode BoltNewmarkSetFromOptions(BoltNewmark *);
PetscErrorCode BoltNewmarkSetUp(BoltNewmark *);
PetscErrorCode BoltNewmarkPreload(BoltNewmark *);
PetscErrorCode BoltNewmarkRun(BoltNewmark *);
PetscErrorCode BoltNewmarkView(BoltNewmark *, PetscViewer);
PetscErrorCode BoltNewmarkReleaseSolver(BoltNewmark *);
PetscErrorCode BoltNewmarkDestroy(BoltNewmark **);
PetscErrorCode BoltNewmarkKeepGivenPreload(BoltNewmark *);
PetscErrorCode BoltNewmarkSetRigidModes(BoltNewmark *, BV);
PetscErrorCode BoltNewmarkSetBolts(BoltNewmark *, BoltLoadSet *);
PetscErrorCode BoltNewmarkSetPreloadTarget(BoltNewmark *, PetscReal);
/* newmark_results.c: what a run hands the rest of the program (read-only) */
typedef enum { BOLT_HISTORY_TIME, BOLT_HISTORY_PROBE, BOLT_HISTORY_ENERGY, BOLT_HISTORY_SLIPPING, BOLT_HISTORY_DISSIPATED, BOLT_HISTORY_LEDGER, BOLT_HISTORY_PAIR_FORCE } BoltHistory;
PetscErrorCode BoltNewmarkGetHistory(BoltNewmark *, BoltHistory, PetscInt *, const PetscReal **);
PetscErrorCode BoltNewmarkGetSnapshots(BoltNewmark *, PetscInt *, Vec **, const PetscReal **, const unsigned char **);
PetscErrorCode BoltNewmarkStaticStartOptions(PetscBool *, PetscBool *);
void           BoltNewmarkTrackChanges(BoltNewmark *);
PetscErrorCode BoltNewmarkGetChangedPoints(BoltNewmark *, const PetscBool **);
PetscErrorCode BoltNewmarkGetModel(BoltNewmark *, BoltOperator **, BoltDual **, Vec *);
PetscErrorCode BoltNewmarkGetTiming(BoltNewmark *, PetscReal *, PetscReal *);
PetscErrorCode BoltNewmarkGetStaticSolve(BoltNewmark *, PetscReal *, PetscReal *);
PetscErrorCode BoltNewmarkGetLoad(BoltNewmark *, BoltLoadHistory *, PetscReal *);
PetscErrorCode BoltLoadHistoryFromOptions(BoltLoadHistory *);
PetscErrorCode BoltNewmarkSetCheckpointBase(BoltNewmark *, const char[]);
PetscErrorCode BoltNewmarkOptionsCheck(MPI_Comm, const char[], char[]);
PetscErrorCode BoltNewmarkPreloadSummaryWrite(BoltNewmark *, BoltJSON *);
PetscErrorCode BoltNewmarkSummaryWrite(BoltNewmark *, BoltJSON *, PetscBool);
PetscErrorCode BoltNewmarkCheckpointWrite(BoltNewmark *);
PetscErrorCode BoltNewmarkCheckpointRead(BoltNewmark *);

#endif
