/* The reduced model's gaps and opening test from rows of the basis at the node pairs (normal
   rows on flat surfaces), set up once and kept while the contact state holds. */
#include "private/rom.h"
#include <petscblaslapack.h>

/* Whether an open point's whole gap is taken near closing (it sticks where it closes, and its
   anchor needs the tangential part): one-sided contact that re-anchors, with normal rows and
   nodal points. */
static PetscBool ROMWholeGapsNearClosing(BoltROM *rom)
{
  BoltContactSet *c = rom->contact;
  return (PetscBool)(BoltContactSetIsComplementarity(c) && BoltContactSetReanchor(c) && !rom->wholeRows && BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL);
}

/* The gaps at the local contact points from rows of node-pair differences D = V_b - V_a (a
   sixth or half of the rows of V_c, and free of the cancellation in u_b - u_a), under the
   penalty law: there the multipliers do not take the trial traction, so the gaps only feed the
   decisions and the penalty acts through K_cr. On flat surfaces only the normal part,
   g = (sum_a N_a n' D_a q) n: the decisions read t.n, where the tangential part cancels to
   round-off; friction's decisions read the slip too, so there the whole gap. With augmentation
   (the multipliers take the trial traction): u_c and the set's interpolation, as the full
   model. everywhere: every row, held points' too, and every open point's whole gap
   (-rom_verify, and the check). */
static PetscErrorCode ROMGaps(BoltOperator *op, Vec q, PetscBool everywhere, PetscReal gap[])
{
  BoltROM           *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactSet    *c   = rom->contact;
  BoltContactState  *s   = BoltOperatorState(op);
  const PetscInt     ngp = 4 * BoltContactSetElementCount(c), quadrature = BoltContactSetQuadrature(c);
  const PetscReal   *gpN = BoltContactSetShapeValues(c), *gpNormal = BoltContactSetNormals(c), activationGap = BoltContactStateActivationGap(s);
  const PetscBool   *active = BoltContactStateActive(s), *mayChange = BoltContactStateMayChange(s);
  const PetscScalar *x;
  const PetscBool    whole = ROMWholeGapsNearClosing(rom);
  PetscReal          xmax  = 0;

  PetscFunctionBeginUser;
  if (BoltContactStateAugmented(s)) {
    PetscCall(ROMContactDisplacements(op, q));
    PetscCall(BoltContactSetGapsOf(c, BoltContactStateWork(s), gap));
    PetscFunctionReturn(0);
  }
  if (rom->pairGaps) { /* the owned pairs' gaps (the held ones once), sent to their points */
    PetscCall(VecGetArrayRead(q, &x));
    ROMRowsTimes(rom->heldRowsDone && !everywhere ? 3 * rom->npLive : 3 * rom->npOwned, rom->n, rom->npRows, 3 * rom->npOwned, x, rom->npGap);
    PetscCall(VecRestoreArrayRead(q, &x));
    rom->heldRowsDone = PETSC_TRUE;
    for (PetscInt k = 0; k < rom->npOwned; k++)
      for (PetscInt i = rom->npSlotStart[k]; i < rom->npSlotStart[k + 1]; i++)
        for (PetscInt l = 0; l < 3; l++) rom->npSlotF[3 * i + l] = PetscRealPart(rom->npGap[rom->npRowOf[k] + l]);
    PetscCall(PetscArrayzero(gap, 3 * ngp)); /* a point whose nodes are both clamped has no gap */
    PetscCall(PetscSFBcastBegin(rom->npSF, MPIU_REAL, rom->npSlotF, gap, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(rom->npSF, MPIU_REAL, rom->npSlotF, gap, MPI_REPLACE));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(q, &x));
  /* the rows of points that may change; those of held points (their state is kept, so no decision
     reads their gaps) once, for gaps that stay defined */
  ROMRowsTimes(rom->heldRowsDone && !everywhere ? rom->nLiveRows : rom->nGapRows, rom->n, rom->Rn, rom->nGapRows, x, rom->gnRow);
  rom->heldRowsDone = PETSC_TRUE;
  for (PetscInt j = 0; j < rom->n && whole; j++) xmax = PetscMax(xmax, PetscAbsReal(PetscRealPart(x[j])));
  rom->gapsXmax = xmax;
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  *r = &rom->gpRows[4 * gp];
    const PetscReal *N = &gpN[4 * gp], *n = &gpNormal[3 * gp]; /* gpN: 4 per point */
    PetscReal       *g = &gap[3 * gp];
    if (!rom->wholeRows) {
      PetscReal gn = 0;
      if (quadrature == BOLT_QUADRATURE_NODAL) gn = r[gp % 4] >= 0 ? PetscRealPart(rom->gnRow[r[gp % 4]]) : 0; /* its own node, weight 1 */
      else
        for (PetscInt a = 0; a < 4; a++)
          if (r[a] >= 0) gn += N[a] * PetscRealPart(rom->gnRow[r[a]]);
      for (PetscInt k = 0; k < 3; k++) g[k] = gn * n[k];
      /* an open pair that closes sticks where it closes: its anchor needs the whole gap, from its
         node pair's rows of D_e in a fixed order (the same bits on any partition). Only where it
         may close: elsewhere the decision -g.n > activationGap is the same with the normal gap
         alone, whose rounding differs from the whole gap's by less than the bound. */
      if (whole && !active[gp] && (everywhere || ((!mayChange || mayChange[gp]) && -gn > activationGap - rom->wholeGapBound[gp] * xmax))) {
        PetscScalar whole3[3];
        ROMRowsTimes(3, rom->n, &rom->De[12 * rom->n * (gp / 4) + 3 * (gp % 4)], 12, x, whole3);
        for (PetscInt k = 0; k < 3; k++) g[k] = PetscRealPart(whole3[k]);
      }
    } else if (quadrature == BOLT_QUADRATURE_NODAL) /* its own node, weight 1 */
      for (PetscInt k = 0; k < 3; k++) g[k] = r[gp % 4] >= 0 ? PetscRealPart(rom->gnRow[r[gp % 4] + k]) : 0;
    else
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal v = 0;
        for (PetscInt a = 0; a < 4; a++)
          if (r[a] >= 0) v += N[a] * PetscRealPart(rom->gnRow[r[a] + k]);
        g[k] = v;
      }
  }
  PetscCall(VecRestoreArrayRead(q, &x));
  PetscFunctionReturn(0);
}

/* Whether the opening test's traction is affine in the point's normal gap (ROMOpenTraction). */
PetscBool ROMOpenTractionAffine(BoltROM *rom, BoltContactState *s)
{
  return (PetscBool)!(BoltContactStateAugmented(s) || BoltContactStateHasFriction(s) || (BoltContactStateOpenTest(s) == BOLT_OPEN_NODAL && !(BoltContactSetQuadrature(rom->contact) == BOLT_QUADRATURE_NODAL && rom->flat)));
}

/* tnC and tnK of ROMOpenTraction, made again (collectively) when the state's version moves. */
static PetscErrorCode ROMOpenTractionTerms(BoltROM *rom, BoltContactState *s)
{
  BoltContactSet  *c   = rom->contact;
  const PetscInt   ngp = 4 * BoltContactSetElementCount(c);
  const PetscReal *gpNormal = BoltContactSetNormals(c);
  PetscReal       *tau; /* 3 per point: the tractions whose normal part is wanted */

  PetscFunctionBeginUser;
  if (rom->tnValid && rom->tnVersion == BoltContactStateVersion(s)) PetscFunctionReturn(0);
  PetscCall(BoltGrowReal(&rom->tnTau, &rom->tnTauAlloc, 3 * ngp + 1));
  tau = rom->tnTau;
  for (PetscInt pass = 0; pass < 2; pass++) {
    PetscReal       *out    = pass ? rom->tnK : rom->tnC;
    const PetscBool *active = BoltContactStateActive(s);
    const PetscReal *lambda = BoltContactStateLambda(s);
    for (PetscInt gp = 0; gp < ngp; gp++) {
      const PetscReal *n    = &gpNormal[3 * gp], zero[3] = {0, 0, 0};
      PetscReal       *t    = &tau[3 * gp];
      if (!active[gp]) t[0] = t[1] = t[2] = 0;
      else if (!pass) PetscCall(PetscArraycpy(t, &lambda[3 * gp], 3));
      else BoltContactStateTrialOf(s, gp, zero, n, t);
    }
    if (BoltContactStateOpenTest(s) == BOLT_OPEN_NODAL) PetscCall(BoltContactSetSmoothedNormalTraction(c, BoltContactStateWork(s), tau, out));
    else
      for (PetscInt gp = 0; gp < ngp; gp++) {
        const PetscReal *t = &tau[3 * gp], *n = &gpNormal[3 * gp];
        out[gp] = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
      }
  }
  rom->tnVersion = BoltContactStateVersion(s);
  rom->tnValid   = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The dual loop's gaps (ROMGaps): those its decisions read, or all with -rom_verify. */
PetscErrorCode ROMContactGaps(BoltOperator *op, Vec q, PetscReal gap[])
{
  BoltROM *rom = (BoltROM *)BoltOperatorContext(op);

  PetscFunctionBeginUser;
  PetscCall(ROMGaps(op, q, rom->gapsEverywhere, gap));
  PetscFunctionReturn(0);
}

/* The check's gaps (BoltDualCheckStep): every point's, held ones included, from the same rows
   (not the augmented ROM's: it is not registered there). On flat surfaces without friction only
   the normal gap, as the decisions read it: the check's normal tractions and penetrations need no
   more. */
PetscErrorCode ROMCheckGaps(BoltOperator *op, Vec q, PetscReal gap[])
{
  PetscFunctionBeginUser;
  PetscCall(ROMGaps(op, q, PETSC_TRUE, gap));
  PetscFunctionReturn(0);
}

/* The opening test's traction of the (anchored) gaps gap at every point, where it is affine in
   them (ROMOpenTraction); registered for the check only there. */
PetscErrorCode ROMCheckTraction(BoltOperator *op, const PetscReal gap[], PetscReal tn[])
{
  BoltROM          *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactSet   *c   = rom->contact;
  const PetscInt    ngp = 4 * BoltContactSetElementCount(c);
  const PetscReal  *gpNormal = BoltContactSetNormals(c);

  PetscFunctionBeginUser;
  PetscCall(ROMOpenTractionTerms(rom, BoltOperatorState(op)));
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscReal *g = &gap[3 * gp], *n = &gpNormal[3 * gp];
    tn[gp] = rom->tnC[gp] + rom->tnK[gp] * (g[0] * n[0] + g[1] * n[1] + g[2] * n[2]);
  }
  PetscFunctionReturn(0);
}

/* The opening test's traction. Under the penalty law the trial traction of a point is affine in
   its gap, t = lambda + P g, so where the test reads t.n of the point alone, or (nodal quadrature,
   flat surfaces) of the points of its own node pair, its traction is C + K g.n per point: C the
   test applied to the multipliers, K to the traction of a unit normal gap. Both change only with
   the state. */
PetscErrorCode ROMOpenTraction(BoltOperator *op, PetscReal tn[])
{
  BoltROM          *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactState *s   = BoltOperatorState(op);

  PetscFunctionBeginUser;
  if (!ROMOpenTractionAffine(rom, s)) PetscCall(BoltContactStateOpenTraction(s, tn));
  else PetscCall(ROMCheckTraction(op, BoltContactStateGap(s), tn));
  PetscFunctionReturn(0);
}

/* Whether the proof of ROMSetKept applies: penalty law without friction, flat surfaces (one
   normal row per node pair), nodal quadrature (a point reads its own row); not with
   -rom_verify, whose runs test every point at every solve (the same decisions). */
PetscBool ROMSetKeptApplies(BoltROM *rom, BoltContactState *s)
{
  return (PetscBool)(!rom->gapsEverywhere && !rom->wholeRows && !rom->pairGaps && BoltContactSetQuadrature(rom->contact) == BOLT_QUADRATURE_NODAL && ROMOpenTractionAffine(rom, s));
}

/* The intervals of ROMSetKept from the state: a closed point stays closed while
   tnC + tnK g < band, i.e. g < (band - tnC) / tnK; an open one stays open while -g <= the
   activation gap, and while its normal gap is farther from closing than the whole gap's rounding
   bound (else the whole gap is taken, ROMContactGaps). Each bound is moved inwards by 1e-10 of
   its terms, far beyond the rounding of the tests themselves, so that a gap inside proves the
   test's outcome. A point without a row (both nodes clamped) has the gap 0 whatever q is. */
static PetscErrorCode ROMSetKeptIntervals(BoltROM *rom, BoltContactState *s)
{
  BoltContactSet  *c   = rom->contact;
  const PetscInt   ngp = 4 * BoltContactSetElementCount(c);
  const PetscBool *active = BoltContactStateActive(s), *mayChange = BoltContactStateMayChange(s);
  const PetscReal  activationGap = BoltContactStateActivationGap(s), openLo = -activationGap + 1e-10 * PetscAbsReal(activationGap);
  const PetscBool  whole = ROMWholeGapsNearClosing(rom);

  PetscFunctionBeginUser;
  PetscCall(ROMOpenTractionTerms(rom, s));
  for (PetscInt r = 0; r < rom->nGapRows; r++) {
    rom->keptLo[r]   = PETSC_MIN_REAL;
    rom->keptHi[r]   = PETSC_MAX_REAL;
    rom->keptCoef[r] = 0;
  }
  rom->keptNever = PETSC_FALSE;
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  r    = rom->gpRows[4 * gp + gp % 4];
    const PetscReal band = BoltContactStateBandTraction(s, BoltContactSetElementPair(c, gp / 4)), C = rom->tnC[gp], K = rom->tnK[gp];
    if (mayChange && !mayChange[gp]) continue; /* held: its state stays whatever its gap */
    if (active[gp]) {
      const PetscReal hi = K > 0 ? (band - C) / K - 1e-10 * (PetscAbsReal(band) + PetscAbsReal(C)) / K : PETSC_MIN_REAL;
      if (r < 0) rom->keptNever = (PetscBool)(rom->keptNever || !(C < band));
      else { /* (and within 1e4 times its distance from opening on the other side, where K g's rounding stays below the margin) */
        rom->keptHi[r] = PetscMin(rom->keptHi[r], hi);
        if (K > 0) rom->keptLo[r] = PetscMax(rom->keptLo[r], -1e4 * (PetscAbsReal(band) + PetscAbsReal(C)) / K);
      }
    } else {
      if (r < 0) rom->keptNever = (PetscBool)(rom->keptNever || activationGap < 0);
      else {
        rom->keptLo[r] = PetscMax(rom->keptLo[r], openLo);
        if (whole) rom->keptCoef[r] = PetscMax(rom->keptCoef[r], rom->wholeGapBound[gp]);
      }
    }
  }
  rom->keptVersion = BoltContactStateVersion(s);
  rom->keptValid   = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Whether the gaps of the last ROMContactGaps prove that no point would change its state, so
   that the dual loop may skip the point-by-point update (BoltDualUpdateActive): each live row's
   normal gap inside the interval of its points (ROMSetKeptIntervals). Rows read once per solve
   instead of every point's test and traction. Collective. */
PetscErrorCode ROMSetKept(BoltOperator *op, PetscBool *kept)
{
  BoltROM          *rom = (BoltROM *)BoltOperatorContext(op);
  BoltContactState *s   = BoltOperatorState(op);
  PetscInt          in  = 1, all;

  PetscFunctionBeginUser; /* (registered only where ROMSetKeptApplies) */
  if (!rom->keptValid || rom->keptVersion != BoltContactStateVersion(s)) PetscCall(ROMSetKeptIntervals(rom, s));
  if (rom->keptNever) in = 0;
  for (PetscInt r = 0; r < rom->nLiveRows && in; r++) {
    const PetscReal g = PetscRealPart(rom->gnRow[r]);
    in = g < rom->keptHi[r] && g > rom->keptLo[r] + rom->keptCoef[r] * rom->gapsXmax;
  }
  PetscCall(MPIU_Allreduce(&in, &all, 1, MPIU_INT, MPI_MIN, rom->comm));
  *kept = (PetscBool)(all == 1);
  PetscFunctionReturn(0);
}

/* A point's normal rounded to 2^-40: the normals of a flat face's points differ in their last
   bits; rounded, they are one normal, whichever point of whichever rank makes a row. */
static void ROMRowNormal(const PetscReal n[3], PetscReal nr[3])
{
  for (PetscInt k = 0; k < 3; k++) nr[k] = ldexp(rint(ldexp(n[k], 40)), -40);
}

/* The gap rows, from the elements' D_e so that a row has the same bits on any partition. Whether
   the surfaces are flat: at every node the normals of all points around it, over all ranks (the
   nodal area vector sums them), agree with each point's to 1e-12. On flat surfaces one row n' D
   per node pair and rounded point normal (one per node pair), else the three rows of D. */
PetscErrorCode ROMSetUpGapRows(BoltROM *rom, const PetscBool mayChange[])
{
  BoltContactSet *c = rom->contact;
  const PetscInt  nloc = BoltContactSetLocalSize(c);
  const PetscInt  n = rom->n, ngp = 4 * BoltContactSetElementCount(c);
  PetscInt       *first, *next, *rowGp, *rowNode, *pos, width;
  PetscBool       flat = PETSC_TRUE, *live;

  PetscFunctionBeginUser;
  PetscCall(PetscFree4(rom->gpRows, rom->tnC, rom->tnK, rom->wholeGapBound));
  PetscCall(PetscFree2(rom->Rn, rom->gnRow));
  PetscCall(PetscMalloc4(4 * ngp + 1, &rom->gpRows, ngp + 1, &rom->tnC, ngp + 1, &rom->tnK, ngp + 1, &rom->wholeGapBound));
  PetscCall(PetscMalloc4(nloc + 1, &first, 4 * ngp + 1, &next, 4 * ngp + 1, &rowGp, 4 * ngp + 1, &rowNode));
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  *loc = &BoltContactSetElementLocal(c)[24 * (gp / 4)];
    const PetscReal *N = &BoltContactSetShapeValues(c)[4 * gp], *n = &BoltContactSetNormals(c)[3 * gp];
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt *ii = loc[12 + 3 * a] >= 0 ? &loc[12 + 3 * a] : &loc[3 * a]; /* the pair's DOFs on side b, or a */
      PetscReal       A[3], x[3];
      if (N[a] == 0 || ii[0] < 0) continue;
      for (PetscInt k = 0; k < 3; k++) A[k] = BoltContactSetNodalArea(c)[ii[k]];
      x[0] = A[1] * n[2] - A[2] * n[1]; /* A x n */
      x[1] = A[2] * n[0] - A[0] * n[2];
      x[2] = A[0] * n[1] - A[1] * n[0];
      if (PetscSqrtReal(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-12 * PetscSqrtReal(A[0] * A[0] + A[1] * A[1] + A[2] * A[2])) flat = PETSC_FALSE;
    }
  }
  PetscCall(MPIU_Allreduce(&flat, &rom->flat, 1, MPIU_BOOL, MPI_LAND, rom->comm));
  /* friction reads the tangential gaps too (the augmented ROM takes u_c = V_c q instead) */
  rom->wholeRows = (PetscBool)(!rom->flat || BoltContactSetHasFriction(c));
  width          = rom->wholeRows ? 3 : 1;
  /* each point's gap is its own node pair's: the pairs' owners make them (ROMSetUpPairForces) */
  rom->pairGaps = (PetscBool)(rom->wholeRows && BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL && !rom->augment);
  if (rom->pairGaps) {
    rom->nGapRows = rom->nLiveRows = 0;
    rom->heldRowsDone = PETSC_FALSE;
    PetscCall(PetscMalloc2(1, &rom->Rn, 1, &rom->gnRow));
    PetscCall(PetscFree4(first, next, rowGp, rowNode));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < nloc; i++) first[i] = -1;
  rom->nGapRows = 0;
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscInt  *loc = &BoltContactSetElementLocal(c)[24 * (gp / 4)];
    const PetscReal *N = &BoltContactSetShapeValues(c)[4 * gp];
    PetscReal        n[3];
    ROMRowNormal(&BoltContactSetNormals(c)[3 * gp], n);
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt slot = loc[12 + 3 * a] >= 0 ? loc[12 + 3 * a] : loc[3 * a]; /* the pair's first DOF on side b, or a */
      PetscInt       r;
      rom->gpRows[4 * gp + a] = -1;
      PetscCheck(BoltContactSetQuadrature(c) != BOLT_QUADRATURE_NODAL || N[a] == (a == gp % 4 ? 1.0 : 0.0), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Nodal quadrature: point %" PetscInt_FMT " is not at its own node", gp);
      if (N[a] == 0 || slot < 0) continue; /* no weight, or both sides clamped: no gap */
      for (r = first[slot]; r >= 0; r = next[r]) {
        PetscReal m[3];
        ROMRowNormal(&BoltContactSetNormals(c)[3 * rowGp[r]], m);
        if (rom->wholeRows || (m[0] == n[0] && m[1] == n[1] && m[2] == n[2])) break;
      }
      if (r < 0) {
        r = rom->nGapRows;
        rom->nGapRows += width;
        next[r]     = first[slot];
        first[slot] = r;
        rowGp[r]    = gp;
        rowNode[r]  = a;
      }
      rom->gpRows[4 * gp + a] = r;
    }
  }
  /* the rows of node pairs with a point that may change first (live), then the held ones */
  PetscCall(PetscCalloc2(rom->nGapRows + 1, &live, rom->nGapRows + 1, &pos));
  for (PetscInt gp = 0; gp < ngp; gp++)
    for (PetscInt a = 0; a < 4; a++)
      if (rom->gpRows[4 * gp + a] >= 0 && (!mayChange || mayChange[gp])) live[rom->gpRows[4 * gp + a]] = PETSC_TRUE;
  rom->nLiveRows = 0;
  for (PetscInt pass = 0, k = 0; pass < 2; pass++)
    for (PetscInt r = 0; r < rom->nGapRows; r += width) {
      if (live[r] != (pass == 0)) continue;
      pos[r] = k;
      k += width;
      if (!pass) rom->nLiveRows = k;
    }
  for (PetscInt i = 0; i < 4 * ngp; i++)
    if (rom->gpRows[i] >= 0) rom->gpRows[i] = pos[rom->gpRows[i]];
  rom->heldRowsDone = PETSC_FALSE;
  /* |n' D x - nr' D x| and the two sums' rounding stay below 1e-12 sum_jk |D_kj| |x|_max (n up to
     a few thousand); 1e-9 leaves room */
  for (PetscInt gp = 0; gp < ngp; gp++) {
    const PetscReal *D = &rom->De[12 * n * (gp / 4) + 3 * (gp % 4)];
    PetscReal        b = 0;
    for (PetscInt j = 0; j < n; j++) b += PetscAbsReal(D[12 * j]) + PetscAbsReal(D[12 * j + 1]) + PetscAbsReal(D[12 * j + 2]);
    rom->wholeGapBound[gp] = 1e-9 * b;
  }
  PetscCall(PetscMalloc2(rom->nGapRows * n + 1, &rom->Rn, rom->nGapRows + 1, &rom->gnRow));
  PetscCall(PetscFree3(rom->keptLo, rom->keptHi, rom->keptCoef));
  PetscCall(PetscMalloc3(rom->nGapRows + 1, &rom->keptLo, rom->nGapRows + 1, &rom->keptHi, rom->nGapRows + 1, &rom->keptCoef));
  rom->keptValid = PETSC_FALSE;
  for (PetscInt i = 0; i < nloc; i++)
    for (PetscInt r = first[i]; r >= 0; r = next[r]) {
      const PetscReal *D = &rom->De[12 * n * (rowGp[r] / 4) + 3 * rowNode[r]];
      PetscReal        nr[3];
      ROMRowNormal(&BoltContactSetNormals(c)[3 * rowGp[r]], nr);
      for (PetscInt j = 0; j < n; j++) {
        if (!rom->wholeRows) rom->Rn[pos[r] + rom->nGapRows * j] = nr[0] * D[12 * j] + nr[1] * D[12 * j + 1] + nr[2] * D[12 * j + 2];
        else
          for (PetscInt k = 0; k < 3; k++) rom->Rn[pos[r] + k + rom->nGapRows * j] = D[12 * j + k];
      }
    }
  PetscCall(PetscFree4(first, next, rowGp, rowNode));
  PetscCall(PetscFree2(live, pos));
  PetscFunctionReturn(0);
}
