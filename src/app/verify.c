/* Checks of the assembled model and the export of its matrices: the operator on a fixed field
   (-verify_fields: the same K x and M x on any number of ranks; a linear field is the patch
   test), the rigid motions of each free part (-check_rigid), and the tied stiffness and the mass
   matrix, full and reduced, in PETSc binary format for petsc4py (-export_matrices). */
#include "private/app.h"

/* A matrix in PETSc binary format, written under a temporary name and renamed. Sequential
   matrices (the ROM's, the same on every rank) are written by rank 0. */
PetscErrorCode BoltExportMatrix(Mat A, const char dir[], const char name[])
{
  char        tmp[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN];
  PetscViewer v;
  PetscMPIInt size, rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)A);

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (size == 1 && rank != 0) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", dir, name));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
  PetscCall(PetscViewerBinaryOpen(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerBinarySetSkipInfo(v, PETSC_TRUE));
  PetscCall(MatView(A, v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCheck(rename(tmp, path) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", tmp, path);
  PetscFunctionReturn(0);
}

/* K_tied.petsc and M.petsc in dir (created if needed). */
PetscErrorCode BoltExportTied(const char dir[], Mat Ktied, Mat M)
{
  PetscFunctionBeginUser;
  PetscCall(BoltMakeDir(PetscObjectComm((PetscObject)Ktied), dir));
  PetscCall(BoltExportMatrix(Ktied, dir, "K_tied.petsc"));
  PetscCall(BoltExportMatrix(M, dir, "M.petsc"));
  PetscFunctionReturn(0);
}

/* The reduced tied joint, K_r + V' K_c V with every contact point active, and M_r:
   rom_K_tied.petsc and rom_M.petsc in dir. Leaves the contact state reset (all active). */
PetscErrorCode BoltExportReduced(const char dir[], BoltROM *rom, BoltOperator *romOp)
{
  Mat Kcr, Kt, Mr, Kr;

  PetscFunctionBeginUser;
  PetscCall(BoltROMGetMatrices(rom, &Mr, &Kr));
  PetscCall(BoltContactStateReset(BoltOperatorState(romOp)));
  PetscCall(BoltOperatorContactStiffness(romOp, &Kcr));
  PetscCall(MatDuplicate(Kr, MAT_COPY_VALUES, &Kt));
  PetscCall(MatAXPY(Kt, 1.0, Kcr, SAME_NONZERO_PATTERN));
  PetscCall(BoltExportMatrix(Kt, dir, "rom_K_tied.petsc"));
  PetscCall(BoltExportMatrix(Mr, dir, "rom_M.petsc"));
  PetscCall(MatDestroy(&Kt));
  PetscFunctionReturn(0);
}

/* A general linear field u = A x + b: the patch test's exact solution. */
static PetscErrorCode LinearField(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  const PetscReal A[3][3] = {{1.0, 0.3, -0.2}, {0.4, -0.7, 0.5}, {-0.6, 0.2, 0.9}}, b[3] = {1e-3, -2e-3, 3e-3};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 3; i++) u[i] = b[i] + A[i][0] * X[0] + A[i][1] * X[1] + A[i][2] * X[2];
  PetscFunctionReturn(0);
}

/* A smooth, fixed vector field for operator checks. */
static PetscErrorCode SmoothField(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  PetscFunctionBeginUser;
  u[0] = PetscSinReal(97 * X[0] + 31 * X[1]) + 0.1 * part;
  u[1] = PetscCosReal(71 * X[1] - 23 * X[2]);
  u[2] = PetscSinReal(53 * X[2] + 41 * X[0]);
  PetscFunctionReturn(0);
}

/* x (kind 0: smooth, 1: linear), K x and M x, laid out as layout; the caller destroys them. */
PetscErrorCode BoltVerifyFields(BoltMesh *mesh, Mat K, Mat M, Vec layout, PetscInt kind, Vec *x, Vec *Kx, Vec *Mx)
{
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(layout, x));
  PetscCall(VecDuplicate(layout, Kx));
  PetscCall(VecDuplicate(layout, Mx));
  PetscCall(BoltMeshFillVertexField(mesh, kind ? LinearField : SmoothField, NULL, *x));
  PetscCall(MatMult(K, *x, *Kx));
  PetscCall(MatMult(M, *x, *Mx));
  PetscFunctionReturn(0);
}

/* Per part, max over the six rigid motions r of |K_p r| / (|K_p| |r|): zero up to round-off for a
   stiffness that holds no spurious constraint. Needs the free-free model (-clamp false), which
   the run checks before its set-up. */
PetscErrorCode BoltCheckRigid(BoltAssembler *asmb, Vec layout, PetscReal rigid[])
{
  BoltMesh *mesh;
  Vec       x, Kx;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMesh(asmb, &mesh));
  PetscCall(VecDuplicate(layout, &x));
  PetscCall(VecDuplicate(layout, &Kx));
  for (PetscInt p = 0; p < BoltMeshPartCount(mesh); p++) {
    Mat       Kp;
    PetscReal knorm;
    rigid[p] = 0;
    PetscCall(BoltAssemblerPartStiffness(asmb, p, &Kp));
    PetscCall(MatNorm(Kp, NORM_FROBENIUS, &knorm));
    for (PetscInt k = 0; k < 6; k++) {
      const PetscReal center[3] = {0.1, 0.0, 0.01};
      PetscReal       rn, yn;
      PetscCall(BoltMeshRigidMotion(mesh, k, center, x));
      PetscCall(MatMult(Kp, x, Kx));
      PetscCall(VecNorm(x, NORM_2, &rn));
      PetscCall(VecNorm(Kx, NORM_2, &yn));
      rigid[p] = PetscMax(rigid[p], yn / (knorm * rn));
    }
    PetscCall(MatDestroy(&Kp));
    PetscCall(PetscPrintf(BoltMeshComm(mesh), "Rigid motions of part %s: max |K r| / (|K| |r|) = %.3e\n", BoltMeshPartName(mesh, p), (double)rigid[p]));
  }
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&Kx));
  PetscFunctionReturn(0);
}
