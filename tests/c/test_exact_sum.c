static char help[] = "Verification of BoltExactSum (src/sys/exact_sum.c) against exact integer arithmetic.\n"
                     "Five columns of 4000 dyadic terms (integers times 2^-72, below 1 in magnitude), built to\n"
                     "cancel: pairs +a, -a of every magnitude from 2^-72 to 1, pairs that cancel all but a few\n"
                     "low bits, small terms, and two sums that fall exactly halfway between two doubles; each\n"
                     "column shuffled. The exact sum of each column is an __int128 count of 2^-72, rounded to the\n"
                     "nearest double (ties to even) here. Every order and split over the ranks must give that\n"
                     "double bit for bit; the plain double sum of the same terms must not.\n"
                     "Prints PASS/FAIL name value per check, SUM column hex (the split sums) and INFO lines;\n"
                     "-terms FILE writes the terms (one row a line, hex) for an outside reference. Exits\n"
                     "non-zero if any check fails.\n";

#include <boltrom.h>
#include <stdint.h>

#define NC   5    /* columns: sums taken together */
#define NT   4000 /* terms per column (over all ranks) */
#define UEXP -72  /* every term is a multiple of 2^UEXP */

/* The accuracy BoltExactSum documents (src/sys/exact_sum.c): about 106 - 2 log2(2 N) bits of the
   bound, 80 bits for N = 4000 terms bounded by 1; terms on a grid 8 bits coarser (2^-72) are
   therefore summed without error, and the one rounding left is the final one to a double. */

static uint64_t state = 0x2545F4914F6CDD1DULL;
static uint64_t Next(void) /* splitmix64 */
{
  uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z          = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z          = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}
static int Uniform(int lo, int hi) { return lo + (int)(Next() % (uint64_t)(hi - lo + 1)); }

/* A random term of magnitude in [2^t, 2^(t+1)), as many significant bits as the grid allows (at
   most 53), random sign */
static double Random(int t)
{
  int      bits = PetscMin(53, t - UEXP + 1);
  uint64_t m    = (Next() >> (64 - bits)) | ((uint64_t)1 << (bits - 1));
  double   x    = ldexp((double)m, t - bits + 1);
  return (Next() & 1) ? -x : x;
}

/* x as a count of 2^UEXP (exact); *off set if x is not on that grid */
static __int128 Units(double x, PetscBool *off)
{
  int     e;
  int64_t m;
  if (x == 0) return 0;
  m = (int64_t)ldexp(frexp(x, &e), 53); /* x = m 2^(e-53) exactly */
  e = e - 53 - UEXP;
  if (e >= 0) return (__int128)m * ((__int128)1 << e);
  if (m % ((int64_t)1 << -e)) *off = PETSC_TRUE;
  return (__int128)(m / ((int64_t)1 << -e));
}

/* v 2^UEXP rounded to the nearest double, ties to the even one */
static double Round(__int128 v)
{
  unsigned __int128 a = v < 0 ? -(unsigned __int128)v : (unsigned __int128)v;
  int               len = 0, e = UEXP;
  for (unsigned __int128 t = a; t; t >>= 1) len++;
  if (len > 53) {
    int               sh = len - 53;
    unsigned __int128 q = a >> sh, rem = a - (q << sh), half = (unsigned __int128)1 << (sh - 1);
    if (rem > half || (rem == half && (q & 1))) q++;
    a = q;
    e += sh;
  }
  return (v < 0 ? -1.0 : 1.0) * ldexp((double)(uint64_t)a, e);
}

static double T[NC][NT];

/* Column c: the terms, then a shuffle. The exact sums are 0 (column 0), that of the residues of
   near pairs and small terms (1), 2^-10 + 2^-63 (2: a tie, to the even 2^-10), 2^-10 + 2^-62 +
   2^-63 (3: a tie, to the even 2^-10 + 2^-61), a small negative one (4). */
static void Build(int c)
{
  int k = 0, pairs = c == 0 ? 2000 : c == 1 ? 1500 : c == 2 ? 1999 : c == 3 ? 1998 : 1800;
  for (int p = 0; p < pairs; p++) { /* +a, -a: any magnitude the grid holds */
    double a = Random(Uniform(UEXP, -1));
    T[c][k++] = a;
    T[c][k++] = -a;
  }
  if (c == 1 || c == 4) { /* b and -c, c = b without its last 1..30 (col 1) or 1..8 (col 4) bits */
    for (int p = 0; p < (c == 1 ? 400 : 200); p++) {
      double b = PetscAbsReal(Random(Uniform(-20, -1))), r;
      int    e, cut = Uniform(1, c == 1 ? 30 : 8);
      (void)frexp(b, &e);
      r = ldexp(floor(ldexp(b, 53 - e - cut)), e + cut - 53); /* b without its last cut bits */
      T[c][k++] = c == 1 ? b : -b;
      T[c][k++] = c == 1 ? -r : r;
    }
  }
  if (c == 1)
    for (int p = 0; p < 200; p++) T[c][k++] = Random(Uniform(UEXP, -40));
  if (c == 2) {
    T[c][k++] = 0x1p-10;
    T[c][k++] = 0x1p-63;
  }
  if (c == 3) {
    T[c][k++] = 0x1p-10;
    T[c][k++] = 0x1p-62;
    T[c][k++] = 0x1p-64;
    T[c][k++] = 0x1p-64;
  }
  for (int i = NT - 1; i > 0; i--) { /* Fisher-Yates */
    int    j = (int)(Next() % (uint64_t)(i + 1));
    double t = T[c][i];
    T[c][i]  = T[c][j];
    T[c][j]  = t;
  }
}

static int ByMagnitude(const void *a, const void *b)
{
  double x = PetscAbsReal(*(const double *)a), y = PetscAbsReal(*(const double *)b);
  return (x > y) - (x < y);
}

/* the same bits (0 and -0 told apart) */
static PetscBool Same(const double a[], const double b[])
{
  for (int c = 0; c < NC; c++)
    if (memcmp(&a[c], &b[c], sizeof(double))) return PETSC_FALSE;
  return PETSC_TRUE;
}

static PetscInt nfail = 0;
static PetscErrorCode Check(PetscBool ok, const char name[], double value)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s %.6e\n", ok ? "PASS" : "FAIL", name, value));
  if (!ok) nfail++;
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscMPIInt   rank, size;
  BoltExactSum *sum;
  double        bound = 0, exact[NC], got[NC], x[NC], (*S)[NT];
  __int128      units[NC] = {0};
  PetscBool     off = PETSC_FALSE, write;
  char          file[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-terms", file, sizeof(file), &write));
  PetscCall(BoltExactSumCreate(&sum));
  for (int c = 0; c < NC; c++) Build(c); /* every rank builds every term */
  for (int c = 0; c < NC; c++)
    for (int i = 0; i < NT; i++) {
      units[c] += Units(T[c][i], &off);
      bound = PetscMax(bound, PetscAbsReal(T[c][i]));
    }
  for (int c = 0; c < NC; c++) exact[c] = Round(units[c]);
  PetscCall(Check((PetscBool)(!off && bound < 1), "terms_on_the_grid_below_one", bound));
  /* the sums the columns were built to have (the integer reference checked by construction) */
  PetscCall(Check((PetscBool)(units[0] == 0 && exact[2] == 0x1p-10 && exact[3] == 0x1p-10 + 0x1p-61 && exact[4] < 0 && exact[1] != 0), "exact_sums_as_built", (double)exact[2]));
  if (write && rank == 0) {
    FILE *fp = fopen(file, "w");
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", file);
    for (int i = 0; i < NT; i++) {
      for (int c = 0; c < NC; c++) fprintf(fp, "%a%s", T[c][i], c + 1 < NC ? " " : "\n");
    }
    fclose(fp);
  }
  for (int c = 0; c < NC; c++) {
    char line[128];
    PetscCall(PetscSNPrintf(line, sizeof(line), "INFO exact %d %a (%.17g)\n", c, exact[c], exact[c]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s", line));
  }

  /* the plain double sum in the shuffled order: wrong in every column, and in those with a
     nonzero sum by 0.35 of it at worst (column 4; asserted above 0.1) */
  {
    double worst = 0;
    int    wrong = 0;
    for (int c = 0; c < NC; c++) {
      double plain = 0, rel;
      for (int i = 0; i < NT; i++) plain += T[c][i];
      wrong += plain != exact[c];
      rel = exact[c] != 0 ? PetscAbsReal(plain - exact[c]) / PetscAbsReal(exact[c]) : 0;
      worst = PetscMax(worst, rel);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "INFO plain %d %a error %.3e relative %.3e\n", c, plain, PetscAbsReal(plain - exact[c]), rel));
    }
    PetscCall(Check((PetscBool)(wrong == NC), "plain_double_sum_wrong_in_every_column", (double)wrong));
    PetscCall(Check((PetscBool)(worst > 0.1), "plain_double_sum_worst_relative_error", worst));
  }

  /* one rank, shuffled order */
  PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
  for (int i = 0; i < NT; i++) {
    for (int c = 0; c < NC; c++) x[c] = T[c][i];
    BoltExactSumAdd(sum, x);
  }
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_SELF, got));
  PetscCall(Check(Same(got, exact), "one_rank_shuffled_is_the_rounded_exact_sum", 0));
  /* one rank, reverse order */
  PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
  for (int i = NT - 1; i >= 0; i--) {
    for (int c = 0; c < NC; c++) x[c] = T[c][i];
    BoltExactSumAdd(sum, x);
  }
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_SELF, got));
  PetscCall(Check(Same(got, exact), "one_rank_reversed_is_the_rounded_exact_sum", 0));
  /* round-robin over the ranks, each in reverse order */
  PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
  for (int i = NT - 1; i >= 0; i--) {
    if (i % size != rank) continue;
    for (int c = 0; c < NC; c++) x[c] = T[c][i];
    BoltExactSumAdd(sum, x);
  }
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, got));
  PetscCall(Check(Same(got, exact), "round_robin_over_ranks_is_the_rounded_exact_sum", (double)size));
  for (int c = 0; c < NC; c++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "SUM %d %a\n", c, got[c]));
  /* sorted by magnitude, contiguous blocks over the ranks; a rank's partials kept half-way
     (GetPartials), the sum begun afresh and the partials put back (SetPartials) */
  PetscCall(PetscMalloc1(NC, &S));
  for (int c = 0; c < NC; c++) {
    PetscCall(PetscArraycpy(S[c], T[c], NT));
    qsort(S[c], NT, sizeof(double), ByMagnitude);
  }
  {
    int    lo = (int)((long)NT * rank / size), hi = (int)((long)NT * (rank + 1) / size), mid = (lo + hi) / 2;
    double kept[2 * NC];
    PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
    for (int i = lo; i < hi; i++) {
      if (i == mid) {
        PetscCall(BoltExactSumGetPartials(sum, kept));
        PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
        PetscCall(BoltExactSumSetPartials(sum, kept));
      }
      for (int c = 0; c < NC; c++) x[c] = S[c][i];
      BoltExactSumAdd(sum, x);
    }
    PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, got));
    PetscCall(Check(Same(got, exact), "sorted_blocks_over_ranks_kept_partials_is_the_rounded_exact_sum", (double)size));
  }
  PetscCall(PetscFree(S));

  /* terms replaced in place (AddParts, then ReplaceParts of every third term by its negative, on
     its rank): the rounded exact sum of the new terms */
  {
    PetscReal *parts, fresh[NC];
    __int128   newUnits[NC];
    PetscCall(PetscMalloc1(2 * NC * NT, &parts));
    PetscCall(BoltExactSumBegin(sum, NC, bound, NT));
    for (int i = 0; i < NT; i++) {
      if (i % size != rank) continue;
      for (int c = 0; c < NC; c++) x[c] = T[c][i];
      BoltExactSumAddParts(sum, x, &parts[2 * NC * i], &parts[2 * NC * i + NC]);
    }
    for (int i = NT - 1; i >= 0; i--) {
      if (i % size != rank || i % 3) continue;
      for (int c = 0; c < NC; c++) x[c] = -T[c][i];
      BoltExactSumReplaceParts(sum, x, &parts[2 * NC * i], &parts[2 * NC * i + NC]);
    }
    PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, got));
    for (int c = 0; c < NC; c++) {
      newUnits[c] = 0;
      for (int i = 0; i < NT; i++) newUnits[c] += Units(i % 3 ? T[c][i] : -T[c][i], &off);
      fresh[c] = Round(newUnits[c]);
    }
    PetscCall(Check((PetscBool)(Same(got, fresh) && !Same(got, exact)), "replaced_terms_are_the_rounded_exact_sum_of_the_new", 0));
    PetscCall(PetscFree(parts));
  }
  /* a zero bound (no terms) gives zero sums */
  PetscCall(BoltExactSumBegin(sum, NC, 0.0, NT));
  PetscCall(BoltExactSumEnd(sum, PETSC_COMM_WORLD, got));
  PetscCall(Check((PetscBool)(got[0] == 0 && got[NC - 1] == 0), "zero_bound", got[0]));
  PetscCall(BoltExactSumDestroy(&sum));
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
