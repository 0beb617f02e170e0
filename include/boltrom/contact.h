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
typedef struct _n_BoltContactSet BoltContactSet;

/* The contact state of one model (contact_state.c): its law and penalties, and at every Gauss
   point the multiplier, the gap and the active flags of the last three outer iterations; the
   element matrices and K_c of its active set. Each operator owns one. */
typedef struct _n_BoltContactState BoltContactState;

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
PetscErrorCode BoltContactStateAssembleLinearised(BoltContactState *, Mat, Mat *, PetscInt[3]);
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
/* state_check.c: every point checked from raw gaps computed at every point */
PetscErrorCode BoltContactStateCheck(BoltContactState *, const PetscReal[], const PetscBool[], const PetscReal[], const PetscReal[], PetscReal[3], PetscInt *);
#define BOLT_CONTACT_PACK 108 /* values per element of BoltContactStatePack */
void           BoltContactStatePack(BoltContactState *, PetscInt, PetscReal[]);
void           BoltContactStateUnpack(BoltContactState *, PetscInt, const PetscReal[]);
PetscErrorCode BoltContactStateDestroy(BoltContactState **);
/* To be called (on every rank) after the multipliers or flags were changed from outside. */
void BoltContactStateChanged(BoltContactState *);
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
void           BoltContactStatePointPenalties(const BoltContactState *, PetscInt, PetscReal *, PetscReal *);
/* Element e's 24x24 stiffness of its active points under the state's law. */
PetscErrorCode BoltContactStateElementStiffness(BoltContactState *, PetscInt, PetscReal[576]);

/* access.c, state_access.c: what the set and a state tell other modules; the arrays are the
   state's own, written in place, followed by BoltContactStateChanged */
BoltMesh *BoltContactSetMesh(const BoltContactSet *);
PetscInt BoltContactSetElementCount(const BoltContactSet *);
PetscInt BoltContactSetPairCount(const BoltContactSet *);
const char *BoltContactSetPairName(const BoltContactSet *, PetscInt);
PetscReal BoltContactSetPairArea(const BoltContactSet *, PetscInt);
PetscReal BoltContactSetFriction(const BoltContactSet *, PetscInt);
PetscReal BoltContactSetPairPenalty(const BoltContactSet *, PetscInt);
PetscReal BoltContactSetPairStickStiffness(const BoltContactSet *, PetscInt);
PetscInt BoltContactSetLocalSize(const BoltContactSet *);
PetscInt BoltContactSetPointCountGlobal(const BoltContactSet *);
PetscInt BoltContactSetDofCount(const BoltContactSet *);
PetscInt BoltContactSetQuadrature(const BoltContactSet *);
const char *BoltContactSetLawType(const BoltContactSet *);
PetscBool BoltContactSetReanchor(const BoltContactSet *);
PetscBool BoltContactSetAugmented(const BoltContactSet *);
PetscReal BoltContactSetGapTolerance(const BoltContactSet *);
PetscReal BoltContactSetPenaltyFactor(const BoltContactSet *);
PetscReal BoltContactSetActivationGap(const BoltContactSet *);
PetscReal BoltContactSetMatchTolerance(const BoltContactSet *);
const char *BoltContactSetOpenTest(const BoltContactSet *);
void BoltContactSetSlipTolerances(const BoltContactSet *, PetscReal *, PetscReal *);
PetscReal BoltContactSetMinEdge(const BoltContactSet *);
const PetscReal *BoltContactSetShapeValues(const BoltContactSet *);
const PetscReal *BoltContactSetWeights(const BoltContactSet *);
const PetscReal *BoltContactSetNormals(const BoltContactSet *);
const PetscInt *BoltContactSetElementLocal(const BoltContactSet *);
const PetscInt *BoltContactSetLocalGlobal(const BoltContactSet *);
const PetscReal *BoltContactSetNodalArea(const BoltContactSet *);
VecScatter BoltContactSetScatterContext(const BoltContactSet *);
Vec BoltContactSetLayout(const BoltContactSet *);
PetscErrorCode BoltContactSetSummaryWrite(const BoltContactSet *, BoltJSON *);
PetscErrorCode BoltContactSetPairValuesWrite(const BoltContactSet *, BoltJSON *, const char[], const PetscInt[], const PetscReal[]);
BoltContactSet *BoltContactStateSet(const BoltContactState *);
BoltContactWork *BoltContactStateWork(const BoltContactState *);
const char *BoltContactStateLawType(const BoltContactState *);
PetscReal *BoltContactStateLambda(BoltContactState *);
PetscReal *BoltContactStateGap(BoltContactState *);
PetscReal *BoltContactStateAnchor(BoltContactState *);
const PetscReal *BoltContactStateLambdaForce(const BoltContactState *);
PetscBool *BoltContactStateActive(BoltContactState *);
const PetscBool *BoltContactStateActiveOld(const BoltContactState *);
PetscBool *BoltContactStateReleased(BoltContactState *);
PetscBool *BoltContactStateDirty(BoltContactState *);
const PetscReal *BoltContactStateElementBlocks(const BoltContactState *);
PetscInt BoltContactStateActiveCount(const BoltContactState *);
PetscBool BoltContactStateAugmented(const BoltContactState *);
PetscObjectState BoltContactStateVersion(const BoltContactState *);
PetscBool        BoltContactStateSettled(const BoltContactState *);
const PetscBool *BoltContactStateMayChange(const BoltContactState *);
PetscReal BoltContactStateFrictionChange(const BoltContactState *);
PetscBool BoltContactStateCloseOnly(const BoltContactState *);
PetscInt BoltContactStateOpenTest(const BoltContactState *);
PetscBool BoltContactStateStickOnly(const BoltContactState *);
PetscBool BoltContactStateHoldContact(const BoltContactState *);
PetscReal BoltContactStateBandTraction(const BoltContactState *, PetscInt);
PetscReal BoltContactStateActivationGap(const BoltContactState *);
PetscErrorCode BoltContactStateSetCloseOnly(BoltContactState *, PetscBool);
PetscErrorCode BoltContactStateSetHoldContact(BoltContactState *, PetscBool);
PetscErrorCode BoltContactStateSetStickOnly(BoltContactState *, PetscBool);
PetscErrorCode BoltContactStateSetAugment(BoltContactState *, PetscBool);
PetscErrorCode BoltContactStateSetMayChange(BoltContactState *, const PetscBool[]);

#endif
