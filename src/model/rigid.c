/* A free-free model (no clamp, no support): its six rigid-body motions, mass-orthonormal (a SLEPc
   BV), the static solve under inertia relief, and what the modal solve deflates. K is singular
   there, so no factorisation of K alone is made: the solves factor K + sigma M, which is regular,
   with sigma = (2 pi x 10 Hz)^2, below the elastic modes of the structures this code is for
   (docs/decisions.md, "Free-free models"), and take the shift out again by refinement. */
#include "private/model.h"
#include <petscblaslapack.h>

typedef struct {
  PetscInt  mode;
  PetscReal center[3];
} RigidCtx;

/* Rigid motion number mode about center: translations along x, y, z (0-2), rotations about them
   (3-5). */
static PetscErrorCode RigidMotion(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  RigidCtx *r = (RigidCtx *)ctx;
  PetscReal y[3];

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; d++) {
    y[d] = X[d] - r->center[d];
    u[d] = 0;
  }
  if (r->mode < 3) u[r->mode] = 1.0;
  else { /* rotation about axis mode-3: omega x y */
    PetscReal w[3] = {0, 0, 0};
    w[r->mode - 3] = 1.0;
    u[0]           = w[1] * y[2] - w[2] * y[1];
    u[1]           = w[2] * y[0] - w[0] * y[2];
    u[2]           = w[0] * y[1] - w[1] * y[0];
  }
  PetscFunctionReturn(0);
}

/* Rigid motion mode (0-5) about center as a vector x of the global layout (held DOFs absent). */
PetscErrorCode BoltMeshRigidMotion(BoltMesh *mesh, PetscInt mode, const PetscReal center[3], Vec x)
{
  RigidCtx rc = {mode, {center[0], center[1], center[2]}};

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(x));
  PetscCall(BoltMeshFillVertexField(mesh, RigidMotion, &rc, x));
  PetscFunctionReturn(0);
}

/* Whether nothing holds the model: no clamp group removed and no support group. */
PetscBool BoltMeshIsFree(const BoltMesh *m)
{
  return (PetscBool)(!m->clamp && !m->supportGroup[0]);
}

static PetscErrorCode Position(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; d++) u[d] = X[d];
  PetscFunctionReturn(0);
}

/* The six rigid motions of a free model, orthonormal in the mass inner product (x' M y); the
   rotations are about the nodes' centroid, which keeps the columns well conditioned. */
PetscErrorCode BoltAssemblerRigidModes(BoltAssembler *asmb, BV *R)
{
  Vec       x;
  PetscReal center[3], norm;
  PetscInt  n;

  PetscFunctionBeginUser;
  PetscCheck(BoltMeshIsFree(asmb->mesh), BoltMeshComm(asmb->mesh), PETSC_ERR_ARG_WRONGSTATE, "Rigid-body modes need a free model (-clamp false, no -support_group)");
  PetscCall(MatCreateVecs(asmb->M, &x, NULL));
  PetscCall(VecZeroEntries(x));
  PetscCall(BoltMeshFillVertexField(asmb->mesh, Position, NULL, x));
  PetscCall(VecGetSize(x, &n));
  for (PetscInt d = 0; d < 3; d++) {
    PetscScalar sum;
    PetscCall(VecStrideSum(x, d, &sum));
    center[d] = PetscRealPart(sum) / (n / 3);
  }
  PetscCall(BVCreate(PetscObjectComm((PetscObject)asmb->M), R));
  PetscCall(BVSetType(*R, BVSVEC));
  PetscCall(BVSetSizesFromVec(*R, x, 6));
  PetscCall(BVSetMatrix(*R, asmb->M, PETSC_FALSE));
  for (PetscInt k = 0; k < 6; k++) {
    PetscCall(BoltMeshRigidMotion(asmb->mesh, k, center, x));
    PetscCall(BVInsertVec(*R, k, x));
    PetscCall(BVOrthonormalizeColumn(*R, k, PETSC_TRUE, &norm, NULL));
  }
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* x -= R R' M x: the part of x that the rigid motions do not carry (R mass-orthonormal). */
PetscErrorCode BoltRigidProject(BV R, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(BVOrthogonalizeVec(R, x, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

/* Inertia relief: f -= M R R' f, the load less what accelerates the structure as a rigid body,
   so that elastic forces alone balance the rest. */
PetscErrorCode BoltRigidRelieve(BV R, Mat M, Vec f)
{
  PetscScalar c[6];
  Vec         w, Mw;

  PetscFunctionBeginUser;
  PetscCall(BVSetMatrix(R, NULL, PETSC_FALSE));
  PetscCall(BVDotVec(R, f, c)); /* R' f in the Euclidean product */
  PetscCall(BVSetMatrix(R, M, PETSC_FALSE));
  PetscCall(VecDuplicate(f, &w));
  PetscCall(VecDuplicate(f, &Mw));
  PetscCall(BVMultVec(R, 1.0, 0.0, w, c));
  PetscCall(MatMult(M, w, Mw));
  PetscCall(VecAXPY(f, -1.0, Mw));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&Mw));
  PetscFunctionReturn(0);
}

/* The shift of the free model's factorisations [1/s^2]: (2 pi x 10 Hz)^2 (docs/decisions.md). */
PetscReal BoltRigidShift(void)
{
  return 4 * PETSC_PI * PETSC_PI * 100;
}

/* K u = f - M R R' f with u M-orthogonal to the rigid motions R: the static response of a free
   model under inertia relief. K + sigma M is factored once; each pass solves
   (K + sigma M) u+ = f_r + sigma M u and projects out the rigid motions, which shrinks the error
   in mode i by sigma / (w_i^2 + sigma) (0.01 for a first mode at 100 Hz). The passes stop
   when u moves by less than 1e-12 of itself; *passes returns their number. */
PetscErrorCode BoltStaticSolveFree(Mat K, Mat M, BV R, Vec f, Vec u, const char prefix[], PetscInt *passes)
{
  const PetscReal sigma = BoltRigidShift();
  MPI_Comm        comm  = PetscObjectComm((PetscObject)K);
  Mat             A;
  KSP             ksp;
  Vec             fr, rhs, un;
  PetscReal       change = PETSC_MAX_REAL, norm = 0;
  PetscInt        pass;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_STATIC_SOLVE, 0, 0, 0, 0));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &A));
  PetscCall(MatAXPY(A, sigma, M, SUBSET_NONZERO_PATTERN));
  PetscCall(BoltDirectSolverCreate(comm, prefix, A, PETSC_FALSE, MATSOLVERMUMPS, &ksp));
  PetscCall(PetscLogEventBegin(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCall(BoltDirectSolverFactor(ksp, NULL));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_FACTORIZATION, 0, 0, 0, 0));
  PetscCall(VecDuplicate(f, &fr));
  PetscCall(VecDuplicate(f, &rhs));
  PetscCall(VecDuplicate(f, &un));
  PetscCall(VecCopy(f, fr));
  PetscCall(BoltRigidRelieve(R, M, fr));
  PetscCall(VecZeroEntries(u));
  for (pass = 1; pass <= 20 && change > 1e-12 * norm; pass++) {
    PetscCall(MatMult(M, u, rhs));
    PetscCall(VecAYPX(rhs, sigma, fr));
    PetscCall(KSPSolve(ksp, rhs, un));
    PetscCall(BoltRigidProject(R, un));
    PetscCall(VecAXPY(u, -1.0, un)); /* u - u+ */
    PetscCall(VecNorm(u, NORM_2, &change));
    PetscCall(VecCopy(un, u));
    PetscCall(VecNorm(u, NORM_2, &norm));
    PetscCheck(!PetscIsInfOrNanReal(norm), comm, PETSC_ERR_NOT_CONVERGED, "Static solve of the free model failed (|u| = %g): check the contact pairs that join its parts", (double)norm);
  }
  PetscCheck(change <= 1e-12 * norm, comm, PETSC_ERR_NOT_CONVERGED, "Static solve of the free model: the shift refinement stalled at a change of %.3e after %" PetscInt_FMT " passes; a part may be joined to none other", (double)(change / norm), pass - 1);
  *passes = pass - 1;
  PetscCall(VecDestroy(&fr));
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&un));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_STATIC_SOLVE, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The frequencies [Hz] of the rigid motions under K: sqrt of the eigenvalues of R' K R (R mass-
   orthonormal), ascending. Zero up to round-off when K holds no spurious constraint. */
PetscErrorCode BoltRigidFrequencies(BV R, Mat K, PetscReal freq[6])
{
  Mat          H;
  PetscScalar *h, work[64];
  PetscReal    w[6];
  PetscBLASInt n = 6, lwork = 64, info;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, 6, 6, NULL, &H));
  { /* R' K R in the Euclidean product (R stays mass-orthonormal: only the projection drops M) */
    Mat       B;
    PetscBool indef;
    PetscCall(BVGetMatrix(R, &B, &indef));
    PetscCall(PetscObjectReference((PetscObject)B));
    PetscCall(BVSetMatrix(R, NULL, PETSC_FALSE));
    PetscCall(BVMatProject(R, K, R, H));
    PetscCall(BVSetMatrix(R, B, indef));
    PetscCall(MatDestroy(&B));
  }
  PetscCall(MatDenseGetArray(H, &h));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &n, h, &n, w, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (%d)", (int)info);
  PetscCall(MatDenseRestoreArray(H, &h));
  for (PetscInt k = 0; k < 6; k++) freq[k] = PetscSqrtReal(PetscAbsReal(w[k])) / (2 * PETSC_PI);
  PetscCall(PetscSortReal(6, freq));
  PetscCall(MatDestroy(&H));
  PetscFunctionReturn(0);
}
