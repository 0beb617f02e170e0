/* The stick law (the paper's): augmented Lagrangian with normal and tangential penalties at the
   2x2 Gauss points of each face pair; a closed point sticks with elastic slip only (no Coulomb
   limit), opens when its traction is tensile beyond a band and closes again when it penetrates
   beyond the activation gap. The penalty (200 E/m) is part of the model. Its penalty traction,
   trial and stiffness are also the strict law's. */
#include "private/contact.h"

/* Trial traction t = lambda + epsN (g.n) n + epsT (g - (g.n) n), with the gap g = u_b - u_a and
   n the outward normal of side a. */
void BoltContactLawPenaltyTraction(const PetscReal lambda[3], const PetscReal g[3], const PetscReal n[3], PetscReal epsN, PetscReal epsT, PetscReal t[3])
{
  const PetscReal gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  for (PetscInt k = 0; k < 3; k++) t[k] = lambda[k] + epsT * g[k] + (epsN - epsT) * gn * n[k];
}

/* An active point's trial traction: the penalty traction of its multiplier and gap, without
   the tangential penalty where it slides. */
void BoltContactLawPenaltyTrial(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal t[3])
{
  s->law->ops.traction(&s->lambda[3 * gp], &s->gap[3 * gp], &s->set->gpNormal[3 * gp], s->epsN[pair], BoltContactStateEpsT(s, gp, pair), t);
}

PetscReal BoltContactLawPenaltyStickStiffness(const BoltContactState *s, PetscInt pair)
{
  return s->epsT[pair];
}

/* The penalties over the active points, none tangential at the sliding ones. */
PetscErrorCode BoltContactLawPenaltyElementStiffness(BoltContactState *s, PetscInt e, PetscReal Ke[576])
{
  BoltContactSet *c    = s->set;
  const PetscInt  pair = c->elem[e].pair;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetElementStiffness(c, e, s->epsN[pair], s->law->ops.stickStiffness(s, pair), &s->active[4 * e], &s->released[4 * e], NULL, Ke));
  PetscFunctionReturn(0);
}

/* Open, closed and sticking, or closed and sliding. */
unsigned char BoltContactLawPointCode(const BoltContactState *s, PetscInt gp)
{
  return !s->active[gp] ? BOLT_POINT_OPEN : s->released[gp] ? BOLT_POINT_SLIP : BOLT_POINT_STICK;
}

/* The violation of a closed point: its penetration (its tangential gap is the penalty's law). */
static PetscReal StickViolation(const BoltContactState *s, PetscInt gp, PetscBool *squared)
{
  const PetscReal *g = &s->gap[3 * gp], *n = &s->set->gpNormal[3 * gp];
  const PetscReal  gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  *squared = PETSC_FALSE;
  return -gn;
}

PetscErrorCode BoltContactLawCreate_Stick(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(law, sizeof(*law)));
  law->ops.traction         = BoltContactLawPenaltyTraction;
  law->ops.trial            = BoltContactLawPenaltyTrial;
  law->ops.violation        = StickViolation;
  law->ops.stickStiffness   = BoltContactLawPenaltyStickStiffness;
  law->ops.elementStiffness = BoltContactLawPenaltyElementStiffness;
  law->ops.pointCode        = BoltContactLawPointCode;
  law->penaltyFactor        = 200.0;
  PetscFunctionReturn(0);
}
