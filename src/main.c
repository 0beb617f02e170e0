static const char help[] = "boltrom: vibration of bolted joints with contact, full and reduced order models.\n"
                           "Usage: mpiexec -n 2 bin/boltrom -options_file inputs/tied-joint.yaml [-help] [-log_view]\n"
                           "This stage builds the model, solves the tied joint statically and finds its eigenfrequencies.\n\n";

#include "boltrom.h"
#include "boltrom_krylov.h"

typedef struct {
  char      outputDir[PETSC_MAX_PATH_LEN];
  char      outputName[BOLTROM_NAME_LEN];
  char      summary[PETSC_MAX_PATH_LEN];
  PetscBool staticSolve, verifyFields, checkRigid, writeOutput, fom, rom, romCheckS0;
  char      exportDir[PETSC_MAX_PATH_LEN]; /* tied K and M, full and reduced, for petsc4py */
  PetscInt  verifyField; /* 0 smooth, 1 linear */
  PetscInt  nev;
} BoltRunOptions;

/* A matrix in PETSc binary format, written under a temporary name and renamed. Sequential
   matrices (the ROM's, the same on every rank) are written by rank 0. */
static PetscErrorCode BoltExportMatrix(Mat A, const char dir[], const char name[])
{
  char        tmp[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN];
  PetscViewer v;
  PetscMPIInt size, rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)A);

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (size == 1 && rank != 0) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", dir, name));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
  PetscCall(PetscViewerBinaryOpen(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerBinarySetSkipInfo(v, PETSC_TRUE));
  PetscCall(MatView(A, v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCheck(rename(tmp, path) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename %s to %s", tmp, path);
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltRunOptionsSetFromOptions(MPI_Comm comm, BoltRunOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(o->outputDir, "output", sizeof(o->outputDir)));
  PetscCall(PetscStrncpy(o->outputName, "joint", sizeof(o->outputName)));
  o->summary[0]   = '\0';
  o->staticSolve  = PETSC_TRUE;
  o->verifyFields = PETSC_FALSE;
  o->checkRigid   = PETSC_FALSE;
  o->writeOutput  = PETSC_TRUE;
  o->nev          = 3;
  o->fom          = PETSC_FALSE;
  o->rom          = PETSC_FALSE;
  o->romCheckS0   = PETSC_FALSE;
  o->exportDir[0] = '\0';
  o->verifyField  = 0;
  PetscOptionsBegin(comm, NULL, "Run", "boltrom");
  PetscCall(PetscOptionsString("-output_dir", "Folder for the HDF5/XDMF results (created if needed)", NULL, o->outputDir, o->outputDir, sizeof(o->outputDir), NULL));
  PetscCall(PetscOptionsString("-output_name", "Base name of the HDF5/XDMF files", NULL, o->outputName, o->outputName, sizeof(o->outputName), NULL));
  PetscCall(PetscOptionsBool("-output", "Write the HDF5/XDMF results", NULL, o->writeOutput, &o->writeOutput, NULL));
  PetscCall(PetscOptionsString("-summary", "Write a JSON summary to this file (keys in the README)", NULL, o->summary, o->summary, sizeof(o->summary), NULL));
  PetscCall(PetscOptionsBool("-static", "Solve the tied joint (all contact elements active) under the load", NULL, o->staticSolve, &o->staticSolve, NULL));
  PetscCall(PetscOptionsBool("-fom", "Run the full-order model with contact: static preload, then the Newmark transient", NULL, o->fom, &o->fom, NULL));
  PetscCall(PetscOptionsBool("-rom", "Run the reduced-order model: offline reduction (or a matching -rom_file), static preload, Newmark transient", NULL, o->rom, &o->rom, NULL));
  PetscCall(PetscOptionsString("-export_matrices", "Folder for the tied stiffness and the mass matrix, full (K_tied.petsc, M.petsc) and, with -rom, reduced (rom_K_tied.petsc, rom_M.petsc), in PETSc binary format (python/compare_eigen.py reads them)", NULL, o->exportDir, o->exportDir, sizeof(o->exportDir), NULL));
  PetscCall(PetscOptionsBool("-rom_check_s0", "Check the ROM against the FOM at s = s0 with every contact point active (exact for an order-1 ROM without interface reduction)", NULL, o->romCheckS0, &o->romCheckS0, NULL));
  PetscCall(PetscOptionsInt("-modal_nev", "Number of eigenfrequencies of the tied joint (0: none)", NULL, o->nev, &o->nev, NULL));
  PetscCall(PetscOptionsBool("-verify_fields", "Also write K x and M x for a fixed smooth field x (checks across rank counts)", NULL, o->verifyFields, &o->verifyFields, NULL));
  {
    const char *kinds[] = {"smooth", "linear"};
    PetscCall(PetscOptionsEList("-verify_field", "The field x of -verify_fields: smooth (sines) or linear (patch test: K x vanishes at interior nodes)", NULL, kinds, 2, kinds[o->verifyField], &o->verifyField, NULL));
  }
  PetscCall(PetscOptionsBool("-check_rigid", "Check K r = 0 for the six rigid motions of every part (use with -clamp false)", NULL, o->checkRigid, &o->checkRigid, NULL));
  PetscOptionsEnd();
  PetscCheck(o->nev >= 0 && o->nev <= 100, comm, PETSC_ERR_USER_INPUT, "-modal_nev must be in [0, 100] (got %" PetscInt_FMT ")", o->nev);
  PetscFunctionReturn(0);
}

/* Options that nobody asked for are spelling mistakes or leftovers: refuse them. */
static PetscErrorCode BoltCheckUnusedOptions(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  if (n) {
    char msg[1024] = "";
    for (PetscInt i = 0; i < n && i < 8; i++) {
      PetscCall(PetscStrlcat(msg, i ? ", -" : "-", sizeof(msg)));
      PetscCall(PetscStrlcat(msg, names[i], sizeof(msg)));
    }
    PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "Unknown or unused option(s) %s: check the spelling against bin/boltrom -help", msg);
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}

/* A general linear field u = A x + b: the patch test's exact solution. */
static PetscErrorCode LinearField(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  const PetscReal A[3][3] = {{1.0, 0.3, -0.2}, {0.4, -0.7, 0.5}, {-0.6, 0.2, 0.9}}, b[3] = {1e-3, -2e-3, 3e-3};

  for (PetscInt i = 0; i < 3; i++) u[i] = b[i] + A[i][0] * X[0] + A[i][1] * X[1] + A[i][2] * X[2];
  return 0;
}

/* A smooth, fixed vector field for operator checks. */
static PetscErrorCode SmoothField(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  u[0] = PetscSinReal(97 * X[0] + 31 * X[1]) + 0.1 * part;
  u[1] = PetscCosReal(71 * X[1] - 23 * X[2]);
  u[2] = PetscSinReal(53 * X[2] + 41 * X[0]);
  return 0;
}

typedef struct {
  PetscInt  mode;
  PetscReal center[3];
} RigidCtx;

static PetscErrorCode RigidMotion(const PetscReal X[3], PetscInt part, PetscReal u[3], void *ctx)
{
  RigidCtx *r = (RigidCtx *)ctx;
  PetscReal y[3];

  for (PetscInt d = 0; d < 3; d++) {
    y[d] = X[d] - r->center[d];
    u[d] = 0;
  }
  if (r->mode < 3) u[r->mode] = 1.0;
  else { /* rotation about axis mode-3: omega x y */
    PetscReal w[3] = {0, 0, 0};
    w[r->mode - 3] = 1.0;
    u[0]           = w[1] * y[2] - w[2] * y[1];
    u[1]           = w[2] * y[0] - w[0] * y[2];
    u[2]           = w[0] * y[1] - w[1] * y[0];
  }
  return 0;
}

static PetscErrorCode BoltRun(void)
{
  MPI_Comm        comm = PETSC_COMM_WORLD;
  BoltRunOptions  opt;
  BoltMesh       *mesh;
  BoltAssembler  *asmb;
  BoltContactSet *contact;
  BoltLoadSet    *loads;
  Mat             Ktied = NULL;
  BoltOperator   *fomOp = NULL;
  BoltNewmark    *fomNm = NULL, *romNm = NULL;
  BoltPreloadState *fomPreload = NULL;
  BoltOperator   *romOp = NULL;
  BoltROM        *rom   = NULL;
  PetscReal       errL2 = 0, errMean = 0, romCheckError = -1;
  PetscReal       preloadForce[BOLTROM_MAX_PAIRS], tractionStats[3] = {0, 0, 0}, staticPenetration = 0, staticChange = 0;
  PetscInt        preloadActive = 0;
  Vec             u = NULL, x = NULL, Kx = NULL, Mx = NULL;
  PetscReal       probe = 0, freq[100], rigid[BOLTROM_MAX_PARTS];
  PetscInt        nconv = 0;
  PetscLogDouble  t0, tSetUp, tStatic = 0, tModal = 0;
  PetscViewer     out = PETSC_VIEWER_STDOUT_WORLD;
  PetscMPIInt     size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(BoltLogRegister());
  PetscCall(PetscTime(&t0));
  PetscCall(BoltRunOptionsSetFromOptions(comm, &opt));
  PetscCall(PetscLogStagePush(boltLog.stageSetUp));
  PetscCall(BoltMeshCreate(comm, &mesh));
  PetscCall(BoltMeshSetFromOptions(mesh));
  PetscCall(BoltAssemblerCreate(mesh, &asmb));
  PetscCall(BoltAssemblerSetFromOptions(asmb));
  PetscCall(BoltContactSetCreate(mesh, &contact));
  PetscCall(BoltContactSetSetFromOptions(contact));
  PetscCall(BoltLoadSetCreate(mesh, &loads));
  PetscCall(BoltLoadSetSetFromOptions(loads));
  {
    PetscBool help;
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    if (help && !mesh->filename[0]) { /* -help alone: list the options (solvers' too) and stop */
      KSP ksp;
      EPS eps;
      PetscCall(KSPCreate(comm, &ksp));
      PetscCall(KSPSetOptionsPrefix(ksp, "static_"));
      PetscCall(KSPSetFromOptions(ksp));
      PetscCall(KSPDestroy(&ksp));
      PetscCall(EPSCreate(comm, &eps));
      PetscCall(EPSSetOptionsPrefix(eps, "modal_"));
      PetscCall(EPSSetFromOptions(eps));
      PetscCall(EPSDestroy(&eps));
      { /* time integration, Krylov basis and reduction options (their objects need no model) */
        BoltOperator         stub = {0};
        BoltNewmark         *nm;
        BoltKrylov          *kry;
        BoltReductionOptions ropt;
        stub.comm = comm;
        stub.name = "FOM";
        PetscCall(BoltNewmarkCreate(&stub, &nm));
        PetscCall(BoltNewmarkSetFromOptions(nm));
        PetscCall(BoltNewmarkDestroy(&nm));
        PetscCall(BoltKrylovCreate(comm, &kry));
        PetscCall(BoltKrylovSetFromOptions(kry));
        PetscCall(BoltKrylovDestroy(&kry));
        PetscCall(BoltReductionOptionsSetFromOptions(comm, &ropt));
      }
      PetscCall(BoltLoadSetDestroy(&loads));
      PetscCall(BoltContactSetDestroy(&contact));
      PetscCall(BoltAssemblerDestroy(&asmb));
      PetscCall(BoltMeshDestroy(&mesh));
      PetscCall(PetscLogStagePop());
      PetscFunctionReturn(0);
    }
  }
  if (opt.summary[0]) PetscCall(BoltMakeParentDir(comm, opt.summary)); /* fail now, not after the solve */
  PetscCall(BoltMeshSetUp(mesh));
  PetscCall(BoltAssemblerSetUp(asmb));
  PetscCall(BoltContactSetSetUp(contact));
  PetscCall(BoltContactSetCheckSupport(contact));
  PetscCall(MatCreateVecs(asmb->K, &u, NULL));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(BoltLoadSetSetUp(loads, u));
  PetscCall(BoltContactSetSetUpQuadrature(contact, u)); /* each model makes its own contact state on it */
  PetscCall(PetscLogStagePop());
  PetscCall(BoltMeshView(mesh, out));
  PetscCall(BoltAssemblerView(asmb, out));
  PetscCall(BoltContactSetView(contact, out));
  PetscCall(BoltLoadSetView(loads, out));
  {
    PetscLogDouble t;
    PetscCall(PetscTime(&t));
    tSetUp = t - t0;
  }

  /* the tied joint: every contact element active with its penalty stiffness */
  if (contact->npairs) PetscCall(BoltContactSetAssembleTied(contact, asmb->K, &Ktied));
  else {
    PetscCall(PetscObjectReference((PetscObject)asmb->K));
    Ktied = asmb->K;
  }
  if (opt.staticSolve) {
    PetscLogDouble ts, te;
    PetscCall(PetscLogStagePush(boltLog.stageStatic));
    PetscCall(PetscTime(&ts));
    PetscCall(BoltStaticSolve(Ktied, loads->load, u, "static_"));
    PetscCall(PetscTime(&te));
    tStatic = te - ts;
    PetscCall(BoltLoadSetProbe(loads, u, &probe));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscPrintf(comm, "Static (tied): probe u_%c at '%s' = %.10e m under %g N (%.2f s)\n", "xyz"[loads->probeComponent], loads->probeGroup, (double)probe, (double)loads->loadForce, (double)tStatic));
  }
  if (opt.exportDir[0]) {
    PetscCall(BoltMakeDir(comm, opt.exportDir));
    PetscCall(BoltExportMatrix(Ktied, opt.exportDir, "K_tied.petsc"));
    PetscCall(BoltExportMatrix(asmb->M, opt.exportDir, "M.petsc"));
  }
  if (opt.nev > 0) {
    PetscLogDouble ts, te;
    PetscCall(PetscLogStagePush(boltLog.stageModal));
    PetscCall(PetscTime(&ts));
    PetscCall(BoltModalSolve(Ktied, asmb->M, opt.nev, "modal_", &nconv, freq));
    PetscCall(PetscTime(&te));
    tModal = te - ts;
    PetscCall(PetscLogStagePop());
    PetscCall(PetscPrintf(comm, "Eigenfrequencies (tied) [Hz]:"));
    for (PetscInt i = 0; i < nconv; i++) PetscCall(PetscPrintf(comm, " %.6f", (double)freq[i]));
    PetscCall(PetscPrintf(comm, " (%.2f s)\n", (double)tModal));
  }
  if (opt.verifyFields) {
    PetscCall(VecDuplicate(u, &x));
    PetscCall(VecDuplicate(u, &Kx));
    PetscCall(VecDuplicate(u, &Mx));
    PetscCall(BoltMeshFillVertexField(mesh, opt.verifyField ? LinearField : SmoothField, NULL, x));
    PetscCall(MatMult(Ktied, x, Kx));
    PetscCall(MatMult(asmb->M, x, Mx));
  }
  if (opt.checkRigid) {
    PetscCheck(!mesh->clamp, comm, PETSC_ERR_USER_INPUT, "-check_rigid needs the free-free model: add -clamp false");
    PetscCall(VecDuplicate(u, &x));
    PetscCall(VecDuplicate(u, &Kx));
    for (PetscInt p = 0; p < mesh->nparts; p++) {
      Mat       Kp;
      PetscReal knorm;
      rigid[p] = 0;
      PetscCall(BoltAssemblerPartStiffness(asmb, p, &Kp));
      PetscCall(MatNorm(Kp, NORM_FROBENIUS, &knorm));
      for (PetscInt k = 0; k < 6; k++) {
        RigidCtx  rc = {k, {0.1, 0.0, 0.01}};
        PetscReal rn, yn;
        PetscCall(VecZeroEntries(x));
        PetscCall(BoltMeshFillVertexField(mesh, RigidMotion, &rc, x));
        PetscCall(MatMult(Kp, x, Kx));
        PetscCall(VecNorm(x, NORM_2, &rn));
        PetscCall(VecNorm(Kx, NORM_2, &yn));
        rigid[p] = PetscMax(rigid[p], yn / (knorm * rn));
      }
      PetscCall(MatDestroy(&Kp));
      PetscCall(PetscPrintf(comm, "Rigid motions of part %s: max |K r| / (|K| |r|) = %.3e\n", mesh->partName[p], (double)rigid[p]));
    }
  }
  if (opt.fom) {
    PetscReal force[BOLTROM_MAX_PAIRS];
    PetscCall(BoltFOMCreate(asmb, contact, loads, PETSC_TRUE, &fomOp));
    PetscCall(BoltNewmarkCreate(fomOp, &fomNm));
    PetscCall(PetscSNPrintf(fomNm->checkpointBase, sizeof(fomNm->checkpointBase), "%s/%s", opt.outputDir, opt.outputName));
    PetscCall(BoltNewmarkSetFromOptions(fomNm));
    fomNm->preloadTarget = loads->hasPreload ? loads->preloadForce : 0;
    PetscCall(BoltNewmarkSetUp(fomNm));
    PetscCall(PetscLogStagePush(boltLog.stagePreload));
    PetscCall(BoltNewmarkPreload(fomNm));
    PetscCall(PetscLogStagePop());
    PetscCall(BoltContactStateNormalForcePerPair(fomOp->state, force));
    PetscCall(PetscPrintf(comm, "Preload %g N: static contact solve in %g outer / %g inner iterations; normal force per pair [N]:", (double)loads->preloadForce, (double)fomNm->staticOuter, (double)fomNm->staticInner));
    for (PetscInt p = 0; p < contact->npairs; p++) PetscCall(PetscPrintf(comm, " %s %.6f", contact->pairName[p], (double)force[p]));
    PetscCall(PetscPrintf(comm, "\n"));
    for (PetscInt p = 0; p < contact->npairs; p++) preloadForce[p] = force[p];
    PetscCall(BoltMemoryPrint(comm, "the FOM's preload"));
    PetscCall(BoltContactStateTractionStats(fomOp->state, &tractionStats[0], &tractionStats[1], &tractionStats[2]));
    preloadActive = fomOp->state->nactive;
    staticPenetration = fomNm->dual->lastPenetration;
    staticChange      = fomNm->dual->lastChange;
    if (opt.rom) PetscCall(BoltPreloadStateCreate(fomOp, fomNm->q, fomNm->staticOuter, fomNm->staticInner, &fomPreload)); /* the ROM's offline phase starts from it */
    PetscCall(PetscLogStagePush(boltLog.stageTransient));
    PetscCall(BoltNewmarkRun(fomNm));
    PetscCall(PetscLogStagePop());
    PetscCall(BoltNewmarkView(fomNm, out));
    /* at 562k DOFs the FOM's factorisation and the offline phase's two would not fit in memory together */
    PetscCall(BoltNewmarkReleaseSolver(fomNm));
    PetscCall(MatDestroy(&fomOp->C)); /* the FOM has run: its damping is not needed any more */
    PetscCall(BoltMemoryRelease());
    PetscCall(BoltMemoryPrint(comm, "the FOM run (its solver released)"));
  }
  if (opt.rom) {
    BoltReductionOptions ropt;
    PetscCall(BoltReductionOptionsSetFromOptions(comm, &ropt));
    ropt.fomPreload = fomPreload;
    PetscCall(BoltROMBuild(&ropt, asmb, contact, loads, &rom));
    PetscCall(BoltPreloadStateDestroy(&fomPreload));
    PetscCall(BoltROMOperatorCreate(rom, &romOp));
    if (opt.romCheckS0) PetscCall(BoltROMCheckAtS0(rom, romOp, asmb, contact, loads, &romCheckError));
    if (opt.exportDir[0]) { /* the reduced tied joint: K_r + V' K_c V with every contact point active */
      Mat Kcr, Kt;
      PetscCall(BoltContactStateReset(romOp->state));
      PetscCall(romOp->ops.contactStiffness(romOp, &Kcr));
      PetscCall(MatDuplicate(rom->Kr, MAT_COPY_VALUES, &Kt));
      PetscCall(MatAXPY(Kt, 1.0, Kcr, SAME_NONZERO_PATTERN));
      PetscCall(BoltExportMatrix(Kt, opt.exportDir, "rom_K_tied.petsc"));
      PetscCall(BoltExportMatrix(rom->Mr, opt.exportDir, "rom_M.petsc"));
      PetscCall(MatDestroy(&Kt));
    }
    PetscCall(BoltNewmarkCreate(romOp, &romNm));
    PetscCall(PetscSNPrintf(romNm->checkpointBase, sizeof(romNm->checkpointBase), "%s/%s", opt.outputDir, opt.outputName));
    PetscCall(BoltNewmarkSetFromOptions(romNm));
    romNm->preloadTarget = loads->hasPreload ? loads->preloadForce : 0;
    PetscCall(BoltNewmarkSetUp(romNm));
    PetscCall(BoltROMSetPreloadState(rom, romNm, loads->preloadForce));
    PetscCall(PetscLogStagePush(boltLog.stagePreload));
    PetscCall(BoltNewmarkPreload(romNm));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscLogStagePush(boltLog.stageTransient));
    PetscCall(BoltNewmarkRun(romNm));
    PetscCall(PetscLogStagePop());
    PetscCall(BoltNewmarkView(romNm, out));
    if (opt.fom) {
      PetscCall(BoltHistoryErrors(fomNm->nsteps + 1, fomNm->probeValue, romNm->probeValue, &errL2, &errMean));
      PetscCall(PetscPrintf(comm, "ROM against FOM at '%s': e_L2 %.4e, mean relative error %.4e; speedup (online) %.1f\n", loads->probeGroup, (double)errL2, (double)errMean, (double)(fomNm->tOnline / romNm->tOnline)));
    }
  }
  if (!opt.rom) { /* a scene file may carry the ROM's settings while the ROM is switched off */
    BoltReductionOptions ropt;
    BoltKrylov          *kry;
    PetscCall(BoltReductionOptionsSetFromOptions(comm, &ropt));
    PetscCall(BoltKrylovCreate(comm, &kry));
    PetscCall(BoltKrylovSetFromOptions(kry));
    PetscCall(BoltKrylovDestroy(&kry));
  }
  /* every option must have been used before anything is written */
  PetscCall(BoltCheckUnusedOptions(comm));

  PetscCall(PetscLogStagePush(boltLog.stageOutput));
  if (opt.writeOutput) {
    BoltOutput h5;
    PetscCall(BoltOutputOpen(mesh, opt.outputDir, opt.outputName, &h5));
    if (opt.staticSolve) PetscCall(BoltOutputVertexField(&h5, mesh, u, "displacement"));
    PetscCall(BoltOutputVertexField(&h5, mesh, loads->load, "load"));
    if (loads->hasPreload) PetscCall(BoltOutputVertexField(&h5, mesh, loads->preload, "preload"));
    if (opt.fom) {
      PetscCall(BoltOutputVertexField(&h5, mesh, fomNm->q, "fom_final_displacement"));
      PetscCall(BoltOutputSeries(&h5, "/fom", "time", fomNm->nsteps + 1, fomNm->probeTime));
      PetscCall(BoltOutputSeries(&h5, "/fom", "probe", fomNm->nsteps + 1, fomNm->probeValue));
      PetscCall(BoltOutputSeries(&h5, "/fom", "energy", fomNm->nsteps + 1, fomNm->energy));
      if (fomNm->nsnap) PetscCall(BoltOutputSnapshots(&h5, mesh, fomNm->nsnap, fomNm->snap, fomNm->snapTime));
    }
    if (opt.rom) {
      PetscCall(BoltOutputSeries(&h5, "/rom", "time", romNm->nsteps + 1, romNm->probeTime));
      PetscCall(BoltOutputSeries(&h5, "/rom", "probe", romNm->nsteps + 1, romNm->probeValue));
      PetscCall(BoltOutputSeries(&h5, "/rom", "energy", romNm->nsteps + 1, romNm->energy));
    }
    if (opt.verifyFields) {
      PetscCall(BoltOutputVertexField(&h5, mesh, x, "x"));
      PetscCall(BoltOutputVertexField(&h5, mesh, Kx, "Kx"));
      PetscCall(BoltOutputVertexField(&h5, mesh, Mx, "Mx"));
    }
    PetscCall(BoltOutputClose(&h5, mesh));
    PetscCall(PetscPrintf(comm, "Wrote %s/%s.h5 and %s/%s.xmf (open the .xmf in ParaView)\n", opt.outputDir, opt.outputName, opt.outputDir, opt.outputName));
  }
  if (opt.summary[0]) {
    BoltJSON j;
    PetscCall(BoltJSONOpen(comm, opt.summary, &j));
    PetscCall(BoltJSONString(&j, "mesh", mesh->filename));
    PetscCall(BoltJSONInt(&j, "ranks", size));
    PetscCall(BoltJSONString(&j, "element", mesh->formulation == HEX8_FULL ? "full" : "incompatible"));
    PetscCall(BoltJSONString(&j, "partitioner", mesh->partitioner));
    PetscCall(BoltJSONInt(&j, "edge_cut", mesh->edgeCut));
    PetscCall(BoltJSONInt(&j, "nodes", mesh->nverticesGlobal));
    PetscCall(BoltJSONInt(&j, "elements", mesh->ncellsGlobal));
    PetscCall(BoltJSONInt(&j, "dofs", 3 * mesh->nverticesGlobal));
    PetscCall(BoltJSONInt(&j, "free_dofs", mesh->ndofsFree));
    PetscCall(BoltJSONInt(&j, "contact_dofs", contact->contactDofs));
    PetscCall(BoltJSONBeginObject(&j, "contact_dofs_per_pair"));
    for (PetscInt p = 0; p < contact->npairs; p++) PetscCall(BoltJSONInt(&j, contact->pairName[p], contact->contactDofsPerPair[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "contact_elements_per_pair"));
    for (PetscInt p = 0; p < contact->npairs; p++) PetscCall(BoltJSONInt(&j, contact->pairName[p], contact->elementsPerPair[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "contact_area_per_pair"));
    for (PetscInt p = 0; p < contact->npairs; p++) PetscCall(BoltJSONReal(&j, contact->pairName[p], contact->areaPerPair[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "elements_per_part"));
    for (PetscInt p = 0; p < mesh->nparts; p++) PetscCall(BoltJSONInt(&j, mesh->partName[p], asmb->elementsPerPart[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "mass_per_part"));
    for (PetscInt p = 0; p < mesh->nparts; p++) PetscCall(BoltJSONReal(&j, mesh->partName[p], asmb->massPerPart[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "volume_per_part"));
    for (PetscInt p = 0; p < mesh->nparts; p++) PetscCall(BoltJSONReal(&j, mesh->partName[p], asmb->volumePerPart[p]));
    PetscCall(BoltJSONEndObject(&j));
    PetscCall(BoltJSONBeginObject(&j, "material_per_part"));
    for (PetscInt p = 0; p < mesh->nparts; p++) PetscCall(BoltJSONString(&j, mesh->partName[p], mesh->materials.mat[mesh->partMaterial[p]].name));
    PetscCall(BoltJSONEndObject(&j));
    if (opt.staticSolve) {
      PetscCall(BoltJSONBeginObject(&j, "static"));
      PetscCall(BoltJSONReal(&j, "load_force", loads->loadForce));
      PetscCall(BoltJSONString(&j, "probe_group", loads->probeGroup));
      PetscCall(BoltJSONInt(&j, "probe_component", loads->probeComponent));
      PetscCall(BoltJSONRealArray(&j, "probe_coordinates", 3, loads->probeCoord));
      PetscCall(BoltJSONReal(&j, "probe_displacement", probe));
      PetscCall(BoltJSONReal(&j, "seconds", tStatic));
      PetscCall(BoltJSONEndObject(&j));
    }
    if (opt.nev > 0) {
      PetscCall(BoltJSONBeginObject(&j, "modal"));
      PetscCall(BoltJSONRealArray(&j, "frequencies_hz", nconv, freq));
      PetscCall(BoltJSONReal(&j, "seconds", tModal));
      PetscCall(BoltJSONEndObject(&j));
    }
    if (opt.checkRigid) {
      PetscCall(BoltJSONBeginObject(&j, "rigid_residual_per_part"));
      for (PetscInt p = 0; p < mesh->nparts; p++) PetscCall(BoltJSONReal(&j, mesh->partName[p], rigid[p]));
      PetscCall(BoltJSONEndObject(&j));
    }
    if (opt.fom) {
      PetscCall(BoltJSONBeginObject(&j, "preload"));
      PetscCall(BoltJSONReal(&j, "force", loads->preloadForce));
      PetscCall(BoltJSONReal(&j, "layer_force_scale", fomNm->preloadScale));
      PetscCall(BoltJSONReal(&j, "outer", fomNm->staticOuter));
      PetscCall(BoltJSONReal(&j, "inner", fomNm->staticInner));
      PetscCall(BoltJSONInt(&j, "factorizations", fomNm->staticFactorizations));
      PetscCall(BoltJSONInt(&j, "solves", fomNm->staticSolves));
      PetscCall(BoltJSONReal(&j, "penetration_max", staticPenetration));
      PetscCall(BoltJSONReal(&j, "multiplier_change", staticChange));
      PetscCall(BoltJSONReal(&j, "traction_normal_min", tractionStats[0]));
      PetscCall(BoltJSONReal(&j, "traction_normal_max", tractionStats[1]));
      PetscCall(BoltJSONReal(&j, "traction_tangential_max", tractionStats[2]));
      PetscCall(BoltJSONInt(&j, "active_points", preloadActive));
      PetscCall(BoltJSONBeginObject(&j, "normal_force_per_pair"));
      for (PetscInt p = 0; p < contact->npairs; p++) PetscCall(BoltJSONReal(&j, contact->pairName[p], preloadForce[p]));
      PetscCall(BoltJSONEndObject(&j));
      PetscCall(BoltJSONEndObject(&j));
      PetscCall(BoltJSONBeginObject(&j, "fom"));
      PetscCall(BoltJSONInt(&j, "steps", fomNm->nsteps));
      PetscCall(BoltJSONReal(&j, "dt", fomNm->dt));
      PetscCall(BoltJSONReal(&j, "online_s", fomNm->tOnline));
      PetscCall(BoltJSONReal(&j, "contact_stiffness_s", fomNm->dual->tContactStiffness));
      PetscCall(BoltJSONReal(&j, "displacements_s", fomNm->dual->tDisplacements));
      PetscCall(BoltJSONReal(&j, "contact_forces_s", fomNm->dual->tContactForces));
      PetscCall(BoltJSONInt(&j, "factorizations", fomNm->dual->factorizations));
      PetscCall(BoltJSONInt(&j, "solves", fomNm->dual->solves));
      PetscCall(BoltJSONInt(&j, "outer_total", fomNm->dual->outerTotal));
      PetscCall(BoltJSONInt(&j, "inner_total", fomNm->dual->innerTotal));
      PetscCall(BoltJSONInt(&j, "outer_max", fomNm->dual->outerMax));
      PetscCall(BoltJSONInt(&j, "inner_max", fomNm->dual->innerMax));
      PetscCall(BoltJSONInt(&j, "failures", fomNm->dual->failures));
      PetscCall(BoltJSONInt(&j, "cycles", fomNm->dual->cycles));
      PetscCall(BoltJSONInt(&j, "active_points", fomOp->state->nactive));
      PetscCall(BoltJSONInt(&j, "contact_points", contact->ngpGlobal));
      PetscCall(BoltJSONReal(&j, "probe_final", fomNm->probeValue[fomNm->nsteps]));
      {
        PetscReal mn = 0, mx = 0;
        for (PetscInt i = 0; i <= fomNm->nsteps; i++) {
          mn = PetscMin(mn, fomNm->probeValue[i]);
          mx = PetscMax(mx, fomNm->probeValue[i]);
        }
        PetscCall(BoltJSONReal(&j, "probe_min", mn));
        PetscCall(BoltJSONReal(&j, "probe_max", mx));
      }
      PetscCall(BoltJSONEndObject(&j));
    }
    if (opt.rom) {
      PetscCall(BoltJSONBeginObject(&j, "rom"));
      PetscCall(BoltJSONInt(&j, "dim", rom->n));
      PetscCall(BoltJSONInt(&j, "order", rom->order));
      PetscCall(BoltJSONReal(&j, "s0", rom->s0));
      PetscCall(BoltJSONInt(&j, "inputs", rom->ninputs));
      PetscCall(BoltJSONInt(&j, "n_ccm", rom->nCCM));
      PetscCall(BoltJSONInt(&j, "n_jim", rom->nJIM));
      PetscCall(BoltJSONString(&j, "source", rom->fromFile ? "file" : "built"));
      PetscCall(BoltJSONReal(&j, "offline_s", rom->tOffline));
      PetscCall(BoltJSONReal(&j, "offline_inputs_s", rom->tInputs));
      PetscCall(BoltJSONReal(&j, "offline_basis_s", rom->tBasis));
      PetscCall(BoltJSONReal(&j, "offline_factor_s", rom->tFactor));
      PetscCall(BoltJSONReal(&j, "offline_solves_s", rom->tSolve));
      PetscCall(BoltJSONReal(&j, "offline_orth_s", rom->tOrth));
      PetscCall(BoltJSONReal(&j, "offline_interface_s", rom->tInterface));
      PetscCall(BoltJSONReal(&j, "offline_projection_s", rom->tProject));
      PetscCall(BoltJSONString(&j, "contact_law", rom->augment ? "augmented" : "penalty"));
      PetscCall(BoltJSONInt(&j, "preload_state", rom->preloadState));
      PetscCall(BoltJSONReal(&j, "contact_penalty_scale", rom->penaltyScale));
      PetscCall(BoltJSONReal(&j, "contact_band_scale", rom->bandScale));
      PetscCall(BoltJSONInt(&j, "closed_krylov", rom->nClosed));
      PetscCall(BoltJSONInt(&j, "steps", romNm->nsteps));
      PetscCall(BoltJSONReal(&j, "online_s", romNm->tOnline));
      PetscCall(BoltJSONReal(&j, "contact_stiffness_s", romNm->dual->tContactStiffness));
      PetscCall(BoltJSONReal(&j, "displacements_s", romNm->dual->tDisplacements));
      PetscCall(BoltJSONReal(&j, "contact_forces_s", romNm->dual->tContactForces));
      PetscCall(BoltJSONInt(&j, "factorizations", romNm->dual->factorizations));
      PetscCall(BoltJSONInt(&j, "solves", romNm->dual->solves));
      PetscCall(BoltJSONInt(&j, "outer_total", romNm->dual->outerTotal));
      PetscCall(BoltJSONInt(&j, "inner_total", romNm->dual->innerTotal));
      PetscCall(BoltJSONInt(&j, "failures", romNm->dual->failures));
      PetscCall(BoltJSONInt(&j, "cycles", romNm->dual->cycles));
      PetscCall(BoltJSONReal(&j, "probe_final", romNm->probeValue[romNm->nsteps]));
      if (opt.romCheckS0) PetscCall(BoltJSONReal(&j, "check_s0_error", romCheckError));
      if (rom->orthogonality >= 0) PetscCall(BoltJSONReal(&j, "orthogonality", rom->orthogonality));
      PetscCall(BoltJSONEndObject(&j));
      if (opt.fom) {
        PetscCall(BoltJSONReal(&j, "speedup", fomNm->tOnline / romNm->tOnline));
        PetscCall(BoltJSONBeginObject(&j, "errors"));
        PetscCall(BoltJSONBeginObject(&j, loads->probeGroup));
        PetscCall(BoltJSONReal(&j, "e_L2", errL2));
        PetscCall(BoltJSONReal(&j, "e_mean", errMean));
        PetscCall(BoltJSONEndObject(&j));
        PetscCall(BoltJSONEndObject(&j));
      }
    }
    PetscCall(BoltJSONReal(&j, "setup_s", tSetUp));
    PetscCall(BoltJSONClose(&j));
  }
  PetscCall(PetscLogStagePop());

  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&Kx));
  PetscCall(VecDestroy(&Mx));
  PetscCall(MatDestroy(&Ktied));
  PetscCall(BoltNewmarkDestroy(&fomNm));
  PetscCall(BoltPreloadStateDestroy(&fomPreload));
  PetscCall(BoltNewmarkDestroy(&romNm));
  PetscCall(BoltOperatorDestroy(&romOp));
  PetscCall(BoltROMDestroy(&rom));
  PetscCall(BoltOperatorDestroy(&fomOp));
  PetscCall(BoltLoadSetDestroy(&loads));
  PetscCall(BoltContactSetDestroy(&contact));
  PetscCall(BoltAssemblerDestroy(&asmb));
  PetscCall(BoltMeshDestroy(&mesh));
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
  for (int i = 0; i < argc; i++) {
    if (!strcmp(argv[i], "-options_file") && i + 1 < argc && nscenes < 16) scenes[nscenes++] = argv[++i];
    else args[nargs++] = argv[i];
  }
  args[nargs] = NULL;
  PetscCall(SlepcInitialize(&nargs, &args, NULL, help));
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
  ierr = BoltRun();
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
