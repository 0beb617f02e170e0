#ifndef BOLTROM_PRIVATE_SOLVE_H
#define BOLTROM_PRIVATE_SOLVE_H
/* Inside the solvers (src/solve/): what the dual loop's files share and no other module sees. */
#include "boltrom.h"

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
  PetscReal       tContactStiffness, tDisplacements, tContactForces;
  PetscReal       lastChange, lastPenetration; /* of the last inner iteration */
  /* strict law: the worst converged state so far (BoltContactStateComplementarity) */
  PetscReal       worstPenetration, worstTension, worstCompression, worstProduct;
};

#endif
