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

/* ------------------------------------------------------------------ log_events.c */
typedef struct {
  PetscLogEvent meshRead, meshDistribute, assembly, contactSetUp, contactAssembly, loads;
  PetscLogEvent factorization, staticSolve, modalSolve, output;
  PetscLogEvent contactStiffness, displacements, contactForces; /* the paper's Table 2 phases */
  PetscLogEvent contactUpdate;                                  /* the state's augmentation and decisions */
  PetscLogEvent basis, projection, krylovFactor, krylovSolve, krylovOrth, interfaceReduction;
  PetscLogStage stageSetUp, stageStatic, stageModal, stageOutput, stagePreload, stageTransient;
} BoltLog;
extern BoltLog boltLog;
PetscErrorCode BoltLogRegister(void);
PetscErrorCode BoltMemoryPrint(MPI_Comm, const char[]);
PetscErrorCode BoltMemoryRelease(void);

/* ------------------------------------------------------------------ material.c */
typedef struct {
  char      name[BOLTROM_NAME_LEN];
  PetscReal E, nu, rho;
} BoltMaterial;

typedef struct {
  PetscInt     nmat;
  BoltMaterial mat[BOLTROM_MAX_PARTS];
} BoltMaterialTable;

PetscErrorCode BoltMaterialTableSetFromOptions(MPI_Comm, BoltMaterialTable *);
PetscErrorCode BoltMaterialTableFind(MPI_Comm, const BoltMaterialTable *, const char[], PetscInt *);

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
  BoltMaterialTable materials;
  Hex8Formulation   formulation;
} BoltMesh;

PetscErrorCode BoltMeshCreate(MPI_Comm, BoltMesh **);
PetscErrorCode BoltMeshSetFromOptions(BoltMesh *);
PetscErrorCode BoltMeshSetUp(BoltMesh *);
PetscErrorCode BoltMeshView(BoltMesh *, PetscViewer);
PetscErrorCode BoltMeshDestroy(BoltMesh **);
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
typedef struct {
  BoltMesh  *mesh;
  Mat        K, M;             /* structural stiffness and consistent mass, clamp removed */
  PetscReal  rayleighAlpha, rayleighBeta;
  PetscReal  massPerPart[BOLTROM_MAX_PARTS], volumePerPart[BOLTROM_MAX_PARTS];
  PetscInt   elementsPerPart[BOLTROM_MAX_PARTS];
} BoltAssembler;

PetscErrorCode BoltAssemblerCreate(BoltMesh *, BoltAssembler **);
PetscErrorCode BoltAssemblerSetFromOptions(BoltAssembler *);
PetscErrorCode BoltAssemblerSetUp(BoltAssembler *);
PetscErrorCode BoltAssemblerDamping(BoltAssembler *, Mat *);
PetscErrorCode BoltAssemblerPartStiffness(BoltAssembler *, PetscInt, Mat *);
PetscErrorCode BoltAssemblerView(BoltAssembler *, PetscViewer);
PetscErrorCode BoltAssemblerDestroy(BoltAssembler **);

/* ------------------------------------------------------------------ contact.c */
/* A contact element: two matching quad faces, a and b. Only the owner of face a keeps it. */
typedef struct {
  PetscInt  pair;
  PetscInt  key;      /* face a's number in the mesh as read: names the element on any ranks */
  PetscReal Xa[12];
  PetscInt  dofs[24]; /* global DOFs of [a nodes, b nodes], -1 where clamped */
} BoltContactElement;

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
  Vec                 uc, fc;         /* local contact displacements and forces (sequential) */
  Vec                 fcWork, fGlobal; /* nodal sums across ranks: local and global layout */
  PetscReal          *nodalForce, *tau; /* nlocal, and 3 per Gauss point: work space of the opening test */
} BoltContactSet;

/* The contact state of one model (contact_state.c): its law and penalties, and at every Gauss
   point the multiplier, the gap and the active flags of the last three outer iterations; the
   element matrices and K_c of its active set. Each operator owns one. */
typedef struct {
  BoltContactSet *set;
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
PetscErrorCode BoltContactSetAssembleTied(BoltContactSet *, Mat, Mat *);
PetscErrorCode BoltContactSetStiffnessMatrix(BoltContactSet *, Mat *);
PetscErrorCode BoltContactSetScatter(BoltContactSet *, Vec);
PetscErrorCode BoltContactSetGapsOf(BoltContactSet *, PetscReal[]);
PetscErrorCode BoltContactSetForcesOf(BoltContactSet *, const PetscReal[], Vec);
PetscErrorCode BoltContactSetNodalStates(BoltContactSet *, const unsigned char[], Vec);
void           BoltContactElementForces(BoltContactSet *, PetscInt, const PetscReal[], PetscReal[12]);
PetscErrorCode BoltContactSetSmoothedNormalTraction(BoltContactSet *, const PetscReal[], PetscReal[]);
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
typedef struct {
  BoltMesh *mesh;
  char      loadGroup[BOLTROM_NAME_LEN];
  PetscReal loadDirection[3], loadForce;
  char      preloadGroup[2][BOLTROM_NAME_LEN];
  PetscReal preloadAxis[3], preloadForce;
  PetscBool hasPreload;
  Vec       load, preload; /* the load and preload vectors, global layout */
  Vec       loadUnit;      /* the load pattern of a 1 N force */
  char      probeGroup[BOLTROM_NAME_LEN]; /* probe: displacement component at this point group */
  PetscInt  probeComponent;
  PetscInt  probeDof;               /* global DOF of the probe on its owner, -1 elsewhere */
  PetscReal probeCoord[3];
} BoltLoadSet;

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
typedef struct {
  PetscErrorCode (*contactDisplacements)(BoltOperator *, Vec);             /* q -> contact->uc */
  PetscErrorCode (*contactForces)(BoltOperator *, const PetscReal[], Vec); /* Gauss-point tractions -> F (overwritten) */
  PetscErrorCode (*contactStiffness)(BoltOperator *, Mat *);               /* K_c of the active set */
  /* optional, else from contactDisplacements and the state's own computation: */
  PetscErrorCode (*contactGaps)(BoltOperator *, Vec, PetscReal[]);         /* q -> the gaps at the local contact points */
  PetscErrorCode (*openTraction)(BoltOperator *, PetscReal[]);             /* the traction of the opening test (BoltContactStateOpenTraction) */
  PetscErrorCode (*probe)(BoltOperator *, Vec, PetscReal *);
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
} BoltOperatorOps;

struct BoltOperator_s {
  const char       *name;     /* "FOM" or "ROM" */
  MPI_Comm          comm;     /* for messages and errors (the ROM's matrices live on every rank) */
  MatSolverType     solverType; /* LU of the effective matrix: MUMPS (FOM) or LAPACK (ROM) */
  PetscBool         exactConstraints; /* every contact gap can be closed (FOM, ROM without interface reduction) */
  PetscBool         keepStructural; /* the dual loop keeps K + a1 M + a4 C summed for its factorisations (small dense matrices: the ROM) */
  char              prefix[16]; /* options prefix of its solver: fom_ or rom_ */
  Mat               M, C, K;
  PetscReal         rayleigh[2];   /* C = rayleigh[0] M + rayleigh[1] K (BoltOperatorSetDamping) */
  Vec               load, preload; /* external load pattern and preload, in its coordinates */
  BoltContactSet   *contact;  /* the shared geometry */
  BoltContactState *state;    /* this model's own contact state */
  void             *ctx;
  BoltOperatorOps   ops;
};

PetscErrorCode BoltOperatorCreate(MPI_Comm, const char[], BoltContactSet *, BoltOperator **);
PetscErrorCode BoltOperatorSetSystem(BoltOperator *, Mat, Mat, Mat, Vec, Vec);
PetscErrorCode BoltOperatorSetDamping(BoltOperator *, Mat, PetscReal, PetscReal);
PetscErrorCode BoltOperatorView(BoltOperator *, PetscViewer);
PetscErrorCode BoltOperatorDestroy(BoltOperator **);

/* A static preloaded equilibrium, kept so that a later solve of the same scene (the ROM's offline
   phase after the FOM's run) starts from it instead of solving it again. */
typedef struct {
  Vec        q, preload;     /* displacement; preload vector as calibrated */
  PetscReal *lambda;         /* 12 per local contact element */
  PetscBool *active;         /* 4 per local contact element */
  PetscBool *released;       /* 4 per local contact element */
  PetscReal *anchor;         /* 12 per local contact element: where re-closed points stick */
  PetscReal  outer, inner;   /* iterations its solve took */
} BoltPreloadState;

PetscErrorCode BoltPreloadStateCreate(BoltOperator *, Vec, PetscReal, PetscReal, BoltPreloadState **);
PetscErrorCode BoltPreloadStateApply(const BoltPreloadState *, BoltOperator *, Vec);
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
/* contact_monitor.c: diagnostics of the loop (-contact_monitor) */
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

typedef struct {
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
  PetscBool       quasiStatic;    /* -ts_quasistatic: steps without inertia or damping */
  PetscBool       calibratePreload;
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
  PetscReal       tOnline;
  PetscReal       staticOuter, staticInner;
  PetscInt        staticFactorizations, staticSolves;
  /* checkpoints (checkpoint.c): <checkpointBase>-fom.ckpt.h5 / -rom.ckpt.h5 */
  PetscInt        checkpointEvery;  /* write one every this many steps (0: never) */
  char            checkpointBase[PETSC_MAX_PATH_LEN];
  PetscBool       restart;          /* continue from the checkpoint instead of step 0 */
  PetscReal       tOnlineBefore;    /* online time spent before the restart */
  PetscReal       tCheckpoint;      /* time spent writing checkpoints (not online work) */
} BoltNewmark;

PetscErrorCode BoltNewmarkCreate(BoltOperator *, BoltNewmark **);
PetscErrorCode BoltNewmarkSetFromOptions(BoltNewmark *);
PetscErrorCode BoltNewmarkSetUp(BoltNewmark *);
PetscErrorCode BoltNewmarkPreload(BoltNewmark *);
PetscErrorCode BoltNewmarkRun(BoltNewmark *);
PetscErrorCode BoltNewmarkView(BoltNewmark *, PetscViewer);
PetscErrorCode BoltNewmarkReleaseSolver(BoltNewmark *);
PetscErrorCode BoltNewmarkDestroy(BoltNewmark **);
PetscErrorCode BoltNewmarkKeepGivenPreload(BoltNewmark *);
PetscErrorCode BoltNewmarkCheckpointWrite(BoltNewmark *);
PetscErrorCode BoltNewmarkCheckpointRead(BoltNewmark *);

/* ------------------------------------------------------------------ exact_sum.c */
/* n sums over ranks that give the same bits on any partition (two fixed grids per term) */
typedef struct {
  PetscInt   n, nalloc;
  PetscReal  sigma[2];
  PetscReal *acc; /* 2 n: the exact partial sums of the two grids */
} BoltExactSum;
PetscErrorCode BoltExactSumBegin(BoltExactSum *, PetscInt, PetscReal, PetscInt);
void           BoltExactSumAdd(BoltExactSum *, const PetscReal[]);
void           BoltExactSumAddParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
void           BoltExactSumReplaceParts(BoltExactSum *, const PetscReal[], PetscReal[], PetscReal[]);
PetscErrorCode BoltExactSumEnd(BoltExactSum *, MPI_Comm, PetscReal[]);
PetscErrorCode BoltExactSumDestroy(BoltExactSum *);

/* ------------------------------------------------------------------ gather.c */
PetscErrorCode BoltGatherAll(MPI_Comm, MPI_Datatype, const void *, PetscInt, void *, PetscInt *, PetscInt *, PetscInt *);
PetscErrorCode BoltGrowReal(PetscReal **, PetscInt *, PetscInt);

/* ------------------------------------------------------------------ reduction.c, rom.c */
#include "boltrom_krylov.h" /* BoltKrylov: the basis's options */

/* The reduction's options as given (-rom_*, read by BoltROMSetFromOptions); 0 or -1 where the
   default is resolved by BoltROMSetUp */
typedef struct {
  MPI_Comm   comm;
  PetscInt   nCCM, nJIM;
  BoltKrylov *krylov;       /* the Krylov basis's options (-krylov_*), owned by the ROM */
  char       file[PETSC_MAX_PATH_LEN];
  PetscBool  rebuild;       /* rebuild a ROM file that does not match (else refuse) */
  PetscBool  extraInputs;   /* allow a load that is not an input of the ROM */
  PetscBool  checkOrthogonality;
  PetscBool  augment, augmentSet; /* -rom_contact_augment, if given (else the law follows the reduction) */
  PetscBool  preloadState, preloadStateSet; /* -rom_preload_state */
  PetscReal  penaltyScale;                  /* -rom_contact_penalty_scale, or 0 for the default */
  PetscReal  bandScale;                     /* -rom_contact_band_scale, or 0 for the default */
  PetscInt   nClosed;                       /* -rom_closed_krylov */
  PetscReal  staticPenaltyScale;            /* -rom_static_penalty_scale */
  PetscBool  closedKeepActive;              /* -rom_closed_keep_active */
  PetscBool  staticShapes;                  /* -rom_static_shapes */
  PetscReal  openingScale;                  /* -rom_opening_shapes: the load's scale whose changed pairs get shapes, 0 none */
  PetscBool  openingScaleSet;               /* given (else the law's default) */
  PetscReal  slipScale;                     /* -rom_slip_shapes: friction, the load's scale whose pairs beyond the cone get shapes */
  PetscReal  coneShapes;                    /* -rom_cone_shapes: friction, the pairs at this fraction of the cone in the preloaded state get shapes, 0 none */
  PetscBool  coneTraction;                  /* -rom_cone_traction */
  PetscInt   coneModes;                     /* -rom_cone_modes: the cone shapes compressed to this many per direction, 0 a shape per pair */
  PetscInt   updateRank;                    /* -rom_update_rank: largest low-rank update of the online factorisation, -1 default */
  PetscBool  holdUnmarked;                  /* -rom_hold_unmarked */
  PetscBool  holdUnmarkedSet;               /* given (else true, but false under friction) */
  PetscBool  gapsEverywhere;                /* -rom_gaps_everywhere */
  PetscInt   nOpenKrylov;                   /* -rom_opening_krylov */
  PetscInt   nSnapshotModes;                /* -rom_snapshot_modes: POD modes of the FOM's snapshots of this run, 0 none */
  PetscReal  snapshotTol;                   /* -rom_snapshot_tol: their smallest singular value, relative */
  const BoltPreloadState *fomPreload;       /* the FOM's preloaded state of this run, or NULL */
  PetscInt   nFomSnapshots;                 /* the FOM's displacement snapshots of this run (-snapshot_every) */
  Vec       *fomSnapshots;
} BoltReductionOptions;

/* The ROM file's fingerprint: typed fields, each a setting the basis depends on. */
#define BOLTROM_FINGERPRINT_FIELDS 256
typedef struct {
  char          key[BOLTROM_NAME_LEN + 32];
  PetscDataType type; /* PETSC_INT, PETSC_REAL or PETSC_STRING */
  PetscInt      i;
  PetscReal     r;
  char          s[BOLTROM_NAME_LEN];
} BoltROMFingerprintField;
typedef struct {
  PetscInt                n;
  BoltROMFingerprintField field[BOLTROM_FINGERPRINT_FIELDS];
} BoltROMFingerprint;

/* The reduced model: projected matrices (replicated on every rank, small and dense), the rows
   of the basis at this rank's contact DOFs and at the probe, and the reduced contact stiffness
   kept up to date element by element. */
typedef struct {
  MPI_Comm        comm;
  BoltReductionOptions opt;          /* the options as given (BoltROMSetFromOptions) */
  PetscBool       view;              /* -rom_view: print the settings used once set up */
  PetscBool       staticShapes;      /* resolved: static shapes in the basis */
  PetscReal       staticPenaltyScale; /* resolved: the offline static solves' penalty, x the FOM's */
  PetscInt        n;                 /* reduced dimension */
  Mat             Mr, Cr, Kr, Kcr;   /* MATSEQDENSE n x n on every rank */
  PetscReal       rayleigh[2];       /* C_r = rayleigh[0] M_r + rayleigh[1] K_r */
  Vec             loadr, preloadr;   /* MATSEQ n */
  Vec             loadUnitr;         /* V' (1 N load pattern), kept in the ROM file */
  PetscScalar    *Vc;                /* nlocal x n, column-major: rows of V at contact->localGlobal */
  PetscReal      *Vprobe;            /* n: the probe row of V */
  PetscReal      *Ke;                /* 144 per local contact element: M_e of K_e = [M_e -M_e; -M_e M_e] inside Kcr */
  PetscReal      *De;                /* 12 x n per local contact element: V_b - V_a at its node pairs (0 where clamped) */
  PetscReal      *DeMax;             /* per local contact element: max |De| */
  PetscReal      *felem;             /* 12 per local contact element: the side-b forces of the tractions */
  PetscScalar    *work, *work2, *dK, *packed; /* scratch (packed: an upper triangle) */
  PetscReal      *dMe;               /* 144 per local contact element: scratch of the K_cr update */
  PetscInt       *dirtyElems;        /* per local contact element: scratch of the K_cr update */
  PetscReal      *kcrSend, *kcrRecv, *kcrDT; /* scratch of the node-pair K_cr update, kept between updates */
  PetscInt        kcrSendAlloc, kcrRecvAlloc, kcrDTAlloc; /* (a fresh megabyte-sized buffer per update spent its time in page faults) */
  BoltExactSum    sum;               /* the reductions over ranks, partition-independent */
  /* what the online phase keeps while the contact state's version holds (BoltContactState) */
  PetscScalar    *Fr;                /* n: the reduced forces of the state's multipliers */
  PetscObjectState FrVersion, KcrVersion, tnVersion;
  PetscBool       FrValid, KcrValid, tnValid;
  /* the gaps from node-pair differences D = V_b - V_a: on flat surfaces the normal gaps n' D q
     (a sixth of the rows of V_c), all that the penalty law's decisions need (the tangential gaps
     act only through the penalty, which is inside K_cr); under friction the whole gaps, three
     rows per node pair (half the rows of V_c, and no cancellation in u_b - u_a) */
  PetscBool       flat;              /* the normals of all points at each node agree (global) */
  PetscBool       wholeRows;         /* three rows of D per node pair (curved surfaces, or friction), else one normal row */
  PetscInt        nGapRows, nLiveRows; /* all rows; the first nLiveRows are those of points that may change */
  PetscBool       heldRowsDone;      /* the held points' rows were taken once */
  PetscScalar    *Rn;                /* nGapRows x n, column-major */
  PetscInt       *gpRows;            /* 4 per local point: the row of each node it interpolates (-1: none) */
  PetscScalar    *gnRow;             /* nGapRows: scratch */
  PetscReal      *tnC, *tnK;         /* per local point: the opening test's traction is tnC + tnK g.n */
  /* the whole gap of an open point is needed only where it closes (it sticks there): it is taken
     from the point's rows of D_e when its normal gap is within wholeGapBound x |q|_max of closing,
     a bound on the rounding between the normal row and the whole gap's normal part */
  PetscReal      *wholeGapBound;     /* per local point */
  BoltContactSet *contact;
  /* offline figures */
  PetscInt        order, ninputs, nCCM, nJIM, rankPerOrder[8];
  PetscReal       s0, tOffline, tInputs, tBasis, tProject, tFactor, tSolve, tOrth, tInterface;
  PetscBool       fromFile;
  PetscBool       augment;       /* contact law of the reduced dual loop */
  PetscReal       orthogonality; /* max |V'V - I|, or -1 if not measured */
  BoltROMFingerprint fingerprint; /* what the basis depends on (src/rom/fingerprint.c) */
  /* the FOM's preloaded state (offline): multipliers per newton of preload and the active set,
     per local contact element; the reduced dual loop starts from them and keeps them frozen */
  PetscBool       preloadState;
  PetscReal      *lambda0;       /* 12 per local contact element, per N of preload */
  PetscReal      *gap0;          /* the gaps of that state, likewise */
  PetscBool      *active0;       /* 4 per local contact element */
  PetscBool      *released0;     /* 4 per local contact element: closed but sliding (strict law) */
  PetscReal       penaltyScale;  /* the ROM's penalties: this times the FOM's */
  PetscReal       bandScale;     /* the ROM's activation band (traction): this times the FOM's */
  PetscInt        nClosed;       /* closed-contact Krylov vectors in the basis */
  PetscReal       openingScale;  /* opening shapes of the pairs this multiple of the load changes (0: none) */
  PetscReal       slipScale;     /* friction: also of the pairs beyond the cone, sticking, under this multiple */
  PetscReal       coneShapes;    /* friction: also of the pairs whose preloaded traction is this fraction of the cone or more (0: none) */
  PetscBool       coneTraction;  /* with them: a shape along the pair's tangential traction too (else along its normal only) */
  PetscInt        coneModes;     /* with them and training snapshots: this many shapes per direction, of the snapshots' patterns at the pairs (0: one per pair) */
  PetscInt        nOpenKrylov;   /* opened-joint Krylov vectors with them */
  PetscInt        nOpeningPairs; /* node pairs with opening shapes in the basis */
  PetscInt        nSnapshotModes; /* POD modes of the FOM's snapshots in the basis */
  PetscInt        nConePairs;    /* friction: node pairs with cone shapes in the basis */
  PetscInt        nConeModes;    /* friction: the cone shapes in the basis when compressed (-rom_cone_modes), else 0 */
  PetscBool      *marked;        /* 4 per local contact element: the point's state changed in those static solves (NULL: not made) */
  PetscBool       holdUnmarked;  /* -rom_hold_unmarked: online, the other points keep their preloaded state */
  PetscBool       gapsEverywhere; /* -rom_gaps_everywhere: every point's gaps at every solve (a check) */
  PetscReal       epsSaved[3 * BOLTROM_MAX_PAIRS]; /* the FOM's penalties (N, T) and bands per pair, while the ROM's are set */
  PetscInt        updateRank;    /* -rom_update_rank as given (-1: the default) */
  PetscInt        updateRankUsed; /* as resolved when the operator was made (0: refactorise) */
  struct BoltROMUpdate_s *update; /* low-rank updates of the online factorisation (rom_update.c), or NULL */
  /* F_r = sum_p D_p' F_p over node pairs p (D_p: the pair's three rows of D = V_b - V_a, F_p the
     side-b force of its points). Each node pair has one owner rank, in turn over the pairs in the
     order of their first point's name; its points' nodal forces reach the owner, which sums them
     in the order of their names: a node pair's term has the same bits on any partition, costs a
     quarter of the four element terms it replaces, and the ranks share the pairs evenly. */
  PetscInt        npOwned, npGlobal; /* node pairs this rank owns, and all of them */
  PetscInt       *npSlotStart;   /* npOwned + 1: the owned pairs' points in npSlotF */
  PetscInt       *npGlobalOf;    /* per owned pair: its index among all pairs (its rows in npRowsAll) */
  PetscReal      *npDMax;        /* per owned pair: max |D_p| */
  PetscReal      *npSlotF;       /* 3 per point of an owned pair: its nodal force, from its element's rank */
  PetscReal      *npF, *npFSum;  /* 3 per owned pair: F_p, and the F_p whose term fAcc holds */
  PetscSF         npSF;          /* leaves: felem of the local elements (and, alike, their points' gaps); roots: npSlotF */
  /* every node pair's rows of D on every rank: the owners' force terms read their pairs' rows
     there, and the online K_cr and low-rank updates gather a changed point's 3 x 3 block and its
     pair's index, not its 3n values of D */
  PetscReal      *npRowsAll;     /* 3n per node pair (all ranks'), n x 3 column-major, in the pairs' order */
  PetscInt       *npOfPoint;     /* 4 per local contact element: its node pair's index (-1: both nodes clamped) */
  /* under friction with the nodal quadrature (pairGaps) the owners make the gaps too, D_p q, and
     send them to the pairs' points: the rows of pairs with a point that may change first */
  PetscBool       pairGaps;
  PetscInt        npLive;        /* owned pairs with a point that may change */
  PetscInt       *npRowOf;       /* per owned pair: its first row in npRows */
  PetscScalar    *npRows;        /* 3 npOwned x n, column-major: the owned pairs' rows of npRowsAll again, as one block for the gaps' product (npRowsAll keeps a pair's rows together for its force term) */
  PetscScalar    *npGap;         /* 3 npOwned: scratch */
  /* with low-rank updates, F_r of the state's multipliers is updated for the pairs whose forces changed */
  PetscReal      *fAcc;          /* 2n: this rank's exact partial sums */
  PetscReal      *fParts;        /* 2n per owned pair: its term's parts in fAcc */
  PetscReal       fGridBound;    /* the bound the sums' grid was set for (kept by checkpoints) */
  PetscBool       fGridValid, fPartsValid;
} BoltROM;

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
typedef struct {
  MPI_Comm comm;
  char     dir[PETSC_MAX_PATH_LEN];
  char     name[BOLTROM_NAME_LEN];
  char     h5tmp[PETSC_MAX_PATH_LEN], h5final[PETSC_MAX_PATH_LEN];
  PetscViewer viewer;
  PetscInt nfields;
  char     field[16][BOLTROM_NAME_LEN];
  PetscInt fieldComponents[16];
  PetscBool fieldOnCells[16];
  PetscInt  nseries;            /* temporal XDMF series of displacement snapshots: the FOM's, the ROM's */
  struct {
    char       prefix[8];       /* of the series' fields: <prefix>snapshot_<i>, <prefix>contact_state_<i> */
    PetscInt   n;
    PetscReal *time;
    PetscBool  states;          /* with the contact state at each snapshot */
  } series[2];
} BoltOutput;

PetscErrorCode BoltOutputOpen(BoltMesh *, const char[], const char[], BoltOutput *);
PetscErrorCode BoltOutputVertexField(BoltOutput *, BoltMesh *, Vec, const char[]);
PetscErrorCode BoltOutputClose(BoltOutput *, BoltMesh *);
PetscErrorCode BoltOutputSeries(BoltOutput *, const char[], const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputPairForces(BoltOutput *, const char[], BoltContactSet *, PetscInt, const PetscReal[]);
PetscErrorCode BoltOutputSnapshot(BoltOutput *, BoltMesh *, const char[], PetscInt, Vec);
PetscErrorCode BoltOutputSnapshotSeries(BoltOutput *, const char[], PetscInt, const PetscReal[], PetscBool);
PetscErrorCode BoltOutputContactState(BoltOutput *, BoltMesh *, BoltContactSet *, const unsigned char[], const char[]);
PetscErrorCode BoltOutputSnapshotStates(BoltOutput *, BoltMesh *, const char[], BoltContactSet *, PetscInt, const unsigned char[]);

/* JSON summary: a flat writer for the keys the README documents. */
typedef struct {
  FILE     *fp;
  char      tmp[PETSC_MAX_PATH_LEN], final[PETSC_MAX_PATH_LEN];
  PetscInt  depth;
  PetscBool first[16];
} BoltJSON;
PetscErrorCode BoltJSONOpen(MPI_Comm, const char[], BoltJSON *);
PetscErrorCode BoltJSONBeginObject(BoltJSON *, const char[]);
PetscErrorCode BoltJSONEndObject(BoltJSON *);
PetscErrorCode BoltJSONInt(BoltJSON *, const char[], PetscInt);
PetscErrorCode BoltJSONReal(BoltJSON *, const char[], PetscReal);
PetscErrorCode BoltJSONString(BoltJSON *, const char[], const char[]);
PetscErrorCode BoltJSONRealArray(BoltJSON *, const char[], PetscInt, const PetscReal[]);
PetscErrorCode BoltJSONClose(BoltJSON *);

/* ------------------------------------------------------------------ sys/hdf5.c: folders, datasets */
PetscErrorCode BoltMakeDir(MPI_Comm, const char[]);
PetscErrorCode BoltMakeParentDir(MPI_Comm, const char[]);
/* sys/option_vector.c: a vector option of exactly n finite reals, inside PetscOptionsBegin/End */
PetscErrorCode BoltOptionsRealVector(PetscOptionItems *, const char[], const char[], PetscInt, PetscReal[], PetscBool *);
PetscErrorCode BoltHDF5WriteValues(PetscViewer, MPI_Comm, const char[], PetscInt, PetscInt, const PetscScalar[], PetscBool);
PetscErrorCode BoltHDF5WriteVecs(PetscViewer, MPI_Comm, PetscInt, const char *const[], Vec[], PetscBool);
PetscErrorCode BoltReadAll(PetscViewer, MPI_Comm, const char[], PetscInt *, PetscReal **);
/* Sorted keys of a keyed dataset and the permutation to their rows. */
typedef struct {
  PetscInt  n, *key, *row;
} BoltKeyIndex;
PetscErrorCode BoltKeyIndexCreate(PetscInt, const PetscReal[], BoltKeyIndex *);
PetscErrorCode BoltKeyIndexFind(BoltKeyIndex *, PetscInt, PetscInt *);
PetscErrorCode BoltKeyIndexDestroy(BoltKeyIndex *);
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
typedef struct {
  char      outputDir[PETSC_MAX_PATH_LEN];
  char      outputName[BOLTROM_NAME_LEN];
  char      summary[PETSC_MAX_PATH_LEN];
  PetscBool staticSolve, verifyFields, checkRigid, writeOutput, fom, rom, romCheckS0;
  char      exportDir[PETSC_MAX_PATH_LEN]; /* tied K and M, full and reduced, for petsc4py */
  PetscInt  verifyField;                   /* 0 smooth, 1 linear */
  PetscInt  nev;
} BoltRunOptions;

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
typedef struct {
  BoltMesh       *mesh;
  BoltAssembler  *asmb;
  BoltContactSet *contact;
  BoltLoadSet    *loads;
  PetscReal       tSetUp;
  PetscBool       staticSolve;                   /* "static": the tied joint under the load */
  Vec             u;                             /* its displacement */
  PetscReal       probe, tStatic;
  Vec             x, Kx, Mx;                     /* -verify_fields, or NULL */
  PetscInt        nev, nconv;                    /* "modal" if nev > 0 */
  PetscReal       freq[100], tModal;
  PetscBool       checkRigid;                    /* "rigid_residual_per_part" */
  PetscReal       rigid[BOLTROM_MAX_PARTS];
  BoltNewmark    *fomRun;                        /* "preload" and "fom": the FOM's run */
  PetscReal       preloadForce[BOLTROM_MAX_PAIRS]; /* the FOM's preloaded state, before its transient */
  PetscReal       tractionStats[3], preloadPenetration, preloadChange;
  PetscInt        preloadActive, preloadSliding;
  BoltROM        *rom;                           /* "rom": the reduced model and its run */
  BoltNewmark    *romRun;
  PetscBool       romCheckS0;
  PetscReal       romCheckError;
  PetscReal       errL2, errMean;                /* "speedup" and "errors": with both runs */
} BoltSummary;

PetscErrorCode BoltSummaryWrite(MPI_Comm, const char[], const BoltSummary *);
PetscErrorCode BoltSummaryWriteFields(const BoltSummary *, const char[], const char[]);
/* metadata.c: the result file's root attributes and the summary's load and friction fields */
PetscErrorCode BoltSummaryWriteAttributes(const BoltSummary *, PetscViewer);
PetscErrorCode BoltSummaryWriteLoad(BoltJSON *, const BoltSummary *);

/* ------------------------------------------------------------------ run.c (stages) */
/* A run's objects, made and configured by main; sum collects what the stages report. */
typedef struct {
  MPI_Comm          comm;
  BoltRunOptions    opt;
  BoltMesh         *mesh;
  BoltAssembler    *asmb;
  BoltContactSet   *contact;
  BoltLoadSet      *loads;
  Vec               u;
  Mat               Ktied;
  BoltOperator     *fomOp, *romOp;
  BoltNewmark      *fomNm, *romNm;
  BoltPreloadState *fomPreload;
  BoltROM          *rom;
  BoltSummary       sum;
} BoltRun;

PetscErrorCode BoltRunTied(BoltRun *);
PetscErrorCode BoltRunFOM(BoltRun *);
PetscErrorCode BoltRunROM(BoltRun *);

#endif
