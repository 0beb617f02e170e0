#ifndef BOLTROM_CONTACT_H
#define BOLTROM_CONTACT_H
/* boltrom's public contact API (src/contact): contact pairs, contact laws and one model's contact state. Included by boltrom.h. */

/* ------------------------------------------------------------------ contact.c */
/* A contact element: two matching quad faces, a and b. Only the owner of face a keeps it. */
typedef struct _n_BoltContactElement BoltContactElement;

enum { BOLT_OPEN_NODAL = 0, BOLT_OPEN_GAUSS = 1 };
enum { BOLT_QUADRATURE_GAUSS = 0, BOLT_QUADRATURE_NODAL = 1 };

/* A contact law (src/contact/laws/, one file per law), a registered type: an ops table of what
   the law does at one contact point (trial traction, return map, stiffness block, convergence
   measure, point code, energy terms) and its properties; its body is the contact module's
   (include/private/contact.h). Other modules ask the set or the state (BoltContactSetHasFriction
   and the like below). */
typedef struct _p_BoltContactLaw BoltContactLaw;
extern PetscFunctionList BoltContactLawList;
PetscErrorCode BoltContactLawRegister(const char[], PetscErrorCode (*)(BoltContactLaw *));
PetscErrorCode BoltContactLawRegisterAll(void);
PetscErrorCode BoltContactLawCreate(MPI_Comm, const char[], BoltContactLaw **);
PetscErrorCode BoltContactLawDestroy(BoltContactLaw **);

/* The contact geometry, shared by every model: pairs, matched elements, Gauss-point data, the
   local contact vector and its scatter, and the defaults of the law each model's state starts
   from. It holds no state of a solve (BoltContactState does) apart from scratch vectors that a
   call fills and reads before it returns. */
typedef struct {
  BoltMesh           *mesh;
  PetscInt            npairs;
  char                pairName[BOLTROM_MAX_PAIRS][BOLTROM_NAME_LEN];
  PetscInt            pairPart[BOLTROM_MAX_PAIRS][2];
  PetscReal           penaltyFactor;              /* x E of the softer part, per metre */
  PetscReal           epsN[BOLTROM_MAX_PAIRS], epsT[BOLTROM_MAX_PAIRS]; /* default penalties */
  PetscReal           bandTraction[BOLTROM_MAX_PAIRS]; /* default tension [Pa] beyond which a closed point opens */
  PetscReal           friction[BOLTROM_MAX_PAIRS]; /* Coulomb coefficient per pair (frictional law) */
  PetscReal           frictionDefault;             /* -contact_friction */
  PetscReal           slipAngleTolerance;          /* -contact_slip_angle_tolerance [rad] */
  PetscReal           slipStiffnessRatio;          /* -contact_slip_stiffness_ratio */
  PetscReal           stickFactor;                 /* -contact_stick_stiffness_factor: x E of the softer part, per metre */
  PetscReal           stickStiffness[BOLTROM_MAX_PAIRS]; /* frictional law: tangential stiffness of a sticking pair [Pa/m] */
  PetscBool           frictionSet;
  PetscInt            contactDofsPerPair[BOLTROM_MAX_PAIRS], contactDofs;
  PetscInt            elementsPerPair[BOLTROM_MAX_PAIRS];
  PetscReal           areaPerPair[BOLTROM_MAX_PAIRS];
  PetscReal           matchTolerance;              /* relative to the mesh size */
  PetscInt            nelem;
  BoltContactElement *elem;
  /* defaults of the law (-contact_*), copied into each new state */
  char                lawType[64];    /* -contact_law: a BoltContactLawList entry */
  BoltContactLaw     *law;            /* its operations and properties (owned) */
  PetscBool           augment;        /* -contact_augment: augmented Lagrangian (false: pure penalty) */
  PetscReal           activationGap;  /* penetration [m] beyond which an open point closes */
  PetscInt            openTest;       /* BOLT_OPEN_NODAL: a closed point opens on its traction smoothed
                                         through the nodes; BOLT_OPEN_GAUSS: on its own multiplier */
  PetscBool           reanchor;       /* -contact_reclose stick: a strict-law pair that closes again sticks where it closes */
  PetscInt            quadrature;     /* BOLT_QUADRATURE_GAUSS (2x2) or _NODAL (points at the nodes) */
  PetscReal           hMin;           /* shortest edge of a contact face (global) */
  PetscReal           gapTolerance;   /* default gap tolerance of the strict law [m]: 1e-9 hMin */
  PetscReal          *gpN, *gpW, *gpNormal; /* shape values (16), area weights (4), normals (12) per element */
  PetscInt           *elemLocal;      /* 24 per element: index in the local contact vector, -1 if clamped */
  PetscInt            nlocal;         /* length of the local contact vector */
  PetscInt           *localGlobal;    /* its global DOFs */
  PetscInt            ngpGlobal;
  VecScatter          scatter;        /* global displacement -> uc */
  PetscReal          *nodalArea;      /* nlocal: sum w N n over all Gauss points (vector area of the node) */
  /* scratch */
  Vec                 layout;         /* a vector of the global layout (never written: a template) */
} BoltContactSet;

/* The contact state of one model (contact_state.c): its law and penalties, and at every Gauss
   point the multiplier, the gap and the active flags of the last three outer iterations; the
   element matrices and K_c of its active set. Each operator owns one. */
typedef struct {
  BoltContactSet *set;
  struct _n_BoltContactWork *work; /* this state's work space (displacements, forces, sums) */
  char            lawType[64];
  BoltContactLaw *law;            /* the set's */
  PetscBool       augment;        /* augmented Lagrangian (false: penalty, lambda fixed) */
  PetscReal       activationGap;
  PetscInt        openTest;
  PetscReal       epsN[BOLTROM_MAX_PAIRS], epsT[BOLTROM_MAX_PAIRS], bandTraction[BOLTROM_MAX_PAIRS];
  PetscReal       stickStiffness[BOLTROM_MAX_PAIRS]; /* frictional law: elastic stick [Pa/m], not scaled with the penalties (it is physics) */
  PetscReal      *lambda, *gap;   /* 3 per Gauss point: multiplier (traction) and gap u_b - u_a */
  PetscBool      *active, *activeOld, *activeOlder;
  PetscBool      *released;       /* strict law, -contact_reclose slide: the point has opened, and slides (normal contact only) when closed */
  PetscBool       reanchor;       /* strict law, -contact_reclose stick: a pair that closes again sticks where it closes */
  PetscReal      *anchor;         /* 3 per point: tangential position where a re-closed pair sticks (0: since the start);
                                     frictional law: the tangential raw gap from which its elastic stick is measured */
  PetscReal      *lambdaForce;    /* 3 per point: lambda - epsT anchor, the multipliers that the solve's forces take */
  PetscReal      *lambdaPrev;     /* 3 per point: the multipliers of the converged step before the last (BoltContactStateExtrapolate) */
  PetscInt       *closedSteps;    /* per point: converged steps in a row it ended closed, at most 2 */
  PetscReal      *slipStart;      /* strict laws, 3 per point: its raw gap (u_b - u_a) at the start of the step */
  PetscReal      *tractionStart;  /* strict laws, 3 per point: its traction at the start of the step */
  PetscReal       contactWork;    /* strict laws: work of the contact tractions over the converged steps [J] (local) */
  PetscReal       dissipated;     /* frictional law: energy dissipated by slip over the converged steps [J] (local) */
  PetscReal      *slipDir;        /* frictional law, 4 per point: the direction a slipping pair slides along in K_c,
                                     and K_c's stiffness across it (the return map's derivative, k_t mu |t_N| / |trial|) */
  PetscBool       stickOnly;      /* frictional law: closed pairs never slip (the basis's static shapes) */
  PetscReal       frictionChange; /* frictional law: the last update's largest slip-traction change [Pa] over the largest pressure (global) */
  PetscReal       slipStiffnessRatio; /* frictional law: K_c takes a slipping pair's new stiffness when off by more than this factor */
  PetscReal       slipAngleTolerance; /* frictional law: a slipping pair's direction turns when its traction is off it by more [rad] */
  PetscBool       anchored;       /* some local point has a non-zero anchor */
  const PetscBool *mayChange;     /* per point, or NULL (all): the points whose state may change (a ROM's: those of its opening shapes) */
  PetscBool       closeOnly;      /* anti-cycling (the dual loop): points may close but not open */
  PetscBool       holdContact;    /* the closed and open points stay so (a kept active set), but under friction still stick or slip */
  PetscBool      *dirty;          /* element whose activity or penalty changed since its Ke was built */
  PetscReal      *Ke;             /* 576 per element: stiffness of its active Gauss points (made when first needed) */
  Mat             Kc;             /* contact stiffness in the global layout (COO; made when first needed) */
  PetscBool       KcAssembled;    /* Kc holds the current element matrices */
  PetscInt        nactive;
  /* raised on every rank together whenever the multipliers, the active or sliding flags or the
     penalties may have changed (BoltContactStateChanged): a model that caches what it derives
     from the state compares it, and every rank takes the same decision without a reduction */
  PetscObjectState version;
  PetscBool        lambdaZero; /* the multipliers are +0 on every rank (penalty law, after an augmentation) */
} BoltContactState;

/* contact.c: the geometry */
PetscErrorCode BoltContactSetCreate(BoltMesh *, BoltContactSet **);
PetscErrorCode BoltContactSetSetFromOptions(BoltContactSet *);
PetscErrorCode BoltContactSetSetUp(BoltContactSet *);
PetscErrorCode BoltContactSetSetUpQuadrature(BoltContactSet *, Vec);
PetscErrorCode BoltContactSetCheckSupport(BoltContactSet *);
PetscInt         BoltContactSetElementPair(const BoltContactSet *, PetscInt);
PetscInt         BoltContactSetElementKey(const BoltContactSet *, PetscInt);
const PetscInt  *BoltContactSetElementDofs(const BoltContactSet *, PetscInt);
const PetscReal *BoltContactSetElementCoordinates(const BoltContactSet *, PetscInt);
/* The work space of one model's contact computations (each contact state owns one, so the FOM's
   and the ROM's never share): the local contact displacements and forces, and nodal sums. */
typedef struct _n_BoltContactWork BoltContactWork;
PetscErrorCode BoltContactWorkCreate(BoltContactSet *, BoltContactWork **);
PetscErrorCode BoltContactWorkGetDisplacements(BoltContactWork *, Vec *);
PetscErrorCode BoltContactWorkDestroy(BoltContactWork **);
PetscErrorCode BoltContactSetAssembleTied(BoltContactSet *, Mat, Mat *);
PetscErrorCode BoltContactSetStiffnessMatrix(BoltContactSet *, Mat *);
PetscErrorCode BoltContactSetScatter(BoltContactSet *, BoltContactWork *, Vec);
PetscErrorCode BoltContactSetGapsOf(BoltContactSet *, BoltContactWork *, PetscReal[]);
PetscErrorCode BoltContactSetForcesOf(BoltContactSet *, BoltContactWork *, const PetscReal[], Vec);
PetscErrorCode BoltContactSetNodalStates(BoltContactSet *, BoltContactWork *, const unsigned char[], Vec);
void           BoltContactElementForces(BoltContactSet *, PetscInt, const PetscReal[], PetscReal[12]);
PetscErrorCode BoltContactSetSmoothedNormalTraction(BoltContactSet *, BoltContactWork *, const PetscReal[], PetscReal[]);
PetscErrorCode BoltContactSetElementStiffness(BoltContactSet *, PetscInt, PetscReal, PetscReal, const PetscBool[], const PetscBool[], const PetscReal[], PetscReal[576]);
PetscErrorCode BoltContactSetView(BoltContactSet *, PetscViewer);
PetscErrorCode BoltContactSetDestroy(BoltContactSet **);

/* contact_state.c: one model's state */
PetscErrorCode BoltContactStateCreate(BoltContactSet *, BoltContactState **);
PetscErrorCode BoltContactStateReset(BoltContactState *);
void             BoltContactStateAnchorGaps(BoltContactState *, PetscReal[]);
void             BoltContactStateSetAnchors(BoltContactState *, const PetscReal[]);
const PetscReal *BoltContactStateForceMultipliers(BoltContactState *);
PetscErrorCode BoltContactStateSetPenaltyScale(BoltContactState *, PetscReal, PetscReal);
PetscErrorCode BoltContactStateGaps(BoltContactState *);
PetscErrorCode BoltContactStateAugment(BoltContactState *, PetscReal *, PetscReal *);
PetscErrorCode BoltContactStateOpenTraction(BoltContactState *, PetscReal[]);
PetscErrorCode BoltContactStateUpdateActive(BoltContactState *, const PetscReal[], PetscInt *, PetscBool *);
PetscErrorCode BoltContactStateCloseCycle(BoltContactState *, PetscInt *);
void           BoltContactStateExtrapolate(BoltContactState *);
void           BoltContactStateEndStep(BoltContactState *);
void           BoltContactStateEndSolve(BoltContactState *, PetscBool);
void           BoltContactStateStaticStart(BoltContactState *);
PetscErrorCode BoltContactStateStickEnergy(BoltContactState *, PetscReal *);
PetscErrorCode BoltContactStateContactWork(BoltContactState *, PetscReal *);
#define BOLT_FRICTION_MARGIN 1e-6 /* a sticking pair slips once its traction is beyond the cone by this fraction */
PetscErrorCode BoltContactStateDissipated(BoltContactState *, PetscReal *);
PetscErrorCode BoltContactStateSetTotals(BoltContactState *, PetscReal, PetscReal);
PetscErrorCode BoltContactStateSetActive(BoltContactState *, const PetscBool[], const PetscBool[]);
PetscErrorCode BoltContactStateStiffness(BoltContactState *, Mat *);
PetscErrorCode BoltContactStateNormalForcePerPair(BoltContactState *, PetscReal[]);
#define BOLT_PAIR_FORCE 4 /* per pair: the force on side b (x, y, z) and the normal force */
PetscErrorCode BoltContactStatePairForces(BoltContactState *, PetscReal[]);
PetscErrorCode BoltContactStateNodalForces(BoltContactState *, Vec);
/* A contact point's state in the output (BoltContactStatePointCodes): open, closed and sticking
   (inside the cone under friction), or closed and sliding (on the cone, or a re-closed pair that
   slides under -contact_reclose slide). A node's state in the output is 1 + the code of most of
   the points at it (BoltOutputContactState), 0 where it has none. */
enum { BOLT_POINT_OPEN = 0, BOLT_POINT_STICK = 1, BOLT_POINT_SLIP = 2 };
void           BoltContactStatePointCodes(BoltContactState *, unsigned char[]);
PetscErrorCode BoltContactStateTractionStats(BoltContactState *, PetscReal *, PetscReal *, PetscReal *);
PetscErrorCode BoltContactStateDot(BoltContactState *, const PetscReal[], const PetscReal[], PetscReal *);
PetscErrorCode BoltContactStatePenetration(BoltContactState *, PetscReal[], PetscReal *);
PetscErrorCode BoltContactStateCountActive(BoltContactState *);
PetscErrorCode BoltContactStateCountReclosed(BoltContactState *, PetscInt *, PetscInt *);
PetscErrorCode BoltContactStateReleaseStiffness(BoltContactState *);
PetscErrorCode BoltContactStateComplementarity(BoltContactState *, PetscReal *, PetscReal *, PetscReal *, PetscReal *);
#define BOLT_CONTACT_PACK 108 /* values per element of BoltContactStatePack */
void           BoltContactStatePack(BoltContactState *, PetscInt, PetscReal[]);
void           BoltContactStateUnpack(BoltContactState *, PetscInt, const PetscReal[]);
PetscErrorCode BoltContactStateDestroy(BoltContactState **);
/* To be called (on every rank) after the multipliers or flags were changed from outside. */
static inline void BoltContactStateChanged(BoltContactState *s)
{
  s->version++;
  s->lambdaZero = PETSC_FALSE;
}
/* What a state's law is (contact_law.c), for the modules that choose by it: Coulomb friction at
   closed pairs (slip, dissipation, a convergence measure of its own); one-sided contact at every
   node pair solved by the active-set loop (its gaps close to the gap tolerance); a penalty whose
   energy 1/2 q' K_c q the contact stores; multipliers that hold the tractions of the last solve
   (the strict laws' loop, and friction with a penalty normal, the interface-reduced ROM, where
   the normal part is the penalty's traction and the tangential one the return map's). */
PetscBool BoltContactSetHasFriction(const BoltContactSet *);
PetscBool BoltContactSetIsComplementarity(const BoltContactSet *);
PetscBool BoltContactStateHasFriction(const BoltContactState *);
PetscBool BoltContactStateIsComplementarity(const BoltContactState *);
PetscBool BoltContactStateHasPenaltyEnergy(const BoltContactState *);
PetscBool BoltContactStateLambdaIsTraction(const BoltContactState *);
/* The law's trial traction at point gp of a multiplier and a gap under the point's penalties. */
void           BoltContactStateTrialOf(const BoltContactState *, PetscInt, const PetscReal[3], const PetscReal[3], PetscReal[3]);
/* Element e's 24x24 stiffness of its active points under the state's law. */
PetscErrorCode BoltContactStateElementStiffness(BoltContactState *, PetscInt, PetscReal[576]);

#endif
