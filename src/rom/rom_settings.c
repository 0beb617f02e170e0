/* The ROM's settings: every default of the reduction resolved from its options and the scene,
   the fingerprint of what the basis depends on, the reuse of a matching ROM file, and the
   default's choice of the tied ROM (-rom_train auto). */
#include "private/rom.h"
#include "private/boltrom_krylov.h"
#include <petscviewerhdf5.h>

/* The ROM's activation band (the tension at which a closed point opens), relative to the FOM's.
   Under the near-hard penalty a reduced gap error of a nanometre is a traction of megapascals:
   at the rim of the preloaded zone the FOM's band lets such errors open points the FOM keeps
   closed. A wider band helps there but not in paper-step (docs/decisions.md), so 1 stays the default
   for the stick law. Under the strict law the band (1e-10 E) is its FOM's solver tolerance. An
   interface-reduced ROM without opening shapes cannot resolve tractions at single rim pairs that
   finely (its rim pairs then open and close about a hundred times in paper-step at level 1 while
   the FOM's set holds) and judges with the stick law's band, 2e5 times the strict one. With
   opening shapes, or snapshot modes of the FOM's run, it can open the pairs the load opens, and
   keeps the strict band (docs/decisions.md).
   Which applies is known once the basis is. */
static PetscReal ROMDefaultBand(BoltContactSet *contact, BoltROM *rom)
{
  return BoltContactSetIsComplementarity(contact) && !rom->augment && rom->nOpeningPairs == 0 && rom->nSnapshotModes == 0 ? 2e5 : 1.0;
}

/* Whether the points outside the opening shapes keep their preloaded state online: yes, but not
   under friction. There a pair the static solves leave sticking may still slip in
   the dynamic response, and the basis gives it some room to (level 0.5, 20 kN and a 300 N step,
   mu 0.1: held, e_L2 1.2e-3 and 5.2 % less dissipation than the FOM; free, 1.6e-4 and 0.7 %; the
   same on two other scenes either way). */
static PetscBool ROMDefaultHold(BoltContactSet *contact)
{
  return (PetscBool)!BoltContactSetHasFriction(contact);
}

/* The reduction's part of the fingerprint: the static shapes and modes in the basis, each
   field 0 where it does not apply (the closed-contact Krylov's active set is named either way,
   so that files built with the set free are rebuilt). */
static PetscErrorCode ROMFingerprintShapes(BoltReductionOptions *o, BoltROM *rom, PetscBool staticShapes, PetscReal staticPenaltyScale)
{
  BoltROMFingerprint *fp = &rom->fingerprint;

  PetscFunctionBeginUser;
  PetscCall(BoltROMFingerprintInt(fp, "trained", o->trainAuto ? 3 : o->trained ? (o->trainStatic ? 2 : 1) : 0)); /* 2: from static solves; 3: auto */
  PetscCall(BoltROMFingerprintString(fp, "static_shapes", !staticShapes ? "none" : rom->preloadState ? "preload state" : "static shapes"));
  PetscCall(BoltROMFingerprintInt(fp, "closed_krylov", staticShapes ? o->nClosed : 0));
  PetscCall(BoltROMFingerprintInt(fp, "closed_krylov_keep_active", staticShapes && o->nClosed > 0)); /* always kept */
  PetscCall(BoltROMFingerprintReal(fp, "static_penalty_scale", staticShapes ? staticPenaltyScale : 0));
  PetscCall(BoltROMFingerprintReal(fp, "opening_scale", rom->openingScale));
  PetscCall(BoltROMFingerprintInt(fp, "opened_joint_krylov", rom->openingScale > 0 ? rom->nOpenKrylov : 0));
  PetscCall(BoltROMFingerprintReal(fp, "slip_scale", rom->slipScale));
  PetscCall(BoltROMFingerprintReal(fp, "cone_shapes", rom->coneShapes));
  PetscCall(BoltROMFingerprintInt(fp, "cone_traction", rom->coneShapes > 0 ? rom->coneTraction : 0));
  PetscCall(BoltROMFingerprintInt(fp, "cone_modes", rom->coneModes));
  PetscCall(BoltROMFingerprintInt(fp, "snapshot_modes", o->nSnapshotModes));
  PetscCall(BoltROMFingerprintReal(fp, "snapshot_tol", o->nSnapshotModes > 0 ? o->snapshotTol : 0));
  PetscFunctionReturn(0);
}

/* The ROM's settings from the reduction's options and the scene (each default resolved here),
   and the fingerprint of what its basis depends on. */
PetscErrorCode ROMResolveSettings(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads)
{
  BoltReductionOptions *o = &rom->opt;
  BoltKrylov           *kry;
  PetscBool             staticShapes;
  PetscReal             staticPenaltyScale;

  PetscFunctionBeginUser;
  rom->contact     = contact;
  PetscCall(BoltAssemblerGetRayleigh(asmb, &rom->rayleigh[0], &rom->rayleigh[1])); /* C_r = V' C V (a ROM file holds the same: its fingerprint has them) */
  /* With interface reduction the ROM has fewer DOFs than contact constraints: multipliers that
     close every active gap are not unique (their signs, which decide the active set, are
     arbitrary) and closing the gaps exactly locks the reduced interface. The penalty law keeps
     the reduced contact problem well posed, so it is the law there. */
  rom->augment = (PetscBool)(BoltContactSetAugmented(contact) && o->nCCM + o->nJIM == 0);
  PetscCheck(o->krylov, o->comm, PETSC_ERR_ARG_WRONGSTATE, "BoltROMBuild needs the Krylov options: configure the reduction with BoltReductionSetFromOptions");
  kry = o->krylov;
  if (o->trained) o->nCCM = o->nJIM = 0; /* -rom_train reduces no interface: its node pairs are inputs as they are */
  PetscCall(BoltROMFingerprintScene(asmb, contact, loads, kry->order, kry->s0, kry->deflationTol, o->nCCM, o->nJIM, &rom->fingerprint));
  /* the preloaded state needs the penalty law (the augmented ROM closes its own gaps) and a preload */
  rom->preloadState = (PetscBool)(!rom->augment && BoltLoadSetHasPreload(loads) && BoltLoadSetPreloadForce(loads) != 0);
  /* Against a FOM that closes its gaps the increments want a near-hard penalty: 1e5 E/m (500 x
     the paper's), where the penalty law alone matches the augmented FOM. It needs the
     closed-contact Krylov shapes, which the basis always has: without them so stiff a penalty
     locked the reduced interface (docs/decisions.md). The scale is relative to the FOM's
     penalty, whatever its law. */
  rom->penaltyScale = rom->preloadState && BoltContactSetAugmented(contact) ? 1e5 / BoltContactSetPenaltyFactor(contact) : 1.0;
  if (o->trained) PetscCall(ROMTrainedSettings(rom, loads));
  /* the static shapes enrich the augmented ROM's basis too, where its own multipliers close the gaps */
  staticShapes = (PetscBool)(BoltLoadSetHasPreload(loads) && BoltLoadSetPreloadForce(loads) != 0);
  rom->nClosed = staticShapes ? o->nClosed : 0;
  /* Opening shapes by default for the interface-reduced ROM under the strict law (the ROM without
     interface reduction has every node pair's force among its inputs; the stick law's scenes are
     the paper's, whose figures stay as they were) */
  /* ... and none by default with snapshot modes, which carry the openings and slips the FOM made */
  /* (a ROM trained on static solves looks for its changing pairs at this scale, and takes no shapes) */
  if (o->trained) rom->openingScale = staticShapes && o->trainStatic ? o->openingScale : 0;
  else rom->openingScale = staticShapes ? (BoltContactSetIsComplementarity(contact) && rom->preloadState && o->nSnapshotModes == 0 ? o->openingScale : 0.0) : 0;
  rom->nOpenKrylov  = rom->openingScale > 0 && !o->trained ? o->nOpenKrylov : 0;
  rom->slipScale    = rom->openingScale > 0 && BoltContactSetHasFriction(contact) ? (o->periodicLoad ? o->slipScalePeriodic : o->slipScale) : 0;
  rom->coneShapes   = staticShapes && rom->preloadState && BoltContactSetHasFriction(contact) && !o->trained ? o->coneShapes : 0;
  rom->coneTraction = o->coneTraction;
  rom->coneModes    = rom->coneShapes > 0 ? o->coneModes : 0;
  staticPenaltyScale = PetscMax(1.0, 2e6 / BoltContactSetPenaltyFactor(contact)); /* 2e6 E/m */
  PetscCall(ROMFingerprintShapes(o, rom, staticShapes, staticPenaltyScale));
  rom->staticShapes       = staticShapes;
  rom->staticPenaltyScale = staticPenaltyScale;
  PetscFunctionReturn(0);
}

/* Whether an existing -rom_file is damaged or cut short (its seal, checked on rank 0). Such a file
   is refused, as one that does not match, unless -rom_rebuild names a file to build into. */
PetscErrorCode BoltROMCheckFileIntact(BoltROM *rom, PetscBool *damaged)
{
  BoltReductionOptions *o    = &rom->opt;
  BoltSealState         seal = BOLT_SEAL_OK;
  PetscMPIInt           rank;
  PetscBool             exists;

  PetscFunctionBeginUser;
  *damaged = PETSC_FALSE;
  if (!o->file[0]) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(o->comm, &rank));
  if (!rank) {
    PetscCall(PetscTestFile(o->file, 'r', &exists));
    if (exists) PetscCall(BoltHDF5CheckSeal(o->file, &seal));
  }
  PetscCallMPI(MPI_Bcast(&seal, 1, MPI_INT, 0, o->comm));
  *damaged = (PetscBool)(seal == BOLT_SEAL_BAD);
  PetscCheck(!*damaged || o->rebuildFile[0], o->comm, PETSC_ERR_FILE_UNEXPECTED, "ROM file %s is damaged or cut short (it cannot be read through, or its data do not match the checksum written with it): build a new one with -rom_rebuild FILE (the same name overwrites it), or remove it", o->file);
  PetscFunctionReturn(0);
}

/* A -rom_file built for another scene (why: its first difference), unless -rom_rebuild names a
   file to build into: refused, the file kept as it is. */
static PetscErrorCode ROMRefuseOtherScene(BoltROM *rom, const char why[])
{
  BoltReductionOptions *o = &rom->opt;

  PetscFunctionBeginUser;
  PetscCheck(o->rebuildFile[0], o->comm, PETSC_ERR_USER_INPUT, "ROM file %s was built for another scene (%s) and is kept as it is: point -rom_file at a new file, or build one for this scene with -rom_rebuild FILE (the same name overwrites it)", o->file, why);
  PetscFunctionReturn(0);
}

/* Before any model runs: an existing -rom_file built for another scene, or for another load, is
   refused now, not after the FOM's run (its fingerprint and input against the scene's, the file
   not read further). */
PetscErrorCode BoltROMCheckFile(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads)
{
  BoltReductionOptions *o = &rom->opt;
  PetscBool             exists, matched, native;
  PetscViewer           v;
  char                  why[512];

  PetscFunctionBeginUser;
  if (!o->file[0] || o->rebuildFile[0]) PetscFunctionReturn(0);
  PetscCall(PetscTestFile(o->file, 'r', &exists));
  if (!exists) PetscFunctionReturn(0);
  PetscCall(ROMResolveSettings(rom, asmb, contact, loads));
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, o->file, FILE_MODE_READ, &v));
  PetscCall(BoltROMFingerprintMatch(&rom->fingerprint, v, &matched, why, sizeof(why)));
  if (matched) PetscCall(BoltROMFingerprintMatchLoad(v, loads, o->extraInputs, &matched, &native, why, sizeof(why)));
  PetscCall(PetscViewerDestroy(&v));
  if (!matched) PetscCall(ROMRefuseOtherScene(rom, why));
  PetscFunctionReturn(0);
}

/* Reads -rom_file into rom when the file exists and its fingerprint matches (*reused). A file that
   does not match is never overwritten unasked: a trained ROM once went that way, replaced by one
   built without its training. It is refused with the first difference, or with -rom_rebuild FILE
   the ROM is built for this scene into FILE, which becomes the run's ROM file. */
PetscErrorCode ROMReuseFile(BoltROM *rom, BoltContactSet *contact, BoltLoadSet *loads, PetscLogDouble t0, PetscBool *reused)
{
  BoltReductionOptions *o = &rom->opt;
  PetscLogDouble        t3;
  PetscBool             exists, damaged;
  char                  why[512];

  PetscFunctionBeginUser;
  *reused = PETSC_FALSE;
  PetscCall(PetscTestFile(o->file, 'r', &exists));
  if (!exists) PetscFunctionReturn(0);
  PetscCall(BoltROMCheckFileIntact(rom, &damaged));
  if (damaged) {
    PetscCall(PetscPrintf(o->comm, "ROM file %s is damaged or cut short: building the ROM into %s, as asked (-rom_rebuild)\n", o->file, o->rebuildFile));
    PetscCall(PetscStrncpy(o->file, o->rebuildFile, sizeof(o->file)));
    PetscFunctionReturn(0);
  }
  PetscCall(BoltROMLoad(o->file, rom, contact, loads, reused, why, sizeof(why)));
  if (*reused) {
    PetscCall(PetscTime(&t3));
    rom->tOffline = t3 - t0;
    PetscCall(PetscPrintf(o->comm, "ROM: reusing %s (dimension %" PetscInt_FMT "): the offline phase is skipped\n", o->file, rom->n));
    PetscFunctionReturn(0);
  }
  PetscCall(ROMRefuseOtherScene(rom, why));
  PetscCall(PetscPrintf(o->comm, "ROM file %s does not match this scene (%s): building the ROM into %s, as asked (-rom_rebuild)\n", o->file, why, o->rebuildFile));
  PetscCall(PetscStrncpy(o->file, o->rebuildFile, sizeof(o->file)));
  PetscFunctionReturn(0);
}

/* The online settings, which depend on the basis: the activation band, which points are held,
   the largest low-rank update of the factorisation. Low-rank updates by default where the
   active set is expected to move (the strict law's penalty ROM, nodal points); the stick law's
   keeps refactorising, as in the paper. */
PetscErrorCode ROMResolveOnline(BoltROM *rom, BoltContactSet *contact)
{
  BoltReductionOptions *o = &rom->opt;

  PetscFunctionBeginUser;
  rom->bandScale      = ROMDefaultBand(contact, rom);
  rom->holdUnmarked   = ROMDefaultHold(contact);
  rom->gapsEverywhere = o->verify;
  rom->updateRankUsed = o->verify ? 0 : (BoltContactSetIsComplementarity(contact) && !rom->augment && BoltContactSetQuadrature(contact) == BOLT_QUADRATURE_NODAL ? (3 * rom->n) / 5 : 0); /* 0: refactorise */
  PetscFunctionReturn(0);
}

/* -rom_train auto, the default: the static solves that mark the opening shapes' node pairs (at
   -/+ the opening scale x the load) are made first. Where they change no point, the joint is
   linear over the load's range as far as statics can tell, and the ROM is the tied one: the
   trained construction with no pair free, every pair checked online (paper-step at levels 0.6
   and 0.7: e_L2 6e-4 instead of the paper's 5e-2; docs/decisions.md). Elsewhere it is the
   paper's ROM with its opening shapes. Not under friction, where the dynamic response slips
   pairs that static solves leave sticking (docs/decisions.md, the held points), nor with
   snapshot modes. The fingerprint stays the request's (auto), so a later default run reuses the
   file whichever it became; a tied build takes over the marks and the state solved. */
PetscErrorCode ROMAutoChoose(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads)
{
  BoltReductionOptions *o  = &rom->opt;
  const PetscInt        np = 4 * BoltContactSetElementCount(contact);
  PetscInt              nchanged = 0;

  PetscFunctionBeginUser;
  rom->autoTied = PETSC_FALSE;
  if (!o->trainAuto || o->trained || rom->openingScale <= 0 || BoltContactSetHasFriction(contact) || o->nSnapshotModes > 0) PetscFunctionReturn(0);
  if (BoltLoadSetBoltCount(loads) && !o->fomPreload) PetscFunctionReturn(0); /* (the build says why it needs the FOM) */
  PetscCall(BoltROMStaticChanges(asmb, contact, loads, rom, o->fomPreload, &rom->autoChanged, &rom->autoSolved));
  for (PetscInt i = 0; i < np; i++) nchanged += rom->autoChanged[i] ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nchanged, 1, MPIU_INT, MPI_SUM, rom->comm));
  if (nchanged > 0) { /* the paper's ROM, built as without auto (the same bits): it solves its own preloaded state */
    PetscCall(ROMAutoRelease(rom));
    PetscCall(PetscPrintf(rom->comm, "ROM: -rom_train auto: the static solves change %" PetscInt_FMT " contact points: the paper's ROM with its opening shapes\n", nchanged));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscPrintf(rom->comm, "ROM: -rom_train auto: the static solves change no contact point: the tied ROM (every closed pair tied, each checked online; -rom_train none for the paper's)\n"));
  PetscCall(ROMSwitchTied(rom, asmb, contact, loads));
  PetscFunctionReturn(0);
}

/* The tied ROM's settings in place of the paper's (chosen by auto now, or read from a file that
   auto made so), under the request's fingerprint. */
PetscErrorCode ROMSwitchTied(BoltROM *rom, BoltAssembler *asmb, BoltContactSet *contact, BoltLoadSet *loads)
{
  BoltROMFingerprint *keep;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(1, &keep));
  *keep                = rom->fingerprint;
  rom->opt.trained     = PETSC_TRUE;
  rom->opt.trainStatic = PETSC_TRUE;
  PetscCall(ROMResolveSettings(rom, asmb, contact, loads));
  rom->fingerprint = *keep;
  rom->autoTied    = PETSC_TRUE;
  PetscCall(PetscFree(keep));
  PetscFunctionReturn(0);
}

/* The marks and the state auto solved, handed to the build of the tied ROM. */
PetscErrorCode ROMAutoTake(BoltROM *rom, PetscBool **changed, BoltPreloadState **solved)
{
  PetscFunctionBeginUser;
  *changed         = rom->autoChanged;
  *solved          = rom->autoSolved;
  rom->autoChanged = NULL;
  rom->autoSolved  = NULL;
  PetscFunctionReturn(0);
}

/* What auto made and no build took over. */
PetscErrorCode ROMAutoRelease(BoltROM *rom)
{
  PetscFunctionBeginUser;
  PetscCall(BoltPreloadStateDestroy(&rom->autoSolved));
  PetscCall(PetscFree(rom->autoChanged));
  PetscFunctionReturn(0);
}
