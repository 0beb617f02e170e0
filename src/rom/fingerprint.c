/* The ROM file's fingerprint: every setting the basis depends on (mesh, materials, damping,
   contact law and penalties, friction, the reduction's options), one typed field each, written
   as attributes of /rom/fingerprint and compared field by field, so that a file built for
   another scene is named by the first setting that differs. The load's amplitude is not in it:
   a file serves any amplitude. */
#include "private/rom.h"
#include <petscviewerhdf5.h>
#include <string.h>

/* Bumped when the recipe of the basis changes, so that older files are rebuilt. */
#define BOLT_ROM_FORMAT 10

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

/* The scene's part of the fingerprint: mesh, elements, materials, damping, contact law and
   penalties per pair, and the Krylov and interface reduction's sizes. */
PetscErrorCode BoltROMFingerprintScene(BoltAssembler *asmb, BoltContactSet *c, BoltLoadSet *loads, PetscInt order, PetscReal s0, PetscReal defl, PetscInt nCCM, PetscInt nJIM, BoltROMFingerprint *fp)
{
  BoltMesh          *m;
  unsigned long long h;
  char               key[BOLTROM_NAME_LEN + 32], hex[32];
  PetscReal          alpha, beta;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMesh(asmb, &m));
  PetscCall(BoltAssemblerGetRayleigh(asmb, &alpha, &beta));
  fp->n = 0;
  PetscCall(FileHash(BoltMeshComm(m), BoltMeshFileName(m), &h));
  PetscCall(PetscSNPrintf(hex, sizeof(hex), "%016llx", h));
  PetscCall(BoltROMFingerprintInt(fp, "format", BOLT_ROM_FORMAT));
  PetscCall(BoltROMFingerprintString(fp, "mesh_hash", hex));
  PetscCall(BoltROMFingerprintString(fp, "element", BoltMeshFormulation(m) == HEX8_FULL ? "full" : "incompatible"));
  PetscCall(BoltROMFingerprintReal(fp, "rayleigh_alpha", alpha));
  PetscCall(BoltROMFingerprintReal(fp, "rayleigh_beta", beta));
  PetscCall(BoltROMFingerprintInt(fp, "krylov_order", order));
  PetscCall(BoltROMFingerprintReal(fp, "krylov_s0", s0));
  PetscCall(BoltROMFingerprintReal(fp, "krylov_deflation_tol", defl));
  PetscCall(BoltROMFingerprintInt(fp, "n_ccm", nCCM));
  PetscCall(BoltROMFingerprintInt(fp, "n_jim", nJIM));
  PetscCall(BoltROMFingerprintString(fp, "preload_group_lower", BoltLoadSetPreloadGroup(loads, 0)));
  PetscCall(BoltROMFingerprintString(fp, "preload_group_upper", BoltLoadSetPreloadGroup(loads, 1)));
  if (BoltMeshIsFree(m)) PetscCall(BoltROMFingerprintInt(fp, "free_free", 1)); /* its basis holds the rigid motions; a held model's has none */
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
  PetscCall(BoltROMFingerprintString(fp, "contact_law", BoltContactSetLawType(c)));
  PetscCall(BoltROMFingerprintString(fp, "contact_quadrature", BoltContactSetQuadrature(c) == BOLT_QUADRATURE_NODAL ? "nodal" : "gauss"));
  PetscCall(BoltROMFingerprintInt(fp, "contact_reclose_stick", BoltContactSetIsComplementarity(c) && BoltContactSetReanchor(c)));
  for (PetscInt p = 0; p < BoltContactSetPairCount(c); p++) {
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_penalty", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, BoltContactSetPairPenalty(c, p)));
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_friction", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, BoltContactSetHasFriction(c) ? BoltContactSetFriction(c, p) : 0));
    PetscCall(PetscSNPrintf(key, sizeof(key), "pair_%s_stick_stiffness", BoltContactSetPairName(c, p)));
    PetscCall(BoltROMFingerprintReal(fp, key, BoltContactSetHasFriction(c) ? BoltContactSetPairStickStiffness(c, p) : 0));
  }
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
        PetscCall(PetscSNPrintf(why, len, "%s: the file has %" PetscInt_FMT ", the scene %" PetscInt_FMT, f->key, i, f->i));
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
