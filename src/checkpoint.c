/* Checkpoints of a Newmark run (FOM or ROM) in HDF5: everything the time loop carries from one
   step to the next, so that a restarted run continues exactly where the checkpoint left it.
   Group /checkpoint:
   - q, v, a (and snapshot_<k>): the model's vectors. The FOM's are written with dof_keys, the
     key of each DOF in the mesh as read (3 x vertex + component), and the ROM's are the reduced
     vectors themselves, so a checkpoint does not depend on how the mesh was partitioned;
   - contact_keys and contact_state: per contact element, its key (face a in the mesh as read)
     and the multipliers, gaps and active flags of the last three outer iterations at its 4
     Gauss points (36 values);
   - history: the step counters and timings, then the probe, energy and snapshot-time histories.
   A restart may use other ranks: every rank reads the keyed data and picks its own rows. */
#include "boltrom.h"
#include <petscviewerhdf5.h>
#include <ctype.h>

#define BOLT_CKPT_NGLOBALS 14
#define BOLT_CKPT_CONTACT  36

static PetscErrorCode BoltCheckpointFingerprint(BoltNewmark *nm, char fp[], size_t len)
{
  BoltOperator *op = nm->op;
  PetscInt      n;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(nm->q, &n));
  PetscCall(PetscSNPrintf(fp, len, "boltrom checkpoint 1; model %s; mesh %s; unknowns %" PetscInt_FMT "; contact points %" PetscInt_FMT "; dt %.17g; beta %.17g; gamma %.17g; load history %d, %.17g Hz; contact law %s", op->name, op->contact->mesh->filename, n, op->contact->ngpGlobal, (double)nm->dt, (double)nm->beta, (double)nm->gamma, (int)nm->history, (double)nm->frequency, op->augment ? "augmented" : "penalty"));
  PetscFunctionReturn(0);
}

/* <base>-fom.ckpt.h5 or <base>-rom.ckpt.h5 */
static PetscErrorCode BoltCheckpointPath(const char base[], const char model[], char file[], size_t len)
{
  char lower[8];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(lower, model, sizeof(lower)));
  for (char *p = lower; *p; p++) *p = (char)tolower((unsigned char)*p);
  PetscCall(PetscSNPrintf(file, len, "%s-%s.ckpt.h5", base, lower));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltCheckpointFileName(BoltNewmark *nm, char file[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(BoltCheckpointPath(nm->checkpointBase, nm->op->name, file, len));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkCheckpointWrite(BoltNewmark *nm)
{
  BoltOperator   *op   = nm->op;
  BoltContactSet *c    = op->contact;
  MPI_Comm        comm = op->comm;
  PetscMPIInt     rank;
  PetscInt        nhist = BOLT_CKPT_NGLOBALS + 3 * (nm->step + 1) + nm->nsnap, k = 0, ne = c->nelem;
  PetscScalar    *buf;
  PetscViewer     v;
  PetscBool       dist;
  char            file[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN + 8], fp[PETSC_MAX_PATH_LEN + 512];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(BoltCheckpointFileName(nm, file, sizeof(file)));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", file));
  PetscCall(BoltCheckpointFingerprint(nm, fp, sizeof(fp)));
  dist = op->meshLayout;
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/checkpoint"));
  {
    Vec fields[3] = {nm->q, nm->v, nm->acc};
    if (dist) {
      Vec keys;
      PetscCall(BoltMeshDofKeys(c->mesh, nm->q, &keys));
      PetscCall(PetscObjectSetName((PetscObject)keys, "dof_keys"));
      PetscCall(VecView(keys, v));
      PetscCall(VecDestroy(&keys));
    }
    for (PetscInt f = 0; f < 3 + nm->nsnap; f++) {
      const char        *names[3] = {"q", "v", "a"};
      char               name[32];
      Vec                x = f < 3 ? fields[f] : nm->snap[f - 3];
      const PetscScalar *a;
      PetscInt           n;
      if (f < 3) PetscCall(PetscStrncpy(name, names[f], sizeof(name)));
      else PetscCall(PetscSNPrintf(name, sizeof(name), "snapshot_%" PetscInt_FMT, f - 3));
      PetscCall(VecGetLocalSize(x, &n));
      PetscCall(VecGetArrayRead(x, &a));
      PetscCall(BoltHDF5WriteValues(v, comm, name, n, 1, a, dist ? PETSC_FALSE : PETSC_TRUE));
      PetscCall(VecRestoreArrayRead(x, &a));
    }
  }
  if (!dist) {
    /* the reduced contact stiffness is a sum updated element by element: its round-off depends
       on the path, so it is kept as it is rather than rebuilt */
    Mat                Kc;
    const PetscScalar *a;
    PetscInt           nr;
    PetscCall(op->contactStiffness(op, &Kc));
    PetscCall(MatGetSize(Kc, &nr, NULL));
    PetscCall(MatDenseGetArrayRead(Kc, &a));
    PetscCall(BoltHDF5WriteValues(v, comm, "reduced_contact_stiffness", nr * nr, 1, a, PETSC_TRUE));
    PetscCall(MatDenseRestoreArrayRead(Kc, &a));
  }
  PetscCall(PetscMalloc1(BOLT_CKPT_CONTACT * ne + nhist + 1, &buf));
  for (PetscInt e = 0; e < ne; e++) buf[e] = c->elem[e].key;
  PetscCall(BoltHDF5WriteValues(v, comm, "contact_keys", ne, 1, buf, PETSC_FALSE));
  for (PetscInt e = 0; e < ne; e++) {
    for (PetscInt i = 0; i < 12; i++) buf[k++] = c->lambda[12 * e + i];
    for (PetscInt i = 0; i < 12; i++) buf[k++] = c->gap[12 * e + i];
    for (PetscInt i = 0; i < 4; i++) buf[k++] = c->active[4 * e + i];
    for (PetscInt i = 0; i < 4; i++) buf[k++] = c->activeOld[4 * e + i];
    for (PetscInt i = 0; i < 4; i++) buf[k++] = c->activeOlder[4 * e + i];
  }
  PetscCall(BoltHDF5WriteValues(v, comm, "contact_state", BOLT_CKPT_CONTACT * ne, 1, buf, PETSC_FALSE));
  {
    PetscReal g[BOLT_CKPT_NGLOBALS] = {(PetscReal)nm->step, (PetscReal)nm->nsnap, (PetscReal)nm->factorizations, (PetscReal)nm->solves, (PetscReal)nm->outerTotal, (PetscReal)nm->innerTotal, (PetscReal)nm->outerMax, (PetscReal)nm->innerMax, (PetscReal)nm->cycles, (PetscReal)nm->failures, nm->tContactStiffness, nm->tDisplacements, nm->tContactForces, nm->tOnline};
    k = 0;
    for (PetscInt i = 0; i < BOLT_CKPT_NGLOBALS; i++) buf[k++] = g[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->probeTime[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->probeValue[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->energy[i];
    for (PetscInt i = 0; i < nm->nsnap; i++) buf[k++] = nm->snapTime[i];
    PetscCall(BoltHDF5WriteValues(v, comm, "history", nhist, 1, buf, PETSC_TRUE));
  }
  PetscCall(PetscFree(buf));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "fingerprint", PETSC_STRING, fp));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "step", PETSC_INT, &nm->step));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "preload_scale", PETSC_REAL, &nm->preloadScale));
  PetscCall(PetscViewerDestroy(&v));
  /* rename once every rank has closed the file: a run killed before this point leaves the
     previous checkpoint complete */
  PetscCallMPI(MPI_Barrier(comm));
  if (!rank) PetscCheck(rename(tmp, file) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", tmp, file);
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkCheckpointRead(BoltNewmark *nm)
{
  BoltOperator   *op   = nm->op;
  BoltContactSet *c    = op->contact;
  MPI_Comm        comm = op->comm;
  PetscInt        step, nsnap, k = 0, n, missing = 0;
  PetscReal      *h, *x;
  PetscViewer     v;
  PetscBool       exists, dist;
  char            file[PETSC_MAX_PATH_LEN], fp[PETSC_MAX_PATH_LEN + 512], *fpFile = NULL;

  PetscFunctionBeginUser;
  PetscCall(BoltCheckpointFileName(nm, file, sizeof(file)));
  PetscCall(PetscTestFile(file, 'r', &exists));
  if (!exists) {
    /* a model killed before its first checkpoint starts over, but with no checkpoint of
       either model the base name is probably wrong */
    char other[PETSC_MAX_PATH_LEN];
    PetscCall(BoltCheckpointPath(nm->checkpointBase, nm->op->meshLayout ? "ROM" : "FOM", other, sizeof(other)));
    PetscCall(PetscTestFile(other, 'r', &exists));
    PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "-restart: there is no checkpoint %s; write one first with -checkpoint_every N (and the same -checkpoint_file)", file);
    PetscCall(PetscPrintf(comm, "%s: no checkpoint %s: starting at step 0\n", op->name, file));
    PetscFunctionReturn(0);
  }
  PetscCall(BoltCheckpointFingerprint(nm, fp, sizeof(fp)));
  dist = op->meshLayout;
  PetscCall(PetscViewerHDF5Open(comm, file, FILE_MODE_READ, &v));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/checkpoint/history", "fingerprint", PETSC_STRING, NULL, &fpFile));
  {
    PetscBool same;
    PetscCall(PetscStrcmp(fp, fpFile, &same));
    PetscCheck(same, comm, PETSC_ERR_USER_INPUT, "-restart: the checkpoint %s was written by another run (%s); this run is (%s): restart with the same mesh, time step, load history and contact law", file, fpFile, fp);
  }
  PetscCall(PetscFree(fpFile));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/checkpoint/history", "step", PETSC_INT, NULL, &step));
  PetscCheck(step <= nm->nsteps, comm, PETSC_ERR_USER_INPUT, "-restart: the checkpoint %s is at step %" PetscInt_FMT ", past the end of this run (%" PetscInt_FMT " steps): raise -ts_end", file, step, nm->nsteps);
  {
    /* the preload calibration of the run that wrote the checkpoint: the static solve of this
       run converged to the loop's tolerance, not to round-off, and differs slightly */
    PetscReal scale;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/checkpoint/history", "preload_scale", PETSC_REAL, NULL, &scale));
    PetscCall(VecScale(op->preload, scale / nm->preloadScale));
    nm->preloadScale = scale;
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/checkpoint"));
  PetscCall(BoltReadAll(v, comm, "history", &n, &h));
  nsnap = (PetscInt)h[1];
  PetscCheck(n == BOLT_CKPT_NGLOBALS + 3 * (step + 1) + nsnap && (PetscInt)h[0] == step, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (its history does not match its step)", file);
  PetscCheck(nsnap == 0 || (nm->snapshotEvery > 0 && nsnap <= nm->nsteps / nm->snapshotEvery + 1), comm, PETSC_ERR_USER_INPUT, "-restart: the checkpoint %s holds snapshots: restart with the same -snapshot_every", file);

  /* the model's vectors */
  {
    Vec          fields[3] = {nm->q, nm->v, nm->acc}, keys = NULL;
    BoltKeyIndex ix        = {0, NULL, NULL};
    PetscInt     nloc;
    if (dist) {
      PetscReal *kall;
      PetscCall(BoltReadAll(v, comm, "dof_keys", &n, &kall));
      PetscCall(BoltKeyIndexCreate(n, kall, &ix));
      PetscCall(PetscFree(kall));
      PetscCall(BoltMeshDofKeys(c->mesh, nm->q, &keys));
    }
    PetscCall(VecGetLocalSize(nm->q, &nloc));
    for (PetscInt f = 0; f < 3 + nsnap; f++) {
      const char  *names[3] = {"q", "v", "a"};
      char         name[32];
      Vec          y = f < 3 ? fields[f] : nm->snap[f - 3];
      PetscScalar *a;
      if (f < 3) PetscCall(PetscStrncpy(name, names[f], sizeof(name)));
      else PetscCall(PetscSNPrintf(name, sizeof(name), "snapshot_%" PetscInt_FMT, f - 3));
      PetscCall(BoltReadAll(v, comm, name, &n, &x));
      PetscCall(VecGetArray(y, &a));
      if (dist) {
        const PetscScalar *kmine;
        PetscCall(VecGetArrayRead(keys, &kmine));
        for (PetscInt i = 0; i < nloc; i++) {
          PetscInt row;
          PetscCall(BoltKeyIndexFind(&ix, (PetscInt)PetscRealPart(kmine[i]), &row));
          if (row < 0) missing++;
          else a[i] = x[row];
        }
        PetscCall(VecRestoreArrayRead(keys, &kmine));
      } else {
        PetscCheck(n == nloc, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s holds %" PetscInt_FMT " reduced coordinates, this ROM has %" PetscInt_FMT, file, n, nloc);
        for (PetscInt i = 0; i < nloc; i++) a[i] = x[i];
      }
      PetscCall(VecRestoreArray(y, &a));
      PetscCall(PetscFree(x));
    }
    PetscCall(VecDestroy(&keys));
    PetscCall(BoltKeyIndexDestroy(&ix));
  }
  /* the contact state of this rank's elements */
  {
    PetscReal   *kall;
    BoltKeyIndex ix;
    PetscCall(BoltReadAll(v, comm, "contact_keys", &n, &kall));
    PetscCall(BoltKeyIndexCreate(n, kall, &ix));
    PetscCall(PetscFree(kall));
    PetscCall(BoltReadAll(v, comm, "contact_state", &n, &x));
    PetscCheck(n == BOLT_CKPT_CONTACT * ix.n, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (contact state of %" PetscInt_FMT " values for %" PetscInt_FMT " elements)", file, n, ix.n);
    for (PetscInt e = 0; e < c->nelem; e++) {
      PetscInt         row;
      const PetscReal *s;
      PetscCall(BoltKeyIndexFind(&ix, c->elem[e].key, &row));
      if (row < 0) {
        missing++;
        continue;
      }
      s = &x[BOLT_CKPT_CONTACT * row];
      for (PetscInt i = 0; i < 12; i++) c->lambda[12 * e + i] = s[i];
      for (PetscInt i = 0; i < 12; i++) c->gap[12 * e + i] = s[12 + i];
      for (PetscInt i = 0; i < 4; i++) c->active[4 * e + i] = s[24 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
      for (PetscInt i = 0; i < 4; i++) c->activeOld[4 * e + i] = s[28 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
      for (PetscInt i = 0; i < 4; i++) c->activeOlder[4 * e + i] = s[32 + i] != 0 ? PETSC_TRUE : PETSC_FALSE;
    }
    PetscCall(PetscFree(x));
    PetscCall(BoltKeyIndexDestroy(&ix));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &missing, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!missing, comm, PETSC_ERR_USER_INPUT, "-restart: %" PetscInt_FMT " DOFs or contact elements of this model are not in the checkpoint %s: it was written for another mesh or clamp", missing, file);
  /* K_c for the restored active set: the FOM's is assembled from the element matrices at the
     first step; the ROM's is brought up to date, then replaced by the saved sum */
  for (PetscInt e = 0; e < c->nelem; e++) c->dirty[e] = PETSC_TRUE;
  c->KcAssembled = PETSC_FALSE;
  if (!dist) {
    Mat          Kc;
    PetscScalar *a;
    PetscInt     nr;
    PetscCall(op->contactStiffness(op, &Kc));
    PetscCall(MatGetSize(Kc, &nr, NULL));
    PetscCall(BoltReadAll(v, comm, "reduced_contact_stiffness", &n, &x));
    PetscCheck(n == nr * nr, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (reduced contact stiffness of %" PetscInt_FMT " values)", file, n);
    PetscCall(MatDenseGetArray(Kc, &a));
    for (PetscInt i = 0; i < n; i++) a[i] = x[i];
    PetscCall(MatDenseRestoreArray(Kc, &a));
    PetscCall(MatAssemblyBegin(Kc, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Kc, MAT_FINAL_ASSEMBLY));
    PetscCall(PetscFree(x));
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  {
    PetscInt nact = 0;
    for (PetscInt i = 0; i < 4 * c->nelem; i++) nact += c->active[i] ? 1 : 0;
    PetscCall(MPIU_Allreduce(&nact, &c->nactive, 1, MPIU_INT, MPI_SUM, comm));
  }

  k                     = 0;
  nm->step              = (PetscInt)h[k++];
  nm->nsnap             = (PetscInt)h[k++];
  nm->factorizations    = (PetscInt)h[k++];
  nm->solves            = (PetscInt)h[k++];
  nm->outerTotal        = (PetscInt)h[k++];
  nm->innerTotal        = (PetscInt)h[k++];
  nm->outerMax          = (PetscInt)h[k++];
  nm->innerMax          = (PetscInt)h[k++];
  nm->cycles            = (PetscInt)h[k++];
  nm->failures          = (PetscInt)h[k++];
  nm->tContactStiffness = h[k++];
  nm->tDisplacements    = h[k++];
  nm->tContactForces    = h[k++];
  nm->tOnlineBefore     = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->probeTime[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->probeValue[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->energy[i] = h[k++];
  for (PetscInt i = 0; i < nsnap; i++) nm->snapTime[i] = h[k++];
  PetscCall(PetscFree(h));
  PetscCall(PetscPrintf(comm, "%s: restarted from %s at step %" PetscInt_FMT ", t = %g s\n", op->name, file, nm->step, (double)(nm->step * nm->dt)));
  PetscFunctionReturn(0);
}
