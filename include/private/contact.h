#ifndef BOLTROM_PRIVATE_CONTACT_H
#define BOLTROM_PRIVATE_CONTACT_H
/* Inside the contact module (src/contact/): a contact law's body, the operations its state's
   loops call at one contact point, and what the laws share. A law registered from elsewhere
   (BoltContactLawRegister) fills the same table. */
#include "boltrom.h"

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
