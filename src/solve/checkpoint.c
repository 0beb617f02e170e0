/* Checkpoints of a Newmark run (FOM or ROM) in HDF5: everything the time loop carries from one
   step to the next, so that a restarted run continues exactly where the checkpoint left it.
   Group /checkpoint:
   - q, v, a (and snapshot_<k>): the model's vectors. The FOM's are written with dof_keys, the
     key of each DOF in the mesh as read (3 x vertex + component), and the ROM's are the reduced
     vectors themselves, so a checkpoint does not depend on how the mesh was partitioned;
   - contact_keys and contact_state: per contact element, its key (face a in the mesh as read)
     and its contact state at its 4 points (BoltContactStatePack: multipliers, gaps, active flags
     of the last three outer iterations, anchors, friction state);
   - history: the step counters and timings, then the probe, energy, slipping-pair, friction
     dissipation, energy accounting, pair-force and snapshot-time histories.
   A restart may use other ranks: every rank reads the keyed data and picks its own rows. */
#include "private/solve.h"
#include <petscviewerhdf5.h>
#include <ctype.h>

#define BOLT_CKPT_NGLOBALS 15
#define BOLT_CKPT_CONTACT  BOLT_CONTACT_PACK

static PetscErrorCode BoltCheckpointFingerprint(BoltNewmark *nm, char fp[], size_t len)
{
  BoltOperator *op = nm->op;
  PetscInt      n;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(nm->q, &n));
  PetscCall(PetscSNPrintf(fp, len, "boltrom checkpoint 3; model %s; mesh %s; unknowns %" PetscInt_FMT "; contact points %" PetscInt_FMT "; dt %.17g; beta %.17g; gamma %.17g; load history %d, %.17g Hz; contact law %s", op->name, BoltMeshFileName(BoltContactSetMesh(op->contact)), n, BoltContactSetPointCountGlobal(op->contact), (double)nm->dt, (double)nm->beta, (double)nm->gamma, (int)nm->history, (double)nm->frequency, BoltContactStateAugmented(op->state) ? "augmented" : "penalty"));
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

/* The vectors a checkpoint holds, with their dataset names: q, v, a, their products with M and
   K that the steps carry (BoltNewmarkProductsStep: a continued run takes the same bits), and the
   snapshots so far. Free with BoltCheckpointVectorsFree. */
#define BOLT_CKPT_STATE 9
static PetscErrorCode BoltCheckpointVectors(BoltNewmark *nm, char ***names, Vec **fields)
{
  const char *base[BOLT_CKPT_STATE]  = {"q", "v", "a", "Mq", "Mv", "Ma", "Kq", "Kv", "Ka"};
  Vec         state[BOLT_CKPT_STATE] = {nm->q, nm->v, nm->acc, nm->Mq, nm->Mv, nm->Ma, nm->Kq, nm->Kv, nm->Ka};
  PetscInt    n                      = BOLT_CKPT_STATE + nm->nsnap;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(n, names, n, fields));
  for (PetscInt f = 0; f < n; f++) {
    char name[32];
    if (f < BOLT_CKPT_STATE) PetscCall(PetscStrncpy(name, base[f], sizeof(name)));
    else PetscCall(PetscSNPrintf(name, sizeof(name), "snapshot_%" PetscInt_FMT, f - BOLT_CKPT_STATE));
    PetscCall(PetscStrallocpy(name, &(*names)[f]));
    (*fields)[f] = f < BOLT_CKPT_STATE ? state[f] : nm->snap[f - BOLT_CKPT_STATE];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltCheckpointVectorsFree(PetscInt n, char ***names, Vec **fields)
{
  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < n; f++) PetscCall(PetscFree((*names)[f]));
  PetscCall(PetscFree2(*names, *fields));
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkCheckpointWrite(BoltNewmark *nm)
{
  BoltOperator   *op   = nm->op;
  BoltContactSet *c    = op->contact;
  MPI_Comm        comm = op->comm;
  PetscMPIInt     rank;
  PetscInt        nhist = BOLT_CKPT_NGLOBALS + (5 + BOLT_LEDGER + BOLT_PAIR_FORCE * BoltContactSetPairCount(c)) * (nm->step + 1) + nm->nsnap, k = 0, ne = BoltContactSetElementCount(c);
  PetscScalar    *buf;
  PetscViewer     v;
  char            file[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN + 8], fp[PETSC_MAX_PATH_LEN + 512], **names;
  Vec            *fields;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(BoltCheckpointFileName(nm, file, sizeof(file)));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", file));
  PetscCall(BoltCheckpointFingerprint(nm, fp, sizeof(fp)));
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/checkpoint"));
  PetscCall(BoltCheckpointVectors(nm, &names, &fields));
  PetscCall((*op->ops.vectorsSave)(op, v, BOLT_CKPT_STATE + nm->nsnap, (const char *const *)names, fields));
  PetscCall(BoltCheckpointVectorsFree(BOLT_CKPT_STATE + nm->nsnap, &names, &fields));
  if (op->ops.stateSave) PetscCall((*op->ops.stateSave)(op, v));
  PetscCall(PetscMalloc1(BOLT_CKPT_CONTACT * ne + nhist + 1, &buf));
  for (PetscInt e = 0; e < ne; e++) buf[e] = BoltContactSetElementKey(c, e);
  PetscCall(BoltHDF5WriteValues(v, comm, "contact_keys", ne, 1, buf, PETSC_FALSE));
  for (PetscInt e = 0; e < ne; e++) {
    BoltContactStatePack(op->state, e, &buf[k]);
    k += BOLT_CONTACT_PACK;
  }
  PetscCall(BoltHDF5WriteValues(v, comm, "contact_state", BOLT_CKPT_CONTACT * ne, 1, buf, PETSC_FALSE));
  if (nm->nsnap) { /* the contact state at each snapshot so far, per element: nsnap x 4 codes */
    PetscScalar *cs;
    PetscCall(PetscMalloc1(4 * nm->nsnap * ne + 1, &cs));
    for (PetscInt e = 0; e < ne; e++)
      for (PetscInt i = 0; i < nm->nsnap; i++)
        for (PetscInt q = 0; q < 4; q++) cs[(e * nm->nsnap + i) * 4 + q] = nm->snapCodes[4 * ne * i + 4 * e + q];
    PetscCall(BoltHDF5WriteValues(v, comm, "snapshot_contact_state", 4 * nm->nsnap * ne, 1, cs, PETSC_FALSE));
    PetscCall(PetscFree(cs));
  }
  {
    BoltDual *d                     = nm->dual;
    PetscReal g[BOLT_CKPT_NGLOBALS] = {(PetscReal)nm->step, (PetscReal)nm->nsnap, (PetscReal)d->factorizations, (PetscReal)d->solves, (PetscReal)d->outerTotal, (PetscReal)d->innerTotal, (PetscReal)d->outerMax, (PetscReal)d->innerMax, (PetscReal)d->cycles, (PetscReal)d->failures, d->tContactStiffness, d->tDisplacements, d->tContactForces, nm->tOnline, (PetscReal)d->updates};
    k = 0;
    for (PetscInt i = 0; i < BOLT_CKPT_NGLOBALS; i++) buf[k++] = g[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->probeTime[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->probeValue[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->energy[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->slipping[i];
    for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->dissipated[i];
    for (PetscInt r = 0; r < BOLT_LEDGER; r++)
      for (PetscInt i = 0; i <= nm->step; i++) buf[k++] = nm->ledger[r * (nm->nsteps + 1) + i];
    for (PetscInt i = 0; i < BOLT_PAIR_FORCE * BoltContactSetPairCount(c) * (nm->step + 1); i++) buf[k++] = nm->pairForce[i];
    for (PetscInt i = 0; i < nm->nsnap; i++) buf[k++] = nm->snapTime[i];
    PetscCall(BoltHDF5WriteValues(v, comm, "history", nhist, 1, buf, PETSC_TRUE));
  }
  PetscCall(PetscFree(buf));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "fingerprint", PETSC_STRING, fp));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "step", PETSC_INT, &nm->step));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", "preload_scale", PETSC_REAL, &nm->preloadScale));
  for (PetscInt b = 0; nm->bolts && b < BoltLoadSetBoltCount(nm->bolts); b++) { /* -preload_bolts: each bolt's calibrated layer force */
    char name[BOLTROM_NAME_LEN + 32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "bolt_%s_layer_force", BoltLoadSetBoltName(nm->bolts, b)));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/checkpoint/history", name, PETSC_REAL, &nm->boltLayerForce[b]));
  }
  PetscCall(PetscViewerDestroy(&v));
  /* rename once every rank has closed the file: a run killed before this point leaves the
     previous checkpoint complete */
  PetscCallMPI(MPI_Barrier(comm));
  if (!rank) PetscCall(BoltHDF5Seal(tmp));
  if (!rank) PetscCheck(rename(tmp, file) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", tmp, file);
  PetscFunctionReturn(0);
}

/* The preload of the run that wrote the checkpoint v (file): its calibration's scale, or with
   -preload_bolts each bolt's layer force. */
static PetscErrorCode CheckpointReadPreload(BoltNewmark *nm, PetscViewer v, const char file[])
{
  BoltOperator *op   = nm->op;
  MPI_Comm      comm = op->comm;
  PetscReal     scale;

  PetscFunctionBeginUser;
  /* the static solve of this run converged to the loop's tolerance, not to round-off, and
     differs slightly from the one of the run that wrote the checkpoint */
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/checkpoint/history", "preload_scale", PETSC_REAL, NULL, &scale));
  PetscCall(VecScale(op->preload, scale / nm->preloadScale));
  nm->preloadScale = scale;
  if (!nm->bolts) PetscFunctionReturn(0);
  PetscCall(VecZeroEntries(op->preload));
  for (PetscInt b = 0; b < BoltLoadSetBoltCount(nm->bolts); b++) {
    char      name[BOLTROM_NAME_LEN + 32];
    PetscBool has;
    PetscCall(PetscSNPrintf(name, sizeof(name), "bolt_%s_layer_force", BoltLoadSetBoltName(nm->bolts, b)));
    PetscCall(PetscViewerHDF5HasAttribute(v, "/checkpoint/history", name, &has));
    PetscCheck(has, comm, PETSC_ERR_USER_INPUT, "-restart: the checkpoint %s has no bolt %s: restart with the -preload_bolts of the run that wrote it", file, BoltLoadSetBoltName(nm->bolts, b));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/checkpoint/history", name, PETSC_REAL, NULL, &nm->boltLayerForce[b]));
    PetscCall(VecAXPY(op->preload, nm->boltLayerForce[b], BoltLoadSetBoltUnit(nm->bolts, b)));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkCheckpointRead(BoltNewmark *nm)
{
  BoltOperator   *op   = nm->op;
  BoltContactSet *c    = op->contact;
  const PetscInt  ne = BoltContactSetElementCount(c);
  MPI_Comm        comm = op->comm;
  PetscInt        step, nsnap, k = 0, n, missing = 0;
  PetscReal      *h, *x;
  PetscViewer     v;
  PetscBool       exists;
  char            file[PETSC_MAX_PATH_LEN], fp[PETSC_MAX_PATH_LEN + 512], *fpFile = NULL;

  PetscFunctionBeginUser;
  PetscCall(BoltCheckpointFileName(nm, file, sizeof(file)));
  PetscCall(PetscTestFile(file, 'r', &exists));
  if (!exists) {
    /* a model killed before its first checkpoint starts over, but with no checkpoint of
       either model the base name is probably wrong */
    char other[PETSC_MAX_PATH_LEN];
    PetscCall(BoltCheckpointPath(nm->checkpointBase, strcmp(op->name, "FOM") ? "FOM" : "ROM", other, sizeof(other)));
    PetscCall(PetscTestFile(other, 'r', &exists));
    PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "-restart: there is no checkpoint %s; write one first with -checkpoint_every N (and the same -checkpoint_file)", file);
    PetscCall(PetscPrintf(comm, "%s: no checkpoint %s: starting at step 0\n", op->name, file));
    PetscFunctionReturn(0);
  }
  {
    BoltSealState seal = BOLT_SEAL_OK;
    PetscMPIInt   rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) PetscCall(BoltHDF5CheckSeal(file, &seal));
    PetscCallMPI(MPI_Bcast(&seal, 1, MPI_INT, 0, comm));
    PetscCheck(seal != BOLT_SEAL_BAD, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged or cut short (it cannot be read through, or its data do not match the checksum written with it): remove it and run again from the start (or from a copy of an intact checkpoint)", file);
  }
  PetscCall(BoltCheckpointFingerprint(nm, fp, sizeof(fp)));
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
  PetscCall(CheckpointReadPreload(nm, v, file));
  PetscCall(PetscViewerHDF5PushGroup(v, "/checkpoint"));
  PetscCall(BoltReadAll(v, comm, "history", &n, &h));
  nsnap = (PetscInt)h[1];
  PetscCheck(n == BOLT_CKPT_NGLOBALS + (5 + BOLT_LEDGER + BOLT_PAIR_FORCE * BoltContactSetPairCount(c)) * (step + 1) + nsnap && (PetscInt)h[0] == step, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (its history does not match its step)", file);
  PetscCheck(nsnap == 0 || (nm->snapshotEvery > 0 && nsnap <= nm->nsteps / nm->snapshotEvery + 1), comm, PETSC_ERR_USER_INPUT, "-restart: the checkpoint %s holds snapshots: restart with the same -snapshot_every", file);

  /* the model's vectors */
  {
    char **names;
    Vec   *fields;
    nm->nsnap = nsnap;
    PetscCall(BoltCheckpointVectors(nm, &names, &fields));
    PetscCall((*op->ops.vectorsLoad)(op, v, BOLT_CKPT_STATE + nsnap, (const char *const *)names, fields, &missing));
    PetscCall(BoltCheckpointVectorsFree(BOLT_CKPT_STATE + nsnap, &names, &fields));
  }
  /* the contact state of this rank's elements */
  {
    PetscReal   *kall;
    BoltKeyIndex *ix;
    PetscCall(BoltReadAll(v, comm, "contact_keys", &n, &kall));
    PetscCall(BoltKeyIndexCreate(n, kall, &ix));
    PetscCall(PetscFree(kall));
    PetscCall(BoltReadAll(v, comm, "contact_state", &n, &x));
    PetscCheck(n == BOLT_CKPT_CONTACT * BoltKeyIndexSize(ix), comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (contact state of %" PetscInt_FMT " values for %" PetscInt_FMT " elements)", file, n, BoltKeyIndexSize(ix));
    for (PetscInt e = 0; e < ne; e++) {
      PetscInt         row;
      const PetscReal *s;
      PetscCall(BoltKeyIndexFind(ix, BoltContactSetElementKey(c, e), &row));
      if (row < 0) {
        missing++;
        continue;
      }
      s = &x[BOLT_CKPT_CONTACT * row];
      BoltContactStateUnpack(op->state, e, s);
    }
    PetscCall(PetscFree(x));
    if (nsnap) {
      PetscBool has;
      PetscCall(PetscViewerHDF5HasDataset(v, "snapshot_contact_state", &has));
      PetscCheck(has, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s holds snapshots but not their contact states (an older boltrom wrote it): run again from the start", file);
      PetscCall(BoltReadAll(v, comm, "snapshot_contact_state", &n, &x));
      PetscCheck(n == 4 * nsnap * BoltKeyIndexSize(ix), comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint %s is damaged (snapshot contact states of %" PetscInt_FMT " values for %" PetscInt_FMT " elements)", file, n, BoltKeyIndexSize(ix));
      for (PetscInt e = 0; e < ne; e++) {
        PetscInt row;
        PetscCall(BoltKeyIndexFind(ix, BoltContactSetElementKey(c, e), &row));
        if (row < 0) continue; /* counted as missing above */
        for (PetscInt i = 0; i < nsnap; i++)
          for (PetscInt q = 0; q < 4; q++) nm->snapCodes[4 * ne * i + 4 * e + q] = (unsigned char)x[(row * nsnap + i) * 4 + q];
      }
      PetscCall(PetscFree(x));
    }
    PetscCall(BoltKeyIndexDestroy(&ix));
    BoltContactStateChanged(op->state); /* before stateLoad: the ROM brings K_cr up to date there */
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &missing, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!missing, comm, PETSC_ERR_USER_INPUT, "-restart: %" PetscInt_FMT " DOFs or contact elements of this model are not in the checkpoint %s: it was written for another mesh or clamp", missing, file);
  /* K_c for the restored active set: the FOM's is assembled from the element matrices at the
     first step; the ROM's is kept as it was (stateLoad) */
  if (op->ops.stateLoad) PetscCall((*op->ops.stateLoad)(op, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(BoltContactStateCountActive(op->state));

  k                     = 0;
  nm->step              = (PetscInt)h[k++];
  nm->nsnap             = (PetscInt)h[k++];
  nm->dual->factorizations    = (PetscInt)h[k++];
  nm->dual->solves            = (PetscInt)h[k++];
  nm->dual->outerTotal        = (PetscInt)h[k++];
  nm->dual->innerTotal        = (PetscInt)h[k++];
  nm->dual->outerMax          = (PetscInt)h[k++];
  nm->dual->innerMax          = (PetscInt)h[k++];
  nm->dual->cycles            = (PetscInt)h[k++];
  nm->dual->failures          = (PetscInt)h[k++];
  nm->dual->tContactStiffness = h[k++];
  nm->dual->tDisplacements    = h[k++];
  nm->dual->tContactForces    = h[k++];
  nm->tOnlineBefore     = h[k++];
  nm->dual->updates     = (PetscInt)h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->probeTime[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->probeValue[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->energy[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->slipping[i] = h[k++];
  for (PetscInt i = 0; i <= step; i++) nm->dissipated[i] = h[k++];
  for (PetscInt r = 0; r < BOLT_LEDGER; r++)
    for (PetscInt i = 0; i <= step; i++) nm->ledger[r * (nm->nsteps + 1) + i] = h[k++];
  for (PetscInt i = 0; i < BOLT_PAIR_FORCE * BoltContactSetPairCount(c) * (step + 1); i++) nm->pairForce[i] = h[k++];
  for (PetscInt i = 0; i < nsnap; i++) nm->snapTime[i] = h[k++];
  PetscCall(PetscFree(h));
  /* the contact tractions' work and the friction's dissipation so far go on from the histories'
     totals (the state sums them per rank: the first rank takes them) */
  PetscCall(BoltContactStateSetTotals(op->state, nm->ledger[BOLT_LEDGER_CONTACT * (nm->nsteps + 1) + step], nm->dissipated[step]));
  PetscCall(PetscPrintf(comm, "%s: restarted from %s at step %" PetscInt_FMT ", t = %g s\n", op->name, file, nm->step, (double)(nm->step * nm->dt)));
  PetscFunctionReturn(0);
}
