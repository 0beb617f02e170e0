/* Contact laws, registered by name (-contact_law) so that other laws plug in beside boltrom's:
   each fills an ops table (include/private/contact.h) with what it does at one contact point,
   one file per law (stick.c, strict.c, coulomb.c). Here the registry, and the answers to what
   the other modules ask of a law. */
#include "private/contact.h"

PetscFunctionList BoltContactLawList = NULL;
static PetscBool  BoltContactLawRegistered = PETSC_FALSE;

/* Registers a law: create fills a zeroed law (its ops table and properties). */
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

/* A new law of the registered type (*law: replaced, the old one freed). */
PetscErrorCode BoltContactLawCreate(MPI_Comm comm, const char type[], BoltContactLaw **law)
{
  PetscErrorCode (*create)(BoltContactLaw *) = NULL;

  PetscFunctionBeginUser;
  PetscCall(BoltContactLawRegisterAll());
  PetscCall(PetscFunctionListFind(BoltContactLawList, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "Unknown contact law '%s': -contact_law must be one of those bin/boltrom -help lists", type);
  PetscCall(PetscFree(*law));
  PetscCall(PetscNew(law));
  PetscCall((*create)(*law));
  PetscCheck((*law)->ops.traction && (*law)->ops.trial && (*law)->ops.violation && (*law)->ops.stickStiffness && (*law)->ops.elementStiffness && (*law)->ops.pointCode, comm, PETSC_ERR_PLIB, "Contact law '%s' leaves a required operation empty (traction, trial, violation, stick stiffness, element stiffness, point code)", type);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactLawDestroy(BoltContactLaw **law)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*law));
  PetscFunctionReturn(0);
}


PetscBool BoltContactSetHasFriction(const BoltContactSet *c)
{
  return c->law->friction;
}

PetscBool BoltContactSetIsComplementarity(const BoltContactSet *c)
{
  return c->law->complementarity;
}

PetscBool BoltContactStateHasFriction(const BoltContactState *s)
{
  return s->law->friction;
}

PetscBool BoltContactStateIsComplementarity(const BoltContactState *s)
{
  return s->law->complementarity;
}

/* A penalty law's contact stores 1/2 q' K_c q; a complementarity law's closed gaps store none. */
PetscBool BoltContactStateHasPenaltyEnergy(const BoltContactState *s)
{
  return (PetscBool)!s->law->complementarity;
}

PetscBool BoltContactStateLambdaIsTraction(const BoltContactState *s)
{
  return (PetscBool)(s->law->complementarity && (s->augment || s->law->friction));
}
