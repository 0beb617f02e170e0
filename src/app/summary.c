/* A run's JSON summary (-summary): the model, the load, the tied analyses, and the FOM's and the
   ROM's runs with their counters and phase times; docs/outputs.md lists the keys. The HDF5/XDMF
   file of its fields and histories is fields.c's. */
#include "private/app.h"

/* The model: sizes, partition, and per pair and per part figures. */
static PetscErrorCode SummaryModel(BoltJSON *j, const BoltSummary *s, PetscMPIInt size)
{
  BoltMesh       *mesh    = s->mesh;
  BoltAssembler  *asmb    = s->asmb;
  BoltContactSet *contact = s->contact;

  PetscFunctionBeginUser;
  PetscCall(BoltMeshSummaryWrite(mesh, j));
  PetscCall(BoltJSONInt(j, "ranks", size));
  PetscCall(BoltContactSetSummaryWrite(contact, j));
  {
    PetscInt  elements[BOLTROM_MAX_PARTS];
    PetscReal mass[BOLTROM_MAX_PARTS], volume[BOLTROM_MAX_PARTS];
    for (PetscInt p = 0; p < BoltMeshPartCount(mesh); p++) PetscCall(BoltAssemblerGetPart(asmb, p, &mass[p], &volume[p], &elements[p]));
    PetscCall(BoltMeshPartValuesWrite(mesh, j, "elements_per_part", elements, NULL));
    PetscCall(BoltMeshPartValuesWrite(mesh, j, "mass_per_part", NULL, mass));
    PetscCall(BoltMeshPartValuesWrite(mesh, j, "volume_per_part", NULL, volume));
  }
  PetscCall(BoltJSONBeginObject(j, "material_per_part"));
  for (PetscInt p = 0; p < BoltMeshPartCount(mesh); p++) {
    const char *name;
    PetscCall(BoltMeshPartMaterial(mesh, p, &name, NULL, NULL, NULL));
    PetscCall(BoltJSONString(j, BoltMeshPartName(mesh, p), name));
  }
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}

/* The tied joint's analyses: static, modal, rigid motions. */
static PetscErrorCode SummaryTied(BoltJSON *j, const BoltSummary *s)
{
  BoltLoadSet *loads = s->loads;

  PetscFunctionBeginUser;
  if (s->staticSolve) {
    PetscCall(BoltJSONBeginObject(j, "static"));
    PetscCall(BoltJSONReal(j, "load_force", BoltLoadSetLoadForce(loads)));
    PetscCall(BoltJSONString(j, "probe_group", BoltLoadSetProbeGroup(loads)));
    PetscCall(BoltJSONInt(j, "probe_component", BoltLoadSetProbeComponent(loads)));
    PetscCall(BoltJSONRealArray(j, "probe_coordinates", 3, BoltLoadSetProbeCoordinates(loads)));
    PetscCall(BoltJSONReal(j, "probe_displacement", s->probe));
    PetscCall(BoltJSONReal(j, "seconds", s->tStatic));
    if (s->freeFree) PetscCall(BoltJSONInt(j, "inertia_relief_passes", s->staticPasses));
    PetscCall(BoltJSONEndObject(j));
  }
  if (s->nev > 0) {
    PetscCall(BoltJSONBeginObject(j, "modal"));
    PetscCall(BoltJSONString(j, "contact_state", s->modalContact == BOLT_MODAL_PRELOAD ? "preload" : "tied"));
    if (s->modalContact == BOLT_MODAL_PRELOAD) {
      PetscCall(BoltJSONInt(j, "closed_points", s->modalPoints[0]));
      PetscCall(BoltJSONInt(j, "stuck_points", s->modalPoints[1]));
      PetscCall(BoltJSONInt(j, "contact_points", s->modalPoints[2]));
    }
    PetscCall(BoltJSONRealArray(j, "frequencies_hz", s->nconv, s->freq));
    PetscCall(BoltJSONInt(j, "rigid_modes_deflated", s->freeFree ? 6 : 0));
    if (s->freeFree) PetscCall(BoltJSONRealArray(j, "rigid_mode_frequencies_hz", 6, s->rigidFreq));
    PetscCall(BoltJSONReal(j, "seconds", s->tModal));
    PetscCall(BoltJSONEndObject(j));
  }
  if (s->checkRigid) PetscCall(BoltMeshPartValuesWrite(s->mesh, j, "rigid_residual_per_part", NULL, s->rigid));
  PetscFunctionReturn(0);
}

/* The FOM's preloaded state, and its run if it ran. */
static PetscErrorCode SummaryFOM(BoltJSON *j, const BoltSummary *s)
{
  const BoltContactSet *contact = s->contact;

  PetscFunctionBeginUser;
  PetscCall(BoltJSONBeginObject(j, "preload"));
  PetscCall(BoltJSONReal(j, "force", BoltLoadSetPreloadForce(s->loads)));
  if (s->hasStud) PetscCall(BoltJSONReal(j, "stud_tension", s->studTension));
  PetscCall(BoltNewmarkPreloadSummaryWrite(s->preloadRun, j));
  PetscCall(BoltJSONReal(j, "penetration_max", s->preloadPenetration));
  PetscCall(BoltJSONReal(j, "multiplier_change", s->preloadChange));
  PetscCall(BoltJSONReal(j, "traction_normal_min", s->tractionStats[0]));
  PetscCall(BoltJSONReal(j, "traction_normal_max", s->tractionStats[1]));
  PetscCall(BoltJSONReal(j, "traction_tangential_max", s->tractionStats[2]));
  PetscCall(BoltJSONInt(j, "active_points", s->preloadActive));
  PetscCall(BoltJSONInt(j, "sliding_points", s->preloadSliding));
  PetscCall(BoltContactSetPairValuesWrite(contact, j, "normal_force_per_pair", NULL, s->preloadForce));
  PetscCall(BoltJSONEndObject(j));
  if (!s->fomRun) PetscFunctionReturn(0);
  PetscCall(BoltJSONBeginObject(j, "fom"));
  PetscCall(BoltNewmarkSummaryWrite(s->fomRun, j, PETSC_TRUE));
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}

/* The reduced model (offline figures) and its run; against the FOM's run if there is one. */
static PetscErrorCode SummaryROM(BoltJSON *j, const BoltSummary *s)
{
  PetscFunctionBeginUser;
  PetscCall(BoltJSONBeginObject(j, "rom"));
  PetscCall(BoltROMSummaryWrite(s->rom, j));
  {
    BoltOperator *op;
    PetscCall(BoltNewmarkGetModel(s->romRun, &op, NULL, NULL));
    PetscCall(BoltJSONInt(j, "held_points", BoltContactStateMayChange(BoltOperatorState(op)) != NULL));
  }
  PetscCall(BoltNewmarkSummaryWrite(s->romRun, j, PETSC_FALSE));
  if (s->romCheckS0) PetscCall(BoltJSONReal(j, "check_s0_error", s->romCheckError));
  if (s->romBolts) {
    PetscCall(BoltJSONBeginObject(j, "bolt_stud_tension"));
    for (PetscInt b = 0; b < s->romBolts; b++) PetscCall(BoltJSONReal(j, BoltLoadSetBoltName(s->loads, b), s->romStudTension[b]));
    PetscCall(BoltJSONEndObject(j));
  }
  PetscCall(BoltJSONEndObject(j));
  if (s->fomRun) {
    PetscReal tf, tr;
    PetscCall(BoltNewmarkGetTiming(s->fomRun, NULL, &tf));
    PetscCall(BoltNewmarkGetTiming(s->romRun, NULL, &tr));
    PetscCall(BoltJSONReal(j, "speedup", tf / tr));
    PetscCall(BoltJSONBeginObject(j, "errors"));
    PetscCall(BoltJSONBeginObject(j, BoltLoadSetProbeGroup(s->loads)));
    PetscCall(BoltJSONReal(j, "e_L2", s->errL2));
    PetscCall(BoltJSONReal(j, "e_mean", s->errMean));
    PetscCall(BoltJSONEndObject(j));
    PetscCall(BoltJSONEndObject(j));
  }
  PetscFunctionReturn(0);
}

/* Writes the summary to path (rank 0, under a temporary name renamed when complete). */
PetscErrorCode BoltSummaryWrite(MPI_Comm comm, const char path[], const BoltSummary *s)
{
  BoltJSON   *j;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(BoltJSONOpen(comm, path, &j));
  PetscCall(SummaryModel(j, s, size));
  PetscCall(BoltSummaryWriteLoad(j, s));
  PetscCall(SummaryTied(j, s));
  if (s->preloadRun) PetscCall(SummaryFOM(j, s));
  if (s->rom) PetscCall(SummaryROM(j, s));
  PetscCall(BoltJSONReal(j, "setup_s", s->tSetUp));
  PetscCall(BoltJSONClose(&j));
  PetscFunctionReturn(0);
}
