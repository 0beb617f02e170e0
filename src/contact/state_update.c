/* The contact state's updates in the dual loop: trial tractions, augmentations of the
   multipliers, the stick/slip return and the active-set decisions, re-closing and anchoring. */
#include "boltrom.h"
#include <stdint.h>
#include <string.h>

/* v less its parts along n and d: the directions in which a slipping pair is held. */
static inline void BoltAcross(const PetscReal n[3], const PetscReal d[3], const PetscReal v[3], PetscReal out[3])
{
  const PetscReal vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2], vd = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
  for (PetscInt k = 0; k < 3; k++) out[k] = v[k] - vn * n[k] - vd * d[k];
}

static inline PetscReal BoltNorm3(const PetscReal v[3])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Coulomb, a closed pair: the tangential traction it would have if it had stuck since the start
   of the step (or since it closed), its tangential traction then plus k_t times the change of its
   tangential raw gap since then (the anchor; the gaps of a frictional state are raw). */
static void BoltContactStateStickTrial(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal trial[3])
{
  const PetscReal *n = &s->set->gpNormal[3 * gp], *g = &s->gap[3 * gp], *a = &s->anchor[3 * gp], *t0 = &s->tractionStart[3 * gp];
  const PetscReal  kt = s->stickStiffness[pair];
  PetscReal        dg[3], dn, t0n;

  for (PetscInt k = 0; k < 3; k++) dg[k] = g[k] - a[k];
  dn  = dg[0] * n[0] + dg[1] * n[1] + dg[2] * n[2];
  t0n = t0[0] * n[0] + t0[1] * n[1] + t0[2] * n[2];
  for (PetscInt k = 0; k < 3; k++) trial[k] = t0[k] - t0n * n[k] + kt * (dg[k] - dn * n[k]);
}

/* The trial traction of an active point: the law's. Under Coulomb friction the normal part is
   augmented as the strict law's, and the tangential part is the return map of the elastic stick's
   trial onto the cone mu |t_N| at a slipping pair (a sticking pair whose trial leaves the cone is
   turned to slipping by BoltContactStateStickSlip). */
static void BoltContactStateTrial(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal t[3])
{
  const PetscReal *g = &s->gap[3 * gp], *n = &s->set->gpNormal[3 * gp];

  if (s->law.friction) {
    const PetscReal *lam = &s->lambda[3 * gp];
    /* (a penalty normal, the interface-reduced ROM's, has no multiplier: P g.n is all of it) */
    const PetscReal  tn  = (s->augment ? lam[0] * n[0] + lam[1] * n[1] + lam[2] * n[2] : 0) + s->epsN[pair] * (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]);
    PetscReal        tt[3], scale = 1;
    BoltContactStateStickTrial(s, gp, pair, tt);
    if (s->released[gp]) {
      const PetscReal len = BoltNorm3(tt);
      scale               = len > 0 ? s->set->friction[pair] * PetscMax(-tn, 0.0) / len : 0;
    }
    for (PetscInt k = 0; k < 3; k++) t[k] = tn * n[k] + scale * tt[k];
    return;
  }
  s->law.traction(&s->lambda[3 * gp], g, n, s->epsN[pair], BoltContactStateEpsT(s, gp, pair), t);
}

/* One augmentation: lambda <- trial traction at active points, 0 elsewhere. Returns the
   relative change of the multipliers and the largest violation of an active point's
   constraint: its penetration -g.n, or under the strict law (a closed pair sticks) |g|. */
PetscErrorCode BoltContactStateAugment(BoltContactState *s, PetscReal *relChange, PetscReal *maxPenetration)
{
  BoltContactSet *c = s->set;
  PetscReal       change = 0, size = 0, nchanged = 0, pen = 0, pen2 = 0, sums[3], glob[4];
  /* under friction the multipliers take the tractions with a penalty normal too: the sticks'
     and slips' tangential tractions are history the loop carries */
  const PetscBool take   = (PetscBool)(s->augment || s->law.friction);
  PetscBool       update = take;

  PetscFunctionBeginUser;
  /* the penalty law sets the multipliers to zero (no trial traction): nothing to update once
     they are (all bits of +0 are zero) */
  if (!update && !s->lambdaZero) {
    uint64_t bits = 0;
    for (PetscInt k = 0; k < 12 * c->nelem; k++) {
      uint64_t b;
      memcpy(&b, &s->lambda[k], sizeof(b));
      bits |= b;
    }
    update = (PetscBool)(bits != 0);
  }
  /* (sums in scalars, not in the array handed to MPI: kept in memory they stalled the loop; the
     sticking points' largest |g| as the root of the largest g.g, the same number) */
  for (PetscInt e = 0; e < c->nelem && (update || s->augment); e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      PetscReal       *lam = &s->lambda[3 * gp], t[3] = {0, 0, 0};
      const PetscReal *g = &s->gap[3 * gp], *n = &c->gpNormal[3 * gp];
      if (update) {
        if (s->active[gp] && take) BoltContactStateTrial(s, gp, pair, t);
        for (PetscInt k = 0; k < 3; k++) {
          change += PetscSqr(t[k] - lam[k]);
          size += PetscSqr(t[k]);
          if (t[k] != lam[k]) nchanged++; /* (a change below the square's underflow counts too) */
          lam[k] = t[k];
        }
      }
      if (s->active[gp] && s->augment) { /* (a penalty's penetration is its law, not a violation) */
        const PetscReal gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];
        if (s->law.strict && !s->released[gp] && !s->law.friction) pen2 = PetscMax(pen2, g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        else pen = PetscMax(pen, !s->law.strict ? -gn : PetscAbsReal(gn));
      }
    }
  }
  pen = PetscMax(pen, PetscSqrtReal(pen2));
  sums[0] = change;
  sums[1] = size;
  sums[2] = nchanged; /* the count goes with the sums */
  /* multipliers known to be +0 everywhere stay so under the penalty law: the sums are zero */
  if (!take && s->lambdaZero) glob[0] = glob[1] = glob[2] = 0;
  else PetscCall(MPIU_Allreduce(sums, glob, 3, MPIU_REAL, MPI_SUM, c->mesh->comm));
  /* the penalty law has no violation to measure: zero on every rank, without asking */
  if (s->augment) PetscCall(MPIU_Allreduce(&pen, &glob[3], 1, MPIU_REAL, MPI_MAX, c->mesh->comm));
  else glob[3] = 0;
  *relChange      = glob[1] > 0 ? PetscSqrtReal(glob[0] / glob[1]) : PetscSqrtReal(glob[0]);
  *maxPenetration = glob[3];
  if (glob[2] > 0) BoltContactStateChanged(s);
  if (!take) s->lambdaZero = PETSC_TRUE; /* the penalty law has set them to +0 on every rank */
  PetscFunctionReturn(0);
}

/* A pair that closes sticks from where it is: its anchor takes the tangential part of its
   gap (the gaps held are relative to the old anchor). */
static void BoltContactStateAnchorAt(BoltContactState *s, PetscInt gp)
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

/* Strict law: a pair that closes again sticks where it closes (its anchor), or with
   -contact_reclose slide slides (normal contact only); tied back to where it started it would
   snap, and stick-open-stick would cycle (docs/model.md section 8). */
static void BoltContactStateReclose(BoltContactState *s, PetscInt gp)
{
  s->closedSteps[gp] = 0; /* its multipliers start afresh */
  if (s->law.friction) { /* its elastic stick starts from no traction where it closes */
    const PetscReal *t0 = &s->tractionStart[3 * gp], *n = &s->set->gpNormal[3 * gp];
    const PetscReal  kt = s->stickStiffness[s->set->elem[gp / 4].pair], t0n = t0[0] * n[0] + t0[1] * n[1] + t0[2] * n[2];
    for (PetscInt k = 0; k < 3; k++) s->anchor[3 * gp + k] = s->gap[3 * gp + k] + (t0[k] - t0n * n[k]) / kt;
    s->released[gp] = PETSC_FALSE;
    return;
  }
  if (!s->law.strict) return;
  if (s->reanchor) BoltContactStateAnchorAt(s, gp);
  else s->released[gp] = PETSC_TRUE;
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

/* Strict laws, after a converged solve: the work the contact tractions did over the step (with
count), and the raw gaps and tractions from which the next step's are measured. Per point, the
mean of its traction at the step's ends times its gap's change, times its area: the trapezoidal
rule of the Newmark step, so that with the structure's energies it balances the external work
(BoltNewmark's energy accounting). The friction's part: that over the slip of the pairs slipping
at the step's end (their traction is lambda + K_c's part across the slip). */
void BoltContactStateEndSolve(BoltContactState *s, PetscBool count)
{
  BoltContactSet *c = s->set;

  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *n = &c->gpNormal[3 * gp];
    PetscReal        t[3] = {0, 0, 0}, raw[3];
    for (PetscInt k = 0; k < 3; k++) raw[k] = s->gap[3 * gp + k] + (s->law.friction ? 0 : s->anchor[3 * gp + k]);
    if (s->active[gp])
      for (PetscInt k = 0; k < 3; k++) t[k] = s->lambda[3 * gp + k];
    if (count) {
      PetscReal work = 0, fric = 0;
      for (PetscInt k = 0; k < 3; k++) work += 0.5 * (s->tractionStart[3 * gp + k] + t[k]) * (raw[k] - s->slipStart[3 * gp + k]);
      if (s->law.friction && s->active[gp]) {
        /* the slip beyond the elastic stick's: the gap's tangential change from the stick's rest
           position less the traction's change over k_t (zero at a pair that stuck throughout) */
        const PetscReal *a = &s->anchor[3 * gp], *t0 = &s->tractionStart[3 * gp], kt = s->stickStiffness[c->elem[gp / 4].pair];
        PetscReal        slip[3], mean[3], sn, mn;
        for (PetscInt k = 0; k < 3; k++) {
          slip[k] = raw[k] - a[k] - (t[k] - t0[k]) / kt;
          mean[k] = 0.5 * (t0[k] + t[k]);
        }
        sn = slip[0] * n[0] + slip[1] * n[1] + slip[2] * n[2];
        mn = mean[0] * n[0] + mean[1] * n[1] + mean[2] * n[2];
        for (PetscInt k = 0; k < 3; k++) fric += (mean[k] - mn * n[k]) * (slip[k] - sn * n[k]);
      }
      s->contactWork += c->gpW[gp] * work;
      s->dissipated += c->gpW[gp] * fric;
    }
    for (PetscInt k = 0; k < 3; k++) {
      s->slipStart[3 * gp + k]     = raw[k];
      s->tractionStart[3 * gp + k] = t[k];
      if (s->law.friction) s->anchor[3 * gp + k] = raw[k]; /* the next step's sticks start here */
    }
  }
}

/* The multipliers whose forces the solve takes: lambda, less epsT times the anchor where there
   is one (K_eff's penalty acts on the raw gap, the traction on the anchored one). */
const PetscReal *BoltContactStateForceMultipliers(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  if (s->law.friction) {
    /* the normal multiplier, and the tangential traction less K_c's part: at a sticking pair that
       of its elastic stick (K_c: k_t on the raw gap), at a slipping one the return map linearised
       at the last solve's gap (K_c: its stiffness across the slip direction) */
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      const PetscInt   pair = c->elem[gp / 4].pair;
      const PetscReal *n = &c->gpNormal[3 * gp], *lam = &s->lambda[3 * gp], *d = &s->slipDir[4 * gp];
      PetscReal       *f = &s->lambdaForce[3 * gp];
      const PetscReal  lt = lam[0] * n[0] + lam[1] * n[1] + lam[2] * n[2], ln = s->augment ? lt : 0; /* (a penalty normal: K_c carries it all) */
      if (!s->active[gp]) {
        f[0] = f[1] = f[2] = 0;
      } else if (!s->released[gp]) {
        const PetscReal *a = &s->anchor[3 * gp], *t0 = &s->tractionStart[3 * gp], kt = s->stickStiffness[pair];
        const PetscReal  an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2], t0n = t0[0] * n[0] + t0[1] * n[1] + t0[2] * n[2];
        for (PetscInt k = 0; k < 3; k++) f[k] = ln * n[k] + t0[k] - t0n * n[k] - kt * (a[k] - an * n[k]);
      } else {
        PetscReal across[3];
        BoltAcross(n, d, &s->gap[3 * gp], across);
        for (PetscInt k = 0; k < 3; k++) f[k] = lam[k] + (ln - lt) * n[k] - d[3] * across[k];
      }
    }
    return s->lambdaForce;
  }
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
      PetscReal *t  = &c->tau[3 * gp];
      if (!s->active[gp]) t[0] = t[1] = t[2] = 0;
      else if (BoltContactStateLambdaIsTraction(s)) PetscCall(PetscArraycpy(t, &s->lambda[3 * gp], 3));
      else BoltContactStateTrial(s, gp, pair, t);
    }
  }
  if (s->openTest == BOLT_OPEN_NODAL) PetscCall(BoltContactSetSmoothedNormalTraction(c, c->tau, tnOpen));
  else
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      const PetscReal *t = &c->tau[3 * gp], *n = &c->gpNormal[3 * gp];
      tnOpen[gp] = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    }
  PetscFunctionReturn(0);
}

/* Coulomb, a pair that stays closed, after an augmentation (lambda holds its traction by its
   state's law, BoltContactStateTrial): the return map of its elastic stick's trial traction.
   - sticking, with the trial beyond the cone mu |t_N|: it slips, its traction on the cone along
     the trial;
   - slipping, with the trial back inside the cone, turned against the slip direction d, or no
     longer pressed: it sticks, with the trial as its traction;
   - slipping on: its traction stays on the cone along the trial. K_c's stiffness across the
     direction d is the return map's derivative, k_t mu |t_N| / |trial| (none along d: the law's
     Newton step); it is renewed when the trial has turned by more than
     -contact_slip_angle_tolerance or the derivative is off by more than
     -contact_slip_stiffness_ratio (else K_c keeps the last one, a quasi-Newton step).
   *moved is how far the traction is from the one the solve linearised [Pa] (zero at a sticking
   pair: its law is linear). Returns whether K_c changed. */
static PetscBool BoltContactStateStickSlip(BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal *moved)
{
  const PetscReal *n  = &s->set->gpNormal[3 * gp], *f = &s->lambdaForce[3 * gp];
  PetscReal       *t  = &s->lambda[3 * gp], *d = &s->slipDir[4 * gp];
  const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], bound = s->set->friction[pair] * PetscMax(-tn, 0.0);
  const PetscReal  kt = s->stickStiffness[pair];
  PetscReal        trial[3], len;

  *moved = 0;
  BoltContactStateStickTrial(s, gp, pair, trial);
  len = BoltNorm3(trial);
  if (!s->released[gp]) {
    if (len <= bound * (1 + BOLT_FRICTION_MARGIN) || s->stickOnly) return PETSC_FALSE;
    for (PetscInt k = 0; k < 3; k++) {
      d[k] = trial[k] / len;
      t[k] = tn * n[k] + bound * d[k];
    }
    d[3]            = kt * bound / len;
    s->released[gp] = PETSC_TRUE;
    return PETSC_TRUE;
  }
  /* back inside the cone; or the trial has turned against the slip (Newton's step jumped across
     the cone's inside, where a point reversing its slip sticks: from there it slips again if it
     must, else the two directions take turns). Under the loop's anti-cycling rule a slipping
     pair slips on (the slipping set only grows), on the cone along its trial. */
  if (!s->closeOnly && (len <= bound || tn >= 0 || trial[0] * d[0] + trial[1] * d[1] + trial[2] * d[2] <= 0)) {
    for (PetscInt k = 0; k < 3; k++) t[k] = tn * n[k] + trial[k];
    s->released[gp] = PETSC_FALSE;
    return PETSC_TRUE;
  }
  {
    const PetscReal ka     = kt * bound / len;
    const PetscReal cosine = (trial[0] * d[0] + trial[1] * d[1] + trial[2] * d[2]) / len;
    /* (under the anti-cycling rule K_c keeps what it has: only the traction moves) */
    const PetscBool turn   = (PetscBool)(!s->closeOnly && len > 0 && (cosine < 1 - 0.5 * PetscSqr(s->slipAngleTolerance) || ka > s->slipStiffnessRatio * d[3] || ka * s->slipStiffnessRatio < d[3]));
    PetscReal       across[3], fn = f[0] * n[0] + f[1] * n[1] + f[2] * n[2];
    /* the tangential traction the solve saw: its force's, plus K_c's across d */
    BoltAcross(n, d, &s->gap[3 * gp], across);
    for (PetscInt k = 0; k < 3; k++) {
      const PetscReal seen = f[k] - fn * n[k] + d[3] * across[k];
      *moved               = PetscMax(*moved, PetscAbsReal(t[k] - tn * n[k] - seen));
    }
    if (turn) {
      for (PetscInt k = 0; k < 3; k++) d[k] = trial[k] / len;
      d[3] = ka;
    }
    return turn;
  }
}

/* New active set from the opening test's tractions (BoltContactStateOpenTraction, or a model's
   own) and the gaps; counts the points that changed (global) and tells whether the set equals
   the one two outer iterations back (cycling between two sets). */
PetscErrorCode BoltContactStateUpdateActive(BoltContactState *s, const PetscReal tnOpen[], PetscInt *nchanged, PetscBool *cycling)
{
  BoltContactSet *c = s->set;
  PetscInt        loc[3] = {0, 0, 0}, glob[3];
  PetscReal       fric = 0, press = 0;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < c->nelem; e++) {
    const PetscInt pair = c->elem[e].pair;
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt  gp = 4 * e + q;
      PetscBool now;
      /* A band of width activationGap (or the traction bandTraction) around zero keeps
         points at the edge of the contact zone, whose gaps and tractions are at round-off
         level, from chattering between the sets: a closed point opens when its traction is
         tensile beyond the band, an open point closes when it penetrates beyond it. */
      {
        const PetscReal *g = &s->gap[3 * gp], *n = &c->gpNormal[3 * gp];
        const PetscReal  band = s->bandTraction[pair];
        if ((s->mayChange && !s->mayChange[gp]) || s->holdContact) now = s->active[gp];
        else if (s->active[gp]) now = (s->closeOnly || tnOpen[gp] < band) ? PETSC_TRUE : PETSC_FALSE;
        else now = -(g[0] * n[0] + g[1] * n[1] + g[2] * n[2]) > s->activationGap ? PETSC_TRUE : PETSC_FALSE;
      }
      s->activeOlder[gp] = s->activeOld[gp];
      s->activeOld[gp]   = s->active[gp];
      if (s->law.friction && now && s->active[gp] && !(s->mayChange && !s->mayChange[gp])) {
        PetscReal moved;
        if (BoltContactStateStickSlip(s, gp, pair, &moved)) {
          loc[0]++;
          loc[2]++; /* a change of stick and slip is not a two-set cycle of the open and closed sets */
          s->dirty[e] = PETSC_TRUE;
        }
        fric = PetscMax(fric, moved);
        if (s->law.friction) { /* the pressure scale of the friction's convergence test */
          const PetscReal *t = &s->lambda[3 * gp], *n = &c->gpNormal[3 * gp];
          press = PetscMax(press, -(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]));
        }
      }
      /* a sticking pair that opened and now closes to slide is in a new state, not a cycle */
      if (s->law.strict && now && !s->active[gp] && !s->released[gp]) loc[2]++;
      if (now != s->active[gp]) {
        loc[0]++;
        s->dirty[e] = PETSC_TRUE;
        if (!now) {
          s->lambda[3 * gp] = s->lambda[3 * gp + 1] = s->lambda[3 * gp + 2] = 0;
          if (s->law.friction) s->released[gp] = PETSC_FALSE; /* it closes again sticking */
        } else BoltContactStateReclose(s, gp);
      }
      s->active[gp] = now;
      if (now) loc[1]++;
      if (now != s->activeOlder[gp]) loc[2]++;
    }
  }
  PetscCall(MPIU_Allreduce(loc, glob, 3, MPIU_INT, MPI_SUM, c->mesh->comm));
  if (s->law.friction) {
    PetscReal both[2] = {fric, press}, glob2[2];
    PetscCall(MPIU_Allreduce(both, glob2, 2, MPIU_REAL, MPI_MAX, c->mesh->comm));
    s->frictionChange = glob2[1] > 0 ? glob2[0] / glob2[1] : 0;
  }
  *nchanged  = glob[0];
  s->nactive = glob[1];
  if (glob[0] || s->law.friction) BoltContactStateChanged(s); /* friction moves slipping pairs' multipliers */
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
  PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_INT, MPI_SUM, c->mesh->comm));
  *nclosed   = glob[0];
  s->nactive = glob[1];
  if (glob[0]) BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}
