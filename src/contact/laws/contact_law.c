/* Contact laws at a contact point, registered by name (-contact_law) so that other laws plug in
   beside the first. Physics only: no loops, no solvers. */
#include "boltrom.h"

PetscFunctionList BoltContactLawList = NULL;
static PetscBool  BoltContactLawRegistered = PETSC_FALSE;

/* stick: augmented Lagrangian with normal and tangential penalties, stick with elastic slip only
   (no Coulomb limit). Trial traction t = lambda + epsN (g.n) n + epsT (g - (g.n) n), with the
   gap g = u_b - u_a and n the outward normal of side a. */
static void StickTraction(const PetscReal lambda[3], const PetscReal g[3], const PetscReal n[3], PetscReal epsN, PetscReal epsT, PetscReal t[3])
{
  const PetscReal gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  for (PetscInt k = 0; k < 3; k++) t[k] = lambda[k] + epsT * g[k] + (epsN - epsT) * gn * n[k];
}

/* stick (the paper's law): points are the 2x2 Gauss points of each face pair; a closed point
   opens only when its traction is tensile beyond a band, an open one closes when it penetrates
   beyond the activation gap; the penalty (200 E/m) is part of the model. */
static PetscErrorCode BoltContactLawCreate_Stick(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  law->traction      = StickTraction;
  law->strict        = PETSC_FALSE;
  law->penaltyFactor = 200.0;
  PetscFunctionReturn(0);
}

/* strict: one-sided contact at every matched node pair (nodal quadrature): gap.n >= 0, normal
   traction <= 0 and their product zero, with no band; a closed pair sticks (its whole gap
   vector is closed). The penalty is only the augmentation parameter of the active-set loop:
   stiff (3e7 E/m), so that one solve closes a step's gaps to the tolerance once the set is
   right, and far enough from round-off (1e9 E/m moves the results by 2e-4). */
static PetscErrorCode BoltContactLawCreate_Strict(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  law->traction      = StickTraction;
  law->strict        = PETSC_TRUE;
  law->penaltyFactor = 3e7;
  PetscFunctionReturn(0);
}

/* coulomb: the strict law's normal contact with Coulomb friction at every closed node pair. A
   closed pair sticks (its tangential gap held by the penalty and its multiplier) while its
   tangential traction is inside the cone mu |t_N|, and slips on the cone otherwise: a slipping
   pair has no tangential penalty, and its tangential traction mu |t_N| along its slip over the
   step is a force the loop updates after every solve (docs/model.md, friction). */
static PetscErrorCode BoltContactLawCreate_Coulomb(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactLawCreate_Strict(law));
  law->friction = PETSC_TRUE;
  /* a softer augmentation than the strict law's: the same solves and results on the joint, and
     the energy accounting balances to 1e-8 instead of 5e-7 (the stiff penalty's rounding in the
     equilibrium of the tractions the ledger takes) */
  law->penaltyFactor = 1e6;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactLawRegister(const char name[], PetscErrorCode (*create)(BoltContactLaw *))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&BoltContactLawList, name, create));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltContactLawFinalize(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&BoltContactLawList));
  BoltContactLawRegistered = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactLawRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (BoltContactLawRegistered) PetscFunctionReturn(0);
  BoltContactLawRegistered = PETSC_TRUE;
  PetscCall(BoltContactLawRegister("strict", BoltContactLawCreate_Strict));
  PetscCall(BoltContactLawRegister("stick", BoltContactLawCreate_Stick));
  PetscCall(BoltContactLawRegister("coulomb", BoltContactLawCreate_Coulomb));
  PetscCall(PetscRegisterFinalize(BoltContactLawFinalize));
  PetscFunctionReturn(0);
}

/* Fills law with the registered type's functions. */
PetscErrorCode BoltContactLawSetType(MPI_Comm comm, const char type[], BoltContactLaw *law)
{
  PetscErrorCode (*create)(BoltContactLaw *) = NULL;

  PetscFunctionBeginUser;
  PetscCall(BoltContactLawRegisterAll());
  PetscCall(PetscFunctionListFind(BoltContactLawList, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "Unknown contact law '%s': -contact_law must be one of those bin/boltrom -help lists", type);
  PetscCall((*create)(law));
  PetscFunctionReturn(0);
}

PetscBool BoltContactSetHasFriction(const BoltContactSet *c)
{
  return c->law.friction;
}

PetscBool BoltContactSetIsComplementarity(const BoltContactSet *c)
{
  return c->law.strict;
}

PetscBool BoltContactStateHasFriction(const BoltContactState *s)
{
  return s->law.friction;
}

PetscBool BoltContactStateIsComplementarity(const BoltContactState *s)
{
  return s->law.strict;
}

PetscBool BoltContactStateHasPenaltyEnergy(const BoltContactState *s)
{
  return (PetscBool)!s->law.strict;
}

PetscBool BoltContactStateLambdaIsTraction(const BoltContactState *s)
{
  return (PetscBool)(s->law.strict && (s->augment || s->law.friction));
}
