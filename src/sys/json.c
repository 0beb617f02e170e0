/* A JSON writer for the run's summary: written on rank 0 under a temporary name, renamed when
   complete; the other ranks hold an empty writer. Each module writes its own keys. */
#include "private/sys.h"

static void BoltJSONKey(BoltJSON *j, const char key[])
{
  if (!j->fp) return;
  fprintf(j->fp, "%s\n%*s", j->first[j->depth] ? "" : ",", 2 * (int)j->depth, "");
  j->first[j->depth] = PETSC_FALSE;
  if (key) fprintf(j->fp, "\"%s\": ", key);
}

PetscErrorCode BoltJSONOpen(MPI_Comm comm, const char path[], BoltJSON **jp)
{
  PetscMPIInt rank;
  BoltJSON   *j;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(jp));
  j = *jp;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(j->final, path, sizeof(j->final)));
  PetscCall(PetscSNPrintf(j->tmp, sizeof(j->tmp), "%s.tmp", path));
  j->fp = fopen(j->tmp, "w");
  PetscCheck(j->fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write the summary %s: check -summary and that its folder exists", path);
  fprintf(j->fp, "{");
  j->depth    = 1;
  j->first[1] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONBeginObject(BoltJSON *j, const char key[])
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  BoltJSONKey(j, key);
  fprintf(j->fp, "{");
  j->depth++;
  j->first[j->depth] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONEndObject(BoltJSON *j)
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  j->depth--;
  fprintf(j->fp, "\n%*s}", 2 * (int)j->depth, "");
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONInt(BoltJSON *j, const char key[], PetscInt v)
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  BoltJSONKey(j, key);
  fprintf(j->fp, "%" PetscInt_FMT, v);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONReal(BoltJSON *j, const char key[], PetscReal v)
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  BoltJSONKey(j, key);
  if (PetscIsInfOrNanReal(v)) fprintf(j->fp, "null");
  else fprintf(j->fp, "%.17g", (double)v);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONString(BoltJSON *j, const char key[], const char v[])
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  BoltJSONKey(j, key);
  fprintf(j->fp, "\"%s\"", v);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltJSONRealArray(BoltJSON *j, const char key[], PetscInt n, const PetscReal v[])
{
  PetscFunctionBeginUser;
  if (!j->fp) PetscFunctionReturn(0);
  BoltJSONKey(j, key);
  fprintf(j->fp, "[");
  for (PetscInt i = 0; i < n; i++) fprintf(j->fp, "%s%.17g", i ? ", " : "", (double)v[i]);
  fprintf(j->fp, "]");
  PetscFunctionReturn(0);
}

/* Completes the file and frees the writer. */
PetscErrorCode BoltJSONClose(BoltJSON **jp)
{
  BoltJSON *j = *jp;

  PetscFunctionBeginUser;
  if (!j) PetscFunctionReturn(0);
  if (j->fp) {
    fprintf(j->fp, "\n}\n");
    PetscCheck(fclose(j->fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write %s", j->tmp);
    j->fp = NULL;
    PetscCheck(rename(j->tmp, j->final) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", j->tmp, j->final);
  }
  PetscCall(PetscFree(*jp));
  PetscFunctionReturn(0);
}

/* An object of one value per name (the parts', the contact pairs'): the integers vi, or else the
   reals vr. */
PetscErrorCode BoltJSONNamedValues(BoltJSON *j, const char key[], PetscInt n, const char names[][BOLTROM_NAME_LEN], const PetscInt vi[], const PetscReal vr[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONBeginObject(j, key));
  for (PetscInt i = 0; i < n; i++) {
    if (vi) PetscCall(BoltJSONInt(j, names[i], vi[i]));
    else PetscCall(BoltJSONReal(j, names[i], vr[i]));
  }
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}
