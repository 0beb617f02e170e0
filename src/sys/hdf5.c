/* Files and folders: folders made before the files written into them, and the HDF5 datasets
   (PetscViewerHDF5) that the models, checkpoints and ROM files write and read back, with a
   sorted index to find a row by its key, and attributes of a file's root group. */
#include "private/sys.h"
#include <petscviewerhdf5.h>
#include <sys/stat.h>

PetscErrorCode BoltMakeDir(MPI_Comm comm, const char dir[])
{
  PetscMPIInt rank;
  PetscBool   ok = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char   path[PETSC_MAX_PATH_LEN];
    size_t len;
    PetscCall(PetscStrncpy(path, dir, sizeof(path)));
    PetscCall(PetscStrlen(path, &len));
    for (size_t i = 1; i <= len && ok; i++) { /* mkdir -p */
      if (path[i] == '/' || path[i] == '\0') {
        char      save = path[i];
        PetscBool exists;
        path[i] = '\0';
        PetscCall(PetscTestDirectory(path, 'w', &exists));
        if (!exists) {
          PetscCall(PetscTestDirectory(path, 'r', &exists));
          if (!exists && mkdir(path, 0755) != 0) ok = PETSC_FALSE;
        }
        path[i] = save;
      }
    }
    if (ok) PetscCall(PetscTestDirectory(dir, 'w', &ok));
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_BOOL, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot create or write the directory %s: choose a writable one (-output_dir, -summary, -rom_file)", dir);
  PetscFunctionReturn(0);
}

/* Creates the folder of a file path (nothing for a bare file name), so that a file that
   cannot be written is reported before the work that produces it. */
PetscErrorCode BoltMakeParentDir(MPI_Comm comm, const char path[])
{
  char  dir[PETSC_MAX_PATH_LEN], *slash;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(dir, path, sizeof(dir)));
  PetscCall(PetscStrrchr(dir, '/', &slash));
  if (slash != dir) {
    slash[-1] = '\0';
    PetscCall(BoltMakeDir(comm, dir));
  }
  PetscFunctionReturn(0);
}

/* One HDF5 dataset of comm from n values per rank, in rank order; rootOnly: rank 0's alone (data
   that every rank holds alike). cols > 1 shapes it (rows, cols). */
PetscErrorCode BoltHDF5WriteValues(PetscViewer v, MPI_Comm comm, const char name[], PetscInt n, PetscInt cols, const PetscScalar x[], PetscBool rootOnly)
{
  Vec          w;
  PetscMPIInt  rank;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rootOnly && rank) n = 0;
  PetscCall(VecCreateMPI(comm, n, PETSC_DETERMINE, &w));
  if (cols > 1) PetscCall(VecSetBlockSize(w, cols));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  PetscCall(VecGetArray(w, &a));
  PetscCall(PetscArraycpy(a, x, n));
  PetscCall(VecRestoreArray(w, &a));
  PetscCall(VecView(w, v));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* Each vector's local values as the dataset names[f] (BoltHDF5WriteValues: rootOnly for vectors
   that are the same on every rank). */
PetscErrorCode BoltHDF5WriteVecs(PetscViewer v, MPI_Comm comm, PetscInt n, const char *const names[], Vec x[], PetscBool rootOnly)
{
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < n; f++) {
    const PetscScalar *a;
    PetscInt           nloc;
    PetscCall(VecGetLocalSize(x[f], &nloc));
    PetscCall(VecGetArrayRead(x[f], &a));
    PetscCall(BoltHDF5WriteValues(v, comm, names[f], nloc, 1, a, rootOnly));
    PetscCall(VecRestoreArrayRead(x[f], &a));
  }
  PetscFunctionReturn(0);
}

/* A whole dataset on every rank (freed by the caller). */
PetscErrorCode BoltReadAll(PetscViewer v, MPI_Comm comm, const char name[], PetscInt *n, PetscReal **x)
{
  Vec                w, all;
  VecScatter         sc;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &w));
  PetscCall(PetscObjectSetName((PetscObject)w, name));
  PetscCall(VecLoad(w, v));
  PetscCall(VecScatterCreateToAll(w, &sc, &all));
  PetscCall(VecScatterBegin(sc, w, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, w, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetSize(all, n));
  PetscCall(PetscMalloc1(*n + 1, x));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt i = 0; i < *n; i++) (*x)[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* A sorted index of n keys (integers stored as reals), to find the row of a key. */
PetscErrorCode BoltKeyIndexCreate(PetscInt n, const PetscReal keys[], BoltKeyIndex **ixp)
{
  BoltKeyIndex *ix;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(ixp));
  ix    = *ixp;
  ix->n = n;
  PetscCall(PetscMalloc2(n + 1, &ix->key, n + 1, &ix->row));
  for (PetscInt i = 0; i < n; i++) {
    ix->key[i] = (PetscInt)keys[i];
    ix->row[i] = i;
  }
  PetscCall(PetscSortIntWithArray(n, ix->key, ix->row));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltKeyIndexFind(BoltKeyIndex *ix, PetscInt key, PetscInt *row)
{
  PetscInt loc;

  PetscFunctionBeginUser;
  PetscCall(PetscFindInt(key, ix->n, ix->key, &loc));
  *row = loc >= 0 ? ix->row[loc] : -1;
  PetscFunctionReturn(0);
}

/* The number of keys. */
PetscInt BoltKeyIndexSize(const BoltKeyIndex *ix)
{
  return ix->n;
}

PetscErrorCode BoltKeyIndexDestroy(BoltKeyIndex **ix)
{
  PetscFunctionBeginUser;
  if (!*ix) PetscFunctionReturn(0);
  PetscCall(PetscFree2((*ix)->key, (*ix)->row));
  PetscCall(PetscFree(*ix));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ attributes of the root group */
#define BoltCallH5(call) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5 error in %s", #call); \
  } while (0)

/* Attribute name of the root group "/" of the file that v has open: n values of type t (n < 0: a
   scalar). Collective: every rank calls it with the same values, as parallel HDF5 asks. */
static PetscErrorCode BoltHDF5RootAttribute(PetscViewer v, const char name[], hid_t t, PetscInt n, const void *values)
{
  hid_t   file, space, attr;
  hsize_t dim = (hsize_t)PetscMax(n, 0);

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  space = n < 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
  BoltCallH5(space);
  attr = H5Acreate2(file, name, t, space, H5P_DEFAULT, H5P_DEFAULT);
  BoltCallH5(attr);
  BoltCallH5(H5Awrite(attr, t, values));
  BoltCallH5(H5Aclose(attr));
  BoltCallH5(H5Sclose(space));
  PetscFunctionReturn(0);
}

/* n strings (n < 0: one), as variable-length UTF-8 strings (h5py reads them as str). */
static PetscErrorCode BoltHDF5RootStrings(PetscViewer v, const char name[], PetscInt n, const char *const s[])
{
  hid_t t = H5Tcopy(H5T_C_S1);

  PetscFunctionBeginUser;
  BoltCallH5(t);
  BoltCallH5(H5Tset_size(t, H5T_VARIABLE));
  BoltCallH5(H5Tset_cset(t, H5T_CSET_UTF8));
  PetscCall(BoltHDF5RootAttribute(v, name, t, n, s));
  BoltCallH5(H5Tclose(t));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltHDF5AttributeString(PetscViewer v, const char name[], const char value[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltHDF5RootStrings(v, name, -1, &value));
  PetscFunctionReturn(0);
}

/* An array of n strings (an empty array for n = 0). */
PetscErrorCode BoltHDF5AttributeStrings(PetscViewer v, const char name[], PetscInt n, const char *const values[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltHDF5RootStrings(v, name, n, values));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltHDF5AttributeInt(PetscViewer v, const char name[], PetscInt value)
{
  long long i = value;

  PetscFunctionBeginUser;
  PetscCall(BoltHDF5RootAttribute(v, name, H5T_NATIVE_LLONG, -1, &i));
  PetscFunctionReturn(0);
}

/* n reals (n < 0: a scalar). */
PetscErrorCode BoltHDF5AttributeReals(PetscViewer v, const char name[], PetscInt n, const PetscReal values[])
{
  double one, *a;

  PetscFunctionBeginUser;
  if (n < 0) {
    one = (double)values[0];
    PetscCall(BoltHDF5RootAttribute(v, name, H5T_NATIVE_DOUBLE, -1, &one));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(n + 1, &a));
  for (PetscInt i = 0; i < n; i++) a[i] = (double)values[i];
  PetscCall(BoltHDF5RootAttribute(v, name, H5T_NATIVE_DOUBLE, n, a));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}
