/* Diagnostics of the dual contact loop (-contact_monitor): which points open and close in each
   outer iteration, where, and the tension the multipliers carry before the active set is
   updated. They print; they change nothing. */
#include "private/solve.h"

/* Diagnostics of one outer iteration: points opened / closed per pair, the distance from the
   pair's centroid (the bolt axis for the joint) of the points that changed, and the largest
   distance of an active point (the edge of the contact zone). */
PetscErrorCode BoltContactMonitorOuter(BoltDual *d, PetscInt outer, PetscInt inner, PetscInt nchanged, PetscBool cycling)
{
  BoltContactState *s = d->op->state;
  BoltContactSet   *c = BoltContactStateSet(s);
  const PetscInt  ne = BoltContactSetElementCount(c);
  const PetscInt    P = BOLTROM_MAX_PAIRS;
  PetscInt          cnt[2 * BOLTROM_MAX_PAIRS];
  PetscReal         ctr[3 * BOLTROM_MAX_PAIRS], rmin[BOLTROM_MAX_PAIRS], rmax[2 * BOLTROM_MAX_PAIRS];

  PetscFunctionBeginUser;
  for (PetscInt p = 0; p < 2 * P; p++) {
    cnt[p]  = 0;
    rmax[p] = 0;
  }
  for (PetscInt p = 0; p < P; p++) rmin[p] = PETSC_MAX_REAL;
  for (PetscInt p = 0; p < 3 * P; p++) ctr[p] = 0;
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt q = 0; q < 4; q++)
      for (PetscInt a = 0; a < 4; a++)
        for (PetscInt d = 0; d < 3; d++) ctr[3 * BoltContactSetElementPair(c, e) + d] += BoltContactSetWeights(c)[4 * e + q] * BoltContactSetShapeValues(c)[16 * e + 4 * q + a] * BoltContactSetElementCoordinates(c, e)[3 * a + d] / BoltContactSetPairArea(c, BoltContactSetElementPair(c, e));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ctr, 3 * P, MPIU_REAL, MPI_SUM, d->op->comm));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt  gp = 4 * e + q, p = BoltContactSetElementPair(c, e);
      PetscReal x[3] = {0, 0, 0}, r;
      for (PetscInt a = 0; a < 4; a++)
        for (PetscInt d = 0; d < 3; d++) x[d] += BoltContactSetShapeValues(c)[16 * e + 4 * q + a] * BoltContactSetElementCoordinates(c, e)[3 * a + d];
      r = PetscSqrtReal(PetscSqr(x[0] - ctr[3 * p]) + PetscSqr(x[1] - ctr[3 * p + 1]));
      if (BoltContactStateActive(s)[gp]) rmax[P + p] = PetscMax(rmax[P + p], r);
      if (BoltContactStateActive(s)[gp] == BoltContactStateActiveOld(s)[gp]) continue;
      cnt[2 * p + (BoltContactStateActive(s)[gp] ? 1 : 0)]++;
      rmin[p] = PetscMin(rmin[p], r);
      rmax[p] = PetscMax(rmax[p], r);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2 * P, MPIU_INT, MPI_SUM, d->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rmin, P, MPIU_REAL, MPI_MIN, d->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rmax, 2 * P, MPIU_REAL, MPI_MAX, d->op->comm));
  char fric[40] = "";
  if (BoltContactStateHasFriction(s)) PetscCall(PetscSNPrintf(fric, sizeof(fric), " friction %.3e", (double)BoltContactStateFrictionChange(s)));
  PetscCall(PetscPrintf(d->op->comm, "  %s step %" PetscInt_FMT " outer %3" PetscInt_FMT ": inner %4" PetscInt_FMT " change %.3e pen %.3e%s | changed %" PetscInt_FMT " active %" PetscInt_FMT "%s |", d->op->name, d->step, outer, inner, (double)d->lastChange, (double)d->lastPenetration, fric, nchanged, BoltContactStateActiveCount(s), cycling ? " CYCLING" : ""));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++)
    if (cnt[2 * p] || cnt[2 * p + 1]) PetscCall(PetscPrintf(d->op->comm, " %s -%" PetscInt_FMT " +%" PetscInt_FMT " at r %.2f..%.2f mm, active to %.2f mm;", BoltContactSetPairName(c, p), cnt[2 * p], cnt[2 * p + 1], (double)(1e3 * rmin[p]), (double)(1e3 * rmax[p]), (double)(1e3 * rmax[P + p])));
  PetscCall(PetscPrintf(d->op->comm, "\n"));
  PetscFunctionReturn(0);
}

/* Diagnostics before an active-set update: the active points whose multiplier is tensile beyond
   the band (they are about to open), and for them the normal traction smoothed through the
   nodes (nodal normal force / nodal area, interpolated back to the Gauss point): a multiplier
   that exerts a tensile force shows it in both, a spurious one in the first only. */
PetscErrorCode BoltContactMonitorTension(BoltDual *d)
{
  BoltContactState *s = d->op->state;
  BoltContactSet   *c = BoltContactStateSet(s);
  const PetscInt  ne = BoltContactSetElementCount(c);
  PetscInt          cnt[2] = {0, 0};
  PetscReal        *ts, mx[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, mn = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(4 * ne + 1, &ts));
  PetscCall(BoltContactSetSmoothedNormalTraction(c, BoltContactStateWork(s), BoltContactStateLambda(s), ts));
  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal band = BoltContactStateBandTraction(s, BoltContactSetElementPair(c, e));
    for (PetscInt q = 0; q < 4; q++) {
      PetscInt         gp = 4 * e + q;
      const PetscReal *n = &BoltContactSetNormals(c)[3 * gp], *l = &BoltContactStateLambda(s)[3 * gp];
      PetscReal        ln = l[0] * n[0] + l[1] * n[1] + l[2] * n[2], ps = ts[gp];
      if (!BoltContactStateActive(s)[gp]) continue;
      mx[2] = PetscMax(mx[2], ps);
      if (ln < band) continue;
      cnt[0]++;
      if (ps < 0) cnt[1]++;
      mx[0] = PetscMax(mx[0], ln);
      mx[1] = PetscMax(mx[1], ps);
      mn    = PetscMin(mn, ps);
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, d->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mx, 3, MPIU_REAL, MPI_MAX, d->op->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &mn, 1, MPIU_REAL, MPI_MIN, d->op->comm));
  PetscCall(PetscPrintf(d->op->comm, "    tension: %" PetscInt_FMT " active points with lambda_n >= band (max %.3e Pa); their nodal-smoothed traction %.3e..%.3e Pa, compressive at %" PetscInt_FMT "; max smoothed over the active set %.3e Pa\n", cnt[0], (double)mx[0], (double)mn, (double)mx[1], cnt[1], (double)mx[2]));
  PetscCall(PetscFree(ts));
  PetscFunctionReturn(0);
}
