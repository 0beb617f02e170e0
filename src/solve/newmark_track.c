/* Which contact points a Newmark run changed: the training of a trained ROM (-rom_train), off
   unless asked for (BoltNewmarkTrackChanges), since it reads every point's state at every step. */
#include "private/solve.h"

/* The points whose state (open, sticking, slipping: BoltContactStatePointCodes) differs from the
   preloaded one after some converged step of the transient, and those that slip there (a slip
   moves even where it does not change): what a trained ROM must let change. A restarted run
   knows only the steps it ran itself. */
void BoltNewmarkTrackChanges(BoltNewmark *nm)
{
  nm->trackChanges = PETSC_TRUE;
}

PetscErrorCode BoltNewmarkTrackStart(BoltNewmark *nm)
{
  const PetscInt np = 4 * BoltContactSetElementCount(nm->op->contact);

  PetscFunctionBeginUser;
  if (!nm->trackChanges) PetscFunctionReturn(0);
  if (!nm->codes0) PetscCall(PetscMalloc3(np + 1, &nm->codes0, np + 1, &nm->codesNow, np + 1, &nm->changed));
  BoltContactStatePointCodes(nm->op->state, nm->codes0);
  for (PetscInt k = 0; k < np; k++) nm->changed[k] = PETSC_FALSE;
  PetscFunctionReturn(0);
}

void BoltNewmarkTrackStep(BoltNewmark *nm)
{
  const PetscInt np = 4 * BoltContactSetElementCount(nm->op->contact);

  if (!nm->trackChanges) return;
  BoltContactStatePointCodes(nm->op->state, nm->codesNow);
  for (PetscInt k = 0; k < np; k++)
    if (nm->codesNow[k] != nm->codes0[k] || nm->codesNow[k] == BOLT_POINT_SLIP) nm->changed[k] = PETSC_TRUE;
}

PetscErrorCode BoltNewmarkGetChangedPoints(BoltNewmark *nm, const PetscBool **changed)
{
  PetscFunctionBeginUser;
  *changed = nm->trackChanges ? nm->changed : NULL;
  PetscFunctionReturn(0);
}
