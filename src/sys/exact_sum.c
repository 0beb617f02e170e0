/* Sums over ranks whose result does not depend on the order of the terms or on the ranks that
   hold them. Each term is split on two fixed binary grids, set by a global bound of the terms
   and their global count: on a grid coarse enough that no partial sum needs more than 53 bits,
   every addition is exact, in whatever order, and MPI's sum of the ranks' partials is exact too.
   The first grid keeps about 53 - log2(2 N) leading bits of a term, the second as many again,
   so the result is accurate to some 80 bits of the bound: more than a plain double sum, and the
   same bits on any partition. The reduced model needs it: its effective matrix, under a
   near-hard contact penalty, lifts the last bit of a reduced force to 1e-7 of the response. */
#include "private/sys.h"

/* Grids for terms bounded by |x| <= bound (global) with at most nterms of them (global). */
PetscErrorCode BoltExactSumBegin(BoltExactSum *s, PetscInt n, PetscReal bound, PetscInt nterms)
{
  int e1, e2;

  PetscFunctionBeginUser;
  if (n > s->nalloc) {
    PetscCall(PetscFree(s->acc));
    PetscCall(PetscMalloc1(2 * n, &s->acc));
    s->nalloc = n;
  }
  s->n = n;
  PetscCall(PetscArrayzero(s->acc, 2 * n));
  /* sigma1 = 2^e1 >= 2 N bound: a term lands on the multiples of 2^(e1-53), the partial sums
     stay below 2^e1; what is left of a term is below 2^(e1-53), whose grid is sigma2 >= 2 N
     2^(e1-53). A zero bound leaves the grids at zero: every term is then zero. */
  s->sigma[0] = s->sigma[1] = 0;
  if (bound > 0) {
    (void)frexp(2.0 * (double)PetscMax(nterms, 1) * (double)bound, &e1);
    (void)frexp(2.0 * (double)PetscMax(nterms, 1), &e2);
    s->sigma[0] = ldexp(1.0, e1);
    s->sigma[1] = ldexp(1.0, e1 - 53 + e2);
  }
  PetscFunctionReturn(0);
}

/* x split onto the two grids: (sigma + x) - sigma rounds x to the grid of sigma, and x minus
   that is exact. Must not be compiled with -ffast-math. */
static inline void BoltExactSumSplit(PetscReal s1, PetscReal s2, PetscReal x, PetscReal *q, PetscReal *r)
{
  *q = (s1 + x) - s1;
  *r = (s2 + (x - *q)) - s2;
}

/* acc += x (n values), each split onto the two grids. */
void BoltExactSumAdd(BoltExactSum *s, const PetscReal x_[])
{
  const PetscReal s1 = s->sigma[0], s2 = s->sigma[1];
  PetscReal *restrict       a1 = s->acc, *restrict a2 = s->acc + s->n;
  const PetscReal *restrict x = x_;

  if (s1 == 0) return;
  for (PetscInt j = 0; j < s->n; j++) {
    PetscReal q, r;
    BoltExactSumSplit(s1, s2, x[j], &q, &r);
    a1[j] += q;
    a2[j] += r;
  }
}

/* As BoltExactSumAdd, keeping the parts x was split into (p1 on the first grid, p2 on the
   second), so that BoltExactSumReplaceParts can take the same term out again exactly. */
void BoltExactSumAddParts(BoltExactSum *s, const PetscReal x_[], PetscReal p1_[], PetscReal p2_[])
{
  const PetscReal s1 = s->sigma[0], s2 = s->sigma[1];
  PetscReal *restrict       a1 = s->acc, *restrict a2 = s->acc + s->n, *restrict p1 = p1_, *restrict p2 = p2_;
  const PetscReal *restrict x = x_;

  for (PetscInt j = 0; j < s->n; j++) {
    PetscReal q = 0, r = 0; /* a zero grid: every term is zero */
    if (s1 != 0) BoltExactSumSplit(s1, s2, x[j], &q, &r);
    a1[j] += q;
    a2[j] += r;
    p1[j] = q;
    p2[j] = r;
  }
}

/* A term added by BoltExactSumAddParts replaced by x: its old parts p1, p2 taken out and x's
   added (and kept in p1, p2) in one pass. Every operation is exact on the grids, so the sums are
   those of the current terms added afresh. */
void BoltExactSumReplaceParts(BoltExactSum *s, const PetscReal x_[], PetscReal p1_[], PetscReal p2_[])
{
  const PetscReal s1 = s->sigma[0], s2 = s->sigma[1];
  PetscReal *restrict       a1 = s->acc, *restrict a2 = s->acc + s->n, *restrict p1 = p1_, *restrict p2 = p2_;
  const PetscReal *restrict x = x_;

  for (PetscInt j = 0; j < s->n; j++) {
    PetscReal q = 0, r = 0;
    if (s1 != 0) BoltExactSumSplit(s1, s2, x[j], &q, &r);
    a1[j] = (a1[j] - p1[j]) + q;
    a2[j] = (a2[j] - p2[j]) + r;
    p1[j] = q;
    p2[j] = r;
  }
}

/* out = the sums over all ranks (collective). */
PetscErrorCode BoltExactSumEnd(BoltExactSum *s, MPI_Comm comm, PetscReal out[])
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, s->acc, (PetscMPIInt)(2 * s->n), MPIU_REAL, MPI_SUM, comm));
  for (PetscInt j = 0; j < s->n; j++) out[j] = s->acc[j] + s->acc[s->n + j];
  PetscFunctionReturn(0);
}

/* This rank's exact partial sums (2 n: the two grids'), to keep them between sums that change a
   few terms (Set puts kept ones back after Begin). */
PetscErrorCode BoltExactSumGetPartials(BoltExactSum *s, PetscReal acc[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(acc, s->acc, 2 * s->n));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltExactSumSetPartials(BoltExactSum *s, const PetscReal acc[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(s->acc, acc, 2 * s->n));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltExactSumCreate(BoltExactSum **s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(s));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltExactSumDestroy(BoltExactSum **s)
{
  PetscFunctionBeginUser;
  if (!*s) PetscFunctionReturn(0);
  PetscCall(PetscFree((*s)->acc));
  PetscCall(PetscFree(*s));
  PetscFunctionReturn(0);
}
