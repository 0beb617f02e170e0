/* A file's seal: a checksum of every dataset's name and bytes, stored in the file (an attribute
   of its root group) once the file is complete, and compared before the file is read. HDF5 keeps
   no checksum of its own data: flipped bytes in a dataset would be read as numbers. A file cut
   short or damaged in its structure cannot be opened or read through, and fails the check too.
   HDF5's own error report (many lines) is silenced: the caller says what is wrong, in one. */
#include "private/sys.h"
#include <hdf5.h>

#define BOLT_SEAL_ATTR "boltrom_checksum"

typedef struct {
  uint64_t  hash;
  PetscBool bad;
} BoltSealHash;

static void BoltFNV(uint64_t *h, const void *data, size_t n)
{
  const unsigned char *p = (const unsigned char *)data;
  for (size_t i = 0; i < n; i++) *h = (*h ^ p[i]) * 1099511628211ULL;
}

/* One object of the file (visited in name order): a dataset adds its name and its bytes. */
static herr_t BoltSealVisit(hid_t g, const char *name, const H5L_info_t *info, void *ctx)
{
  BoltSealHash *s = (BoltSealHash *)ctx;
  hid_t         obj, type, ntype, space;
  hssize_t      npts;
  size_t        size;
  void         *buf;

  (void)info;
  obj = H5Oopen(g, name, H5P_DEFAULT);
  if (obj < 0) {
    s->bad = PETSC_TRUE;
    return -1;
  }
  if (H5Iget_type(obj) != H5I_DATASET) {
    H5Oclose(obj);
    return 0;
  }
  BoltFNV(&s->hash, name, strlen(name) + 1);
  type  = H5Dget_type(obj);
  ntype = type >= 0 ? H5Tget_native_type(type, H5T_DIR_ASCEND) : -1;
  space = H5Dget_space(obj);
  npts  = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  size  = ntype >= 0 ? H5Tget_size(ntype) : 0;
  if (ntype < 0 || npts < 0 || !size || H5Tis_variable_str(ntype) > 0) s->bad = (PetscBool)(s->bad || ntype < 0 || npts < 0 || !size);
  else if (npts > 0) {
    buf = malloc((size_t)npts * size);
    if (!buf || H5Dread(obj, ntype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) s->bad = PETSC_TRUE;
    else BoltFNV(&s->hash, buf, (size_t)npts * size);
    free(buf);
  }
  if (space >= 0) H5Sclose(space);
  if (ntype >= 0) H5Tclose(ntype);
  if (type >= 0) H5Tclose(type);
  H5Dclose(obj);
  return s->bad ? -1 : 0;
}

/* The checksum of an open file's datasets; *ok false if any cannot be read. */
static void BoltSealCompute(hid_t f, uint64_t *hash, PetscBool *ok)
{
  BoltSealHash s = {14695981039346656037ULL, PETSC_FALSE};

  if (H5Lvisit(f, H5_INDEX_NAME, H5_ITER_INC, BoltSealVisit, &s) < 0) s.bad = PETSC_TRUE;
  *hash = s.hash;
  *ok   = (PetscBool)!s.bad;
}

/* HDF5 prints its error stack to stderr at each failed call unless told not to. */
PetscErrorCode BoltHDF5Quiet(void)
{
  PetscFunctionBeginUser;
  PetscCheck(H5Eset_auto2(H5E_DEFAULT, NULL, NULL) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Cannot silence HDF5's error stack");
  PetscFunctionReturn(0);
}

/* Seals a complete, closed file (on one rank, before it is renamed to its final name). */
PetscErrorCode BoltHDF5Seal(const char file[])
{
  hid_t     f, space, attr;
  uint64_t  hash;
  PetscBool ok;

  PetscFunctionBeginUser;
  f = H5Fopen(file, H5F_ACC_RDWR, H5P_DEFAULT);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot reopen %s to seal it", file);
  BoltSealCompute(f, &hash, &ok);
  space = H5Screate(H5S_SCALAR);
  if (H5Aexists(f, BOLT_SEAL_ATTR) > 0) H5Adelete(f, BOLT_SEAL_ATTR);
  attr = ok ? H5Acreate2(f, BOLT_SEAL_ATTR, H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT) : -1;
  if (attr >= 0) ok = (PetscBool)(H5Awrite(attr, H5T_NATIVE_UINT64, &hash) >= 0);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  if (H5Fclose(f) < 0) ok = PETSC_FALSE;
  PetscCheck(ok && attr >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot seal %s (write its checksum)", file);
  PetscFunctionReturn(0);
}

/* Whether file opens, reads through and matches its seal: *state BOLT_SEAL_OK, BOLT_SEAL_NONE (it
   reads, but was written without a seal) or BOLT_SEAL_BAD (cut short, damaged, or its data
   changed since it was sealed). */
PetscErrorCode BoltHDF5CheckSeal(const char file[], BoltSealState *state)
{
  hid_t     f, attr;
  uint64_t  hash, stored = 0;
  PetscBool ok, has = PETSC_FALSE;

  PetscFunctionBeginUser;
  *state = BOLT_SEAL_BAD;
  f      = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) PetscFunctionReturn(0);
  BoltSealCompute(f, &hash, &ok);
  if (ok && H5Aexists(f, BOLT_SEAL_ATTR) > 0) {
    attr = H5Aopen(f, BOLT_SEAL_ATTR, H5P_DEFAULT);
    has  = (PetscBool)(attr >= 0 && H5Aread(attr, H5T_NATIVE_UINT64, &stored) >= 0);
    ok   = has;
    if (attr >= 0) H5Aclose(attr);
  }
  if (H5Fclose(f) < 0) ok = PETSC_FALSE;
  if (ok) *state = !has ? BOLT_SEAL_NONE : stored == hash ? BOLT_SEAL_OK : BOLT_SEAL_BAD;
  PetscFunctionReturn(0);
}
