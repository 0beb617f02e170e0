static char help[] = "Verification of BoltExactSum (src/sys/exact_sum.c): sums of terms of mixed signs and\n"
                     "magnitudes, with heavy cancellation, split over the ranks in a round-robin and summed\n"
                     "in reverse order, must give the same bits as one rank summing them all in order, and\n"
                     "be correctly rounded up to 1e-20 of the terms' bound (the plain double sum's error is printed).\n"
                     "Prints PASS/FAIL name value per check; exits non-zero if any check fails.\n";

#include <boltrom.h>

/* The terms: x_i,j = a smooth signed pattern times 10^(-8..8), plus pairs that cancel exactly */
static PetscReal Term(PetscInt i, PetscInt j)
{
  PetscReal mag = PetscPowReal(10.0, (PetscReal)((i * 7 + j * 3) % 17) - 8.0);
  PetscReal v   = mag * PetscSinReal(0.37 * (PetscReal)i + 1.3 * (PetscReal)j + 0.1);
  return (i % 2) ? -v * (1 + 1e-12 * j) : v; /* neighbours nearly cancel */
}

int main(int argc, char **argv)
{
  const PetscInt nterms = 4000, n = 5;
  PetscMPIInt    rank, size;
  BoltExactSum  *sum;
  PetscReal      bound = 0, all[5], split[5], x[5];
  PetscInt       nfail = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(BoltExactSumCreate(&sum));
  for (PetscInt i = 0; i < nterms; i++)
    for (PetscInt j = 0; j < n; j++) bound = PetscMax(bound, PetscAbsReal(Term(i, j)));
  /* every term on one rank, in order */
  PetscCall(BoltExactSumBegin(sum, n, bound, nterms));
  for (PetscInt i = 0; i < nterms; i++) {
    for (PetscInt j = 0; j < n; j++) x[j] = Term(i, j);
    BoltExactSumAdd(sum, x);
  }
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_SELF, all));
  /* round-robin over the ranks, each in reverse order */
  PetscCall(BoltExactSumBegin(sum, n, bound, nterms));
  for (PetscInt i = nterms - 1; i >= 0; i--) {
    if (i % size != rank) continue;
    for (PetscInt j = 0; j < n; j++) x[j] = Term(i, j);
    BoltExactSumAdd(sum, x);
  }
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, split));
  {
    PetscReal worst = 0, diff = 0, plainWorst = 0;
    for (PetscInt j = 0; j < n; j++) {
      /* reference: long double, pairs first (each pair is nearly a cancellation) */
      long double ref = 0;
      for (PetscInt i = 0; i < nterms; i += 2) ref += (long double)Term(i, j) + (long double)Term(i + 1, j);
      PetscReal   plain = 0;
      for (PetscInt i = 0; i < nterms; i++) plain += Term(i, j);
      /* the error in units of the result's rounding (half an ulp) plus 1e-20 of the bound */
      worst      = PetscMax(worst, (PetscReal)(fabsl((long double)all[j] - ref) / (fabsl(ref) * 0x1p-53L + 1e-20L * bound)));
      plainWorst = PetscMax(plainWorst, (PetscReal)fabsl((long double)plain - ref) / bound);
      if (split[j] != all[j]) diff = PetscMax(diff, PetscAbsReal(split[j] - all[j]) / bound);
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s same_bits_split_over_%d_ranks %.6e\n", diff == 0 ? "PASS" : "FAIL", size, (double)diff));
    if (diff != 0) nfail++;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s error_over_rounding %.6e\n", worst <= 1 ? "PASS" : "FAIL", (double)worst));
    if (!(worst <= 1)) nfail++;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "INFO plain_double_sum_error_over_bound %.6e\n", (double)plainWorst));
  }
  /* terms replaced in place (BoltExactSumAddParts, then BoltExactSumReplaceParts of every third
     term by the term of i + 1, on its rank): the same bits as summing the new terms afresh */
  {
    PetscReal *parts, fresh[5], replaced[5], diff = 0;
    PetscCall(PetscMalloc1(2 * n * nterms, &parts));
    PetscCall(BoltExactSumBegin(sum, n, bound, nterms));
    for (PetscInt i = 0; i < nterms; i++) {
      if (i % size != rank) continue;
      for (PetscInt j = 0; j < n; j++) x[j] = Term(i, j);
      BoltExactSumAddParts(sum, x, &parts[2 * n * i], &parts[2 * n * i + n]);
    }
    for (PetscInt i = nterms - 1; i >= 0; i--) {
      if (i % size != rank || i % 3 || i + 1 == nterms) continue;
      for (PetscInt j = 0; j < n; j++) x[j] = Term(i + 1, j);
      BoltExactSumReplaceParts(sum, x, &parts[2 * n * i], &parts[2 * n * i + n]);
    }
    PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, replaced));
    PetscCall(BoltExactSumBegin(sum, n, bound, nterms));
    for (PetscInt i = 0; i < nterms; i++) {
      for (PetscInt j = 0; j < n; j++) x[j] = Term(i % 3 || i + 1 == nterms ? i : i + 1, j);
      BoltExactSumAdd(sum, x);
    }
    PetscCall(BoltExactSumEnd(sum, PETSC_COMM_SELF, fresh));
    for (PetscInt j = 0; j < n; j++) diff = PetscMax(diff, PetscAbsReal(replaced[j] - fresh[j]) / bound);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s replaced_terms_same_bits_as_fresh %.6e\n", diff == 0 && replaced[0] != all[0] ? "PASS" : "FAIL", (double)diff));
    if (!(diff == 0 && replaced[0] != all[0])) nfail++;
    PetscCall(PetscFree(parts));
  }
  /* a zero bound (no terms) gives zero sums */
  PetscCall(BoltExactSumBegin(sum, n, 0.0, nterms));
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, split));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s zero_bound %.6e\n", split[0] == 0 && split[n - 1] == 0 ? "PASS" : "FAIL", (double)split[0]));
  if (!(split[0] == 0 && split[n - 1] == 0)) nfail++;
  PetscCall(BoltExactSumDestroy(&sum));
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
