/* The load set as the other modules see it: read-only accessors (the set is loads.c's). */
#include "private/model.h"

/* What the other modules read of the load set (the set owns it all; vectors referenced). */
Vec BoltLoadSetLoad(const BoltLoadSet *l)
{
  return l->load;
}
Vec BoltLoadSetLoadUnit(const BoltLoadSet *l)
{
  return l->loadUnit;
}
Vec BoltLoadSetPreload(const BoltLoadSet *l)
{
  return l->preload;
}
PetscBool BoltLoadSetHasPreload(const BoltLoadSet *l)
{
  return l->hasPreload;
}
PetscReal BoltLoadSetPreloadForce(const BoltLoadSet *l)
{
  return l->preloadForce;
}
const char *BoltLoadSetPreloadGroup(const BoltLoadSet *l, PetscInt side)
{
  return l->preloadGroup[side];
}
const PetscReal *BoltLoadSetPreloadAxis(const BoltLoadSet *l)
{
  return l->preloadAxis;
}
const char *BoltLoadSetLoadGroup(const BoltLoadSet *l)
{
  return l->loadGroup;
}
PetscReal BoltLoadSetLoadForce(const BoltLoadSet *l)
{
  return l->loadForce;
}
const PetscReal *BoltLoadSetLoadDirection(const BoltLoadSet *l)
{
  return l->loadDirection;
}
const char *BoltLoadSetProbeGroup(const BoltLoadSet *l)
{
  return l->probeGroup;
}
PetscInt BoltLoadSetProbeComponent(const BoltLoadSet *l)
{
  return l->probeComponent;
}
PetscInt BoltLoadSetProbeDof(const BoltLoadSet *l)
{
  return l->probeDof;
}
const PetscReal *BoltLoadSetProbeCoordinates(const BoltLoadSet *l)
{
  return l->probeCoord;
}

/* The bolts of -preload_bolts (0 for the one bolt of -preload_lower_group/_upper_group): their
   names, clamp forces [N] and 1 N layer patterns (the preload is the sum of force x pattern). */
PetscInt BoltLoadSetBoltCount(const BoltLoadSet *l)
{
  return l->nbolts;
}
const char *BoltLoadSetBoltName(const BoltLoadSet *l, PetscInt b)
{
  return l->boltName[b];
}
PetscReal BoltLoadSetBoltForce(const BoltLoadSet *l, PetscInt b)
{
  return l->boltForce[b];
}
Vec BoltLoadSetBoltUnit(const BoltLoadSet *l, PetscInt b)
{
  return l->boltUnit[b];
}
