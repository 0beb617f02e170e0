/* The coulomb law: the strict law's normal contact with Coulomb friction at every closed node
   pair. A closed pair sticks (its tangential gap held by an elastic stick, k_t) while its
   tangential traction is inside the cone mu |t_N|, and slips on the cone otherwise: a slipping
   pair has no tangential penalty, and its tangential traction mu |t_N| along its slip over the
   step is a force the loop updates after every solve (docs/model.md, friction). The state's gaps
   are raw (u_b - u_a); its anchors are the sticks' rest positions. */
#include "private/contact.h"

/* v less its parts along n and d: the directions in which a slipping pair is held. */
static inline void CoulombAcross(const PetscReal n[3], const PetscReal d[3], const PetscReal v[3], PetscReal out[3])
{
  const PetscReal vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2], vd = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
  for (PetscInt k = 0; k < 3; k++) out[k] = v[k] - vn * n[k] - vd * d[k];
}

static inline PetscReal CoulombNorm3(const PetscReal v[3])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A closed pair: the tangential traction it would have if it had stuck since the start of the
   step (or since it closed), its tangential traction then plus k_t times the change of its
   tangential raw gap since then (the anchor). */
static void CoulombStickTrial(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal trial[3])
{
  const PetscReal *n = &s->set->gpNormal[3 * gp], *g = &s->gap[3 * gp], *a = &s->anchor[3 * gp], *t0 = &s->tractionStart[3 * gp];
  const PetscReal  kt = s->stickStiffness[pair];
  PetscReal        dg[3], dn, t0n;

  for (PetscInt k = 0; k < 3; k++) dg[k] = g[k] - a[k];
  dn  = dg[0] * n[0] + dg[1] * n[1] + dg[2] * n[2];
  t0n = t0[0] * n[0] + t0[1] * n[1] + t0[2] * n[2];
  for (PetscInt k = 0; k < 3; k++) trial[k] = t0[k] - t0n * n[k] + kt * (dg[k] - dn * n[k]);
}

/* The normal part augmented as the strict law's, the tangential part the return map of the
   elastic stick's trial onto the cone mu |t_N| at a slipping pair (a sticking pair whose trial
   leaves the cone is turned to slipping by CoulombReturnMap). */
static void CoulombTrial(const BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal t[3])
{
  const PetscReal *g = &s->gap[3 * gp], *n = &s->set->gpNormal[3 * gp];
  const PetscReal *lam = &s->lambda[3 * gp];
  /* (a penalty normal, the interface-reduced ROM's, has no multiplier: P g.n is all of it) */
  const PetscReal  tn  = (s->augment ? lam[0] * n[0] + lam[1] * n[1] + lam[2] * n[2] : 0) + s->epsN[pair] * (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]);
  PetscReal        tt[3], scale = 1;

  CoulombStickTrial(s, gp, pair, tt);
  if (s->released[gp]) {
    const PetscReal len = CoulombNorm3(tt);
    scale               = len > 0 ? s->set->friction[pair] * PetscMax(-tn, 0.0) / len : 0;
  }
  for (PetscInt k = 0; k < 3; k++) t[k] = tn * n[k] + scale * tt[k];
}

/* The violation of a closed point: its normal gap |g.n| (its tangential gap is the stick's). */
static PetscReal CoulombViolation(const BoltContactState *s, PetscInt gp, PetscBool *squared)
{
  const PetscReal *g = &s->gap[3 * gp], *n = &s->set->gpNormal[3 * gp];
  const PetscReal  gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];

  *squared = PETSC_FALSE;
  return PetscAbsReal(gn);
}

/* A pair that stays closed, after an augmentation (lambda holds its traction, CoulombTrial):
   the return map of its elastic stick's trial traction.
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
static PetscBool CoulombStickSlip(BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal *moved)
{
  const PetscReal *n  = &s->set->gpNormal[3 * gp], *f = &s->lambdaForce[3 * gp];
  PetscReal       *t  = &s->lambda[3 * gp], *d = &s->slipDir[4 * gp];
  const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], bound = s->set->friction[pair] * PetscMax(-tn, 0.0);
  const PetscReal  kt = s->stickStiffness[pair];
  PetscReal        trial[3], len;

  *moved = 0;
  CoulombStickTrial(s, gp, pair, trial);
  len = CoulombNorm3(trial);
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
    CoulombAcross(n, d, &s->gap[3 * gp], across);
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

/* The return map, and the pressure after it: the scale of the friction's convergence test. */
static PetscBool CoulombReturnMap(BoltContactState *s, PetscInt gp, PetscInt pair, PetscReal *moved, PetscReal *pressure)
{
  const PetscBool  changed = CoulombStickSlip(s, gp, pair, moved);
  const PetscReal *t = &s->lambda[3 * gp], *n = &s->set->gpNormal[3 * gp];

  *pressure = -(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]);
  return changed;
}

/* The friction's convergence measure: the slipping pairs' largest traction change over the
   largest pressure (global). */
static PetscErrorCode CoulombReturnChange(BoltContactState *s, PetscReal moved, PetscReal pressure)
{
  PetscReal both[2] = {moved, pressure}, glob[2];

  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(both, glob, 2, MPIU_REAL, MPI_MAX, BoltMeshComm(s->set->mesh)));
  s->frictionChange = glob[1] > 0 ? glob[0] / glob[1] : 0;
  PetscFunctionReturn(0);
}

/* A pair that opens closes again sticking. */
static void CoulombOpen(BoltContactState *s, PetscInt gp)
{
  s->released[gp] = PETSC_FALSE;
}

/* A pair that closes again: its elastic stick starts from no traction where it closes. */
static void CoulombReclose(BoltContactState *s, PetscInt gp)
{
  const PetscReal *t0 = &s->tractionStart[3 * gp], *n = &s->set->gpNormal[3 * gp];
  const PetscReal  kt = s->stickStiffness[s->set->elem[gp / 4].pair], t0n = t0[0] * n[0] + t0[1] * n[1] + t0[2] * n[2];

  for (PetscInt k = 0; k < 3; k++) s->anchor[3 * gp + k] = s->gap[3 * gp + k] + (t0[k] - t0n * n[k]) / kt;
  s->released[gp] = PETSC_FALSE;
}

/* The elastic stick, not the penalty: physics, not scaled with the penalties. */
static PetscReal CoulombStickStiffness(const BoltContactState *s, PetscInt pair)
{
  return s->stickStiffness[pair];
}

/* The penalties over the active points, at a slipping pair the stiffness across its slip. */
static PetscErrorCode CoulombElementStiffness(BoltContactState *s, PetscInt e, PetscReal Ke[576])
{
  BoltContactSet *c    = s->set;
  const PetscInt  pair = c->elem[e].pair;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetElementStiffness(c, e, s->epsN[pair], s->stickStiffness[pair], &s->active[4 * e], &s->released[4 * e], &s->slipDir[16 * e], Ke));
  PetscFunctionReturn(0);
}

/* The normal multiplier, and the tangential traction less K_c's part: at a sticking pair that of
   its elastic stick (K_c: k_t on the raw gap), at a slipping one the return map linearised at
   the last solve's gap (K_c: its stiffness across the slip direction). */
static const PetscReal *CoulombForceMultipliers(BoltContactState *s)
{
  BoltContactSet *c = s->set;

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
      CoulombAcross(n, d, &s->gap[3 * gp], across);
      for (PetscInt k = 0; k < 3; k++) f[k] = lam[k] + (ln - lt) * n[k] - d[3] * across[k];
    }
  }
  return s->lambdaForce;
}

/* The slip beyond the elastic stick's over the step: the gap's tangential change from the
   stick's rest position less the traction's change over k_t (zero at a pair that stuck
   throughout), times the mean tangential traction. */
static PetscReal CoulombDissipation(const BoltContactState *s, PetscInt gp, const PetscReal raw[3], const PetscReal t[3])
{
  const PetscReal *n = &s->set->gpNormal[3 * gp], *a = &s->anchor[3 * gp], *t0 = &s->tractionStart[3 * gp], kt = s->stickStiffness[s->set->elem[gp / 4].pair];
  PetscReal        slip[3], mean[3], sn, mn, fric = 0;

  for (PetscInt k = 0; k < 3; k++) {
    slip[k] = raw[k] - a[k] - (t[k] - t0[k]) / kt;
    mean[k] = 0.5 * (t0[k] + t[k]);
  }
  sn = slip[0] * n[0] + slip[1] * n[1] + slip[2] * n[2];
  mn = mean[0] * n[0] + mean[1] * n[1] + mean[2] * n[2];
  for (PetscInt k = 0; k < 3; k++) fric += (mean[k] - mn * n[k]) * (slip[k] - sn * n[k]);
  return fric;
}

/* The elastic energy of an active point's stick, area |t_T|^2 / (2 k_t). */
static PetscReal CoulombStickEnergy(const BoltContactState *s, PetscInt gp)
{
  BoltContactSet  *c = s->set;
  const PetscReal *t = &s->lambda[3 * gp], *n = &c->gpNormal[3 * gp];
  const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];

  return c->gpW[gp] * (PetscSqr(t[0] - tn * n[0]) + PetscSqr(t[1] - tn * n[1]) + PetscSqr(t[2] - tn * n[2])) / (2 * s->stickStiffness[c->elem[gp / 4].pair]);
}

/* The next step's sticks start where this one ends. */
static void CoulombEndSolve(BoltContactState *s, PetscInt gp, const PetscReal raw[3])
{
  for (PetscInt k = 0; k < 3; k++) s->anchor[3 * gp + k] = raw[k];
}

/* A static solve starts its sticks from zero gaps. */
static void CoulombStaticStart(BoltContactState *s)
{
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) s->anchor[k] = 0;
}

PetscErrorCode BoltContactLawCreate_Coulomb(BoltContactLaw *law)
{
  PetscFunctionBeginUser;
  PetscCall(BoltContactLawCreate_Strict(law)); /* its normal contact */
  law->ops.trial            = CoulombTrial;
  law->ops.violation        = CoulombViolation;
  law->ops.returnMap        = CoulombReturnMap;
  law->ops.returnChange     = CoulombReturnChange;
  law->ops.open             = CoulombOpen;
  law->ops.reclose          = CoulombReclose;
  law->ops.presetReleased   = NULL; /* every closed pair starts sticking: its trial decides again */
  law->ops.stickStiffness   = CoulombStickStiffness;
  law->ops.elementStiffness = CoulombElementStiffness;
  law->ops.forceMultipliers = CoulombForceMultipliers;
  law->ops.dissipation      = CoulombDissipation;
  law->ops.stickEnergy      = CoulombStickEnergy;
  law->ops.endSolve         = CoulombEndSolve;
  law->ops.staticStart      = CoulombStaticStart;
  law->friction             = PETSC_TRUE;
  law->rawGaps              = PETSC_TRUE;
  /* a softer augmentation than the strict law's: the same solves and results on the joint, and
     the energy accounting balances to 1e-8 instead of 5e-7 (the stiff penalty's rounding in the
     equilibrium of the tractions the ledger takes) */
  law->penaltyFactor = 1e6;
  PetscFunctionReturn(0);
}
