/* The ROM's life cycle. Create; SetFromOptions reads the reduction's options (-rom_*), the
   Krylov basis's (-krylov_*) and those of the offline solvers once, at the start of every run
   whatever -rom says (a scene file may carry the ROM's settings while the ROM is switched off),
   so that a wrong one stops the run before any computation; SetUp resolves every default and
   builds the ROM (reduction.c) or reads a matching ROM file (rom_file.c); View prints the
   settings used; Destroy frees it all. The online operator (rom.c) owns its caches. */
#include "private/rom.h"

PetscErrorCode BoltROMCreate(MPI_Comm comm, BoltROM **romp)
{
  BoltROM *rom;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&rom));
  rom->comm     = comm;
  rom->opt.comm = comm;
  PetscCall(BoltKrylovCreate(comm, &rom->opt.krylov));
  *romp = rom;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMSetFromOptions(BoltROM *rom)
{
  MPI_Comm              comm = rom->comm;
  BoltReductionOptions *o    = &rom->opt;

  PetscFunctionBeginUser;
  o->file[0]     = '\0';
  o->rebuildFile[0] = '\0';
  o->extraInputs = PETSC_FALSE;
  o->nCCM = o->nJIM = 100; /* the paper's */
  o->fomPreload = NULL;
  o->nFomSnapshots = 0;
  o->fomSnapshots  = NULL;
  rom->view     = PETSC_FALSE;
  PetscOptionsBegin(comm, NULL, "Reduction", "boltrom");
  PetscCall(PetscOptionsString("-rom_file", "ROM file (HDF5) to reuse if it matches, or to write", NULL, o->file, o->file, sizeof(o->file), NULL));
  PetscCall(PetscOptionsInt("-rom_n_ccm", "Interface reduction: characteristic constraint mode vectors (0 and -rom_n_jim 0: no interface reduction)", NULL, o->nCCM, &o->nCCM, NULL));
  PetscCall(PetscOptionsInt("-rom_n_jim", "Interface reduction: joint interface mode vectors", NULL, o->nJIM, &o->nJIM, NULL));
  {
    PetscBool set;
    PetscCall(PetscOptionsString("-rom_rebuild", "If -rom_file does not match the scene or is damaged, build the ROM into this file (the same name overwrites it); else such a file is refused, kept as it is", NULL, o->rebuildFile, o->rebuildFile, sizeof(o->rebuildFile), &set));
    /* (once a bool: a ROM file is no longer overwritten unless a file name says so) */
    PetscCheck(!set || (o->rebuildFile[0] && strcmp(o->rebuildFile, "true") && strcmp(o->rebuildFile, "false") && strcmp(o->rebuildFile, "1") && strcmp(o->rebuildFile, "0")), comm, PETSC_ERR_USER_INPUT, "-rom_rebuild takes the file to build the ROM into (got '%s'), e.g. -rom_rebuild new.rom.h5; the same name as -rom_file overwrites that file", o->rebuildFile);
    /* it replaces a -rom_file: with none it would be ignored without a word */
    PetscCheck(!set || o->file[0], comm, PETSC_ERR_USER_INPUT, "-rom_rebuild %s replaces a -rom_file that does not match the scene, but -rom_file is empty: give -rom_file %s to build the ROM into that file", o->rebuildFile, o->rebuildFile);
  }
  {
    char      from[16] = "auto";
    PetscBool set;
    PetscCall(PetscOptionsString("-rom_train", "auto: tied if static solves at -/+ 2x the load change no pair, else none; none: the paper's ROM; fom: free where the FOM changes, static: where those solves do", NULL, from, from, sizeof(from), &set));
    o->trainAuto = PETSC_TRUE;
    if (set && strcmp(from, "auto")) {
      PetscBool fom = (PetscBool)(!from[0] || !strcmp(from, "fom")), off = (PetscBool)!strcmp(from, "none");
      if (!fom && !off && strcmp(from, "static")) { /* as a bool, as it once was */
        PetscCall(PetscStrcasecmp(from, "true", &fom));
        for (const char *const *t = (const char *const[]){"1", "yes", "on", NULL}; *t && !fom; t++) PetscCall(PetscStrcasecmp(from, *t, &fom));
        for (const char *const *f = (const char *const[]){"false", "0", "no", "off", NULL}; *f && !off; f++) PetscCall(PetscStrcasecmp(from, *f, &off));
      }
      o->trainStatic = (PetscBool)!strcmp(from, "static");
      PetscCheck(fom || o->trainStatic || off, comm, PETSC_ERR_USER_INPUT, "-rom_train %s: give auto (the default), none (the paper's ROM), fom (learn from this run's FOM) or static (from static solves at -/+ 2 x the load)", from);
      o->trained   = (PetscBool)(fom || o->trainStatic);
      o->trainAuto = PETSC_FALSE;
    }
  }
  PetscCall(PetscOptionsBool("-rom_allow_foreign_load", "Run a load that is not an input of the ROM (the paper's reuse experiment)", NULL, o->extraInputs, &o->extraInputs, NULL));
  /* Fixed settings of the construction, not options: docs/decisions.md gives the measurement
     behind each ("The construction's fixed settings"). */
  o->nClosed            = 3;
  o->openingScale       = 2;    /* the strict law's; resolved by the law when the ROM is built */
  o->slipScale          = 4;
  o->slipScalePeriodic  = 16;
  o->nOpenKrylov        = 3;
  o->snapshotTol        = 1e-6;
  o->coneShapes = 0;
  PetscCall(PetscOptionsReal("-rom_cone_shapes", "Friction: node pairs at this fraction of the cone in the preloaded state get shapes (normal and traction); 0: none", NULL, o->coneShapes, &o->coneShapes, NULL));
  o->coneTraction = PETSC_TRUE;
  PetscCall(PetscOptionsBool("-rom_cone_traction", "With -rom_cone_shapes: a shape along each pair's tangential traction as well as along its normal (false: the normal only, one shape per pair)", NULL, o->coneTraction, &o->coneTraction, NULL));
  o->coneModes = 0;
  PetscCall(PetscOptionsInt("-rom_cone_modes", "With -rom_cone_shapes and -rom_snapshot_modes: this many shapes per direction from the training run's patterns; 0: one per pair", NULL, o->coneModes, &o->coneModes, NULL));
  o->nSnapshotModes = 0;
  PetscCall(PetscOptionsInt("-rom_snapshot_modes", "Append at most this many POD modes of the FOM's snapshots of the same run (-fom true -snapshot_every k) to the basis; 0: none", NULL, o->nSnapshotModes, &o->nSnapshotModes, NULL));
  /* The checks of a run against itself: the basis's orthogonality, the FOM at s0, and the online
     shortcuts (low-rank updates, only the gaps a decision reads) replaced by the plain way, which
     must give the same history. */
  o->verify = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-rom_verify", "Check the ROM: orthogonality of its basis, the FOM at s0, and online every gap at every solve and a refactorisation at every change (same history, slower)", NULL, o->verify, &o->verify, NULL));
  PetscCall(PetscOptionsBool("-rom_view", "Print the reduction's settings before the offline phase", NULL, rom->view, &rom->view, NULL));
  PetscOptionsEnd();
  PetscCheck(o->coneShapes >= 0 && o->coneShapes <= 1, comm, PETSC_ERR_USER_INPUT, "-rom_cone_shapes must be within [0, 1], a fraction of the friction cone (got %g)", (double)o->coneShapes);
  PetscCheck(o->coneModes >= 0, comm, PETSC_ERR_USER_INPUT, "-rom_cone_modes must be >= 0 (got %" PetscInt_FMT ")", o->coneModes);
  PetscCheck(o->nSnapshotModes >= 0, comm, PETSC_ERR_USER_INPUT, "-rom_snapshot_modes must be >= 0 (got %" PetscInt_FMT ")", o->nSnapshotModes);
  PetscCheck(o->nCCM >= 0 && o->nJIM >= 0, comm, PETSC_ERR_USER_INPUT, "-rom_n_ccm and -rom_n_jim must be >= 0");
  PetscCall(BoltKrylovSetFromOptions(o->krylov));
  PetscFunctionReturn(0);
}

/* The offline phase's solvers and basis vectors read their options (PETSc's and SLEPc's), made
   later from the model: Kt's factorisation (krylov_), the interface reduction's two (ir_,
   ir_interior_), the input block (BV, no prefix). */
PetscErrorCode BoltROMSolversSetFromOptions(BoltROM *rom)
{
  MPI_Comm comm = rom->comm;

  PetscFunctionBeginUser;
  PetscCall(BoltDirectSolverSetFromOptions(comm, "krylov_", PETSC_TRUE, MATSOLVERMUMPS));
  PetscCall(BoltDirectSolverSetFromOptions(comm, "ir_", PETSC_TRUE, MATSOLVERMUMPS));
  PetscCall(BoltDirectSolverSetFromOptions(comm, "ir_interior_", PETSC_TRUE, MATSOLVERMUMPS));
  {
    BV bv;
    PetscCall(BVCreate(comm, &bv));
    PetscCall(BVSetFromOptions(bv));
    PetscCall(BVDestroy(&bv));
  }
  PetscFunctionReturn(0);
}

/* The cross-checks of the ROM's options that need the contact law, made before any computation. */
PetscErrorCode BoltROMCheckOptions(BoltROM *rom, BoltContactSet *contact)
{
  BoltReductionOptions *o = &rom->opt;

  PetscFunctionBeginUser;
  PetscCheck(o->coneShapes == 0 || BoltContactSetHasFriction(contact), rom->comm, PETSC_ERR_USER_INPUT, "-rom_cone_shapes needs a frictional law: add -contact_law coulomb (the %s law has no cone)", BoltContactSetLawType(contact));
  PetscCheck(o->coneModes == 0 || (o->coneShapes > 0 && o->nSnapshotModes > 0), rom->comm, PETSC_ERR_USER_INPUT, "-rom_cone_modes compresses cone shapes with a training run's snapshots: add -rom_cone_shapes r and -rom_snapshot_modes k");
  PetscFunctionReturn(0);
}

/* Whether the scene's load is periodic: its slip shapes then reach further (docs/decisions.md). */
PetscErrorCode BoltROMSetPeriodicLoad(BoltROM *rom, PetscBool periodic)
{
  PetscFunctionBeginUser;
  rom->opt.periodicLoad = periodic;
  PetscFunctionReturn(0);
}

/* What the FOM of this run hands the offline phase, or NULL and 0: its preloaded state (else
   solved offline), its displacement snapshots (for -rom_snapshot_modes) and, per local contact
   point, whether its state left the preloaded one (for -rom_train). Referenced until SetUp
   returns. */
PetscErrorCode BoltROMSetTraining(BoltROM *rom, const BoltPreloadState *fomPreload, PetscInt nsnap, Vec snap[], const PetscBool changed[])
{
  PetscFunctionBeginUser;
  rom->opt.fomPreload    = fomPreload;
  rom->opt.nFomSnapshots = nsnap;
  rom->opt.fomSnapshots  = snap;
  rom->opt.fomChanged    = changed;
  PetscFunctionReturn(0);
}

/* Resolves every default from the options, the scene and (for the online settings) the basis,
   then builds the ROM or reads a matching -rom_file. */
PetscErrorCode BoltROMSetUp(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads)
{
  PetscLogDouble t0;
  PetscBool      reused = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(ROMResolveSettings(rom, asmb, contact, loads));
  if (rom->opt.file[0]) PetscCall(ROMReuseFile(rom, contact, loads, t0, &reused));
  if (reused && rom->autoTied) PetscCall(ROMSwitchTied(rom, asmb, contact, loads)); /* a file auto made tied */
  if (!reused) {
    PetscCall(ROMAutoChoose(rom, asmb, contact, loads));
    PetscCall(ROMBuild(rom, asmb, contact, loads, t0));
    PetscCall(ROMAutoRelease(rom));
  }
  PetscCall(ROMResolveOnline(rom, contact));
  if (rom->opt.trained) PetscCall(ROMTieCheckSetUp(rom, asmb, loads)); /* its ties' forces, for the check */
  PetscCall(BoltROMSetTraining(rom, NULL, 0, NULL, NULL)); /* the caller frees them */
  if (rom->view) PetscCall(BoltROMView(rom, PETSC_VIEWER_STDOUT_(rom->comm)));
  PetscFunctionReturn(0);
}

/* The settings used: the options as resolved by SetUp (before it, the options as given). */
PetscErrorCode BoltROMView(BoltROM *rom, PetscViewer viewer)
{
  BoltReductionOptions *o = &rom->opt;
  BoltKrylov           *k = o->krylov;
  PetscBool             iascii;

  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(rom->comm);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "ROM: Krylov order %" PetscInt_FMT ", s0 %g rad/s, block size %" PetscInt_FMT ", deflation tol %g; CCM %" PetscInt_FMT " + JIM %" PetscInt_FMT "\n", k->order, (double)k->s0, k->blockSize, (double)k->deflationTol, o->nCCM, o->nJIM));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  file %s (if it does not match: %s%s)\n", o->file[0] ? o->file : "(none)", o->rebuildFile[0] ? "built into " : "refused", o->rebuildFile));
  if (!rom->contact) PetscFunctionReturn(0); /* not set up: only the options as given */
  PetscCall(PetscViewerASCIIPrintf(viewer, "  dimension %" PetscInt_FMT " (%s%s), contact %s, preload state %s, static shapes %s\n", rom->n, rom->fromFile ? "from the file" : "built", o->trained ? ", trained: held pairs tied" : "", rom->augment ? "augmented" : "penalty", PetscBools[rom->preloadState], PetscBools[rom->staticShapes]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  penalty scale %g, band scale %g, static penalty scale %g\n", (double)rom->penaltyScale, (double)rom->bandScale, (double)rom->staticPenaltyScale));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  closed-contact Krylov %" PetscInt_FMT " (preloaded set kept), opening shapes at %g x the load, %" PetscInt_FMT " opened-joint Krylov, slip shapes at %g x\n", rom->nClosed, (double)rom->openingScale, rom->nOpenKrylov, (double)rom->slipScale));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  cone shapes at %g (%s), %" PetscInt_FMT " cone modes; snapshot modes %" PetscInt_FMT "\n", (double)rom->coneShapes, rom->coneTraction ? "normal and traction" : "normal", rom->coneModes, o->nSnapshotModes));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  online: largest low-rank update %" PetscInt_FMT " (0: refactorise), unmarked points %s, gaps everywhere %s\n", rom->updateRankUsed, rom->holdUnmarked ? "held" : "free", PetscBools[rom->gapsEverywhere]));
  PetscFunctionReturn(0);
}

/* The ROM's keys of the run summary: its size, the offline phase's times [s], the settings used. */
PetscErrorCode BoltROMSummaryWrite(BoltROM *rom, BoltJSON *j)
{
  const char     *key[] = {"offline_s", "offline_inputs_s", "offline_basis_s", "offline_factor_s", "offline_solves_s", "offline_orth_s", "offline_interface_s", "offline_projection_s"};
  const PetscReal t[]   = {rom->tOffline, rom->tInputs, rom->tBasis, rom->tFactor, rom->tSolve, rom->tOrth, rom->tInterface, rom->tProject};

  PetscFunctionBeginUser;
  PetscCall(BoltJSONInt(j, "dim", rom->n));
  PetscCall(BoltJSONInt(j, "order", rom->order));
  PetscCall(BoltJSONReal(j, "s0", rom->s0));
  PetscCall(BoltJSONInt(j, "inputs", rom->ninputs));
  PetscCall(BoltJSONInt(j, "n_ccm", rom->nCCM));
  PetscCall(BoltJSONInt(j, "n_jim", rom->nJIM));
  PetscCall(BoltJSONString(j, "source", rom->fromFile ? "file" : "built"));
  for (PetscInt k = 0; k < 8; k++) PetscCall(BoltJSONReal(j, key[k], t[k]));
  PetscCall(BoltJSONString(j, "contact_law", rom->augment ? "augmented" : "penalty"));
  PetscCall(BoltJSONInt(j, "preload_state", rom->preloadState));
  PetscCall(BoltJSONReal(j, "contact_penalty_scale", rom->penaltyScale));
  PetscCall(BoltJSONReal(j, "contact_band_scale", rom->bandScale));
  PetscCall(BoltJSONInt(j, "trained", rom->opt.trained));
  PetscCall(BoltJSONString(j, "trained_on", !rom->opt.trained ? "" : rom->opt.trainStatic ? "static solves" : "the FOM's run"));
  PetscCall(BoltJSONInt(j, "auto_tied", rom->autoTied)); /* -rom_train auto chose the tied ROM */
  PetscCall(BoltJSONInt(j, "closed_krylov", rom->nClosed));
  PetscCall(BoltJSONReal(j, "opening_scale", rom->openingScale));
  PetscCall(BoltJSONReal(j, "slip_scale", rom->slipScale));
  PetscCall(BoltJSONInt(j, "opening_krylov", rom->nOpenKrylov));
  PetscCall(BoltJSONInt(j, "snapshot_modes", rom->nSnapshotModes));
  PetscCall(BoltJSONInt(j, "cone_pairs", rom->nConePairs));
  PetscCall(BoltJSONInt(j, "cone_modes", rom->nConeModes));
  PetscCall(BoltJSONInt(j, "update_rank", rom->updateRankUsed));
  PetscCall(BoltJSONInt(j, "update_largest_batch", BoltROMUpdateLargestBatch(rom->update)));
  if (rom->orthogonality >= 0) PetscCall(BoltJSONReal(j, "orthogonality", rom->orthogonality));
  PetscFunctionReturn(0);
}

/* The reduced mass and stiffness (referenced by the ROM: not to be destroyed). */
PetscErrorCode BoltROMGetMatrices(BoltROM *rom, Mat *M, Mat *K)
{
  PetscFunctionBeginUser;
  if (M) *M = rom->Mr;
  if (K) *K = rom->Kr;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMGetFile(BoltROM *rom, const char *file[], const char *rebuild[])
{
  PetscFunctionBeginUser;
  *file = rom->opt.file;
  if (rebuild) *rebuild = rom->opt.rebuildFile;
  PetscFunctionReturn(0);
}

/* -rom_verify: the run checks the ROM against itself and the FOM (slower) */
PetscBool BoltROMVerifies(BoltROM *rom)
{
  return rom->opt.verify;
}

PetscErrorCode BoltROMGetSnapshotModes(BoltROM *rom, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = rom->opt.nSnapshotModes;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltROMDestroy(BoltROM **romp)
{
  BoltROM *rom = *romp;

  PetscFunctionBeginUser;
  if (!rom) PetscFunctionReturn(0);
  PetscCall(ROMOnlineDestroy(rom)); /* if no operator freed them */
  PetscCall(MatDestroy(&rom->Mr));
  PetscCall(MatDestroy(&rom->Cr));
  PetscCall(MatDestroy(&rom->Kr));
  PetscCall(VecDestroy(&rom->loadr));
  PetscCall(VecDestroy(&rom->loadUnitr));
  PetscCall(VecDestroy(&rom->preloadr));
  PetscCall(PetscFree(rom->Vc));
  PetscCall(PetscFree(rom->Vprobe));
  PetscCall(PetscFree(rom->rigidr));
  PetscCall(PetscFree4(rom->lambda0, rom->gap0, rom->active0, rom->released0));
  PetscCall(PetscFree(rom->marked));
  PetscCall(ROMTieCheckDestroy(rom));
  PetscCall(BoltKrylovDestroy(&rom->opt.krylov));
  PetscCall(PetscFree(*romp));
  PetscFunctionReturn(0);
}
