#ifndef BOLTROM_PRIVATE_CONTACT_H
#define BOLTROM_PRIVATE_CONTACT_H
/* Inside the contact module (src/contact/): a contact law's body, the operations its state's
   loops call at one contact point, and what the laws share. A law registered from elsewhere
   (BoltContactLawRegister) fills the same table. */
#include "boltrom.h"

struct _n_BoltContactSet {
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
};

struct _n_BoltContactState {
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
  PetscInt         unchangedUpdates; /* set updates in a row that changed nothing, none of the state changed since */
};

/* A law's operations at point gp of state s (pair: the point's pair). NULL where the law has
   none; the comment of each says what the state does then. */
typedef struct {
  /* trial traction of a multiplier lambda and a gap g (u_b - u_a) under the normal penalty epsN
     and the tangential epsT, n the outward normal of side a */
  void (*traction)(const PetscReal lambda[3], const PetscReal g[3], const PetscReal n[3], PetscReal epsN, PetscReal epsT, PetscReal t[3]);
  /* the trial traction of an active point: what an augmentation gives its multipliers */
  void (*trial)(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal t[3]);
  /* convergence measure: the violation of an active point's constraint that the loop tests
     against its tolerance (a length [m]; a squared length where *squared is set) */
  PetscReal (*violation)(const BoltContactState *s, PetscInt gp, PetscBool *squared);
  /* return map of an active point that stays closed, after an augmentation: stick or slip.
     Returns whether K_c changed; *moved is how far its traction is from the one the solve
     linearised [Pa], *pressure its pressure after the map [Pa]. NULL: no return map */
  PetscBool (*returnMap)(BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal *moved, PetscReal *pressure);
  /* convergence measure of the return maps, from this rank's largest move and pressure
     (collective); NULL: none */
  PetscErrorCode (*returnChange)(BoltContactState *s, PetscReal moved, PetscReal pressure);
  /* a closed point opens (its multipliers are zeroed by the state); NULL: nothing more */
  void (*open)(BoltContactState *s, PetscInt gp);
  /* an open point closes again; NULL: it closes as it was */
  void (*reclose)(BoltContactState *s, PetscInt gp);
  /* whether a point given closed or open from outside (a stored state) slides: from its given
     flags (released NULL: none given); NULL: none slides */
  PetscBool (*presetReleased)(const BoltContactState *s, PetscInt gp, const PetscBool active[], const PetscBool released[]);
  /* stiffness block: the tangential penalty of a closed, sticking point of pair; and element e's
     24x24 stiffness of its active points */
  PetscReal (*stickStiffness)(const BoltContactState *s, PetscInt pair);
  PetscErrorCode (*elementStiffness)(BoltContactState *s, PetscInt e, PetscReal Ke[576]);
  /* the multipliers whose forces the solve takes; NULL: lambda less epsT times the anchors */
  const PetscReal *(*forceMultipliers)(BoltContactState *s);
  /* the point's state in the output: BOLT_POINT_OPEN, _STICK or _SLIP */
  unsigned char (*pointCode)(const BoltContactState *s, PetscInt gp);
  /* energy terms: the energy an active point dissipated over the step, per area [J/m^2], from
     its raw gap and its traction at the step's end (NULL: none); the elastic energy of an
     active point's stick [J] (NULL: none) */
  PetscReal (*dissipation)(const BoltContactState *s, PetscInt gp, const PetscReal raw[3], const PetscReal t[3]);
  PetscReal (*stickEnergy)(const BoltContactState *s, PetscInt gp);
  /* after a converged solve, the point's raw gap at the step's end; NULL: nothing to keep */
  void (*endSolve)(BoltContactState *s, PetscInt gp, const PetscReal raw[3]);
  /* before a static solve from the unloaded state; NULL: nothing to reset */
  void (*staticStart)(BoltContactState *s);
} BoltContactLawOps;

/* A contact law: its operations, and the properties the geometry, the loop and the models ask
   of it (through BoltContactSetHasFriction and its kind). */
struct _p_BoltContactLaw {
  BoltContactLawOps ops;
  PetscReal         penaltyFactor;   /* default -contact_penalty_factor: a physical penalty (banded
                                        law) or the augmentation parameter of the active-set loop */
  PetscBool         complementarity; /* one-sided contact at every node pair (nodal quadrature, no
                                        band), solved by the active-set loop; else the banded
                                        Gauss-point law of the paper */
  PetscBool         friction;        /* Coulomb friction at closed pairs (-contact_friction) */
  PetscBool         rawGaps;         /* the state's gaps are raw (u_b - u_a) and its anchors the
                                        sticks' rest positions, not offsets taken off the gaps */
};

/* The laws of boltrom, for the registry (contact_law.c) */
PetscErrorCode BoltContactLawCreate_Stick(BoltContactLaw *);
PetscErrorCode BoltContactLawCreate_Strict(BoltContactLaw *);
PetscErrorCode BoltContactLawCreate_Coulomb(BoltContactLaw *);
/* what the laws share (stick.c) */
void           BoltContactLawPenaltyTraction(const PetscReal[3], const PetscReal[3], const PetscReal[3], PetscReal, PetscReal, PetscReal[3]);
void           BoltContactLawPenaltyTrial(const BoltContactState *, PetscInt, PetscInt, PetscReal[3]);
PetscReal      BoltContactLawPenaltyStickStiffness(const BoltContactState *, PetscInt);
PetscErrorCode BoltContactLawPenaltyElementStiffness(BoltContactState *, PetscInt, PetscReal[576]);
unsigned char  BoltContactLawPointCode(const BoltContactState *, PetscInt);

/* The tangential penalty at point gp of a pair: none where the point slides (released). */
static inline PetscReal BoltContactStateEpsT(const BoltContactState *s, PetscInt gp, PetscInt pair)
{
  return s->released[gp] ? 0 : s->law->ops.stickStiffness(s, pair);
}
/* One model's work space over the contact set (fields.c). */
struct _n_BoltContactWork {
  Vec        uc, fc;          /* local contact displacements and forces (sequential) */
  Vec        fcWork, fGlobal; /* nodal sums across ranks: local and global layout */
  PetscReal *nodalForce;      /* nlocal: nodal sums */
  PetscReal *tau;             /* 3 per point: tractions being turned into forces or smoothed */
};

struct _n_BoltContactElement {
  PetscInt  pair;
  PetscInt  key;      /* face a's number in the mesh as read: names the element on any ranks */
  PetscReal Xa[12];
  PetscInt  dofs[24]; /* global DOFs of [a nodes, b nodes], -1 where clamped */
};

#endif
