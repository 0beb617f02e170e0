/* What a contact state tells the other modules, and the switches the dual loop and the ROM set
   on it. The arrays are the state's own, written in place (see access.c). */
#include "private/contact.h"

BoltContactSet *BoltContactStateSet(const BoltContactState *s)
{
  return s->set;
}

BoltContactWork *BoltContactStateWork(const BoltContactState *s)
{
  return s->work;
}

const char *BoltContactStateLawType(const BoltContactState *s)
{
  return s->lawType;
}

/* 3 per point: multipliers (tractions), gaps u_b - u_a, anchors, and the multipliers the solve's
   forces take (lambda - epsT anchor). */
PetscReal *BoltContactStateLambda(BoltContactState *s)
{
  return s->lambda;
}

PetscReal *BoltContactStateGap(BoltContactState *s)
{
  return s->gap;
}

PetscReal *BoltContactStateAnchor(BoltContactState *s)
{
  return s->anchor;
}

const PetscReal *BoltContactStateLambdaForce(const BoltContactState *s)
{
  return s->lambdaForce;
}

/* One flag per point: closed, closed at the iteration before, released (strict law, slide). */
PetscBool *BoltContactStateActive(BoltContactState *s)
{
  return s->active;
}

const PetscBool *BoltContactStateActiveOld(const BoltContactState *s)
{
  return s->activeOld;
}

PetscBool *BoltContactStateReleased(BoltContactState *s)
{
  return s->released;
}

/* One flag per element: its stiffness block is out of date (cleared by who rebuilds it). */
PetscBool *BoltContactStateDirty(BoltContactState *s)
{
  return s->dirty;
}

/* 576 per element: the stiffness blocks BoltContactStateStiffness last brought up to date (NULL
   before its first call). */
const PetscReal *BoltContactStateElementBlocks(const BoltContactState *s)
{
  return s->Ke;
}

PetscInt BoltContactStateActiveCount(const BoltContactState *s)
{
  return s->nactive;
}

PetscBool BoltContactStateAugmented(const BoltContactState *s)
{
  return s->augment;
}

PetscObjectState BoltContactStateVersion(const BoltContactState *s)
{
  return s->version;
}

const PetscBool *BoltContactStateMayChange(const BoltContactState *s)
{
  return s->mayChange;
}

PetscReal BoltContactStateFrictionChange(const BoltContactState *s)
{
  return s->frictionChange;
}

PetscBool BoltContactStateCloseOnly(const BoltContactState *s)
{
  return s->closeOnly;
}

PetscInt BoltContactStateOpenTest(const BoltContactState *s)
{
  return s->openTest;
}

PetscBool BoltContactStateStickOnly(const BoltContactState *s)
{
  return s->stickOnly;
}

PetscBool BoltContactStateHoldContact(const BoltContactState *s)
{
  return s->holdContact;
}

PetscReal BoltContactStateBandTraction(const BoltContactState *s, PetscInt p)
{
  return s->bandTraction[p];
}

PetscReal BoltContactStateActivationGap(const BoltContactState *s)
{
  return s->activationGap;
}

/* Anti-cycling (the dual loop): points may close but not open. */
PetscErrorCode BoltContactStateSetCloseOnly(BoltContactState *s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->closeOnly = flg;
  PetscFunctionReturn(0);
}

/* A kept active set: closed and open points stay so, but under friction still stick or slip. */
PetscErrorCode BoltContactStateSetHoldContact(BoltContactState *s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->holdContact = flg;
  PetscFunctionReturn(0);
}

/* Frictional law: closed pairs never slip (the ROM's static shapes). */
PetscErrorCode BoltContactStateSetStickOnly(BoltContactState *s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->stickOnly = flg;
  PetscFunctionReturn(0);
}

/* Augmented Lagrangian (true) or pure penalty with the multipliers fixed. */
PetscErrorCode BoltContactStateSetAugment(BoltContactState *s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->augment = flg;
  PetscFunctionReturn(0);
}

/* The points whose state may change (NULL: all); the array stays the caller's. */
PetscErrorCode BoltContactStateSetMayChange(BoltContactState *s, const PetscBool mayChange[])
{
  PetscFunctionBeginUser;
  s->mayChange = mayChange;
  PetscFunctionReturn(0);
}
