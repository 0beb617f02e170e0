/* Assembler: the structural stiffness K and consistent mass M from the hexahedral kernels,
   with the clamped DOFs removed (negative indices are dropped by MatSetValues). */
#include "private/model.h"

PetscErrorCode BoltAssemblerCreate(BoltMesh *mesh, BoltAssembler **asmb)
{
  BoltAssembler *a;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&a));
  a->mesh          = mesh;
  /* 0.5% of critical damping at 91 Hz (the tied joint's first mode) and at 1 kHz */
  a->rayleighAlpha = 5.24;
  a->rayleighBeta  = 1.46e-6;
  *asmb            = a;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltAssemblerSetFromOptions(BoltAssembler *a)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(a->mesh->comm, NULL, "Assembly", "boltrom");
  PetscCall(PetscOptionsReal("-rayleigh_alpha", "Rayleigh damping C = alpha M + beta K: alpha [1/s]", NULL, a->rayleighAlpha, &a->rayleighAlpha, NULL));
  PetscCall(PetscOptionsReal("-rayleigh_beta", "Rayleigh damping C = alpha M + beta K: beta [s]", NULL, a->rayleighBeta, &a->rayleighBeta, NULL));
  PetscOptionsEnd();
  PetscCheck(a->rayleighAlpha >= 0 && a->rayleighBeta >= 0, a->mesh->comm, PETSC_ERR_USER_INPUT, "Rayleigh coefficients must be >= 0 (got alpha %g, beta %g)", (double)a->rayleighAlpha, (double)a->rayleighBeta);
  PetscFunctionReturn(0);
}

/* Adds the element matrices of the cells of one part (or all parts when part < 0) into K and
   M (either may be NULL) and accumulates the per-part volumes, masses and element counts. */
static PetscErrorCode BoltAssemblerAddCells(BoltAssembler *a, PetscInt onlyPart, Mat K, Mat M)
{
  BoltMesh   *m = a->mesh;
  PetscReal   X[24], Ke[576], Me[576], vol;
  PetscInt    idx[24];
  PetscScalar Ks[576], Ms[576];

  PetscFunctionBeginUser;
  for (PetscInt c = m->cStart; c < m->cEnd; c++) {
    PetscInt            part = m->cellPart[c - m->cStart];
    const BoltMaterial *mat  = &m->materials->mat[m->partMaterial[part]];
    PetscErrorCode      ierr;

    if (onlyPart >= 0 && part != onlyPart) continue;
    PetscCall(BoltMeshCellCoordinates(m, c, X));
    PetscCall(BoltMeshCellDofs(m, c, idx));
    if (K) {
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      ierr = Hex8Stiffness(X, mat->E, mat->nu, m->formulation, Ke);
      PetscCall(PetscPopErrorHandler());
      PetscCheck(!ierr, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "Mesh %s: the hexahedron at (%g, %g, %g) in part %s is inverted or degenerate (det J <= 0): fix its node order or shape", m->filename, (double)X[0], (double)X[1], (double)X[2], m->partName[part]);
      for (PetscInt k = 0; k < 576; k++) Ks[k] = Ke[k];
      PetscCall(MatSetValues(K, 24, idx, 24, idx, Ks, ADD_VALUES));
    }
    if (M) {
      PetscCall(Hex8Mass(X, mat->rho, Me));
      PetscCall(Hex8Volume(X, &vol));
      for (PetscInt k = 0; k < 576; k++) Ms[k] = Me[k];
      PetscCall(MatSetValues(M, 24, idx, 24, idx, Ms, ADD_VALUES));
      a->volumePerPart[part] += vol;
      /* the mass seen by a rigid translation in x: sum of the element mass block, not rho V */
      for (PetscInt i = 0; i < 8; i++)
        for (PetscInt j = 0; j < 8; j++) a->massPerPart[part] += Me[(3 * i) * 24 + 3 * j];
      a->elementsPerPart[part]++;
    }
  }
  if (K) {
    PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSetOption(K, MAT_SYMMETRIC, PETSC_TRUE));
  }
  if (M) {
    PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSetOption(M, MAT_SYMMETRIC, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltAssemblerSetUp(BoltAssembler *a)
{
  BoltMesh *m = a->mesh;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(BOLT_EVENT_ASSEMBLY, 0, 0, 0, 0));
  PetscCall(DMCreateMatrix(m->dm, &a->K));
  PetscCall(DMCreateMatrix(m->dm, &a->M));
  PetscCall(PetscObjectSetName((PetscObject)a->K, "K"));
  PetscCall(PetscObjectSetName((PetscObject)a->M, "M"));
  for (PetscInt p = 0; p < m->nparts; p++) {
    a->massPerPart[p]     = 0;
    a->volumePerPart[p]   = 0;
    a->elementsPerPart[p] = 0;
  }
  PetscCall(BoltAssemblerAddCells(a, -1, a->K, a->M));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, a->volumePerPart, (PetscMPIInt)m->nparts, MPIU_REAL, MPI_SUM, m->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, a->massPerPart, (PetscMPIInt)m->nparts, MPIU_REAL, MPI_SUM, m->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, a->elementsPerPart, (PetscMPIInt)m->nparts, MPIU_INT, MPI_SUM, m->comm));
  PetscCall(PetscLogEventEnd(BOLT_EVENT_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The stiffness of one part alone, in the layout of K (for rigid-body checks). */
PetscErrorCode BoltAssemblerPartStiffness(BoltAssembler *a, PetscInt part, Mat *Kp)
{
  PetscFunctionBeginUser;
  PetscCall(DMCreateMatrix(a->mesh->dm, Kp));
  PetscCall(BoltAssemblerAddCells(a, part, *Kp, NULL));
  PetscFunctionReturn(0);
}

/* C = alpha M + beta K; K and M share one nonzero pattern. */
PetscErrorCode BoltAssemblerDamping(BoltAssembler *a, Mat *C)
{
  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(a->K, MAT_COPY_VALUES, C));
  PetscCall(MatScale(*C, a->rayleighBeta));
  PetscCall(MatAXPY(*C, a->rayleighAlpha, a->M, SAME_NONZERO_PATTERN));
  PetscCall(PetscObjectSetName((PetscObject)*C, "C"));
  PetscFunctionReturn(0);
}

/* The assembled stiffness and mass (referenced by the assembler: not to be destroyed). */
PetscErrorCode BoltAssemblerGetMatrices(BoltAssembler *a, Mat *K, Mat *M)
{
  PetscFunctionBeginUser;
  if (K) *K = a->K;
  if (M) *M = a->M;
  PetscFunctionReturn(0);
}

/* Rayleigh damping C = alpha M + beta K: its coefficients. */
PetscErrorCode BoltAssemblerGetRayleigh(BoltAssembler *a, PetscReal *alpha, PetscReal *beta)
{
  PetscFunctionBeginUser;
  *alpha = a->rayleighAlpha;
  *beta  = a->rayleighBeta;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltAssemblerGetMesh(BoltAssembler *a, BoltMesh **mesh)
{
  PetscFunctionBeginUser;
  *mesh = a->mesh;
  PetscFunctionReturn(0);
}

/* Part p's mass [kg], volume [m^3] and number of elements. */
PetscErrorCode BoltAssemblerGetPart(BoltAssembler *a, PetscInt p, PetscReal *mass, PetscReal *volume, PetscInt *elements)
{
  PetscFunctionBeginUser;
  if (mass) *mass = a->massPerPart[p];
  if (volume) *volume = a->volumePerPart[p];
  if (elements) *elements = a->elementsPerPart[p];
  PetscFunctionReturn(0);
}

PetscErrorCode BoltAssemblerView(BoltAssembler *a, PetscViewer viewer)
{
  BoltMesh *m = a->mesh;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Assembly: Rayleigh damping alpha %g 1/s, beta %g s\n", (double)a->rayleighAlpha, (double)a->rayleighBeta));
  for (PetscInt p = 0; p < m->nparts; p++) PetscCall(PetscViewerASCIIPrintf(viewer, "  part %-12s %7" PetscInt_FMT " hexahedra, volume %.6e m^3, mass %.6e kg\n", m->partName[p], a->elementsPerPart[p], (double)a->volumePerPart[p], (double)a->massPerPart[p]));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltAssemblerDestroy(BoltAssembler **asmb)
{
  PetscFunctionBeginUser;
  if (!*asmb) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&(*asmb)->K));
  PetscCall(MatDestroy(&(*asmb)->M));
  PetscCall(PetscFree(*asmb));
  PetscFunctionReturn(0);
}
