/* The contact state's updates in the dual loop: augmentations of the multipliers, the
   active-set decisions, re-closing and anchors, the multipliers the solve takes. What a point
   does under its law (trial traction, return map, re-closing) is the law's (src/contact/laws/). */
#include "private/contact.h"

/* One augmentation: lambda <- the law's trial traction at active points, 0 elsewhere. Returns
   the relative change of the multipliers and the largest violation of an active point's
   constraint by the law's measure (its penetration, or the length of its gap where it sticks).
   Under the penalty law the multipliers are not unknowns: they are what was given (zero, or a
   ROM's frozen preloaded tractions, BoltROMSetPreloadState) and stay so. */
PetscErrorCode BoltContactStateAugment(BoltContactState *s, PetscReal *relChange, PetscReal *maxPenetration)
{
  BoltContactSet *c = s->set;
  PetscReal       change = 0, size = 0, nchanged = 0, pen = 0, pen2 = 0, sums[3], glob[4];
  /* with a return map the multipliers take the tractions with a penalty normal too: the sticks'
     and slips' tangential tractions are history the loop carries */
  const PetscBool take = (PetscBool)(s->augment || s->law->ops.returnMap);

  PetscFunctionBeginUser;
  /* (sums in scalars, not in the array handed to MPI: kept in memory they stalled the loop; the
     sticking points' largest |g| as the root of the largest g.g, the same number) */
  for (PetscInt e = 0; e < c->nelem && take; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt   gp  = 4 * e + q;
      PetscReal *lam = &s->lambda[3 * gp], t[3] = {0, 0, 0};
      if (s->active[gp]) s->law->ops.trial(s, gp, pair, t);
      for (PetscInt k = 0; k < 3; k++) {
        change += PetscSqr(t[k] - lam[k]);
        size += PetscSqr(t[k]);
        if (t[k] != lam[k]) nchanged++; /* (a change below the square's underflow counts too) */
        lam[k] = t[k];
      }
      if (s->active[gp] && s->augment) { /* (a penalty's penetration is its law, not a violation) */
        PetscBool       squared;
        const PetscReal v = s->law->ops.violation(s, gp, &squared);
        if (squared) pen2 = PetscMax(pen2, v);
        else pen = PetscMax(pen, v);
      }
    }
  }
  pen = PetscMax(pen, PetscSqrtReal(pen2));
  sums[0] = change;
  sums[1] = size;
  sums[2] = nchanged; /* the count goes with the sums */
  if (!take) glob[0] = glob[1] = glob[2] = 0; /* nothing moved, on any rank */
  else PetscCall(MPIU_Allreduce(sums, glob, 3, MPIU_REAL, MPI_SUM, BoltMeshComm(c->mesh)));
  /* the penalty law has no violation to measure: zero on every rank, without asking */
  if (s->augment) PetscCall(MPIU_Allreduce(&pen, &glob[3], 1, MPIU_REAL, MPI_MAX, BoltMeshComm(c->mesh)));
  else glob[3] = 0;
  *relChange      = glob[1] > 0 ? PetscSqrtReal(glob[0] / glob[1]) : PetscSqrtReal(glob[0]);
  *maxPenetration = glob[3];
  if (glob[2] > 0) BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* A pair that closes again: its multipliers start afresh, and its law says how it closes (the
   strict law: sticking where it closes, or sliding; Coulomb: sticking, from no traction). */
static void BoltContactStateReclose(BoltContactState *s, PetscInt gp)
{
  s->closedSteps[gp] = 0;
  if (s->law->ops.reclose) s->law->ops.reclose(s, gp);
}

/* Anchors of a stored state (NULL: none, every closed point sticks where it started). */
void BoltContactStateSetAnchors(BoltContactState *s, const PetscReal anchor[])
{
  s->anchored = PETSC_FALSE;
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) {
    s->anchor[k] = anchor ? anchor[k] : 0;
    if (s->anchor[k] != 0) s->anchored = PETSC_TRUE;
  }
  BoltContactStateChanged(s); /* the forces of the multipliers move with the anchors */
}

/* At the start of a time step, from a converged one: the multipliers of the points that ended
   the last two steps closed are extrapolated linearly in time, lambda <- 2 lambda_n - lambda_n-1.
   The loop's first solve then starts from tractions that are off by the change of their rate, not
   by their change over the step, and its gaps are that much smaller: where they are within the
   tolerance, the step costs one solve. The converged state moves only within the loop's
   tolerance. Every rank calls it: the state changes. */
void BoltContactStateExtrapolate(BoltContactState *s)
{
  for (PetscInt gp = 0; gp < 4 * s->set->nelem; gp++)
    for (PetscInt k = 3 * gp; k < 3 * gp + 3; k++) {
      const PetscReal before = s->lambdaPrev[k];
      s->lambdaPrev[k] = s->lambda[k];
      if (s->closedSteps[gp] == 2 && s->active[gp]) s->lambda[k] = 2 * s->lambda[k] - before;
    }
  BoltContactStateChanged(s);
}

/* After a converged solve: the work the contact tractions did over the step (with count), and
the raw gaps and tractions from which the next step's are measured. Per point, the mean of its
traction at the step's ends times its gap's change, times its area: the trapezoidal rule of the
Newmark step, so that with the structure's energies it balances the external work (BoltNewmark's
energy accounting); and the energy the law dissipated at the point (friction: over the slip). */
void BoltContactStateEndSolve(BoltContactState *s, PetscBool count)
{
  BoltContactSet *c = s->set;

  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    PetscReal t[3] = {0, 0, 0}, raw[3];
    for (PetscInt k = 0; k < 3; k++) raw[k] = s->gap[3 * gp + k] + (s->law->rawGaps ? 0 : s->anchor[3 * gp + k]);
    if (s->active[gp])
      for (PetscInt k = 0; k < 3; k++) t[k] = s->lambda[3 * gp + k];
    if (count) {
      PetscReal work = 0, fric = 0;
      for (PetscInt k = 0; k < 3; k++) work += 0.5 * (s->tractionStart[3 * gp + k] + t[k]) * (raw[k] - s->slipStart[3 * gp + k]);
      if (s->law->ops.dissipation && s->active[gp]) fric = s->law->ops.dissipation(s, gp, raw, t);
      s->contactWork += c->gpW[gp] * work;
      s->dissipated += c->gpW[gp] * fric;
    }
    for (PetscInt k = 0; k < 3; k++) {
      s->slipStart[3 * gp + k]     = raw[k];
      s->tractionStart[3 * gp + k] = t[k];
    }
    if (s->law->ops.endSolve) s->law->ops.endSolve(s, gp, raw);
  }
}

/* The multipliers whose forces the solve takes: lambda, less epsT times the anchor where there
   is one (K_eff's penalty acts on the raw gap, the traction on the anchored one). */
const PetscReal *BoltContactStateForceMultipliers(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  if (s->law->ops.forceMultipliers) return s->law->ops.forceMultipliers(s);
  if (!s->anchored) return s->lambda;
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      const PetscInt  gp = 4 * e + q;
      const PetscReal eT = s->active[gp] ? BoltContactStateEpsT(s, gp, pair) : 0;
      for (PetscInt k = 0; k < 3; k++) s->lambdaForce[3 * gp + k] = s->lambda[3 * gp + k] - eT * s->anchor[3 * gp + k];
    }
  }
  return s->lambdaForce;
}

/* The normal traction that decides whether a closed point opens, at every local point (used at
   the active ones): the multipliers (converged) with augmentation, the trial traction for the
   penalty alone; smoothed through the nodes (BOLT_OPEN_NODAL) or the point's own. Collective. */
PetscErrorCode BoltContactStateOpenTraction(BoltContactState *s, PetscReal tnOpen[])
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt   gp = 4 * e + q;
      PetscReal *t  = &s->work->tau[3 * gp];
      if (!s->active[gp]) t[0] = t[1] = t[2] = 0;
      else if (BoltContactStateLambdaIsTraction(s)) PetscCall(PetscArraycpy(t, &s->lambda[3 * gp], 3));
      else s->law->ops.trial(s, gp, pair, t);
    }
  }
  if (s->openTest == BOLT_OPEN_NODAL) PetscCall(BoltContactSetSmoothedNormalTraction(c, s->work, s->work->tau, tnOpen));
  else
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      const PetscReal *t = &s->work->tau[3 * gp], *n = &c->gpNormal[3 * gp];
      tnOpen[gp] = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    }
  PetscFunctionReturn(0);
}

/* New active set from the opening test's tractions (BoltContactStateOpenTraction, or a model's
   own) and the gaps; counts the points that changed (global) and tells whether the set equals
   the one two outer iterations back (cycling between two sets). */
PetscErrorCode BoltContactStateUpdateActive(BoltContactState *s, const PetscReal tnOpen[], PetscInt *nchanged, PetscBool *cycling)
{
  BoltContactSet *c = s->set;
  const PetscBool complementarity = BoltContactStateIsComplementarity(s);
  PetscInt        loc[3] = {0, 0, 0}, glob[3];
  PetscReal       fric = 0, press = 0;
  /* the loop's invariants in locals: read through s they would be loaded again after every store
     into the state's arrays, and the loop runs over every point at every solve */
  PetscBool       *active = s->active, *activeOld = s->activeOld, *activeOlder = s->activeOlder, *dirty = s->dirty;
  const PetscBool *released = s->released, *mayChange = s->mayChange;
  const PetscReal *gap = s->gap, *normal = c->gpNormal;
  const PetscBool  holdAll = s->holdContact, closeOnly = s->closeOnly;
  const PetscReal  activationGap = s->activationGap;
  PetscBool (*returnMap)(BoltContactState *, PetscInt, PetscInt, PetscReal *, PetscReal *) = s->law->ops.returnMap;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt  pair = c->elem[e].pair;
    const PetscReal band = s->bandTraction[pair];
    for (PetscInt q = 0; q < 4; q++) {
      const PetscInt  gp   = 4 * e + q;
      const PetscBool mayNot = (PetscBool)(mayChange && !mayChange[gp]), was = active[gp];
      PetscBool       now;
      /* A band of width activationGap (or the traction bandTraction) around zero keeps
         points at the edge of the contact zone, whose gaps and tractions are at round-off
         level, from chattering between the sets: a closed point opens when its traction is
         tensile beyond the band, an open point closes when it penetrates beyond it. */
      if (mayNot || holdAll) now = was;
      else if (was) now = (closeOnly || tnOpen[gp] < band) ? PETSC_TRUE : PETSC_FALSE;
      else {
        const PetscReal *g = &gap[3 * gp], *n = &normal[3 * gp];
        now = -(g[0] * n[0] + g[1] * n[1] + g[2] * n[2]) > activationGap ? PETSC_TRUE : PETSC_FALSE;
      }
      activeOlder[gp] = activeOld[gp];
      activeOld[gp]   = was;
      if (returnMap && now && was && !mayNot) {
        PetscReal moved, pressure;
        if (returnMap(s, gp, pair, &moved, &pressure)) {
          loc[0]++;
          loc[2]++; /* a change of stick and slip is not a two-set cycle of the open and closed sets */
          dirty[e] = PETSC_TRUE;
        }
        fric  = PetscMax(fric, moved);
        press = PetscMax(press, pressure); /* the pressure scale of the return maps' convergence test */
      }
      /* a sticking pair that opened and now closes to slide is in a new state, not a cycle */
      if (complementarity && now && !was && !released[gp]) loc[2]++;
      if (now != was) {
        loc[0]++;
        dirty[e] = PETSC_TRUE;
        if (!now) {
          s->lambda[3 * gp] = s->lambda[3 * gp + 1] = s->lambda[3 * gp + 2] = 0;
          if (s->law->ops.open) s->law->ops.open(s, gp);
        } else BoltContactStateReclose(s, gp);
      }
      active[gp] = now;
      if (now) loc[1]++;
      if (now != activeOlder[gp]) loc[2]++;
    }
  }
  PetscCall(MPIU_Allreduce(loc, glob, 3, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  if (s->law->ops.returnChange) PetscCall(s->law->ops.returnChange(s, fric, press));
  *nchanged  = glob[0];
  s->nactive = glob[1];
  if (glob[0] || s->law->ops.returnMap) BoltContactStateChanged(s); /* the return maps move multipliers */
  else s->unchangedUpdates++;
  /* once points only close (anti-cycling) the set grows and cannot cycle: a return to the set of
     two iterations back is then the points opened just before closing again */
  *cycling   = (!s->closeOnly && glob[0] > 0 && glob[2] == 0) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* After a two-set cycle (BoltContactStateUpdateActive): the points that toggle between the sets
   are closed, i.e. the union of the two sets. Closed is the conservative side: it lets no point
   penetrate, at the price of a traction at the cycling points that the band would have let
   open. Returns the number of points closed. */
PetscErrorCode BoltContactStateCloseCycle(BoltContactState *s, PetscInt *nclosed)
{
  BoltContactSet *c = s->set;
  PetscInt        loc[2] = {0, 0}, glob[2];

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    if (!s->active[gp] && s->activeOld[gp]) {
      s->active[gp]     = PETSC_TRUE;
      BoltContactStateReclose(s, gp);
      s->dirty[gp / 4] = PETSC_TRUE;
      loc[0]++;
    }
    if (s->active[gp]) loc[1]++;
  }
  PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_INT, MPI_SUM, BoltMeshComm(c->mesh)));
  *nclosed   = glob[0];
  s->nactive = glob[1];
  if (glob[0]) BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}
