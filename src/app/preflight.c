/* Checks made before any computation, so that a run that would fail at its end fails at once,
   with nothing written: options that no object reads (a misspelling, a leftover) and folders
   that cannot be written. */
#include "private/app.h"
#include <ctype.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

/* Options that are read only once the solves have begun (or by PETSc at start-up and exit): the
   early checks let them through, the final check after the run still refuses any left unused.
   Names without the leading dash; '*' matches any run of characters. */
static const char *const boltLateOptions[] = {
  "*mat_mumps_*",                                   /* MUMPS's controls, read at the factorisation */
  "*_converged_reason", "*_view", "*_view_*",       /* reports of a solve, read when it ends */
  "log_view*", "traceback", "help",                 /* PETSc's own and main()'s */
  NULL};
/* Read by PetscFinalize, after the final check. */
static const char *const boltExitOptions[] = {"options_left", NULL};
/* Read while the model is set up: the per-pair penalties and friction coefficients (the mesh names the pairs) and the
   options of DMPlex's mesh reader. */
static const char *const boltSetUpOptions[] = {"contact_*_penalty_factor", "contact_*_friction", "dm_plex_*", NULL};

/* Options that are gone: the ROM's construction fixes what they set (docs/decisions.md, "The
   construction's fixed settings"), and its checks are one option. A scene that still names one is told so. */
static const char *const boltRetiredOptions[][2] = {
  {"rom_check_s0", "-rom_verify makes this check with the others"}, {"rom_check_orthogonality", "-rom_verify makes this check with the others"},
  {"rom_gaps_everywhere", "-rom_verify takes every gap, with its other checks"}, {"rom_update_rank", "-rom_verify refactorises at every change, with its other checks"},
  {"rom_preload_state", NULL}, {"rom_contact_penalty_scale", NULL}, {"rom_contact_band_scale", NULL},
  {"rom_closed_krylov", NULL}, {"rom_closed_keep_active", NULL}, {"rom_static_penalty_scale", NULL},
  {"rom_static_shapes", NULL}, {"rom_opening_shapes", NULL}, {"rom_opening_krylov", NULL},
  {"rom_slip_shapes", NULL}, {"rom_hold_unmarked", NULL}, {"rom_snapshot_tol", NULL},
  {"rom_contact_augment", "the ROM follows -contact_augment without interface reduction, and the penalty law with it"},
  {NULL, NULL}};

static PetscErrorCode BoltOptionCheckRetired(MPI_Comm comm, const char name[])
{
  PetscBool same;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; boltRetiredOptions[i][0]; i++) {
    PetscCall(PetscStrcasecmp(name, boltRetiredOptions[i][0], &same));
    PetscCheck(!same || boltRetiredOptions[i][1], comm, PETSC_ERR_USER_INPUT, "-%s is no longer an option: the ROM's construction fixes it (docs/decisions.md); remove it from the scene", name);
    PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "-%s is no longer an option: %s; remove it from the scene", name, boltRetiredOptions[i][1]);
  }
  PetscFunctionReturn(0);
}

/* name matches pattern ('*': any run of characters), ignoring case as PETSc's options do */
static PetscErrorCode BoltGlobMatch(const char pattern[], const char name[], PetscBool *match)
{
  const char *p = pattern, *s = name, *star = NULL, *mark = NULL;

  PetscFunctionBeginUser;
  *match = PETSC_FALSE;
  while (*s) {
    if (*p == '*') {
      star = p++;
      mark = s;
    } else if (*p && tolower((unsigned char)*p) == tolower((unsigned char)*s)) {
      p++;
      s++;
    } else if (star) { /* let the last '*' take one more character */
      p = star + 1;
      s = ++mark;
    } else PetscFunctionReturn(0);
  }
  while (*p == '*') p++;
  *match = (PetscBool)!*p;
  PetscFunctionReturn(0);
}

static PetscErrorCode BoltGlobMatchAny(const char *const patterns[], const char name[], PetscBool *match)
{
  PetscFunctionBeginUser;
  *match = PETSC_FALSE;
  for (PetscInt i = 0; patterns[i] && !*match; i++) PetscCall(BoltGlobMatch(patterns[i], name, match));
  PetscFunctionReturn(0);
}

/* Options that nobody asked for are spelling mistakes or leftovers: refuse them. Before the
   set-up and before the first solve, the options read later (the lists above) are let through. */
PetscErrorCode BoltOptionsCheckUnused(MPI_Comm comm, BoltOptionsStage stage)
{
  PetscInt n, nbad = 0;
  char   **names, **values;
  char     msg[1024] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
    PetscBool late = PETSC_FALSE, setUp = PETSC_FALSE, exit;
    PetscCall(BoltGlobMatchAny(boltExitOptions, names[i], &exit));
    if (stage != BOLT_OPTIONS_FINAL) PetscCall(BoltGlobMatchAny(boltLateOptions, names[i], &late));
    if (stage == BOLT_OPTIONS_BEFORE_SETUP) PetscCall(BoltGlobMatchAny(boltSetUpOptions, names[i], &setUp));
    if (exit || late || setUp) continue;
    PetscCall(BoltOptionCheckRetired(comm, names[i]));
    if (nbad < 8) {
      PetscCall(PetscStrlcat(msg, nbad ? ", -" : "-", sizeof(msg)));
      PetscCall(PetscStrlcat(msg, names[i], sizeof(msg)));
    }
    nbad++;
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!nbad, comm, PETSC_ERR_USER_INPUT, "Unknown or unused option(s) %s: check the spelling against bin/boltrom -help", msg);
  PetscFunctionReturn(0);
}

/* Whether dir can be made and written, without making it: rank 0 climbs to its nearest existing
   ancestor, which must be a folder where a file can be created (a probe, removed at once). The
   permission bits alone would not do: they do not stop root. */
PetscErrorCode BoltCheckWritableDir(MPI_Comm comm, const char dir[], const char option[])
{
  PetscMPIInt rank;
  PetscBool   ok = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char        path[PETSC_MAX_PATH_LEN], probe[PETSC_MAX_PATH_LEN + 64];
    struct stat st;
    size_t      len;
    int         fd;

    PetscCall(PetscStrncpy(path, dir[0] ? dir : ".", sizeof(path)));
    PetscCall(PetscStrlen(path, &len));
    while (len > 1 && path[len - 1] == '/') path[--len] = '\0';
    while (stat(path, &st) != 0) { /* up to the parent: "a/b" -> "a", "/a" -> "/", "a" -> "." */
      char *slash = strrchr(path, '/');
      if (!slash) PetscCall(PetscStrncpy(path, ".", sizeof(path)));
      else if (slash == path) path[1] = '\0';
      else *slash = '\0';
    }
    if (!S_ISDIR(st.st_mode)) ok = PETSC_FALSE; /* a file where a folder is needed */
    else {
      PetscCall(PetscSNPrintf(probe, sizeof(probe), "%s/.boltrom-write-test-%d", path, (int)getpid()));
      fd = open(probe, O_WRONLY | O_CREAT | O_EXCL, 0600);
      if (fd < 0) ok = PETSC_FALSE;
      else {
        close(fd);
        unlink(probe);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_BOOL, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot create or write the directory %s for %s: choose a writable folder", dir, option);
  PetscFunctionReturn(0);
}

/* The folder of the file path (the current one if path has none). */
PetscErrorCode BoltCheckWritableParent(MPI_Comm comm, const char path[], const char option[])
{
  char  dir[PETSC_MAX_PATH_LEN], *slash;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(dir, path, sizeof(dir)));
  PetscCall(PetscStrrchr(dir, '/', &slash));
  if (slash == dir) PetscCall(PetscStrncpy(dir, ".", sizeof(dir))); /* no '/' in path */
  else if (slash == dir + 1) dir[1] = '\0';                        /* "/file": the root */
  else slash[-1] = '\0';
  PetscCall(BoltCheckWritableDir(comm, dir, option));
  PetscFunctionReturn(0);
}

/* The solvers and the time integrators are made later, from the model: objects of the same
   prefixes read their options now and are dropped (the later ones read the same options).
   checkpointBase: the checkpoints' base name if they are written, else "". */
PetscErrorCode BoltPreflightSetFromOptions(MPI_Comm comm, const BoltRunOptions *o, char checkpointBase[])
{
  char name[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s/%s", o->outputDir, o->outputName));
  PetscCall(BoltNewmarkOptionsCheck(comm, name, checkpointBase));
  PetscCall(BoltDirectSolverSetFromOptions(comm, "static_", PETSC_FALSE, MATSOLVERMUMPS));
  PetscCall(BoltModalSetFromOptions(comm, o->nev, "modal_"));
  /* K_eff: the FOM's is symmetric (Cholesky by MUMPS), the ROM's dense (LU by PETSc) */
  PetscCall(BoltDirectSolverSetFromOptions(comm, "fom_", PETSC_TRUE, MATSOLVERMUMPS));
  PetscCall(BoltDirectSolverSetFromOptions(comm, "rom_", PETSC_FALSE, MATSOLVERPETSC));
  PetscFunctionReturn(0);
}

/* Before the model is set up: every option has been read (save those read later, see above) and
   every folder the run writes can be written. The summary's and the ROM file's folders are then
   made, as the files themselves are written without making one. */
PetscErrorCode BoltPreflightCheck(MPI_Comm comm, const BoltRunOptions *o, BoltROM *rom, const char checkpointBase[])
{
  const char *romFile, *rebuildFile;
  PetscInt    snapshotModes;

  PetscFunctionBeginUser;
  PetscCall(BoltROMGetFile(rom, &romFile, &rebuildFile));
  PetscCall(BoltROMGetSnapshotModes(rom, &snapshotModes));
  PetscCall(BoltOptionsCheckUnused(comm, BOLT_OPTIONS_BEFORE_SETUP));
  if (o->writeOutput) PetscCall(BoltCheckWritableDir(comm, o->outputDir, "-output_dir"));
  if (o->summary[0]) PetscCall(BoltCheckWritableParent(comm, o->summary, "-summary"));
  if (o->rom && romFile[0]) PetscCall(BoltCheckWritableParent(comm, romFile, "-rom_file"));
  if (o->rom && rebuildFile[0]) PetscCall(BoltCheckWritableParent(comm, rebuildFile, "-rom_rebuild"));
  if (checkpointBase[0]) PetscCall(BoltCheckWritableParent(comm, checkpointBase, "the checkpoints (-checkpoint_file)"));
  if (o->exportDir[0]) PetscCall(BoltCheckWritableDir(comm, o->exportDir, "-export_matrices"));
  if (o->rom && snapshotModes > 0) { /* the modes come from this run's FOM, or from a ROM file built with them */
    PetscInt  every = 0;
    PetscBool fileThere = PETSC_FALSE;
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-snapshot_every", &every, NULL));
    if (romFile[0]) PetscCall(PetscTestFile(romFile, 'r', &fileThere));
    PetscCheck((o->fom && every > 0) || fileThere, comm, PETSC_ERR_USER_INPUT, "-rom_snapshot_modes needs the FOM's displacement snapshots of the same run: add -fom true -snapshot_every 1, or give a -rom_file built with them");
  }
  if (o->rom) { /* a damaged ROM file is refused now, not after the FOM's run */
    PetscBool damaged;
    PetscCall(BoltROMCheckFileIntact(rom, &damaged));
  }
  if (o->summary[0]) PetscCall(BoltMakeParentDir(comm, o->summary));
  if (o->rom && romFile[0]) PetscCall(BoltMakeParentDir(comm, romFile));
  if (o->rom && rebuildFile[0]) PetscCall(BoltMakeParentDir(comm, rebuildFile));
  PetscFunctionReturn(0);
}
