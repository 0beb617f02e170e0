#ifndef BOLTROM_KRYLOV_H
#define BOLTROM_KRYLOV_H
/* Block second-order Krylov subspace (SOAR) of M q'' + C q' + K q = B u about a real shift s0:
   G_m = span{r_0, ..., r_{m-1}}, r_0 = -Kt^{-1} B, r_1 = P r_0, r_l = P r_{l-1} + Q r_{l-2},
   P = -Kt^{-1} Ct, Q = -Kt^{-1} M, Kt = K + s0 C + s0^2 M, Ct = C + 2 s0 M.
   A Galerkin projection onto G_m matches the first m moments of the transfer function at s0. */
#include <slepcbv.h>

#define BOLTKRYLOV_MAX_ORDER 8

typedef struct {
  MPI_Comm  comm;
  PetscInt  order;                              /* -krylov_order, default 1, 1..8: number of blocks r_0..r_{m-1} */
  PetscReal s0;                                 /* -krylov_s0, real expansion point [rad/s], default 2*pi*100 */
  PetscInt  blockSize;                          /* -krylov_block_size, default 64: right-hand sides per MatMatSolve */
  PetscReal deflationTol;                       /* -krylov_deflation_tol, default 1e-10: relative norm below which a new column is dropped */
  PetscInt  rankPerOrder[BOLTKRYLOV_MAX_ORDER]; /* columns kept from each block after deflation */
  PetscInt  rank;                               /* final dimension of V */
  PetscReal tFactor, tSolve, tOrth;             /* seconds */
  PetscInt  nsolves;                            /* right-hand sides solved with the factored Kt */
  /* Optional replacement of the Kt solve (e.g. the interface-reduced, bordered solve): Sol(:, 0:nc)
     = Kt^{-1} Rhs(:, 0:nc) in the caller's sense. When set, Kt is neither formed nor factored. */
  PetscErrorCode (*solve)(void *, BV, BV, PetscInt);
  void     *solveCtx;
} BoltKrylov;

PetscErrorCode BoltKrylovCreate(MPI_Comm, BoltKrylov **);
PetscErrorCode BoltKrylovSetFromOptions(BoltKrylov *);
PetscErrorCode BoltKrylovBuild(BoltKrylov *, Mat M, Mat C, Mat K, BV B, BV *V);
PetscErrorCode BoltKrylovView(BoltKrylov *, PetscViewer);
PetscErrorCode BoltKrylovDestroy(BoltKrylov **);
#endif
