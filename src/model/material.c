/* Material table: named isotropic elastic materials. Parts refer to them by name. */
#include "private/model.h"

static PetscErrorCode BoltMaterialAdd(BoltMaterialTable *table, const char name[], PetscReal E, PetscReal nu, PetscReal rho)
{
  BoltMaterial *m = &table->mat[table->nmat++];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(m->name, name, sizeof(m->name)));
  m->E   = E;
  m->nu  = nu;
  m->rho = rho;
  PetscFunctionReturn(0);
}

/* Defaults are the paper's Table 1; -materials adds or renames, -material_<name>_E etc. override. */
PetscErrorCode BoltMaterialTableDestroy(BoltMaterialTable **table)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*table));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMaterialTableSetFromOptions(MPI_Comm comm, BoltMaterialTable *table)
{
  char     *names[BOLTROM_MAX_PARTS];
  PetscInt  n = BOLTROM_MAX_PARTS;
  PetscBool set;

  PetscFunctionBeginUser;
  table->nmat = 0;
  PetscCall(BoltMaterialAdd(table, "steel", 210e9, 0.30, 7800.0));
  PetscCall(BoltMaterialAdd(table, "aluminium", 67e9, 0.33, 2700.0));
  PetscOptionsBegin(comm, NULL, "Materials", "boltrom");
  PetscCall(PetscOptionsStringArray("-materials", "Extra material names (each then takes -material_<name>_E, _nu, _rho)", NULL, names, &n, &set));
  if (set) {
    for (PetscInt i = 0; i < n; i++) {
      PetscInt idx = -1;
      for (PetscInt j = 0; j < table->nmat; j++) {
        PetscBool same;
        PetscCall(PetscStrcmp(table->mat[j].name, names[i], &same));
        if (same) idx = j;
      }
      if (idx < 0) {
        PetscCheck(table->nmat < BOLTROM_MAX_PARTS, comm, PETSC_ERR_USER_INPUT, "Too many materials (at most %d)", BOLTROM_MAX_PARTS);
        PetscCall(BoltMaterialAdd(table, names[i], 0.0, 0.0, 0.0));
      }
      PetscCall(PetscFree(names[i]));
    }
  }
  for (PetscInt j = 0; j < table->nmat; j++) {
    BoltMaterial *m = &table->mat[j];
    char          opt[3][BOLTROM_NAME_LEN + 32];

    PetscCall(PetscSNPrintf(opt[0], sizeof(opt[0]), "-material_%s_E", m->name));
    PetscCall(PetscSNPrintf(opt[1], sizeof(opt[1]), "-material_%s_nu", m->name));
    PetscCall(PetscSNPrintf(opt[2], sizeof(opt[2]), "-material_%s_rho", m->name));
    PetscCall(PetscOptionsReal(opt[0], "Young's modulus [Pa]", NULL, m->E, &m->E, NULL));
    PetscCall(PetscOptionsReal(opt[1], "Poisson's ratio, in (-1, 0.5)", NULL, m->nu, &m->nu, NULL));
    PetscCall(PetscOptionsReal(opt[2], "Density [kg/m^3]", NULL, m->rho, &m->rho, NULL));
  }
  PetscOptionsEnd();
  for (PetscInt j = 0; j < table->nmat; j++) {
    BoltMaterial *m = &table->mat[j];
    PetscCheck(m->E > 0, comm, PETSC_ERR_USER_INPUT, "Material %s: Young's modulus E = %g must be > 0: set -material_%s_E", m->name, (double)m->E, m->name);
    PetscCheck(m->nu > -1.0 && m->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "Material %s: Poisson's ratio nu = %g must lie in (-1, 0.5): set -material_%s_nu", m->name, (double)m->nu, m->name);
    PetscCheck(m->rho > 0, comm, PETSC_ERR_USER_INPUT, "Material %s: density rho = %g must be > 0: set -material_%s_rho", m->name, (double)m->rho, m->name);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMaterialTableFind(MPI_Comm comm, const BoltMaterialTable *table, const char name[], PetscInt *idx)
{
  PetscFunctionBeginUser;
  *idx = -1;
  for (PetscInt j = 0; j < table->nmat; j++) {
    PetscBool same;
    PetscCall(PetscStrcmp(table->mat[j].name, name, &same));
    if (same) *idx = j;
  }
  PetscCheck(*idx >= 0, comm, PETSC_ERR_USER_INPUT, "Unknown material '%s': use steel, aluminium or one declared with -materials", name);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltMeshPartMaterial(BoltMesh *m, PetscInt part, const char **name, PetscReal *E, PetscReal *nu, PetscReal *rho)
{
  const BoltMaterial *mat = &m->materials->mat[m->partMaterial[part]];

  PetscFunctionBeginUser;
  if (name) *name = mat->name;
  if (E) *E = mat->E;
  if (nu) *nu = mat->nu;
  if (rho) *rho = mat->rho;
  PetscFunctionReturn(0);
}
