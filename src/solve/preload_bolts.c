/* Several bolts (-preload_bolts), each calibrated to its own clamp force, read from its stud
   (BoltLoadSetStudTension). At a fixed active set the preloaded state is linear in the bolts'
   layer forces, but the bolts load each other through the joint, so no one scale makes them all
   exact: each layer force is corrected by its own bolt's ratio, f_b <- f_b T*_b / T_b, and the
   static contact problem solved again, until every clamp force is within 1e-10 of its target. */
#include "private/solve.h"

/* The bolts of loads, calibrated in the static start (the integrator keeps a reference). */
PetscErrorCode BoltNewmarkSetBolts(BoltNewmark *nm, BoltLoadSet *loads)
{
  PetscFunctionBeginUser;
  nm->bolts = BoltLoadSetBoltCount(loads) > 0 ? loads : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode BoltNewmarkPreloadBolts(BoltNewmark *nm, PetscInt *nout, PetscInt *nin)
{
  BoltOperator   *op = nm->op;
  const PetscInt  nb = BoltLoadSetBoltCount(nm->bolts);
  PetscReal       err = PETSC_MAX_REAL;
  PetscInt        pass;

  PetscFunctionBeginUser;
  *nout = *nin = 0;
  for (PetscInt b = 0; b < nb; b++) nm->boltLayerForce[b] = BoltLoadSetBoltForce(nm->bolts, b);
  for (pass = 1; pass <= 50 && err > 1e-10; pass++) {
    PetscInt o, i;
    PetscCall(VecZeroEntries(op->preload));
    for (PetscInt b = 0; b < nb; b++) PetscCall(VecAXPY(op->preload, nm->boltLayerForce[b], BoltLoadSetBoltUnit(nm->bolts, b)));
    PetscCall(VecCopy(op->preload, nm->rhs));
    PetscCall(BoltDualSolveStatic(nm->dual, nm->rhs, nm->q, 0, &o, &i));
    *nout += o;
    *nin += i;
    err = 0;
    for (PetscInt b = 0; b < nb; b++) {
      const PetscReal target = BoltLoadSetBoltForce(nm->bolts, b);
      PetscBool stud;
      PetscCall(BoltLoadSetStudTension(nm->bolts, b, BoltOperatorStiffness(op), nm->q, op->preload, &nm->boltTension[b], &stud));
      PetscCheck(stud, op->comm, PETSC_ERR_USER_INPUT, "Bolt %s: no hexahedron lies between its layers preload_%s_lower and preload_%s_upper; they must bound one element layer of its stud", BoltLoadSetBoltName(nm->bolts, b), BoltLoadSetBoltName(nm->bolts, b), BoltLoadSetBoltName(nm->bolts, b));
      PetscCheck(nm->boltTension[b] > 0 || target == 0, op->comm, PETSC_ERR_USER_INPUT, "Bolt %s clamps nothing (its stud carries %g N): check its preload layers and the axis (-preload_axis)", BoltLoadSetBoltName(nm->bolts, b), (double)nm->boltTension[b]);
      if (target != 0) err = PetscMax(err, PetscAbsReal(nm->boltTension[b] - target) / PetscAbsReal(target)); /* a bolt of no force takes no layer force: its stud carries what the others impose */
    }
    for (PetscInt b = 0; b < nb; b++)
      if (nm->boltTension[b] > 0 && BoltLoadSetBoltForce(nm->bolts, b) != 0) nm->boltLayerForce[b] *= BoltLoadSetBoltForce(nm->bolts, b) / nm->boltTension[b];
  }
  nm->boltPasses = pass - 1;
  PetscCheck(err <= 1e-10, op->comm, PETSC_ERR_NOT_CONVERGED, "The bolts' preloads did not settle: after %" PetscInt_FMT " static solves a clamp force is still %.3e off its target; the bolts may load each other too strongly (or the contact set keeps changing)", nm->boltPasses, (double)err);
  /* the state and operator hold the last solve's layer forces, whose clamp forces are the ones checked */
  PetscCall(VecZeroEntries(op->preload));
  for (PetscInt b = 0; b < nb; b++) {
    if (nm->boltTension[b] > 0 && BoltLoadSetBoltForce(nm->bolts, b) != 0) nm->boltLayerForce[b] *= nm->boltTension[b] / BoltLoadSetBoltForce(nm->bolts, b); /* undo the last pass's correction */
    PetscCall(VecAXPY(op->preload, nm->boltLayerForce[b], BoltLoadSetBoltUnit(nm->bolts, b)));
  }
  PetscCall(PetscPrintf(op->comm, "Bolts calibrated in %" PetscInt_FMT " static solves; clamp force (layer force) [N]:", nm->boltPasses));
  for (PetscInt b = 0; b < nb; b++) PetscCall(PetscPrintf(op->comm, " %s %.1f (%.1f)", BoltLoadSetBoltName(nm->bolts, b), (double)nm->boltTension[b], (double)nm->boltLayerForce[b]));
  PetscCall(PetscPrintf(op->comm, "\n"));
  PetscFunctionReturn(0);
}

/* Per bolt: its target clamp force, the layer force that gives it, and the clamp force read
   from its stud. */
PetscErrorCode BoltNewmarkBoltsSummaryWrite(BoltNewmark *nm, BoltJSON *j)
{
  PetscFunctionBeginUser;
  if (!nm->bolts) PetscFunctionReturn(0);
  PetscCall(BoltJSONInt(j, "bolt_calibration_solves", nm->boltPasses));
  PetscCall(BoltJSONBeginObject(j, "bolts"));
  for (PetscInt b = 0; b < BoltLoadSetBoltCount(nm->bolts); b++) {
    PetscCall(BoltJSONBeginObject(j, BoltLoadSetBoltName(nm->bolts, b)));
    PetscCall(BoltJSONReal(j, "preload", BoltLoadSetBoltForce(nm->bolts, b)));
    PetscCall(BoltJSONReal(j, "layer_force", nm->boltLayerForce[b]));
    PetscCall(BoltJSONReal(j, "stud_tension", nm->boltTension[b]));
    PetscCall(BoltJSONEndObject(j));
  }
  PetscCall(BoltJSONEndObject(j));
  PetscFunctionReturn(0);
}
