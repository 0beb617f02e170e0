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
