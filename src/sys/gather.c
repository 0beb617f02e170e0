/* Records of every rank gathered on every rank in rank order: the counts first, then one
   MPI_Allgatherv. The contact set (nodes, node pairs) and the ROM's K_cr updates use it; and the
   grow-only scratch arrays such gathers and their callers keep between calls. */
#include "boltrom.h"

/* Gathers n items of type from each rank. *(void **)recv is made to hold all of them (plus one,
   so that zero items still give a buffer): freshly allocated when alloc is NULL, otherwise
   grown only when *alloc items are too few (the caller keeps it between calls). Returns the
   number of items in *total and, if mine is not NULL, the position of this rank's first. */
PetscErrorCode BoltGatherAll(MPI_Comm comm, MPI_Datatype type, const void *send, PetscInt n, void *recv, PetscInt *alloc, PetscInt *total, PetscInt *mine)
{
  PetscMPIInt size, rank, len, *counts, *displs, tsize;
  PetscInt    sum = 0;
  void      **buf = (void **)recv;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Type_size(type, &tsize));
  PetscCall(PetscMPIIntCast(n, &len));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  PetscCallMPI(MPI_Allgather(&len, 1, MPI_INT, counts, 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    PetscCall(PetscMPIIntCast(sum, &displs[r]));
    sum += counts[r];
  }
  if (!alloc || *alloc < sum + 1) {
    if (alloc) {
      PetscCall(PetscFree(*buf));
      *alloc = PetscMax(sum + 1, 2 * *alloc);
    }
    PetscCall(PetscMalloc((size_t)tsize * (size_t)(alloc ? *alloc : sum + 1), buf));
  }
  PetscCallMPI(MPI_Allgatherv(send, len, type, *buf, counts, displs, type, comm));
  *total = sum;
  if (mine) *mine = displs[rank];
  PetscCall(PetscFree2(counts, displs));
  PetscFunctionReturn(0);
}

/* A scratch array kept between calls: *a holds at least need values afterwards, reallocated (to
   twice its size or need, whichever is more; the contents are not kept) only when too small. */
PetscErrorCode BoltGrowReal(PetscReal **a, PetscInt *alloc, PetscInt need)
{
  PetscFunctionBeginUser;
  if (need <= *alloc) PetscFunctionReturn(0);
  PetscCall(PetscFree(*a));
  *alloc = PetscMax(need, 2 * *alloc);
  PetscCall(PetscMalloc1(*alloc, a));
  PetscFunctionReturn(0);
}
