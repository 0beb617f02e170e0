static const char help[] = "boltrom: vibration of bolted joints with contact, full and reduced order models.\n"
                           "Usage: mpiexec -n 2 bin/boltrom -options_file SCENE.yaml [-option value ...] [-log_view]\n"
                           "boltrom's own options first, by object; then those of the PETSc and SLEPc solvers it configures.\n\n";

#include "private/app.h"

/* Every object made and configured, the solvers' and time integrators' options read: nothing is
   computed yet. checkpointBase: the checkpoints' base name if they are written, else "". */
static PetscErrorCode BoltRunConfigure(BoltRun *r, char checkpointBase[])
{
  PetscFunctionBeginUser;
  PetscCall(BoltMeshCreate(r->comm, &r->mesh));
  PetscCall(BoltMeshSetFromOptions(r->mesh));
  PetscCheck(!r->opt.checkRigid || !BoltMeshClampGroup(r->mesh), r->comm, PETSC_ERR_USER_INPUT, "-check_rigid needs the free-free model: add -clamp false");
  PetscCall(BoltAssemblerCreate(r->mesh, &r->asmb));
  PetscCall(BoltAssemblerSetFromOptions(r->asmb));
  PetscCall(BoltContactSetCreate(r->mesh, &r->contact));
  PetscCall(BoltContactSetSetFromOptions(r->contact));
  PetscCall(BoltLoadSetCreate(r->mesh, &r->loads));
  PetscCall(BoltLoadSetSetFromOptions(r->loads));
  PetscCall(BoltROMCreate(r->comm, &r->rom));
  PetscCall(BoltROMSetFromOptions(r->rom));
  {
    BoltLoadHistory history;
    PetscCall(BoltLoadHistoryFromOptions(&history));
    PetscCall(BoltROMSetPeriodicLoad(r->rom, (PetscBool)(history == BOLT_LOAD_SINE || history == BOLT_LOAD_SWEEP)));
  }
  if (r->opt.rom) PetscCall(BoltROMCheckOptions(r->rom, r->contact));
  PetscCall(BoltPreflightSetFromOptions(r->comm, &r->opt, checkpointBase));
  PetscCall(BoltROMSolversSetFromOptions(r->rom)); /* PETSc's and SLEPc's options last: -help lists boltrom's first */
  PetscFunctionReturn(0);
}

/* The model: mesh, matrices, contact pairs and state, loads. */
static PetscErrorCode BoltRunSetUp(BoltRun *r)
{
  BoltSummary *s = &r->sum;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshSetUp(r->mesh));
  PetscCall(BoltAssemblerSetUp(r->asmb));
  PetscCall(BoltContactSetSetUp(r->contact));
  PetscCall(BoltContactSetCheckSupport(r->contact));
  {
    Mat K;
    PetscCall(BoltAssemblerGetMatrices(r->asmb, &K, NULL));
    PetscCall(MatCreateVecs(K, &r->u, NULL));
  }
  PetscCall(PetscObjectSetName((PetscObject)r->u, "displacement"));
  PetscCall(BoltLoadSetSetUp(r->loads, r->u));
  PetscCall(BoltContactSetSetUpQuadrature(r->contact, r->u)); /* each model makes its own contact state on it */
  s->mesh        = r->mesh;
  s->asmb        = r->asmb;
  s->contact     = r->contact;
  s->loads       = r->loads;
  s->u           = r->u;
  s->staticSolve = r->opt.staticSolve;
  s->nev         = r->opt.nev;
  s->modalContact = r->opt.modalContact;
  s->checkRigid  = r->opt.checkRigid;
  s->romCheckS0  = (PetscBool)(r->opt.rom && BoltROMVerifies(r->rom));
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltRunDestroy(BoltRun *r)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&r->sum.x));
  PetscCall(VecDestroy(&r->sum.Kx));
  PetscCall(VecDestroy(&r->sum.Mx));
  PetscCall(VecDestroy(&r->u));
  PetscCall(MatDestroy(&r->Ktied));
  PetscCall(BVDestroy(&r->rigid));
  PetscCall(BoltNewmarkDestroy(&r->fomNm));
  PetscCall(BoltPreloadStateDestroy(&r->fomPreload));
  PetscCall(BoltNewmarkDestroy(&r->romNm));
  PetscCall(BoltOperatorDestroy(&r->romOp));
  PetscCall(BoltROMDestroy(&r->rom));
  PetscCall(BoltOperatorDestroy(&r->fomOp));
  PetscCall(BoltLoadSetDestroy(&r->loads));
  PetscCall(BoltContactSetDestroy(&r->contact));
  PetscCall(BoltAssemblerDestroy(&r->asmb));
  PetscCall(BoltMeshDestroy(&r->mesh));
  PetscFunctionReturn(0);
}

/* Every object is configured and every option read before anything is computed, so that a wrong
   option or an unwritable folder stops the run at once, with nothing written. */
static PetscErrorCode BoltRunMain(void)
{
  BoltRun        r = {0};
  char           checkpointBase[PETSC_MAX_PATH_LEN];
  PetscBool      help;
  PetscLogDouble t0, t1;
  PetscViewer    out = PETSC_VIEWER_STDOUT_WORLD;

  PetscFunctionBeginUser;
  r.comm = PETSC_COMM_WORLD;
  PetscCall(BoltLogRegister());
  PetscCall(PetscTime(&t0));
  PetscCall(BoltOptionsCheckFinite(r.comm)); /* before any option is read */
  PetscCall(BoltRunOptionsSetFromOptions(r.comm, &r.opt));
  PetscCall(PetscLogStagePush(BOLT_STAGE_SET_UP));
  PetscCall(BoltRunConfigure(&r, checkpointBase));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help && !BoltMeshFileName(r.mesh)[0]) { /* -help alone: the options are listed (above); stop */
    PetscCall(PetscLogStagePop());
    PetscCall(BoltRunDestroy(&r));
    PetscFunctionReturn(0);
  }
  PetscCall(BoltPreflightCheck(r.comm, &r.opt, r.rom, checkpointBase));
  PetscCall(BoltRunSetUp(&r));
  if (r.opt.rom) PetscCall(BoltROMCheckFile(r.rom, r.asmb, r.contact, r.loads)); /* a ROM file of another scene: refused before the FOM runs */
  PetscCall(BoltOptionsCheckUnused(r.comm, BOLT_OPTIONS_BEFORE_SOLVE)); /* the per-pair options too */
  PetscCall(PetscLogStagePop());
  PetscCall(BoltMeshView(r.mesh, out));
  PetscCall(BoltAssemblerView(r.asmb, out));
  PetscCall(BoltContactSetView(r.contact, out));
  PetscCall(BoltLoadSetView(r.loads, out));
  PetscCall(PetscTime(&t1));
  r.sum.tSetUp = t1 - t0;

  PetscCall(BoltRunTied(&r));
  /* the modes about the preload need the FOM's preloaded state, with or without its transient */
  if (r.opt.fom || (r.opt.nev > 0 && r.opt.modalContact == BOLT_MODAL_PRELOAD)) PetscCall(BoltRunFOM(&r));
  if (r.opt.rom) PetscCall(BoltRunROM(&r));
  PetscCall(BoltOptionsCheckUnused(r.comm, BOLT_OPTIONS_FINAL)); /* the safety net, before anything is written */

  PetscCall(PetscLogStagePush(BOLT_STAGE_OUTPUT));
  if (r.opt.writeOutput) PetscCall(BoltSummaryWriteFields(&r.sum, r.opt.outputDir, r.opt.outputName));
  if (r.opt.summary[0]) PetscCall(BoltSummaryWrite(r.comm, r.opt.summary, &r.sum));
  PetscCall(PetscLogStagePop());
  PetscCall(BoltRunDestroy(&r));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscBool      traceback = PETSC_FALSE;
  PetscMPIInt    rank, size;

  /* Scene files are read after initialisation, under the one-line error handler, so that a
     malformed file gives a message naming it rather than PETSc's trace from inside its start-up;
     the command line is then inserted again so that it still overrides the files. */
  char **args = (char **)malloc(sizeof(char *) * (argc + 1)), *scenes[16];
  int    nargs = 0, nscenes = 0;
  /* -help is kept from PETSc's start-up, which would print its own options first; set after it,
     it lists boltrom's options first, then those of the solvers as they are configured */
  int wantHelp = 0;
  for (int i = 0; i < argc; i++) {
    if (!strcmp(argv[i], "-options_file") && i + 1 < argc && nscenes < 16) scenes[nscenes++] = argv[++i];
    else if (i > 0 && (!strcmp(argv[i], "-help") || !strcmp(argv[i], "-h") || !strcmp(argv[i], "--help"))) {
      wantHelp = 1;
      if (i + 1 < argc && !strcmp(argv[i + 1], "intro")) i++; /* PETSc's "-help intro": the same list here */
    }
    else args[nargs++] = argv[i];
  }
  args[nargs] = NULL;
  /* Open MPI's shared-memory file-pointer component names its semaphore after the file's base
     name only: a run killed while it wrote rom.h5.tmp left that semaphore taken, and every later
     run writing a file of that name waited on it for ever. The files here use no shared file
     pointer; the component that locks with fcntl is released when its process dies. A user's
     own OMPI_MCA_sharedfp wins. */
  if (!getenv("OMPI_MCA_sharedfp") || !getenv("OMPI_MCA_sharedfp")[0]) setenv("OMPI_MCA_sharedfp", "^sm", 1);
  PetscCall(SlepcInitialize(&nargs, &args, NULL, help));
  if (wantHelp) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s", help));
    PetscCall(PetscOptionsSetValue(NULL, "-help", NULL));
  }
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  for (int k = 0; k < nscenes; k++) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = PetscOptionsInsertFile(PETSC_COMM_WORLD, NULL, scenes[k], PETSC_TRUE);
    PetscCall(PetscPopErrorHandler());
    if (ierr) {
      if (rank == 0) fprintf(stderr, "boltrom: error: Cannot read the scene file %s: it is missing or not valid YAML (one 'option: value' per line; quote values with commas)\n", scenes[k]);
      PetscOptionsClear(NULL);
      SlepcFinalize();
      free(args);
      return 1;
    }
  }
  if (nscenes) PetscCall(PetscOptionsInsert(NULL, &nargs, &args, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-traceback", &traceback, NULL));
  /* Errors come back as one line naming the problem; -traceback shows PETSc's full trace. */
  if (!traceback) PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  if (!traceback) PetscCall(BoltHDF5Quiet());
  ierr = BoltRunMain();
  if (!traceback) PetscCall(PetscPopErrorHandler());
  if (ierr) {
    const char *text;
    char       *specific = NULL;
    PetscErrorMessage(ierr, &text, &specific);
    if (rank == 0 || size == 1) fprintf(stderr, "boltrom: error: %s\n", specific && specific[0] ? specific : text);
    else fprintf(stderr, "boltrom: error on rank %d: %s\n", rank, specific && specific[0] ? specific : text);
    fflush(stderr);
    if (size > 1) MPI_Abort(PETSC_COMM_WORLD, (int)ierr);
    PetscOptionsClear(NULL); /* no -options_left report on an error */
    SlepcFinalize();
    free(args);
    return (int)ierr;
  }
  PetscCall(SlepcFinalize());
  free(args);
  return 0;
}
