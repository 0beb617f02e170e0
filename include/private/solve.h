#ifndef BOLTROM_PRIVATE_SOLVE_H
#define BOLTROM_PRIVATE_SOLVE_H
/* Inside the solvers (src/solve/): what the dual loop's files share and no other module sees. */
#include "boltrom.h"

/* A model's operations (BoltOperatorSetOperation fills them). */
struct _n_BoltOperatorOps {
  PetscErrorCode (*contactDisplacements)(BoltOperator *, Vec);             /* q -> contact->uc */
  PetscErrorCode (*contactForces)(BoltOperator *, const PetscReal[], Vec); /* Gauss-point tractions -> F (overwritten) */
  PetscErrorCode (*contactStiffness)(BoltOperator *, Mat *);               /* K_c of the active set */
  /* optional, else from contactDisplacements and the state's own computation: */
  PetscErrorCode (*contactGaps)(BoltOperator *, Vec, PetscReal[]);         /* q -> the gaps at the local contact points */
  PetscErrorCode (*checkGaps)(BoltOperator *, Vec, PetscReal[]);           /* q -> the gaps at every local point, held ones included (the check) */
  PetscErrorCode (*checkTraction)(BoltOperator *, const PetscReal[], PetscReal[]); /* anchored gaps -> the opening test's traction at every local point (the check; else the state's) */
  PetscErrorCode (*heldTractions)(BoltOperator *, Vec, Vec, Vec, PetscReal, const PetscBool **, const PetscReal **); /* q, v, a, the load's amplitude -> the tractions of the points its basis ties (NULL: none), for the check */
  PetscErrorCode (*openTraction)(BoltOperator *, PetscReal[]);             /* the traction of the opening test (BoltContactStateOpenTraction) */
  PetscErrorCode (*setKept)(BoltOperator *, PetscBool *);                  /* collective: whether the last contactGaps prove that no point's state would change */
  PetscErrorCode (*probe)(BoltOperator *, Vec, PetscReal *);
  PetscErrorCode (*pairForces)(BoltOperator *, Vec, PetscReal[]);          /* optional: q -> the pair resultants (else the state's) */
  /* checkpoints: the model's vectors (named datasets) and whatever else its state holds */
  PetscErrorCode (*vectorsSave)(BoltOperator *, PetscViewer, PetscInt, const char *const[], Vec[]);
  PetscErrorCode (*vectorsLoad)(BoltOperator *, PetscViewer, PetscInt, const char *const[], Vec[], PetscInt *);
  PetscErrorCode (*stateSave)(BoltOperator *, PetscViewer);
  PetscErrorCode (*stateLoad)(BoltOperator *, PetscViewer);
  PetscErrorCode (*view)(BoltOperator *, PetscViewer);
  PetscErrorCode (*destroy)(BoltOperator *);
  /* optional, else the dual loop factorises K_eff afresh and solves with it: */
  PetscErrorCode (*factor)(BoltOperator *, BoltDual *);          /* after a change of the active set */
  PetscErrorCode (*solve)(BoltOperator *, BoltDual *, Vec, Vec); /* K_eff x = b */
};

struct BoltOperator_s {
  const char       *name;     /* "FOM" or "ROM" */
  MPI_Comm          comm;     /* for messages and errors (the ROM's matrices live on every rank) */
  MatSolverType     solverType; /* LU of the effective matrix: MUMPS (FOM) or LAPACK (ROM) */
  PetscBool         exactConstraints; /* every contact gap can be closed (FOM, ROM without interface reduction) */
  PetscBool         keepStructural; /* the dual loop keeps K + a1 M + a4 C summed for its factorisations (small dense matrices: the ROM) */
  char              prefix[16]; /* options prefix of its solver: fom_ or rom_ */
  Mat               M, C, K;
  Vec               Mdiag, Kdiag;  /* the diagonals of M and K in modal coordinates (a reduced basis): their products are pointwise */
  Mat               Krigid;        /* added to K in static solves only: a free ROM's stiffness on its rigid motions (BoltOperatorSetRigidStiffness) */
  PetscReal         rayleigh[2];   /* C = rayleigh[0] M + rayleigh[1] K (BoltOperatorSetDamping) */
  Vec               load, preload; /* external load pattern and preload, in its coordinates */
  BoltContactSet   *contact;  /* the shared geometry */
  BoltContactState *state;    /* this model's own contact state */
  void             *ctx;
  BoltOperatorOps   ops;
};


/* fom.c's context; fom_update.c: its low-rank updates of the transient's factorisation */
typedef struct _n_BoltFOMUpdate BoltFOMUpdate;
typedef struct {
  BoltLoadSet   *loads;
  BoltFOMUpdate *update; /* NULL: every state change factorised */
} BoltFOMCtx;
PetscErrorCode BoltFOMUpdateView(BoltFOMUpdate *, PetscViewer);
PetscErrorCode BoltFOMUpdateDestroy(BoltFOMUpdate **);

PetscErrorCode BoltDualInnerRegisterAll(void);
PetscErrorCode BoltDualFactor(BoltDual *d);
PetscErrorCode BoltDualSolveWithForces(BoltDual *d, Vec rhs0, const PetscReal lambda[], Vec q);
PetscErrorCode BoltDualGapsOf(BoltDual *d, Vec q, PetscReal gap[]);
struct _n_BoltPreloadState {
  Vec        q, preload;     /* displacement; preload vector as calibrated */
  PetscReal *lambda;         /* 12 per local contact element */
  PetscBool *active;         /* 4 per local contact element */
  PetscBool *released;       /* 4 per local contact element */
  PetscReal *anchor;         /* 12 per local contact element: where re-closed points stick */
  PetscReal  outer, inner;   /* iterations its solve took */
};

struct BoltDual_s {
  BoltOperator   *op;
  char            innerType[32];  /* -contact_inner */
  BoltDualInnerFn inner;
  PetscInt        maxOuter, maxInner;
  PetscReal       tolLambda, tolPenetration, tolFriction; /* relative multiplier change; penetration [m]; slip traction change / normal traction */
  PetscBool       tolPenetrationSet;         /* given as an option (else the law's default) */
  PetscBool       warmStart;      /* keep the multipliers across outer iterations and steps */
  PetscBool       closeCycles;    /* anti-cycling (-contact_cycle_close): once the set cycles or is slow to settle, points only close */
  PetscBool       continueOnFailure;
  PetscInt        monitor;        /* -contact_monitor: 1 a line per outer iteration, 2 also per CG iteration */
  PetscBool       keepActiveSet;  /* a static solve keeps the given active set */
  /* the effective matrix: K + K_c, or a1 M + a4 C + K + K_c */
  PetscBool       dynamic;
  PetscReal       massCoef, dampingCoef;
  Mat             Keff;
  KSP             ksp;
  Mat             Kstruct;        /* K + a1 M + a4 C of structStamp's coefficients (op->keepStructural) */
  PetscReal       structStamp[3]; /* dynamic, massCoef, dampingCoef it was summed with */
  /* preload calibration: each outer iteration scales to the target clamping force */
  PetscBool       calibrating;
  PetscReal       preloadTarget, preloadScale;
  PetscInt        step;           /* where the loop is, for messages */
  PetscReal       time;
  Vec             Fc, work, qp, FcLambda;
  PetscReal      *tnOpen;         /* per Gauss point: the traction of the opening test */
  PetscBool       extrapolate;    /* -contact_extrapolate: the strict law's steps start from extrapolated multipliers */
  PetscReal      *cgR, *cgP, *cgAp; /* CG residual (gaps), direction, its gaps; 3 per Gauss point */
  /* counters and phase times (the paper's Table 2) */
  PetscInt        factorizations, updates, solves, outerTotal, innerTotal, outerMax, innerMax, cycles, failures;
  PetscInt        keptUpdates; /* set updates the model proved to change nothing (BoltDualUpdateActive), of the transient */
  PetscReal       tContactStiffness, tDisplacements, tContactForces;
  PetscReal       lastChange, lastPenetration; /* of the last inner iteration */
  /* strict law: the worst converged state so far (BoltContactStateComplementarity) */
  PetscReal       worstPenetration, worstTension, worstCompression, worstProduct;
  /* every node pair checked after each converged transient step (BoltDualCheckStep): the worst
     penetration [m], tension [Pa] and cone excess, held points that would leave their state */
  PetscReal       checkWorst[3], tCheck;
  PetscInt        checkEvery, checkSteps, checkLeaving, checkFirstStep;
  PetscReal       checkFirstTime;
  PetscReal      *checkGaps; /* 3 per local point */
  PetscReal      *checkAnchored, *checkTn; /* 3 and 1 per local point: the check's anchored gaps and tractions, where the model gives them */
};

struct _n_BoltNewmark {
  BoltOperator   *op;
  BoltDual       *dual;
  PetscReal       beta, gamma, dt, tEnd;
  BoltLoadHistory history;
  PetscReal       frequency;
  PetscReal       rampTime; /* -load_ramp_time (0: tEnd) */
  PetscReal       releaseTime; /* -load_release_time: the release history drops the load after it */
  PetscReal       sweepStart; /* -load_sweep_start: the stepped sine's first-cycle amplitude, a fraction of the load */
  PetscBool       monitor;
  PetscBool       staticWithLoad; /* the static contact solve carries the external load too */
  BoltLoadSet    *bolts;          /* -preload_bolts: each bolt calibrated from its stud (preload_bolts.c); or NULL */
  PetscReal       boltLayerForce[BOLTROM_MAX_BOLTS], boltTension[BOLTROM_MAX_BOLTS];
  PetscInt        boltPasses;     /* static solves the bolts' calibration took */
  PetscBool       quasiStatic;    /* -ts_quasistatic: steps without inertia or damping */
  PetscBool       calibratePreload;
  BV              rigid; /* a free model's rigid motions (global layout), taken out of the preloaded state; or NULL */
  PetscReal       preloadTarget, preloadScale;
  PetscReal       a[7];    /* Newmark coefficients a1..a6 (a[0] unused) */
  Vec             q, v, acc, rhs, work;
  PetscInt        nsteps, step;
  PetscReal      *probeTime, *probeValue, *energy;
  PetscReal      *slipping, *dissipated; /* per step: slipping contact points, energy dissipated by friction so far [J] */
  PetscReal       stickEnergy0;  /* frictional law: the elastic sticks' energy at the start of the transient [J] */
  PetscReal      *ledger;     /* per step, BOLT_LEDGER rows of nsteps + 1 (BoltLedger): the energy accounting [J] */
  PetscReal      *pairForce;  /* per step, BOLT_PAIR_FORCE per contact pair (BoltContactStatePairForces) [N] */
  Vec             dq;         /* the step's displacement change (energy accounting) */
  /* M and K times the state: M q, M v, M a, K q, K v, K a, and M v, K v of the step's start
     (BoltNewmarkProductsStep) */
  Vec             Mq, Mv, Ma, Kq, Kv, Ka, MvOld, KvOld;
  PetscInt        snapshotEvery, nsnap;
  Vec            *snap;
  PetscReal      *snapTime;
  unsigned char  *snapCodes;  /* per snapshot, each local contact point's state (BoltContactStatePointCodes) */
  unsigned char  *codes0, *codesNow; /* each local contact point's state after the preload, and now */
  PetscBool      *changed;    /* per local contact point: its state has differed from the preloaded one after some step */
  PetscBool       trackChanges; /* record changed (BoltNewmarkTrackChanges) */
  PetscReal       tOnline;
  PetscReal       staticOuter, staticInner;
  PetscInt        staticFactorizations, staticSolves;
  /* checkpoints (checkpoint.c): <checkpointBase>-fom.ckpt.h5 / -rom.ckpt.h5 */
  PetscInt        checkpointEvery;  /* write one every this many steps (0: never) */
  char            checkpointBase[PETSC_MAX_PATH_LEN];
  PetscBool       restart;          /* continue from the checkpoint instead of step 0 */
  PetscReal       tOnlineBefore;    /* online time spent before the restart */
  PetscReal       tCheckpoint;      /* time spent writing checkpoints (not online work) */
};

/* dual_check.c: every node pair checked after each converged transient step */
PetscErrorCode BoltDualCheckStep(BoltDual *, Vec, Vec, Vec, PetscReal);
PetscErrorCode BoltDualCheckSummaryWrite(BoltDual *, BoltJSON *);

/* newmark_track.c: the contact points whose state the transient changed (a trained ROM's inputs) */
PetscErrorCode BoltNewmarkTrackStart(BoltNewmark *);
void           BoltNewmarkTrackStep(BoltNewmark *);

/* preload_bolts.c: several bolts, each calibrated to its own clamp force */
PetscErrorCode BoltNewmarkPreloadBolts(BoltNewmark *, PetscInt *, PetscInt *);
PetscErrorCode BoltNewmarkBoltsSummaryWrite(BoltNewmark *, BoltJSON *);

#endif
