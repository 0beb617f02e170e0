/* The fields and histories of a run in <dir>/<name>.h5, with the XDMF files beside it that
   ParaView opens: the tied joint's fields, then the FOM's and the ROM's runs through one writer
   (the ROM's displacement in full, V q, while it keeps its whole basis). */
#include "private/app.h"

/* A model's contact state at the end of its run, at the nodes (BoltOutputContactState). */
static PetscErrorCode FieldsFinalContactState(BoltOutput *h5, BoltMesh *mesh, BoltContactState *state, const char name[])
{
  BoltContactSet *c = BoltContactStateSet(state);
  unsigned char  *codes;

  PetscFunctionBeginUser;
  if (!BoltContactSetPointCountGlobal(c)) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(4 * BoltContactSetElementCount(c) + 1, &codes));
  BoltContactStatePointCodes(state, codes);
  PetscCall(BoltOutputContactState(h5, mesh, c, codes, name));
  PetscCall(PetscFree(codes));
  PetscFunctionReturn(0);
}

/* A run's histories under group /<model>: time, probe, energy and its accounting, the pair
   forces and, under friction, the slipping points and the dissipated energy. */
static PetscErrorCode FieldsHistories(BoltOutput *h5, const char model[], BoltNewmark *nm)
{
  const char      *rows[BOLT_LEDGER] = {"external_work", "kinetic", "strain", "rayleigh", "contact_work", "balance"};
  const PetscReal *t, *probe, *energy, *L, *P;
  PetscInt         N;
  BoltOperator    *op;
  char             group[32], ledger[64];

  PetscFunctionBeginUser;
  PetscCall(BoltNewmarkGetModel(nm, &op, NULL, NULL));
  PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_TIME, &N, &t));
  N++; /* the start and every step */
  PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_PROBE, NULL, &probe));
  PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_ENERGY, NULL, &energy));
  PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_LEDGER, NULL, &L));
  PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_PAIR_FORCE, NULL, &P));
  PetscCall(PetscSNPrintf(group, sizeof(group), "/%s", model));
  PetscCall(PetscSNPrintf(ledger, sizeof(ledger), "/%s/energy_accounting", model));
  PetscCall(BoltOutputSeries(h5, group, "time", N, t));
  PetscCall(BoltOutputSeries(h5, group, "probe", N, probe));
  PetscCall(BoltOutputSeries(h5, group, "energy", N, energy));
  for (PetscInt r = 0; r < BOLT_LEDGER; r++) PetscCall(BoltOutputSeries(h5, ledger, rows[r], N, &L[r * N]));
  PetscCall(BoltOutputPairForces(h5, group, BoltOperatorContact(op), N, P));
  if (BoltContactStateHasFriction(BoltOperatorState(op))) {
    const PetscReal *slipping, *dissipated;
    PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_SLIPPING, NULL, &slipping));
    PetscCall(BoltNewmarkGetHistory(nm, BOLT_HISTORY_DISSIPATED, NULL, &dissipated));
    PetscCall(BoltOutputSeries(h5, group, "slipping", N, slipping));
    PetscCall(BoltOutputSeries(h5, group, "dissipated", N, dissipated));
  }
  PetscFunctionReturn(0);
}

/* The displacement snapshots of a run (u: a work vector of the full layout) as the fields
   <prefix>snapshot_<i> and, with contact, <prefix>contact_state_<i>, and their temporal series. */
static PetscErrorCode FieldsSnapshots(BoltOutput *h5, BoltMesh *mesh, const char prefix[], BoltNewmark *nm, BoltROM *rom, Vec u)
{
  BoltOperator        *op;
  BoltContactSet      *c;
  PetscInt             nsnap;
  Vec                 *snap;
  const PetscReal     *time;
  const unsigned char *codes;

  PetscFunctionBeginUser;
  PetscCall(BoltNewmarkGetModel(nm, &op, NULL, NULL));
  PetscCall(BoltNewmarkGetSnapshots(nm, &nsnap, &snap, &time, &codes));
  c = BoltOperatorContact(op);
  for (PetscInt i = 0; i < nsnap; i++) {
    if (rom) PetscCall(BoltROMExpand(rom, snap[i], u));
    PetscCall(BoltOutputSnapshot(h5, mesh, prefix, i, rom ? u : snap[i]));
  }
  if (BoltContactSetPointCountGlobal(c)) PetscCall(BoltOutputSnapshotStates(h5, mesh, prefix, c, nsnap, codes));
  PetscCall(BoltOutputSnapshotSeries(h5, prefix, nsnap, time, BoltContactSetPointCountGlobal(c) ? PETSC_TRUE : PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* One model's run, the FOM's (rom NULL) or the ROM's: <model>_final_displacement, the FOM's
   final contact forces, <model>_final_contact_state, the histories and the snapshots. The
   FOM's snapshots keep their names (snapshot_<i>, <name>-series.xmf); the ROM's take rom_. */
static PetscErrorCode FieldsRun(BoltOutput *h5, const BoltSummary *s, const char model[], BoltNewmark *nm, BoltROM *rom)
{
  BoltMesh     *mesh  = s->mesh;
  PetscBool     whole = PETSC_TRUE;
  Vec           u, q;
  BoltOperator *op;
  PetscInt      nsnap;
  char          name[BOLTROM_NAME_LEN];

  PetscFunctionBeginUser;
  PetscCall(BoltNewmarkGetModel(nm, &op, NULL, &q));
  PetscCall(BoltNewmarkGetSnapshots(nm, &nsnap, NULL, NULL, NULL));
  if (rom) PetscCall(BoltROMBasisEnsure(rom, mesh, BoltLoadSetLoad(s->loads), &whole)); /* else it says why not */
  PetscCall(VecDuplicate(BoltLoadSetLoad(s->loads), &u));
  if (whole) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "%s_final_displacement", model));
    if (rom) PetscCall(BoltROMExpand(rom, q, u));
    PetscCall(BoltOutputVertexField(h5, mesh, rom ? u : q, name));
  }
  if (!rom) { /* the FOM's nodal contact forces */
    PetscCall(BoltContactStateNodalForces(BoltOperatorState(op), u));
    PetscCall(BoltOutputVertexField(h5, mesh, u, "fom_final_contact_force"));
  }
  PetscCall(PetscSNPrintf(name, sizeof(name), "%s_final_contact_state", model));
  PetscCall(FieldsFinalContactState(h5, mesh, BoltOperatorState(op), name));
  PetscCall(FieldsHistories(h5, model, nm));
  if (nsnap && whole) PetscCall(FieldsSnapshots(h5, mesh, rom ? "rom_" : "", nm, rom, u));
  PetscCall(VecDestroy(&u));
  PetscFunctionReturn(0);
}

/* The fields and histories of the run: <dir>/<name>.h5 and .xmf (ParaView), with the run's
   description as attributes of the root group (metadata.c). */
PetscErrorCode BoltSummaryWriteFields(const BoltSummary *s, const char dir[], const char name[])
{
  BoltMesh    *mesh  = s->mesh;
  BoltLoadSet *loads = s->loads;
  BoltOutput   h5;

  PetscFunctionBeginUser;
  PetscCall(BoltOutputOpen(mesh, dir, name, &h5));
  PetscCall(BoltSummaryWriteAttributes(s, h5.viewer));
  if (s->staticSolve) PetscCall(BoltOutputVertexField(&h5, mesh, s->u, "displacement"));
  PetscCall(BoltOutputVertexField(&h5, mesh, BoltLoadSetLoad(loads), "load"));
  if (BoltLoadSetHasPreload(loads)) PetscCall(BoltOutputVertexField(&h5, mesh, BoltLoadSetPreload(loads), "preload"));
  if (s->fomRun) PetscCall(FieldsRun(&h5, s, "fom", s->fomRun, NULL));
  if (s->romRun) PetscCall(FieldsRun(&h5, s, "rom", s->romRun, s->rom));
  if (s->x) {
    PetscCall(BoltOutputVertexField(&h5, mesh, s->x, "x"));
    PetscCall(BoltOutputVertexField(&h5, mesh, s->Kx, "Kx"));
    PetscCall(BoltOutputVertexField(&h5, mesh, s->Mx, "Mx"));
  }
  PetscCall(BoltOutputClose(&h5, mesh));
  PetscCall(PetscPrintf(BoltMeshComm(mesh), "Wrote %s/%s.h5 and %s/%s.xmf (open the .xmf in ParaView)\n", dir, name, dir, name));
  PetscFunctionReturn(0);
}
