/* The strict law: one-sided contact at every matched node pair (nodal quadrature): gap.n >= 0,
   normal traction <= 0 and their product zero, with no band; a closed pair sticks (its whole gap
   vector is closed). The penalty is only the augmentation parameter of the active-set loop:
   stiff (3e7 E/m), so that one solve closes a step's gaps to the tolerance once the set is
   right, and far enough from round-off (1e9 E/m moves the results by 2e-4). A pair that opened
   and closes again sticks where it closes, or with -contact_reclose slide slides (normal contact
   only): tied back to where it started it would snap, and stick-open-stick would cycle. */
#include "private/contact.h"

/* The violation of a closed point: its whole gap |g| where it sticks (returned squared), its
   normal gap |g.n| where it slides. */
static PetscReal StrictViolation(const BoltContactState *s, PetscInt gp, PetscBool *squared)
{
  const PetscReal *g = &s->gap[3 * gp], *n = &s->set->gpNormal[3 * gp];
  const PetscReal  gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  *squared = (PetscBool)!s->released[gp];
  if (*squared) return g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
  return PetscAbsReal(gn);
}

/* A pair that closes sticks from where it is: its anchor takes the tangential part of its gap
   (the gaps held are relative to the old anchor). */
static void StrictAnchorAt(BoltContactState *s, PetscInt gp)
{
  const PetscReal *n = &s->set->gpNormal[3 * gp];
  PetscReal       *a = &s->anchor[3 * gp], *g = &s->gap[3 * gp], raw[3], gn;

  for (PetscInt k = 0; k < 3; k++) raw[k] = g[k] + a[k];
  gn = raw[0] * n[0] + raw[1] * n[1] + raw[2] * n[2];
  for (PetscInt k = 0; k < 3; k++) {
    a[k] = raw[k] - gn * n[k];
    g[k] = raw[k] - a[k];
  }
  s->anchored = PETSC_TRUE;
}

static void StrictReclose(BoltContactState *s, PetscInt gp)
{
  if (s->reanchor) StrictAnchorAt(s, gp);
  else s->released[gp] = PETSC_TRUE;
}

/* A stored state's sliding points: those given, else the open ones (they will slide). */
static PetscBool StrictPresetReleased(const BoltContactState *s, PetscInt gp, const PetscBool active[], const PetscBool released[])
{
  return released ? released[gp] : (PetscBool)!active[gp];
}

PetscErrorCode BoltContactLawCreate_Strict(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactLawCreate_Stick(law)); /* its penalty traction, trial and stiffness */
  law->ops.violation      = StrictViolation;
  law->ops.reclose        = StrictReclose;
  law->ops.presetReleased = StrictPresetReleased;
  law->complementarity    = PETSC_TRUE;
  law->penaltyFactor      = 3e7;
  PetscFunctionReturn(0);
}
