#ifndef BOLTROM_H
#define BOLTROM_H
/* boltrom: vibration of bolted joints with contact, full and reduced order models.
   One struct per concept, each with a Create / SetFromOptions / SetUp / View / Destroy cycle. */
#include <petscdmplex.h>
#include <petscksp.h>
#include <slepceps.h>
#include <petscsf.h>
#include <petscbt.h>
#include "boltrom_element.h"

#define BOLTROM_MAX_PARTS 32
#define BOLTROM_MAX_PAIRS 32
#define BOLTROM_NAME_LEN  128

/* sys/json.c: the run summary's writer, which every module may write its keys to */
typedef struct _n_BoltJSON BoltJSON;

/* ------------------------------------------------------------------ log_events.c */
/* Every -log_view event and stage of boltrom (the paper's Table 2 phases: CONTACT_STIFFNESS,
   DISPLACEMENTS, CONTACT_FORCES), registered once by BoltLogRegister */
extern PetscLogEvent BOLT_EVENT_MESH_READ, BOLT_EVENT_MESH_DISTRIBUTE, BOLT_EVENT_ASSEMBLY,
                     BOLT_EVENT_CONTACT_SET_UP, BOLT_EVENT_CONTACT_ASSEMBLY, BOLT_EVENT_LOADS,
                     BOLT_EVENT_FACTORIZATION, BOLT_EVENT_STATIC_SOLVE, BOLT_EVENT_MODAL_SOLVE,
                     BOLT_EVENT_OUTPUT, BOLT_EVENT_CONTACT_STIFFNESS, BOLT_EVENT_DISPLACEMENTS,
                     BOLT_EVENT_CONTACT_FORCES, BOLT_EVENT_CONTACT_UPDATE, BOLT_EVENT_BASIS,
                     BOLT_EVENT_PROJECTION, BOLT_EVENT_KRYLOV_FACTOR, BOLT_EVENT_KRYLOV_SOLVE,
                     BOLT_EVENT_KRYLOV_ORTH, BOLT_EVENT_INTERFACE_REDUCTION;
extern PetscLogStage BOLT_STAGE_SET_UP, BOLT_STAGE_STATIC, BOLT_STAGE_MODAL, BOLT_STAGE_OUTPUT,
                     BOLT_STAGE_PRELOAD, BOLT_STAGE_TRANSIENT;
PetscErrorCode BoltLogRegister(void);
PetscErrorCode BoltMemoryPrint(MPI_Comm, const char[]);
PetscErrorCode BoltMemoryRelease(void);

/* ------------------------------------------------------------------ material.c */
typedef struct _n_BoltMaterial BoltMaterial;

typedef struct _n_BoltMaterialTable BoltMaterialTable;

PetscErrorCode BoltMaterialTableSetFromOptions(MPI_Comm, BoltMaterialTable *);
PetscErrorCode BoltMaterialTableFind(MPI_Comm, const BoltMaterialTable *, const char[], PetscInt *);
PetscErrorCode BoltMaterialTableDestroy(BoltMaterialTable **);

/* ------------------------------------------------------------------ mesh.c */
/* The distributed mesh, its parts and groups, and the DOF layout (3 per vertex, clamp removed). */
typedef struct {
  MPI_Comm          comm;
  char              filename[PETSC_MAX_PATH_LEN];
  char              clampGroup[BOLTROM_NAME_LEN];
  PetscBool         clamp;          /* remove the clamp group's DOFs from the global system */
  char              supportGroup[BOLTROM_NAME_LEN]; /* -support_group: nodes held in some components only ("": none) */
  PetscInt          supportComponents[3], nsupportComponents; /* the components held there, ascending */
  char              partitioner[64]; /* metis (ours, through a shell partitioner) or a PETSc type */
  DM                dm;
  PetscInt          nparts;
  char              partName[BOLTROM_MAX_PARTS][BOLTROM_NAME_LEN];
  PetscInt          partMaterial[BOLTROM_MAX_PARTS]; /* index in the material table */
  char              partMaterialMap[PETSC_MAX_PATH_LEN]; /* part:material,... */
  PetscInt          cStart, cEnd, vStart, vEnd;
  PetscInt         *cellPart;        /* part index of each local cell */
  PetscInt          pStart, pEnd;
  PetscBT           pointGhost;      /* point owned by another rank (pStart-based) */
  PetscInt         *pointOriginal;   /* number of each local point in the mesh as read (pStart-based) */
  PetscInt          partTag[BOLTROM_MAX_PARTS]; /* gmsh physical tag = label value */
  PetscInt          nverticesGlobal, ncellsGlobal, ndofsFree;
  PetscInt          edgeCut;         /* faces between cells of different ranks, after distribution */
  BoltMaterialTable *materials;  /* owned */
  Hex8Formulation   formulation;
} BoltMesh;

PetscErrorCode BoltMeshCreate(MPI_Comm, BoltMesh **);
PetscErrorCode BoltMeshSetFromOptions(BoltMesh *);
PetscErrorCode BoltMeshSetUp(BoltMesh *);
PetscErrorCode BoltMeshView(BoltMesh *, PetscViewer);
PetscErrorCode BoltMeshDestroy(BoltMesh **);
/* Part p's material: its name, Young's modulus [Pa], Poisson's ratio and density [kg/m^3] */
PetscErrorCode BoltMeshPartMaterial(BoltMesh *, PetscInt, const char **, PetscReal *, PetscReal *, PetscReal *);
PetscErrorCode BoltMeshHasGroup(BoltMesh *, const char[], PetscBool *);
PetscErrorCode BoltMeshCellCoordinates(BoltMesh *, PetscInt, PetscReal[24]);
PetscErrorCode BoltMeshCellDofs(BoltMesh *, PetscInt, PetscInt[24]);
PetscErrorCode BoltMeshCellVertices(BoltMesh *, PetscInt, PetscInt[8]);
PetscErrorCode BoltMeshVertexDofs(BoltMesh *, PetscInt, PetscInt[3]);
PetscErrorCode BoltMeshSetNodeValues(Vec, const PetscInt[3], const PetscScalar[3], InsertMode);
PetscErrorCode BoltMeshDofKeys(BoltMesh *, Vec, Vec *);
PetscErrorCode BoltMeshVertexOwned(BoltMesh *, PetscInt, PetscBool *);
PetscErrorCode BoltMeshGroupPoints(BoltMesh *, const char[], PetscBool, PetscInt *, PetscInt **);
PetscErrorCode BoltMeshGroupVertices(BoltMesh *, const char[], PetscBool, PetscInt *, PetscInt **);
PetscErrorCode BoltMeshFaceVertices(BoltMesh *, PetscInt, PetscInt *, PetscInt[4], PetscReal[12]);
PetscErrorCode BoltMeshFillVertexField(BoltMesh *, PetscErrorCode (*)(const PetscReal[3], PetscInt, PetscReal[3], void *), void *, Vec);

/* ------------------------------------------------------------------ assembly.c */
typedef struct _n_BoltAssembler BoltAssembler;

PetscErrorCode BoltAssemblerCreate(BoltMesh *, BoltAssembler **);
PetscErrorCode BoltAssemblerSetFromOptions(BoltAssembler *);
PetscErrorCode BoltAssemblerSetUp(BoltAssembler *);
PetscErrorCode BoltAssemblerDamping(BoltAssembler *, Mat *);
PetscErrorCode BoltAssemblerPartStiffness(BoltAssembler *, PetscInt, Mat *);
PetscErrorCode BoltAssemblerView(BoltAssembler *, PetscViewer);
PetscErrorCode BoltAssemblerGetMatrices(BoltAssembler *, Mat *, Mat *);
PetscErrorCode BoltAssemblerGetRayleigh(BoltAssembler *, PetscReal *, PetscReal *);
PetscErrorCode BoltAssemblerGetMesh(BoltAssembler *, BoltMesh **);
PetscErrorCode BoltAssemblerGetPart(BoltAssembler *, PetscInt, PetscReal *, PetscReal *, PetscInt *);
PetscErrorCode BoltAssemblerDestroy(BoltAssembler **);

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

/* ------------------------------------------------------------------ loads.c */
typedef struct _n_BoltLoadSet BoltLoadSet;
Vec              BoltLoadSetLoad(const BoltLoadSet *);
Vec              BoltLoadSetLoadUnit(const BoltLoadSet *);
Vec              BoltLoadSetPreload(const BoltLoadSet *);
PetscBool        BoltLoadSetHasPreload(const BoltLoadSet *);
PetscReal        BoltLoadSetPreloadForce(const BoltLoadSet *);
const char      *BoltLoadSetPreloadGroup(const BoltLoadSet *, PetscInt);
const char      *BoltLoadSetLoadGroup(const BoltLoadSet *);
PetscReal        BoltLoadSetLoadForce(const BoltLoadSet *);
const PetscReal *BoltLoadSetLoadDirection(const BoltLoadSet *);
const char      *BoltLoadSetProbeGroup(const BoltLoadSet *);
PetscInt         BoltLoadSetProbeComponent(const BoltLoadSet *);
PetscInt         BoltLoadSetProbeDof(const BoltLoadSet *);
const PetscReal *BoltLoadSetProbeCoordinates(const BoltLoadSet *);

PetscErrorCode BoltLoadSetCreate(BoltMesh *, BoltLoadSet **);
PetscErrorCode BoltLoadSetSetFromOptions(BoltLoadSet *);
PetscErrorCode BoltLoadSetSetUp(BoltLoadSet *, Vec);
PetscErrorCode BoltLoadSetProbe(BoltLoadSet *, Vec, PetscReal *);
PetscErrorCode BoltLoadSetView(BoltLoadSet *, PetscViewer);
PetscErrorCode BoltLoadSetDestroy(BoltLoadSet **);

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
typedef enum { BOLT_OP_CONTACT_DISPLACEMENTS, BOLT_OP_CONTACT_FORCES, BOLT_OP_CONTACT_STIFFNESS, BOLT_OP_CONTACT_GAPS, BOLT_OP_OPEN_TRACTION, BOLT_OP_PROBE, BOLT_OP_VECTORS_SAVE, BOLT_OP_VECTORS_LOAD, BOLT_OP_STATE_SAVE, BOLT_OP_STATE_LOAD, BOLT_OP_VIEW, BOLT_OP_DESTROY, BOLT_OP_FACTOR, BOLT_OP_SOLVE } BoltOperatorOp;
PetscErrorCode    BoltOperatorSetOperation(BoltOperator *, BoltOperatorOp, void (*)(void));
PetscErrorCode    BoltOperatorSetSolver(BoltOperator *, const char[], MatSolverType, PetscBool, PetscBool);
PetscErrorCode    BoltOperatorGetSolver(BoltOperator *, const char *[], MatSolverType *);
PetscErrorCode    BoltOperatorSetContext(BoltOperator *, void *);
PetscErrorCode    BoltOperatorCopyLoads(BoltOperator *, Vec, Vec);
PetscErrorCode    BoltOperatorContactDisplacements(BoltOperator *, Vec);
PetscErrorCode    BoltOperatorContactStiffness(BoltOperator *, Mat *);
PetscErrorCode    BoltOperatorProbe(BoltOperator *, Vec, PetscReal *);
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
PetscErrorCode BoltNewmarkSetPreloadTarget(BoltNewmark *, PetscReal);
/* newmark_results.c: what a run hands the rest of the program (read-only) */
typedef enum { BOLT_HISTORY_TIME, BOLT_HISTORY_PROBE, BOLT_HISTORY_ENERGY, BOLT_HISTORY_SLIPPING, BOLT_HISTORY_DISSIPATED, BOLT_HISTORY_LEDGER, BOLT_HISTORY_PAIR_FORCE } BoltHistory;
PetscErrorCode BoltNewmarkGetHistory(BoltNewmark *, BoltHistory, PetscInt *, const PetscReal **);
PetscErrorCode BoltNewmarkGetSnapshots(BoltNewmark *, PetscInt *, Vec **, const PetscReal **, const unsigned char **);
PetscErrorCode BoltNewmarkGetModel(BoltNewmark *, BoltOperator **, BoltDual **, Vec *);
PetscErrorCode BoltNewmarkGetTiming(BoltNewmark *, PetscReal *, PetscReal *);
PetscErrorCode BoltNewmarkGetStaticSolve(BoltNewmark *, PetscReal *, PetscReal *);
PetscErrorCode BoltNewmarkGetLoad(BoltNewmark *, BoltLoadHistory *, PetscReal *);
PetscErrorCode BoltNewmarkSetCheckpointBase(BoltNewmark *, const char[]);
PetscErrorCode BoltNewmarkOptionsCheck(MPI_Comm, const char[], char[]);
PetscErrorCode BoltNewmarkPreloadSummaryWrite(BoltNewmark *, BoltJSON *);
PetscErrorCode BoltNewmarkSummaryWrite(BoltNewmark *, BoltJSON *, PetscBool);
PetscErrorCode BoltNewmarkCheckpointWrite(BoltNewmark *);
PetscErrorCode BoltNewmarkCheckpointRead(BoltNewmark *);

/* ------------------------------------------------------------------ exact_sum.c */
/* n sums over ranks that give the same bits on any partition (two fixed grids per term) */
typedef struct _n_BoltExactSum BoltExactSum;
PetscErrorCode BoltExactSumBegin(BoltExactSum *, PetscInt, PetscReal, PetscInt);
void           BoltExactSumAdd(BoltExactSum *, const PetscReal[]);
void           BoltExactSumAddParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
void           BoltExactSumReplaceParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
PetscErrorCode BoltExactSumEnd(BoltExactSum *, MPI_Comm, PetscReal[]);
PetscErrorCode BoltExactSumCreate(BoltExactSum **);
PetscErrorCode BoltExactSumGetPartials(BoltExactSum *, PetscReal[]);
PetscErrorCode BoltExactSumSetPartials(BoltExactSum *, const PetscReal[]);
PetscErrorCode BoltExactSumDestroy(BoltExactSum **);

/* ------------------------------------------------------------------ gather.c */
PetscErrorCode BoltGatherAll(MPI_Comm, MPI_Datatype, const void *, PetscInt, void *, PetscInt *, PetscInt *, PetscInt *);
PetscErrorCode BoltGrowReal(PetscReal **, PetscInt *, PetscInt);

/* ------------------------------------------------------------------ reduction.c, rom.c */
/* The reduction's options as given (-rom_*, read by BoltROMSetFromOptions); 0 or -1 where the
   default is resolved by BoltROMSetUp */
typedef struct _n_BoltReductionOptions BoltReductionOptions;

/* The ROM file's fingerprint: typed fields, each a setting the basis depends on. */
#define BOLTROM_FINGERPRINT_FIELDS 256
typedef struct _n_BoltROMFingerprintField BoltROMFingerprintField;
typedef struct _n_BoltROMFingerprint BoltROMFingerprint;

/* The reduced model: projected matrices (replicated on every rank, small and dense), the rows
   of the basis at this rank's contact DOFs and at the probe, and the reduced contact stiffness
   kept up to date element by element. */
typedef struct _n_BoltROM BoltROM;

/* rom_update.c: the online factorisation kept across changes of the active set */
typedef struct BoltROMUpdate_s BoltROMUpdate;
PetscErrorCode BoltROMUpdateCreate(BoltROM *, BoltOperator *, PetscInt);
PetscErrorCode BoltROMUpdateSettle(BoltOperator *);
void           BoltROMUpdateSummed(BoltROMUpdate *, BoltROM *, PetscInt);
PetscErrorCode BoltROMUpdateView(BoltROMUpdate *, PetscViewer);
PetscInt       BoltROMUpdateLargestBatch(const BoltROMUpdate *);
PetscErrorCode BoltROMUpdateDestroy(BoltROMUpdate **);


/* The ROM's life cycle (rom_object.c): options read once at the start whatever -rom says (a
   scene may carry them with the ROM off), every default resolved by SetUp, which builds the ROM
   or reads a matching -rom_file; the online operator owns its caches. */
PetscErrorCode BoltROMCreate(MPI_Comm, BoltROM **);
PetscErrorCode BoltROMSetFromOptions(BoltROM *);
PetscErrorCode BoltROMSolversSetFromOptions(BoltROM *);
PetscErrorCode BoltROMCheckOptions(BoltROM *, BoltContactSet *);
PetscErrorCode BoltROMSetTraining(BoltROM *, const BoltPreloadState *, PetscInt, Vec[]);
PetscErrorCode BoltROMSetUp(BoltROM *, BoltAssembler *, BoltContactSet *, BoltLoadSet *);
PetscErrorCode BoltROMView(BoltROM *, PetscViewer);
PetscErrorCode BoltROMSummaryWrite(BoltROM *, BoltJSON *);
PetscErrorCode BoltROMGetMatrices(BoltROM *, Mat *, Mat *);
PetscErrorCode BoltROMDestroy(BoltROM **);
PetscErrorCode BoltROMGetFile(BoltROM *, const char *[]);
PetscErrorCode BoltROMGetSnapshotModes(BoltROM *, PetscInt *);
PetscErrorCode BoltROMOperatorCreate(BoltROM *, BoltOperator **);
PetscErrorCode BoltROMSetPreloadState(BoltROM *, BoltNewmark *, PetscReal);
PetscErrorCode BoltROMCheckAtS0(BoltROM *, BoltOperator *, BoltAssembler *, BoltContactSet *, BoltLoadSet *, PetscReal *);
PetscErrorCode BoltHistoryErrors(PetscInt, const PetscReal[], const PetscReal[], PetscReal *, PetscReal *);
/* rom_field.c: the ROM's displacement in full, u = V q, while the ROM keeps its whole basis (built, or read from its file) */
PetscErrorCode BoltROMKeepBasis(BoltROM *, BV);
PetscErrorCode BoltROMHasBasis(BoltROM *, PetscBool *);
PetscErrorCode BoltROMExpand(BoltROM *, Vec, Vec);
PetscErrorCode BoltROMReleaseBasis(BoltROM *);
PetscErrorCode BoltROMBasisSave(BoltROM *, BV, BoltMesh *, PetscViewer);
PetscErrorCode BoltROMBasisEnsure(BoltROM *, BoltMesh *, Vec, PetscBool *);

/* ------------------------------------------------------------------ analysis.c */
PetscErrorCode BoltStaticSolve(Mat, Vec, Vec, const char[]);
PetscErrorCode BoltModalSolve(Mat, Mat, PetscInt, const char[], PetscInt *, PetscReal[]);

/* ------------------------------------------------------------------ app/output.c, app/json.c */
typedef struct _n_BoltOutput BoltOutput;

PetscErrorCode BoltOutputOpen(BoltMesh *, const char[], const char[], BoltOutput *);
PetscErrorCode BoltOutputVertexField(BoltOutput *, BoltMesh *, Vec, const char[]);
PetscErrorCode BoltOutputClose(BoltOutput *, BoltMesh *);
PetscErrorCode BoltOutputSeries(BoltOutput *, const char[], const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputPairForces(BoltOutput *, const char[], BoltContactSet *, PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputSnapshot(BoltOutput *, BoltMesh *, const char[], PetscInt, Vec);
PetscErrorCode BoltOutputSnapshotSeries(BoltOutput *, const char[], PetscInt, const PetscReal[], PetscBool);
PetscErrorCode BoltOutputContactState(BoltOutput *, BoltMesh *, BoltContactSet *, const unsigned char[], const char[]);
PetscErrorCode BoltOutputSnapshotStates(BoltOutput *, BoltMesh *, const char[], BoltContactSet *, PetscInt, const unsigned char[]);

/* The JSON summary writer (src/sys/json.c); docs/outputs.md lists the keys. */
PetscErrorCode BoltJSONOpen(MPI_Comm, const char[], BoltJSON **);
PetscErrorCode BoltJSONBeginObject(BoltJSON *, const char[]);
PetscErrorCode BoltJSONEndObject(BoltJSON *);
PetscErrorCode BoltJSONInt(BoltJSON *, const char[], PetscInt);
PetscErrorCode BoltJSONReal(BoltJSON *, const char[], PetscReal);
PetscErrorCode BoltJSONString(BoltJSON *, const char[], const char[]);
PetscErrorCode BoltJSONRealArray(BoltJSON *, const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltJSONClose(BoltJSON **);

/* ------------------------------------------------------------------ sys/hdf5.c: folders, datasets */
PetscErrorCode BoltMakeDir(MPI_Comm, const char[]);
PetscErrorCode BoltMakeParentDir(MPI_Comm, const char[]);
/* sys/option_vector.c: a vector option of exactly n finite reals, inside PetscOptionsBegin/End */
PetscErrorCode BoltOptionsRealVector(PetscOptionItems *, const char[], const char[], PetscInt, PetscReal[], PetscBool *);
PetscErrorCode BoltHDF5WriteValues(PetscViewer, MPI_Comm, const char[], PetscInt, PetscInt, const PetscScalar[], PetscBool);
PetscErrorCode BoltHDF5WriteVecs(PetscViewer, MPI_Comm, PetscInt, const char *const[], Vec[], PetscBool);
PetscErrorCode BoltReadAll(PetscViewer, MPI_Comm, const char[], PetscInt *, PetscReal **);
/* Sorted keys of a keyed dataset and the permutation to their rows. */
typedef struct _n_BoltKeyIndex BoltKeyIndex;
PetscErrorCode BoltKeyIndexCreate(PetscInt, const PetscReal[], BoltKeyIndex **);
PetscInt       BoltKeyIndexSize(const BoltKeyIndex *);
PetscErrorCode BoltKeyIndexFind(BoltKeyIndex *, PetscInt, PetscInt *);
PetscErrorCode BoltKeyIndexDestroy(BoltKeyIndex **);
/* Attributes of the root group "/" of an open HDF5 viewer's file (collective, same values on every rank) */
PetscErrorCode BoltHDF5AttributeString(PetscViewer, const char[], const char[]);
PetscErrorCode BoltHDF5AttributeStrings(PetscViewer, const char[], PetscInt, const char *const[]);
PetscErrorCode BoltHDF5AttributeInt(PetscViewer, const char[], PetscInt);
PetscErrorCode BoltHDF5AttributeReals(PetscViewer, const char[], PetscInt, const PetscReal[]);

/* ------------------------------------------------------------------ solver.c */
/* Direct solvers (PREONLY + LU or Cholesky) of the analyses, the reduction and the time
   integrators; prefix NULL: not configurable from the command line. */
PetscErrorCode BoltDirectSolverSetType(KSP, PetscBool, MatSolverType);
PetscErrorCode BoltDirectSolverCreate(MPI_Comm, const char[], Mat, PetscBool, MatSolverType, KSP *);
PetscErrorCode BoltDirectSolverSetFromOptions(MPI_Comm, const char[], PetscBool, MatSolverType);
PetscErrorCode BoltModalSetFromOptions(MPI_Comm, PetscInt, const char[]); /* analysis.c */


/* ------------------------------------------------------------------ run.c */
/* What a run does and where it writes (main's options). */
typedef struct _n_BoltRunOptions BoltRunOptions;

PetscErrorCode BoltRunOptionsSetFromOptions(MPI_Comm, BoltRunOptions *);

/* ------------------------------------------------------------------ preflight.c */
/* Checks before any computation: options nobody reads, folders that cannot be written. */
typedef enum { BOLT_OPTIONS_BEFORE_SETUP, BOLT_OPTIONS_BEFORE_SOLVE, BOLT_OPTIONS_FINAL } BoltOptionsStage;
PetscErrorCode BoltOptionsCheckUnused(MPI_Comm, BoltOptionsStage);
PetscErrorCode BoltCheckWritableDir(MPI_Comm, const char[], const char[]);
PetscErrorCode BoltCheckWritableParent(MPI_Comm, const char[], const char[]);
PetscErrorCode BoltPreflightSetFromOptions(MPI_Comm, const BoltRunOptions *, char[]);
PetscErrorCode BoltPreflightCheck(MPI_Comm, const BoltRunOptions *, BoltROM *, const char[]);

/* ------------------------------------------------------------------ verify.c */
/* Checks of the assembled model (-verify_fields, -check_rigid) and the export of the tied and
   reduced matrices (-export_matrices) for petsc4py. */
PetscErrorCode BoltExportMatrix(Mat, const char[], const char[]);
PetscErrorCode BoltExportTied(const char[], Mat, Mat);
PetscErrorCode BoltExportReduced(const char[], BoltROM *, BoltOperator *);
PetscErrorCode BoltVerifyFields(BoltMesh *, Mat, Mat, Vec, PetscInt, Vec *, Vec *, Vec *);
PetscErrorCode BoltCheckRigid(BoltAssembler *, Vec, PetscReal[]);

/* ------------------------------------------------------------------ summary.c */
/* A run's results: its objects and the figures of its stages, written as the JSON summary
   (-summary) and the HDF5/XDMF fields. A stage that did not run leaves its pointer NULL or its
   flag false, and has no block. */
typedef struct _n_BoltSummary BoltSummary;

PetscErrorCode BoltSummaryWrite(MPI_Comm, const char[], const BoltSummary *);
PetscErrorCode BoltSummaryWriteFields(const BoltSummary *, const char[], const char[]);
/* metadata.c: the result file's root attributes and the summary's load and friction fields */
PetscErrorCode BoltSummaryWriteAttributes(const BoltSummary *, PetscViewer);
PetscErrorCode BoltSummaryWriteLoad(BoltJSON *, const BoltSummary *);

/* ------------------------------------------------------------------ run.c (stages) */
/* A run's objects, made and configured by main; sum collects what the stages report. */
typedef struct _n_BoltRun BoltRun;

PetscErrorCode BoltRunTied(BoltRun *);
PetscErrorCode BoltRunFOM(BoltRun *);
PetscErrorCode BoltRunROM(BoltRun *);

#endif
