/* What the contact state measures for the history and the checks: contact work, stick energy
   and dissipation, tractions and resultants per pair, nodal forces and point codes for output,
   penetration and complementarity. */
#include "private/contact.h"
#include <stdint.h>
#include <string.h>

/* The elastic energy of the law's sticks over the closed pairs [J], over all ranks (friction:
   area |t_T|^2 / (2 k_t) per pair; zero without). With the friction's dissipation it accounts
   for the contact tractions' work. */
PetscErrorCode BoltContactStateStickEnergy(BoltContactState *s, PetscReal *energy)
{
  BoltContactSet *c   = s->set;
  PetscReal       loc = 0;

  PetscFunctionBeginUser;
  if (s->law->ops.stickEnergy)
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      if (!s->active[gp]) continue;
      loc += s->law->ops.stickEnergy(s, gp);
    }
  PetscCall(MPIU_Allreduce(&loc, energy, 1, MPIU_REAL, MPI_SUM, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* Before a static solve: it goes from the unloaded state, so slips and contact work are
   measured from zero gaps and tractions (not from where a run left them). */
void BoltContactStateStaticStart(BoltContactState *s)
{
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) s->slipStart[k] = s->tractionStart[k] = 0;
  if (s->law->ops.staticStart) s->law->ops.staticStart(s);
}

/* The work the contact tractions did so far [J], over all ranks. */
PetscErrorCode BoltContactStateContactWork(BoltContactState *s, PetscReal *work)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&s->contactWork, work, 1, MPIU_REAL, MPI_SUM, BoltMeshComm(s->set->mesh)));
  PetscFunctionReturn(0);
}

/* Sets the work of the contact tractions and the friction's dissipation so far [J], totals over
   all ranks (a restart): the first rank holds them. Collective. */
PetscErrorCode BoltContactStateSetTotals(BoltContactState *s, PetscReal contactWork, PetscReal dissipated)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(BoltMeshComm(s->set->mesh), &rank));
  s->contactWork = rank ? 0 : contactWork;
  s->dissipated  = rank ? 0 : dissipated;
  PetscFunctionReturn(0);
}

/* The energy the slipping pairs dissipated so far [J], over all ranks. */
PetscErrorCode BoltContactStateDissipated(BoltContactState *s, PetscReal *energy)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&s->dissipated, energy, 1, MPIU_REAL, MPI_SUM, BoltMeshComm(s->set->mesh)));
  PetscFunctionReturn(0);
}

/* After a converged time step: count the points that ended it closed. */
void BoltContactStateEndStep(BoltContactState *s)
{
  for (PetscInt gp = 0; gp < 4 * s->set->nelem; gp++) s->closedSteps[gp] = s->active[gp] ? PetscMin(s->closedSteps[gp] + 1, 2) : 0;
}

/* Gaps relative to the anchors (after the raw gaps u_b - u_a were computed into gap). */
void BoltContactStateAnchorGaps(BoltContactState *s, PetscReal gap[])
{
  if (!s->anchored || s->law->rawGaps) return; /* (raw gaps: the anchors are the sticks' rest positions) */
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) gap[k] -= s->anchor[k];
}

/* The contact traction at a point: the trial traction lambda + P g where active (equal to
   lambda once the augmentations converge; P g alone for pure penalty), zero elsewhere. The
   strict loop's multipliers already are the trial tractions of its last solve (its stiff
   penalty on the remaining gap would count that gap twice). */
static void BoltContactStateTraction(BoltContactState *s, PetscBool lambdaIsTraction, PetscInt e, PetscInt gp, PetscReal t[3])
{
  BoltContactSet *c = s->set;

  if (!s->active[gp]) {
    t[0] = t[1] = t[2] = 0;
    return;
  }
  if (lambdaIsTraction) {
    for (PetscInt k = 0; k < 3; k++) t[k] = s->lambda[3 * gp + k];
    return;
  }
  s->law->ops.traction(&s->lambda[3 * gp], &s->gap[3 * gp], &c->gpNormal[3 * gp], s->epsN[c->elem[e].pair], BoltContactStateEpsT(s, gp, c->elem[e].pair), t);
}

/* Each pair's resultant over all ranks, BOLT_PAIR_FORCE values per pair: the force on its side b,
   -int t dA (x, y, z) [N], and the normal force int t.n dA (negative in compression). What a
   joint transmits through each interface, and how near its shear is to mu times its clamp. */
PetscErrorCode BoltContactStatePairForces(BoltContactState *s, PetscReal force[])
{
  BoltContactSet *c = s->set;
  const PetscBool lambdaIsTraction = BoltContactStateLambdaIsTraction(s);

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < BOLT_PAIR_FORCE * c->npairs; p++) force[p] = 0;
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      PetscReal        t[3], *f = &force[BOLT_PAIR_FORCE * c->elem[e].pair];
      const PetscReal *n = &c->gpNormal[3 * gp], w = c->gpW[gp];
      BoltContactStateTraction(s, lambdaIsTraction, e, gp, t);
      for (PetscInt k = 0; k < 3; k++) f[k] -= w * t[k];
      f[3] += w * (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, force, (PetscMPIInt)(BOLT_PAIR_FORCE * c->npairs), MPIU_REAL, MPI_SUM, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* Sum over each pair of the normal contact force, int t.n dA (negative in compression). */
PetscErrorCode BoltContactStateNormalForcePerPair(BoltContactState *s, PetscReal force[])
{
  PetscReal all[BOLT_PAIR_FORCE * BOLTROM_MAX_PAIRS];

  PetscFunctionBeginUser;
  PetscCall(BoltContactStatePairForces(s, all));
  for (PetscInt p = 0; p < s->set->npairs; p++) force[p] = all[BOLT_PAIR_FORCE * p + 3];
  PetscFunctionReturn(0);
}

/* The nodal forces the contact tractions exert on the structure, -B' t, in the global layout of
   F (both sides of every pair). For the output: they are what balances the loads, node by node,
   where the tractions are per contact point. */
PetscErrorCode BoltContactStateNodalForces(BoltContactState *s, Vec F)
{
  BoltContactSet *c = s->set;
  const PetscBool lambdaIsTraction = BoltContactStateLambdaIsTraction(s);

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) BoltContactStateTraction(s, lambdaIsTraction, gp / 4, gp, &s->work->tau[3 * gp]);
  PetscCall(BoltContactSetForcesOf(c, s->work, s->work->tau, F));
  PetscCall(VecScale(F, -1.0)); /* B' t is on the right-hand side with a minus */
  PetscFunctionReturn(0);
}

/* Each local point's state for the output: BOLT_POINT_OPEN, _STICK or _SLIP. */
void BoltContactStatePointCodes(BoltContactState *s, unsigned char codes[])
{
  for (PetscInt gp = 0; gp < 4 * s->set->nelem; gp++) codes[gp] = s->law->ops.pointCode(s, gp);
}

/* Min and max normal traction over active points, and the largest tangential traction. */
PetscErrorCode BoltContactStateTractionStats(BoltContactState *s, PetscReal *tnMin, PetscReal *tnMax, PetscReal *ttMax)
{
  BoltContactSet *c = s->set;
  const PetscBool lambdaIsTraction = BoltContactStateLambdaIsTraction(s);
  PetscReal       mn = PETSC_MAX_REAL, mx = -PETSC_MAX_REAL, tt = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *n = &c->gpNormal[3 * gp];
    PetscReal        lam[3], ln, t2 = 0;
    if (!s->active[gp]) continue;
    BoltContactStateTraction(s, lambdaIsTraction, gp / 4, gp, lam);
    ln = lam[0] * n[0] + lam[1] * n[1] + lam[2] * n[2];
    mn = PetscMin(mn, ln);
    mx = PetscMax(mx, ln);
    for (PetscInt k = 0; k < 3; k++) t2 += PetscSqr(lam[k] - ln * n[k]);
    tt = PetscMax(tt, PetscSqrtReal(t2));
  }
  PetscCall(MPIU_Allreduce(&mn, tnMin, 1, MPIU_REAL, MPI_MIN, BoltMeshComm(c->mesh)));
  PetscCall(MPIU_Allreduce(&mx, tnMax, 1, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  PetscCall(MPIU_Allreduce(&tt, ttMax, 1, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* Area-weighted inner product over the active Gauss points: sum w x.y (global). */
PetscErrorCode BoltContactStateDot(BoltContactState *s, const PetscReal x[], const PetscReal y[], PetscReal *dot)
{
  BoltContactSet *c = s->set;
  PetscReal       loc = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++)
    if (s->active[gp]) loc += c->gpW[gp] * (x[3 * gp] * y[3 * gp] + x[3 * gp + 1] * y[3 * gp + 1] + x[3 * gp + 2] * y[3 * gp + 2]);
  PetscCall(MPIU_Allreduce(&loc, dot, 1, MPIU_REAL, MPI_SUM, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* Largest penetration -g.n over the active points (global); zeroes g at inactive points. */
PetscErrorCode BoltContactStatePenetration(BoltContactState *s, PetscReal g[], PetscReal *pen)
{
  BoltContactSet *c = s->set;
  PetscReal       loc = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *n = &c->gpNormal[3 * gp];
    if (!s->active[gp]) {
      g[3 * gp] = g[3 * gp + 1] = g[3 * gp + 2] = 0;
      continue;
    }
    loc = PetscMax(loc, -(g[3 * gp] * n[0] + g[3 * gp + 1] * n[1] + g[3 * gp + 2] * n[2]));
  }
  PetscCall(MPIU_Allreduce(&loc, pen, 1, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  PetscFunctionReturn(0);
}

/* How far the current state is from one-sided contact at its points (strict law), from the
   gaps of the last solve and the multipliers: the largest penetration -g.n at any point [m];
   the largest tension of a closed point, judged on its node pair's traction (nodal force over
   tributary area) [Pa], and the largest compression [Pa]; and the largest |t.n g.n| [N/m]. */
PetscErrorCode BoltContactStateComplementarity(BoltContactState *s, PetscReal *penetration, PetscReal *tension, PetscReal *compression, PetscReal *product)
{
  BoltContactSet *c = s->set;
  PetscReal      *tn, loc[4] = {0, 0, 0, 0}, glob[4];

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++)
    for (PetscInt k = 0; k < 3; k++) s->work->tau[3 * gp + k] = s->active[gp] ? s->lambda[3 * gp + k] : 0;
  PetscCall(PetscMalloc1(4 * c->nelem + 1, &tn));
  PetscCall(BoltContactSetSmoothedNormalTraction(c, s->work, s->work->tau, tn));
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *g = &s->gap[3 * gp], *n = &c->gpNormal[3 * gp], gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];
    loc[0] = PetscMax(loc[0], -gn);
    if (s->active[gp]) loc[1] = PetscMax(loc[1], tn[gp]);
    loc[2] = PetscMax(loc[2], -tn[gp]);
    loc[3] = PetscMax(loc[3], PetscAbsReal(tn[gp] * gn));
  }
  PetscCall(PetscFree(tn));
  PetscCall(MPIU_Allreduce(loc, glob, 4, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  *penetration = glob[0];
  *tension     = glob[1];
  *compression = glob[2];
  *product     = glob[3];
  PetscFunctionReturn(0);
}
