/* The ROM file's fingerprint: every setting the basis depends on (mesh, materials, damping,
   contact law and penalties, friction, the reduction's options), one typed field each, written
   as attributes of /rom/fingerprint and compared field by field, so that a file built for
   another scene is named by the first setting that differs. The load's amplitude is not in it:
   a file serves any amplitude. */
#include "private/rom.h"
#include <petscviewerhdf5.h>
#include <string.h>

/* Bumped when the recipe of the basis or the fields of the file change, so that an older file is
   refused by its format, not by a field it could not have had. */
#define BOLT_ROM_FORMAT 13

static PetscErrorCode FileHash(MPI_Comm comm, const char path[], unsigned long long *hash)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *hash = 1469598103934665603ULL; /* FNV-1a */
  if (rank == 0) {
    FILE *fp = fopen(path, "rb");
    int   ch;
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot read %s", path);
    while ((ch = fgetc(fp)) != EOF) *hash = (*hash ^ (unsigned long long)(unsigned char)ch) * 1099511628211ULL;
    fclose(fp);
  }
  PetscCallMPI(MPI_Bcast(hash, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode FingerprintAdd(BoltROMFingerprint *fp, const char key[], PetscDataType type, PetscInt i, PetscReal r, const char s[])
{
  BoltROMFingerprintField *f;

  PetscFunctionBeginUser;
  PetscCheck(fp->n < BOLTROM_FINGERPRINT_FIELDS, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ROM fingerprint: more than %d fields", BOLTROM_FINGERPRINT_FIELDS);
  f       = &fp->field[fp->n++];
  f->type = type;
  f->i    = i;
  f->r    = r;
  PetscCall(PetscStrncpy(f->key, key, sizeof(f->key)));
  PetscCall(PetscStrncpy(f->s, s ? s : "", sizeof(f->s)));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMFingerprintInt(BoltROMFingerprint *fp, const char key[], PetscInt value)
{
  return FingerprintAdd(fp, key, PETSC_INT, value, 0, NULL);
}

PetscErrorCode BoltROMFingerprintReal(BoltROMFingerprint *fp, const char key[], PetscReal value)
{
  return FingerprintAdd(fp, key, PETSC_REAL, 0, value, NULL);
}

PetscErrorCode BoltROMFingerprintString(BoltROMFingerprint *fp, const char key[], const char value[])
{
  return FingerprintAdd(fp, key, PETSC_STRING, 0, 0, value);
}

/* A direction as x,y,z to the last bit (the scene normalises it the same way each run). */
static PetscErrorCode DirectionString(const PetscReal d[3], char s[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(s, len, "%.17g,%.17g,%.17g", (double)d[0], (double)d[1], (double)d[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode FingerprintDirection(BoltROMFingerprint *fp, const char key[], const PetscReal d[3])
{
  char s[96];

  PetscFunctionBeginUser;
  PetscCall(DirectionString(d, s, sizeof(s)));
  PetscCall(BoltROMFingerprintString(fp, key, s));
  PetscFunctionReturn(0);
}

/* The contact's part: the law and every setting that decides the preloaded state the file keeps
   and the static shapes solved from it (penalty, friction coefficient and stick stiffness per
   pair, as resolved; the activation gap, node matching, opening test and slip tolerances). The
   contact loop's stopping tolerances are not in it: they move the file's state no more than they
   move the FOM's. */
static PetscErrorCode FingerprintContact(BoltContactSet *c, BoltROMFingerprint *fp)
{
  char      key[BOLTROM_NAME_LEN + 32];
  PetscBool friction = BoltContactSetHasFriction(c);
  PetscReal angle, ratio;

  PetscFunctionBeginUser;
  BoltContactSetSlipTolerances(c, &angle, &ratio);
  PetscCall(BoltROMFingerprintString(fp, "contact_law", BoltContactSetLawType(c)));
  PetscCall(BoltROMFingerprintString(fp, "contact_quadrature", BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL ? "nodal" : "gauss"));
  PetscCall(BoltROMFingerprintInt(fp, "contact_reclose_stick", BoltContactSetIsComplementarity(c) && BoltContactSetReanchor(c)));
  PetscCall(BoltROMFingerprintInt(fp, "contact_augment", BoltContactSetAugmented(c)));
  PetscCall(BoltROMFingerprintReal(fp, "contact_activation_gap", BoltContactSetActivationGap(c)));
  PetscCall(BoltROMFingerprintReal(fp, "contact_match_tolerance", BoltContactSetMatchTolerance(c)));
  PetscCall(BoltROMFingerprintString(fp, "contact_open_test", BoltContactSetOpenTest(c)));
  PetscCall(BoltROMFingerprintReal(fp, "contact_slip_angle_tolerance", friction ? angle : 0));
  PetscCall(BoltROMFingerprintReal(fp, "contact_slip_stiffness_ratio", friction ? ratio : 0));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) {
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_penalty", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, BoltContactSetPairPenalty(c, p)));
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_friction", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, friction ? BoltContactSetFriction(c, p) : 0));
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_stick_stiffness", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, friction ? BoltContactSetPairStickStiffness(c, p) : 0));
  }
  PetscFunctionReturn(0);
}

/* The model's supports: the clamp group (if its DOFs are removed) and the support group with its
   held components; each changes the stiffness every shape of the basis is solved with. */
static PetscErrorCode FingerprintSupports(BoltMesh *m, BoltROMFingerprint *fp)
{
  const PetscInt *comp;
  PetscInt        ncomp = BoltMeshSupportComponents(m, &comp);
  char            s[BOLTROM_NAME_LEN + 16];

  PetscFunctionBeginUser;
  PetscCall(BoltROMFingerprintString(fp, "clamp_group", BoltMeshClampGroup(m) ? BoltMeshClampGroup(m) : "none"));
  PetscCall(PetscStrncpy(s, "none", sizeof(s)));
  if (BoltMeshSupportGroup(m)[0]) {
    PetscCall(PetscSNPrintf(s, sizeof(s), "%s:", BoltMeshSupportGroup(m)));
    for (PetscInt i = 0; i < ncomp; i++) PetscCall(PetscStrlcat(s, comp[i] == 0 ? "x" : comp[i] == 1 ? "y" : "z", sizeof(s)));
  }
  PetscCall(BoltROMFingerprintString(fp, "support", s));
  if (BoltMeshIsFree(m)) PetscCall(BoltROMFingerprintInt(fp, "free_free", 1)); /* its basis holds the rigid motions; a held model's has none */
  PetscFunctionReturn(0);
}

/* The scene's part of the fingerprint: mesh, elements, supports, materials, damping, the preload
   (groups, axis, how the static start treats it; each bolt's force when there are several), the
   contact, and the Krylov and interface reduction's sizes. Not in it: the load's amplitude and
   history, and one bolt's force (the file keeps its state per newton of preload): a file serves
   any of them. The load's group and direction are the file's input (BoltROMFingerprintMatchLoad).
   Nor the time step and Newmark parameters, which no shape of the basis is solved with. */
PetscErrorCode BoltROMFingerprintScene(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, PetscInt order, PetscReal s0, PetscReal defl, PetscInt nCCM, PetscInt nJIM, BoltROMFingerprint *fp)
{
  BoltMesh          *m;
  unsigned long long h;
  char               key[BOLTROM_NAME_LEN + 32], hex[32];
  PetscReal          alpha, beta;
  PetscBool          calibrate, withLoad;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMesh(asmb, &m));
  PetscCall(BoltAssemblerGetRayleigh(asmb, &alpha, &beta));
  /* read as the FOM's static start reads them (newmark.c), which the file's preloaded state is */
  PetscCall(BoltNewmarkStaticStartOptions(&calibrate, &withLoad));
  fp->n = 0;
  PetscCall(FileHash(BoltMeshComm(m), BoltMeshFileName(m), &h));
  PetscCall(PetscSNPrintf(hex, sizeof(hex), "%016llx", h));
  PetscCall(BoltROMFingerprintInt(fp, "format", BOLT_ROM_FORMAT));
  PetscCall(BoltROMFingerprintString(fp, "mesh_hash", hex));
  PetscCall(BoltROMFingerprintString(fp, "element", BoltMeshFormulation(m) == HEX8_FULL ? "full" : "incompatible"));
  PetscCall(FingerprintSupports(m, fp));
  PetscCall(BoltROMFingerprintReal(fp, "rayleigh_alpha", alpha));
  PetscCall(BoltROMFingerprintReal(fp, "rayleigh_beta", beta));
  PetscCall(BoltROMFingerprintInt(fp, "krylov_order", order));
  PetscCall(BoltROMFingerprintReal(fp, "krylov_s0", s0));
  PetscCall(BoltROMFingerprintReal(fp, "krylov_deflation_tol", defl));
  PetscCall(BoltROMFingerprintInt(fp, "n_ccm", nCCM));
  PetscCall(BoltROMFingerprintInt(fp, "n_jim", nJIM));
  PetscCall(BoltROMFingerprintString(fp, "preload_group_lower", BoltLoadSetPreloadGroup(loads, 0)));
  PetscCall(BoltROMFingerprintString(fp, "preload_group_upper", BoltLoadSetPreloadGroup(loads, 1)));
  PetscCall(FingerprintDirection(fp, "preload_axis", BoltLoadSetPreloadAxis(loads)));
  PetscCall(BoltROMFingerprintInt(fp, "preload_calibrate", calibrate));
  PetscCall(BoltROMFingerprintInt(fp, "static_contact_load", withLoad));
  /* several bolts: each its own input, and the static shapes and the preloaded state depend on
     their forces' ratios, which no one scale restores (one bolt's force only scales them) */
  for (PetscInt b = 0; b < BoltLoadSetBoltCount(loads); b++) {
    PetscCall(PetscSNPrintf(key, sizeof(key), "bolt_%s_force", BoltLoadSetBoltName(loads, b)));
    PetscCall(BoltROMFingerprintReal(fp, key, BoltLoadSetBoltForce(loads, b)));
  }
  for (PetscInt p = 0; p < BoltMeshPartCount(m); p++) {
    PetscReal E, nu, rho;
    PetscCall(BoltMeshPartMaterial(m, p, NULL, &E, &nu, &rho));
    PetscCall(PetscSNPrintf(key, sizeof(key), "part_%s_E", BoltMeshPartName(m, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, E));
    PetscCall(PetscSNPrintf(key, sizeof(key), "part_%s_nu", BoltMeshPartName(m, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, nu));
    PetscCall(PetscSNPrintf(key, sizeof(key), "part_%s_rho", BoltMeshPartName(m, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, rho));
  }
  PetscCall(FingerprintContact(c, fp));
  PetscFunctionReturn(0);
}

/* Each field an attribute of /rom/fingerprint, with the count of fields beside them. */
PetscErrorCode BoltROMFingerprintWrite(const BoltROMFingerprint *fp, PetscViewer v)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/fingerprint", "fields", PETSC_INT, &fp->n));
  for (PetscInt k = 0; k < fp->n; k++) {
    const BoltROMFingerprintField *f = &fp->field[k];
    if (f->type == PETSC_INT) PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/fingerprint", f->key, PETSC_INT, &f->i));
    else if (f->type == PETSC_REAL) PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/fingerprint", f->key, PETSC_REAL, &f->r));
    else PetscCall(PetscViewerHDF5WriteAttribute(v, "/rom/fingerprint", f->key, PETSC_STRING, f->s));
  }
  PetscFunctionReturn(0);
}

/* Whether the file's fingerprint has every field of fp with the same value (reals to 1e-12,
   relative) and no other; else *why names the first field that differs. */
PetscErrorCode BoltROMFingerprintMatch(const BoltROMFingerprint *fp, PetscViewer v, PetscBool *matched, char why[], size_t len)
{
  PetscBool has;
  PetscInt  nfile;

  PetscFunctionBeginUser;
  *matched = PETSC_FALSE;
  PetscCall(PetscViewerHDF5HasAttribute(v, "/rom/fingerprint", "fields", &has));
  if (!has) {
    PetscCall(PetscSNPrintf(why, len, "the file has no fingerprint of format %d: it comes from an older boltrom", BOLT_ROM_FORMAT));
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 0; k < fp->n; k++) {
    const BoltROMFingerprintField *f = &fp->field[k];
    PetscCall(PetscViewerHDF5HasAttribute(v, "/rom/fingerprint", f->key, &has));
    if (!has) {
      PetscCall(PetscSNPrintf(why, len, "the file has no %s", f->key));
      PetscFunctionReturn(0);
    }
    if (f->type == PETSC_INT) {
      PetscInt i;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/fingerprint", f->key, PETSC_INT, NULL, &i));
      if (i != f->i) {
        static const char *const train[] = {" (-rom_train none)", " (fom)", " (static)", " (auto)"}; /* the trained field's values */
        const PetscBool   named   = (PetscBool)(!strcmp(f->key, "trained") && i >= 0 && i < 4 && f->i >= 0 && f->i < 4);
        const char       *older   = !strcmp(f->key, "format") && i < f->i ? ": an older boltrom wrote it" : "";
        PetscCall(PetscSNPrintf(why, len, "%s: the file has %" PetscInt_FMT "%s, the scene %" PetscInt_FMT "%s%s", f->key, i, named ? train[i] : "", f->i, named ? train[f->i] : "", older));
        PetscFunctionReturn(0);
      }
    } else if (f->type == PETSC_REAL) {
      PetscReal r;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/fingerprint", f->key, PETSC_REAL, NULL, &r));
      if (PetscAbsReal(r - f->r) > 1e-12 * PetscMax(PetscAbsReal(r), PetscAbsReal(f->r))) {
        char a[32], b[32]; /* short where the short forms differ */
        PetscCall(PetscSNPrintf(a, sizeof(a), "%g", (double)r));
        PetscCall(PetscSNPrintf(b, sizeof(b), "%g", (double)f->r));
        if (!strcmp(a, b)) {
          PetscCall(PetscSNPrintf(a, sizeof(a), "%.17g", (double)r));
          PetscCall(PetscSNPrintf(b, sizeof(b), "%.17g", (double)f->r));
        }
        PetscCall(PetscSNPrintf(why, len, "%s: the file has %s, the scene %s", f->key, a, b));
        PetscFunctionReturn(0);
      }
    } else {
      char     *s;
      PetscBool same;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/fingerprint", f->key, PETSC_STRING, NULL, &s));
      PetscCall(PetscStrcmp(s, f->s, &same));
      if (!same) PetscCall(PetscSNPrintf(why, len, "%s: the file has '%s', the scene '%s'", f->key, s, f->s));
      PetscCall(PetscFree(s));
      if (!same) PetscFunctionReturn(0);
    }
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/fingerprint", "fields", PETSC_INT, NULL, &nfile));
  if (nfile != fp->n) {
    PetscCall(PetscSNPrintf(why, len, "the file's fingerprint has %" PetscInt_FMT " fields, the scene's %" PetscInt_FMT " (other parts or pairs)", nfile, fp->n));
    PetscFunctionReturn(0);
  }
  *matched = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Whether name is one of the comma-separated list. */
static PetscErrorCode InList(const char list[], const char name[], PetscBool *in)
{
  char **items;
  int    n;

  PetscFunctionBeginUser;
  *in = PETSC_FALSE;
  PetscCall(PetscStrToArray(list, ',', &n, &items));
  for (int k = 0; k < n && !*in; k++) PetscCall(PetscStrcmp(items[k], name, in));
  PetscCall(PetscStrToArrayDestroy(n, items));
  PetscFunctionReturn(0);
}

/* Whether the file (its fingerprint matched) serves this scene's load and probe. The load is the
   file's input if its group and direction are the file's (*native: the stored projection serves
   any amplitude); another load only with -rom_allow_foreign_load (foreign), projected with the
   rows the file keeps at its group. The probe needs rows too. Else *served is false and why says
   what differs. */
PetscErrorCode BoltROMFingerprintMatchLoad(PetscViewer v, BoltLoadSet *loads, PetscBool foreign, PetscBool *served, PetscBool *native, char why[], size_t len)
{
  const char      *load = BoltLoadSetLoadGroup(loads), *probe = BoltLoadSetProbeGroup(loads);
  const PetscReal *d    = BoltLoadSetLoadDirection(loads);
  char            *input, *groups, a[96], b[96];
  PetscReal        fd[3];
  PetscBool        same, rows;

  PetscFunctionBeginUser;
  *served = *native = PETSC_FALSE;
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "input_load", PETSC_STRING, NULL, &input));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "point_groups", PETSC_STRING, NULL, &groups));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "input_direction_x", PETSC_REAL, NULL, &fd[0]));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "input_direction_y", PETSC_REAL, NULL, &fd[1]));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/rom/Mr", "input_direction_z", PETSC_REAL, NULL, &fd[2]));
  PetscCall(PetscStrcmp(input, load, &same));
  for (PetscInt k = 0; k < 3; k++) same = (PetscBool)(same && PetscAbsReal(fd[k] - d[k]) <= 1e-12);
  PetscCall(InList(groups, load, &rows));
  *native = same;
  PetscCall(DirectionString(fd, a, sizeof(a)));
  PetscCall(DirectionString(d, b, sizeof(b)));
  if (!same && !(foreign && rows))
    PetscCall(PetscSNPrintf(why, len, "input_load: the file has '%s' along %s, the scene '%s' along %s%s", input, a, load, b, !foreign ? "; -rom_allow_foreign_load projects it with the rows the file keeps" : ", where the file keeps no rows of the basis to project it with"));
  else {
    PetscCall(InList(groups, probe, &rows));
    if (!rows) PetscCall(PetscSNPrintf(why, len, "probe: the file keeps no rows of the basis at '%s' (it has %s)", probe, groups));
    *served = rows;
  }
  PetscCall(PetscFree(input));
  PetscCall(PetscFree(groups));
  PetscFunctionReturn(0);
}
