/* A run: what it does and where it writes (main's options), and its stages once the model is set
   up: the tied joint's analyses, the full-order model, the reduced-order model. */
#include "private/app.h"

PetscErrorCode BoltRunOptionsSetFromOptions(MPI_Comm comm, BoltRunOptions *o)
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
  o->fomUpdateRank = -1;
  o->fom          = PETSC_FALSE;
  o->rom          = PETSC_FALSE;
  o->exportDir[0] = '\0';
  o->verifyField  = 0;
  o->modalContact = BOLT_MODAL_TIED;
  PetscOptionsBegin(comm, NULL, "Run", "boltrom");
  PetscCall(PetscOptionsString("-output_dir", "Folder for the HDF5/XDMF results (created if needed)", NULL, o->outputDir, o->outputDir, sizeof(o->outputDir), NULL));
  PetscCall(PetscOptionsString("-output_name", "Base name of the HDF5/XDMF files", NULL, o->outputName, o->outputName, sizeof(o->outputName), NULL));
  PetscCall(PetscOptionsBool("-output", "Write the HDF5/XDMF results", NULL, o->writeOutput, &o->writeOutput, NULL));
  PetscCall(PetscOptionsString("-summary", "Write a JSON summary to this file (its keys: docs/outputs.md)", NULL, o->summary, o->summary, sizeof(o->summary), NULL));
  PetscCall(PetscOptionsBool("-static", "Solve the tied joint (all contact elements active) under the load", NULL, o->staticSolve, &o->staticSolve, NULL));
  PetscCall(PetscOptionsBool("-fom", "Run the full-order model with contact: static preload, then the Newmark transient", NULL, o->fom, &o->fom, NULL));
  PetscCall(PetscOptionsInt("-fom_update_rank", "Transient FOM: largest rank of a low-rank update of its factorisation before a state change is factorised afresh (-1: from its flops; 0: always)", NULL, o->fomUpdateRank, &o->fomUpdateRank, NULL));
  PetscCall(PetscOptionsBool("-rom", "Run the reduced-order model: offline reduction (or a matching -rom_file), static preload, Newmark transient", NULL, o->rom, &o->rom, NULL));
  PetscCall(PetscOptionsString("-export_matrices", "Folder for K_tied.petsc and M.petsc (with -rom also rom_K_tied.petsc, rom_M.petsc), PETSc binary; read by python/compare_eigen.py", NULL, o->exportDir, o->exportDir, sizeof(o->exportDir), NULL));
  PetscCall(PetscOptionsInt("-modal_nev", "Number of eigenfrequencies (0: none), of the joint in the state -modal_contact", NULL, o->nev, &o->nev, NULL));
  {
    const char *states[] = {"tied", "preload"};
    PetscCall(PetscOptionsEList("-modal_contact", "Modes of the tied joint (every contact element active) or about the FOM's preload (open pairs carry nothing, slipping ones no shear)", NULL, states, 2, states[o->modalContact], &o->modalContact, NULL));
  }
  PetscCall(PetscOptionsBool("-verify_fields", "Also write K x and M x for a fixed smooth field x (checks across rank counts)", NULL, o->verifyFields, &o->verifyFields, NULL));
  {
    const char *kinds[] = {"smooth", "linear"};
    PetscCall(PetscOptionsEList("-verify_field", "The field x of -verify_fields: smooth (sines) or linear (patch test: K x vanishes at interior nodes)", NULL, kinds, 2, kinds[o->verifyField], &o->verifyField, NULL));
  }
  PetscCall(PetscOptionsBool("-check_rigid", "Check K r = 0 for the six rigid motions of every part (use with -clamp false)", NULL, o->checkRigid, &o->checkRigid, NULL));
  PetscOptionsEnd();
  PetscCheck(o->fomUpdateRank >= -1, comm, PETSC_ERR_USER_INPUT, "-fom_update_rank must be >= 0, or -1 to size it from the factorisation (got %" PetscInt_FMT ")", o->fomUpdateRank);
  PetscCheck(o->nev >= 0 && o->nev <= 100, comm, PETSC_ERR_USER_INPUT, "-modal_nev must be in [0, 100] (got %" PetscInt_FMT ")", o->nev);
  PetscFunctionReturn(0);
}

/* A model's time integrator, set up (checkpoints beside the results unless -checkpoint_file). */
static PetscErrorCode BoltRunNewmarkCreate(BoltRun *r, BoltOperator *op, BoltNewmark **nm)
{
  char name[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(BoltOperatorView(op, PETSC_VIEWER_STDOUT_(r->comm)));
  PetscCall(BoltNewmarkCreate(op, nm));
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/%s", r->opt.outputDir, r->opt.outputName));
  PetscCall(BoltNewmarkSetCheckpointBase(*nm, name));
  PetscCall(BoltNewmarkSetFromOptions(*nm));
  PetscCall(BoltNewmarkSetPreloadTarget(*nm, BoltLoadSetHasPreload(r->loads) ? BoltLoadSetPreloadForce(r->loads) : 0));
  PetscCall(BoltNewmarkSetUp(*nm));
  PetscFunctionReturn(0);
}

/* A free model's rigid motions, made the first time an analysis asks and shared by the tied
   analyses and the FOM; NULL for a held model. */
static PetscErrorCode BoltRunRigidModes(BoltRun *r, BV *R)
{
  PetscFunctionBeginUser;
  if (BoltMeshIsFree(r->mesh) && !r->rigid) PetscCall(BoltAssemblerRigidModes(r->asmb, &r->rigid));
  *R = r->rigid;
  PetscFunctionReturn(0);
}

/* The nev lowest eigenfrequencies of K (the tied joint's, or linearised about the preload), a free
   model's rigid motions deflated; printed with the contact state they are about. */
static PetscErrorCode BoltRunModal(BoltRun *r, Mat K, BV R)
{
  BoltSummary   *s       = &r->sum;
  const PetscBool preload = (PetscBool)(r->opt.modalContact == BOLT_MODAL_PRELOAD);
  PetscLogDouble ts, te;
  Mat            M;

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMatrices(r->asmb, NULL, &M));
  PetscCall(PetscLogStagePush(BOLT_STAGE_MODAL));
  PetscCall(PetscTime(&ts));
  PetscCall(BoltModalSolve(K, M, R, preload, r->opt.nev, "modal_", &s->nconv, s->freq));
  if (R) PetscCall(BoltRigidFrequencies(R, K, s->rigidFreq));
  PetscCall(PetscTime(&te));
  s->tModal = te - ts;
  PetscCall(PetscLogStagePop());
  if (preload) PetscCall(PetscPrintf(r->comm, "Eigenfrequencies (about the preload: %" PetscInt_FMT " of %" PetscInt_FMT " contact points closed, %" PetscInt_FMT " of them stuck%s) [Hz]:", s->modalPoints[0], s->modalPoints[2], s->modalPoints[1], R ? "; free-free: the 6 rigid-body modes apart" : ""));
  else PetscCall(PetscPrintf(r->comm, R ? "Eigenfrequencies (tied, free-free: the 6 rigid-body modes apart) [Hz]:" : "Eigenfrequencies (tied) [Hz]:"));
  for (PetscInt i = 0; i < s->nconv; i++) PetscCall(PetscPrintf(r->comm, " %.6f", (double)s->freq[i]));
  PetscCall(PetscPrintf(r->comm, " (%.2f s)\n", (double)s->tModal));
  if (R) PetscCall(PetscPrintf(r->comm, "  rigid-body modes under K (should be 0) [Hz]: largest %.3e\n", (double)s->rigidFreq[5]));
  s->freeFree = (PetscBool)(R != NULL);
  PetscFunctionReturn(0);
}

/* The tied joint (every contact element active with its penalty stiffness): static solve,
   eigenfrequencies, and the checks and exports of the assembled model. */
PetscErrorCode BoltRunTied(BoltRun *r)
{
  BoltSummary   *s = &r->sum;
  PetscLogDouble ts, te;
  Mat            K, M;
  BV             R = NULL; /* a free model's rigid motions: inertia relief, deflated modes */

  PetscFunctionBeginUser;
  PetscCall(BoltAssemblerGetMatrices(r->asmb, &K, &M));
  if (r->opt.staticSolve || (r->opt.nev > 0 && r->opt.modalContact == BOLT_MODAL_TIED)) PetscCall(BoltRunRigidModes(r, &R));
  if (BoltContactSetPairCount(r->contact)) PetscCall(BoltContactSetAssembleTied(r->contact, K, &r->Ktied));
  else {
    PetscCall(PetscObjectReference((PetscObject)K));
    r->Ktied = K;
  }
  if (r->opt.staticSolve) {
    PetscCall(PetscLogStagePush(BOLT_STAGE_STATIC));
    PetscCall(PetscTime(&ts));
    if (R) PetscCall(BoltStaticSolveFree(r->Ktied, M, R, BoltLoadSetLoad(r->loads), r->u, "static_", &s->staticPasses));
    else PetscCall(BoltStaticSolve(r->Ktied, BoltLoadSetLoad(r->loads), r->u, "static_"));
    PetscCall(PetscTime(&te));
    s->tStatic = te - ts;
    PetscCall(BoltLoadSetProbe(r->loads, r->u, &s->probe));
    PetscCall(PetscLogStagePop());
    if (R) PetscCall(PetscPrintf(r->comm, "Static (tied, free-free): inertia relief, the rigid-body motion taken out (%" PetscInt_FMT " shifted solves)\n", s->staticPasses));
    PetscCall(PetscPrintf(r->comm, "Static (tied): probe u_%c at '%s' = %.10e m under %g N (%.2f s)\n", "xyz"[BoltLoadSetProbeComponent(r->loads)], BoltLoadSetProbeGroup(r->loads), (double)s->probe, (double)BoltLoadSetLoadForce(r->loads), (double)s->tStatic));
  }
  if (r->opt.exportDir[0]) PetscCall(BoltExportTied(r->opt.exportDir, r->Ktied, M));
  if (r->opt.nev > 0 && r->opt.modalContact == BOLT_MODAL_TIED) PetscCall(BoltRunModal(r, r->Ktied, R));
  if (r->opt.verifyFields) PetscCall(BoltVerifyFields(r->mesh, r->Ktied, M, r->u, r->opt.verifyField, &s->x, &s->Kx, &s->Mx));
  if (r->opt.checkRigid) PetscCall(BoltCheckRigid(r->asmb, r->u, s->rigid));
  s->freeFree = (PetscBool)(s->freeFree || R != NULL);
  PetscFunctionReturn(0);
}

/* The modes linearised about the FOM's preloaded contact state (-modal_contact preload). */
static PetscErrorCode BoltRunPreloadModal(BoltRun *r)
{
  Mat K, Kpre;
  BV  R;

  PetscFunctionBeginUser;
  PetscCall(BoltRunRigidModes(r, &R));
  PetscCall(BoltAssemblerGetMatrices(r->asmb, &K, NULL));
  PetscCall(BoltContactStateAssembleLinearised(BoltOperatorState(r->fomOp), K, &Kpre, r->sum.modalPoints));
  PetscCall(BoltRunModal(r, Kpre, R));
  PetscCall(MatDestroy(&Kpre));
  PetscFunctionReturn(0);
}

/* The full-order model with contact: static preload, the modes about it (-modal_contact preload),
   then the transient (-fom; without it the preload is solved for the modes alone). */
PetscErrorCode BoltRunFOM(BoltRun *r)
{
  BoltContactSet *contact = r->contact;
  BoltSummary    *s       = &r->sum;

  PetscFunctionBeginUser;
  PetscCall(BoltFOMCreate(r->asmb, contact, r->loads, r->opt.fom, &r->fomOp));
  PetscCall(BoltFOMUpdateCreate(r->fomOp, r->opt.fomUpdateRank));
  PetscCall(BoltRunNewmarkCreate(r, r->fomOp, &r->fomNm));
  PetscCall(BoltNewmarkSetBolts(r->fomNm, r->loads));
  {
    BV R;
    PetscCall(BoltRunRigidModes(r, &R));
    if (R) PetscCall(BoltNewmarkSetRigidModes(r->fomNm, R));
  }
  PetscCall(PetscLogStagePush(BOLT_STAGE_PRELOAD));
  PetscCall(BoltNewmarkPreload(r->fomNm));
  PetscCall(PetscLogStagePop());
  PetscCall(BoltContactStateNormalForcePerPair(BoltOperatorState(r->fomOp), s->preloadForce));
  {
    PetscReal outer, inner;
    PetscCall(BoltNewmarkGetStaticSolve(r->fomNm, &outer, &inner));
    PetscCall(PetscPrintf(r->comm, "Preload %g N: static contact solve in %" PetscInt_FMT " outer / %" PetscInt_FMT " inner iterations\n", (double)BoltLoadSetPreloadForce(r->loads), (PetscInt)outer, (PetscInt)inner));
  }
  if (BoltContactSetPairCount(contact) <= 6) { /* a line each would be long for many pairs: then their range (the summary has each) */
    PetscCall(PetscPrintf(r->comm, "  normal force per pair [N]:"));
    for (PetscInt p = 0; p < BoltContactSetPairCount(contact); p++) PetscCall(PetscPrintf(r->comm, " %s %.1f", BoltContactSetPairName(contact, p), (double)s->preloadForce[p]));
    PetscCall(PetscPrintf(r->comm, "\n"));
  } else {
    PetscReal lo = PETSC_MAX_REAL, hi = PETSC_MIN_REAL;
    for (PetscInt p = 0; p < BoltContactSetPairCount(contact); p++) {
      lo = PetscMin(lo, s->preloadForce[p]);
      hi = PetscMax(hi, s->preloadForce[p]);
    }
    PetscCall(PetscPrintf(r->comm, "  normal force of the %" PetscInt_FMT " pairs from %.1f to %.1f N (each in the summary)\n", BoltContactSetPairCount(contact), (double)lo, (double)hi));
  }
  PetscCall(BoltMemoryPrint(r->comm, "the FOM's preload"));
  PetscCall(BoltContactStateTractionStats(BoltOperatorState(r->fomOp), &s->tractionStats[0], &s->tractionStats[1], &s->tractionStats[2]));
  s->preloadActive      = BoltContactStateActiveCount(BoltOperatorState(r->fomOp));
  PetscCall(BoltContactStateCountReclosed(BoltOperatorState(r->fomOp), &s->preloadSliding, NULL));
  {
    BoltDual *dual;
    Vec       q;
    PetscReal outer, inner;
    PetscCall(BoltNewmarkGetModel(r->fomNm, NULL, &dual, &q));
    PetscCall(BoltNewmarkGetStaticSolve(r->fomNm, &outer, &inner));
    PetscCall(BoltDualGetLastConvergence(dual, &s->preloadPenetration, &s->preloadChange));
    if (r->opt.rom && r->opt.fom) PetscCall(BoltPreloadStateCreate(r->fomOp, q, outer, inner, &r->fomPreload)); /* the ROM's offline phase starts from it */
    if (BoltLoadSetHasPreload(r->loads) && !BoltLoadSetBoltCount(r->loads)) { /* the clamp force read from the stud, not from the contact forces */
      Mat K;
      PetscCall(BoltAssemblerGetMatrices(r->asmb, &K, NULL));
      PetscCall(BoltLoadSetStudTension(r->loads, 0, K, q, BoltOperatorPreloadVec(r->fomOp), &s->studTension, &s->hasStud));
      if (s->hasStud) PetscCall(PetscPrintf(r->comm, "  stud tension beyond the preload layers: %.1f N\n", (double)s->studTension));
    }
  }
  s->preloadRun = r->fomNm;
  if (r->opt.nev > 0 && r->opt.modalContact == BOLT_MODAL_PRELOAD) PetscCall(BoltRunPreloadModal(r));
  if (!r->opt.fom) { /* solved for the modes alone: no transient, and the ROM must not take it for a FOM run */
    PetscCall(BoltNewmarkReleaseSolver(r->fomNm));
    PetscFunctionReturn(0);
  }
  if (r->opt.rom && BoltROMIsTrained(r->rom)) BoltNewmarkTrackChanges(r->fomNm); /* what -rom_train learns */
  PetscCall(PetscLogStagePush(BOLT_STAGE_TRANSIENT));
  PetscCall(BoltNewmarkRun(r->fomNm));
  PetscCall(PetscLogStagePop());
  PetscCall(BoltNewmarkView(r->fomNm, PETSC_VIEWER_STDOUT_(r->comm)));
  /* at 562k DOFs the FOM's factorisation and the offline phase's two would not fit in memory together */
  PetscCall(BoltNewmarkReleaseSolver(r->fomNm));
  PetscCall(BoltFOMUpdateCreate(r->fomOp, 0)); /* and the columns its low-rank updates kept */
  PetscCall(BoltOperatorReleaseDamping(r->fomOp)); /* the FOM has run: its damping is not needed any more */
  PetscCall(BoltMemoryRelease());
  PetscCall(BoltMemoryPrint(r->comm, "the FOM run (its solver released)"));
  s->fomRun = r->fomNm;
  PetscFunctionReturn(0);
}

/* Several bolts: each bolt's clamp force read from its stud in the ROM's preloaded state, V q
   with the FOM's calibrated layer forces, against the FOM's: the ROM's preload is driven by
   those forces and must clamp as the FOM's does. Needs the FOM's run and the whole basis. */
static PetscErrorCode BoltRunROMStudTensions(BoltRun *r)
{
  BoltSummary *s = &r->sum;
  PetscBool    whole = PETSC_FALSE, stud;
  Vec          q, u;
  Mat          K;

  PetscFunctionBeginUser;
  if (!BoltLoadSetBoltCount(r->loads) || !r->fomOp) PetscFunctionReturn(0);
  PetscCall(BoltROMBasisEnsure(r->rom, r->mesh, BoltLoadSetLoad(r->loads), &whole));
  if (!whole) PetscFunctionReturn(0);
  PetscCall(BoltNewmarkGetModel(r->romNm, NULL, NULL, &q));
  PetscCall(BoltAssemblerGetMatrices(r->asmb, &K, NULL));
  PetscCall(VecDuplicate(BoltLoadSetLoad(r->loads), &u));
  PetscCall(BoltROMExpand(r->rom, q, u));
  PetscCall(PetscPrintf(r->comm, "ROM: clamp force read from each stud in its preloaded state [N]:"));
  for (PetscInt b = 0; b < BoltLoadSetBoltCount(r->loads); b++) {
    PetscCall(BoltLoadSetStudTension(r->loads, b, K, u, BoltOperatorPreloadVec(r->fomOp), &s->romStudTension[b], &stud));
    PetscCall(PetscPrintf(r->comm, " %s %.1f", BoltLoadSetBoltName(r->loads, b), (double)s->romStudTension[b]));
  }
  PetscCall(PetscPrintf(r->comm, "\n"));
  s->romBolts = BoltLoadSetBoltCount(r->loads);
  PetscCall(VecDestroy(&u));
  PetscFunctionReturn(0);
}

/* The reduced-order model: offline reduction (or a matching ROM file), static preload, transient,
   and its errors against the FOM's run if there is one. */
PetscErrorCode BoltRunROM(BoltRun *r)
{
  BoltSummary *s = &r->sum;

  PetscFunctionBeginUser;
  /* the FOM's preloaded state, snapshots (for -rom_snapshot_modes) and changed points (for
     -rom_train), if it ran */
  {
    PetscInt         nsnap   = 0;
    Vec             *snap    = NULL;
    const PetscBool *changed = NULL;
    if (s->fomRun) PetscCall(BoltNewmarkGetSnapshots(s->fomRun, &nsnap, &snap, NULL, NULL));
    if (s->fomRun) PetscCall(BoltNewmarkGetChangedPoints(s->fomRun, &changed));
    PetscCall(BoltROMSetTraining(r->rom, r->fomPreload, nsnap, snap, changed));
  }
  PetscCall(BoltROMSetUp(r->rom, r->asmb, r->contact, r->loads));
  PetscCall(BoltPreloadStateDestroy(&r->fomPreload));
  PetscCall(BoltROMOperatorCreate(r->rom, &r->romOp));
  if (!r->opt.writeOutput && !BoltLoadSetBoltCount(r->loads)) PetscCall(BoltROMReleaseBasis(r->rom)); /* kept only for the output's V q (and the bolts' stud tensions) */
  if (BoltROMVerifies(r->rom)) PetscCall(BoltROMCheckAtS0(r->rom, r->romOp, r->asmb, r->contact, r->loads, &s->romCheckError));
  if (r->opt.exportDir[0]) PetscCall(BoltExportReduced(r->opt.exportDir, r->rom, r->romOp));
  PetscCall(BoltRunNewmarkCreate(r, r->romOp, &r->romNm));
  PetscCall(BoltROMSetPreloadState(r->rom, r->romNm, BoltLoadSetPreloadForce(r->loads)));
  PetscCall(PetscLogStagePush(BOLT_STAGE_PRELOAD));
  PetscCall(BoltNewmarkPreload(r->romNm));
  PetscCall(PetscLogStagePop());
  PetscCall(BoltRunROMStudTensions(r));
  PetscCall(PetscLogStagePush(BOLT_STAGE_TRANSIENT));
  PetscCall(BoltNewmarkRun(r->romNm));
  PetscCall(PetscLogStagePop());
  PetscCall(BoltNewmarkView(r->romNm, PETSC_VIEWER_STDOUT_(r->comm)));
  if (s->fomRun) {
    const PetscReal *pf, *pr;
    PetscInt         n;
    PetscReal        tf, tr;
    PetscCall(BoltNewmarkGetHistory(r->fomNm, BOLT_HISTORY_PROBE, &n, &pf));
    PetscCall(BoltNewmarkGetHistory(r->romNm, BOLT_HISTORY_PROBE, NULL, &pr));
    PetscCall(BoltNewmarkGetTiming(r->fomNm, NULL, &tf));
    PetscCall(BoltNewmarkGetTiming(r->romNm, NULL, &tr));
    PetscCall(BoltHistoryErrors(n + 1, pf, pr, &s->errL2, &s->errMean));
    PetscCall(PetscPrintf(r->comm, "ROM against FOM at '%s': e_L2 %.4e, mean relative error %.4e; speedup (online) %.1f\n", BoltLoadSetProbeGroup(r->loads), (double)s->errL2, (double)s->errMean, (double)(tf / tr)));
  }
  s->rom    = r->rom;
  s->romRun = r->romNm;
  PetscFunctionReturn(0);
}
