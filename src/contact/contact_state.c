/* The contact state of one model: its law and penalties, and the multipliers, gaps and active
   sets at the Gauss points, with the element matrices and K_c of the active set. The full and
   the reduced model each own one over the shared geometry (BoltContactSet), so neither changes
   the other's penalties or multipliers. */
#include "boltrom.h"
#include <stdint.h>
#include <string.h>

/* A state with the geometry's default law and penalties, every point active, no multipliers. */
PetscErrorCode BoltContactStateCreate(BoltContactSet *c, BoltContactState **sp)
{
  BoltContactState *s;
  const PetscInt    ne = c->nelem;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->set = c;
  PetscCall(PetscStrncpy(s->lawType, c->lawType, sizeof(s->lawType)));
  s->law = c->law; /* looked up once, when the set read -contact_law */
  s->augment       = c->augment;
  s->activationGap = c->activationGap;
  /* the strict law judges a closed pair on its nodal traction (force over tributary area): with
     nodal quadrature that is the node pair's own multiplier, shared by its element corners */
  s->openTest      = s->law.strict ? BOLT_OPEN_NODAL : c->openTest;
  for (PetscInt p = 0; p < c->npairs; p++) {
    s->epsN[p]         = c->epsN[p];
    s->epsT[p]         = c->epsT[p];
    s->bandTraction[p] = c->bandTraction[p];
    s->stickStiffness[p] = c->stickStiffness[p];
  }
  PetscCall(PetscCalloc2(12 * ne + 1, &s->lambda, 12 * ne + 1, &s->gap));
  PetscCall(PetscCalloc2(12 * ne + 1, &s->anchor, 12 * ne + 1, &s->lambdaForce));
  PetscCall(PetscCalloc4(12 * ne + 1, &s->lambdaPrev, 4 * ne + 1, &s->closedSteps, 12 * ne + 1, &s->slipStart, 16 * ne + 1, &s->slipDir));
  PetscCall(PetscCalloc1(12 * ne + 1, &s->tractionStart));
  s->reanchor = c->reanchor;
  s->slipAngleTolerance = c->slipAngleTolerance;
  s->slipStiffnessRatio = c->slipStiffnessRatio;
  PetscCall(PetscMalloc4(4 * ne + 1, &s->active, 4 * ne + 1, &s->activeOld, 4 * ne + 1, &s->activeOlder, 4 * ne + 1, &s->released));
  PetscCall(PetscMalloc1(ne + 1, &s->dirty));
  PetscCall(BoltContactStateReset(s));
  *sp = s;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltContactStateDestroy(BoltContactState **sp)
{
  BoltContactState *s = *sp;

  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  PetscCall(PetscFree2(s->lambda, s->gap));
  PetscCall(PetscFree2(s->anchor, s->lambdaForce));
  PetscCall(PetscFree4(s->lambdaPrev, s->closedSteps, s->slipStart, s->slipDir));
  PetscCall(PetscFree(s->tractionStart));
  PetscCall(PetscFree4(s->active, s->activeOld, s->activeOlder, s->released));
  PetscCall(PetscFree(s->dirty));
  PetscCall(PetscFree(s->Ke));
  PetscCall(MatDestroy(&s->Kc));
  PetscCall(PetscFree(*sp));
  PetscFunctionReturn(0);
}

/* This model's penalties: scale times the geometry's defaults, and its opening band (the
   tension at which a closed point opens) band times the default; every element is due for a
   stiffness update. */
PetscErrorCode BoltContactStateSetPenaltyScale(BoltContactState *s, PetscReal scale, PetscReal band)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < c->npairs; p++) {
    s->epsN[p]         = c->epsN[p] * scale;
    s->epsT[p]         = c->epsT[p] * scale;
    s->bandTraction[p] = c->bandTraction[p] * band;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Frees the element matrices and K_c (a finished run's); the next stiffness request rebuilds
   them from the active set. */
PetscErrorCode BoltContactStateReleaseStiffness(BoltContactState *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(s->Ke));
  PetscCall(MatDestroy(&s->Kc));
  s->KcAssembled = PETSC_FALSE;
  for (PetscInt e = 0; e < s->set->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Closed points that slide (strict law, -contact_reclose slide: they have opened once), and
   closed points that stick where they closed again (-contact_reclose stick), global. */
PetscErrorCode BoltContactStateCountReclosed(BoltContactState *s, PetscInt *nsliding, PetscInt *nanchored)
{
  PetscInt n[2] = {0, 0}, glob[2];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4 * s->set->nelem; i++) {
    const PetscReal *a = &s->anchor[3 * i];
    n[0] += (s->active[i] && s->released[i]) ? 1 : 0;
    n[1] += (s->active[i] && (a[0] != 0 || a[1] != 0 || a[2] != 0)) ? 1 : 0;
  }
  PetscCall(MPIU_Allreduce(n, glob, 2, MPIU_INT, MPI_SUM, s->set->mesh->comm));
  *nsliding = glob[0];
  if (nanchored) *nanchored = glob[1];
  PetscFunctionReturn(0);
}

/* nactive from the active flags (after they were set from outside, e.g. a checkpoint). */
PetscErrorCode BoltContactStateCountActive(BoltContactState *s)
{
  PetscInt nact = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4 * s->set->nelem; i++) nact += s->active[i] ? 1 : 0;
  PetscCall(MPIU_Allreduce(&nact, &s->nactive, 1, MPIU_INT, MPI_SUM, s->set->mesh->comm));
  PetscFunctionReturn(0);
}

/* Element e's state as BOLT_CONTACT_PACK values (checkpoints): multipliers (12), gaps (12), the
   active flags of the last three outer iterations and the released flags (4 each), anchors (12),
   the multipliers of the step before (12), the closed steps in a row (4) and the raw gaps at the
   start of the step (12), the slip directions and stiffnesses (16, friction) and the tractions at
   the start of the step (12). */
void BoltContactStatePack(BoltContactState *s, PetscInt e, PetscReal buf[])
{
  PetscInt k = 0;

  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->lambda[12 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->gap[12 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->active[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->activeOld[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->activeOlder[4 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->released[4 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->anchor[12 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->lambdaPrev[12 * e + i];
  for (PetscInt i = 0; i < 4; i++) buf[k++] = s->closedSteps[4 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->slipStart[12 * e + i];
  for (PetscInt i = 0; i < 16; i++) buf[k++] = s->slipDir[16 * e + i];
  for (PetscInt i = 0; i < 12; i++) buf[k++] = s->tractionStart[12 * e + i];
}

/* The inverse of BoltContactStatePack; the element is due for a stiffness update. Not collective:
   the caller calls BoltContactStateChanged once all elements are unpacked. */
void BoltContactStateUnpack(BoltContactState *s, PetscInt e, const PetscReal buf[])
{
  for (PetscInt i = 0; i < 12; i++) s->lambda[12 * e + i] = buf[i];
  for (PetscInt i = 0; i < 12; i++) s->gap[12 * e + i] = buf[12 + i];
  for (PetscInt i = 0; i < 4; i++) s->active[4 * e + i] = buf[24 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->activeOld[4 * e + i] = buf[28 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->activeOlder[4 * e + i] = buf[32 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 4; i++) s->released[4 * e + i] = buf[36 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt i = 0; i < 12; i++) {
    s->anchor[12 * e + i] = buf[40 + i];
    if (buf[40 + i] != 0) s->anchored = PETSC_TRUE;
  }
  for (PetscInt i = 0; i < 12; i++) s->lambdaPrev[12 * e + i] = buf[52 + i];
  for (PetscInt i = 0; i < 4; i++) s->closedSteps[4 * e + i] = (PetscInt)buf[64 + i];
  for (PetscInt i = 0; i < 12; i++) s->slipStart[12 * e + i] = buf[68 + i];
  for (PetscInt i = 0; i < 16; i++) s->slipDir[16 * e + i] = buf[80 + i];
  for (PetscInt i = 0; i < 12; i++) s->tractionStart[12 * e + i] = buf[96 + i];
  s->dirty[e]    = PETSC_TRUE;
  s->KcAssembled = PETSC_FALSE;
}

PetscErrorCode BoltContactStateReset(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt g = 0; g < 4 * c->nelem; g++) {
    s->active[g] = s->activeOld[g] = s->activeOlder[g] = PETSC_TRUE;
    s->released[g] = PETSC_FALSE;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  s->KcAssembled = PETSC_FALSE;
  PetscCall(PetscArrayzero(s->lambda, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->gap, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->anchor, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->slipStart, 12 * c->nelem));
  PetscCall(PetscArrayzero(s->tractionStart, 12 * c->nelem));
  s->dissipated = s->contactWork = 0;
  s->anchored = PETSC_FALSE;
  s->nactive = c->ngpGlobal;
  BoltContactStateChanged(s);
  PetscFunctionReturn(0);
}

/* Gap vectors g = u_b - u_a at every Gauss point, from uc, less the anchors. */
PetscErrorCode BoltContactStateGaps(BoltContactState *s)
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  PetscCall(BoltContactSetGapsOf(c, s->gap));
  BoltContactStateAnchorGaps(s, s->gap);
  PetscFunctionReturn(0);
}

/* v less its parts along n and d: the directions in which a slipping pair is held. */
static inline void BoltAcross(const PetscReal n[3], const PetscReal d[3], const PetscReal v[3], PetscReal out[3])
{
  const PetscReal vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2], vd = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
  for (PetscInt k = 0; k < 3; k++) out[k] = v[k] - vn * n[k] - vd * d[k];
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

static inline PetscReal BoltNorm3(const PetscReal v[3])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
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

/* The elastic energy of the frictional sticks, sum over closed pairs of area |t_T|^2 / (2 k_t)
   [J], over all ranks (zero without friction). With the friction's dissipation it accounts for
   the contact tractions' work. */
PetscErrorCode BoltContactStateStickEnergy(BoltContactState *s, PetscReal *energy)
{
  BoltContactSet *c   = s->set;
  PetscReal       loc = 0;

  PetscFunctionBeginUser;
  if (s->law.friction)
    for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
      const PetscReal *t = &s->lambda[3 * gp], *n = &c->gpNormal[3 * gp];
      const PetscReal  tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
      if (!s->active[gp]) continue;
      loc += c->gpW[gp] * (PetscSqr(t[0] - tn * n[0]) + PetscSqr(t[1] - tn * n[1]) + PetscSqr(t[2] - tn * n[2])) / (2 * s->stickStiffness[c->elem[gp / 4].pair]);
    }
  PetscCall(MPIU_Allreduce(&loc, energy, 1, MPIU_REAL, MPI_SUM, c->mesh->comm));
  PetscFunctionReturn(0);
}

/* Before a static solve: it goes from the unloaded state, so slips and contact work are
   measured from zero gaps and tractions (not from where a run left them). */
void BoltContactStateStaticStart(BoltContactState *s)
{
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) s->slipStart[k] = s->tractionStart[k] = 0;
  if (s->law.friction)
    for (PetscInt k = 0; k < 12 * s->set->nelem; k++) s->anchor[k] = 0;
}

/* The work the contact tractions did so far [J], over all ranks. */
PetscErrorCode BoltContactStateContactWork(BoltContactState *s, PetscReal *work)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&s->contactWork, work, 1, MPIU_REAL, MPI_SUM, s->set->mesh->comm));
  PetscFunctionReturn(0);
}

/* Sets the work of the contact tractions and the friction's dissipation so far [J], totals over
   all ranks (a restart): the first rank holds them. Collective. */
PetscErrorCode BoltContactStateSetTotals(BoltContactState *s, PetscReal contactWork, PetscReal dissipated)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(s->set->mesh->comm, &rank));
  s->contactWork = rank ? 0 : contactWork;
  s->dissipated  = rank ? 0 : dissipated;
  PetscFunctionReturn(0);
}

/* The energy the slipping pairs dissipated so far [J], over all ranks. */
PetscErrorCode BoltContactStateDissipated(BoltContactState *s, PetscReal *energy)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&s->dissipated, energy, 1, MPIU_REAL, MPI_SUM, s->set->mesh->comm));
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
  if (!s->anchored || s->law.friction) return; /* a frictional state's anchors are its sticks' rest positions */
  for (PetscInt k = 0; k < 12 * s->set->nelem; k++) gap[k] -= s->anchor[k];
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

/* Puts a given active set in place (a stored preloaded state), with the points that slide
   (released; NULL: under the strict law, those that are open): the sets of the last two outer
   iterations are taken to be the same, and every element is due for a stiffness update. */
PetscErrorCode BoltContactStateSetActive(BoltContactState *s, const PetscBool active[], const PetscBool released[])
{
  BoltContactSet *c = s->set;
  PetscInt        nact = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    s->active[gp] = s->activeOld[gp] = s->activeOlder[gp] = active[gp];
    /* an open point will slide; under friction every closed pair starts sticking, and its trial
       traction decides again whether it slips */
    s->released[gp] = (PetscBool)(s->law.strict && !s->law.friction && (released ? released[gp] : !active[gp]));
    if (active[gp]) nact++;
  }
  for (PetscInt e = 0; e < c->nelem; e++) s->dirty[e] = PETSC_TRUE;
  BoltContactStateChanged(s);
  PetscCall(MPIU_Allreduce(&nact, &s->nactive, 1, MPIU_INT, MPI_SUM, c->mesh->comm));
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

/* K_c of the active Gauss points in the global layout; only elements whose activity changed
   are recomputed. */
PetscErrorCode BoltContactStateStiffness(BoltContactState *s, Mat *Kc)
{
  BoltContactSet *c = s->set;
  PetscScalar    *v;
  PetscInt        changed = 0, any;

  PetscFunctionBeginUser;
  if (!s->Kc) { /* a model that never asks for the global K_c (the ROM) holds none */
    PetscCall(PetscMalloc1(576 * c->nelem + 1, &s->Ke));
    PetscCall(BoltContactSetStiffnessMatrix(c, &s->Kc));
  }
  for (PetscInt e = 0; e < c->nelem; e++) {
    if (!s->dirty[e]) continue;
    PetscCall(BoltContactSetElementStiffness(c, e, s->epsN[c->elem[e].pair], BoltContactStateStickStiffness(s, c->elem[e].pair), &s->active[4 * e], &s->released[4 * e], BoltContactStateSlipDirs(s, e), &s->Ke[576 * e]));
    s->dirty[e] = PETSC_FALSE;
    changed++;
  }
  PetscCall(MPIU_Allreduce(&changed, &any, 1, MPIU_INT, MPI_SUM, c->mesh->comm));
  *Kc = s->Kc;
  if (!any && s->KcAssembled) PetscFunctionReturn(0); /* nothing changed since the last call */
  s->KcAssembled = PETSC_TRUE;
#if defined(PETSC_USE_COMPLEX)
  SETERRQ(c->mesh->comm, PETSC_ERR_SUP, "Real scalars only");
#else
  v = (PetscScalar *)s->Ke;
#endif
  PetscCall(MatSetValuesCOO(s->Kc, v, INSERT_VALUES));
  PetscFunctionReturn(0);
}

/* The contact traction at a point: the trial traction lambda + P g where active (equal to
   lambda once the augmentations converge; P g alone for pure penalty), zero elsewhere. The
   strict loop's multipliers already are the trial tractions of its last solve (its stiff
   penalty on the remaining gap would count that gap twice). */
static void BoltContactStateTraction(BoltContactState *s, PetscInt e, PetscInt gp, PetscReal t[3])
{
  BoltContactSet *c = s->set;

  if (!s->active[gp]) {
    t[0] = t[1] = t[2] = 0;
    return;
  }
  if (BoltContactStateLambdaIsTraction(s)) {
    for (PetscInt k = 0; k < 3; k++) t[k] = s->lambda[3 * gp + k];
    return;
  }
  s->law.traction(&s->lambda[3 * gp], &s->gap[3 * gp], &c->gpNormal[3 * gp], s->epsN[c->elem[e].pair], BoltContactStateEpsT(s, gp, c->elem[e].pair), t);
}

/* Each pair's resultant over all ranks, BOLT_PAIR_FORCE values per pair: the force on its side b,
   -int t dA (x, y, z) [N], and the normal force int t.n dA (negative in compression). What a
   joint transmits through each interface, and how near its shear is to mu times its clamp. */
PetscErrorCode BoltContactStatePairForces(BoltContactState *s, PetscReal force[])
{
  BoltContactSet *c = s->set;

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < BOLT_PAIR_FORCE * c->npairs; p++) force[p] = 0;
  for (PetscInt e = 0; e < c->nelem; e++)
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      PetscReal        t[3], *f = &force[BOLT_PAIR_FORCE * c->elem[e].pair];
      const PetscReal *n = &c->gpNormal[3 * gp], w = c->gpW[gp];
      BoltContactStateTraction(s, e, gp, t);
      for (PetscInt k = 0; k < 3; k++) f[k] -= w * t[k];
      f[3] += w * (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, force, (PetscMPIInt)(BOLT_PAIR_FORCE * c->npairs), MPIU_REAL, MPI_SUM, c->mesh->comm));
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

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) BoltContactStateTraction(s, gp / 4, gp, &c->tau[3 * gp]);
  PetscCall(BoltContactSetForcesOf(c, c->tau, F));
  PetscCall(VecScale(F, -1.0)); /* B' t is on the right-hand side with a minus */
  PetscFunctionReturn(0);
}

/* Each local point's state for the output: BOLT_POINT_OPEN, _STICK or _SLIP. */
void BoltContactStatePointCodes(BoltContactState *s, unsigned char codes[])
{
  for (PetscInt gp = 0; gp < 4 * s->set->nelem; gp++) codes[gp] = !s->active[gp] ? BOLT_POINT_OPEN : s->released[gp] ? BOLT_POINT_SLIP : BOLT_POINT_STICK;
}

/* Min and max normal traction over active points, and the largest tangential traction. */
PetscErrorCode BoltContactStateTractionStats(BoltContactState *s, PetscReal *tnMin, PetscReal *tnMax, PetscReal *ttMax)
{
  BoltContactSet *c = s->set;
  PetscReal       mn = PETSC_MAX_REAL, mx = -PETSC_MAX_REAL, tt = 0;

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *n = &c->gpNormal[3 * gp];
    PetscReal        lam[3], ln, t2 = 0;
    if (!s->active[gp]) continue;
    BoltContactStateTraction(s, gp / 4, gp, lam);
    ln = lam[0] * n[0] + lam[1] * n[1] + lam[2] * n[2];
    mn = PetscMin(mn, ln);
    mx = PetscMax(mx, ln);
    for (PetscInt k = 0; k < 3; k++) t2 += PetscSqr(lam[k] - ln * n[k]);
    tt = PetscMax(tt, PetscSqrtReal(t2));
  }
  PetscCall(MPIU_Allreduce(&mn, tnMin, 1, MPIU_REAL, MPI_MIN, c->mesh->comm));
  PetscCall(MPIU_Allreduce(&mx, tnMax, 1, MPIU_REAL, MPI_MAX, c->mesh->comm));
  PetscCall(MPIU_Allreduce(&tt, ttMax, 1, MPIU_REAL, MPI_MAX, c->mesh->comm));
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
  PetscCall(MPIU_Allreduce(&loc, dot, 1, MPIU_REAL, MPI_SUM, c->mesh->comm));
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
  PetscCall(MPIU_Allreduce(&loc, pen, 1, MPIU_REAL, MPI_MAX, c->mesh->comm));
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
    for (PetscInt k = 0; k < 3; k++) c->tau[3 * gp + k] = s->active[gp] ? s->lambda[3 * gp + k] : 0;
  PetscCall(PetscMalloc1(4 * c->nelem + 1, &tn));
  PetscCall(BoltContactSetSmoothedNormalTraction(c, c->tau, tn));
  for (PetscInt gp = 0; gp < 4 * c->nelem; gp++) {
    const PetscReal *g = &s->gap[3 * gp], *n = &c->gpNormal[3 * gp], gn = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];
    loc[0] = PetscMax(loc[0], -gn);
    if (s->active[gp]) loc[1] = PetscMax(loc[1], tn[gp]);
    loc[2] = PetscMax(loc[2], -tn[gp]);
    loc[3] = PetscMax(loc[3], PetscAbsReal(tn[gp] * gn));
  }
  PetscCall(PetscFree(tn));
  PetscCall(MPIU_Allreduce(loc, glob, 4, MPIU_REAL, MPI_MAX, c->mesh->comm));
  *penetration = glob[0];
  *tension     = glob[1];
  *compression = glob[2];
  *product     = glob[3];
  PetscFunctionReturn(0);
}
