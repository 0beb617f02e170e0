/* Rows of the basis times reduced coordinates, each row summed in one fixed order, and the node
   pairs of a list of contact points: the pieces the reduced operator's files share. */
#include "private/rom.h"
#include <petscblaslapack.h>

/* u = A x for a column-major m x n block A (leading dimension lda) of rows of the basis. Each row
   is summed in the same order whatever its position in the block (a BLAS kernel may treat the
   rows of a vector block and of its tail differently), so a row gets the same bits on any
   partition. Where the CPU has AVX2 a clone with four rows per vector runs instead: the same
   products and sums per row (the file is compiled without contraction into FMAs), so the same
   bits. */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void ROMRowsTimes(PetscInt m, PetscInt n, const PetscScalar *A, PetscInt lda, const PetscScalar *x, PetscScalar *u)
{
  for (PetscInt i = 0; i < m; i++) u[i] = 0;
  for (PetscInt j = 0; j < n; j += 4) { /* four columns per pass over u, still in order j */
    const PetscInt     nb = PetscMin(4, n - j);
    const PetscScalar *restrict c0 = A + lda * j, x0 = x[j];
    PetscScalar *restrict       uu = u;
    if (nb == 4) {
      const PetscScalar *restrict c1 = c0 + lda, *restrict c2 = c1 + lda, *restrict c3 = c2 + lda, x1 = x[j + 1], x2 = x[j + 2], x3 = x[j + 3];
      for (PetscInt i = 0; i < m; i++) uu[i] = uu[i] + c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
    } else
      for (PetscInt k = 0; k < nb; k++)
        for (PetscInt i = 0; i < m; i++) uu[i] += c0[i + lda * k] * x[j + k];
  }
}

static int ROMPointByPairThenName(const void *x, const void *y)
{
  const ROMPointRecord *a = (const ROMPointRecord *)x, *b = (const ROMPointRecord *)y;
  if (a->dofB != b->dofB) return a->dofB < b->dofB ? -1 : 1;
  if (a->dofA != b->dofA) return a->dofA < b->dofA ? -1 : 1;
  return a->name < b->name ? -1 : (a->name > b->name ? 1 : 0);
}

static int ROMPointByName(const void *x, const void *y)
{
  const ROMPointRecord *a = (const ROMPointRecord *)x, *b = (const ROMPointRecord *)y;
  return a->name < b->name ? -1 : (a->name > b->name ? 1 : 0);
}

/* The node pairs of nrec point records: rec sorted by pair, then name; first[k] the first point of
   pair k, its pos where the pair's points start in rec, the pairs in the order of those points'
   names. The global DOFs group the points on any partition; only the names order them. Returns
   the number of pairs. */
PetscInt ROMNodePairs(PetscInt nrec, ROMPointRecord rec[], ROMPointRecord first[])
{
  PetscInt npair = 0;

  qsort(rec, (size_t)nrec, sizeof(ROMPointRecord), ROMPointByPairThenName);
  for (PetscInt i = 0; i < nrec; i++) {
    if (i > 0 && rec[i].dofB == rec[i - 1].dofB && rec[i].dofA == rec[i - 1].dofA) continue;
    first[npair]     = rec[i];
    first[npair].pos = i;
    npair++;
  }
  qsort(first, (size_t)npair, sizeof(ROMPointRecord), ROMPointByName);
  return npair;
}
