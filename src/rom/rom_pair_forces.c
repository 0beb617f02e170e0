/* The reduced model's pair resultants (the /rom/pair_force history): what its contact exerts on
   each pair's side b, as BoltContactStatePairForces gives the FOM's. Under a penalty law the
   traction of an active point is t = lambda_F + P D q (its force multipliers and its penalty on
   the whole gap of its node pair, as the reduced operator applies them: F_r + K_cr q), affine in
   q. So each pair's resultant is b + A q, with A (BOLT_PAIR_FORCE rows per pair, n columns) and b
   summed per rank over its points and changed, when the contact state's version moves, at the
   points that changed; a step costs one small product and a reduction of BOLT_PAIR_FORCE values
   per pair instead of a pass over every contact point. */
#include "private/rom.h"

/* Whether the resultants are affine in q: the penalty law without friction (the strict and
   stick laws' interface-reduced ROM), whose multipliers are given, not tractions. Elsewhere
   (augmented ROMs, friction) the multipliers are the tractions, and the state's own sum over its
   points is the model's force. */
static PetscBool ROMPairForcesAffine(BoltContactState *s)
{
  return (PetscBool)(!BoltContactStateHasFriction(s) && !BoltContactStateAugmented(s));
}

/* Adds sign times point gp's term to the local A and b: its force multipliers t0, and its
   penalty P (3 x 3, column-major) on the whole gap rows of the node pairs it interpolates (its
   own under the nodal quadrature), read from the node pairs' rows of D. */
static void ROMPairForceTerm(BoltROM *rom, PetscInt gp, PetscReal sign, const PetscReal t0[3], const PetscReal P[9])
{
  BoltContactSet  *c  = rom->contact;
  const PetscInt   n = rom->n, m = BOLT_PAIR_FORCE * BoltContactSetPairCount(c), e = gp / 4;
  const PetscInt   p = BOLT_PAIR_FORCE * BoltContactSetElementPair(c, e);
  const PetscBool  nodal = (PetscBool)(BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL);
  const PetscReal *nv = &BoltContactSetNormals(c)[3 * gp], *N = &BoltContactSetShapeValues(c)[4 * gp];
  const PetscReal  wt = sign * BoltContactSetWeights(c)[gp];
  PetscReal       *A = rom->pfLocal, *b = &rom->pfLocal[m * n], coef[4][3];

  for (PetscInt k = 0; k < 3; k++) b[p + k] -= wt * t0[k];
  b[p + 3] += wt * (t0[0] * nv[0] + t0[1] * nv[1] + t0[2] * nv[2]);
  /* row k of the resultant takes -w (P g)_k, the normal row w n' P g: coefficients of g's parts */
  for (PetscInt l = 0; l < 3; l++) {
    for (PetscInt k = 0; k < 3; k++) coef[k][l] = -wt * P[3 * l + k];
    coef[3][l] = wt * (nv[0] * P[3 * l] + nv[1] * P[3 * l + 1] + nv[2] * P[3 * l + 2]);
  }
  for (PetscInt i = 0; i < 4; i++) {
    const PetscInt   k = rom->npOfPoint[4 * e + i];
    const PetscReal  Ni = nodal ? (i == gp % 4 ? 1.0 : 0.0) : N[i];
    const PetscReal *D = k >= 0 ? &rom->npRowsAll[3 * n * k] : NULL;
    if (!D || Ni == 0) continue; /* both nodes clamped: no gap */
    for (PetscInt r = 0; r < 4; r++) {
      PetscReal *restrict a = &A[(p + r) * n];
      const PetscReal     c0 = Ni * coef[r][0], c1 = Ni * coef[r][1], c2 = Ni * coef[r][2];
      for (PetscInt j = 0; j < n; j++) a[j] += c0 * D[j] + c1 * D[n + j] + c2 * D[2 * n + j];
    }
  }
}

/* This rank's part of A and b for the current state. Each local point's term is kept with what
   made it (its multipliers, its penalties and the 3 x 3 P they make); a new state replaces the
   terms of the points where these changed, so a set change costs its changed points, not every
   point. */
static PetscErrorCode ROMPairForceMap(BoltROM *rom, BoltContactState *s)
{
  BoltContactSet  *c  = rom->contact;
  const PetscInt   ngp = 4 * BoltContactSetElementCount(c);
  const PetscBool *active = BoltContactStateActive(s);
  const PetscReal *lf = BoltContactStateForceMultipliers(s);

  PetscFunctionBeginUser;
  for (PetscInt gp = 0; gp < ngp; gp++) {
    PetscReal *old = &rom->pfTerm[16 * gp], eN = 0, eT = 0;
    PetscBool  same = (PetscBool)(active[gp] == rom->pfIn[gp]);
    if (active[gp]) BoltContactStatePointPenalties(s, gp, &eN, &eT);
    for (PetscInt k = 0; k < 3 && same && active[gp]; k++) same = (PetscBool)(old[k] == lf[3 * gp + k]);
    if (same && active[gp]) same = (PetscBool)(old[12] == eN && old[13] == eT);
    if (same) continue;
    if (rom->pfIn[gp]) ROMPairForceTerm(rom, gp, -1, old, &old[3]);
    if (active[gp]) {
      const PetscReal zero[3] = {0, 0, 0};
      for (PetscInt k = 0; k < 3; k++) { /* P's columns: the law's traction of unit gaps */
        PetscReal unit[3] = {0, 0, 0};
        unit[k] = 1;
        BoltContactStateTrialOf(s, gp, zero, unit, &old[3 + 3 * k]);
      }
      PetscCall(PetscArraycpy(old, &lf[3 * gp], 3));
      old[12] = eN;
      old[13] = eT;
      ROMPairForceTerm(rom, gp, 1, old, &old[3]);
    }
    rom->pfIn[gp] = active[gp];
  }
  PetscFunctionReturn(0);
}

/* The pair resultants at q (BOLT_PAIR_FORCE per pair, the same on every rank). */
PetscErrorCode ROMPairResultants(BoltOperator *op, Vec q, PetscReal force[])
{
  BoltROM           *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactState  *s   = BoltOperatorState(op);
  const PetscInt     n = rom->n, m = BOLT_PAIR_FORCE * BoltContactSetPairCount(rom->contact);
  const PetscScalar *x;

  PetscFunctionBeginUser;
  if (!ROMPairForcesAffine(s)) {
    PetscCall(BoltContactStatePairForces(s, force));
    PetscFunctionReturn(0);
  }
  if (!rom->pfLocal) {
    const PetscInt ngp = 4 * BoltContactSetElementCount(rom->contact);
    PetscCall(PetscCalloc3(m * (n + 1), &rom->pfLocal, 16 * ngp + 1, &rom->pfTerm, ngp + 1, &rom->pfIn));
  }
  if (!rom->pfValid || rom->pfVersion != BoltContactStateVersion(s)) {
    PetscCall(ROMPairForceMap(rom, s));
    rom->pfVersion = BoltContactStateVersion(s);
    rom->pfValid   = PETSC_TRUE;
  }
  PetscCall(VecGetArrayRead(q, &x));
  for (PetscInt r = 0; r < m; r++) {
    const PetscReal *a = &rom->pfLocal[r * n];
    PetscReal        v = rom->pfLocal[m * n + r];
    for (PetscInt j = 0; j < n; j++) v += a[j] * PetscRealPart(x[j]);
    force[r] = v;
  }
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, force, (PetscMPIInt)m, MPIU_REAL, MPI_SUM, rom->comm));
  PetscFunctionReturn(0);
}
